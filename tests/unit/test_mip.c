/* test_mip.c: exact maximum-intensity projection: interior maxima, the
 * queue's early stop, non-finite voxels, hard rays, agreement with an
 * exhaustive walk and with dense sampling, and invariance under the
 * last-t bound, bricking and the hierarchy's shape. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "vx_camera.h"
#include "vx_cell.h"
#include "vx_mip.h"
#include "helper_ray.h"

static double
hash01(uint64_t seed, uint64_t i)
{
	uint64_t x = seed * 0x9E3779B97F4A7C15ull + i * 0xBF58476D1CE4E5B9ull;

	x ^= x >> 30;
	x *= 0xBF58476D1CE4E5B9ull;
	x ^= x >> 27;
	x *= 0x94D049BB133111EBull;
	x ^= x >> 31;
	return (double)(x >> 11) * 0x1p-53;
}

static void
make_random(vx_grid *g, const int64_t d[3], uint64_t seed,
    const char *layout)
{
	vx_err e = { 0, "" };
	uint64_t i = 0;

	assert_int_equal(vx_grid_alloc(g, d, VX_F32, layout, &e), 0);
	for (int64_t z = 0; z < d[2]; z++)
		for (int64_t y = 0; y < d[1]; y++)
			for (int64_t x = 0; x < d[0]; x++)
				vx_grid_set(g, x, y, z, 100 * hash01(seed, i++));
	vx_grid_range(g);
}

static void
build(vx_macro *m, const vx_grid *g, int nlev, int s)
{
	int sizes[VX_MACRO_MAXLEV][3];
	vx_err e = { 0, "" };

	for (int l = 0; l < nlev; l++)
		sizes[l][0] = sizes[l][1] = sizes[l][2] = s;
	assert_int_equal(vx_macro_build(m, g, nlev, (const int (*)[3])sizes, 1,
	    &e), 0);
}

/* field: the trilinear value at o + t d (clamped into the volume); NaN for
 * a cell with a non-finite corner. */
static double
field(const vx_grid *g, const double o[3], const double d[3], double t)
{
	double p[3], l[3];
	int64_t c[3];
	float v[8];

	for (int a = 0; a < 3; a++) {
		p[a] = o[a] + t * d[a];
		c[a] = (int64_t)floor(p[a]);
		if (c[a] > g->dims[a] - 2)
			c[a] = g->dims[a] - 2;
		if (c[a] < 0)
			c[a] = 0;
		l[a] = p[a] - (double)c[a];
	}
	vx_grid_cell(g, c[0], c[1], c[2], v);
	if (!vx_cell_finite(v))
		return NAN;
	return vx_cell_trilinear(v, l);
}

/* dense: the maximum of the field sampled at n + 1 points of the clipped
 * ray (a lower bound of the true maximum: oracle by brute force); with
 * zoom > 0, the search is refined zoom times around the best sample, each
 * time over the two neighbouring intervals with n more samples, which
 * converges to the maximum also where it sits on a kink (a cell face). */
static double
dense(const vx_grid *g, const double o[3], const double d[3], int n,
    int zoom)
{
	double ta, tb, best = -INFINITY, tbest = 0;

	if (!grid_segment(g, o, d, &ta, &tb))
		return -INFINITY;
	for (int r = 0; r <= zoom; r++) {
		double lo = ta, hi = tb, h = (tb - ta) / n;

		if (r > 0) {
			h = (tb - ta) / n;
			for (int k = 0; k < r; k++)
				h *= 2.0 / n;
			lo = tbest - n / 2 * h;
			hi = tbest + n / 2 * h;
			lo = lo < ta ? ta : lo;
			hi = hi > tb ? tb : hi;
		}
		for (int i = 0; i <= n; i++) {
			double t = lo + (hi - lo) * i / n, f = field(g, o, d, t);

			if (f > best) {
				best = f;
				tbest = t;
			}
		}
	}
	return best;
}

/* The interior maximum: corner (1,1,1) = 27, others 0, the ray
 * from (0,0,1) towards (1,1,0): f = 27 t^2 (1 - t) is 0 at both faces and
 * 4 at t = 2/3 (oracle: calculus on the cubic by hand). */
