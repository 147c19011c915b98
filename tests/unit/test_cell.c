/* test_cell.c: ray vs trilinear cell: the cubic, its first root in the hard
 * cases (double and triple roots, vanishing leading coefficient, corners at
 * the isovalue, non-finite and huge data, 2^k scaling), crack-free face
 * values, the exact cell maximum, gradients and normals.  Each case names
 * its independent oracle. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <float.h>
#include <cmocka.h>

#include "vx_cell.h"

#ifndef RANDOM_N
#define RANDOM_N 200   /* cases of random_roots (raise for a stress run) */
#endif

/* The double-root cell: corner (1,1,1) = 27, the others 0; along
 * o = (0,0,1), d = (1,1,-1): p(t) = (t, t, 1-t), so f = 27 t^2 (1-t) - iso. */
static const float dbl_cell[8] = { 0, 0, 0, 0, 0, 0, 0, 27 };
static const double dbl_o[3] = { 0, 0, 1 }, dbl_d[3] = { 1, 1, -1 };

/* roots of 27 t^3 - 27 t^2 + iso = 0 for 0 < iso < 4 by Viete's
 * trigonometric formula (t = s + 1/3, s^3 - s/3 + (iso - 2)/27 = 0):
 * t_j = 1/3 + 2/3 cos(acos(1 - iso/2)/3 - 2 pi j/3); an oracle that shares
 * nothing with the code under test. */
static long double
viete(double iso, int j)
{
	long double th = acosl(1.0L - (long double)iso / 2) / 3;

	return 1.0L / 3 + 2.0L / 3 * cosl(th - 2 * 3.14159265358979323846264338L * j / 3);
}

static void
double_root(void **state)
{
	double k[4], t;
	int r;

	(void)state;
	/* coefficients: expanded by hand, 27 t^2 - 27 t^3 - iso */
	vx_cell_poly(dbl_cell, dbl_o, dbl_d, 4, k);
	assert_true(k[0] == -4 && k[1] == 0 && k[2] == 27 && k[3] == -27);
	/* iso 4 touches at 2/3 (factorization: -27 (t - 2/3)^2 (t + 1/3)) */
	for (int s = 0; s < VX_CELL_SOLVER_LAST; s++) {
		r = vx_cell_first_root(k, 0, 1, -4, -4, s, &t, NULL);
		assert_true(r != VX_CELL_MISS);
		assert_true(fabs(t - 2.0 / 3) <= 1e-7);
	}
	/* iso 1 crosses at Viete's roots 0.2175679 and 0.9597951 */
	vx_cell_poly(dbl_cell, dbl_o, dbl_d, 1, k);
	r = vx_cell_first_root(k, 0, 1, -1, -1, VX_CELL_EXACT, &t, NULL);
	assert_int_equal(r, VX_CELL_CROSS);
	assert_true(fabsl(t - viete(1, 1)) <= 1e-9);
	assert_true(fabs(t - 0.2175679) <= 1e-7);
	r = vx_cell_first_root(k, 0.5, 1, vx_cell_poly_eval(k, 0.5), -1,
	    VX_CELL_EXACT, &t, NULL);
	assert_int_equal(r, VX_CELL_CROSS);
	assert_true(fabsl(t - viete(1, 0)) <= 1e-9);
	assert_true(fabs(t - 0.9597951) <= 1e-7);
	/* iso 5 misses: max of 27 t^2 (1-t) on [0,1] is 4 (calculus) */
	vx_cell_poly(dbl_cell, dbl_o, dbl_d, 5, k);
	for (int s = 0; s < VX_CELL_SOLVER_LAST; s++)
		assert_int_equal(vx_cell_first_root(k, 0, 1, -5, -5, s, &t, NULL),
		    VX_CELL_MISS);
}


/* Touches: the double-root cell seen along other parametrizations of the
 * same line, touched from below and from above, and just beside the
 * touching isovalue.  Oracle: f = s 27 t'^2 (1-t') - iso with t' the
 * position along the line (factorization as above; Viete for the crossing). */
static void
touches(void **state)
{
	static const float neg[8] = { 0, 0, 0, 0, 0, 0, 0, -27 };
	static const struct {
		const float *c;
		double o[3], d[3], t0, t1, iso;
		int r;
		double t, tol;
	} tc[] = {
		{ dbl_cell, { 0, 0, 1 }, { 1, 1, -1 }, 0, 1, 4, VX_CELL_TOUCH, 2.0 / 3, 1e-12 },
		/* reversed: t' = 1 - t */
		{ dbl_cell, { 1, 1, 0 }, { -1, -1, 1 }, 0, 1, 4, VX_CELL_TOUCH, 1.0 / 3, 1e-12 },
		/* t measured from 5 cells before the cell */
		{ dbl_cell, { -5, -5, 6 }, { 1, 1, -1 }, 5, 6, 4, VX_CELL_TOUCH, 5 + 2.0 / 3, 1e-12 },
		/* d not normalized: t' = 3t */
		{ dbl_cell, { 0, 0, 1 }, { 3, 3, -3 }, 0, 1.0 / 3, 4, VX_CELL_TOUCH, 2.0 / 9, 1e-12 },
		/* touched from above: f = 4 - 27 t^2 (1-t) >= 0, zero at 2/3 */
		{ neg, { 0, 0, 1 }, { 1, 1, -1 }, 0, 1, -4, VX_CELL_TOUCH, 2.0 / 3, 1e-12 },
		/* beside the touching isovalue by 1e-14 (relative): a miss
		 * (touched from below and from above), and two crossings
		 * 7.7e-8 apart; touches are decided exactly, none is taken
		 * for a hit however near */
		{ dbl_cell, { 0, 0, 1 }, { 1, 1, -1 }, 0, 1, 4 * (1 + 1e-14), VX_CELL_MISS, 0, 0 },
		{ neg, { 0, 0, 1 }, { 1, 1, -1 }, 0, 1, -4 * (1 + 1e-14), VX_CELL_MISS, 0, 0 },
		{ dbl_cell, { 0, 0, 1 }, { 1, 1, -1 }, 0, 1, 4 * (1 - 1e-14), VX_CELL_CROSS, -1, 1e-7 },
		/* by 1e-9: a miss, and two crossings 2.4e-5 apart */
		{ dbl_cell, { 0, 0, 1 }, { 1, 1, -1 }, 0, 1, 4 * (1 + 1e-9), VX_CELL_MISS, 0, 0 },
		{ dbl_cell, { 0, 0, 1 }, { 1, 1, -1 }, 0, 1, 4 * (1 - 1e-9), VX_CELL_CROSS, -1, 1e-9 },
	};
	double k[4], t;

	(void)state;
	for (size_t i = 0; i < sizeof tc / sizeof tc[0]; i++) {
		double p0[3], p1[3], f0, f1, want = tc[i].t;

		for (int a = 0; a < 3; a++) {
			p0[a] = tc[i].o[a] + tc[i].t0 * tc[i].d[a];
			p1[a] = tc[i].o[a] + tc[i].t1 * tc[i].d[a];
		}
		f0 = vx_cell_trilinear(tc[i].c, p0) - tc[i].iso;
		f1 = vx_cell_trilinear(tc[i].c, p1) - tc[i].iso;
		if (want < 0)
			want = (double)viete(tc[i].iso, 1);
		vx_cell_poly(tc[i].c, tc[i].o, tc[i].d, tc[i].iso, k);
		for (int s = 0; s < VX_CELL_SOLVER_LAST; s++) {
			int r = vx_cell_first_root(k, tc[i].t0, tc[i].t1, f0, f1, s,
			    &t, NULL);
			if (r != tc[i].r)
				fail_msg("touch case %zu solver %d: r %d", i, s, r);
			if (r && s == VX_CELL_EXACT && !(fabs(t - want) <= tc[i].tol))
				fail_msg("touch case %zu: t %.17g want %.17g", i, t, want);
		}
	}
}

/* ---- helpers ---- */

/* Hash-based randomness (splitmix64 finalizer): no rand(), reproducible. */
static uint64_t
mix(uint64_t x)
{
	x += 0x9e3779b97f4a7c15ULL;
	x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
	x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
	return x ^ (x >> 31);
}

/* uniform in [0, 1) from (seed, i, j) */
static double
uni(uint64_t seed, uint64_t i, uint64_t j)
{
	return (double)(mix(seed ^ mix(i ^ mix(j))) >> 11) * 0x1p-53;
}

/* Oracle field: the trilinear interpolation as the sum of the 8 corner
 * weights (the textbook form, Parker's eq. (1)), in long double.  Shares no
 * code or arrangement with the nested interpolation of cell.c. */
static long double
tri_l(const float c[8], long double x, long double y, long double z)
{
	long double s = 0;

	for (int i = 0; i < 8; i++) {
		long double w = ((i & 1) ? x : 1 - x) * ((i & 2) ? y : 1 - y) *
		    ((i & 4) ? z : 1 - z);
		s += w * c[i];
	}
	return s;
}

typedef struct ray_case {
	float c[8];
	double iso, o[3], d[3], t0, t1, f0, f1;
} ray_case;

static long double
F(const ray_case *rc, long double t)
{
	return tri_l(rc->c, rc->o[0] + t * rc->d[0], rc->o[1] + t * rc->d[1],
	    rc->o[2] + t * rc->d[2]) - rc->iso;
}

/* Dense-sampling oracle for the first root: sample F at n+1 points, the
 * ends taking the caller's signs (f0, f1), find the first sign change and
 * bisect it in long double.  Returns 0 if no sign change is seen. */
