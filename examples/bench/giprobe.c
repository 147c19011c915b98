/* giprobe.c: where voxlux's path-traced reference spends its rays, for
 * RESULTS-gipeer.md: the work per ray of the global-illumination rays
 * (bounce and shadow rays) that `raycast --set "illumination pathtrace"`
 * traces, and their CPU time alone, without the primary rays.
 *
 * Loads a stream (volume and macrocells: `vread | brick | macrocell`) and a
 * scene, finds each pixel's first hit on its one isosurface as raycast does
 * (the first crossing from t = 0), and there makes the estimate raycast's
 * shade() makes (vx_gi_direct once, then vx_gi_sample per path, the same
 * stream per hit point: the same rays), in one thread.  Prints "key value"
 * lines: rays, paths, the traversal's counters per ray (macrocells
 * examined per level, leaves stepped through, leaves visited, cells handed
 * to the kernel, root queries) and the GI part's CPU time per path.
 *
 *   giprobe --scene FILE [--spp N] [--flat] [--mask]
 *           [--sizes AxBxC[,DxExF...]] [--walks]
 *           STREAM
 *
 * --flat walks every cell (no hierarchy); --mask gives the GI rays the
 * frame's cell mask for the isovalue (vx_cellmask: a leaf stepped through
 * is decided by a bit, its samples read only when it brackets): what
 * raycast's primary rays use, which the GI rays do not.  The hits and
 * pictures are the same in every mode (the walks visit the same cells).
 * --walks: for the first bounce ray of every path (the very rays of
 * vx_gi_sample at depth 0, cut at the first crossing that blocks them),
 * the leaves a flat walk steps through, and the steps of a proximity
 * walk (Cohen & Sheffer 1994): a byte per leaf holding its Chebyshev
 * distance in leaves to the nearest leaf whose range brackets the
 * isovalue, so a ray in an empty leaf at distance k jumps to the exit
 * of the (2k - 1)^3 leaves around it, all empty; and the CPU time of that walk
 * (a sketch here, not the core's code) beside the core's trace of the
 * same rays.
 * --sizes builds the macrocells here with those level sizes (macrocell(1)
 * --sizes) instead of using the stream's: how the walk's length depends on
 * the hierarchy's shape.
 *
 * Build (gipeer.mk does): cc -O2 -fopenmp -I../../src/core/... giprobe.c
 *   ../../build/libvoxlux.a -lpng -lz -lm */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vx_camera.h"
#include "vx_cellmask.h"
#include "vx_gi.h"
#include "vx_grid.h"
#include "vx_iso.h"
#include "vx_macro.h"
#include "vx_macroio.h"
#include "vx_scene.h"
#include "vx_stream.h"
#include "vx_rng.h"
#include "vx_warp.h"

#define BENCH_NAME "giprobe"
#include "benchutil.h"

