/* test_iso.c: rays against isosurfaces of whole volumes: no holes, no double
 * hits, hierarchy = flat = bricked bit for bit, hard cells through the real
 * traversal, non-finite voxels, scale invariance. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "vx_iso.h"
#include "helper_ray.h"

/* hash01: a deterministic number in [0,1) from (seed, i). */
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

/* sphere: an n^3 f32 volume holding the distance from the centre, in
 * samples: the isosurface r is a closed surface for r < (n-1)/2. */
static void
make_sphere(vx_grid *g, int n, const char *layout)
{
	int64_t d[3] = { n, n, n };
	vx_err e = { 0, "" };
	double c = (n - 1) / 2.0;

	assert_int_equal(vx_grid_alloc(g, d, VX_F32, layout, &e), 0);
	for (int z = 0; z < n; z++)
		for (int y = 0; y < n; y++)
			for (int x = 0; x < n; x++)
				vx_grid_set(g, x, y, z, sqrt((x - c) * (x - c) +
				    (y - c) * (y - c) + (z - c) * (z - c)));
	vx_grid_range(g);
}

static void
make_random(vx_grid *g, int n, uint64_t seed, const char *layout)
{
	int64_t d[3] = { n, n + 1, n + 2 };
	vx_err e = { 0, "" };
	uint64_t i = 0;

	assert_int_equal(vx_grid_alloc(g, d, VX_F32, layout, &e), 0);
	for (int z = 0; z < n + 2; z++)
		for (int y = 0; y < n + 1; y++)
			for (int x = 0; x < n; x++)
				vx_grid_set(g, x, y, z, hash01(seed, i++));
	vx_grid_range(g);
}

typedef struct collect {
	int n;
	double t[256];
	int surf[256];
	int entering[256];
	int kind[256];
	int64_t cell[256][3];
} collect;

static int
collect_hit(void *ctx, const vx_iso_hit *h)
{
	collect *c = ctx;

	if (c->n < 256) {
		c->t[c->n] = h->t;
		c->surf[c->n] = h->surface;
		c->entering[c->n] = h->entering;
		c->kind[c->n] = h->kind;
		memcpy(c->cell[c->n], h->cell, sizeof h->cell);
	}
	c->n++;
	return 0;
}

static void
trace_all(const vx_iso_tracer *tr, const double o[3], const double d[3],
    const double *iso, int niso, collect *c)
{
	memset(c, 0, sizeof *c);
	vx_iso_trace(tr, o, d, 0, INFINITY, iso, niso, collect_hit, c, NULL);
}

/* No holes, no double hits: rays from outside through a closed sphere
 * cross it an even number of times, alternately entering and leaving
 * (oracle: the Jordan curve property of a closed surface), and exactly
 * twice when the line passes clearly inside (oracle: geometry of the
 * sphere, whose trilinear isosurface stays within a fraction of a voxel of
 * the true one).  The ray set includes rays in grid planes and along grid
 * lines, through cell edges and vertices. */
static void
sphere_no_holes(void **state)
{
	vx_grid g;
	vx_macro m;
	vx_err e = { 0, "" };
	int sizes[VX_MACRO_MAXLEV][3];
	double iso = 9.3f;
	int n = 24, bad = 0, tested = 0;
	double c = (n - 1) / 2.0;

	(void)state;
	make_sphere(&g, n, NULL);
	int nlev = vx_macro_default_sizes(VX_F32, 2, sizes);
	assert_int_equal(vx_macro_build(&m, &g, nlev, (const int (*)[3])sizes,
	    1, &e), 0);
	vx_iso_tracer tr = { &g, &m, 0, VX_CELL_EXACT, NULL, 0 };
	for (int k = 0; k < 4000; k++) {
		double o[3], d[3], q[3], len = 0;
		collect col;

		/* a target point inside the sphere's bounding region: grid
		 * points, edge midpoints and random points */
		for (int a = 0; a < 3; a++) {
			double r = hash01(7, 3 * k + a);

			q[a] = k % 3 == 0 ? floor(c - 8 + 16 * r) :
			    k % 3 == 1 ? floor(c - 8 + 16 * r) + (a == 0 ? 0.5 : 0) :
			    c - 8 + 16 * r;
		}
		for (int a = 0; a < 3; a++) {
			d[a] = hash01(11, 3 * k + a) - 0.5;
			if (k % 5 == 0 && a > 0)
				d[a] = 0;          /* axis-parallel: along grid lines */
			if (k % 5 == 1 && a == 2)
				d[a] = 0;          /* in a grid plane */
			len += d[a] * d[a];
		}
		if (len == 0)
			continue;
		for (int a = 0; a < 3; a++)
			o[a] = q[a] - 40 * d[a] / sqrt(len);
		trace_all(&tr, o, d, &iso, 1, &col);
		tested++;
		if (col.n % 2 != 0)
			bad++;
		for (int i = 0; i < col.n && i < 256; i++)
			if (col.entering[i] != (i % 2 == 1))
				bad++;  /* f >= iso is outside the sphere: the ray
				           leaves that set first, then re-enters */
		/* distance of the line from the centre */
		double w[3], dd = 0, wd = 0;
		for (int a = 0; a < 3; a++) {
			w[a] = c - o[a];
			wd += w[a] * d[a];
		}
		for (int a = 0; a < 3; a++) {
			double p = w[a] - wd / len * d[a];
			dd += p * p;
		}
		if (sqrt(dd) < iso - 1 && col.n != 2)
			bad++;
		if (sqrt(dd) > iso + 1 && col.n != 0)
			bad++;
	}
	if (bad)
		fail_msg("%d of %d rays through the sphere broke parity", bad,
		    tested);
	vx_macro_free(&m);
	vx_grid_free(&g);
}