static int
oracle_first_root(const ray_case *rc, int n, long double *t)
{
	long double t0 = rc->t0, t1 = rc->t1, a = t0, b;
	int sa = rc->f0 >= 0, sb;

	for (int i = 1; i <= n; i++) {
		b = t0 + (t1 - t0) * i / n;
		sb = i == n ? rc->f1 >= 0 : F(rc, b) >= 0;
		if (sb != sa) {
			for (int j = 0; j < 80; j++) {
				long double m = a + (b - a) / 2;
				if ((F(rc, m) >= 0) == sa)
					a = m;
				else
					b = m;
			}
			*t = a + (b - a) / 2;
			return 1;
		}
		a = b;
	}
	return 0;
}

/* A random ray through a random cell.  Corners: uniform in [-1,1], u8-like
 * integers with iso on or between them, or mixed magnitudes.  The ray joins
 * random points P, Q on the cube's surface (sometimes on the same face: a
 * ray in a face plane), parametrized so t runs over [t0, t0 + L], with f0
 * and f1 the face values at P and Q, as a renderer computes them. */
static void
gen_case(uint64_t seed, uint64_t i, ray_case *rc)
{
	int kind = (int)(mix(seed ^ mix(i)) % 3);
	double lo = INFINITY, hi = -INFINITY, P[3], Q[3];
	int ap, sp, aq, sq;
	double up, vp, uq, vq, L, t0;

	for (int j = 0; j < 8; j++) {
		double x = uni(seed, i, j);
		switch (kind) {
		case 0: rc->c[j] = (float)(2 * x - 1); break;
		case 1: rc->c[j] = (float)floor(x * 256); break;
		default: rc->c[j] = (float)((2 * x - 1) *
		    pow(10, 6 * uni(seed, i, 20 + j) - 3)); break;
		}
		lo = fmin(lo, rc->c[j]);
		hi = fmax(hi, rc->c[j]);
	}
	ap = (int)(uni(seed, i, 11) * 3);
	sp = uni(seed, i, 12) < 0.5;
	aq = (int)(uni(seed, i, 13) * 3);
	sq = uni(seed, i, 14) < 0.5;
	if (uni(seed, i, 15) < 0.1) {   /* same face: a ray in a face plane */
		aq = ap;
		sq = sp;
	} else if (aq == ap && sq == sp) {
		sq = !sp;
	}
	up = uni(seed, i, 16);
	vp = uni(seed, i, 17);
	uq = uni(seed, i, 18);
	vq = uni(seed, i, 19);
	{
		static const int ua[3] = { 1, 0, 0 }, va[3] = { 2, 2, 1 };
		P[ap] = sp; P[ua[ap]] = up; P[va[ap]] = vp;
		Q[aq] = sq; Q[ua[aq]] = uq; Q[va[aq]] = vq;
	}
	L = uni(seed, i, 30) < 0.5 ? 1 : 3;
	t0 = uni(seed, i, 31) < 0.5 ? 0 : 1.5;
	for (int a = 0; a < 3; a++) {
		rc->d[a] = (Q[a] - P[a]) / L;
		rc->o[a] = P[a] - t0 * rc->d[a];
	}
	rc->t0 = t0;
	rc->t1 = t0 + L;
	/* the isovalue: within the corners' range, or (half the time) the
	 * field at a random point of the ray, so that many rays hit */
	rc->iso = lo + (hi - lo) * uni(seed, i, 8);
	if (uni(seed, i, 32) < 0.5) {
		rc->iso = 0;
		rc->iso = (double)F(rc, t0 + L * uni(seed, i, 33));
	}
	if (kind == 1 && uni(seed, i, 9) < 0.5)
		rc->iso = floor(rc->iso) + (uni(seed, i, 10) < 0.5 ? 0.5 : 0);
	rc->f0 = vx_cell_face_value(rc->c, ap, sp, up, vp) - rc->iso;
	rc->f1 = vx_cell_face_value(rc->c, aq, sq, uq, vq) - rc->iso;
}

static double
corner_scale(const float c[8], double iso)
{
	double s = fabs(iso);

	for (int i = 0; i < 8; i++)
		s = fmax(s, fabs(c[i]));
	return s;
}

/* ---- the hard cases ---- */

/* A checkerboard cell, corners (-1)^(x+y+z): the field is
 * (1-2x)(1-2y)(1-2z) (each factor is 1 at 0 and -1 at 1, and a product of
 * linear factors is trilinear).  Along the main diagonal p = (t,t,t):
 * f = (1-2t)^3 - iso = 1 - 6t + 12t^2 - 8t^3 - iso; for iso = 0 a triple
 * root at t = 1/2 (f' = -6(1-2t)^2 has a double root there: the
 * discriminant is exactly 0).  Oracle: 1-2t = cbrt(iso). */
static void
triple_root(void **state)
{
	static const float cb[8] = { 1, -1, -1, 1, -1, 1, 1, -1 };
	static const double o[3] = { 0, 0, 0 }, d[3] = { 1, 1, 1 };
	/* tol: the root's condition, about u * sum|k_j t^j| / |f'(t)| with
	 * f' = -6 (1-2t)^2 (u: rounding of k0 = 1 - iso), plus margin */
	static const struct { double iso, tol; } tc[] = {
		{ 0, 1e-12 },
		{ 0.125, 1e-12 },        /* t = 1/4 */
		{ -0.125, 1e-12 },       /* t = 3/4 */
		{ 1e-9, 1e-9 },          /* 1-2t = 1e-3: f' = -6e-6 */
		{ -1e-9, 1e-9 },
		{ 1e-15, 1e-6 },         /* 1-2t = 1e-5: f' = -6e-10 */
	};
	double k[4], t;

	(void)state;
	vx_cell_poly(cb, o, d, 0, k);
	assert_true(k[0] == 1 && k[1] == -6 && k[2] == 12 && k[3] == -8);
	for (size_t i = 0; i < sizeof tc / sizeof tc[0]; i++) {
		vx_cell_poly(cb, o, d, tc[i].iso, k);
		int r = vx_cell_first_root(k, 0, 1, 1 - tc[i].iso,
		    -1 - tc[i].iso, VX_CELL_EXACT, &t, NULL);
		long double want = (1 - cbrtl(tc[i].iso)) / 2;
		if (r != VX_CELL_CROSS || !(fabsl(t - want) <= tc[i].tol))
			fail_msg("triple root case %zu: r %d t %.17g want %.17Lg",
			    i, r, t, want);
		for (int s = 1; s < VX_CELL_SOLVER_LAST; s++) {
			r = vx_cell_first_root(k, 0, 1, 1 - tc[i].iso,
			    -1 - tc[i].iso, s, &t, NULL);
			assert_int_equal(r, VX_CELL_CROSS);
			assert_true(t >= 0 && t <= 1);
		}
	}
}

/* Axis-parallel rays: f is linear (k3 = k2 = 0).  Oracle: along x at
 * (y, z) the field is e0 + (e1 - e0) x with e0, e1 the values on the two
 * x faces (the textbook trilinear in long double), so t = (iso-e0)/(e1-e0).
 * Rays in a face plane (y = 0): f is quadratic (k3 = 0); rays nearly axis
 * parallel: k3 tiny but nonzero.  Oracle for those: dense sampling with
 * long double bisection on the textbook trilinear. */
static void
degenerate_leading(void **state)
{
	static const float c[8] = { 0.5f, 3, -1, 2, 1.25f, -2, 4, 0 };
	static const struct {
		double o[3], d[3], t0, t1;
		int k3zero, k2zero;
	} tc[] = {
		{ { 0, 0.3, 0.7 }, { 1, 0, 0 }, 0, 1, 1, 1 },
		{ { 0.4, 0, 0.2 }, { 0, 1, 0 }, 0, 1, 1, 1 },
		{ { 0.9, 0.1, 0 }, { 0, 0, 2 }, 0, 0.5, 1, 1 },
		{ { 0.9, 0.1, 1 }, { 0, 0, -1 }, 0, 1, 1, 1 },
		{ { 0.2, 0, 0.1 }, { 0.6, 0, 0.8 }, 0, 1.125, 1, 0 },
		{ { 0, 1, 0 }, { 1, 0, 1 }, 0, 1, 1, 0 },
		{ { 0, 0.25, 0.5 }, { 1, 1e-9, -1e-9 }, 0, 1, 0, 0 },
		{ { 0, 0.25, 0.5 }, { 1, 1e-12, 1e-13 }, 0, 1, 0, 0 },
	};
	double k[4], t;

	(void)state;
	for (size_t i = 0; i < sizeof tc / sizeof tc[0]; i++) {
		ray_case rc;
		long double want;
		double p0[3], p1[3];

		memcpy(rc.c, c, sizeof c);
		memcpy(rc.o, tc[i].o, sizeof rc.o);
		memcpy(rc.d, tc[i].d, sizeof rc.d);
		rc.t0 = tc[i].t0;
		rc.t1 = tc[i].t1;
		/* the isovalue: the field 37% of the way along (so a root
		 * exists; for the linear cases it is the only one) */
		rc.iso = 0;
		rc.iso = (double)F(&rc, rc.t0 + 0.37L * (rc.t1 - rc.t0));
		for (int a = 0; a < 3; a++) {
			p0[a] = rc.o[a] + rc.t0 * rc.d[a];
			p1[a] = rc.o[a] + rc.t1 * rc.d[a];
		}
		rc.f0 = vx_cell_trilinear(c, p0) - rc.iso;
		rc.f1 = vx_cell_trilinear(c, p1) - rc.iso;
		vx_cell_poly(c, rc.o, rc.d, rc.iso, k);
		assert_true((k[3] == 0) == tc[i].k3zero);
		assert_true((k[2] == 0) == tc[i].k2zero);
		if (tc[i].k2zero) {
			/* linear closed form; the axis is the one d moves on */
			int a = rc.d[0] != 0 ? 0 : rc.d[1] != 0 ? 1 : 2;
			long double q0[3], q1[3];
			for (int b = 0; b < 3; b++)
				q0[b] = q1[b] = rc.o[b];
			q0[a] = 0;
			q1[a] = 1;
			long double e0 = tri_l(c, q0[0], q0[1], q0[2]);
			long double e1 = tri_l(c, q1[0], q1[1], q1[2]);
			long double x = (rc.iso - e0) / (e1 - e0);
			want = (x - rc.o[a]) / rc.d[a];
		} else {
			assert_true(oracle_first_root(&rc, 100000, &want));
		}
		int r = vx_cell_first_root(k, rc.t0, rc.t1, rc.f0, rc.f1,
		    VX_CELL_EXACT, &t, NULL);
		if (r != VX_CELL_CROSS || !(fabsl(t - want) <= 1e-12))
			fail_msg("degenerate case %zu: r %d t %.17g want %.17Lg",
			    i, r, t, want);
	}
}