static double
cpu_now(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int
keep_first(void *ctx, const vx_iso_hit *h)
{
	*(vx_iso_hit *)ctx = *h;
	return 1;
}

/* ---- --walks: the proximity walk, sketched ---- */

typedef struct blocker {
	vx_iso_hit hit;
	int found, high;
} blocker;

/* as gi.c's first_fn: a crossing into the far side (or a touch) blocks */
static int
block_fn(void *ctx, const vx_iso_hit *h)
{
	blocker *b = ctx;

	if (h->kind != VX_CELL_TOUCH && h->entering == b->high)
		return 0;
	b->hit = *h;
	b->found = 1;
	return 1;
}

/* dist_field: per leaf (n[0] x n[1] x n[2], x fastest) its Chebyshev
 * distance in leaves to the nearest leaf whose 8 samples bracket iso
 * (0 for those), capped at 255: two raster passes of the 26-neighbour
 * chamfer with unit weights (exact for this metric) */
static uint8_t *
dist_field(const vx_grid *g, double iso, const int64_t n[3])
{
	size_t nl = (size_t)n[0] * n[1] * n[2];
	uint8_t *D = malloc(nl);
	int64_t x, y, z;

	if (D == NULL)
		die("out of memory", NULL);
	for (z = 0; z < n[2]; z++)
		for (y = 0; y < n[1]; y++)
			for (x = 0; x < n[0]; x++) {
				float c[8], lo = INFINITY, hi = -INFINITY;

				vx_grid_cell(g, x, y, z, c);
				for (int k = 0; k < 8; k++) {
					lo = c[k] < lo ? c[k] : lo;
					hi = c[k] > hi ? c[k] : hi;
				}
				D[x + n[0] * (y + n[1] * z)] =
				    lo <= iso && iso <= hi ? 0 : 255;
			}
	for (int pass = 0; pass < 2; pass++) {
		int s = pass ? -1 : 1;

		for (int64_t zi = 0; zi < n[2]; zi++)
		for (int64_t yi = 0; yi < n[1]; yi++)
		for (int64_t xi = 0; xi < n[0]; xi++) {
			int64_t cx = pass ? n[0] - 1 - xi : xi;
			int64_t cy = pass ? n[1] - 1 - yi : yi;
			int64_t cz = pass ? n[2] - 1 - zi : zi;
			size_t q = (size_t)(cx + n[0] * (cy + n[1] * cz));
			int best = D[q];

			/* the 13 neighbours already passed in this order */
			for (int dz = -1; dz <= 0; dz++)
				for (int dy = -1; dy <= 1; dy++)
					for (int dx = -1; dx <= 1; dx++) {
						int64_t a = cx + s * dx, b = cy + s * dy,
						    e = cz + s * dz;
						int v;

						if (dz == 0 && (dy > 0 ||
						    (dy == 0 && dx >= 0)))
							continue;
						if (a < 0 || b < 0 || e < 0 || a >= n[0] ||
						    b >= n[1] || e >= n[2])
							continue;
						v = D[a + n[0] * (b + n[1] * e)] + 1;
						best = v < best ? v : best;
					}
			D[q] = (uint8_t)best;
		}
	}
	return D;
}

/* walk_steps: steps from t = 0 to t = tend (clipped to the leaf grid) of
 * the ray o + t d over leaves n: with D, a leaf at distance k > 0 jumps to
 * the exit of its empty cube; D == NULL steps leaf by leaf (the flat
 * walk's count) */
static long
walk_steps(const double o[3], const double d[3], double tend,
    const int64_t n[3], const uint8_t *D)
{
	double ta = 0, tb = tend, inv[3];
	long steps = 0;

	for (int a = 0; a < 3; a++) {
		inv[a] = 1 / d[a];
		if (d[a] == 0) {
			if (o[a] < 0 || o[a] > n[a])
				return 0;
			continue;
		}
		double t0 = (0 - o[a]) * inv[a], t1 = (n[a] - o[a]) * inv[a];

		if (t0 > t1) {
			double t = t0;

			t0 = t1;
			t1 = t;
		}
		ta = t0 > ta ? t0 : ta;
		tb = t1 < tb ? t1 : tb;
	}
	for (double t = ta; t < tb; ) {
		int64_t c[3];
		double texit = INFINITY;
		int k;

		for (int a = 0; a < 3; a++) {
			double p = o[a] + t * d[a];
			/* the leaf the ray is in just after t */
			int64_t f = (int64_t)floor(p);

			if (d[a] < 0 && p == (double)f)
				f--;
			c[a] = f < 0 ? 0 : f >= n[a] ? n[a] - 1 : f;
		}
		k = D ? D[c[0] + n[0] * (c[1] + n[1] * c[2])] : 0;
		steps++;
		for (int a = 0; a < 3; a++) {
			double pl, te;

			if (d[a] == 0)
				continue;
			pl = d[a] > 0 ? (double)(c[a] + (k ? k : 1)) :
			    (double)(c[a] - (k ? k - 1 : 0));
			te = (pl - o[a]) * inv[a];
			texit = te < texit ? te : texit;
		}
		if (!(texit > t))
			break;      /* no progress: rounding at a corner */
		t = texit;
	}
	return steps;
}

int
main(int argc, char **argv)
{
	const char *scene = NULL, *stream = NULL, *sizes = NULL;
	int spp = -1, flat = 0, use_mask = 0, walks = 0, i, k, npix;
	vx_err e = { 0, "" };
	vx_stream st;
	vx_scene s;
	vx_grid g;
	vx_macro m;
	vx_cellmask mask;
	vx_gi gi;
	vx_iso_tracer tr;
	vx_gi_stats gs;
	vx_iso_hit *hits;
	double lo[3], hi[3], c0, gi_cpu, prim_cpu, nr;
	long gsrc = -1;
	int status;
	double iso;             /* traced as a double, the mask's as a float */
	float isof;
	uint64_t nhit = 0;

	for (i = 1; i < argc; i++) {
		if (!strcmp(argv[i], "--scene") && i + 1 < argc)
			scene = argv[++i];
		else if (!strcmp(argv[i], "--spp") && i + 1 < argc)
			spp = atoi(argv[++i]);
		else if (!strcmp(argv[i], "--flat"))
			flat = 1;
		else if (!strcmp(argv[i], "--sizes") && i + 1 < argc)
			sizes = argv[++i];
		else if (!strcmp(argv[i], "--mask"))
			use_mask = 1;
		else if (!strcmp(argv[i], "--walks"))
			walks = 1;
		else if (argv[i][0] != '-' && stream == NULL)
			stream = argv[i];
		else
			break;
	}
	if (i < argc || scene == NULL || stream == NULL)
		die("usage: giprobe --scene FILE [--spp N] [--flat] [--mask] "
		    "[--sizes AxBxC[,DxExF...]] [--walks] STREAM", NULL);

	load_scene(&s, scene);
	if (spp > 0)
		s.pt_samples = spp;
	if (s.nsurface != 1)
		die("the scene must have exactly one surface", NULL);
	iso = s.surface[0].iso;
	isof = (float)iso;

	load_stream(&st, stream);
	if (vx_grid_from_stream(&g, &st, NULL, &gsrc, &e) != 0)
		die(stream, &e);
	if (sizes != NULL) {
		int sz[VX_MACRO_MAXLEV][3], nlev;

		if ((nlev = vx_macro_parse_sizes(sizes, sz, &e)) < 0)
			die("--sizes", &e);
		if (vx_macro_build(&m, &g, nlev, (const int (*)[3])sz, 1,
		    &e) != 0)
			die("macrocells", &e);
	} else {
		if (vx_macro_from_stream(&m, &st, &g, gsrc, &status, NULL,
		    &e) != 0)
			die("macrocells", &e);
		if (status != VX_MACRO_LOADED)
			die("the stream has no macrocells (run macrocell)",
			    NULL);
	}
	vx_stream_free(&st);
	vx_grid_box(&g, lo, hi);
	if (vx_camera_resolve(&s.camera, lo, hi, &e) != 0)
		die("camera", &e);
	if (vx_gi_setup(&gi, &s, &g, flat ? NULL : &m, &e) != 0)
		die("scene", &e);
	vx_cellmask_init(&mask);
	if (use_mask && !flat) {
		if (vx_cellmask_build(&mask, &m, &g, &isof, 1, 0, 1, &e) != 0)
			die("cell mask", &e);
		if (!mask.ready)
			die("no cell mask for these macrocells", NULL);
		gi.tr.mask = &mask;
	}
	memset(&tr, 0, sizeof tr);
	tr.g = &g;
	tr.m = &m;
	tr.solver = VX_CELL_EXACT;

	/* the primary hits (not part of the figures below) */
	npix = s.camera.w * s.camera.h;
	if ((hits = malloc(sizeof *hits * (size_t)npix)) == NULL)
		die("out of memory", NULL);
	c0 = cpu_now();
	for (k = 0; k < npix; k++) {
		double o[3], d[3], oi[3], di[3];

		vx_camera_ray(&s.camera, k % s.camera.w + 0.5,
		    k / s.camera.w + 0.5, o, d);
		vx_world_to_index(&g, o, oi);
		vx_world_to_index_dir(&g, d, di);
		hits[k].t = -1;
		if (!vx_iso_trace(&tr, oi, di, 0, INFINITY, &iso, 1,
		    keep_first, &hits[k], NULL))
			hits[k].t = -1;
	}
	prim_cpu = cpu_now() - c0;

	/* the GI part of shade(), timed alone */
	memset(&gs, 0, sizeof gs);
	c0 = cpu_now();
	for (k = 0; k < npix; k++) {
		const vx_iso_hit *h = &hits[k];
		double o[3], d[3], dw[3], n[3], P[3], D[3], E[3];
		uint64_t stream_id = 0xcbf29ce484222325u, bits;
		int high = !h->entering;

		if (h->t < 0)
			continue;
		nhit++;
		vx_camera_ray(&s.camera, k % s.camera.w + 0.5,
		    k / s.camera.w + 0.5, o, d);
		memcpy(dw, d, sizeof dw);
		vx_iso_normal(&g, h, dw, n);
		vx_index_to_world(&g, h->p, P);
		for (int a = 0; a < 3; a++) {
			memcpy(&bits, &h->p[a], sizeof bits);
			stream_id = (stream_id ^ bits) * 0x100000001b3u;
		}
		vx_gi_direct(&gi, P, h->p, n, iso, high, D, &gs);
		for (i = 0; i < s.pt_samples; i++)
			vx_gi_sample(&gi, h->p, n, iso, high, D, stream_id,
			    (uint64_t)i, E, &gs);
	}
	gi_cpu = cpu_now() - c0;

	nr = (double)gs.iso.rays > 0 ? (double)gs.iso.rays : 1;
	printf("mode %s sizes", flat ? "flat" : use_mask ? "hierarchy+mask" :
	    "hierarchy");
	for (int l = 1; l <= m.nlev; l++)
		printf("%s%dx%dx%d", l > 1 ? "," : " ", m.size[l][0],
		    m.size[l][1], m.size[l][2]);
	printf("\n");
	printf("image %dx%d spp %d iso %g\n", s.camera.w,
	    s.camera.h, s.pt_samples, iso);
	printf("primary_hits %llu primary_cpu_ms %.1f\n",
	    (unsigned long long)nhit, 1e3 * prim_cpu);
	printf("paths %llu bounce_rays %llu shadow_rays %llu bounce_hits "
	    "%llu gi_rays %llu\n", (unsigned long long)gs.samples,
	    (unsigned long long)gs.rays, (unsigned long long)gs.shadow_rays,
	    (unsigned long long)gs.hits, (unsigned long long)gs.iso.rays);
	printf("per_gi_ray");
	for (int l = m.nlev; l >= 1 && !flat; l--)
		printf(" macro_l%d %.2f", l, (double)gs.iso.trav.macro[l] / nr);
	printf(" leaves_stepped %.2f leaves_visited %.2f cells_to_kernel %.2f "
	    "roots %.2f\n", (double)(gs.iso.trav.leaves +
	    gs.iso.trav.culled) / nr, (double)gs.iso.trav.leaves / nr,
	    (double)gs.iso.cells / nr, (double)gs.iso.roots / nr);
	printf("gi_cpu_ms %.1f ns_per_path %.1f ns_per_gi_ray %.1f\n",
	    1e3 * gi_cpu, 1e9 * gi_cpu / (gs.samples ? (double)gs.samples : 1),
	    1e9 * gi_cpu / nr);
	if (walks) {
		/* the first bounce ray of every path, as vertex() in gi.c
		 * makes it */
		int64_t n[3] = { g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1 };
		double c1 = cpu_now(), t_core = 0, t_prox = 0;
		uint8_t *D = dist_field(&g, iso, n);
		double t_field = cpu_now() - c1;
		long flat_steps = 0, prox_steps = 0, nray = 0, r;
		size_t cap = (size_t)npix * (size_t)s.pt_samples;
		double (*ray)[7] = malloc(sizeof *ray * (cap ? cap : 1));
		blocker b;

		if (ray == NULL)
			die("out of memory", NULL);
		for (k = 0; k < npix; k++) {
			const vx_iso_hit *h = &hits[k];
			double o[3], d[3], n0[3], tt[3], bb[3], ni[3], l;
			uint64_t stream_id = 0xcbf29ce484222325u, bits;

			if (h->t < 0)
				continue;
			vx_camera_ray(&s.camera, k % s.camera.w + 0.5,
			    k / s.camera.w + 0.5, o, d);
			vx_iso_normal(&g, h, d, n0);
			for (int a = 0; a < 3; a++) {
				memcpy(&bits, &h->p[a], sizeof bits);
				stream_id = (stream_id ^ bits) * 0x100000001b3u;
			}
			vx_onb(n0, tt, bb);
			vx_world_to_index_dir(&g, n0, ni);
			l = sqrt(ni[0] * ni[0] + ni[1] * ni[1] + ni[2] * ni[2]);
			for (i = 0; i < s.pt_samples; i++) {
				double u[2], lw[3], w[3];

				vx_rng_ld2(gi.seed, stream_id, (uint64_t)i, 0, u);
				vx_warp_cosine_hemisphere(u, lw);
				vx_onb_to_world(n0, tt, bb, lw, w);
				for (int a = 0; a < 3; a++)
					ray[nray][a] = h->p[a] + gi.eps * ni[a] / l;
				vx_world_to_index_dir(&g, w, &ray[nray][3]);
				ray[nray][6] = !h->entering;   /* high */
				nray++;
			}
		}
		/* the core's trace of these rays (the blocking hit: where
		 * the walks end), then the two walks, each timed as a loop */
		c1 = cpu_now();
		for (r = 0; r < nray; r++) {
			b.found = 0;
			b.high = (int)ray[r][6];
			vx_iso_trace(&gi.tr, ray[r], ray[r] + 3, 0, INFINITY,
			    &iso, 1, block_fn, &b, NULL);
			ray[r][6] = b.found ? b.hit.t : INFINITY;
		}
		t_core = cpu_now() - c1;
		for (r = 0; r < nray; r++)
			flat_steps += walk_steps(ray[r], ray[r] + 3, ray[r][6], n,
			    NULL);
		c1 = cpu_now();
		for (r = 0; r < nray; r++)
			prox_steps += walk_steps(ray[r], ray[r] + 3, ray[r][6], n,
			    D);
		t_prox = cpu_now() - c1;
		free(ray);
		printf("walks first_bounce_rays %ld flat_leaf_steps %.2f "
		    "proximity_steps %.2f per ray\n", nray,
		    (double)flat_steps / (nray ? nray : 1),
		    (double)prox_steps / (nray ? nray : 1));
		printf("walks field_ms %.1f core_trace_ns %.1f "
		    "proximity_walk_ns %.1f per ray (the walk alone: no cell "
		    "kernel)\n",
		    1e3 * t_field, 1e9 * t_core / (nray ? nray : 1),
		    1e9 * t_prox / (nray ? nray : 1));
		free(D);
	}
	free(hits);
	vx_cellmask_free(&mask);
	vx_macro_free(&m);
	vx_grid_free(&g);
	return 0;
}
