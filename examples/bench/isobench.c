/* isobench.c: frame times of voxlux's ray-cast isosurface renderer
 * (vx_raycast_render, what raycast(1) runs), for examples/bench/isobench.py.
 *
 * Loads a stream once (volume, and its macrocells when the stream has them:
 * `vread | brick | macrocell`), then renders the scene --warm times untimed
 * and -n times timed, and prints the medians; with --latency V,V,... it then
 * changes the isovalue to each V in turn and times the one render that
 * shows it: nothing is rebuilt for a new isovalue (the macrocells hold
 * ranges, not surfaces).  Output: "key value" lines on stdout.
 *
 *   isobench --scene FILE [--set LINE]... [--iso V[,V...]] [--view NAME]
 *            [--size WxH] [-j N] [--flat] [--no-cellmask] [-n FRAMES] [--warm N]
 *            [--fresh-cellmask] [--ab-cellmask ROUNDS]
 *            [--latency V[,V...]] [--pfm OUT.pfm] [--stats]
 *            [--sizes AxBxC[,DxExF...]] STREAM
 *
 * --pfm writes the first timed frame's red channel as a gray PFM (the
 * bench scenes are white: r = g = b), flattened over black, as the Embree
 * peer writes its frame.  --stats times the phases (traversal,
 * intersection, shading: Parker's Table 1) in one extra frame; timed frames
 * never run with the phase clocks on.  --no-cellmask renders without the
 * cell mask (raycast(1) --no-cellmask; every frame builds its own mask
 * otherwise, lazily, as raycast does: its cost is in the frame time).
 * --ab-cellmask R then renders R rounds of one frame with the mask and one
 * without, alternating in this process, and prints both modes' median and
 * fastest CPU times and the median of the per-round ratios: the steadiest
 * measure of the mask's saving on a shared machine.  --sizes builds the macrocells here
 * with those level sizes (macrocell(1) --sizes) instead of using the
 * stream's, and prints the build time.
 *
 * Build (examples/bench/Makefile does): cc -O2 -fopenmp -I../../src/core
 *   isobench.c ../../build/libvoxlux.a -lpng -lz -lm */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vx_camera.h"
#include "vx_grid.h"
#include "vx_image.h"
#include "vx_imageio.h"
#include "vx_cellmask.h"
#include "vx_macro.h"
#include "vx_macroio.h"
#include "vx_plan.h"
#include "vx_raycast.h"
#include "vx_scene.h"
#include "vx_stream.h"

#define BENCH_NAME "isobench"
#include "benchutil.h"

#define MAXFRAMES 1000

typedef struct bench {
	vx_scene s;
	vx_plan plan;
	vx_grid g;
	vx_macro m;
	int have_m;
	vx_raycast_opts ro;
	vx_cellmask keep;        /* the cell mask kept between frames */
	double lo[3], hi[3];
} bench;

/* render: one frame of the current scene; wall and CPU seconds. */
static void
render(bench *b, vx_image *color, vx_raycast_stats *rs, double *wall,
    double *cpu)
{
	vx_err e = { 0, "" };
	vx_scene s = b->s;
	double w0, c0;

	w0 = now(CLOCK_MONOTONIC);
	c0 = now(CLOCK_PROCESS_CPUTIME_ID);
	/* what an isovalue change costs: the plan, the camera, the frame */
	vx_scene_plan_isosurface(&s, &b->plan);
	if (vx_camera_resolve(&s.camera, b->lo, b->hi, &e) != 0)
		die("camera", &e);
	vx_image_init(color);
	if (vx_raycast_render(&s, &b->plan, &b->g, b->have_m ? &b->m : NULL,
	    NULL, &b->ro, color, NULL, NULL, rs, &e) != 0)
		die("render", &e);
	*wall = now(CLOCK_MONOTONIC) - w0;
	*cpu = now(CLOCK_PROCESS_CPUTIME_ID) - c0;
}

static void
write_gray_pfm(const char *path, const vx_image *color)
{
	vx_err e = { 0, "" };
	vx_image gray;
	FILE *f;
	size_t i, n = (size_t)color->w * (size_t)color->h;

	if (vx_image_alloc(&gray, color->w, color->h, 1, &e) != 0)
		die("image", &e);
	for (i = 0; i < n; i++)
		gray.px[i] = color->px[4 * i];     /* premultiplied: over black */
	if ((f = fopen(path, "wb")) == NULL)
		die(path, NULL);
	if (vx_pfm_write(&gray, f, &e) != 0 || fclose(f) != 0)
		die(path, &e);
	vx_image_free(&gray);
}