/* An eye 1000 cells away: with o relative to corner 0 the cubic in t is
 * ill-conditioned on [1000, 1001] (the documented loss, about 2e-7);
 * measuring t from the entry point, as the header recommends, gives the
 * root to rounding.  Oracle: Viete's root + 1000. */
static void
far_origin(void **state)
{
	static const double far[3] = { -1000, -1000, 1001 };
	double k[4], t, oc[3];
	long double want = 1000 + viete(1, 1);

	(void)state;
	vx_cell_poly(dbl_cell, far, dbl_d, 1, k);
	assert_int_equal(vx_cell_first_root(k, 1000, 1001, -1, -1,
	    VX_CELL_EXACT, &t, NULL), VX_CELL_CROSS);
	assert_true(fabsl(t - want) <= 1e-5);
	for (int a = 0; a < 3; a++)
		oc[a] = far[a] + 1000 * dbl_d[a];
	vx_cell_poly(dbl_cell, oc, dbl_d, 1, k);
	assert_int_equal(vx_cell_first_root(k, 0, 1, -1, -1, VX_CELL_EXACT, &t,
	    NULL), VX_CELL_CROSS);
	assert_true(fabsl(1000 + t - want) <= 1e-12);
}

/* Corners c_i = i, so the field is x + 2y + 4z exactly (trilinear of a
 * linear function is itself); the oracle is that plane.  Isovalues equal to
 * corner values, rays starting or ending on those corners: sign(0) = +
 * decides.  All corners equal the isovalue: no hit (documented policy); a
 * flat cell off the isovalue: no hit. */
static void
iso_at_corners(void **state)
{
	static const float lin[8] = { 0, 1, 2, 3, 4, 5, 6, 7 };
	static const float flat[8] = { 5, 5, 5, 5, 5, 5, 5, 5 };
	static const struct {
		const float *c;
		double o[3], d[3], iso;
		int r;          /* expected: VX_CELL_MISS or _CROSS */
		double t;
	} tc[] = {
		/* from corner 0 (value 0) up the diagonal: rho = 7t */
		{ lin, { 0, 0, 0 }, { 1, 1, 1 }, 0, VX_CELL_MISS, 0 },  /* 0 then + */
		{ lin, { 0, 0, 0 }, { 1, 1, 1 }, 7, VX_CELL_CROSS, 1 }, /* - then 0 */
		{ lin, { 0, 0, 0 }, { 1, 1, 1 }, 3, VX_CELL_CROSS, 3.0 / 7 },
		/* down the diagonal: rho = 7 - 7t */
		{ lin, { 1, 1, 1 }, { -1, -1, -1 }, 0, VX_CELL_MISS, 0 },
		{ lin, { 1, 1, 1 }, { -1, -1, -1 }, 7, VX_CELL_CROSS, 0 },
		/* along edge 0-1 (rho = t) to the corner at the isovalue */
		{ lin, { 0, 0, 0 }, { 1, 0, 0 }, 1, VX_CELL_CROSS, 1 },
		/* along edge 1-3 (rho = 1 + 2t) through the face x = 1 */
		{ lin, { 1, 0, 0 }, { 0, 1, 0 }, 3, VX_CELL_CROSS, 1 },
		/* all corners at the isovalue: k == 0, no hit */
		{ flat, { 0, 0.5, 0 }, { 1, 0.2, 1 }, 5, VX_CELL_MISS, 0 },
		{ flat, { 0, 0, 0 }, { 1, 1, 1 }, 5, VX_CELL_MISS, 0 },
		/* flat cell off the isovalue */
		{ flat, { 0, 0, 0 }, { 1, 1, 1 }, 4, VX_CELL_MISS, 0 },
		{ flat, { 0, 0, 0 }, { 1, 1, 1 }, 6, VX_CELL_MISS, 0 },
	};

	(void)state;
	for (size_t i = 0; i < sizeof tc / sizeof tc[0]; i++) {
		double k[4], p1[3], t = -42, f0, f1;

		for (int a = 0; a < 3; a++)
			p1[a] = tc[i].o[a] + tc[i].d[a];
		f0 = vx_cell_trilinear(tc[i].c, tc[i].o) - tc[i].iso;
		f1 = vx_cell_trilinear(tc[i].c, p1) - tc[i].iso;
		vx_cell_poly(tc[i].c, tc[i].o, tc[i].d, tc[i].iso, k);
		for (int s = 0; s < VX_CELL_SOLVER_LAST; s++) {
			int r = vx_cell_first_root(k, 0, 1, f0, f1, s, &t, NULL);
			if (r != tc[i].r)
				fail_msg("corner case %zu solver %d: r %d", i, s, r);
			if (r == VX_CELL_MISS)
				assert_true(t == -42);   /* untouched */
			else if (!(fabs(t - tc[i].t) <= 1e-15))
				fail_msg("corner case %zu solver %d: t %.17g want %.17g",
				    i, s, t, tc[i].t);
		}
	}
}

/* Two cells sharing the face x = 1 of a grid whose field is x (iso 1):
 * the face is exactly on the isosurface.  A ray across both, either way,
 * gets exactly one hit, at the shared face, because both cells see the
 * same face value (0, sign +).  Oracle: the plane x = 1.  The same holds
 * when the second cell is entirely at the isovalue. */
static void
shared_face_once(void **state)
{
	static const float A[8] = { 0, 1, 0, 1, 0, 1, 0, 1 };     /* x in [0,1] */
	static const float B[8] = { 1, 2, 1, 2, 1, 2, 1, 2 };     /* x in [1,2] */
	static const float E[8] = { 1, 1, 1, 1, 1, 1, 1, 1 };     /* all iso */
	const float *second[2] = { B, E };
	const double y = 0.375, z = 0.8125, iso = 1;

	(void)state;
	for (int w = 0; w < 2; w++)
		for (int dir = 0; dir < 2; dir++) {
			/* world ray along x from 0 to 2 (or back); t = x or 2 - x */
			const float *cells[2] = { A, second[w] };
			int hits = 0;
			double thit = -1;

			for (int step = 0; step < 2; step++) {
				int ci = dir ? 1 - step : step;
				const float *c = cells[ci];
				double o[3], d[3], k[4], t, t0 = step, t1 = step + 1;
				double f0, f1;

				/* cell-local: x_local = world x - ci */
				o[0] = dir ? 2 - ci : -ci;
				d[0] = dir ? -1 : 1;
				o[1] = y; o[2] = z; d[1] = d[2] = 0;
				f0 = vx_cell_face_value(c, 0, dir ? 1 : 0, y, z) - iso;
				f1 = vx_cell_face_value(c, 0, dir ? 0 : 1, y, z) - iso;
				vx_cell_poly(c, o, d, iso, k);
				if (vx_cell_first_root(k, t0, t1, f0, f1,
				    VX_CELL_EXACT, &t, NULL)) {
					hits++;
					thit = t;
				}
			}
			if (hits != 1 || thit != 1)
				fail_msg("second %d dir %d: %d hits, t %g", w, dir,
				    hits, thit);
		}
}

/* Any NaN or infinite corner: no hit, no maximum, no NaN anywhere. */
static void
nonfinite(void **state)
{
	static const float vals[3] = { NAN, INFINITY, -INFINITY };
	static const double o[3] = { 0.1, 0.2, 0.3 }, d[3] = { 0.5, 0.4, 0.3 };

	(void)state;
	for (int v = 0; v < 3; v++)
		for (int i = 0; i < 8; i++) {
			float c[8] = { 1, -1, 2, -2, 3, -3, 0.5f, -0.5f };
			double k[4], t = 7, tm, fm, n[3], f0, f1;
			int r;

			c[i] = vals[v];
			assert_int_equal(vx_cell_finite(c), 0);
			vx_cell_poly(c, o, d, 0.25, k);
			f0 = vx_cell_trilinear(c, o) - 0.25;
			/* even with finite caller values, non-finite k misses */
			for (int s = 0; s < VX_CELL_SOLVER_LAST; s++) {
				r = vx_cell_first_root(k, 0, 1, -1, 1, s, &t, NULL);
				assert_int_equal(r, VX_CELL_MISS);
				r = vx_cell_first_root(k, 0, 1, f0, 1, s, &t, NULL);
				assert_int_equal(r, VX_CELL_MISS);
			}
			assert_true(t == 7);
			assert_int_equal(vx_cell_max(k, 0, 1, &tm, &fm), 0);
			assert_true(tm == 0 && fm == -INFINITY);
			/* a face holding the bad corner is not finite */
			f1 = vx_cell_face_value(c, 0, i & 1, 0.5, 0.5);
			assert_false(isfinite(f1));
			r = vx_cell_normal(c, o, d, n);
			assert_true(isfinite(n[0]) && isfinite(n[1]) && isfinite(n[2]));
			assert_int_equal(r, VX_NORMAL_RAY);
		}
	/* non-finite caller values or interval */
	{
		double k[4] = { -1, 2, 0, 0 }, t = 7, tm, fm;
		assert_int_equal(vx_cell_first_root(k, 0, 1, NAN, 1, 0, &t, NULL), 0);
		assert_int_equal(vx_cell_first_root(k, 0, 1, -1, INFINITY, 0, &t, NULL), 0);
		assert_int_equal(vx_cell_first_root(k, 0, NAN, -1, 1, 0, &t, NULL), 0);
		assert_int_equal(vx_cell_first_root(k, -INFINITY, 1, -1, 1, 0, &t, NULL), 0);
		assert_int_equal(vx_cell_first_root(k, 1, 0, -1, 1, 0, &t, NULL), 0);
		assert_true(t == 7);
		assert_int_equal(vx_cell_max(k, 0, INFINITY, &tm, &fm), 0);
		/* a zero-length interval: the caller's signs decide */
		assert_int_equal(vx_cell_first_root(k, 0.5, 0.5, -1, 1, 0, &t, NULL),
		    VX_CELL_CROSS);
		assert_true(t == 0.5);
	}
}