/* Adversarial rays for crack-freedom: each aimed at a point where the
 * isosurface meets a cell face (found by solving the face's bilinear
 * interpolant for the isovalue), from a random direction, so the crossing
 * lies on the shared face up to rounding.  Parity must hold for every one
 * (oracle: Jordan, as above).  Without shared face values (each cell
 * evaluating its own trilinear form at the face) rays here slip through or
 * hit twice. */
static void
sphere_face_crossings(void **state)
{
	vx_grid g;
	double iso = 7.37f;
	int n = 20, bad = 0, tested = 0;

	(void)state;
	make_sphere(&g, n, NULL);
	vx_iso_tracer tr = { &g, NULL, 1, VX_CELL_EXACT, NULL, 0 };
	for (int k = 0; k < 6000; k++) {
		int64_t j = 2 + (int64_t)(15 * hash01(21, k));
		int64_t l = 2 + (int64_t)(15 * hash01(22, k));
		double v = hash01(23, k), f[4], q[3], o[3], d[3], len = 0;
		int axis = k % 3;
		/* along the face axis: find the integer plane x_axis = p whose
		 * face at (j, l) brackets iso along u */
		int found = 0;
		for (int64_t p = 1; p < n - 1 && !found; p++) {
			int64_t ix[3];
			double a0, a1, u;
			ix[axis] = p;
			ix[(axis + 1) % 3] = j;
			ix[(axis + 2) % 3] = l;
			/* values at the 4 face corners: (u,v) in {0,1}^2 */
			for (int c = 0; c < 4; c++) {
				int64_t w[3] = { ix[0], ix[1], ix[2] };
				w[(axis + 1) % 3] += c & 1;
				w[(axis + 2) % 3] += c >> 1;
				f[c] = (float)vx_grid_get(&g, w[0], w[1], w[2]);
			}
			a0 = f[0] + v * (f[2] - f[0]);
			a1 = f[1] + v * (f[3] - f[1]);
			if ((a0 - iso) * (a1 - iso) >= 0)
				continue;
			u = (iso - a0) / (a1 - a0);
			q[axis] = (double)p;
			q[(axis + 1) % 3] = (double)j + u;
			q[(axis + 2) % 3] = (double)l + v;
			found = 1;
		}
		if (!found)
			continue;
		for (int a = 0; a < 3; a++) {
			d[a] = hash01(24, 3 * k + a) - 0.5;
			len += d[a] * d[a];
		}
		for (int a = 0; a < 3; a++)
			o[a] = q[a] - 40 * d[a] / sqrt(len);
		collect col;
		int cross = 0;
		trace_all(&tr, o, d, &iso, 1, &col);
		tested++;
		/* parity of the crossings only: the isosurface has creases on
		 * cell faces, so a ray through a face point may touch the
		 * surface there without crossing it (a touch hit, or none when
		 * the face value misses iso by rounding) for a set of
		 * directions of positive measure */
		for (int h = 0; h < col.n && h < 256; h++)
			cross += col.kind[h] == VX_CELL_CROSS;
		if (cross % 2 != 0)
			bad++;
	}
	assert_true(tested > 1000);
	if (bad)
		fail_msg("%d of %d rays aimed at face crossings broke parity", bad,
		    tested);
	vx_grid_free(&g);
}

static int
same_hits(const collect *a, const collect *b)
{
	if (a->n != b->n)
		return 0;
	for (int i = 0; i < a->n && i < 256; i++)
		if (a->t[i] != b->t[i] || a->surf[i] != b->surf[i])
			return 0;
	return 1;
}

/* Hierarchical = flat = bricked = with a cell mask, bit for bit, on random
 * volumes with several isovalues (oracle: the flat walk over a linear
 * layout, which involves no hierarchy, no bricking and no mask). */
static void
hierarchy_flat_bricked_identical(void **state)
{
	vx_err e = { 0, "" };
	int sizes[VX_MACRO_MAXLEV][3] = { { 2, 2, 2 }, { 2, 2, 2 } };

	(void)state;
	for (uint64_t seed = 1; seed <= 3; seed++) {
		vx_grid g, b;
		vx_macro m, mb;

		make_random(&g, 13, seed, NULL);
		make_random(&b, 13, seed, "bricked 2x2x2 2x2x2");
		assert_int_equal(vx_macro_build(&m, &g, 2,
		    (const int (*)[3])sizes, 1, &e), 0);
		assert_int_equal(vx_macro_build(&mb, &b, 2,
		    (const int (*)[3])sizes, 2, &e), 0);
		vx_iso_tracer th = { &g, &m, 0, VX_CELL_EXACT, NULL, 0 };
		vx_iso_tracer tf = { &g, &m, 1, VX_CELL_EXACT, NULL, 0 };
		vx_iso_tracer tb = { &b, &mb, 0, VX_CELL_EXACT, NULL, 0 };
		float iso[3] = { 0.2f, 0.5f, 0.93f };   /* the masks' */
		double isod[3] = { iso[0], iso[1], iso[2] };
		/* cell masks (lazy, bricked) for the three isovalue lists */
		vx_cellmask mk[3];
		for (int q = 0; q < 3; q++) {
			assert_int_equal(vx_cellmask_build(&mk[q], &mb, &b, iso,
			    q + 1, 1, 1, &e), 0);
			assert_true(mk[q].ready);
		}
		for (int k = 0; k < 500; k++) {
			double o[3], d[3];
			collect ch, cf, cb, cm;

			for (int a = 0; a < 3; a++) {
				o[a] = -5 + 25 * hash01(seed * 100 + 1, 3 * k + a);
				d[a] = hash01(seed * 100 + 2, 3 * k + a) - 0.5;
			}
			if (k % 7 == 0)
				d[k % 3] = 0;
			int ni = 1 + k % 3;
			trace_all(&th, o, d, isod, ni, &ch);
			trace_all(&tf, o, d, isod, ni, &cf);
			trace_all(&tb, o, d, isod, ni, &cb);
			vx_iso_tracer tm = tb;
			tm.mask = &mk[ni - 1];
			trace_all(&tm, o, d, isod, ni, &cm);
			if (!same_hits(&ch, &cf) || !same_hits(&ch, &cb) ||
			    !same_hits(&ch, &cm))
				fail_msg("seed %llu ray %d: %d hierarchical, %d flat, "
				    "%d bricked, %d masked hits",
				    (unsigned long long)seed, k, ch.n, cf.n, cb.n,
				    cm.n);
		}
		for (int q = 0; q < 3; q++) {
			assert_true(vx_cellmask_built(&mk[q]) > 0);
			vx_cellmask_free(&mk[q]);
		}
		vx_macro_free(&m);
		vx_macro_free(&mb);
		vx_grid_free(&g);
		vx_grid_free(&b);
	}
}

