/* t2bench.c: Wyman et al.'s Table 2 in one process, for RESULTS-gi.md: the
 * frame time of each shading mode of one scene, every mode rendered in
 * turn in each round, many rounds, so that a shared machine's noise falls
 * on all modes alike and the ratios are taken within a round.
 *
 * Loads a stream once (volume and macrocells: `vread | brick | macrocell`)
 * and the irradiance volumes of the --irr streams (bake-irr's output, any
 * store), then renders with vx_raycast_render (what raycast(1) runs) the
 * modes
 *   lambert   illumination local, effects -shadows -specular -interreflection
 *   lambert+s illumination local, effects -specular -interreflection
 *   phong+s   illumination local, effects -interreflection (Blinn-Phong with
 *             the scene's shadows)
 *   LABEL     illumination irradiance (trilinear) from --irr LABEL=STREAM
 * A frame is what raycast's --stats times: the isosurface plan, the camera,
 * vx_raycast_render (its own cell mask built per frame, as raycast builds
 * one; reading the stream excluded).  --warm rounds untimed first, then -n
 * timed rounds, each mode once a round, the order rotated from round to
 * round.  Prints "key value" lines: per mode the median and the fastest
 * CPU time (the process's, over the frame) and wall time of its frames, and
 * the median and quartiles of the per-round ratio of its CPU time to
 * phong+s's.
 *
 *   t2bench --scene FILE [--irr LABEL=STREAM]... [-j N] [-n ROUNDS]
 *           [--warm N] [--size WxH] [--only LABEL] STREAM
 *
 * --only renders that mode alone (for a profiler; no ratios).
 *
 * Build (gi.mk does): cc -O2 -fopenmp -I../../src/core/... t2bench.c
 *   ../../build/libvoxlux.a -lpng -lz -lm */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vx_camera.h"
#include "vx_grid.h"
#include "vx_image.h"
#include "vx_irrvol.h"
#include "vx_macro.h"
#include "vx_macroio.h"
#include "vx_plan.h"
#include "vx_raycast.h"
#include "vx_scene.h"
#include "vx_stream.h"

#define BENCH_NAME "t2bench"
#include "benchutil.h"

#define MAXROUNDS 1000
#define MAXIRR 8
#define NLOCAL 3
#define MAXMODES (NLOCAL + MAXIRR)

typedef struct mode {
	char label[64];
	vx_scene s;
	const vx_irrvol *irr;
	double cpu[MAXROUNDS], wall[MAXROUNDS], ratio[MAXROUNDS];
} mode;

static mode modes[MAXMODES];

/* frame: one frame of mode md; its CPU and wall seconds */
static void
frame(const mode *md, const vx_grid *g, const vx_macro *m, int have_m,
    int nthreads, const double lo[3], const double hi[3], double *cpu,
    double *wall)
{
	vx_err e = { 0, "" };
	vx_scene s = md->s;
	vx_raycast_opts ro;
	vx_raycast_stats rs;
	vx_image color;
	vx_plan plan;
	double w0, c0;

	w0 = now(CLOCK_MONOTONIC);
	c0 = now(CLOCK_PROCESS_CPUTIME_ID);
	vx_scene_plan_isosurface(&s, &plan);
	if (vx_camera_resolve(&s.camera, lo, hi, &e) != 0)
		die("camera", &e);
	vx_raycast_opts_init(&ro);
	ro.nthreads = nthreads;
	ro.irr = md->irr;
	ro.irr_interp = VX_INTERP_TRILINEAR;
	vx_image_init(&color);
	if (vx_raycast_render(&s, &plan, g, have_m ? m : NULL, NULL, &ro,
	    &color, NULL, NULL, &rs, &e) != 0)
		die(md->label, &e);
	*cpu = now(CLOCK_PROCESS_CPUTIME_ID) - c0;
	*wall = now(CLOCK_MONOTONIC) - w0;
	vx_image_free(&color);
}