/* Scaling values and isovalue by 2^k changes nothing: bit-identical t and
 * return code for every solver (oracle: the unscaled run itself; the
 * arithmetic is exact under power-of-two scaling).  Includes the double
 * and triple root cells and random cells. */
static void
scaling(void **state)
{
	static const int ks[] = { -60, -20, 0, 20, 60 };

	(void)state;
	for (int i = 0; i < 64; i++) {
		ray_case rc;

		if (i == 0) {
			memcpy(rc.c, dbl_cell, sizeof rc.c);
			memcpy(rc.o, dbl_o, sizeof rc.o);
			memcpy(rc.d, dbl_d, sizeof rc.d);
			rc.iso = 4;
			rc.t0 = 0;
			rc.t1 = 1;
			rc.f0 = rc.f1 = -4;
		} else if (i == 1) {
			static const float cb[8] = { 1, -1, -1, 1, -1, 1, 1, -1 };
			memcpy(rc.c, cb, sizeof rc.c);
			rc.o[0] = rc.o[1] = rc.o[2] = 0;
			rc.d[0] = rc.d[1] = rc.d[2] = 1;
			rc.iso = 0;
			rc.t0 = 0;
			rc.t1 = 1;
			rc.f0 = 1;
			rc.f1 = -1;
		} else {
			gen_case(7, (uint64_t)i, &rc);
			if (rc.c[0] == 0 && 0)
				continue;
		}
		for (int s = 0; s < VX_CELL_SOLVER_LAST; s++) {
			double tref = 0, t, k[4], tm, fm, tmref = 0, fmref = 0;
			int rref = 0, r;

			for (size_t j = 0; j < sizeof ks / sizeof ks[0]; j++) {
				float c[8];
				for (int a = 0; a < 8; a++)
					c[a] = ldexpf(rc.c[a], ks[j]);
				vx_cell_poly(c, rc.o, rc.d, ldexp(rc.iso, ks[j]), k);
				t = -1;
				r = vx_cell_first_root(k, rc.t0, rc.t1,
				    ldexp(rc.f0, ks[j]), ldexp(rc.f1, ks[j]), s, &t, NULL);
				assert_int_equal(vx_cell_max(k, rc.t0, rc.t1, &tm, &fm), 1);
				if (ks[j] == -60) {
					rref = r;
					tref = t;
					tmref = tm;
					fmref = ldexp(fm, 60);
				} else if (r != rref || memcmp(&t, &tref, sizeof t) != 0 ||
				    tm != tmref || ldexp(fm, -ks[j]) != fmref) {
					fail_msg("case %d solver %d 2^%d: r %d/%d t %.17g/%.17g",
					    i, s, ks[j], r, rref, t, tref);
				}
			}
		}
	}
}

/* Corners near the float limits (+-1e38, +-FLT_MAX): no overflow, and the
 * hit is bit-identical to that of the same cell scaled down by 2^-120
 * (oracle: exact power-of-two scaling, as above), and matches the dense
 * sampling oracle. */
static void
float_limits(void **state)
{
	static const float big[][8] = {
		{ 1e38f, -1e38f, 3e38f, -3e38f, 2e38f, -2.5e38f, 1.5e38f, -1e38f },
		{ FLT_MAX, -FLT_MAX, -FLT_MAX, FLT_MAX, -FLT_MAX, FLT_MAX, FLT_MAX,
		  -FLT_MAX },
		{ 0, 0, 0, 0, 0, 0, 0, FLT_MAX },
	};
	static const double isos[] = { 0, 1e37, 0.5 * FLT_MAX };
	static const double o[3] = { 0.05, 0.1, 0.93 }, d[3] = { 0.9, 0.8, -0.9 };

	(void)state;
	for (size_t i = 0; i < 3; i++) {
		ray_case rc;
		float small[8];
		double k[4], ks[4], p1[3], t, ts, tm, fm;
		long double want;
		int r, rs;

		memcpy(rc.c, big[i], sizeof rc.c);
		memcpy(rc.o, o, sizeof o);
		memcpy(rc.d, d, sizeof d);
		rc.iso = isos[i];
		rc.t0 = 0;
		rc.t1 = 1;
		for (int a = 0; a < 3; a++)
			p1[a] = o[a] + d[a];
		rc.f0 = vx_cell_trilinear(rc.c, o) - rc.iso;
		rc.f1 = vx_cell_trilinear(rc.c, p1) - rc.iso;
		assert_true(isfinite(rc.f0) && isfinite(rc.f1));
		for (int a = 0; a < 8; a++)
			small[a] = ldexpf(rc.c[a], -120);
		vx_cell_poly(rc.c, o, d, rc.iso, k);
		vx_cell_poly(small, o, d, ldexp(rc.iso, -120), ks);
		for (int a = 0; a < 4; a++)
			assert_true(isfinite(k[a]) && k[a] == ldexp(ks[a], 120));
		r = vx_cell_first_root(k, 0, 1, rc.f0, rc.f1, 0, &t, NULL);
		rs = vx_cell_first_root(ks, 0, 1, ldexp(rc.f0, -120),
		    ldexp(rc.f1, -120), 0, &ts, NULL);
		assert_int_equal(r, rs);
		assert_int_equal(r, oracle_first_root(&rc, 100000, &want));
		if (r) {
			assert_true(t == ts);
			assert_true(fabsl(t - want) <= 1e-9);
		}
		assert_int_equal(vx_cell_max(k, 0, 1, &tm, &fm), 1);
		assert_true(isfinite(fm));
	}
}

/* Face values: neighbouring cells of a random f32 grid (bricked layout, so
 * the corners come through vx_grid_cell's tables) give bit-identical values
 * on their shared face for hashed (u, v); the value lies within the face's
 * corner range and matches the textbook bilinear form (long double). */
static void
face_values_shared(void **state)
{
	float a[3][3][3];  /* [z][y][x] samples of a 3x3x3 grid: 8 cells */

	(void)state;
	for (int rep = 0; rep < 20; rep++) {
		for (int z = 0; z < 3; z++)
			for (int y = 0; y < 3; y++)
				for (int x = 0; x < 3; x++) {
					double r = uni(99, (uint64_t)rep, (uint64_t)(x + 3 * y + 9 * z));
					a[z][y][x] = (float)((2 * r - 1) *
					    pow(10, rep % 5 * 9 - 18));
				}
		for (int axis = 0; axis < 3; axis++)
			for (int cell = 0; cell < 4; cell++) {
				/* cell pair along axis: lower cell L at 0, upper U at 1 */
				int off[3] = { 0, 0, 0 }, pos[3];
				float L[8], U[8];
				int o1 = axis == 0 ? 1 : 0, o2 = axis == 2 ? 1 : 2;

				pos[axis] = 0;
				pos[o1] = cell & 1;
				pos[o2] = cell >> 1;
				off[axis] = 1;
				for (int i = 0; i < 8; i++) {
					int x = pos[0] + (i & 1), y = pos[1] + ((i >> 1) & 1),
					    z = pos[2] + (i >> 2);
					L[i] = a[z][y][x];
					U[i] = a[z + off[2]][y + off[1]][x + off[0]];
				}
				for (int j = 0; j < 50; j++) {
					double u = uni(5, (uint64_t)(rep * 1000 + axis * 100 + cell), (uint64_t)j);
					double v = uni(6, (uint64_t)(rep * 1000 + axis * 100 + cell), (uint64_t)j);
					double fl = vx_cell_face_value(L, axis, 1, u, v);
					double fu = vx_cell_face_value(U, axis, 0, u, v);
					assert_memory_equal(&fl, &fu, sizeof fl);
					/* textbook bilinear in long double */
					int b = 1 << axis, bu = 1 << o1, bv = 1 << o2;
					long double want =
					    (1 - (long double)u) * (1 - (long double)v) * L[b] +
					    (long double)u * (1 - (long double)v) * L[b | bu] +
					    (1 - (long double)u) * v * L[b | bv] +
					    (long double)u * v * L[b | bu | bv];
					double lo = fmin(fmin(L[b], L[b | bu]), fmin(L[b | bv], L[b | bu | bv]));
					double hi = fmax(fmax(L[b], L[b | bu]), fmax(L[b | bv], L[b | bu | bv]));
					assert_true(fl >= lo && fl <= hi);
					assert_true(fabsl(fl - want) <= 1e-14L * fmax(fabs(lo), fabs(hi)));
					/* the trilinear on that face agrees */
					double p[3];
					p[axis] = 1;
					p[o1] = u;
					p[o2] = v;
					assert_true(fabs(vx_cell_trilinear(L, p) - fl) <=
					    1e-14 * fmax(fabs(lo), fabs(hi)));
				}
				/* at the face's corners, the corner values exactly */
				assert_true(vx_cell_face_value(L, axis, 1, 1, 1) == L[7]);
				assert_true(vx_cell_face_value(L, axis, 0, 0, 0) == L[0]);
			}
	}
	/* the clamps: (u, v) outside [0,1], and values of wildly different
	 * magnitude, stay within the corner range */
	{
		static const float c[8] = { 1e-30f, 3e30f, -7, 1e20f, 0.1f, 5, 2, 3 };
		for (int j = 0; j < 200; j++) {
			double u = 3 * uni(8, 1, (uint64_t)j) - 1, v = 3 * uni(8, 2, (uint64_t)j) - 1;
			for (int axis = 0; axis < 3; axis++)
				for (int side = 0; side < 2; side++) {
					double f = vx_cell_face_value(c, axis, side, u, v);
					double lo = INFINITY, hi = -INFINITY;
					for (int i = 0; i < 8; i++)
						if (((i >> axis) & 1) == side) {
							lo = fmin(lo, c[i]);
							hi = fmax(hi, c[i]);
						}
					assert_true(f >= lo && f <= hi);
				}
		}
	}
}