/* The double root through the whole pipeline: a 2x2x2 volume with
 * corner (1,1,1) = 27, others 0; the ray from (0,0,1) towards (1,1,0) sees
 * f(t) = 27 t^2 (1 - t) (oracle: expand the trilinear form by hand):
 * iso 4 touches at t = 2/3; iso 1 crosses at 0.2175679 and 0.9597951. */
static void
double_root_volume(void **state)
{
	int64_t dims[3] = { 2, 2, 2 };
	vx_grid g;
	vx_err e = { 0, "" };
	double o[3] = { 0, 0, 1 }, d[3] = { 1, 1, -1 };
	collect c;

	(void)state;
	assert_int_equal(vx_grid_alloc(&g, dims, VX_F32, NULL, &e), 0);
	vx_grid_set(&g, 1, 1, 1, 27);
	vx_grid_range(&g);
	vx_iso_tracer tr = { &g, NULL, 1, VX_CELL_EXACT, NULL, 0 };
	double iso4 = 4, iso1 = 1, iso5 = 5;
	trace_all(&tr, o, d, &iso4, 1, &c);
	assert_int_equal(c.n, 1);
	assert_true(fabs(c.t[0] - 2.0 / 3.0) < 1e-7);
	trace_all(&tr, o, d, &iso1, 1, &c);
	assert_int_equal(c.n, 2);
	assert_true(fabs(c.t[0] - 0.2175679) < 1e-7);
	assert_true(fabs(c.t[1] - 0.9597951) < 1e-7);
	trace_all(&tr, o, d, &iso5, 1, &c);
	assert_int_equal(c.n, 0);
	vx_grid_free(&g);
}

/* NaN and Inf voxels: hits stay finite, cells with a non-finite corner are
 * skipped (oracle: the policy in vx_iso.h), and the rest of the surface is
 * still found. */
static void
nonfinite_voxels(void **state)
{
	vx_grid g;
	double iso = 6.5f;
	int hits = 0;

	(void)state;
	make_sphere(&g, 20, NULL);
	vx_grid_set(&g, 9, 9, 9, NAN);
	vx_grid_set(&g, 3, 9, 9, INFINITY);
	vx_grid_set(&g, 9, 3, 9, -INFINITY);
	vx_grid_range(&g);
	assert_true(isfinite(g.vmin) && isfinite(g.vmax));
	vx_iso_tracer tr = { &g, NULL, 1, VX_CELL_EXACT, NULL, 0 };
	for (int k = 0; k < 400; k++) {
		double o[3] = { -10, 0, 0 }, d[3] = { 1, 0, 0 };
		collect c;

		o[1] = 5 + 9 * hash01(3, k);
		o[2] = 5 + 9 * hash01(4, k);
		d[1] = 0.1 * (hash01(5, k) - 0.5);
		trace_all(&tr, o, d, &iso, 1, &c);
		for (int i = 0; i < c.n && i < 256; i++)
			assert_true(isfinite(c.t[i]));
		hits += c.n > 0;
	}
	assert_true(hits > 200);
	vx_grid_free(&g);
}

/* Values and isovalue scaled by 2^k give bit-identical hits (oracle:
 * exact scaling; every decision is relative). */
static void
scale_invariance(void **state)
{
	static const int ks[] = { -60, -20, 20, 60 };
	vx_grid g, s;

	(void)state;
	make_random(&g, 9, 42, NULL);
	for (size_t ki = 0; ki < sizeof ks / sizeof ks[0]; ki++) {
		double f = ldexp(1.0, ks[ki]);

		make_random(&s, 9, 42, NULL);
		for (int z = 0; z < 11; z++)
			for (int y = 0; y < 10; y++)
				for (int x = 0; x < 9; x++)
					vx_grid_set(&s, x, y, z, vx_grid_get(&g, x, y, z) * f);
		vx_grid_range(&s);
		vx_iso_tracer t1 = { &g, NULL, 1, VX_CELL_EXACT, NULL, 0 };
		vx_iso_tracer t2 = { &s, NULL, 1, VX_CELL_EXACT, NULL, 0 };
		double i1 = 0.5, i2 = 0.5 * f;
		for (int k = 0; k < 200; k++) {
			double o[3], d[3];
			collect a, b;

			for (int a2 = 0; a2 < 3; a2++) {
				o[a2] = -3 + 15 * hash01(9, 3 * k + a2);
				d[a2] = hash01(10, 3 * k + a2) - 0.5;
			}
			trace_all(&t1, o, d, &i1, 1, &a);
			trace_all(&t2, o, d, &i2, 1, &b);
			assert_true(same_hits(&a, &b));
		}
		vx_grid_free(&s);
	}
	vx_grid_free(&g);
}

