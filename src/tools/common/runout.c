/* runout.c: the options and the output the renderers and bakers share
 * (tool.h): one parse of -o, -j, -z, -n, --stats, --explain, --hdr,
 * --bits, --exposure and the PFM side files, one way to write a picture
 * or its stream. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tool.h"
#include "vx_image.h"
#include "vx_plan.h"
#include "vx_scene.h"

void
tool_run_opts_init(tool_run_opts *r)
{
	memset(r, 0, sizeof *r);
	r->out = "-";
	r->zlevel = 1;
	r->bits = 8;
}

int
tool_run_opt(tool_run_opts *r, int c, const char *val)
{
	switch (c) {
	case 'o': r->out = val; break;
	case 'j': r->threads = tool_parse_long("-j", val, 0, 4096); break;
	case 'z': r->zlevel = (int)tool_parse_long("-z", val, 0, 9); break;
	case 'n': r->dry = r->explain = 1; break;
	case TOOL_O_STATS: r->stats = 1; break;
	case TOOL_O_EXPLAIN: r->explain = 1; break;
	case TOOL_O_HDR: r->hdr = 1; break;
	case TOOL_O_BITS: r->bits = tool_parse_bits(val); break;
	case TOOL_O_EXPOSURE:
		r->exposure = tool_parse_double("--exposure", val, -64, 64);
		break;
	case TOOL_O_DEPTH: r->depth = val; break;
	case TOOL_O_NORMALS: r->normals = val; break;
	case TOOL_O_PFM: r->pfm = val; break;
	case TOOL_O_NAME: r->name = val; break;
	default: return 0;
	}
	return 1;
}

void
tool_plan_print(const vx_plan *p)
{
	size_t n = vx_plan_format(p, NULL, 0) + 1;
	char *buf = malloc(n);

	if (buf == NULL)
		tool_fail(VX_ENOMEM, "out of memory");
	vx_plan_format(p, buf, n);
	fprintf(stderr, "%s", buf);
	free(buf);
}

/* the stream of --hdr: what in keeps, the scene, the images */
static void
write_stream(const tool_run_opts *r, vx_stream *in, const char *const *drawn,
    const vx_scene *s, const vx_image *const img[3])
{
	const char *drop[16];
	vx_err e = { 0, "" };
	vx_stream out;
	vx_chunk c;
	int n = 0;

	while (drawn[n] != NULL) {
		if (n >= 13)
			tool_fail(VX_EINTERNAL, "too many chunk types");
		drop[n] = drawn[n];
		n++;
	}
	drop[n++] = VX_CHUNK_SCENE;
	drop[n++] = VX_CHUNK_IMAGE;
	drop[n] = NULL;
	vx_stream_init(&out);
	tool_stream_keep(&out, in, drop);
	if (vx_scene_to_stream(s, &out, &e) != 0)
		tool_fail_err(&e);
	for (int k = 0; k < 3; k++)
		if (img[k] != NULL && (vx_image_to_chunk(img[k], r->zlevel, &c,
		    &e) != 0 || vx_stream_append(&out, &c, &e) != 0))
			tool_fail_err(&e);
	tool_write_stream(&out, r->out);
	vx_stream_free(&out);
}

void
tool_render_write(const tool_run_opts *r, vx_stream *in,
    const char *const *drawn, const vx_scene *s, const vx_image *const img[3],
    const vx_image *display)
{
	vx_err e = { 0, "" };

	if (r->depth != NULL && img[1] != NULL)
		tool_write_pfm(r->depth, img[1]);
	if (r->normals != NULL && img[2] != NULL)
		tool_write_pfm(r->normals, img[2]);
	if (r->pfm != NULL) {
		/* linear RGB over the background: what a PFM can hold */
		vx_image flat;

		if (vx_image_flatten(&flat, img[0], 1, s->background, &e) != 0)
			tool_fail_err(&e);
		tool_write_pfm(r->pfm, &flat);
		vx_image_free(&flat);
	}
	if (r->hdr)
		write_stream(r, in, drawn, s, img);
	else if (display != NULL) {
		size_t hl = 0;
		const char *hist = vx_stream_history(in, &hl);

		tool_write_png(r->out, display, r->bits, -1, hist, hl, NULL, 0);
	} else
		tool_write_png_radiance(r->out, img[0], r->exposure,
		    s->background, r->bits, in);
}