int
main(int argc, char **argv)
{
	const char *scene = NULL, *stream = NULL, *pfm = NULL, *latency = NULL;
	const char *sizes = NULL;
	int nframes = 5, warm = 1, stats = 0, abr = 0, fresh = 0, i, status;
	long gsrc = -1;
	bench b;
	vx_stream st;
	vx_err e = { 0, "" };
	vx_image color;
	vx_raycast_stats rs;
	double wall[MAXFRAMES], cpu[MAXFRAMES], tiles[MAXFRAMES];
	double busy[MAXFRAMES], bins[MAXFRAMES], t0;

	memset(&b, 0, sizeof b);
	vx_raycast_opts_init(&b.ro);
	vx_macro_init(&b.m);
	/* first pass: the scene file, so that the options apply over it */
	for (i = 1; i < argc; i++)
		if (strcmp(argv[i], "--scene") == 0 && i + 1 < argc)
			scene = argv[++i];
	if (scene == NULL)
		die("usage: isobench --scene FILE [options] STREAM", NULL);
	load_scene(&b.s, scene);
	for (i = 1; i < argc; i++) {
		const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
		const char *opt = NULL;

		if (strcmp(a, "--scene") == 0) {
			i++;
			continue;
		}
		if (strcmp(a, "--flat") == 0) {
			b.ro.flat = 1;
			continue;
		}
		if (strcmp(a, "--no-cellmask") == 0) {
			b.ro.no_cellmask = 1;
			continue;
		}
		if (strcmp(a, "--fresh-cellmask") == 0) {
			fresh = 1;
			continue;
		}
		if (strcmp(a, "--ab-cellmask") == 0 && v != NULL) {
			abr = atoi(v);
			if (abr < 1 || abr > MAXFRAMES)
				die("--ab-cellmask: 1 to 1000 rounds", NULL);
			i++;
			continue;
		}
		if (strcmp(a, "--stats") == 0) {
			stats = 1;
			continue;
		}
		if (a[0] != '-') {
			stream = a;
			continue;
		}
		if (v == NULL)
			die("option needs a value", NULL);
		i++;
		if (strcmp(a, "-j") == 0)
			b.ro.nthreads = atoi(v);
		else if (strcmp(a, "-n") == 0)
			nframes = atoi(v);
		else if (strcmp(a, "--warm") == 0)
			warm = atoi(v);
		else if (strcmp(a, "--pfm") == 0)
			pfm = v;
		else if (strcmp(a, "--latency") == 0)
			latency = v;
		else if (strcmp(a, "--sizes") == 0)
			sizes = v;
		else if (strcmp(a, "--set") == 0)
			opt = "set";
		else if (strcmp(a, "--iso") == 0)
			opt = "iso";
		else if (strcmp(a, "--view") == 0)
			opt = "view";
		else if (strcmp(a, "--size") == 0)
			opt = "size";
		else
			die("unknown option", NULL);
		if (opt != NULL && vx_scene_option(&b.s, opt, v, &e) != 0)
			die(a, &e);
	}
	if (stream == NULL || nframes < 1 || nframes > MAXFRAMES || warm < 0)
		die("usage: isobench --scene FILE [options] STREAM", NULL);

	/* load: the stream, the volume, its macrocells */
	t0 = now(CLOCK_MONOTONIC);
	load_stream(&st, stream);
	if (vx_grid_from_stream(&b.g, &st, NULL, &gsrc, &e) != 0)
		die(stream, &e);
	if (!b.ro.flat && sizes == NULL) {
		if (vx_macro_from_stream(&b.m, &st, &b.g, gsrc, &status, NULL,
		    &e) != 0)
			die("macrocells", &e);
		if (status != VX_MACRO_LOADED)
			die("the stream has no macrocells for its volume (run "
			    "macrocell) or use --flat or --sizes", NULL);
		b.have_m = 1;
	}
	vx_stream_free(&st);
	printf("load_ms %.3f\n", 1e3 * (now(CLOCK_MONOTONIC) - t0));
	if (!b.ro.flat && sizes != NULL) {
		int sz[VX_MACRO_MAXLEV][3], nlev;

		if ((nlev = vx_macro_parse_sizes(sizes, sz, &e)) < 0)
			die("--sizes", &e);
		t0 = now(CLOCK_MONOTONIC);
		if (vx_macro_build(&b.m, &b.g, nlev, (const int (*)[3])sz,
		    b.ro.nthreads, &e) != 0)
			die("macrocells", &e);
		printf("build_ms %.3f\n", 1e3 * (now(CLOCK_MONOTONIC) - t0));
		b.have_m = 1;
	}
	if (b.have_m)
		printf("macro_bytes %zu\nmacro_share %.5f\n", vx_macro_bytes(&b.m),
		    (double)vx_macro_bytes(&b.m) / ((double)b.g.dims[0] *
		    (double)b.g.dims[1] * (double)b.g.dims[2] *
		    (double)vx_type_size(b.g.type)));
	printf("layout %s\n", b.g.lay.nlev ? "bricked" : "linear");
	printf("traversal %s\n", b.ro.flat ? "flat" : "hierarchical");
	vx_grid_box(&b.g, b.lo, b.hi);
	vx_cellmask_init(&b.keep);
	if (!fresh)
		b.ro.mask_keep = &b.keep;

	for (i = 0; i < warm; i++) {
		render(&b, &color, &rs, &wall[0], &cpu[0]);
		vx_image_free(&color);
	}
	for (i = 0; i < nframes; i++) {
		render(&b, &color, &rs, &wall[i], &cpu[i]);
		tiles[i] = rs.tile_seconds;
		busy[i] = rs.thread_seconds;
		bins[i] = rs.bin_seconds;
		if (i == 0 && pfm != NULL)
			write_gray_pfm(pfm, &color);
		vx_image_free(&color);
	}
	printf("threads %d\n", b.ro.nthreads);
	printf("frames %d\n", nframes);
	printf("frame_ms %.3f\n", 1e3 * median(wall, nframes));
	printf("frame_ms_min %.3f\n", 1e3 * wall[0]);
	printf("frame_ms_max %.3f\n", 1e3 * wall[nframes - 1]);
	printf("frame_cpu_ms %.3f\n", 1e3 * median(cpu, nframes));
	/* the tiles' wall time and the threads' time in them (vx_raycast_stats) */
	printf("tile_ms %.3f\n", 1e3 * median(tiles, nframes));
	printf("thread_ms %.3f\n", 1e3 * median(busy, nframes));
	printf("bin_ms %.3f\n", 1e3 * median(bins, nframes));
	printf("cellmask %s\nmask_bytes %llu\nmask_blocks %llu\nmask_set %llu\n"
	    "mask_built %llu\n", rs.mask_bytes ? "on" : "off",
	    (unsigned long long)rs.mask_bytes,
	    (unsigned long long)rs.mask_blocks,
	    (unsigned long long)rs.mask_set,
	    (unsigned long long)rs.mask_built);
	printf("rays %llu\ncells %llu\nroots %llu\nhits %llu\ncovered %llu\n",
	    (unsigned long long)rs.primary, (unsigned long long)rs.cells,
	    (unsigned long long)rs.roots, (unsigned long long)rs.hits,
	    (unsigned long long)rs.covered);
	if (stats) {
		b.ro.timing = 1;
		render(&b, &color, &rs, &wall[0], &cpu[0]);
		vx_image_free(&color);
		b.ro.timing = 0;
		printf("share_traverse %.4f\nshare_isect %.4f\n"
		    "share_shade %.4f\n", rs.share_traverse, rs.share_isect,
		    rs.share_shade);
	}
	if (abr > 0) {
		/* the mask's saving: kept, fresh and none, alternating */
		static double cpu3[3][MAXFRAMES], rat[2][MAXFRAMES];
		double w;
		int keep = b.ro.no_cellmask;
		vx_cellmask *kept = b.ro.mask_keep;

		for (i = 0; i < abr; i++) {
			for (int k = 0; k < 3; k++) {
				b.ro.no_cellmask = k == 2;
				b.ro.mask_keep = k == 0 ? &b.keep : NULL;
				render(&b, &color, &rs, &w, &cpu3[k][i]);
				vx_image_free(&color);
			}
			rat[0][i] = cpu3[0][i] / cpu3[2][i];
			rat[1][i] = cpu3[1][i] / cpu3[2][i];
		}
		b.ro.no_cellmask = keep;
		b.ro.mask_keep = kept;
		printf("ab_rounds %d\nab_ratio_kept %.4f\nab_ratio_fresh %.4f\n",
		    abr, median(rat[0], abr), median(rat[1], abr));
		printf("ab_kept_cpu_ms %.3f\nab_fresh_cpu_ms %.3f\n"
		    "ab_nomask_cpu_ms %.3f\n", 1e3 * median(cpu3[0], abr),
		    1e3 * median(cpu3[1], abr), 1e3 * median(cpu3[2], abr));
		printf("ab_kept_cpu_ms_min %.3f\nab_fresh_cpu_ms_min %.3f\n"
		    "ab_nomask_cpu_ms_min %.3f\n", 1e3 * cpu3[0][0],
		    1e3 * cpu3[1][0], 1e3 * cpu3[2][0]);
	}
	if (latency != NULL) {
		/* an isovalue change: the new surface's first frame */
		char *list = strdup(latency), *tok, *save = NULL;

		for (tok = strtok_r(list, ",", &save); tok != NULL;
		    tok = strtok_r(NULL, ",", &save)) {
			double w, c;

			if (vx_scene_option(&b.s, "iso", tok, &e) != 0)
				die("--latency", &e);
			render(&b, &color, &rs, &w, &c);
			vx_image_free(&color);
			printf("latency iso %s ms %.3f cpu_ms %.3f covered %llu\n",
			    tok, 1e3 * w, 1e3 * c,
			    (unsigned long long)rs.covered);
		}
		free(list);
	}
	vx_cellmask_free(&b.keep);
	vx_macro_free(&b.m);
	vx_grid_free(&b.g);
	return 0;
}