/* Randomized: the first root from EXACT agrees with the dense-sampling
 * oracle (10^5 samples, long double bisection) within 1e-9 relative, and
 * no root is reported where the oracle sees none, except touches and
 * root pairs closer than the sampling step, which are verified by a finer
 * local oracle.  The other solvers make the same hit-or-miss decision. */
static void
random_roots(void **state)
{
	int n = RANDOM_N, hits = 0, misses = 0, touches = 0, close_pairs = 0;
	double worst = 0;

	(void)state;
	for (int i = 0; i < n; i++) {
		ray_case rc;
		double k[4], t = 0, ts;
		long double want;
		int r, ro;

		gen_case(1234, (uint64_t)i, &rc);
		vx_cell_poly(rc.c, rc.o, rc.d, rc.iso, k);
		r = vx_cell_first_root(k, rc.t0, rc.t1, rc.f0, rc.f1,
		    VX_CELL_EXACT, &t, NULL);
		ro = oracle_first_root(&rc, 100000, &want);
		if (r == VX_CELL_TOUCH)
			touches++;
		if (r != VX_CELL_MISS) {
			assert_true(t >= rc.t0 && t <= rc.t1);
			if (!ro || t < want - 1e-9 * fmax(1, fabsl(want))) {
				/* earlier than the sampler saw: a touch or a
				 * close pair inside one sampling step; check
				 * that F has a zero there on a fine grid */
				long double h = (rc.t1 - rc.t0) / 1e5L, m = INFINITY;
				ray_case lc = rc;
				long double tl;
				lc.t0 = fmaxl(rc.t0, t - 2 * h);
				lc.t1 = fminl(rc.t1, t + 2 * h);
				lc.f0 = (double)F(&rc, lc.t0);
				lc.f1 = (double)F(&rc, lc.t1);
				for (int j = 0; j <= 1000; j++)
					m = fminl(m, fabsl(F(&rc, lc.t0 + (lc.t1 - lc.t0) * j / 1000)));
				if (!oracle_first_root(&lc, 1000, &tl) &&
				    m > 1e-9L * corner_scale(rc.c, rc.iso))
					fail_msg("case %d: hit at %.17g, oracle %d %.17Lg",
					    i, t, ro, want);
				close_pairs++;
				continue;
			}
			double err = (double)fabsl(t - want) / fmax(1, fabsl(want));
			worst = fmax(worst, err);
			if (!(err <= 1e-9))
				fail_msg("case %d: t %.17g oracle %.17Lg", i, t, want);
			hits++;
		} else {
			if (ro)
				fail_msg("case %d: miss, oracle root %.17Lg", i, want);
			misses++;
		}
		for (int s = 1; s < VX_CELL_SOLVER_LAST; s++) {
			assert_int_equal(vx_cell_first_root(k, rc.t0, rc.t1, rc.f0,
			    rc.f1, s, &ts, NULL), r);
			if (r)
				assert_true(ts >= rc.t0 && ts <= rc.t1);
		}
	}
	printf("# random_roots: %d hits, %d misses, %d touches, %d close pairs,"
	    " worst relative error %.3g\n", hits, misses, touches, close_pairs,
	    worst);
	assert_true(hits > n / 3 && misses > n / 10);
	assert_true(close_pairs <= n / 50);
}

/* the computed cubic k in long double */
static long double
cubic_l(const double k[4], long double t)
{
	return (((long double)k[3] * t + k[2]) * t + k[1]) * t + k[0];
}

/* EXACT reaches the root of the cubic it is given to full precision: on
 * the random cases of random_roots (more of them), every crossing t lies
 * within 4 ulp of max(|t0|, |t1|) (the contract's bracket) plus the
 * rounding floor 8 u terms(t) / |f'(t)| (Horner's error in f, over the
 * slope) of the oracle root: a long double bisection (64-bit mantissa, 100
 * halvings) on the same coefficients, bracketed by widening around t
 * until the long double cubic changes sign.  And Halley's cubic
 * convergence from the secant point keeps the refinement short: a mean of
 * at most 3.5 evaluations a crossing (3.07 here, worst error 0.42 of the
 * bound; the Newton solver before it took 7.09, worst 0.91). */
static void
exact_full_precision(void **state)
{
	int n = 20 * RANDOM_N, cross = 0;
	long evals = 0;
	double worst = 0;

	(void)state;
	for (int i = 0; i < n; i++) {
		ray_case rc;
		double k[4], t = 0, at, terms, slope, tol, bound;
		long double a, b, d;
		int it = 0, sa, ok = 0;

		gen_case(4321, (uint64_t)i, &rc);
		vx_cell_poly(rc.c, rc.o, rc.d, rc.iso, k);
		if (vx_cell_first_root(k, rc.t0, rc.t1, rc.f0, rc.f1,
		    VX_CELL_EXACT, &t, &it) != VX_CELL_CROSS)
			continue;
		for (d = 1e-13L * (rc.t1 - rc.t0); d < 4 * (rc.t1 - rc.t0) &&
		    !ok; d *= 4) {
			a = fmaxl(rc.t0, t - d);
			b = fminl(rc.t1, t + d);
			ok = (cubic_l(k, a) >= 0) != (cubic_l(k, b) >= 0);
		}
		if (!ok)
			continue;   /* a root of the face values only: no oracle */
		sa = cubic_l(k, a) >= 0;
		for (int j = 0; j < 100; j++) {
			long double m = a + (b - a) / 2;

			if ((cubic_l(k, m) >= 0) == sa)
				a = m;
			else
				b = m;
		}
		at = fabs(t);
		terms = fabs(k[0]) + at * (fabs(k[1]) + at * (fabs(k[2]) +
		    at * fabs(k[3])));
		slope = fabs((3 * k[3] * t + 2 * k[2]) * t + k[1]);
		tol = 4 * 0x1p-52 * fmax(fabs(rc.t0), fabs(rc.t1));
		bound = tol + 8 * 0x1p-53 * terms / slope;
		if (!((double)fabsl(t - a) <= bound))
			fail_msg("case %d: t %.17g, oracle %.20Lg, bound %.3g", i,
			    t, a, bound);
		worst = fmax(worst, (double)fabsl(t - a) / bound);
		cross++;
		evals += it;
	}
	printf("# exact_full_precision: %d crossings, worst error %.3g of the "
	    "bound, %.2f evaluations a crossing\n", cross, worst,
	    (double)evals / cross);
	assert_true(cross > n / 3);
	assert_true(2 * evals <= 7 * (long)cross);
}

/* A critical point at, just inside and just beyond the segment's end:
 * f = (t - p)^2 - 1/4 on [0, 1], p = 1 + e, crosses zero once, at p - 1/2
 * (algebra; the oracle is that closed form in long double).  For e > 0
 * f' = 2 (t - p) keeps its sign on [0, 1] but comes within 2 e of zero at
 * the end: with e large, the solver sees a monotone segment and computes
 * no critical point; with e tiny (2^-60) or 0 it must compute them (the
 * Bernstein margin of f' is not met) and still find the one crossing; for
 * e < 0 the extremum lies inside, below zero, and the crossing comes
 * before it.  The same cubic times -1 and with a zero k3 written as
 * 2^-600: the same root.  And f = (t - q)^2 - 1/16, q = 3/4 + e, whose
 * extremum lies inside for every e here: its crossings p - 1/4 = 1/2 + e
 * and 1 + e, both in the segment for e < 0 (f positive at both ends: a
 * solver that took the segment for monotone would miss them). */
static void
crit_at_end(void **state)
{
	static const double es[] = { 0.25, 1e-3, 0x1p-20, 0x1p-40, 0x1p-60, 0,
	    -0x1p-60, -0x1p-20, -1e-3, -0.25 };

	(void)state;
	for (size_t i = 0; i < sizeof es / sizeof es[0]; i++)
		for (int sg = -1; sg <= 1; sg += 2)
			for (int tiny = 0; tiny < 4; tiny++) {
				int two = tiny >> 1;
				long double p = (two ? 0.75L : 1) + es[i];
				long double h = two ? 0.25L : 0.5L;
				long double want = p - h;
				double k[4], t = -1;

				/* (t - p)^2 - h^2 = t^2 - 2 p t + p^2 - h^2 */
				k[0] = sg * (double)(p * p - h * h);
				k[1] = sg * (double)(-2 * p);
				k[2] = sg * 1.0;
				k[3] = tiny & 1 ? 0x1p-600 : 0;
				assert_int_equal(vx_cell_first_root(k, 0, 1,
				    k[0], vx_cell_poly_eval(k, 1), VX_CELL_EXACT,
				    &t, NULL), VX_CELL_CROSS);
				if (!(fabsl(t - want) <= 1e-15L))
					fail_msg("e %g sign %d tiny %d: t %.17g, "
					    "want %.17Lg", es[i], sg, tiny, t,
					    want);
			}
}

/* vx_cell_max on the double-root cell (iso 0): f = 27 t^2 (1-t) is 0 at
 * both faces and 4 at t = 2/3 (calculus).  Ties go to the smallest t.
 * Randomized: never below the dense-sampling maximum (beyond rounding),
 * within 1e-9 of the long double golden-section refinement of it. */