/* normal_oracle: the unit world normal of the trilinear field of corners c
 * at index point p (cell-local), spacing sp, facing against dw, in long
 * double from the field's partial derivatives written out (not
 * vx_cell_gradient); *ok 0 when the gradient is 0 */
static void
normal_oracle(const float c[8], const double p[3], const double sp[3],
    const double dw[3], double n[3], int *ok)
{
	long double g[3] = { 0, 0, 0 }, len = 0, dot = 0;

	for (int i = 0; i < 8; i++) {
		long double wx = (i & 1) ? p[0] : 1 - p[0];
		long double wy = (i >> 1 & 1) ? p[1] : 1 - p[1];
		long double wz = (i >> 2 & 1) ? p[2] : 1 - p[2];
		long double sx = (i & 1) ? 1 : -1, sy = (i >> 1 & 1) ? 1 : -1;
		long double sz = (i >> 2 & 1) ? 1 : -1;

		g[0] += c[i] * sx * wy * wz;
		g[1] += c[i] * wx * sy * wz;
		g[2] += c[i] * wx * wy * sz;
	}
	for (int a = 0; a < 3; a++) {
		g[a] /= sp[a];
		len += g[a] * g[a];
		dot += g[a] * dw[a];
	}
	len = sqrtl(len);
	*ok = len > 0;
	for (int a = 0; a < 3; a++)
		n[a] = (double)(g[a] / (dot > 0 ? -len : len));
}

/* vx_iso_normal against the oracle: random cells and points, isotropic,
 * anisotropic and extreme spacings (world gradients near 2^+-1000: the
 * careful path), values scaled by 2^k (the same normal); a vanishing
 * gradient takes the centre's, a flat cell the ray's */
static void
iso_normal_table(void **state)
{
	static const double sps[][3] = {
		{ 1, 1, 1 }, { 0.5, 2, 1.25 }, { 0.9375, 0.9375, 3 },
		{ 1e-300, 1, 1 }, { 1, 1e300, 1e-300 }, { 1e300, 1e300, 1e300 },
	};
	static const int ks[] = { 0, -60, 60 };
	(void)state;
	for (size_t si = 0; si < sizeof sps / sizeof sps[0]; si++) {
		vx_grid g;

		memset(&g, 0, sizeof g);
		memcpy(g.spacing, sps[si], sizeof g.spacing);
		for (int k = 0; k < 300; k++) {
			vx_iso_hit h;
			double dw[3], n[3], want[3], wk[3];
			int ok;

			memset(&h, 0, sizeof h);
			for (int a = 0; a < 3; a++) {
				h.cell[a] = 3 + a;
				h.p[a] = h.cell[a] + hash01(20, 3 * k + a);
				dw[a] = hash01(21, 3 * k + a) - 0.5;
			}
			for (int i = 0; i < 8; i++)
				h.c[i] = (float)(255 * hash01(22, 8 * k + i));
			double pl[3] = { h.p[0] - 3, h.p[1] - 4, h.p[2] - 5 };
			normal_oracle(h.c, pl, g.spacing, dw, want, &ok);
			assert_true(ok);
			for (size_t ki = 0; ki < sizeof ks / sizeof ks[0]; ki++) {
				vx_iso_hit hk = h;

				for (int i = 0; i < 8; i++)
					hk.c[i] = ldexpf(h.c[i], ks[ki]);
				assert_int_equal(vx_iso_normal(&g, &hk, dw, n),
				    VX_NORMAL_GRADIENT);
				if (ki == 0)
					memcpy(wk, n, sizeof wk);
				for (int a = 0; a < 3; a++) {
					assert_true(fabs(n[a] - want[a]) < 1e-14);
					/* 2^k scales the gradient exactly */
					assert_true(n[a] == wk[a]);
				}
			}
		}
		/* a flat cell: no gradient anywhere, the normal faces the
		 * ray */
		vx_iso_hit h;
		double dw[3] = { 0.3, -0.4, 1.2 }, n[3], l;

		memset(&h, 0, sizeof h);
		for (int i = 0; i < 8; i++)
			h.c[i] = 5;
		h.p[0] = h.p[1] = h.p[2] = 0.5;
		assert_int_equal(vx_iso_normal(&g, &h, dw, n), VX_NORMAL_RAY);
		l = sqrt(dw[0] * dw[0] + dw[1] * dw[1] + dw[2] * dw[2]);
		for (int a = 0; a < 3; a++)
			assert_true(fabs(n[a] + dw[a] / l) < 1e-15);
		/* c = x y z: no gradient at corner 0, the centre's is
		 * (1/4, 1/4, 1/4) */
		memset(&h, 0, sizeof h);
		h.c[7] = 1;
		assert_int_equal(vx_iso_normal(&g, &h, dw, n),
		    VX_NORMAL_CENTER);
		double pc[3] = { 0.5, 0.5, 0.5 }, wc[3];
		int ok;
		normal_oracle(h.c, pc, g.spacing, dw, wc, &ok);
		for (int a = 0; a < 3; a++)
			assert_true(fabs(n[a] - wc[a]) < 1e-14);
	}
}

