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
	enum { O_PRINT = 256, O_REMOVE };
	static const struct option lo[] = {
		TOOL_SCENE_LONG, { "print", 0, 0, O_PRINT }, { "remove", 0, 0, O_REMOVE },
		{ "output", 1, 0, 'o' }, { "help", 0, 0, 'h' }, { 0, 0, 0, 0 }
	};
	const char *in, *out = "-";
	tool_scene_opts so;
	int print = 0, remove = 0, c;
	vx_stream st;
	vx_scene s;
	vx_err e = { 0, "" };
	long idx;

	tool_init("vscene", argc, argv);
	memset(&so, 0, sizeof so);
	while ((c = getopt_long(argc, argv, ":o:h", lo, NULL)) != -1) {
		switch (c) {
		case 'o': out = optarg; break;
		case O_PRINT: print = 1; break;
		case O_REMOVE: remove = 1; break;
		default:
			if (!tool_scene_opt(&so, c, optarg, usage))
				tool_opt_other(c, usage, argv);
		}
	}
	in = tool_opt_input(argc, argv, usage);
	if (remove && (so.file != NULL || so.n > 0))
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
	tool_scene_opts_load(&s, &so, &st);
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
