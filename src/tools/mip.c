/* mip: exact maximum-intensity projection (Parker et al. 1999 §4.3). */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tool.h"
#include "vx_camera.h"
#include "vx_grid.h"
#include "vx_image.h"
#include "vx_imageio.h"
#include "vx_macro.h"
#include "vx_mip.h"
#include "vx_plan.h"
#include "vx_scene.h"
#include "vx_tetimport.h"
#include "vx_tetleaf.h"
#include "vx_tonemap.h"

static const char usage[] =
    "mip [--scene FILE] [--size WxH] [--view NAME|AZ,EL] [--perspective]\n"
    "    [--fov DEG] [--name VOLUME] [--window LO,HI] [--colormap NAME]\n"
    "    [--bits 8|16] [--no-last-t] [--exhaustive] [-j N] [--stats]\n"
    "    [--explain] [-n] [--hdr] [-z LEVEL] [--depth FILE.pfm] [-o OUT]\n"
    "    [STREAM|-]";

typedef struct opts {
	const char *in;
	int lastt, exhaustive, persp, has_window;
	double window[2];
	vx_colormap cmap;
	tool_run_opts run;        /* -o, -j, --hdr, --stats, ... */
	tool_scene_opts so;      /* --scene, --size, --view, --fov */
} opts;

static void
parse(opts *o, int argc, char **argv)
{
	enum { O_PERSP = 256, O_WINDOW, O_CMAP, O_NOLAST, O_EXH };
	static const struct option lo[] = {
		{ "scene", 1, 0, TOOL_O_SCENE }, TOOL_SCENE_LONG_CAMERA,
		{ "perspective", 0, 0, O_PERSP }, { "name", 1, 0, TOOL_O_NAME },
		{ "window", 1, 0, O_WINDOW }, { "colormap", 1, 0, O_CMAP },
		{ "no-last-t", 0, 0, O_NOLAST }, { "exhaustive", 0, 0, O_EXH },
		{ "depth", 1, 0, TOOL_O_DEPTH },
		TOOL_RUN_LONG, TOOL_RENDER_LONG, { 0, 0, 0, 0 }
	};
	int c;

	memset(o, 0, sizeof *o);
	tool_run_opts_init(&o->run);
	o->lastt = 1;
	o->cmap = VX_COLORMAP_GRAY;
	while ((c = getopt_long(argc, argv, TOOL_RUN_SHORT, lo, NULL)) != -1) {
		switch (c) {
		case O_PERSP: o->persp = 1; break;
		case O_WINDOW:
			tool_parse_doubles("--window", optarg, o->window, 2);
			if (!(o->window[0] < o->window[1]))
				tool_usage_fail(usage, "--window: LO must be below HI");
			o->has_window = 1;
			break;
		case O_CMAP:
			o->cmap = (vx_colormap)tool_parse_enum("--colormap",
			    &vx_colormap_enum, optarg);
			break;
		case O_NOLAST: o->lastt = 0; break;
		case O_EXH: o->exhaustive = 1; break;
		default:
			if (!tool_run_opt(&o->run, c, optarg) &&
			    !tool_scene_opt(&o->so, c, optarg, usage))
				tool_opt_other(c, usage, argv);
		}
	}
	o->in = tool_opt_input(argc, argv, usage);
}

static void
explain(const opts *o, const vx_scene *s, const vx_macro *m, int nthr)
{
	vx_plan p;
	int nl = s->nlight;

	vx_plan_init(&p, "mip");
	vx_plan_add(&p, "maximum", VX_PLAN_ON, 1, "%s",
	    o->exhaustive ? "every cell along each ray solved (reference mode)" :
	    "priority queue over macrocells (rays along a grid axis through "
	    "integer samples: a column walk, macrocells by largest maximum "
	    "first); exact cubic maximum per cell");
	vx_plan_add(&p, "use last t", o->lastt && !o->exhaustive ? VX_PLAN_ON :
	    VX_PLAN_OFF, 0, "%s", o->lastt ? "lower bound from the previous "
	    "ray's maximum in the tile" : "switched off (--no-last-t)");
	vx_plan_add(&p, "lights", VX_PLAN_OFF, 0, "a projection is not shaded: "
	    "%d light%s and %d surface%s of the scene ignored", nl,
	    nl == 1 ? "" : "s", s->nsurface, s->nsurface == 1 ? "" : "s");
	tool_plan_print(&p);
	fprintf(stderr, "mip: %dx%d %s, %d hierarchy level%s, %d thread%s\n",
	    s->camera.w, s->camera.h, s->camera.projection == VX_ORTHOGRAPHIC ?
	    "orthographic" : "perspective", m->nlev, m->nlev == 1 ? "" : "s",
	    nthr, nthr == 1 ? "" : "s");
}