/* field_at: the trilinear field of g at index point p (long double, the
 * corners read one by one; p inside the grid) */
static long double
field_at(const vx_grid *g, const long double p[3])
{
	int64_t c[3];
	long double u[3], f = 0;

	for (int a = 0; a < 3; a++) {
		long double fl = floorl(p[a]);

		c[a] = (int64_t)fl;
		if (c[a] > g->dims[a] - 2)
			c[a] = g->dims[a] - 2;
		if (c[a] < 0)
			c[a] = 0;
		u[a] = p[a] - (long double)c[a];
	}
	for (int i = 0; i < 8; i++) {
		long double w = ((i & 1) ? u[0] : 1 - u[0]) *
		    ((i >> 1 & 1) ? u[1] : 1 - u[1]) *
		    ((i >> 2 & 1) ? u[2] : 1 - u[2]);

		f += w * vx_grid_get(g, c[0] + (i & 1), c[1] + (i >> 1 & 1),
		    c[2] + (i >> 2 & 1));
	}
	return f;
}

/* first_hit_oracle: the first t in [t0, t1] where the field along o + t d
 * crosses iso, by marching in steps of h and bisecting the first sign
 * change; -1 for none.  Two crossings within one step escape it (then the
 * tracer's hit comes earlier, and is checked to be a root itself). */
static double
first_hit_oracle(const vx_grid *g, const double o[3], const double d[3],
    double t0, double t1, double iso, double h)
{
	long double p[3], fa, fb;
	double a = t0, b;
	int s0;

	for (int k = 0; k < 3; k++)
		p[k] = o[k] + (long double)a * d[k];
	fa = field_at(g, p) - iso;
	s0 = fa >= 0;
	for (; a < t1; a = b, fa = fb) {
		b = a + h < t1 ? a + h : t1;
		for (int k = 0; k < 3; k++)
			p[k] = o[k] + (long double)b * d[k];
		fb = field_at(g, p) - iso;
		if ((fb >= 0) != s0) {
			double lo = a, hi = b;

			for (int it = 0; it < 80; it++) {
				double mid = 0.5 * (lo + hi);

				for (int k = 0; k < 3; k++)
					p[k] = o[k] + (long double)mid * d[k];
				if ((field_at(g, p) - iso >= 0) == s0)
					lo = mid;
				else
					hi = mid;
			}
			return 0.5 * (lo + hi);
		}
	}
	return -1;
}

/* The first hit against an independent oracle (the field marched and
 * bisected in long double) on random volumes, flat, hierarchical and
 * masked: no crossing missed (a hit no later than the oracle's), no hit
 * that is not a root (|f| tiny there).  Face values taken at the wrong
 * point show here as hits that are not roots and as missed crossings (a
 * mutation, face_field's in-face axes swapped: 69 missed, 207 not roots). */