static void
cell_max(void **state)
{
	double k[4], tm, fm;
	int worse = 0;
	double worst = 0;

	(void)state;
	vx_cell_poly(dbl_cell, dbl_o, dbl_d, 0, k);
	assert_int_equal(vx_cell_max(k, 0, 1, &tm, &fm), 1);
	assert_true(fabs(tm - 2.0 / 3) <= 1e-15 && fm <= 4 && fm >= 4 - 1e-13);
	/* only the ends: t in [0, 0.5] peaks at 0.5 (f increasing there) */
	assert_int_equal(vx_cell_max(k, 0, 0.5, &tm, &fm), 1);
	/* (ends other than t = 0 are rounded down: never above f there) */
	assert_true(tm == 0.5 && fm <= 27 * 0.25 * 0.5 &&
	    fm >= 27 * 0.25 * 0.5 - 1e-14);
	/* ties: f = t^2 - t is 0 at both ends: smallest t */
	{
		double q[4] = { 0, -1, 1, 0 }, c0[4] = { 3, 0, 0, 0 };
		assert_int_equal(vx_cell_max(q, 0, 1, &tm, &fm), 1);
		assert_true(tm == 0 && fm == 0);
		assert_int_equal(vx_cell_max(c0, -2, 5, &tm, &fm), 1);
		assert_true(tm == -2 && fm <= 3 && fm >= 3 - 1e-14);
	}
	for (int i = 0; i < 100; i++) {
		ray_case rc;
		long double best = -INFINITY, bt = 0, h, a, b, scale;
		const int n = 100000;

		gen_case(4321, (uint64_t)i, &rc);
		rc.iso = 0;
		vx_cell_poly(rc.c, rc.o, rc.d, 0, k);
		assert_int_equal(vx_cell_max(k, rc.t0, rc.t1, &tm, &fm), 1);
		h = ((long double)rc.t1 - rc.t0) / n;
		for (int j = 0; j <= n; j++) {
			long double t = rc.t0 + h * j, f = F(&rc, t);
			if (f > best) {
				best = f;
				bt = t;
			}
		}
		scale = corner_scale(rc.c, 0);
		/* the value is rounded down by Horner's error bound, 2^-50
		 * of the terms' magnitudes (vx_cell_poly_low) */
		double at = fabs(tm), terms = fabs(k[0]) + at * (fabs(k[1]) +
		    at * (fabs(k[2]) + at * fabs(k[3])));
		if (fm < best - 1e-14L * scale - 0x1p-47 * terms) {
			worse++;
			fail_msg("case %d: max %.17g below sampled %.17Lg", i, fm, best);
		}
		/* golden-section refinement around the best sample */
		a = fmaxl(rc.t0, bt - h);
		b = fminl(rc.t1, bt + h);
		for (int j = 0; j < 100; j++) {
			long double m1 = b - (b - a) * 0.6180339887498948482L;
			long double m2 = a + (b - a) * 0.6180339887498948482L;
			if (F(&rc, m1) >= F(&rc, m2))
				b = m2;
			else
				a = m1;
		}
		long double refined = fmaxl(best, F(&rc, (a + b) / 2));
		double err = (double)(fabsl(fm - refined) / scale);
		worst = fmax(worst, err);
		if (!(err <= 1e-9))
			fail_msg("case %d: max %.17g refined %.17Lg", i, fm, refined);
		/* and the field at tmax is that maximum */
		assert_true(fabsl(F(&rc, tm) - fm) <= 1e-12L * scale);
	}
	printf("# cell_max: worst relative error %.3g\n", worst);
	assert_int_equal(worse, 0);
}

/* Gradient: central differences are exact for a trilinear field along each
 * axis (it is linear in each coordinate), so the long double central
 * difference of the textbook form is the oracle.  Normals: unit, facing the
 * ray, parallel to the gradient; fallbacks at a saddle (x-1/4)(y-1/4)
 * (gradient 0 at (1/4, 1/4, z), not at the centre) and at the checkerboard
 * centre and in a flat cell (both vanish: -d). */
static void
gradient_normal(void **state)
{
	(void)state;
	for (int i = 0; i < 100; i++) {
		ray_case rc;
		double p[3], g[3], n[3];
		long double h = 0.25L;

		gen_case(77, (uint64_t)i, &rc);
		for (int a = 0; a < 3; a++)
			p[a] = uni(78, (uint64_t)i, (uint64_t)a);
		vx_cell_gradient(rc.c, p, g);
		for (int a = 0; a < 3; a++) {
			long double q1[3] = { p[0], p[1], p[2] }, q0[3] = { p[0], p[1], p[2] };
			q1[a] += h;
			q0[a] -= h;
			long double want = (tri_l(rc.c, q1[0], q1[1], q1[2]) -
			    tri_l(rc.c, q0[0], q0[1], q0[2])) / (2 * h);
			assert_true(fabsl(g[a] - want) <= 1e-13L * corner_scale(rc.c, 0));
		}
		assert_int_equal(vx_cell_normal(rc.c, p, rc.d, n), VX_NORMAL_GRADIENT);
		double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
		double gl = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
		double dot = n[0] * rc.d[0] + n[1] * rc.d[1] + n[2] * rc.d[2];
		double cg = (n[0] * g[0] + n[1] * g[1] + n[2] * g[2]) / gl;
		assert_true(fabs(len - 1) <= 1e-15 && dot <= 0);
		assert_true(fabs(fabs(cg) - 1) <= 1e-14);
	}
	{
		static const float sad[8] = { 0.0625f, -0.1875f, -0.1875f, 0.5625f,
		    0.0625f, -0.1875f, -0.1875f, 0.5625f };
		static const float cb[8] = { 1, -1, -1, 1, -1, 1, 1, -1 };
		static const float flat[8] = { 2, 2, 2, 2, 2, 2, 2, 2 };
		const double p[3] = { 0.25, 0.25, 0.6 }, c[3] = { 0.5, 0.5, 0.5 };
		const double d[3] = { -1, -1, 0 }, dz[3] = { 0, 0, 0 };
		double n[3];

		/* centre gradient (1/4, 1/4, 0), facing d */
		assert_int_equal(vx_cell_normal(sad, p, d, n), VX_NORMAL_CENTER);
		assert_true(fabs(n[0] - sqrt(0.5)) < 1e-15 &&
		    fabs(n[1] - sqrt(0.5)) < 1e-15 && n[2] == 0);
		assert_int_equal(vx_cell_normal(cb, c, d, n), VX_NORMAL_RAY);
		assert_true(fabs(n[0] - sqrt(0.5)) < 1e-15 && n[2] == 0);
		assert_int_equal(vx_cell_normal(flat, p, d, n), VX_NORMAL_RAY);
		assert_int_equal(vx_cell_normal(flat, p, dz, n), VX_NORMAL_NONE);
		assert_true(n[0] == 0 && n[1] == 0 && n[2] == 0);
	}
}

/* ---- vx_cell_sign_bound: the early-out must never hide a root ---- */

/* sb_check: the guarantee of vx_cell_sign_bound for the cubic k on [0, L]:
 * when it returns +1 (-1), vx_cell_first_root misses with every solver for
 * end values f0, f1 of that sign (the caller's own, 0 and tiny ones); and,
 * by an independent oracle, the cubic sampled densely in long double keeps
 * that sign.  Returns the bound's answer. */
static int
sb_check(const double k[4], double L, double f0, double f1, const char *what,
    uint64_t i)
{
	int sg = vx_cell_sign_bound(k, L);
	double t;

	if (sg == 0)
		return 0;
	assert_true(sg == 1 || sg == -1);
	const double ends[][2] = {
		{ f0, f1 },
		{ sg > 0 ? 0.0 : -0x1p-1074, sg > 0 ? 0x1p-1074 : -0.0 },
		{ sg * 1e300, sg * 1e-300 },
	};
	for (size_t e = 0; e < sizeof ends / sizeof ends[0]; e++) {
		double a = ends[e][0], b = ends[e][1];

		if ((a >= 0) != (sg > 0) || (b >= 0) != (sg > 0))
			continue;   /* the guarantee says nothing then */
		for (int s = 0; s < VX_CELL_SOLVER_LAST; s++) {
			int r = vx_cell_first_root(k, 0, L, a, b, s, &t, NULL);
			if (r != VX_CELL_MISS)
				fail_msg("%s %llu: sign_bound %d but solver %d "
				    "finds %d at %.17g (k %a %a %a %a, L %a)",
				    what, (unsigned long long)i, sg, s, r, t,
				    k[0], k[1], k[2], k[3], L);
		}
	}
	if (isfinite(L) && L < 1e100)
		for (int j = 0; j <= 256; j++) {
			long double x = (long double)L * j / 256;
			long double f = ((k[3] * x + k[2]) * x + k[1]) * x + k[0];
			if (!(sg > 0 ? f > 0 : f < 0))
				fail_msg("%s %llu: sign_bound %d but f(%Lg) = %Lg",
				    what, (unsigned long long)i, sg, x, f);
		}
	return sg;
}

/* Random cells (the three corner distributions of gen_case), each ray
 * solved from its entry point as a renderer does, at the case's isovalue
 * and at isovalues just beside the cubic's extrema on the segment (near
 * double roots: the touch tolerance's territory), and the same cells
 * scaled by 2^k up to the float limits.  Oracle: vx_cell_first_root
 * itself (all three solvers) and dense long double sampling.  Also checks
 * that the early-out is not vacuous: it decides most grazing rays. */
