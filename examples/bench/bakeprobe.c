/* bakeprobe.c: where bake-irr's paths go, for RESULTS-gi.md: the work and
 * the CPU time of a bake's samples by the texel's own isovalue.
 *
 * Loads a stream (volume and macrocells: `vread | brick | macrocell`) and a
 * scene, plans the bake as bake-irr does by default (the texels of the
 * lattice cells, at scale 1, whose range meets the scene's isovalues), and
 * for every --every'th wanted texel makes bake-irr's estimate (the same
 * start point, normal and isovalue: vx_bake_texel_setup; vx_gi_direct once,
 * then --samples paths of vx_gi_sample, the texel's stream), in one thread.
 * Prints, per band of texel isovalues, the texels, the CPU time per path,
 * bounce rays per path and how many of them hit a surface, shadow rays per
 * path, and per ray (bounce and shadow) the leaves the walk stepped through
 * and those it handed to the cell kernel.
 *
 *   bakeprobe --scene FILE [--samples N] [--every K] STREAM
 *
 * Build (gi.mk does): cc -O2 -fopenmp -I../../src/core/... bakeprobe.c
 *   ../../build/libvoxlux.a -lpng -lz -lm */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vx_bake.h"
#include "vx_camera.h"
#include "vx_gi.h"
#include "vx_grid.h"
#include "vx_irrvol.h"
#include "vx_macro.h"
#include "vx_macroio.h"
#include "vx_scene.h"
#include "vx_stream.h"

#define BENCH_NAME "bakeprobe"
#include "benchutil.h"

#define NB 12