static void
first_hit_oracle_random(void **state)
{
	vx_err e = { 0, "" };
	int sizes[VX_MACRO_MAXLEV][3] = { { 4, 4, 4 }, { 2, 2, 2 } };

	(void)state;
	for (uint64_t seed = 11; seed <= 12; seed++) {
		vx_grid g;
		vx_macro m;
		vx_cellmask mk;
		float iso = 0.5f;
		double isod = iso;

		make_random(&g, 10, seed, NULL);
		assert_int_equal(vx_macro_build(&m, &g, 2,
		    (const int (*)[3])sizes, 1, &e), 0);
		assert_int_equal(vx_cellmask_build(&mk, &m, &g, &iso, 1, 1, 1,
		    &e), 0);
		vx_iso_tracer tr[3] = { { &g, NULL, 1, VX_CELL_EXACT, NULL, 0 },
		    { &g, &m, 0, VX_CELL_EXACT, NULL, 0 },
		    { &g, &m, 0, VX_CELL_EXACT, &mk, 0 } };
		int missed = 0, notroot = 0, n = 0;

		for (int k = 0; k < 150; k++) {
			double o[3], d[3], q[3], len = 0, t0, t1;

			/* from outside the box towards a random point in it */
			for (int a = 0; a < 3; a++) {
				q[a] = 0.5 + 8 * hash01(seed + 40, 3 * k + a);
				o[a] = q[a] + 30 * (hash01(seed + 41, 3 * k + a) -
				    0.5);
			}
			for (int a = 0; a < 3; a++) {
				d[a] = q[a] - o[a];
				len += d[a] * d[a];
			}
			for (int a = 0; a < 3; a++)
				d[a] /= sqrt(len);
			/* the segment inside the grid [0, dims - 1] */
			if (!grid_segment(&g, o, d, &t0, &t1) || !(t0 < t1))
				continue;
			/* a hair inside, where the oracle's field is the
			 * grid's */
			t0 += 1e-9;
			t1 -= 1e-9;
			double to = first_hit_oracle(&g, o, d, t0, t1, iso,
			    1e-3);
			for (int w = 0; w < 3; w++) {
				vx_iso_hit h;
				int got = vx_iso_first(&tr[w], o, d, t0, t1, &isod,
				    1, &h, NULL);

				n++;
				if (to >= 0 && (!got || h.t > to + 1e-7))
					missed++;
				if (got) {
					long double p[3];

					for (int a = 0; a < 3; a++)
						p[a] = o[a] + (long double)h.t *
						    d[a];
					if (fabsl(field_at(&g, p) - iso) > 1e-9)
						notroot++;
				}
			}
		}
		if (missed || notroot)
			fprintf(stderr, "# seed %d: %d queries, %d missed, %d "
			    "not roots\n", (int)seed, n, missed, notroot);
		assert_true(n > 300);
		assert_int_equal(missed, 0);
		assert_int_equal(notroot, 0);
		vx_cellmask_free(&mk);
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
}

/* cert_same: the hits of ray (o, d) by tr with the end-value certificate
 * on and off (face_ends): the same t bits, kinds, cells, surfaces; the
 * certificate's counts added to *cert, the bound's to *bounded. */
static int
cert_same(const vx_iso_tracer *tr, const double o[3], const double d[3],
    const double *iso, int niso, uint64_t *bounded, uint64_t *cert)
{
	vx_iso_tracer off = *tr;
	vx_iso_stats s0, s1;
	static collect a, b;

	off.face_ends = 1;
	memset(&s0, 0, sizeof s0);
	memset(&s1, 0, sizeof s1);
	memset(&a, 0, sizeof a);
	memset(&b, 0, sizeof b);
	vx_iso_trace(tr, o, d, 0, INFINITY, iso, niso, collect_hit, &a, &s0);
	vx_iso_trace(&off, o, d, 0, INFINITY, iso, niso, collect_hit, &b, &s1);
	assert_int_equal(s1.certified, 0);
	*bounded += s0.bounded;
	*cert += s0.certified;
	if (s0.cells != s1.cells || s0.bounded != s1.bounded)
		return 0;
	/* (memcmp: whole collects, zeroed first, so t's bits too) */
	return memcmp(&a, &b, sizeof a) == 0;
}

/* A grazed cell's end values vouched for by its cubic (iso.c's
 * ends_certain, with its proof) instead of taken from its faces: the same
 * hits, cells and bound misses, bit for bit (oracle: the faces,
 * face_ends = 1).  Random volumes, near and far eyes (the points' rounding
 * grows with |o|), values scaled by 2^-20 .. 2^40, where the certificate
 * settles nearly every bound miss; and rays built to split the two, along
 * the level set of F = 1000 (x - y) a few ulps to 2^-40 off it: the cubic
 * and the face values are then within their rounding of iso, and the
 * certificate must decline every one.  Mutations: the certificate always
 * vouching, 420 of 5200 rays differ; its bound 2^-30 times too small,
 * 154. */
static void
ends_certificate(void **state)
{
	vx_err e = { 0, "" };
	int sizes[VX_MACRO_MAXLEV][3] = { { 4, 4, 4 }, { 2, 2, 2 } };
	uint64_t bounded = 0, cert = 0;
	int bad = 0, rays = 0;

	(void)state;
	for (int k2 = -20; k2 <= 40; k2 += 30) {
		vx_grid g;
		vx_macro m;
		double iso[2] = { ldexp(0.5, k2), ldexp(0.3125, k2) };

		make_random(&g, 10, 31, NULL);
		for (int z = 0; z < 12; z++)
			for (int y = 0; y < 11; y++)
				for (int x = 0; x < 10; x++)
					vx_grid_set(&g, x, y, z, ldexp(vx_grid_get(&g,
					    x, y, z), k2));
		vx_grid_range(&g);
		assert_int_equal(vx_macro_build(&m, &g, 2,
		    (const int (*)[3])sizes, 1, &e), 0);
		vx_iso_tracer tr[2] = { { &g, NULL, 1, VX_CELL_EXACT, NULL, 0 },
		    { &g, &m, 0, VX_CELL_EXACT, NULL, 0 } };

		for (int k = 0; k < 200; k++) {
			double o[3], d[3], q[3], len = 0;
			double far = k % 4 == 0 ? 1e6 : k % 4 == 1 ? 1e3 : 20;

			for (int a = 0; a < 3; a++) {
				q[a] = 0.5 + 8 * hash01(32, 3 * k + a);
				o[a] = q[a] + far * (hash01(33, 3 * k + a) - 0.5);
			}
			for (int a = 0; a < 3; a++) {
				d[a] = q[a] - o[a];
				len += d[a] * d[a];
			}
			for (int a = 0; a < 3; a++)
				d[a] /= sqrt(len);
			for (int w = 0; w < 2; w++) {
				rays++;
				bad += !cert_same(&tr[w], o, d, iso, 1 + k % 2,
				    &bounded, &cert);
			}
		}
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
	/* the certificate did the work on these */
	assert_true(cert > bounded / 2);
	{
		vx_grid g;
		int64_t dims[3] = { 9, 9, 4 };
		double iso = 500.3f;
		uint64_t b2 = 0, c2 = 0;

		assert_int_equal(vx_grid_alloc(&g, dims, VX_F32, NULL, &e), 0);
		for (int z = 0; z < 4; z++)
			for (int y = 0; y < 9; y++)
				for (int x = 0; x < 9; x++)
					vx_grid_set(&g, x, y, z, 1000.0 * (x - y));
		vx_grid_range(&g);
		vx_iso_tracer tr = { &g, NULL, 1, VX_CELL_EXACT, NULL, 0 };

		for (int k = 0; k < 4000; k++) {
			double y0 = 0.3 + 4 * hash01(34, k), z0 = 0.2 + 2.6 *
			    hash01(35, k);
			double eta = (hash01(36, k) - 0.5) * 0x1p-40 *
			    ldexp(1, -(int)(12 * hash01(37, k)));
			double o[3] = { y0 + iso / 1000.0 + eta, y0, z0 };
			double d[3] = { 1, 1, (hash01(38, k) - 0.5) * 1e-9 };

			if (k % 3 == 1) {
				d[0] = 0.1 + hash01(39, k);
				d[1] = d[0];
			}
			rays++;
			bad += !cert_same(&tr, o, d, &iso, 1, &b2, &c2);
		}
		vx_grid_free(&g);
	}
	if (bad)
		fprintf(stderr, "# %d of %d rays' hits differ\n", bad, rays);
	assert_int_equal(bad, 0);
}

/* Isovalues are doubles, drawn as given: a volume whose samples are at
 * most P (one peak sample P, the rest 0) has no hit for any isovalue
 * above P, however close (P + its double ulp, halfway to the next float,
 * beyond the float range), and hits for one just below P, on every walk
 * (flat, hierarchical, masked: the walk's float-rounded isovalue brackets
 * a superset).  Oracle: the trilinear field never exceeds the samples'
 * maximum, and reaches P at the peak sample (rays through it). */
static void
iso_between_floats(void **state)
{
	static const struct { vx_type type; double peak; } vols[] = {
		{ VX_F32, 1.0 }, { VX_F32, 0x1.fffffep127 }, { VX_F32, -0x1p-140 },
		{ VX_U8, 100 }, { VX_U16, 65535 }, { VX_I16, -7 },
	};
	int sizes[2][3] = { { 2, 2, 2 }, { 2, 2, 2 } };
	vx_err e = { 0, "" };

	(void)state;
	for (size_t vi = 0; vi < sizeof vols / sizeof vols[0]; vi++) {
		int64_t dims[3] = { 7, 6, 5 };
		double P = vols[vi].peak, below = vols[vi].type == VX_F32 &&
		    P < 0 ? 2 * P : P == 0x1.fffffep127 ? 0x1.fffffcp127 : P - 1;
		vx_grid g;
		vx_macro m;

		assert_int_equal(vx_grid_alloc(&g, dims, vols[vi].type, NULL,
		    &e), 0);
		for (int z = 0; z < 5; z++)
			for (int y = 0; y < 6; y++)
				for (int x = 0; x < 7; x++)
					vx_grid_set(&g, x, y, z, x == 3 && y == 2 &&
					    z == 2 ? P : below);
		vx_grid_range(&g);
		assert_int_equal(vx_macro_build(&m, &g, 2,
		    (const int (*)[3])sizes, 1, &e), 0);
		double above[] = { P + fabs(P) * 0x1p-52 + 0x1p-1074,
		    P + fabs(P) * 0x1p-25, 1e300, INFINITY };
		double under[] = { P - fabs(P) * 0x1p-52, P - fabs(P) * 0x1p-26 };
		for (int q = 0; q < 6; q++) {
			double iso[2];
			int want = q >= 4, ni = q == 3 || q == 5 ? 2 : 1;
			float fiso[2];
			vx_cellmask mk;

			iso[0] = q < 4 ? above[q] : under[q - 4];
			iso[1] = q == 3 ? above[0] : q == 5 ? above[1] : 0;
			if (q == 3 && !isfinite(iso[0]))
				continue;
			for (int j = 0; j < ni; j++)
				fiso[j] = (float)iso[j];
			assert_true(iso[0] != P);
			assert_int_equal(vx_cellmask_build(&mk, &m, &g, fiso, ni, 1,
			    1, &e), 0);
			vx_iso_tracer tr[3] = { { &g, NULL, 1, VX_CELL_EXACT, NULL, 0 },
			    { &g, &m, 0, VX_CELL_EXACT, NULL, 0 },
			    { &g, &m, 0, VX_CELL_EXACT, &mk, 0 } };
			for (int k = 0; k < 60; k++) {
				/* rays through the peak sample or near it */
				double o[3], d[3], aim[3] = { 3, 2, 2 };
				collect c;

				if (k % 2)
					for (int a = 0; a < 3; a++)
						aim[a] += 0.3 * (hash01(7, 3 * k + a) - 0.5);
				/* dyadic: o + 9 d is aim exactly */
				for (int a = 0; a < 3; a++) {
					d[a] = (double)(int)(9 * hash01(8, 3 * k + a) -
					    4.5) / 8;
					o[a] = aim[a] - 9 * d[a];
				}
				if (d[0] == 0 && d[1] == 0 && d[2] == 0)
					d[k % 3] = 0.125;
				for (int w = 0; w < 3; w++) {
					trace_all(&tr[w], o, d, iso, ni, &c);
					if (!want && c.n != 0)
						fail_msg("volume %zu iso %.17g: %d hits "
						    "(walk %d ray %d), want none", vi,
						    iso[0], c.n, w, k);
					if (want && k % 2 == 0 && c.n == 0)
						fail_msg("volume %zu iso %.17g: no hit "
						    "through the peak (walk %d ray %d)",
						    vi, iso[0], w, k);
				}
			}
			vx_cellmask_free(&mk);
		}
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
}

/* Touches on cell faces, edges and vertices: fields that are exact in
 * every cell (bilinear or piecewise linear in the samples) whose zero set
 * the ray meets without crossing it, at a point on a face between two
 * cells, on an edge, or at a vertex, from above (f >= 0 around: each a
 * single touch hit) and from below (f <= 0: an entry and an exit at the
 * same t); and the isovalues beside 0 by 2^-30 (above: a miss, or two
 * crossings; below: the other).  Oracle: the algebra of each field along
 * the dyadic ray, whose every step is exact:
 *   face:   f = s (x - 1)(y - 1/2), the ray (1, 1/2, z0) + u (1, 1, 1/4):
 *           f = s u^2, zero at u = 0 on the face x = 1 (smooth);
 *   kink:   f = s |x - 1| (samples 1 0 1 along x), ray (1,.3,.6) + u (1, 1/2,
 *           1/4): f = s |u|, zero on the face (a corner of the graph);
 *   edge:   f = s (x - 1)(y - 1), ray (1, 1, z0) + u (1, 1, 1/8): f = s u^2;
 *   vertex: f = s (|x - 1| + |y - 1| + |z - 1|), ray through (1, 1, 1).
 * The walks (flat, hierarchical, masked) agree. */
static void
face_edge_touches(void **state)
{
	int sizes[2][3] = { { 2, 2, 2 }, { 2, 2, 2 } };
	vx_err e = { 0, "" };

	(void)state;
	for (int kind = 0; kind < 4; kind++)
		for (int s = -1; s <= 1; s += 2) {
			int64_t dims[3] = { 3, 3, 3 };
			double P[3], D[3];
			vx_grid g;
			vx_macro m;

			assert_int_equal(vx_grid_alloc(&g, dims, VX_F32, NULL, &e),
			    0);
			for (int z = 0; z < 3; z++)
				for (int y = 0; y < 3; y++)
					for (int x = 0; x < 3; x++) {
						double f = kind == 0 ? (x - 1) * (y - 0.5) :
						    kind == 1 ? fabs(x - 1.0) : kind == 2 ?
						    (x - 1.0) * (y - 1) : fabs(x - 1.0) +
						    fabs(y - 1.0) + fabs(z - 1.0);
						vx_grid_set(&g, x, y, z, s * f);
					}
			vx_grid_range(&g);
			assert_int_equal(vx_macro_build(&m, &g, 2,
			    (const int (*)[3])sizes, 1, &e), 0);
			/* the touch point P and direction D */
			static const double Ps[4][3] = { { 1, 0.5, 0.75 },
			    { 1, 0.25, 0.5 }, { 1, 1, 0.5 }, { 1, 1, 1 } };
			static const double Ds[4][3] = { { 1, 1, 0.25 },
			    { 1, 0.5, 0.25 }, { 1, 1, 0.125 },
			    { 0.5, 0.25, 0.125 } };
			for (int a = 0; a < 3; a++) {
				P[a] = Ps[kind][a];
				D[a] = Ds[kind][a];
			}
			for (int q = 0; q < 3; q++) {
				double iso = q == 0 ? 0 : q == 1 ? 0x1p-30 : -0x1p-30;
				float fiso = (float)iso;
				vx_cellmask mk;

				assert_int_equal(vx_cellmask_build(&mk, &m, &g, &fiso,
				    1, 1, 1, &e), 0);
				vx_iso_tracer tr[3] = {
				    { &g, NULL, 1, VX_CELL_EXACT, NULL, 0 },
				    { &g, &m, 0, VX_CELL_EXACT, NULL, 0 },
				    { &g, &m, 0, VX_CELL_EXACT, &mk, 0 } };
				for (int dir = -1; dir <= 1; dir += 2)
					for (int w = 0; w < 3; w++) {
						double o[3], d[3];
						collect c;
						int nt = 0, nc = 0;

						for (int a = 0; a < 3; a++) {
							d[a] = dir * D[a];
							o[a] = P[a] - 4 * d[a];   /* t = 4 */
						}
						trace_all(&tr[w], o, d, &iso, 1, &c);
						for (int h = 0; h < c.n; h++) {
							nt += c.kind[h] == VX_CELL_TOUCH;
							nc += c.kind[h] == VX_CELL_CROSS;
						}
						/* f >= iso around P (s = +1, iso <= 0):
						 * touch when iso = 0, else above it all
						 * along: nothing; f <= iso (s = -1, iso >=
						 * 0) likewise; the others cross twice */
						int above = s > 0, touch = q == 0;
						int cross2 = (above && q == 1) ||
						    (!above && q == 2);
						int okk;

						if (touch && above)
							okk = c.n == 1 && nt == 1 &&
							    c.t[0] == 4;
						else if (touch)
							okk = (c.n == 2 && nc == 2 &&
							    c.t[0] == 4 && c.t[1] == 4) ||
							    (c.n == 1 && nt == 1 &&
							    c.t[0] == 4);
						else if (cross2)
							okk = c.n == 2 && nc == 2 &&
							    c.t[0] < 4 && c.t[1] > 4;
						else
							okk = c.n == 0;
						if (!okk)
							fail_msg("field %d sign %d iso %g dir "
							    "%d walk %d: %d hits (%d touches, %d "
							    "crossings), first at %.17g", kind, s,
							    iso, dir, w, c.n, nt, nc, c.n ?
							    c.t[0] : 0.0);
					}
				vx_cellmask_free(&mk);
			}
			vx_macro_free(&m);
			vx_grid_free(&g);
		}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(sphere_no_holes),
		cmocka_unit_test(sphere_face_crossings),
		cmocka_unit_test(hierarchy_flat_bricked_identical),
		cmocka_unit_test(double_root_volume),
		cmocka_unit_test(nonfinite_voxels),
		cmocka_unit_test(scale_invariance),
		cmocka_unit_test(iso_normal_table),
		cmocka_unit_test(first_hit_oracle_random),
		cmocka_unit_test(ends_certificate),
		cmocka_unit_test(iso_between_floats),
		cmocka_unit_test(face_edge_touches),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
