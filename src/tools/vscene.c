/* vscene: put a scene into the stream (or change or print the one there),
 * so every later filter of a pipeline sees it. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tool.h"
#include "vx_env.h"
#include "vx_scene.h"

static const char usage[] =
    "vscene [--scene FILE] [--set LINE] [--iso V[,V...]] [--size WxH]\n"
    "       [--view NAME|AZ,EL] [--light SPEC] [--lights none]\n"
    "       [--effects WORDS] [--background R,G,B] [--fov DEG]\n"
    "       [--print] [--remove] [-o OUT] [STREAM|-]";

int
main(int argc, char **argv)
{
	enum { O_SCENE = 256, O_SET, O_ISO, O_SIZE, O_VIEW, O_LIGHT, O_LIGHTS,
	    O_EFFECTS, O_BG, O_FOV, O_PRINT, O_REMOVE };
	static const struct option lo[] = {
		{ "scene", 1, 0, O_SCENE }, { "set", 1, 0, O_SET },
		{ "iso", 1, 0, O_ISO }, { "size", 1, 0, O_SIZE },
		{ "view", 1, 0, O_VIEW }, { "light", 1, 0, O_LIGHT },
		{ "lights", 1, 0, O_LIGHTS }, { "effects", 1, 0, O_EFFECTS },
		{ "background", 1, 0, O_BG }, { "fov", 1, 0, O_FOV },
		{ "print", 0, 0, O_PRINT }, { "remove", 0, 0, O_REMOVE },
		{ "output", 1, 0, 'o' }, { "help", 0, 0, 'h' }, { 0, 0, 0, 0 }
	};
	const char *in, *out = "-", *file = NULL;
	const char *set_name[64], *set_val[64];
	int nset = 0, print = 0, remove = 0, c, li;
	vx_stream st;
	vx_scene s;
	vx_err e = { 0, "" };
	long idx;

	tool_init("vscene", argc, argv);
	while ((c = getopt_long(argc, argv, ":o:h", lo, &li)) != -1) {
		switch (c) {
		case 'o': out = optarg; break;
		case O_SCENE: file = optarg; break;
		case O_PRINT: print = 1; break;
		case O_REMOVE: remove = 1; break;
		case O_SET: case O_ISO: case O_SIZE: case O_VIEW: case O_LIGHT:
		case O_LIGHTS: case O_EFFECTS: case O_BG: case O_FOV:
			if (nset == 64)
				tool_usage_fail(usage, "too many scene options");
			set_name[nset] = lo[li].name;   /* the scene option's */
			set_val[nset++] = optarg;
			break;
		default:
			tool_opt_other(c, usage, argv);
		}
	}
	in = tool_opt_input(argc, argv, usage);
	if (remove && (file != NULL || nset > 0))
		tool_usage_fail(usage, "--remove takes no scene options");
	vx_stream_init(&st);
	tool_read_stream(&st, in);
	if (remove) {
		while ((idx = vx_stream_find(&st, VX_CHUNK_SCENE, 0)) >= 0)
			vx_stream_remove(&st, (size_t)idx);
		tool_write_stream(&st, out);
		vx_stream_free(&st);
		return tool_finish();
	}
	/* the base: the file, else the stream's scene, else the defaults */
	tool_scene_load(&s, file, &st, nset, set_name, set_val);
	/* environment maps: read, their content hashes recorded or checked */
	if (vx_env_scene_resolve(&s, &e) != 0)
		tool_fail_err(&e);
	if (print) {
		char *text;
		size_t n;

		if (vx_scene_format(&s, &text, &n, &e) != 0)
			tool_fail_err(&e);
		fwrite(text, 1, n, stdout);
		free(text);
		vx_stream_free(&st);
		return tool_finish();
	}
	if (vx_scene_to_stream(&s, &st, &e) != 0)
		tool_fail_err(&e);
	tool_write_stream(&st, out);
	vx_stream_free(&st);
	return tool_finish();
}