int
main(int argc, char **argv)
{
	const char *scene = NULL, *stream = NULL, *irrarg[MAXIRR], *only = NULL;
	static const char *local[NLOCAL][2] = {
		{ "lambert", "-shadows -specular -interreflection" },
		{ "lambert+s", "-specular -interreflection" },
		{ "phong+s", "-interreflection" },
	};
	int nirr = 0, nthreads = 1, rounds = 21, warm = 1, w = 0, h = 0;
	int nmode, i, k, status, have_m;
	static vx_stream ist[MAXIRR];
	static vx_irrvol irr[MAXIRR];
	vx_err e = { 0, "" };
	vx_scene base;
	vx_stream st;
	vx_grid g;
	vx_macro m;
	long gsrc = -1, ii;
	double lo[3], hi[3];

	for (i = 1; i < argc; i++) {
		const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;

		if (!strcmp(a, "--scene") && v != NULL)
			scene = argv[++i];
		else if (!strcmp(a, "--irr") && v != NULL && nirr < MAXIRR &&
		    strchr(v, '=') != NULL)
			irrarg[nirr++] = argv[++i];
		else if (!strcmp(a, "--only") && v != NULL)
			only = argv[++i];
		else if (!strcmp(a, "-j") && v != NULL)
			nthreads = atoi(argv[++i]);
		else if (!strcmp(a, "-n") && v != NULL)
			rounds = atoi(argv[++i]);
		else if (!strcmp(a, "--warm") && v != NULL)
			warm = atoi(argv[++i]);
		else if (!strcmp(a, "--size") && v != NULL) {
			if (sscanf(argv[++i], "%dx%d", &w, &h) != 2 || w < 1 ||
			    h < 1)
				die("--size WxH", NULL);
		} else if (a[0] != '-' && stream == NULL)
			stream = a;
		else
			die("usage: t2bench --scene FILE [--irr LABEL=STREAM]... "
			    "[-j N] [-n ROUNDS] [--warm N] [--size WxH] "
			    "[--only LABEL] STREAM", NULL);
	}
	if (scene == NULL || stream == NULL || rounds < 1 ||
	    rounds > MAXROUNDS || warm < 0 || nthreads < 1)
		die("usage: t2bench --scene FILE [--irr LABEL=STREAM]... "
		    "[-j N] [-n ROUNDS] [--warm N] [--size WxH] "
		    "[--only LABEL] STREAM", NULL);

	load_scene(&base, scene);
	if (w > 0) {
		base.camera.w = w;
		base.camera.h = h;
	}
	load_stream(&st, stream);
	if (vx_grid_from_stream(&g, &st, NULL, &gsrc, &e) != 0)
		die(stream, &e);
	vx_macro_init(&m);
	if (vx_macro_from_stream(&m, &st, &g, gsrc, &status, NULL, &e) != 0)
		die("macrocells", &e);
	have_m = status == VX_MACRO_LOADED;
	vx_grid_box(&g, lo, hi);

	nmode = 0;
	for (k = 0; k < NLOCAL; k++, nmode++) {
		mode *md = &modes[nmode];

		snprintf(md->label, sizeof md->label, "%s", local[k][0]);
		md->s = base;
		if (vx_scene_apply(&md->s, "illumination local", &e) != 0 ||
		    vx_scene_option(&md->s, "effects", local[k][1], &e) != 0)
			die(scene, &e);
	}
	for (k = 0; k < nirr; k++, nmode++) {
		mode *md = &modes[nmode];
		const char *eq = strchr(irrarg[k], '=');
		size_t n = (size_t)(eq - irrarg[k]);

		snprintf(md->label, sizeof md->label, "%.*s",
		    (int)(n < sizeof md->label ? n : sizeof md->label - 1),
		    irrarg[k]);
		load_stream(&ist[k], eq + 1);
		vx_irr_init(&irr[k]);
		if (vx_irr_from_stream(&irr[k], &ist[k], g.name, &ii, &e) != 0)
			die(eq + 1, &e);
		if (ii < 0)
			die("no irradiance volume of the volume in", NULL);
		md->irr = &irr[k];
		md->s = base;
		if (vx_scene_apply(&md->s, "illumination irradiance", &e) != 0)
			die(scene, &e);
	}

	if (only != NULL) {
		for (k = 0; k < nmode && strcmp(modes[k].label, only); k++)
			;
		if (k == nmode)
			die("--only: no such mode", NULL);
		for (int r = 0; r < warm + rounds; r++) {
			double c, wl;

			frame(&modes[k], &g, &m, have_m, nthreads, lo, hi, &c,
			    &wl);
			printf("frame %s cpu_ms %.2f wall_ms %.2f\n", only,
			    1e3 * c, 1e3 * wl);
		}
		return 0;
	}
	printf("scene %s\nimage %dx%d\nthreads %d\nrounds %d\nwarm %d\n",
	    scene, base.camera.w, base.camera.h, nthreads, rounds, warm);
	for (int r = -warm; r < rounds; r++) {
		for (int j = 0; j < nmode; j++) {
			/* the order rotates from round to round */
			mode *md = &modes[(j + (r < 0 ? 0 : r)) % nmode];
			double c, wl;

			frame(md, &g, &m, have_m, nthreads, lo, hi, &c, &wl);
			if (r >= 0) {
				md->cpu[r] = c;
				md->wall[r] = wl;
			}
		}
		if (r >= 0)
			for (int j = 0; j < nmode; j++)
				modes[j].ratio[r] = modes[j].cpu[r] /
				    modes[NLOCAL - 1].cpu[r];
	}
	for (int j = 0; j < nmode; j++) {
		mode *md = &modes[j];
		double cmed = quantile(md->cpu, rounds, 0.5);
		double cmin = md->cpu[0];
		double wmed = quantile(md->wall, rounds, 0.5);
		double wmin = md->wall[0];
		double q1 = quantile(md->ratio, rounds, 0.25);
		double q2 = quantile(md->ratio, rounds, 0.5);
		double q3 = quantile(md->ratio, rounds, 0.75);

		printf("mode %s cpu_med_ms %.2f cpu_min_ms %.2f wall_med_ms "
		    "%.2f wall_min_ms %.2f ratio_med %.3f ratio_q1 %.3f "
		    "ratio_q3 %.3f\n", md->label, 1e3 * cmed, 1e3 * cmin,
		    1e3 * wmed, 1e3 * wmin, q2, q1, q3);
	}
	for (k = 0; k < nirr; k++) {
		vx_irr_free(&irr[k]);
		vx_stream_free(&ist[k]);
	}
	vx_macro_free(&m);
	vx_grid_free(&g);
	vx_stream_free(&st);
	return 0;
}