static void
interior_maximum(void **state)
{
	int64_t dims[3] = { 2, 2, 2 };
	vx_grid g;
	vx_macro m;
	vx_mip_work w;
	vx_err e = { 0, "" };
	double o[3] = { 0, 0, 1 }, d[3] = { 1, 1, -1 }, v, t;

	(void)state;
	assert_int_equal(vx_grid_alloc(&g, dims, VX_F32, NULL, &e), 0);
	vx_grid_set(&g, 1, 1, 1, 27);
	vx_grid_range(&g);
	build(&m, &g, 1, 2);
	assert_int_equal(vx_mip_work_init(&w, &m, &e), 0);
	assert_int_equal(vx_mip_ray(&g, &m, &w, o, d, 0, INFINITY, 0, &v, &t,
	    NULL), 1);
	assert_true(fabs(v - 4) < 1e-12);
	assert_true(fabs(t - 2.0 / 3.0) < 1e-7);
	assert_int_equal(vx_mip_ray_exhaustive(&g, o, d, 0, INFINITY, &v, &t), 1);
	assert_true(fabs(v - 4) < 1e-12);
	vx_mip_work_free(&w);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* A constant volume: the first cell solved gives the maximum and the queue
 * stops (oracle: nothing can beat a constant). */
static void
constant_volume_stops(void **state)
{
	int64_t dims[3] = { 33, 33, 33 };
	vx_grid g;
	vx_macro m;
	vx_mip_work w;
	vx_mip_stats st;
	vx_err e = { 0, "" };
	double o[3] = { -5, 3.3, 7.7 }, d[3] = { 1, 0.1, 0.05 }, v, t;

	(void)state;
	assert_int_equal(vx_grid_alloc(&g, dims, VX_U8, NULL, &e), 0);
	for (int z = 0; z < 33; z++)
		for (int y = 0; y < 33; y++)
			for (int x = 0; x < 33; x++)
				vx_grid_set(&g, x, y, z, 77);
	vx_grid_range(&g);
	build(&m, &g, 2, 4);
	assert_int_equal(vx_mip_work_init(&w, &m, &e), 0);
	for (int lt = 0; lt < 2; lt++) {
		memset(&st, 0, sizeof st);
		assert_int_equal(vx_mip_ray(&g, &m, &w, o, d, 0, INFINITY, lt, &v,
		    &t, &st), 1);
		assert_true(v == 77);
		assert_int_equal(st.cells, 1);
	}
	vx_mip_work_free(&w);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* NaN and infinite voxels: never a NaN result; where every cell on the ray
 * has a non-finite corner there is no value (oracle: the policy). */
static void
nonfinite(void **state)
{
	int64_t dims[3] = { 9, 9, 9 };
	vx_grid g;
	vx_macro m;
	vx_mip_work w;
	vx_err e = { 0, "" };
	double v, t;

	(void)state;
	make_random(&g, dims, 5, NULL);
	for (int k = 0; k < 9; k++) {
		vx_grid_set(&g, k, 4, 4, NAN);
		vx_grid_set(&g, 4, k, 4, INFINITY);
	}
	vx_grid_range(&g);
	build(&m, &g, 2, 2);
	assert_int_equal(vx_mip_work_init(&w, &m, &e), 0);
	for (int k = 0; k < 300; k++) {
		double o[3], d[3];

		for (int a = 0; a < 3; a++) {
			o[a] = 4 + 8 * (hash01(1, 3 * k + a) - 0.5);
			d[a] = hash01(2, 3 * k + a) - 0.5;
		}
		if (k % 3 == 0) {    /* along the NaN row */
			o[0] = -1; o[1] = 4; o[2] = 4;
			d[0] = 1; d[1] = d[2] = 0;
		}
		int hit = vx_mip_ray(&g, &m, &w, o, d, 0, INFINITY, 1, &v, &t, NULL);
		assert_false(isnan(v));
		assert_false(isnan(t));
		if (k % 3 == 0)
			assert_int_equal(hit, 0);
	}
	/* far eyes (a camera at 1e308): the last-t sample's point is NaN or
	 * beyond int64; no NaN result, and no conversion of either to an
	 * integer (UBSan's float-cast-overflow in SANITIZE=1 builds) */
	for (int k = 0; k < 24; k++) {
		double o[3], d[3], len = 0;

		for (int a = 0; a < 3; a++) {
			o[a] = (k >> a & 1 ? -1 : 1) * (k < 8 ? 1e308 : k < 16 ?
			    1.7e308 : 1e300);
			d[a] = 4 - o[a];
			len = fabs(d[a]) > len ? fabs(d[a]) : len;
		}
		for (int a = 0; a < 3; a++)
			d[a] /= len;
		if (k % 4 == 3)         /* what an overflowing |eye| gives */
			d[k % 3] = NAN;
		for (int lt = 0; lt < 2; lt++) {
			vx_mip_ray(&g, &m, &w, o, d, 0, INFINITY, lt, &v, &t, NULL);
			assert_false(isnan(v));
			assert_false(isnan(t));
		}
	}
	vx_mip_work_free(&w);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* Random volumes and rays, including axis-parallel rays, rays in grid
 * planes and grazing the box: the queue's maximum and its t equal the
 * exhaustive walk's bit for bit (the rule fixes both whatever the order);
 * it is never below a dense sampling (oracle: a sampled maximum is a lower
 * bound) and within 1e-6 relative of it when the sampling is fine (oracle:
 * refinement converges to the true maximum); with the last-t bound on or
 * off, bricked or linear, any hierarchy shape: the same value and t, bit
 * for bit. */
static void
randomized(void **state)
{
	int64_t dims[3] = { 11, 7, 13 };
	vx_err e = { 0, "" };
	int refined_bad = 0, refined = 0;

	(void)state;
	for (uint64_t seed = 1; seed <= 3; seed++) {
		vx_grid g, b;
		vx_macro m, m2, mb;
		vx_mip_work w, w2, wb;

		make_random(&g, dims, seed, NULL);
		make_random(&b, dims, seed, "bricked 2x2x2 2x2x2");
		build(&m, &g, 2, 2);
		build(&m2, &g, 1, 3);
		build(&mb, &b, 2, 2);
		assert_int_equal(vx_mip_work_init(&w, &m, &e), 0);
		assert_int_equal(vx_mip_work_init(&w2, &m2, &e), 0);
		assert_int_equal(vx_mip_work_init(&wb, &mb, &e), 0);
		for (int k = 0; k < 400; k++) {
			double o[3], d[3], v1, t1, v2, t2, v3, t3, v4, t4, v5, t5;
			double ve, te;

			for (int a = 0; a < 3; a++) {
				o[a] = -4 + 20 * hash01(seed * 10 + 1, 3 * k + a);
				d[a] = hash01(seed * 10 + 2, 3 * k + a) - 0.5;
			}
			if (k % 5 == 0)
				d[(k / 5) % 3] = 0;                /* in a plane */
			if (k % 7 == 0) {                          /* along a grid line */
				o[0] = -2; o[1] = (double)(k % 6); o[2] = (double)(k % 12);
				d[0] = 1; d[1] = d[2] = 0;
			}
			if (k % 11 == 0) {                         /* grazing the box */
				o[0] = -2; o[1] = 0; o[2] = 3.5;
				d[0] = 1; d[1] = 0; d[2] = 0.01;
			}
			int h1 = vx_mip_ray(&g, &m, &w, o, d, 0, INFINITY, 0, &v1,
			    &t1, NULL);
			int h2 = vx_mip_ray(&g, &m, &w, o, d, 0, INFINITY, 1, &v2,
			    &t2, NULL);
			int h3 = vx_mip_ray(&b, &mb, &wb, o, d, 0, INFINITY, 1, &v3,
			    &t3, NULL);
			int h4 = vx_mip_ray(&g, &m2, &w2, o, d, 0, INFINITY, 1, &v4,
			    &t4, NULL);
			int he = vx_mip_ray_exhaustive(&g, o, d, 0, INFINITY, &ve,
			    &te);
			(void)v5; (void)t5;
			assert_int_equal(h1, he);
			assert_int_equal(h2, he);
			assert_int_equal(h3, he);
			assert_int_equal(h4, he);
			if (!he)
				continue;
			if (!(v1 == ve && t1 == te && v2 == v1 && t2 == t1 &&
			    v3 == v1 && t3 == t1 && v4 == v1 && t4 == t1))
				fail_msg("seed %llu ray %d: %.17g %.17g %.17g %.17g vs "
				    "exhaustive %.17g (t %.17g %.17g vs %.17g)",
				    (unsigned long long)seed, k, v1, v2, v3, v4, ve,
				    t1, t4, te);
			double ds = dense(&g, o, d, 2000, 0);
			assert_true(v1 >= ds - 1e-9 * fabs(ds));
			if (k % 4 == 0) {
				double fine = dense(&g, o, d, 2000, 6);
				refined++;
				if (!(fabs(v1 - fine) <= 1e-6 * fabs(v1) + 1e-12))
					refined_bad++;
			}
		}
		vx_mip_work_free(&w);
		vx_mip_work_free(&w2);
		vx_mip_work_free(&wb);
		vx_macro_free(&m);
		vx_macro_free(&m2);
		vx_macro_free(&mb);
		vx_grid_free(&g);
		vx_grid_free(&b);
	}
	if (refined_bad)
		fail_msg("%d of %d refined samplings differ by more than 1e-6",
		    refined_bad, refined);
}

/* make_typed: a volume of type t whose integer samples take few distinct
 * values (so that equal maxima, i.e. ties, are common) and whose f32
 * samples include NaN and Inf. */
static void
make_typed(vx_grid *g, const int64_t dims[3], vx_type t, const char *layout,
    uint64_t seed)
{
	vx_err e = { 0, "" };
	uint64_t i = 0;

	assert_int_equal(vx_grid_alloc(g, dims, t, layout, &e), 0);
	for (int64_t z = 0; z < dims[2]; z++)
		for (int64_t y = 0; y < dims[1]; y++)
			for (int64_t x = 0; x < dims[0]; x++, i++) {
				double h = hash01(seed, i), v;

				switch (t) {
				case VX_U8: v = 17 * floor(h * 16); break;
				case VX_U16: v = 4000 * floor(h * 9); break;
				case VX_I16: v = 1000 * floor(h * 9) - 4000; break;
				default:
					v = h < 0.01 ? NAN : h > 0.995 ? INFINITY :
					    100 * h - 50;
					break;
				}
				vx_grid_set(g, x, y, z, v);
			}
	vx_grid_range(g);
}

/* The specialized walks (fused, typed, the default) against the plain walk
 * (walk() with a visitor per cell, w.plain = 1): every ray gives the same
 * hit, the same value and t bit for bit, and the same queue and cell
 * counts, for each sample type (integer ones with many equal samples, so
 * that ties decide t; f32 with NaN and Inf), linear and bricked layouts,
 * hierarchies of 0 to 3 levels, the last-t bound on, and rays along axes,
 * in grid planes, through lattice lines and corners, grazing the box
 * (oracle: the plain walk is the straightforward implementation). */
static void
fast_equals_plain(void **state)
{
	static const vx_type types[] = { VX_U8, VX_U16, VX_I16, VX_F32 };
	static const char *const layouts[] = { NULL, "bricked 2x2x2 2x2x2",
	    "bricked 4x4x4" };
	static const int shapes[][2] = { { 0, 1 }, { 1, 2 }, { 2, 2 },
	    { 1, 3 }, { 3, 2 } };
	int64_t dims[3] = { 12, 9, 14 };
	vx_err e = { 0, "" };
	int rays = 0;

	(void)state;
	for (size_t ti = 0; ti < sizeof types / sizeof *types; ti++)
	for (size_t li = 0; li < sizeof layouts / sizeof *layouts; li++)
	for (size_t si = 0; si < sizeof shapes / sizeof *shapes; si++) {
		vx_grid g;
		vx_macro m;
		vx_mip_work wf, wp;
		uint64_t seed = 100 * ti + 10 * li + si + 1;

		make_typed(&g, dims, types[ti], layouts[li], seed);
		build(&m, &g, shapes[si][0], shapes[si][1]);
		assert_int_equal(vx_mip_work_init(&wf, &m, &e), 0);
		assert_int_equal(vx_mip_work_init(&wp, &m, &e), 0);
		wp.plain = 1;
		for (int k = 0; k < 240; k++, rays++) {
			double o[3], d[3], vf, tf, vp, tp;
			vx_mip_stats sf, sp;

			for (int a = 0; a < 3; a++) {
				o[a] = -3 + 20 * hash01(seed * 7 + 1, 3 * k + a);
				d[a] = hash01(seed * 7 + 2, 3 * k + a) - 0.5;
			}
			switch (k % 8) {
			case 1:                          /* along an axis */
				d[0] = d[1] = d[2] = 0;
				d[k / 8 % 3] = k % 16 < 8 ? 1 : -1;
				o[(k / 8 + 1) % 3] = floor(o[(k / 8 + 1) % 3]);
				break;
			case 2:                          /* in a grid plane */
				d[k / 8 % 3] = 0;
				break;
			case 3:                          /* through lattice lines */
				for (int a = 0; a < 3; a++)
					o[a] = floor(o[a]);
				d[0] = 1; d[1] = k % 16 < 8 ? 1 : -1; d[2] = 0;
				break;
			case 4:                          /* through corners */
				o[0] = -2; o[1] = -2 + k % 3; o[2] = -1;
				d[0] = 1; d[1] = 1; d[2] = k % 16 < 8 ? 1 : 0.5;
				break;
			case 5:                          /* grazing the box */
				o[0] = -2; o[1] = 0; o[2] = 3.5;
				d[0] = 1; d[1] = 0; d[2] = 0.01;
				break;
			default:
				break;
			}
			memset(&sf, 0, sizeof sf);
			memset(&sp, 0, sizeof sp);
			int hf = vx_mip_ray(&g, &m, &wf, o, d, 0, INFINITY, 1, &vf,
			    &tf, &sf);
			int hp = vx_mip_ray(&g, &m, &wp, o, d, 0, INFINITY, 1, &vp,
			    &tp, &sp);
			/* the column walk (integer samples, rays along an axis)
			 * has no queue: its counts differ */
			int column = k % 8 == 1 && types[ti] != VX_F32;

			if (hf != hp || memcmp(&vf, &vp, sizeof vf) != 0 ||
			    memcmp(&tf, &tp, sizeof tf) != 0 ||
			    (!column && memcmp(&sf, &sp, sizeof sf) != 0))
				fail_msg("type %d layout %zu shape %zu ray %d: fast %d "
				    "%.17g %.17g (%llu cells %llu pushes), plain %d "
				    "%.17g %.17g (%llu cells %llu pushes)",
				    (int)types[ti], li, si, k, hf, vf, tf,
				    (unsigned long long)sf.cells,
				    (unsigned long long)sf.pushes, hp, vp, tp,
				    (unsigned long long)sp.cells,
				    (unsigned long long)sp.pushes);
		}
		vx_mip_work_free(&wf);
		vx_mip_work_free(&wp);
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
	assert_int_equal(rays, 4 * 3 * 5 * 240);
}

/* Rays along an axis (the axis-aligned views' own walk, cells_axis_t)
 * against the plain walk, as above, with what that walk decides once per
 * ray: the start and end cell from tmin and tmax cut anywhere (inside a
 * cell, exactly on a sample plane, before the box, empty), origins on
 * sample planes, lattice lines and the box's faces, directions of several
 * lengths and both signs, -0.0 components, several rays in one column
 * (the column walk's cache), and hierarchies of 0 to 2 levels (oracle: the
 * plain walk). */
static void
axis_rays_equal_plain(void **state)
{
	static const vx_type types[] = { VX_U8, VX_U16, VX_I16, VX_F32 };
	static const char *const layouts[] = { NULL, "bricked 4x4x4" };
	static const int shapes[][2] = { { 0, 1 }, { 1, 3 }, { 2, 2 },
	    { 2, 4 } };
	static const double lens[] = { 1, 0.37, 3, 1.0 / 1024, 40 };
	int64_t dims[3] = { 13, 10, 15 };
	vx_err e = { 0, "" };
	int rays = 0;

	(void)state;
	for (size_t ti = 0; ti < sizeof types / sizeof *types; ti++)
	for (size_t li = 0; li < sizeof layouts / sizeof *layouts; li++)
	for (size_t si = 0; si < sizeof shapes / sizeof *shapes; si++) {
		vx_grid g;
		vx_macro m;
		vx_mip_work wf, wp;
		uint64_t seed = 1000 + 100 * ti + 10 * li + si;

		make_typed(&g, dims, types[ti], layouts[li], seed);
		build(&m, &g, shapes[si][0], shapes[si][1]);
		assert_int_equal(vx_mip_work_init(&wf, &m, &e), 0);
		assert_int_equal(vx_mip_work_init(&wp, &m, &e), 0);
		wp.plain = 1;
		for (int k = 0; k < 300; k++, rays++) {
			/* 4 rays in a row share their axis and cell column (the
			 * column walk's cache is then used and filled) */
			int A = k / 4 % 3, U = A == 0 ? 1 : 0, V = A == 2 ? 1 : 2;
			double o[3], d[3] = { 0, 0, 0 }, vf, tf, vp, tp;
			double len = lens[k / 3 % 5], tmin = 0, tmax = INFINITY;
			double h = hash01(seed, 10 * k);
			vx_mip_stats sf, sp;

			d[A] = (k / 15 % 2 ? -1 : 1) * len;
			if (k % 4 == 1)
				d[U] = -0.0;
			o[A] = d[A] > 0 ? -2.5 : (double)dims[A] + 1.5;
			if (k % 9 == 4)            /* starting on a sample plane */
				o[A] = floor(h * (double)dims[A]);
			o[U] = floor((double)(dims[U] - 1) * hash01(seed, k / 4)) +
			    hash01(seed, 10 * k + 1);
			o[V] = floor((double)(dims[V] - 1) * hash01(seed + 1, k / 4)) +
			    hash01(seed, 10 * k + 2);
			switch (k / 2 % 5) {
			case 1:                  /* on a lattice line */
				o[U] = floor(o[U]);
				o[V] = floor(o[V]);
				break;
			case 2:                  /* on the box's faces */
				o[U] = 0;
				o[V] = (double)(dims[V] - 1);
				break;
			case 3:                  /* outside the box */
				o[U] = -0.25;
				break;
			default:
				break;
			}
			switch (k / 7 % 6) {
			case 1:                  /* cut inside cells */
				tmin = (2 + 10 * hash01(seed, 10 * k + 3)) / len;
				tmax = tmin + 8 * hash01(seed, 10 * k + 4) / len;
				break;
			case 2:                  /* cut on sample planes */
				tmin = (fabs(o[A] - floor(o[A])) + 4) / len;
				tmax = tmin + 5 / len;
				break;
			case 3:                  /* an empty segment */
				tmin = 5 / len;
				tmax = 4 / len;
				break;
			case 4:                  /* a single point */
				tmin = tmax = (3.5 + fabs(o[A] - floor(o[A]))) /
				    len;
				break;
			default:
				break;
			}
			memset(&sf, 0, sizeof sf);
			memset(&sp, 0, sizeof sp);
			int hf = vx_mip_ray(&g, &m, &wf, o, d, tmin, tmax, k % 2,
			    &vf, &tf, &sf);
			int hp = vx_mip_ray(&g, &m, &wp, o, d, tmin, tmax, k % 2,
			    &vp, &tp, &sp);
			/* the column walk (integer samples) has no queue: its
			 * counts differ; f32 rays take the queue */
			int column = types[ti] != VX_F32;

			if (hf != hp || memcmp(&vf, &vp, sizeof vf) != 0 ||
			    memcmp(&tf, &tp, sizeof tf) != 0 ||
			    (!column && memcmp(&sf, &sp, sizeof sf) != 0))
				fail_msg("type %d layout %zu shape %zu ray %d: fast %d "
				    "%.17g %.17g (%llu cells %llu skipped), plain %d "
				    "%.17g %.17g (%llu cells %llu skipped)",
				    (int)types[ti], li, si, k, hf, vf, tf,
				    (unsigned long long)sf.cells,
				    (unsigned long long)sf.cells_skipped, hp, vp, tp,
				    (unsigned long long)sp.cells,
				    (unsigned long long)sp.cells_skipped);
		}
		vx_mip_work_free(&wf);
		vx_mip_work_free(&wp);
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
	assert_int_equal(rays, 4 * 2 * 4 * 300);
}

/* Ties: equal maxima at several places go to the smallest t, whatever
 * the hierarchy, the walk (queue, column) and the direction: two peaks of
 * 50 on one grid line, everything else 10, and a constant volume
 * (oracle: the rule, with the peaks' positions worked out by hand: the
 * ray o + t d meets x = 3 at t = 3 + 2 = 5 coming from x = -2, and x = 9
 * at t = 13 - 9 = 4 coming from x = 13). */
static void
ties_smallest_t(void **state)
{
	static const vx_type types[] = { VX_U8, VX_I16, VX_F32 };
	static const int shapes[][2] = { { 0, 1 }, { 1, 2 }, { 2, 2 },
	    { 1, 4 }, { 2, 3 } };
	int64_t dims[3] = { 12, 6, 7 };
	vx_err e = { 0, "" };

	(void)state;
	for (size_t ti = 0; ti < sizeof types / sizeof *types; ti++)
	for (size_t si = 0; si < sizeof shapes / sizeof *shapes; si++)
	for (int cst = 0; cst < 2; cst++) {
		vx_grid g;
		vx_macro m;
		vx_mip_work w, wp;

		assert_int_equal(vx_grid_alloc(&g, dims, types[ti], NULL, &e), 0);
		for (int64_t z = 0; z < dims[2]; z++)
			for (int64_t y = 0; y < dims[1]; y++)
				for (int64_t x = 0; x < dims[0]; x++)
					vx_grid_set(&g, x, y, z, cst ? 20 : 10);
		if (!cst) {
			vx_grid_set(&g, 3, 2, 4, 50);
			vx_grid_set(&g, 9, 2, 4, 50);
		}
		vx_grid_range(&g);
		build(&m, &g, shapes[si][0], shapes[si][1]);
		assert_int_equal(vx_mip_work_init(&w, &m, &e), 0);
		assert_int_equal(vx_mip_work_init(&wp, &m, &e), 0);
		wp.plain = 1;
		for (int dir = 0; dir < 2; dir++)
		for (int lt = 0; lt < 2; lt++)
		for (int pl = 0; pl < 2; pl++) {
			double o[3] = { dir ? 13 : -2, 2, 4 }, d[3] = { dir ? -1 : 1,
			    0, 0 }, v, t;
			double d2[3] = { dir ? -1 : 1, 0, 1e-3 };

			assert_int_equal(vx_mip_ray(&g, &m, pl ? &wp : &w, o, d, 0,
			    INFINITY, lt, &v, &t, NULL), 1);
			assert_true(v == (cst ? 20 : 50));
			/* constant: the entry, at x = 11 or x = 0 */
			assert_true(t == (cst ? 2 : dir ? 4 : 5));
			/* a ray slightly off the line: no exact tie, but the
			 * same answer as the exhaustive walk */
			double ve, te;

			assert_int_equal(vx_mip_ray(&g, &m, pl ? &wp : &w, o, d2, 0,
			    INFINITY, lt, &v, &t, NULL), 1);
			assert_int_equal(vx_mip_ray_exhaustive(&g, o, d2, 0,
			    INFINITY, &ve, &te), 1);
			assert_true(v == ve && t == te);
		}
		vx_mip_work_free(&w);
		vx_mip_work_free(&wp);
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
}

/* bilin: the multilinear interpolation of g's samples at index point p
 * (each coordinate within the samples' range), in long double from the
 * samples written out: a one-sample axis contributes its only sample. */
static long double
bilin(const vx_grid *g, const double p[3])
{
	long double sum = 0;
	int64_t c[3];
	long double l[3];

	for (int a = 0; a < 3; a++) {
		c[a] = g->dims[a] < 2 ? 0 : (int64_t)floor(p[a]);
		if (g->dims[a] >= 2 && c[a] > g->dims[a] - 2)
			c[a] = g->dims[a] - 2;
		l[a] = g->dims[a] < 2 ? 0 : (long double)p[a] - c[a];
	}
	for (int i = 0; i < 8; i++) {
		long double w = 1;
		int64_t q[3];

		for (int a = 0; a < 3; a++) {
			int b = i >> a & 1;

			if (g->dims[a] < 2 && b)
				w = 0;
			w *= b ? l[a] : 1 - l[a];
			q[a] = c[a] + b;
		}
		if (w != 0)
			sum += w * vx_grid_get(g, q[0], q[1], q[2]);
	}
	return sum;
}

/* Volumes with an axis of one sample have no cells: their MIP is the
 * slice (or line, or point) itself.  A ray crossing it meets it at the one
 * t where its coordinate on that axis is 0, and the value there is the
 * bilinear (linear) interpolation of the samples (oracle: bilin, the
 * weights written out); a ray inside the slice gets the maximum along it,
 * never below a dense sampling and within 1e-9 of a fine one (oracle: the
 * field along it); the queue's answer equals the exhaustive one bit for
 * bit; rays beside a line or a point miss. */
static void
one_sample_axes(void **state)
{
	static const int64_t shapes[][3] = { { 7, 5, 1 }, { 6, 1, 4 },
	    { 1, 5, 6 }, { 1, 1, 9 }, { 8, 1, 1 }, { 1, 1, 1 } };
	vx_err e = { 0, "" };

	(void)state;
	for (size_t si = 0; si < sizeof shapes / sizeof shapes[0]; si++) {
		const int64_t *n = shapes[si];
		vx_grid g;
		vx_macro m;
		vx_mip_work w;
		int crossed = 0, inside = 0;

		make_random(&g, n, 40 + si, NULL);
		build(&m, &g, 2, 2);
		assert_int_equal(vx_mip_work_init(&w, &m, &e), 0);
		for (int k = 0; k < 400; k++) {
			double o[3], d[3], q[3], v, t, ve, te;
			int flat = k % 4 == 3, hit, he;

			/* aim at a point of the span (a sample point every
			 * fifth ray), from a random direction */
			for (int a = 0; a < 3; a++) {
				q[a] = n[a] < 2 ? 0 : (k % 5 == 0 ?
				    (double)(int64_t)(hash01(3, 3 * k + a) *
				    (double)n[a]) : hash01(3, 3 * k + a) *
				    (double)(n[a] - 1));
				d[a] = hash01(4, 3 * k + a) - 0.5;
			}
			if (flat)    /* inside the span: no motion off it */
				for (int a = 0; a < 3; a++)
					if (n[a] < 2)
						d[a] = 0;
			if (d[0] == 0 && d[1] == 0 && d[2] == 0)
				continue;
			for (int a = 0; a < 3; a++)
				o[a] = n[a] < 2 && (flat || d[a] == 0) ? 0 :
				    q[a] - 20 * d[a];
			hit = vx_mip_ray(&g, &m, &w, o, d, 0, INFINITY, k % 2,
			    &v, &t, NULL);
			he = vx_mip_ray_exhaustive(&g, o, d, 0, INFINITY, &ve,
			    &te);
			assert_int_equal(hit, he);
			if (hit)
				assert_true(v == ve && t == te);
			if (!flat) {
				int pin = 0;
				double p[3];

				for (int a = 0; a < 3; a++)
					pin |= n[a] < 2 && d[a] != 0;
				if (!pin)
					continue;
				/* the crossing: hit when every one-sample axis
				 * is crossed at the same t and the point lies
				 * in the span */
				int want = 1;
				double ts = NAN;

				for (int a = 0; a < 3; a++)
					if (n[a] < 2 && d[a] != 0) {
						double ta = -o[a] / d[a];

						want &= !(ts == ts) || ta == ts;
						ts = ta;
					} else if (n[a] < 2 && o[a] != 0)
						want = 0;
				for (int a = 0; a < 3 && want; a++) {
					p[a] = n[a] < 2 ? 0 : o[a] + ts * d[a];
					want &= p[a] >= 0 && p[a] <= n[a] - 1;
				}
				assert_int_equal(hit, want);
				if (!hit)
					continue;
				crossed++;
				assert_true(t == ts);
				long double b = bilin(&g, p);
				if (!(fabsl(v - b) <= 1e-12L * (fabsl(b) + 1)))
					fail_msg("shape %zu ray %d: %.17g, bilinear "
					    "%.17Lg", si, k, v, b);
			} else if (hit) {
				/* the span along the ray: dense sampling */
				double best = -INFINITY, ta = 0;   /* tmin */
				double tb = INFINITY;

				inside++;
				for (int a = 0; a < 3; a++) {
					if (n[a] < 2 || d[a] == 0)
						continue;
					double t0 = -o[a] / d[a], t1 = ((double)
					    (n[a] - 1) - o[a]) / d[a];
					if (t0 > t1) {
						double sw = t0;
						t0 = t1;
						t1 = sw;
					}
					ta = t0 > ta ? t0 : ta;
					tb = t1 < tb ? t1 : tb;
				}
				for (int j = 0; j <= 4000; j++) {
					double tt = ta + (tb - ta) * j / 4000, p[3];

					for (int a = 0; a < 3; a++)
						p[a] = n[a] < 2 ? 0 : o[a] + tt * d[a];
					for (int a = 0; a < 3; a++) {
						p[a] = p[a] < 0 ? 0 : p[a];
						p[a] = p[a] > n[a] - 1 ? n[a] - 1 : p[a];
					}
					long double f = bilin(&g, p);
					best = f > best ? (double)f : best;
				}
				if (!(v >= best - 1e-9 * fabs(best)))
					fail_msg("shape %zu ray %d: %.17g below the "
					    "sampled %.17g", si, k, v, best);
				assert_true(v <= best + 1e-2 * (fabs(best) + 1));
			}
		}
		/* each shape with a plane or a line sees crossings */
		if (n[0] * n[1] * n[2] > 1)
			assert_true(crossed > 0);
		if (n[0] * n[1] * n[2] > 1)
			assert_true(inside > 0);
		vx_mip_work_free(&w);
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
}

/* MIP never above the exact maximum: a 2x2x2 volume holding the double-
 * root cell less 4 (corners -4 ... 23, floats), whose field along the line
 * (0,0,1) + u (1,1,-1) is exactly 27 u^2 (1 - u) - 4, maximum 0 at u = 2/3
 * (oracle: the algebra); rays along it both ways, starting inside the
 * cell at u = 1/8 .. 7/8 (so the cubic in t is the affine image u = be +
 * al t), with al = 1..9 odd times 2^-3..2^3, the volume scaled by 2^-60
 * .. 2^60.  The queue and the exhaustive walk give one value, never above
 * 0 (7 of 490 rays were, by 4.4e-16, before) and within 1e-10 of it. */
static void
never_above_exact(void **state)
{
	int64_t dims[3] = { 2, 2, 2 };
	vx_err e = { 0, "" };

	(void)state;
	for (int sc = -60; sc <= 60; sc += 30) {
		vx_grid g;
		vx_macro m;
		vx_mip_work w;
		double f = ldexp(1, sc);

		assert_int_equal(vx_grid_alloc(&g, dims, VX_F32, NULL, &e), 0);
		for (int i = 0; i < 8; i++)
			vx_grid_set(&g, i & 1, i >> 1 & 1, i >> 2, ((i == 7 ? 27 :
			    0) - 4) * f);
		vx_grid_range(&g);
		build(&m, &g, 1, 2);
		assert_int_equal(vx_mip_work_init(&w, &m, &e), 0);
		for (int ai = 1; ai <= 9; ai += 2)
			for (int ae = -3; ae <= 3; ae++)
				for (int bi = 1; bi <= 7; bi++)
					for (int r = 0; r < 2; r++) {
			double al = ldexp(ai, ae), be = bi / 8.0, o[3], d[3];
			double v, t, ve, te;

			for (int a = 0; a < 3; a++) {
				double sg = a < 2 ? 1 : -1;   /* along (1,1,-1) */
				double u0 = r ? 1 - be : be;

				o[a] = (a < 2 ? 0 : 1) + sg * u0;
				d[a] = (r ? -sg : sg) * al;
			}
			assert_int_equal(vx_mip_ray(&g, &m, &w, o, d, 0, INFINITY,
			    1, &v, &t, NULL), 1);
			assert_int_equal(vx_mip_ray_exhaustive(&g, o, d, 0,
			    INFINITY, &ve, &te), 1);
			assert_true(v == ve && t == te);
			/* the segment holds u = 2/3 (maximum 0), or its
			 * maximum is at the start u0: g(u0), exact */
			double u0 = r ? 1 - be : be;
			double want = (r ? u0 > 2.0 / 3 : u0 < 2.0 / 3) ? 0 :
			    (27 * u0 * u0 * (1 - u0) - 4) * f;
			if (!(v <= want && v >= want - 1e-10 * f))
				fail_msg("scale 2^%d al %g be %g ray %d: %.17g "
				    "(exact maximum %.17g)", sc, al, be, r, v,
				    want);
		}
		vx_mip_work_free(&w);
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
}

static int
same_f(float a, float b)
{
	return memcmp(&a, &b, sizeof a) == 0;
}

/* render_equals_rays: vx_mip_render's pictures, for a u8 volume (rays
 * along an axis take the column walk) and an f32 one with a NaN voxel, an
 * axis-aligned orthographic view and a perspective one that sees past the
 * volume, images that are not a whole number of tiles, 1 and 3 threads,
 * tiles of 16, 7 and 5, the last-t bound on and off, the exhaustive mode.
 * Oracle: pixel (x, y) is vx_mip_ray_exhaustive on the camera ray through
 * its centre, value and depth bit for bit, and the volume's minimum
 * (depth +Inf) where that ray finds nothing. */
static void
render_equals_rays(void **state)
{
	static const int64_t d[3] = { 13, 11, 9 };
	static const struct { int nthreads, tile, last_t, exhaustive; } cfg[] = {
		{ 1, 16, 1, 0 }, { 3, 16, 1, 0 }, { 3, 5, 0, 0 }, { 2, 7, 1, 1 },
	};
	vx_err e = { 0, "" };

	(void)state;
	for (int vol = 0; vol < 2; vol++) {
		vx_grid g;
		vx_macro m;
		double lo[3], hi[3];

		if (vol == 0) {
			uint64_t i = 0;

			assert_int_equal(vx_grid_alloc(&g, d, VX_U8, "linear", &e),
			    0);
			for (int64_t z = 0; z < d[2]; z++)
				for (int64_t y = 0; y < d[1]; y++)
					for (int64_t x = 0; x < d[0]; x++)
						vx_grid_set(&g, x, y, z,
						    floor(255 * hash01(7, i++)));
			vx_grid_range(&g);
		} else {
			make_random(&g, d, 11, "linear");
			vx_grid_set(&g, 4, 5, 6, NAN);
			vx_grid_range(&g);
		}
		build(&m, &g, 2, 3);
		vx_grid_box(&g, lo, hi);
		for (int view = 0; view < 2; view++) {
			vx_camera cam;

			vx_camera_init(&cam);
			cam.w = 23;
			cam.h = 17;
			if (view == 0) {
				cam.projection = VX_ORTHOGRAPHIC;
				cam.view = VX_VIEW_TOP;
			} else {
				cam.view = VX_VIEW_ANGLES;
				cam.azimuth = 30;
				cam.elevation = 20;
				cam.distance = 0.8;   /* the box spills over */
			}
			assert_int_equal(vx_camera_resolve(&cam, lo, hi, &e), 0);
			for (size_t c = 0; c < sizeof cfg / sizeof cfg[0]; c++) {
				vx_mip_opts o;
				vx_mip_stats st;
				vx_image val, dep;
				int misses = 0;

				vx_mip_opts_init(&o);
				o.nthreads = cfg[c].nthreads;
				o.tile = cfg[c].tile;
				o.last_t = cfg[c].last_t;
				o.exhaustive = cfg[c].exhaustive;
				vx_image_init(&val);
				vx_image_init(&dep);
				assert_int_equal(vx_mip_render(&cam, &g, &m, &o, &val,
				    &dep, &st, &e), 0);
				assert_int_equal(val.w, 23);
				assert_int_equal(dep.h, 17);
				assert_int_equal(st.threads, cfg[c].nthreads);
				assert_int_equal(st.rays, cfg[c].exhaustive ? 0 :
				    23 * 17);
				for (int y = 0; y < 17; y++)
					for (int x = 0; x < 23; x++) {
						double ow[3], dw[3], oi[3], di[3], v, t;
						int hit;

						vx_camera_ray(&cam, x + 0.5, y + 0.5, ow, dw);
						vx_world_to_index(&g, ow, oi);
						vx_world_to_index_dir(&g, dw, di);
						hit = vx_mip_ray_exhaustive(&g, oi, di, 0,
						    INFINITY, &v, &t);
						misses += !hit;
						assert_true(same_f(*vx_image_pixel(&val, x,
						    y), (float)(hit ? v : g.vmin)));
						assert_true(same_f(*vx_image_pixel(&dep, x,
						    y), (float)(hit ? t : INFINITY)));
					}
				/* both views see the volume and past it (the
				 * top view's frame is wider than the box) */
				assert_true(misses > 0 && misses < 23 * 17);
				vx_image_free(&val);
				vx_image_free(&dep);
			}
		}
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(never_above_exact),
		cmocka_unit_test(one_sample_axes),
		cmocka_unit_test(interior_maximum),
		cmocka_unit_test(constant_volume_stops),
		cmocka_unit_test(nonfinite),
		cmocka_unit_test(randomized),
		cmocka_unit_test(fast_equals_plain),
		cmocka_unit_test(axis_rays_equal_plain),
		cmocka_unit_test(ties_smallest_t),
		cmocka_unit_test(render_equals_rays),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