static void
sign_bound_cells(void **state)
{
	int decided = 0, misses = 0, total = 0;

	(void)state;
	for (int i = 0; i < 3000; i++) {
		ray_case rc;
		double ol[3], L, k[4], tm, fm, km[4], tn, fn;

		gen_case(555, (uint64_t)i, &rc);
		L = rc.t1 - rc.t0;
		for (int a = 0; a < 3; a++)
			ol[a] = rc.o[a] + rc.t0 * rc.d[a];
		vx_cell_poly(rc.c, ol, rc.d, rc.iso, k);
		int sg = sb_check(k, L, rc.f0, rc.f1, "cell", (uint64_t)i);
		double t;
		int r = vx_cell_first_root(k, 0, L, rc.f0, rc.f1, 0, &t, NULL);
		total++;
		if (r == VX_CELL_MISS) {
			misses++;
			decided += sg != 0 && (rc.f0 >= 0) == (sg > 0) &&
			    (rc.f1 >= 0) == (sg > 0);
		}
		/* isovalues beside the extrema: f's max and min on [0, L],
		 * moved by relative steps 2^-j around the touch tolerance */
		vx_cell_poly(rc.c, ol, rc.d, 0, km);
		if (!vx_cell_max(km, 0, L, &tm, &fm))
			continue;
		for (int a = 0; a < 4; a++)
			km[a] = -km[a];
		if (!vx_cell_max(km, 0, L, &tn, &fn))
			continue;
		fn = -fn;
		for (int j = 20; j <= 60; j += 2)
			for (int sgn = -1; sgn <= 1; sgn += 2) {
				double sc = corner_scale(rc.c, 0);
				double isos[2] = { fm + sgn * ldexp(sc, -j),
				    fn + sgn * ldexp(sc, -j) };
				for (int q = 0; q < 2; q++) {
					double kk[4];
					vx_cell_poly(rc.c, ol, rc.d, isos[q], kk);
					sb_check(kk, L, rc.f0 + rc.iso - isos[q],
					    rc.f1 + rc.iso - isos[q], "extremum",
					    (uint64_t)i);
				}
			}
		/* 2^k scaling, up to the float limits (corners stay floats) */
		for (int e = -140; e <= 120; e += 20) {
			float cs[8];
			double ks[4];
			int ok = 1;

			for (int a = 0; a < 8; a++) {
				cs[a] = ldexpf(rc.c[a], e);
				ok &= isfinite(cs[a]) &&
				    (double)cs[a] == ldexp(rc.c[a], e);
			}
			if (!ok)
				continue;
			vx_cell_poly(cs, ol, rc.d, ldexp(rc.iso, e), ks);
			int ss = sb_check(ks, L, ldexp(rc.f0, e), ldexp(rc.f1, e),
			    "scaled", (uint64_t)i);
			/* exact scaling: the same decision (no range limit hit) */
			if (sg != 0 && ss != sg)
				fail_msg("scaled %d by 2^%d: %d vs %d", i, e, ss, sg);
		}
	}
	/* non-vacuous: the test decides most misses (rough cells included) */
	if (!(decided > misses / 2 && misses > total / 4))
		fail_msg("sign_bound decided %d of %d misses (%d rays)", decided,
		    misses, total);
}

/* Cubics built to be hard: a double root r inside [0, L] lifted or lowered
 * by a relative 2^-j (j from 1 to 48: far from the surface down to below
 * the margin 2^-38 and the touch tolerance 2^-40), scaled by 2^e across the whole range the bound
 * accepts and beyond it (|k| near 2^-400 and 2^400: it must say 0 or be
 * right), segment lengths from 0 to 2^110, and random coefficients of
 * random magnitudes.  Oracle: vx_cell_first_root (all solvers) and dense
 * sampling, through sb_check.  The exact touch cases must stay undecided. */
static void
sign_bound_adversarial(void **state)
{
	static const double Ls[] = { 0, 0x1p-60, 1e-9, 0.25, 1, 3, 1e3,
	    0x1p50, 0x1p99, 0x1p100, 0x1p101, 0x1p110 };
	static const int es[] = { -1020, -700, -420, -400, -390, -100, 0, 100,
	    390, 399, 400, 401, 700, 1000 };

	(void)state;
	for (int i = 0; i < 2000; i++) {
		double L = Ls[mix(91 ^ (uint64_t)i) % (sizeof Ls / sizeof Ls[0])];
		int e = es[mix(92 ^ (uint64_t)i) % (sizeof es / sizeof es[0])];
		double r = uni(93, (uint64_t)i, 0), q = -uni(93, (uint64_t)i, 1);
		double A = 1 + uni(93, (uint64_t)i, 2), s = r < 0.5 ? 1 : -1;
		int j = 1 + (int)(mix(94 ^ (uint64_t)i) % 48);
		double eps = (uni(93, (uint64_t)i, 3) < 0.5 ? 1 : -1) * ldexp(1, -j);
		double k[4], lk = L > 0 ? L : 1;

		if (uni(93, (uint64_t)i, 4) < 0.3) {
			q = 1 + uni(93, (uint64_t)i, 5);   /* third root beyond */
		}
		/* f(t) = s A (t/L - r)^2 (t/L - q) + eps A, expanded in t
		 * (rounded: sb_check's oracles see these very coefficients) */
		double c3 = A, c2 = -A * (2 * r + q), c1 = A * (r * r + 2 * r * q);
		double c0 = -A * r * r * q + eps * A;
		k[0] = ldexp(s * c0, e);
		k[1] = ldexp(s * c1, e) / lk;
		k[2] = ldexp(s * c2, e) / lk / lk;
		k[3] = ldexp(s * c3, e) / lk / lk / lk;
		sb_check(k, L, vx_cell_poly_eval(k, 0), vx_cell_poly_eval(k, L),
		    "tangent", (uint64_t)i);
		/* the pure double root (eps = 0) at r inside: always a hit
		 * (touch or crossing) for the solver, so never decided */
		k[0] = ldexp(s * (-A * r * r * q), e);
		if (L > 0 && r > 0 && vx_cell_sign_bound(k, L) != 0 &&
		    vx_cell_first_root(k, 0, L, vx_cell_poly_eval(k, 0),
		    vx_cell_poly_eval(k, L), 0, &A, NULL) != VX_CELL_MISS)
			fail_msg("tangent %d: double root decided", i);
		/* random coefficients, random magnitudes and signs */
		for (int a = 0; a < 4; a++)
			k[a] = (uni(95, (uint64_t)i, (uint64_t)a) - 0.5) *
			    ldexp(1, (int)(mix(96 ^ (uint64_t)(4 * i + a)) % 60) - 30 + e / 2);
		sb_check(k, L, vx_cell_poly_eval(k, 0), vx_cell_poly_eval(k, L),
		    "random", (uint64_t)i);
	}
	/* non-finite input and bad lengths: 0 */
	{
		double k[4] = { 1, 0, 0, 0 };
		assert_int_equal(vx_cell_sign_bound(k, 1), 1);
		k[0] = -1;
		assert_int_equal(vx_cell_sign_bound(k, 1), -1);
		assert_int_equal(vx_cell_sign_bound(k, -1), 0);
		assert_int_equal(vx_cell_sign_bound(k, NAN), 0);
		assert_int_equal(vx_cell_sign_bound(k, INFINITY), 0);
		k[2] = NAN;
		assert_int_equal(vx_cell_sign_bound(k, 1), 0);
		k[2] = INFINITY;
		assert_int_equal(vx_cell_sign_bound(k, 1), 0);
		k[2] = 0;
		k[0] = 0;
		assert_int_equal(vx_cell_sign_bound(k, 1), 0);
	}
}

static void
solver_names(void **state)
{
	(void)state;
	for (int s = 0; s < VX_CELL_SOLVER_LAST; s++)
		assert_int_equal(vx_enum_val(&vx_cell_solver_enum,
		    vx_enum_str(&vx_cell_solver_enum, s)), s);
	assert_int_equal(vx_enum_val(&vx_cell_solver_enum, "cardano"), -1);
	assert_string_equal(vx_enum_str(&vx_cell_solver_enum, 99), "unknown");
}

/* vx_cell_normal_thresh: 2^-40 times the range of the corners that are
 * not NaN, whatever their positions, NaN when all are, not finite when an
 * infinity is among them; a table of hard cases (NaNs in every position,
 * +-Inf, zeros of both signs, one value, subnormals, float limits) and
 * random sets of values drawn from a pool of them, in every order.
 * Oracle: min and max over the non-NaN corners, one at a time. */
static void
normal_thresh_range(void **state)
{
	static const float pool[] = { 0.0f, -0.0f, 1.0f, -1.0f, 3.5f, 1e-45f,
	    -1e-45f, FLT_MAX, -FLT_MAX, INFINITY, -INFINITY, NAN, 127.5f, 2e30f,
	    -7e-20f };
	static const float fixed[][8] = {
		{ NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN },
		{ NAN, 1, 2, 3, 4, 5, 6, 7 },
		{ 0, 1, 2, 3, 4, 5, 6, NAN },
		{ NAN, NAN, NAN, 5, NAN, NAN, NAN, NAN },
		{ 0.0f, -0.0f, 0.0f, -0.0f, -0.0f, 0.0f, -0.0f, 0.0f },
		{ 1, 1, 1, 1, 1, 1, 1, 1 },
		{ INFINITY, 0, 0, 0, 0, 0, 0, 0 },
		{ -INFINITY, INFINITY, 0, 0, 0, 0, 0, NAN },
		{ -FLT_MAX, FLT_MAX, 0, 0, 0, 0, 0, 0 },
		{ 1e-45f, -1e-45f, 0, 0, 0, 0, 0, 0 },
	};
	const uint64_t s = 99;
	int n = (int)(sizeof fixed / sizeof *fixed);

	(void)state;
	for (int k = 0; k < n + 4000; k++) {
		float c[8];
		double lo = NAN, hi = NAN, want, got;

		for (int i = 0; i < 8; i++)
			c[i] = k < n ? fixed[k][i] :
			    pool[mix(s + 8 * (uint64_t)k + (uint64_t)i) %
			    (sizeof pool / sizeof *pool)];
		for (int i = 0; i < 8; i++) {
			if (c[i] != c[i])
				continue;
			if (lo != lo || c[i] < lo)
				lo = c[i];
			if (hi != hi || c[i] > hi)
				hi = c[i];
		}
		want = 0x1p-40 * (hi - lo);
		got = vx_cell_normal_thresh(c);
		if (!(want == got || (want != want && got != got)))
			fail_msg("case %d: thresh %g, want %g", k, got, want);
	}
}