static double
cpu_now(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct band {
	double cpu;
	uint64_t texels, paths, rays, hits, shadow, leaves, culled;
} band;

int
main(int argc, char **argv)
{
	static const double edge[NB + 1] = { -INFINITY, 5, 10, 15, 20, 30, 40,
	    50, 60, 80, 100, 140, INFINITY };
	const char *scene = NULL, *stream = NULL;
	int samples = 4, every = 8, status, i;
	vx_err e = { 0, "" };
	vx_stream st;
	vx_scene s;
	vx_grid g;
	vx_macro m;
	vx_gi gi;
	vx_irrvol v;
	vx_bake_opts o;
	vx_bake_stats bs;
	band bd[NB], tot;
	long gsrc = -1;
	uint64_t n = 0;

	for (i = 1; i < argc; i++) {
		if (!strcmp(argv[i], "--scene") && i + 1 < argc)
			scene = argv[++i];
		else if (!strcmp(argv[i], "--samples") && i + 1 < argc)
			samples = atoi(argv[++i]);
		else if (!strcmp(argv[i], "--every") && i + 1 < argc)
			every = atoi(argv[++i]);
		else if (argv[i][0] != '-' && stream == NULL)
			stream = argv[i];
		else
			break;
	}
	if (i < argc || scene == NULL || stream == NULL || samples < 1 ||
	    every < 1)
		die("usage: bakeprobe --scene FILE [--samples N] [--every K] "
		    "STREAM", NULL);
	load_scene(&s, scene);
	if (s.nsurface < 1)
		die("the scene has no surface", NULL);
	load_stream(&st, stream);
	if (vx_grid_from_stream(&g, &st, NULL, &gsrc, &e) != 0)
		die(stream, &e);
	if (vx_macro_from_stream(&m, &st, &g, gsrc, &status, NULL, &e) != 0)
		die("macrocells", &e);
	if (status != VX_MACRO_LOADED)
		die("the stream has no macrocells (run macrocell)", NULL);
	vx_stream_free(&st);
	if (vx_gi_setup(&gi, &s, &g, &m, &e) != 0)
		die("scene", &e);

	/* bake-irr's default plan: the scene's isovalues, no margin */
	vx_irr_init(&v);
	if (vx_irr_setup(&v, &g, 0, 1, VX_IRR_ACCUM, &e) != 0)
		die("lattice", &e);
	vx_bake_opts_init(&o);
	o.all = 0;
	o.threads = 1;
	o.nband = s.nsurface < VX_BAKE_MAX_BANDS ? s.nsurface :
	    VX_BAKE_MAX_BANDS;
	for (i = 0; i < o.nband; i++)
		o.band[i][0] = o.band[i][1] = s.surface[i].iso;
	memset(&bs, 0, sizeof bs);
	if (vx_bake_plan(&v, &g, &o, &bs, &e) != 0)
		die("plan", &e);

	memset(bd, 0, sizeof bd);
	for (int64_t k = 0; k < v.dims[2]; k++)
	for (int64_t j = 0; j < v.dims[1]; j++)
	for (int64_t t = 0; t < v.dims[0]; t++) {
		int64_t sl = vx_irr_texel(&v, t, j, k);
		double rho, start[3], nrm[3], D[3], sw[3], c0;
		uint64_t id;
		vx_gi_stats gs;
		uint32_t fl;
		int b = 0;

		if (sl < 0 || !(v.flags[sl] & VX_TEXEL_WANTED) ||
		    n++ % (uint64_t)every != 0)
			continue;
		fl = vx_bake_texel_setup(&v, &g, o.offset, gi.high, t, j, k,
		    &rho, start, nrm);
		if (fl & (VX_TEXEL_NAN | VX_TEXEL_FLAT))
			continue;
		while (b < NB - 1 && rho >= edge[b + 1])
			b++;
		/* bake.c's texel_id: the texel's stream */
		id = (uint64_t)t + (uint64_t)v.dims[0] * ((uint64_t)j +
		    (uint64_t)v.dims[1] * (uint64_t)k);
		memset(&gs, 0, sizeof gs);
		c0 = cpu_now();
		vx_index_to_world(&g, start, sw);
		vx_gi_direct(&gi, sw, start, nrm, rho, gi.high, D, &gs);
		for (int q = 0; q < samples; q++) {
			double val[3];

			vx_gi_sample(&gi, start, nrm, rho, gi.high, D, id,
			    (uint64_t)q, val, &gs);
		}
		bd[b].cpu += cpu_now() - c0;
		bd[b].texels++;
		bd[b].paths += (uint64_t)samples;
		bd[b].rays += gs.rays;
		bd[b].hits += gs.hits;
		bd[b].shadow += gs.shadow_rays;
		bd[b].leaves += gs.iso.trav.leaves;
		bd[b].culled += gs.iso.trav.culled;
	}
	memset(&tot, 0, sizeof tot);
	for (int b = 0; b < NB; b++) {
		tot.cpu += bd[b].cpu;
		tot.texels += bd[b].texels;
		tot.paths += bd[b].paths;
		tot.rays += bd[b].rays;
		tot.hits += bd[b].hits;
		tot.shadow += bd[b].shadow;
		tot.leaves += bd[b].leaves;
		tot.culled += bd[b].culled;
	}
	printf("wanted %llu probed %llu (every %d) samples %d\n",
	    (unsigned long long)n, (unsigned long long)tot.texels, every,
	    samples);
	printf("%-12s %8s %8s %9s %6s %9s %8s %8s %6s\n", "iso", "texels",
	    "ns/path", "rays/path", "hit%", "shadow/p", "stepped", "visited",
	    "cpu%");
	for (int b = 0; b <= NB; b++) {
		const band *x = b < NB ? &bd[b] : &tot;
		double nr = (double)(x->rays + x->shadow);
		char lab[32];

		if (x->texels == 0)
			continue;
		if (b < NB)
			snprintf(lab, sizeof lab, "[%g,%g)", edge[b],
			    edge[b + 1]);
		else
			snprintf(lab, sizeof lab, "all");
		printf("%-12s %8llu %8.0f %9.2f %6.1f %9.2f %8.1f %8.2f %6.1f\n",
		    lab, (unsigned long long)x->texels,
		    1e9 * x->cpu / (double)x->paths,
		    (double)x->rays / (double)x->paths,
		    100.0 * (double)x->hits / (double)x->rays,
		    (double)x->shadow / (double)x->paths,
		    (double)(x->leaves + x->culled) / nr,
		    (double)x->leaves / nr, 100 * x->cpu / tot.cpu);
	}
	vx_irr_free(&v);
	vx_macro_free(&m);
	vx_grid_free(&g);
	return 0;
}