int
main(int argc, char **argv)
{
	opts o;
	vx_stream st;
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_image val, dep, disp;
	vx_err e = { 0, "" };
	vx_mip_stats ms;
	double lo[3], hi[3], wlo, whi;
	int nthr, i;
	long gi = -1;
	struct timespec c0, c1;

	tool_init("mip", argc, argv);
	parse(&o, argc, argv);
	vx_stream_init(&st);
	tool_read_stream(&st, o.in);
	vx_scene_init(&s);
	/* an orthographic camera unless a scene says otherwise, then the
	 * options */
	tool_scene_load(&s, o.so.file, &st, 0, NULL, NULL);
	if (o.so.file == NULL && vx_stream_find(&st, VX_CHUNK_SCENE, 0) < 0)
		s.camera.projection = VX_ORTHOGRAPHIC;
	if (o.persp)
		s.camera.projection = VX_PERSPECTIVE;
	for (i = 0; i < o.so.n; i++)
		if (vx_scene_option(&s, o.so.name[i], o.so.val[i], &e) != 0)
			tool_fail_err(&e);
	if (vx_grid_view_stream(&g, &st, o.run.name, &gi, &e) != 0) {
		/* no such volume, but a tet mesh: say so */
		int is_mesh = 0;

		if (vx_tetmesh_find_source(&st, o.run.name, &is_mesh) >= 0 && is_mesh)
			tool_fail(VX_EDATA, "%s%s%s is a tet mesh: mip draws "
			    "volumes (raycast draws a mesh's isosurfaces)",
			    o.run.name ? "'" : "the stream's source", o.run.name ? o.run.name :
			    "", o.run.name ? "'" : "");
		tool_fail_err(&e);
	}
	nthr = tool_threads(o.run.threads);
	tool_macro_load(&m, &st, &g, gi, nthr, o.run.dry);
	if (o.run.explain)
		explain(&o, &s, &m, nthr);
	if (o.run.dry)
		return tool_finish();
	vx_grid_box(&g, lo, hi);
	if (vx_camera_resolve(&s.camera, lo, hi, &e) != 0)
		tool_fail_err(&e);
	int w = s.camera.w, h = s.camera.h;
	vx_mip_opts mo;

	vx_image_init(&val);
	vx_image_init(&dep);
	vx_mip_opts_init(&mo);
	mo.nthreads = nthr;
	mo.last_t = o.lastt;
	mo.exhaustive = o.exhaustive;
	clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c0);
	if (vx_mip_render(&s.camera, &g, &m, &mo, &val, &dep, &ms, &e) != 0)
		tool_fail_err(&e);
	clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c1);
	if (o.run.stats) {
		double sec = ms.seconds;
		double cpu = (double)(c1.tv_sec - c0.tv_sec) +
		    1e-9 * (double)(c1.tv_nsec - c0.tv_nsec);

		fprintf(stderr, "mip: %dx%d, %d thread%s, %.3f s (cpu %.3f s)\n",
		    w, h, nthr, nthr == 1 ? "" : "s", sec, cpu);
		fprintf(stderr, "mip: queue pushes %llu, pops %llu, longest "
		    "queue %llu, pushes saved by last t %llu\n",
		    (unsigned long long)ms.pushes, (unsigned long long)ms.pops,
		    (unsigned long long)ms.max_queue,
		    (unsigned long long)ms.bound_pruned);
		fprintf(stderr, "mip: cells solved %llu (%.1f per ray), cells "
		    "pruned by corners %llu, macrocells opened %llu\n",
		    (unsigned long long)ms.cells,
		    (double)ms.cells / (double)(w * h),
		    (unsigned long long)ms.cells_skipped,
		    (unsigned long long)ms.macro_opened);
	}
	vx_image_init(&disp);
	if (!o.run.hdr) {
		/* the window mapped to [0,1], gray or color-mapped (sRGB) */
		int nc = o.cmap == VX_COLORMAP_GRAY ? 1 : 3;

		wlo = o.has_window ? o.window[0] : g.vmin;
		whi = o.has_window ? o.window[1] : g.vmax;
		if (!(whi > wlo))
			whi = wlo + 1;
		if (vx_image_alloc(&disp, w, h, nc, &e) != 0)
			tool_fail_err(&e);
		for (int y = 0; y < h; y++)
			for (int x = 0; x < w; x++) {
				double t = (*vx_image_pixel(&val, x, y) - wlo) /
				    (whi - wlo), rgb[3];

				t = !(t > 0) ? 0 : t > 1 ? 1 : t;
				if (nc == 1)
					*vx_image_pixel(&disp, x, y) = (float)t;
				else {
					vx_colormap_eval(o.cmap, t, rgb);
					for (int k = 0; k < 3; k++)
						vx_image_pixel(&disp, x, y)[k] =
						    (float)vx_srgb_oetf(rgb[k]);
				}
			}
	}
	{
		/* the volume and its hierarchy are consumed */
		static const char *const drawn[] = { VX_CHUNK_VOLUME,
		    VX_CHUNK_MACRO, NULL };
		const vx_image *img[3] = { &val, &dep, NULL };

		tool_render_write(&o.run, &st, drawn, &s, img, &disp);
	}
	vx_image_free(&disp);
	vx_image_free(&val);
	vx_image_free(&dep);
	vx_macro_free(&m);
	vx_grid_free(&g);
	vx_stream_free(&st);
	return tool_finish();
}