/* Touches decided exactly: cubics whose coefficients are exact doubles,
 * f = s A (t - r)^2 (t - q) + eps with dyadic r inside the segment, q
 * beyond it, A = 2^e (e from -600 to 600) and eps = 0 or +-2^-j A (j from
 * 8 to 52, where eps is still exact in k0: far below the old touch
 * tolerance 2^-40), and the same along rays: the double-root cell (iso 4
 * +- 4 2^-j, its cubic exact for the dyadic ray).  Oracle: the algebra:
 * eps = 0 is a double root at r, a touch there; eps of the sign that
 * lifts the extremum across zero gives two crossings around r, the first
 * before it; the other sign keeps f off zero: a miss.  Every solver
 * decides alike. */
static void
touch_exact(void **state)
{
	static const double rs[] = { 0.375, 0.5, 0.6875, 0.125 };
	int slow = 0;

	(void)state;
	for (int e = -600; e <= 600; e += 40)
		for (size_t ri = 0; ri < sizeof rs / sizeof rs[0]; ri++)
			for (int s = -1; s <= 1; s += 2)
				for (int j = 7; j <= 52; j++)
					for (int es = -1; es <= 1; es += 2) {
		/* j = 7: eps = 0; j >= 8: |eps| <= A / 256, below f's value
		 * at the segment's ends (at least A / 64) */
		double r = rs[ri], q = 2, A = ldexp(1, e);
		double eps = j == 7 ? 0 : es * ldexp(A, -j);
		double k[4], t, want;
		unsigned ex = 0;

		if (j == 7 && es > 0)
			continue;
		k[3] = s * A;
		k[2] = -s * A * (2 * r + q);
		k[1] = s * A * (r * r + 2 * r * q);
		k[0] = -s * A * r * r * q + eps;
		/* the construction is exact: k0 - eps recovers the product */
		assert_true(k[0] - eps == -s * A * r * r * q);
		double f0 = vx_cell_poly_eval(k, 0), f1 = vx_cell_poly_eval(k, 1);
		/* s = +1: a local minimum at r of value eps (q beyond: f is
		 * s A (t - r)^2 (t - q) with t - q < 0, so s = +1 is a
		 * maximum); see which */
		int maxat = s > 0;   /* (t - r)^2 (t - q) <= 0 near r */
		want = eps == 0 ? VX_CELL_TOUCH : (maxat ? eps > 0 : eps < 0) ?
		    VX_CELL_CROSS : VX_CELL_MISS;
		for (int sv = 0; sv < VX_CELL_SOLVER_LAST; sv++) {
			int got = vx_cell_first_root_x(k, 0, 1, f0, f1, sv, &t,
			    NULL, &ex);
			if (got != want)
				fail_msg("e %d r %g s %d eps %d 2^-%d solver %d: %d, "
				    "want %d", e, r, s, es, j, sv, got, (int)want);
			if (got == VX_CELL_TOUCH && t != r)
				fail_msg("touch at %.17g, want %.17g", t, r);
			if (got == VX_CELL_CROSS && !(t <= r))
				fail_msg("first crossing at %.17g after %g", t, r);
		}
		slow += ex > 0;
	}
	/* along rays: the double-root cell and its mirror image */
	for (int j = 0; j <= 52; j++)
		for (int es = -1; es <= 1; es += 2) {
			static const float neg[8] = { 0, 0, 0, 0, 0, 0, 0, -27 };
			double iso = 4 + (j == 0 ? 0 : es * ldexp(4, -j)), k[4], t;

			if (j == 0 && es > 0)
				continue;
			for (int w = 0; w < 2; w++) {
				const float *c = w ? neg : dbl_cell;
				double is = w ? -iso : iso;
				/* f = 27 t^2 (1 - t) - iso, its maximum 4 - iso at
				 * 2/3; the mirror f = iso - 27 t^2 (1 - t), its
				 * minimum iso - 4: both cross for iso < 4 */
				int want = j == 0 ? VX_CELL_TOUCH : es < 0 ?
				    VX_CELL_CROSS : VX_CELL_MISS;
				vx_cell_poly(c, dbl_o, dbl_d, is, k);
				int got = vx_cell_first_root(k, 0, 1, -is, -is,
				    VX_CELL_EXACT, &t, NULL);
				if (got != want)
					fail_msg("cell %d iso 4 %+d 2^-%d: %d, want "
					    "%d", w, es, j, got, want);
				if (got == VX_CELL_TOUCH &&
				    !(fabs(t - 2.0 / 3) <= 1e-15))
					fail_msg("cell %d: touch at %.17g", w, t);
			}
		}
	/* the filter leaves the exact path to the near-touches only */
	assert_true(slow > 0);
}

/* vx_cell_max is never above the exact maximum of its cubic: the
 * double-root cubic g(u) = 27 u^2 (1 - u) - 4 (maximum exactly 0 at u =
 * 2/3, not a double: the critical point is rounded) under affine changes
 * of variable u = al t + be (al = 1..9 odd times 2^-3..2^3, be = -1..1 in
 * eighths) and scalings A = 2^-40..2^40, every coefficient exact; the
 * double-root cell along dyadic rays; the maxima at the segment's ends.
 * Oracle: the algebra (the maximum on u in [0, 1] is 0); and within 2^-47
 * of the terms' magnitudes below it (Horner's bound, vx_cell_poly_low).
 * Rounding put 77 of these up to 4.4e-16 A above 0 before. */
static void
cell_max_never_above(void **state)
{
	double k[4], tm, fm;
	int n = 0;

	(void)state;
	for (int e = -40; e <= 40; e += 8)
		for (int ai = 1; ai <= 9; ai += 2)
			for (int ae = -3; ae <= 3; ae++)
				for (int bi = -8; bi <= 8; bi++) {
		double A = ldexp(1, e), al = ldexp(ai, ae), be = bi / 8.0;
		double t0 = (0 - be) / al, t1 = (1 - be) / al;

		/* A g(al t + be) expanded: exact (small integers times powers
		 * of two) */
		k[3] = A * -27 * al * al * al;
		k[2] = A * (3 * -27 * al * al * be + 27 * al * al);
		k[1] = A * (3 * -27 * al * be * be + 2 * 27 * al * be);
		k[0] = A * (-27 * be * be * be + 27 * be * be - 4);
		n++;
		assert_int_equal(vx_cell_max(k, t0, t1, &tm, &fm), 1);
		if (fm > 0)
			fail_msg("A 2^%d al %g be %g: max %.17g above the exact 0",
			    e, al, be, fm);
		double at = fabs(tm), terms = fabs(k[0]) + at * (fabs(k[1]) +
		    at * (fabs(k[2]) + at * fabs(k[3])));
		if (!(fm >= -0x1p-47 * terms))
			fail_msg("A 2^%d al %g be %g: max %.17g far below 0", e, al,
			    be, fm);
	}
	assert_true(n > 6000);
	/* the double-root cell along the line, and its parametrizations */
	{
		static const double os[4][3] = { { 0, 0, 1 }, { 1, 1, 0 },
		    { -5, -5, 6 }, { 0, 0, 1 } };
		static const double ds[4][3] = { { 1, 1, -1 }, { -1, -1, 1 },
		    { 1, 1, -1 }, { 0.5, 0.5, -0.5 } };
		static const double ts[4][2] = { { 0, 1 }, { 0, 1 }, { 5, 6 },
		    { 0, 2 } };

		for (int w = 0; w < 4; w++) {
			vx_cell_poly(dbl_cell, os[w], ds[w], 4, k);
			assert_int_equal(vx_cell_max(k, ts[w][0], ts[w][1], &tm,
			    &fm), 1);
			/* (t measured from 5 cells before the cell: terms
			 * near 27 * 6^3, Horner's bound 2^-50 of that) */
			if (!(fm <= 0 && fm >= -1e-10))
				fail_msg("double-root cell %d: max %.17g", w, fm);
		}
	}
	/* maxima at the ends: at t0 the value is k0 itself, exactly */
	{
		double q[4] = { 3, -1, 0, 0 };

		assert_int_equal(vx_cell_max(q, 0, 1, &tm, &fm), 1);
		assert_true(tm == 0 && fm == 3);
		q[1] = 1;
		assert_int_equal(vx_cell_max(q, 0, 1, &tm, &fm), 1);
		assert_true(tm == 1 && fm <= 4 && fm >= 4 - 1e-14);
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(double_root),
		cmocka_unit_test(touches),
		cmocka_unit_test(touch_exact),
		cmocka_unit_test(cell_max_never_above),
		cmocka_unit_test(triple_root),
		cmocka_unit_test(degenerate_leading),
		cmocka_unit_test(far_origin),
		cmocka_unit_test(iso_at_corners),
		cmocka_unit_test(shared_face_once),
		cmocka_unit_test(nonfinite),
		cmocka_unit_test(scaling),
		cmocka_unit_test(float_limits),
		cmocka_unit_test(face_values_shared),
		cmocka_unit_test(random_roots),
		cmocka_unit_test(exact_full_precision),
		cmocka_unit_test(crit_at_end),
		cmocka_unit_test(cell_max),
		cmocka_unit_test(gradient_normal),
		cmocka_unit_test(normal_thresh_range),
		cmocka_unit_test(sign_bound_cells),
		cmocka_unit_test(sign_bound_adversarial),
		cmocka_unit_test(solver_names),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
