/* test_macro.c: the min/max hierarchy (build, MCEL chunk, staleness) and the
 * 3D-DDA walks, each checked against an independent oracle: a brute-force
 * intersection of the ray with every leaf box in long double. */
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

#include "vx_macro.h"
#include "vx_macrobox.h"
#include "vx_macroio.h"

typedef long double ld;

/* ---- collecting a walk ---- */

typedef struct rec {
	vx_leaf_visit *v;
	int n, cap;
} rec;

static int
collect(void *ctx, const vx_leaf_visit *v)
{
	rec *r = ctx;

	if (r->n == r->cap)
		return 99;   /* more visits than leaves could ever give */
	r->v[r->n++] = *v;
	return 0;
}

static void
rec_init(rec *r, const int64_t n[3])
{
	r->cap = (int)(n[0] + n[1] + n[2] + 3);
	r->v = calloc((size_t)r->cap, sizeof *r->v);
	r->n = 0;
}

/* hash-based random numbers (deterministic; no shared generator) */
static uint64_t
hash64(uint64_t x)
{
	x += 0x9e3779b97f4a7c15ULL;
	x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
	x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
	return x ^ (x >> 31);
}

static double
urand(uint64_t *s)
{
	*s = hash64(*s);
	return (double)(*s >> 11) * 0x1p-53;
}

static int
irand(uint64_t *s, int n)
{
	return (int)(urand(s) * n);
}

/* ---- the oracle ----
 * For a ray o + t d and the closed box [lo, hi], the set of t with the point
 * in the box (or in its open interior when open != 0), in long double.
 * Crossing times beyond DBL_MAX become infinite, as they do in double. */
static ld
clampinf(ld t)
{
	if (t > (ld)DBL_MAX)
		return INFINITY;
	if (t < -(ld)DBL_MAX)
		return -INFINITY;
	return t;
}

static void
box_interval(const ld lo[3], const ld hi[3], const double o[3],
    const double d[3], int open, ld *t0, ld *t1)
{
	*t0 = -INFINITY;
	*t1 = INFINITY;
	for (int a = 0; a < 3; a++) {
		if (d[a] == 0) {
			int in = open ? (o[a] > lo[a] && o[a] < hi[a]) :
			    (o[a] >= lo[a] && o[a] <= hi[a]);

			if (!in) {
				*t0 = INFINITY;
				*t1 = -INFINITY;
				return;
			}
			continue;
		}
		ld u = clampinf((lo[a] - (ld)o[a]) / (ld)d[a]);
		ld w = clampinf((hi[a] - (ld)o[a]) / (ld)d[a]);

		if (u > w) {
			ld x = u;
			u = w;
			w = x;
		}
		if (u > *t0)
			*t0 = u;
		if (w < *t1)
			*t1 = w;
	}
}

static int
near(ld a, ld b, ld tol)
{
	if (isinf(a) || isinf(b))
		return a == b;
	return fabsl(a - b) <= tol;
}

#define OCHECK(c, ...) do { if (!(c)) { print_message("case %s: ", what); \
	print_message(__VA_ARGS__); print_message("\n"); fail(); } } while (0)

/* oracle_check: the visits v[0..nv) of a walk with nvals == 0 over an
 * n-leaf grid must
 *   - tile the reference segment [sa, sb] (the ray clipped to [tmin, tmax]
 *     and the closed grid box, in long double): consecutive visits share
 *     their t exactly, the ends match sa and sb within tol;
 *   - each lie, over [t0, t1], inside its leaf's closed box (within tol);
 *   - visit each leaf at most once, stepping between face neighbours along
 *     the axis named by exit_axis / entry_axis, in the direction of d;
 *   - include every leaf whose open box meets the segment in more than tol
 *     ("core" leaves).  Leaves touched only on their boundary (measure zero
 *     in the interior: edges, vertices, rays in face planes) may or may not
 *     be visited; tiling decides which side of a face plane is walked.
 * tol is 1e-9 of the segment's largest finite |t| (at least 1e-315). */
static void
oracle_check(const char *what, const int64_t n[3], const double o[3],
    const double d[3], double tmin, double tmax, const vx_leaf_visit *v,
    int nv)
{
	ld lo[3] = { 0, 0, 0 }, hi[3], sa, sb, tol, sc = 0;
	int64_t nleaf = n[0] * n[1] * n[2], i;
	unsigned char *seen;
	int k, a;

	for (a = 0; a < 3; a++)
		hi[a] = (ld)n[a];
	box_interval(lo, hi, o, d, 0, &sa, &sb);
	if (tmin > sa)
		sa = tmin;
	if (tmax < sb)
		sb = tmax;
	if (isnan(tmin) || isnan(tmax))
		sa = INFINITY;   /* an undefined segment is empty */
	if (isfinite(sa))
		sc = fabsl(sa);
	if (isfinite(sb) && fabsl(sb) > sc)
		sc = fabsl(sb);
	if (isfinite(sa) && isfinite(sb) && sb - sa > sc)
		sc = sb - sa;
	tol = sc * 1e-9L;
	if (tol < 1e-315L)
		tol = 1e-315L;
	if (!(sa <= sb + tol)) {
		OCHECK(nv == 0, "ray misses but %d visits", nv);
		return;
	}
	if (!(sa < sb - tol)) {
		/* a touch: at most zero-length visits */
		for (k = 0; k < nv; k++)
			OCHECK(near(v[k].t0, v[k].t1, tol), "touch visit long");
		return;
	}
	OCHECK(nv > 0, "no visits, segment [%Lg, %Lg]", sa, sb);
	OCHECK(near(v[0].t0, sa, tol), "start %.17g vs %Lg", v[0].t0, sa);
	OCHECK(near(v[nv - 1].t1, sb, tol), "end %.17g vs %Lg", v[nv - 1].t1,
	    sb);
	/* entering the grid from outside is entering through a face */
	OCHECK(!(tmin < sa - tol) || v[0].entry_axis >= 0, "entry axis -1");
	/* ending at the grid's boundary is leaving through a face */
	OCHECK(!(tmax > sb + tol) || v[nv - 1].exit_axis >= 0, "exit axis -1");
	seen = calloc((size_t)(nleaf > 0 ? nleaf : 1), 1);
	for (k = 0; k < nv; k++) {
		ld c0, c1, blo[3], bhi[3];

		for (a = 0; a < 3; a++) {
			OCHECK(v[k].i[a] >= 0 && v[k].i[a] < n[a], "leaf out");
			blo[a] = (ld)v[k].i[a];
			bhi[a] = blo[a] + 1;
		}
		i = v[k].i[0] + n[0] * (v[k].i[1] + n[1] * v[k].i[2]);
		OCHECK(v[k].leaf == i, "linear index");
		OCHECK(!seen[i], "leaf %lld %lld %lld visited twice",
		    (long long)v[k].i[0], (long long)v[k].i[1],
		    (long long)v[k].i[2]);
		seen[i] = 1;
		OCHECK(v[k].t0 <= v[k].t1, "t0 > t1 at visit %d", k);
		if (k > 0)
			OCHECK(v[k].t0 == v[k - 1].t1, "gap at visit %d", k);
		box_interval(blo, bhi, o, d, 0, &c0, &c1);
		OCHECK(v[k].t0 >= c0 - tol && v[k].t1 <= c1 + tol,
		    "visit %d [%.17g, %.17g] outside leaf [%Lg, %Lg]", k,
		    v[k].t0, v[k].t1, c0, c1);
		if (v[k].entry_axis >= 0) {
			a = v[k].entry_axis;
			ld p = blo[a] + v[k].entry_side;
			OCHECK(d[a] != 0 && (v[k].entry_side == 0) == (d[a] > 0),
			    "entry side");
			OCHECK(near(v[k].t0, clampinf((p - o[a]) / (ld)d[a]), tol),
			    "entry face time");
		}
		if (v[k].exit_axis >= 0) {
			a = v[k].exit_axis;
			ld p = blo[a] + v[k].exit_side;
			OCHECK(d[a] != 0 && (v[k].exit_side == 1) == (d[a] > 0),
			    "exit side");
			OCHECK(near(v[k].t1, clampinf((p - o[a]) / (ld)d[a]), tol),
			    "exit face time");
		}
		if (k + 1 < nv) {
			a = v[k].exit_axis;
			OCHECK(a >= 0 && v[k + 1].entry_axis == a, "step axis");
			for (int b = 0; b < 3; b++)
				OCHECK(v[k + 1].i[b] - v[k].i[b] == (b == a ?
				    (d[a] > 0 ? 1 : -1) : 0),
				    "visit %d -> %d not a face step", k, k + 1);
		}
	}
	/* every core leaf visited */
	for (int64_t z = 0; z < n[2]; z++)
		for (int64_t y = 0; y < n[1]; y++)
			for (int64_t x = 0; x < n[0]; x++) {
				ld blo[3] = { x, y, z }, bhi[3] = { x + 1, y + 1,
				    z + 1 }, c0, c1;

				box_interval(blo, bhi, o, d, 1, &c0, &c1);
				if (c0 < sa)
					c0 = sa;
				if (c1 > sb)
					c1 = sb;
				OCHECK(!(c1 - c0 > tol) ||
				    seen[x + n[0] * (y + n[1] * z)],
				    "core leaf %lld %lld %lld (%Lg..%Lg) missed",
				    (long long)x, (long long)y, (long long)z,
				    c0, c1);
			}
	free(seen);
}

/* an explicit-leaf hierarchy where every leaf holds [0, 1] */
static void
unit_leaves(vx_macro *m, const int64_t n[3], int nlev, const int sz[][3])
{
	size_t k, nl = (size_t)(n[0] * n[1] * n[2]);
	float *mm = malloc(2 * sizeof(float) * (nl ? nl : 1));
	vx_err e = { 0, "" };

	for (k = 0; k < nl; k++) {
		mm[2 * k] = 0;
		mm[2 * k + 1] = 1;
	}
	assert_int_equal(vx_macro_build_explicit(m, n, mm, nlev, sz, 1, &e), 0);
	free(mm);
}

static int
same_visit(const vx_leaf_visit *a, const vx_leaf_visit *b)
{
	return a->i[0] == b->i[0] && a->i[1] == b->i[1] && a->i[2] == b->i[2] &&
	    a->leaf == b->leaf && memcmp(&a->t0, &b->t0, sizeof a->t0) == 0 &&
	    memcmp(&a->t1, &b->t1, sizeof a->t1) == 0 &&
	    a->entry_axis == b->entry_axis && a->entry_side == b->entry_side &&
	    a->exit_axis == b->exit_axis && a->exit_side == b->exit_side &&
	    memcmp(&a->lo, &b->lo, sizeof a->lo) == 0 &&
	    memcmp(&a->hi, &b->hi, sizeof a->hi) == 0;
}

/* same_prefix: a's visits are b's first a->n ones (same_visit, and with
 * corners the same corner values too) */
static int
same_prefix(const rec *a, const rec *b, int corners)
{
	if (a->n > b->n)
		return 0;
	for (int i = 0; i < a->n; i++)
		if (!same_visit(&a->v[i], &b->v[i]) || (corners &&
		    memcmp(a->v[i].c, b->v[i].c, sizeof a->v[i].c) != 0))
			return 0;
	return 1;
}

/* check_both: run the flat walk and the hierarchical walk (over a few
 * hierarchies) with no values; each must pass the oracle, and they must be
 * identical. */
static void
check_both(const char *what, const int64_t n[3], const double o[3],
    const double d[3], double tmin, double tmax)
{
	static const int sz[][3] = { { 2, 3, 2 }, { 2, 2, 1 }, { 3, 1, 2 } };
	static const int s1[][3] = { { 1, 1, 1 } };
	vx_macro m;
	rec f, h;
	int rc, lev;

	rec_init(&f, n);
	rec_init(&h, n);
	unit_leaves(&m, n, 0, NULL);
	rc = vx_macro_traverse_flat(&m, NULL, o, d, tmin, tmax, NULL, 0,
	    collect, &f, NULL);
	assert_int_equal(rc, 0);
	oracle_check(what, n, o, d, tmin, tmax, f.v, f.n);
	vx_macro_free(&m);
	for (lev = 0; lev <= 4; lev++) {
		vx_trav_stats st;

		memset(&st, 0, sizeof st);
		if (lev == 4)
			unit_leaves(&m, n, 1, s1);
		else
			unit_leaves(&m, n, lev, sz);
		h.n = 0;
		rc = vx_macro_traverse(&m, NULL, o, d, tmin, tmax, NULL, 0,
		    collect, &h, &st);
		assert_int_equal(rc, 0);
		OCHECK(h.n == f.n, "hierarchy (%d levels) visits %d, flat %d",
		    lev, h.n, f.n);
		for (int k = 0; k < f.n; k++)
			OCHECK(same_visit(&h.v[k], &f.v[k]), "visit %d differs",
			    k);
		assert_int_equal(st.leaves, (uint64_t)h.n);
		vx_macro_free(&m);
	}
	free(f.v);
	free(h.v);
}

/* The hard cases, each against the brute-force oracle (and the flat and
 * hierarchical walks against each other). */
static void
walk_hard_cases(void **state)
{
	const double tiny = 1e-300, tiny2 = 1e-30, huge = 1e300;
	const double sub = 4.9406564584124654e-324;
	static const int64_t N[3] = { 5, 4, 3 }, T[3] = { 1, 40, 1 },
	    C[3] = { 4, 4, 4 };
	const struct {
		const char *what;
		const int64_t *n;
		double o[3], d[3], tmin, tmax;
	} t[] = {
		{ "axis +x from outside", N, { -1, 0.5, 0.5 }, { 1, 0, 0 }, 0, INFINITY },
		{ "axis -x with -0.0", N, { 7, 1.5, 2.5 }, { -1, -0.0, 0.0 }, 0, INFINITY },
		{ "axis -0.0 origin on face", N, { -0.0, 1.5, 2.5 }, { 1, -0.0, 0 }, 0, INFINITY },
		{ "diagonal through vertices", C, { 0, 0, 0 }, { 1, 1, 1 }, 0, INFINITY },
		{ "diagonal from outside", C, { -1, -1, -1 }, { 1, 1, 1 }, -INFINITY, INFINITY },
		{ "anti-diagonal", C, { 4, 4, 0 }, { -1, -1, 1 }, 0, INFINITY },
		{ "diagonal in a plane", C, { 0, 0, 2 }, { 1, 1, 0 }, 0, INFINITY },
		{ "2:1 through edges", C, { 0, 0, 0.5 }, { 2, 1, 0 }, 0, INFINITY },
		{ "grazing interior face plane", N, { -1, 2, 0.5 }, { 1, 0, 0.1 }, 0, INFINITY },
		{ "in outer face y=n", N, { -1, 4, 0.5 }, { 1, 0, 0.2 }, 0, INFINITY },
		{ "in outer face y=0", N, { -1, 0, 0.5 }, { 1, 0, 0.2 }, 0, INFINITY },
		{ "along interior edge", N, { -1, 1, 1 }, { 1, 0, 0 }, 0, INFINITY },
		{ "along outer edge", N, { -1, 0, 0 }, { 1, 0, 0 }, 0, INFINITY },
		{ "along far outer edge", N, { 6, 4, 3 }, { -1, 0, 0 }, 0, INFINITY },
		{ "just outside", N, { -1, -1e-12, 0.5 }, { 1, 0, 0 }, 0, INFINITY },
		{ "touching an outer edge", N, { -1, -1, 0.5 }, { 1, 1, 0 }, 0, INFINITY },
		{ "touching a corner", N, { -1, -1, -1 }, { 1, 1, 1 }, 0, INFINITY },
		{ "parallel in face plane, z axis", N, { 0.5, 1, -2 }, { 0, 0, 1 }, 0, INFINITY },
		{ "parallel on edge, z axis", N, { 1, 1, -2 }, { 0, 0, 1 }, 0, INFINITY },
		{ "parallel outside", N, { 0.5, 4.5, -2 }, { 0, 0, 1 }, 0, INFINITY },
		{ "tiny components", N, { -0.5, 0.5, 0.5 }, { 1, tiny, tiny2 }, 0, INFINITY },
		{ "tiny negative", N, { 0.5, -1, 2.5 }, { -tiny, 1, -tiny2 }, 0, INFINITY },
		{ "tiny, origin near plane", N, { 0.25, 0.9999999999, 0.5 }, { 1, tiny, 0 }, 0, INFINITY },
		{ "subnormal component", N, { 0.25, 0.9999999999, 0.5 }, { 1, sub, 0 }, 0, INFINITY },
		{ "subnormal, origin on a plane", N, { 1, 0.5, 0.5 }, { sub, 0, 0 }, 0, INFINITY },
		{ "subnormal, far crossing", N, { -1e-300, 0.5, 0.5 }, { 1e-310, 0, 0 }, 0, INFINITY },
		{ "subnormal only", N, { 0.25, 0.5, 0.5 }, { sub, 0, 0 }, 0, INFINITY },
		{ "huge components", N, { 0.5, 0.5, 0.5 }, { huge, huge / 10, 3 * huge }, 0, INFINITY },
		{ "huge and zero", N, { 0.5, 1.5, 0.5 }, { huge, 0, -huge }, -INFINITY, INFINITY },
		{ "huge and tiny", N, { 0.5, 1.5, 0.5 }, { huge, tiny, 1 }, 0, INFINITY },
		{ "max double", N, { -1, 1.5, 0.5 }, { DBL_MAX, DBL_MAX, 0 }, 0, INFINITY },
		{ "start inside", N, { 1.5, 1.5, 1.5 }, { 0.3, -0.7, 0.2 }, 0, INFINITY },
		{ "start on boundary going in", N, { 0, 1.5, 1.5 }, { 1, 0.1, 0.1 }, 0, INFINITY },
		{ "start on far boundary going in", N, { 5, 1.2, 0.7 }, { -1, 0.2, 0.1 }, 0, INFINITY },
		{ "start on boundary going out", N, { 5, 1.5, 1.5 }, { 1, 0.1, 0.1 }, 0, INFINITY },
		{ "start on interior plane", N, { 2, 1.5, 0.5 }, { 1, 0.3, 0.2 }, 0, INFINITY },
		{ "start on interior vertex", N, { 2, 1, 1 }, { -1, -1, 1 }, 0, INFINITY },
		{ "start on vertex, backwards", N, { 2, 1, 1 }, { -1, -1, 1 }, -INFINITY, 0 },
		{ "tmin tmax clip", N, { -1, 0.5, 0.5 }, { 1, 0.2, 0.1 }, 2.3, 3.7 },
		{ "tmax at a crossing", N, { 0, 0.5, 0.5 }, { 1, 0.2, 0.1 }, 0, 2 },
		{ "tmin at a crossing", N, { 0, 0.5, 0.5 }, { 1, 0.2, 0.1 }, 2, 4.5 },
		{ "point segment", N, { 0, 0.5, 0.5 }, { 1, 0.2, 0.1 }, 2.5, 2.5 },
		{ "empty tmin > tmax", N, { 0, 0.5, 0.5 }, { 1, 0.2, 0.1 }, 3, 2 },
		{ "NaN tmax", N, { 0, 0.5, 0.5 }, { 1, 0.2, 0.1 }, 0, NAN },
		{ "zero direction inside", N, { 1.5, 2.5, 0.5 }, { 0, 0, 0 }, 0, 7 },
		{ "zero direction outside", N, { 1.5, 7.5, 0.5 }, { 0, -0.0, 0 }, 0, 7 },
		{ "thin 1xNx1 along y", T, { 0.5, -3, 0.5 }, { 0, 1, 0 }, 0, INFINITY },
		{ "thin, slightly oblique", T, { 0.5, -3, 0.5 }, { 1e-3, 1, -1e-3 }, 0, INFINITY },
		{ "thin, on its corner edge", T, { 1, 50, 1 }, { 0, -1, 0 }, 0, INFINITY },
		{ "thin, across", T, { -1, 17.5, 0.5 }, { 1, 0.01, 0 }, 0, INFINITY },
		{ "thin, diagonal in box", T, { 0, 0, 0 }, { 1, 40, 1 }, 0, INFINITY },
		{ "far origin", N, { -1e6, 0.5, 0.5 }, { 1, 1e-7, 0 }, 0, INFINITY },
		{ "far origin, oblique", N, { -1e6, -1e6, 0.5 }, { 1, 1, 0.1e-6 }, 0, INFINITY },
	};
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++)
		check_both(t[i].what, t[i].n, t[i].o, t[i].d, t[i].tmin,
		    t[i].tmax);
}

/* A component that is not finite: the walk visits nothing. */
static void
walk_nonfinite_input(void **state)
{
	int64_t n[3] = { 3, 3, 3 };
	double o[3] = { 0.5, 0.5, -1 }, d[3] = { 0, 0, 1 };
	vx_macro m;
	rec r;

	(void)state;
	unit_leaves(&m, n, 0, NULL);
	rec_init(&r, n);
	d[1] = NAN;
	assert_int_equal(vx_macro_traverse(&m, NULL, o, d, 0, INFINITY, NULL,
	    0, collect, &r, NULL), 0);
	d[1] = INFINITY;
	assert_int_equal(vx_macro_traverse(&m, NULL, o, d, 0, INFINITY, NULL,
	    0, collect, &r, NULL), 0);
	d[1] = 0;
	o[0] = NAN;
	assert_int_equal(vx_macro_traverse(&m, NULL, o, d, 0, INFINITY, NULL,
	    0, collect, &r, NULL), 0);
	assert_int_equal(r.n, 0);
	free(r.v);
	vx_macro_free(&m);
}

/* a random ray component: snapped to the lattice often, so ties, face
 * planes and vertices are hit far more than chance would */
static double
rand_coord(uint64_t *s, int64_t n)
{
	switch (irand(s, 4)) {
	case 0: return irand(s, (int)n + 3) - 1;
	case 1: return irand(s, 2 * (int)n + 6) * 0.5 - 1.5;
	default: return urand(s) * (double)(n + 4) - 2;
	}
}

static double
rand_dir(uint64_t *s)
{
	static const double pick[] = { 0, -0.0, 1, -1, 0.5, -2, 1e-300, -1e-30,
	    1e300, 3 };

	if (irand(s, 3) == 0)
		return pick[irand(s, 10)];
	return urand(s) * 2 - 1;
}

/* Random rays over random grids, hierarchies with random sizes: the flat
 * walk passes the oracle and the hierarchical walks equal it. */
static void
walk_random_oracle(void **state)
{
	uint64_t s = 12345;
	char what[64];

	(void)state;
	for (int k = 0; k < 1500; k++) {
		int64_t n[3];
		double o[3], d[3], tmin = 0, tmax = INFINITY;

		for (int a = 0; a < 3; a++)
			n[a] = 1 + irand(&s, 7);
		for (int a = 0; a < 3; a++) {
			o[a] = rand_coord(&s, n[a]);
			d[a] = rand_dir(&s);
		}
		if (irand(&s, 4) == 0) {
			tmin = urand(&s) * 4 - 1;
			tmax = tmin + urand(&s) * 4;
		} else if (irand(&s, 4) == 0)
			tmin = -INFINITY;
		snprintf(what, sizeof what, "random ray %d", k);
		check_both(what, n, o, d, tmin, tmax);
	}
}

/* ---- volumes ---- */

/* rand_grid: dims n, type t, random values (f32: with NaN and Inf among
 * them), in the given layout. */
static void
rand_grid(vx_grid *g, const int64_t dims[3], vx_type t, const char *lay,
    uint64_t seed, int nonfinite)
{
	vx_err e = { 0, "" };
	uint64_t s = seed;
	double c[3], w[3];
	int smooth = irand(&s, 3);   /* 0 noise, 1 ramp, 2 ball */

	for (int a = 0; a < 3; a++) {
		c[a] = urand(&s) * (double)dims[a];
		w[a] = urand(&s) * 30 - 15;
	}

	assert_int_equal(vx_grid_alloc(g, dims, t, lay, &e), 0);
	for (int64_t z = 0; z < dims[2]; z++)
		for (int64_t y = 0; y < dims[1]; y++)
			for (int64_t x = 0; x < dims[0]; x++) {
				double v = urand(&s) * 200;

				if (smooth == 1)
					v = 100 + w[0] * (x - c[0]) + w[1] *
					    (y - c[1]) + w[2] * (z - c[2]) + v / 50;
				else if (smooth == 2)
					v = 20 * sqrt((x - c[0]) * (x - c[0]) +
					    (y - c[1]) * (y - c[1]) + (z - c[2]) *
					    (z - c[2])) + v / 50;

				if (nonfinite && irand(&s, 20) == 0)
					v = irand(&s, 2) ? NAN : -INFINITY;
				vx_grid_set(g, x, y, z, v);
			}
}

/* leaf_range: brute-force range of cell (x,y,z) from its corners. */
static void
leaf_range(const vx_grid *g, int64_t x, int64_t y, int64_t z, float *lo,
    float *hi)
{
	*lo = INFINITY;
	*hi = -INFINITY;
	for (int k = 0; k < 8; k++) {
		float v = (float)vx_grid_get(g, x + (k & 1), y + (k >> 1 & 1),
		    z + (k >> 2 & 1));

		if (!isfinite(v))
			continue;
		if (v < *lo)
			*lo = v;
		if (v > *hi)
			*hi = v;
	}
}

/* Each stored macrocell range equals the brute-force union of its leaves'
 * ranges (oracle: leaf ranges from vx_grid_get, looped over the leaves the
 * macrocell covers); the result does not depend on the thread count. */
static void
build_matches_brute_force(void **state)
{
	static const int sz[][3] = { { 3, 2, 4 }, { 2, 3, 1 }, { 2, 2, 2 } };
	int64_t dims[3] = { 12, 9, 14 };
	vx_grid g;
	vx_macro m, m4;
	vx_err e = { 0, "" };

	(void)state;
	rand_grid(&g, dims, VX_F32, "bricked 2x2x2", 7, 1);
	assert_int_equal(vx_macro_build(&m, &g, 3, sz, 1, &e), 0);
	assert_int_equal(vx_macro_build(&m4, &g, 3, sz, 4, &e), 0);
	for (int l = 1; l <= 3; l++) {
		assert_memory_equal(m.mm[l], m4.mm[l],
		    2 * sizeof(float) * (size_t)(m.dims[l][0] * m.dims[l][1] *
		    m.dims[l][2]));
		for (int64_t cz = 0; cz < m.dims[l][2]; cz++)
			for (int64_t cy = 0; cy < m.dims[l][1]; cy++)
				for (int64_t cx = 0; cx < m.dims[l][0]; cx++) {
					float lo = INFINITY, hi = -INFINITY, a, b;
					int64_t c[3] = { cx, cy, cz }, q0[3], q1[3];

					for (int k = 0; k < 3; k++) {
						q0[k] = c[k] * m.width[l][k];
						q1[k] = q0[k] + m.width[l][k];
						if (q1[k] > dims[k] - 1)
							q1[k] = dims[k] - 1;
					}
					for (int64_t z = q0[2]; z < q1[2]; z++)
						for (int64_t y = q0[1]; y < q1[1]; y++)
							for (int64_t x = q0[0]; x < q1[0];
							    x++) {
								leaf_range(&g, x, y, z, &a,
								    &b);
								lo = fminf(lo, a);
								hi = fmaxf(hi, b);
							}
					vx_macro_cell_range(&m, l, cx, cy, cz, &a, &b);
					assert_true(a == lo && b == hi);
				}
	}
	assert_true(m.root[0] == m4.root[0] && m.root[1] == m4.root[1]);
	vx_macro_free(&m);
	vx_macro_free(&m4);
	vx_grid_free(&g);
}

/* Non-finite policy: a cell whose corners are all NaN/Inf has the empty
 * range and is never visited with values; one with finite corners
 * bracketing the value is. */
static void
nonfinite_policy(void **state)
{
	int64_t dims[3] = { 3, 2, 2 };
	static const int sz[][3] = { { 1, 1, 1 } };
	double o[3] = { -1, 0.5, 0.5 }, d[3] = { 1, 0, 0 };
	float val = 5;
	vx_grid g;
	vx_macro m;
	vx_err e = { 0, "" };
	rec r;

	(void)state;
	assert_int_equal(vx_grid_alloc(&g, dims, VX_F32, NULL, &e), 0);
	for (int z = 0; z < 2; z++)
		for (int y = 0; y < 2; y++) {
			vx_grid_set(&g, 0, y, z, NAN);
			vx_grid_set(&g, 1, y, z, y ? INFINITY : NAN);
			vx_grid_set(&g, 2, y, z, y ? 10 : 0);
		}
	/* cell 0: all non-finite; cell 1: finite corners 0 and 10 */
	assert_int_equal(vx_macro_build(&m, &g, 1, sz, 1, &e), 0);
	assert_true(m.mm[1][0] > m.mm[1][1]);
	assert_true(m.mm[1][2] == 0 && m.mm[1][3] == 10);
	rec_init(&r, m.dims[0]);
	assert_int_equal(vx_macro_traverse(&m, &g, o, d, 0, INFINITY, &val, 1,
	    collect, &r, NULL), 0);
	assert_int_equal(r.n, 1);
	assert_int_equal(r.v[0].i[0], 1);
	assert_true(isinf(r.v[0].c[2]) && r.v[0].lo == 0 && r.v[0].hi == 10);
	free(r.v);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* The hierarchical walk visits exactly the leaves of the flat walk that
 * bracket a value, bit for bit, for random volumes, values, hierarchies and
 * rays; a bricked copy of the volume gives the identical sequence.  Oracle:
 * the flat walk (checked against brute force above) filtered by the
 * brute-force leaf range. */
static void
hierarchy_equals_filtered_flat(void **state)
{
	uint64_t s = 99;
	int culled = 0, rays = 0;

	(void)state;
	for (int k = 0; k < 90; k++) {
		int64_t dims[3];
		int sz[3][3], nlev = irand(&s, 4);
		vx_grid g, gb;
		vx_macro m;
		vx_err e = { 0, "" };

		for (int a = 0; a < 3; a++)
			dims[a] = 2 + irand(&s, 14);
		for (int l = 0; l < 3; l++)
			for (int a = 0; a < 3; a++)
				sz[l][a] = 1 + irand(&s, 5);
		rand_grid(&g, dims, k % 3 ? VX_F32 : VX_U8, NULL, hash64(k),
		    k % 2);
		assert_int_equal(vx_grid_relayout(&gb, &g, "bricked 2x4x2 2x2x2",
		    &e), 0);
		assert_int_equal(vx_macro_build(&m, &g, nlev, sz, 2, &e), 0);
		for (int j = 0; j < 40; j++) {
			double o[3], d[3];
			float vals[3];
			int nv = 1 + irand(&s, 3);
			rec all, f, h, hb;
			vx_trav_stats st;

			for (int a = 0; a < 3; a++) {
				o[a] = rand_coord(&s, dims[a] - 1);
				d[a] = rand_dir(&s);
			}
			if (j % 2) {
				/* through macrocell edges and corners */
				for (int a = 0; a < 3; a++) {
					int w = sz[0][a] * (nlev > 1 &&
					    irand(&s, 2) ? sz[1][a] : 1);

					o[a] = (double)(w * irand(&s, 4));
					d[a] = irand(&s, 4) ? (irand(&s, 2) ? 1 : -1) *
					    (double)sz[0][a] : 0;
				}
			}
			for (int q = 0; q < nv; q++)
				vals[q] = (float)(urand(&s) * 220 - 10);
			if (irand(&s, 5) == 0)
				vals[0] = (float)irand(&s, 200);  /* exact hits */
			rec_init(&all, m.dims[0]);
			rec_init(&f, m.dims[0]);
			rec_init(&h, m.dims[0]);
			rec_init(&hb, m.dims[0]);
			assert_int_equal(vx_macro_traverse_flat(NULL, &g, o, d, 0,
			    INFINITY, NULL, 0, collect, &all, NULL), 0);
			assert_int_equal(vx_macro_traverse_flat(&m, &g, o, d, 0,
			    INFINITY, vals, nv, collect, &f, NULL), 0);
			memset(&st, 0, sizeof st);
			assert_int_equal(vx_macro_traverse(&m, &g, o, d, 0,
			    INFINITY, vals, nv, collect, &h, &st), 0);
			assert_int_equal(vx_macro_traverse(&m, &gb, o, d, 0,
			    INFINITY, vals, nv, collect, &hb, NULL), 0);
			/* the filtered flat walk is the unfiltered one, filtered */
			int q = 0;
			for (int i = 0; i < all.n; i++) {
				float lo, hi;
				int hit = 0;

				leaf_range(&g, all.v[i].i[0], all.v[i].i[1],
				    all.v[i].i[2], &lo, &hi);
				for (int w = 0; w < nv; w++)
					hit |= lo <= vals[w] && vals[w] <= hi;
				if (!hit)
					continue;
				assert_true(q < f.n);
				assert_true(all.v[i].t0 == f.v[q].t0 &&
				    all.v[i].leaf == f.v[q].leaf);
				q++;
			}
			assert_int_equal(q, f.n);
			culled += f.n < all.n;
			rays += all.n > 0;
			assert_int_equal(h.n, f.n);
			assert_int_equal(hb.n, f.n);
			assert_int_equal(st.leaves, (uint64_t)h.n);
			for (int i = 0; i < f.n; i++) {
				assert_true(same_visit(&h.v[i], &f.v[i]));
				assert_true(same_visit(&hb.v[i], &f.v[i]));
				assert_memory_equal(h.v[i].c, f.v[i].c,
				    sizeof h.v[i].c);
				assert_memory_equal(hb.v[i].c, f.v[i].c,
				    sizeof h.v[i].c);
			}
			free(all.v);
			free(f.v);
			free(h.v);
			free(hb.v);
		}
		vx_macro_free(&m);
		vx_grid_free(&g);
		vx_grid_free(&gb);
	}
	/* the values must cull a fair share, or the test proves little */
	assert_true(culled > rays / 3);
}

/* ---- cell masks ---- */

/* check_mask_bits: every bit of eager mask em over m and g against the
 * leaf's corner range read one corner at a time (leaf_range, the oracle),
 * for values vals[0..nv); returns the number of set bits */
static int64_t
check_mask_bits(const vx_cellmask *em, const vx_macro *m, const vx_grid *g,
    const float *vals, int nv)
{
	int64_t nb[3] = { m->dims[1][0], m->dims[1][1], m->dims[1][2] };
	int64_t w[3] = { m->width[1][0], m->width[1][1], m->width[1][2] };
	int64_t ones = 0;

	for (int64_t b = 0; b < nb[0] * nb[1] * nb[2]; b++) {
		int64_t bx = b % nb[0], by = b / nb[0] % nb[1];
		int64_t bz = b / nb[0] / nb[1];

		if (em->slot[b] < 0)
			continue;
		for (int64_t z = 0; z < w[2]; z++)
			for (int64_t y = 0; y < w[1]; y++)
				for (int64_t x = 0; x < w[0]; x++) {
					int64_t X = bx * w[0] + x;
					int64_t Y = by * w[1] + y;
					int64_t Z = bz * w[2] + z;
					int64_t i = x + w[0] * (y + w[1] * z);
					int bit = (int)(em->bits[em->slot[b] +
					    (i >> 6)] >> (i & 63) & 1);
					int want = 0;
					float lo, hi;

					if (X < m->dims[0][0] &&
					    Y < m->dims[0][1] &&
					    Z < m->dims[0][2]) {
						leaf_range(g, X, Y, Z, &lo,
						    &hi);
						for (int q = 0; q < nv; q++)
							want |= lo <= vals[q] &&
							    vals[q] <= hi;
					}
					if (bit != want)
						fail_msg("block %lld leaf "
						    "%lld %lld %lld: bit %d, "
						    "oracle %d", (long long)b,
						    (long long)x, (long long)y,
						    (long long)z, bit, want);
					ones += bit;
				}
	}
	return ones;
}

/* Every bit of a cell mask against the brute-force bracket test of its leaf
 * (oracle: the leaf's corner range from vx_grid_get, as in
 * hierarchy_equals_filtered_flat); bits only in bracketing level-1
 * macrocells; lazy bits (built by walks) equal eager ones.  Hard cases:
 * integer isovalues equal to samples, NaN and Inf samples, a NaN isovalue,
 * isovalues beyond the type's range, rows of up to 63 leaves (bits that
 * straddle 64-bit words), partial macrocells at the grid's far faces. */
static void
cellmask_bits_brute_force(void **state)
{
	static const vx_type types[] = { VX_U8, VX_I16, VX_U16, VX_F32 };
	uint64_t s = 7;

	(void)state;
	for (int k = 0; k < 48; k++) {
		int64_t dims[3];
		int sz[2][3];
		float vals[4];
		int nv = 1 + irand(&s, 3);
		vx_grid g;
		vx_macro m;
		vx_cellmask em, lm;
		vx_err e = { 0, "" };

		for (int a = 0; a < 3; a++) {
			dims[a] = 2 + irand(&s, a == 0 ? 80 : 12);
			sz[0][a] = 1 + irand(&s, a == 0 ? 63 : 6);
			sz[1][a] = 1 + irand(&s, 3);
		}
		rand_grid(&g, dims, types[k % 4], k % 8 < 4 ? NULL :
		    "bricked 4x2x2 2x2x2", hash64(100 + k), types[k % 4] ==
		    VX_F32);
		assert_int_equal(vx_macro_build(&m, &g, 1 + irand(&s, 2), sz, 2,
		    &e), 0);
		for (int q = 0; q < nv; q++)
			vals[q] = irand(&s, 2) ? (float)irand(&s, 200) :
			    (float)(urand(&s) * 220 - 10);
		if (k % 11 == 5)
			vals[nv - 1] = NAN;
		if (k % 13 == 6)
			vals[0] = k % 2 ? 1e30f : -1e30f;
		assert_int_equal(vx_cellmask_build(&em, &m, &g, vals, nv, 0, 2,
		    &e), 0);
		assert_int_equal(vx_cellmask_build(&lm, &m, &g, vals, nv, 1, 1,
		    &e), 0);
		assert_true(em.ready && lm.ready);
		assert_int_equal(vx_cellmask_built(&lm), 0);
		int64_t nb[3] = { m.dims[1][0], m.dims[1][1], m.dims[1][2] };
		int64_t set = 0;
		for (int64_t b = 0; b < nb[0] * nb[1] * nb[2]; b++) {
			float blo = m.mm[1][2 * b], bhi = m.mm[1][2 * b + 1];
			int br = 0;

			for (int q = 0; q < nv; q++)
				br |= blo <= vals[q] && vals[q] <= bhi;
			assert_int_equal(em.slot[b] >= 0, br);
			/* the list of set macrocells, ascending, both masks */
			if (br) {
				assert_int_equal(em.set[set], b);
				assert_int_equal(lm.set[set], b);
			}
			set += br;
		}
		(void)check_mask_bits(&em, &m, &g, vals, nv);
		assert_int_equal(em.nset, set);
		assert_int_equal(vx_cellmask_built(&em), set);
		/* walks build the lazy mask's blocks as they enter them */
		for (int j = 0; j < 60; j++) {
			double o[3], d[3];
			rec r;

			for (int a = 0; a < 3; a++) {
				o[a] = rand_coord(&s, dims[a] - 1);
				d[a] = rand_dir(&s);
			}
			rec_init(&r, m.dims[0]);
			assert_int_equal(vx_macro_traverse_masked(&m, &g, &lm, o,
			    d, 0, INFINITY, vals, nv, collect, &r, NULL), 0);
			free(r.v);
		}
		int64_t built = 0;
		for (int64_t b = 0; b < nb[0] * nb[1] * nb[2]; b++)
			if (lm.slot[b] >= 0 && lm.state[b] == 2) {
				assert_memory_equal(lm.bits + lm.slot[b],
				    em.bits + em.slot[b],
				    (size_t)em.words * sizeof *em.bits);
				built++;
			}
		/* the count kept as blocks are built: the states' count */
		assert_int_equal(vx_cellmask_built(&lm), built);
		vx_cellmask_free(&em);
		vx_cellmask_free(&lm);
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
}

/* cluster_grid: samples of type ty around centre c (c - 4 .. c + 4; f32
 * anywhere within 4 of c), one in 40 the type's lowest tlo, one in 40 its
 * highest thi, f32 one in 40 each NaN or +Inf, -Inf, +-FLT_MAX */
static void
cluster_grid(vx_grid *g, vx_type ty, double c, double tlo, double thi,
    uint64_t *s)
{
	const int64_t *n = g->dims;

	for (int64_t i = 0; i < n[0] * n[1] * n[2]; i++) {
		int r = irand(s, 40);
		double v = c + irand(s, 9) - 4;

		if (ty == VX_F32)
			v = c + (urand(s) - 0.5) * 8;
		if (r == 0 || r == 1)
			v = r == 0 ? tlo : thi;
		if (ty == VX_F32 && r == 2)
			v = irand(s, 2) ? NAN : INFINITY;
		if (ty == VX_F32 && r == 3)
			v = -INFINITY;
		if (ty == VX_F32 && r == 4)
			v = irand(s, 2) ? FLT_MAX : -FLT_MAX;
		if (ty != VX_F32)
			v = v < tlo ? tlo : v > thi ? thi : v;
		vx_grid_set(g, i % n[0], i / n[0] % n[1], i / n[0] / n[1], v);
	}
}

/* Cell masks over the layouts whose rows the mask reads many samples at a
 * time (runs of 4, 8 and 16 bytes, four-row tiles of u8 bricks 4 wide, the
 * last samples of a row read with the chunk; and rows it reads four or one
 * at a time: u8 bricks 2 wide), every type, level-1 macrocells whose rows
 * are one chunk and more, partial ones (dims that do not divide), rows
 * that cross brick edges and macrocells not aligned with the bricks
 * (oracle: check_mask_bits, each leaf's corners read one by one).  Samples
 * cluster around a centre so values bracket often, with the type's
 * extremes; values: samples, halves, the type's extremes and beyond it
 * (no sample below, or none above), NaN; f32 with NaN, infinities and
 * +-FLT_MAX samples. */
static void
cellmask_chunks_brute_force(void **state)
{
	static const vx_type types[] = { VX_U8, VX_U16, VX_I16, VX_F32 };
	static const char *const lays[] = { "linear", NULL,
		"bricked 8x2x2 2x2x2", "bricked 2x2x2 2x2x2",
		"bricked 16x4x2" };
	static const int sz1[][3] = {
		{ 16, 16, 8 }, { 16, 8, 8 }, { 8, 8, 8 }, { 32, 4, 2 },
		{ 15, 5, 3 }, { 31, 12, 2 }, { 63, 4, 1 }, { 47, 3, 4 },
		{ 12, 6, 2 }, { 3, 8, 2 }, { 16, 5, 2 }, { 32, 6, 3 },
		{ 24, 4, 2 }, { 40, 3, 2 },
	};
	uint64_t s = 11;
	int64_t ones = 0, zeros = 0;

	(void)state;
	/* every type and layout; the default bricks with every size */
	for (int cs = 0; cs < 4 * 5 * 14; cs++) {
		int t = cs / 70, l = cs / 14 % 5, q = cs % 14;
		vx_type ty = types[t];
		double tlo = ty == VX_I16 ? -32768 : ty == VX_F32 ? -1e6 : 0;
		double thi = ty == VX_U8 ? 255 : ty == VX_I16 ? 32767 :
		    ty == VX_F32 ? 1e6 : 65535;
		int bricks[VX_LAYOUT_MAXLEV][3], sz[2][3];
		int nv = 2 + irand(&s, 3);
		int64_t dims[3], n;
		char lay[64];
		double c;
		float vals[6];
		vx_grid g;
		vx_macro m;
		vx_cellmask em;
		vx_err e = { 0, "" };

		if (l != 1 && q % 2)
			continue;
		for (int a = 0; a < 3; a++) {
			sz[0][a] = sz1[(q + t) % 14][a];
			sz[1][a] = 2;
			/* one or two macrocells and a part */
			dims[a] = sz[0][a] * (1 + irand(&s, 2)) + 1 +
			    irand(&s, sz[0][a] + 1);
		}
		if (lays[l] == NULL) {
			vx_layout bl = { .nlev = vx_layout_default_bricks(ty,
			    bricks) };

			memcpy(bl.brick, bricks, 2 * sizeof bricks[0]);
			vx_layout_string(&bl, lay, sizeof lay);
		} else
			snprintf(lay, sizeof lay, "%s", lays[l]);
		assert_int_equal(vx_grid_alloc(&g, dims, ty, lay, &e), 0);
		/* the centre: anywhere, the type's ends too */
		c = irand(&s, 4) == 0 ? (irand(&s, 2) ? tlo : thi) :
		    tlo + urand(&s) * (thi - tlo);
		if (ty != VX_F32)
			c = floor(c);
		cluster_grid(&g, ty, c, tlo, thi, &s);
		for (int k = 0; k < nv; k++) {
			int r = irand(&s, 12);

			vals[k] = (float)(c + irand(&s, 7) - 3 +
			    (irand(&s, 2) ? 0.5 : 0));
			if (r == 0 || r == 1)
				vals[k] = (float)(r == 0 ? tlo : thi);
			else if (r == 2 || r == 3)
				vals[k] = (float)(r == 2 ? tlo - 0.5 :
				    thi + 0.5);
			else if (r == 4)
				vals[k] = (float)(thi - 0.5);
			else if (r == 5 && ty == VX_F32)
				vals[k] = irand(&s, 2) ? FLT_MAX : -FLT_MAX;
			else if (r == 6)
				vals[k] = NAN;
		}
		assert_int_equal(vx_macro_build(&m, &g, 2,
		    (const int (*)[3])sz, 1, &e), 0);
		assert_int_equal(vx_cellmask_build(&em, &m, &g, vals, nv, 0, 1,
		    &e), 0);
		assert_true(em.ready);
		n = check_mask_bits(&em, &m, &g, vals, nv);
		ones += n;
		zeros += m.dims[0][0] * m.dims[0][1] * m.dims[0][2] - n;
		vx_cellmask_free(&em);
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
	/* both answers, plenty of each */
	assert_true(ones > 20000);
	assert_true(zeros > 20000);
}

/* The masked walk makes the plain walk's visits, bit for bit (oracle: the
 * plain hierarchical walk, itself checked against the filtered flat walk
 * above), over random grids of every type, layouts, hierarchies, values
 * and rays (through macrocell edges and corners too), with lazy and eager
 * masks, 2 threads walking one lazy mask at once; and a mask that does not
 * apply (level-1 rows over VX_CELLMASK_MAXROW, no levels, other values)
 * leaves the walk plain. */
static void
cellmask_equals_plain_walk(void **state)
{
	static const vx_type types[] = { VX_U8, VX_I16, VX_F32 };
	uint64_t s = 1234;
	int64_t masked = 0;

	(void)state;
	for (int k = 0; k < 36; k++) {
		int64_t dims[3];
		int sz[3][3], nlev = k % 6 == 0 ? 0 : 1 + irand(&s, 3);
		float vals[3];
		int nv = 1 + irand(&s, 3);
		vx_grid g, gb;
		vx_macro m;
		vx_cellmask em, lm;
		vx_err e = { 0, "" };

		for (int a = 0; a < 3; a++)
			dims[a] = 2 + irand(&s, 30);
		for (int l = 0; l < 3; l++)
			for (int a = 0; a < 3; a++)
				sz[l][a] = 1 + irand(&s, 6);
		if (k % 9 == 4)
			sz[0][0] = 64;   /* rows too long: no mask */
		rand_grid(&g, dims, types[k % 3], NULL, hash64(500 + k),
		    types[k % 3] == VX_F32);
		assert_int_equal(vx_grid_relayout(&gb, &g, "bricked 2x4x2 2x2x2",
		    &e), 0);
		assert_int_equal(vx_macro_build(&m, &g, nlev, sz, 2, &e), 0);
		for (int q = 0; q < nv; q++)
			vals[q] = irand(&s, 3) ? (float)irand(&s, 200) :
			    (float)(urand(&s) * 220 - 10);
		assert_int_equal(vx_cellmask_build(&em, &m, &g, vals, nv, 0, 1,
		    &e), 0);
		assert_int_equal(vx_cellmask_build(&lm, &m, &gb, vals, nv, 1, 1,
		    &e), 0);
		assert_int_equal(em.ready, nlev >= 1 && sz[0][0] <= 63);
#ifdef _OPENMP
#pragma omp parallel for num_threads(2) schedule(dynamic, 1)
#endif
		for (int j = 0; j < 80; j++) {
			uint64_t r = hash64(((uint64_t)k << 20) + (uint64_t)j);
			double o[3], d[3];
			rec h, hm, hl, hx;
			vx_trav_stats a, b;
			float other = vals[0] + 1;
			int ok = 1;

			for (int x = 0; x < 3; x++) {
				o[x] = rand_coord(&r, dims[x] - 1);
				d[x] = rand_dir(&r);
			}
			if (j % 2 && nlev >= 1)
				for (int x = 0; x < 3; x++) {
					o[x] = (double)(sz[0][x] * irand(&r, 4));
					d[x] = irand(&r, 4) ? (irand(&r, 2) ? 1 :
					    -1) * (double)sz[0][x] : 0;
				}
			rec_init(&h, m.dims[0]);
			rec_init(&hm, m.dims[0]);
			rec_init(&hl, m.dims[0]);
			rec_init(&hx, m.dims[0]);
			memset(&a, 0, sizeof a);
			memset(&b, 0, sizeof b);
			ok &= vx_macro_traverse(&m, &g, o, d, 0, INFINITY, vals,
			    nv, collect, &h, &a) == 0;
			ok &= vx_macro_traverse_masked(&m, &g, &em, o, d, 0,
			    INFINITY, vals, nv, collect, &hm, &b) == 0;
			ok &= vx_macro_traverse_masked(&m, &gb, &lm, o, d, 0,
			    INFINITY, vals, nv, collect, &hl, NULL) == 0;
			/* other values than the mask's: the plain walk */
			ok &= vx_macro_traverse_masked(&m, &g, &em, o, d, 0,
			    INFINITY, &other, 1, collect, &hx, NULL) == 0;
			ok &= hm.n == h.n && hl.n == h.n;
			ok &= a.leaves == b.leaves && a.culled == b.culled;
			for (int l = 0; l <= VX_MACRO_MAXLEV; l++)
				ok &= a.macro[l] == b.macro[l];
			ok &= same_prefix(&hm, &h, 1) && same_prefix(&hl, &h, 1);
			hx.n = 0;
			ok &= vx_macro_traverse(&m, &g, o, d, 0, INFINITY,
			    &other, 1, collect, &hx, NULL) == 0;
			if (!ok)
				fprintf(stderr, "# grid %d ray %d: masked walk "
				    "differs\n", k, j);
			assert_true(ok);
			free(h.v);
			free(hm.v);
			free(hl.v);
			free(hx.v);
		}
		masked += vx_cellmask_built(&lm);
		vx_cellmask_free(&em);
		vx_cellmask_free(&lm);
		vx_macro_free(&m);
		vx_grid_free(&g);
		vx_grid_free(&gb);
	}
	assert_true(masked > 100);   /* the walks did use lazy bits */
}

static int
lb_cmp(const void *a, const void *b)
{
	double x = ((const vx_cellbox *)a)->lb, y = ((const vx_cellbox *)b)->lb;

	return x < y ? -1 : x > y ? 1 : 0;
}

/* vx_cellmask_boxes: for random volumes, macrocell sizes, values and block
 * edges sub, each box of a level-1 macrocell lies in one of its aligned
 * blocks (sub^3 leaves from its low corner, shorter at its far faces), no
 * two in the same, and is the least box holding that block's leaves whose
 * mask bit is set; every set bit's leaf lies in one of them (oracle: the
 * bits, read leaf by leaf, as the header lays them out); a macrocell that
 * brackets nothing has none, sub 0 gives the whole macrocell, an unready
 * mask nothing. */
static void
cellmask_boxes_cover_bits(void **state)
{
	uint64_t s = 4242;
	int64_t nboxes = 0, partial = 0;

	(void)state;
	for (int k = 0; k < 30; k++) {
		int64_t dims[3];
		int sz[2][3], sub = 1 + irand(&s, 5);
		float vals[2];
		int nv = 1 + irand(&s, 2);
		vx_grid g;
		vx_macro m;
		vx_cellmask mk;
		vx_cellbox out[64 * 64];
		vx_err e = { 0, "" };

		for (int a = 0; a < 3; a++)
			dims[a] = 2 + irand(&s, 25);
		for (int a = 0; a < 3; a++) {
			sz[0][a] = 1 + irand(&s, 9);
			sz[1][a] = 1 + irand(&s, 3);
		}
		rand_grid(&g, dims, k % 3 ? VX_U8 : VX_F32, NULL,
		    hash64(3100 + k), 0);
		assert_int_equal(vx_macro_build(&m, &g, 2, sz, 1, &e), 0);
		for (int q = 0; q < nv; q++)
			vals[q] = (float)irand(&s, 200) + 0.5f;
		vx_cellmask_init(&mk);
		assert_int_equal(vx_cellmask_boxes(&mk, 0, sub, out), 0);
		assert_int_equal(vx_cellmask_build(&mk, &m, &g, vals, nv, 1, 1,
		    &e), 0);
		for (int64_t b = 0; b < mk.nblock; b++) {
			int64_t lo[3], hi[3];
			size_t n = vx_cellmask_boxes(&mk, b, sub, out);
			const int64_t *w = m.width[1];

			vx_macro_cell_box(&m, 1, b, lo, hi);
			if (mk.slot[b] < 0) {
				assert_int_equal(n, 0);
				continue;
			}
			const uint64_t *bits = mk.bits + mk.slot[b];

			for (size_t i = 0; i < n; i++) {
				int64_t bj[3], blo[3], bhi[3];

				/* one block, distinct from the others' */
				for (int a = 0; a < 3; a++) {
					assert_true(out[i].lo[a] >= lo[a] &&
					    out[i].lo[a] < out[i].hi[a] &&
					    out[i].hi[a] <= hi[a]);
					bj[a] = (out[i].lo[a] - lo[a]) / sub;
					assert_int_equal((out[i].hi[a] - 1 - lo[a]) / sub,
					    bj[a]);
					partial += out[i].hi[a] - out[i].lo[a] < sub;
				}
				for (size_t i2 = 0; i2 < i; i2++) {
					int same = 1;

					for (int a = 0; a < 3; a++)
						same &= (out[i2].lo[a] - lo[a]) / sub ==
						    bj[a];
					assert_false(same);
				}
				/* oracle: the least box holding the block's set
				 * bits, by looking at each of its leaves */
				for (int a = 0; a < 3; a++) {
					blo[a] = INT64_MAX;
					bhi[a] = INT64_MIN;
				}
				for (int64_t z = lo[2] + bj[2] * sub; z < hi[2] &&
				    z < lo[2] + (bj[2] + 1) * sub; z++)
					for (int64_t y = lo[1] + bj[1] * sub; y < hi[1] &&
					    y < lo[1] + (bj[1] + 1) * sub; y++)
						for (int64_t x = lo[0] + bj[0] * sub;
						    x < hi[0] && x < lo[0] + (bj[0] + 1) *
						    sub; x++) {
							int64_t li = (x - lo[0]) + w[0] * ((y -
							    lo[1]) + w[1] * (z - lo[2]));
							int64_t p[3] = { x, y, z };

							if (!(bits[li >> 6] >> (li & 63) & 1))
								continue;
							for (int a = 0; a < 3; a++) {
								blo[a] = p[a] < blo[a] ? p[a] :
								    blo[a];
								bhi[a] = p[a] + 1 > bhi[a] ?
								    p[a] + 1 : bhi[a];
							}
						}
				for (int a = 0; a < 3; a++) {
					assert_int_equal(out[i].lo[a], blo[a]);
					assert_int_equal(out[i].hi[a], bhi[a]);
				}
			}
			for (int64_t z = lo[2]; z < hi[2]; z++)
				for (int64_t y = lo[1]; y < hi[1]; y++)
					for (int64_t x = lo[0]; x < hi[0]; x++) {
						int64_t li = (x - lo[0]) + w[0] * ((y -
						    lo[1]) + w[1] * (z - lo[2]));
						int64_t p[3] = { x, y, z };
						int in = 0;

						if (!(bits[li >> 6] >> (li & 63) & 1))
							continue;
						for (size_t i = 0; i < n && !in; i++)
							in = p[0] >= out[i].lo[0] &&
							    p[0] < out[i].hi[0] &&
							    p[1] >= out[i].lo[1] &&
							    p[1] < out[i].hi[1] &&
							    p[2] >= out[i].lo[2] &&
							    p[2] < out[i].hi[2];
						assert_true(in);
					}
			assert_int_equal(vx_cellmask_boxes(&mk, b, sub, NULL), n);
			nboxes += (int64_t)n;
			/* sub 0: the whole macrocell */
			assert_int_equal(vx_cellmask_boxes(&mk, b, 0, out), 1);
			assert_memory_equal(out[0].lo, lo, sizeof lo);
			assert_memory_equal(out[0].hi, hi, sizeof hi);
		}
		vx_cellmask_free(&mk);
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
	assert_true(nboxes > 500 && partial > 50);
}

/* vx_macro_boxes_entry, the ground of raycast's binning: for the boxes of
 * every level-1 macrocell that brackets the values, the walk started just
 * before the earliest entry visits exactly the leaves (same data, same
 * order) of the walk from the segment's start, and none when there is no
 * entry; so does vx_macro_traverse_boxes in one call, over the blocks with
 * and without footprints, footprints as pixel bits, and (lists of at most
 * 64) the query's entries as a mask, with the lists also sorted by this
 * ray's entry times so that the scan stops and resumes (consuming an entry
 * before its lb test: caught here); boxes in any order with lb -Inf give
 * the same time as sorted ones with true lower bounds.  Rays: random, through
 * macrocell corners and edges along axes (ties), and from inside the
 * volume.  Oracle: the walk from 0 (from just before the entry where
 * footprints leave boxes out). */
/* in_boxes: 1 when leaf i lies in one of boxes b[0..n) */
static int
in_boxes(const int64_t i[3], const vx_cellbox *b, size_t n)
{
	for (size_t k = 0; k < n; k++)
		if (i[0] >= b[k].lo[0] && i[0] < b[k].hi[0] &&
		    i[1] >= b[k].lo[1] && i[1] < b[k].hi[1] &&
		    i[2] >= b[k].lo[2] && i[2] < b[k].hi[2])
			return 1;
	return 0;
}

/* em_sorted: id, lbs and pix (n entries, id[i] = i on entry) sorted by
 * lbs = ray (o, d)'s entry time into box id[i] less a margin (slabs:
 * a lower bound of the walk's entry, within rounding of it) */
static void
em_sorted(const vx_cellbox *bx, size_t n, const double o[3],
    const double d[3], uint32_t *id, double *lbs, uint64_t *pix)
{
	for (size_t i = 0; i < n; i++) {
		double t = -INFINITY;

		for (int a = 0; a < 3; a++)
			if (d[a] != 0) {
				double p = (double)(d[a] > 0 ? bx[id[i]].lo[a] :
				    bx[id[i]].hi[a]);
				double ta = (p - o[a]) / d[a];

				t = ta > t ? ta : t;
			}
		lbs[i] = t - 1e-9 * (1 + fabs(t));
	}
	for (size_t i = 1; i < n; i++)
		for (size_t j = i; j > 0 && lbs[j - 1] > lbs[j]; j--) {
			double tl = lbs[j];
			uint32_t ti = id[j];
			uint64_t tp = pix[j];

			lbs[j] = lbs[j - 1];
			id[j] = id[j - 1];
			pix[j] = pix[j - 1];
			lbs[j - 1] = tl;
			id[j - 1] = ti;
			pix[j - 1] = tp;
		}
}

static void
boxes_entry_keeps_visits(void **state)
{
	uint64_t s = 777;
	int64_t entered = 0, none = 0, em_tested = 0;

	(void)state;
	for (int k = 0; k < 24; k++) {
		int64_t dims[3];
		int sz[2][3], nlev = 1 + irand(&s, 2);
		float vals[2];
		int nv = 1 + irand(&s, 2);
		vx_cellbox *bx;
		size_t nbx = 0;
		vx_grid g;
		vx_macro m;
		vx_err e = { 0, "" };

		for (int a = 0; a < 3; a++)
			dims[a] = 3 + irand(&s, 30);
		for (int l = 0; l < 2; l++)
			for (int a = 0; a < 3; a++)
				sz[l][a] = 1 + irand(&s, 6);
		rand_grid(&g, dims, k % 2 ? VX_U8 : VX_F32, NULL,
		    hash64(900 + k), 0);
		assert_int_equal(vx_macro_build(&m, &g, nlev, sz, 1, &e), 0);
		for (int q = 0; q < nv; q++)
			vals[q] = (float)irand(&s, 200) + 0.5f;
		bx = calloc((size_t)(m.dims[1][0] * m.dims[1][1] *
		    m.dims[1][2]), sizeof *bx);
		assert_non_null(bx);
		for (int64_t b = 0; b < m.dims[1][0] * m.dims[1][1] *
		    m.dims[1][2]; b++) {
			int64_t c[3] = { b % m.dims[1][0],
			    (b / m.dims[1][0]) % m.dims[1][1],
			    b / (m.dims[1][0] * m.dims[1][1]) };
			int in = 0;

			for (int q = 0; q < nv; q++)
				in |= m.mm[1][2 * b] <= vals[q] &&
				    vals[q] <= m.mm[1][2 * b + 1];
			if (!in)
				continue;
			bx[nbx].lb = -INFINITY;
			for (int a = 0; a < 3; a++) {
				bx[nbx].lo[a] = c[a] * m.width[1][a];
				bx[nbx].hi[a] = bx[nbx].lo[a] + m.width[1][a];
				if (bx[nbx].hi[a] > m.dims[0][a])
					bx[nbx].hi[a] = m.dims[0][a];
			}
			nbx++;
		}
		/* the blocks of sub^3 leaves of those macrocells that hold a
		 * bracketing leaf (raycast's finer bins), with footprints on a
		 * 4x4 grid of query points */
		vx_cellmask mk;
		vx_cellbox *sbx;
		size_t nsbx = 0;
		int sub = 1 + irand(&s, 5);

		assert_int_equal(vx_cellmask_build(&mk, &m, &g, vals, nv, 1, 1,
		    &e), 0);
		assert_true(mk.ready);
		sbx = calloc((size_t)(m.dims[0][0] * m.dims[0][1] *
		    m.dims[0][2]) + 1, sizeof *sbx);
		assert_non_null(sbx);
		for (int64_t b = 0; b < m.dims[1][0] * m.dims[1][1] *
		    m.dims[1][2]; b++)
			nsbx += vx_cellmask_boxes(&mk, b, sub, sbx + nsbx);
		for (size_t i = 0; i < nsbx; i++) {
			sbx[i].lb = -INFINITY;
			sbx[i].fp[0] = irand(&s, 4);
			sbx[i].fp[1] = irand(&s, 4);
			sbx[i].fp[2] = sbx[i].fp[0] + irand(&s, 4);
			sbx[i].fp[3] = sbx[i].fp[1] + irand(&s, 4);
		}
		for (int j = 0; j < 120; j++) {
			uint64_t r = hash64(((uint64_t)k << 20) + (uint64_t)j);
			double o[3], d[3], te, t0;
			rec h, h2;
			int ok = 1;

			for (int x = 0; x < 3; x++) {
				o[x] = rand_coord(&r, dims[x] - 1);
				d[x] = rand_dir(&r);
			}
			if (j % 3 == 1)   /* along axes through corners */
				for (int x = 0; x < 3; x++) {
					o[x] = (double)(sz[0][x] * irand(&r, 4));
					d[x] = irand(&r, 3) ? (irand(&r, 2) ? 1 :
					    -1) : 0;
				}
			if (j % 3 == 2)   /* from inside, anywhere */
				for (int x = 0; x < 3; x++)
					o[x] = urand(&r) * (double)(dims[x] - 1);
			te = vx_macro_boxes_entry(&m, bx, NULL, nbx, o, d, NULL);
			if (nbx > 0) {
				/* sorted by exact per-box bounds: the early stop
				 * gives the same time */
				vx_cellbox *sb = malloc(nbx * sizeof *sb);

				assert_non_null(sb);
				memcpy(sb, bx, nbx * sizeof *sb);
				for (size_t i = 0; i < nbx; i++)
					sb[i].lb = vx_macro_boxes_entry(&m, &bx[i],
					    NULL, 1, o, d, NULL);
				qsort(sb, nbx, sizeof *sb, lb_cmp);
				ok &= memcmp(&te, &(double){ vx_macro_boxes_entry(
				    &m, sb, NULL, nbx, o, d, NULL) }, sizeof te) == 0;
				free(sb);
			}
			rec_init(&h, m.dims[0]);
			rec_init(&h2, m.dims[0]);
			ok &= vx_macro_traverse(&m, &g, o, d, 0, INFINITY, vals,
			    nv, collect, &h, NULL) == 0;
			if (te == INFINITY) {
				ok &= h.n == 0;
				none++;
			} else {
				t0 = te > 0 ? nextafter(te, -INFINITY) : 0;
				ok &= vx_macro_traverse(&m, &g, o, d, t0,
				    INFINITY, vals, nv, collect, &h2, NULL) == 0;
				ok &= h2.n == h.n && same_prefix(&h2, &h, 1);
				/* the bound: no visit starts before it */
				ok &= h.n == 0 || h.v[0].t0 >= te || h.v[0].t0 == 0;
				entered += h.n > 0;
			}
			/* all the blocks (every bracketing leaf in one), in
			 * one call: the visits of the walk from 0 */
			{
				rec h4;

				rec_init(&h4, m.dims[0]);
				ok &= vx_macro_traverse_boxes(&m, &g, &mk, sbx, NULL,
				    nsbx, NULL, o, d, vals, nv, collect, &h4,
				    NULL) == 0;
				ok &= h4.n == h.n && same_prefix(&h4, &h, 1);
				free(h4.v);
			}
			/* from the entry into the blocks: the same visits */
			double tb = vx_macro_boxes_entry(&m, sbx, NULL, nsbx, o, d,
			    NULL);

			if (tb == INFINITY)
				ok &= h.n == 0;
			else {
				rec h3;

				rec_init(&h3, m.dims[0]);
				t0 = tb > 0 ? nextafter(tb, -INFINITY) : 0;
				ok &= tb >= te;
				ok &= vx_macro_traverse(&m, &g, o, d, t0,
				    INFINITY, vals, nv, collect, &h3, NULL) == 0;
				ok &= h3.n == h.n && same_prefix(&h3, &h, 0);
				ok &= h.n == 0 || h.v[0].t0 >= tb || h.v[0].t0 == 0;
				free(h3.v);
			}
			/* footprints: the boxes whose footprint holds q, as if
			 * the others were not there (oracle: that list) */
			if (nsbx > 0) {
				int32_t q[2] = { irand(&r, 6) - 1, irand(&r, 6) - 1 };
				vx_cellbox *fb = malloc(nsbx * sizeof *fb);
				size_t nf = 0;
				double tq;

				assert_non_null(fb);
				for (size_t i = 0; i < nsbx; i++)
					if (q[0] >= sbx[i].fp[0] && q[0] <= sbx[i].fp[2] &&
					    q[1] >= sbx[i].fp[1] && q[1] <= sbx[i].fp[3])
						fb[nf++] = sbx[i];
				tq = vx_macro_boxes_entry(&m, fb, NULL, nf, o, d, NULL);
				ok &= memcmp(&tq, &(double){ vx_macro_boxes_entry(&m,
				    sbx, NULL, nsbx, o, d, q) }, sizeof tq) == 0;
				/* vx_macro_traverse_boxes: in one call, the
				 * visits of the walk from 0 to the leaves of
				 * those boxes (oracle: the walk from 0, its
				 * visits outside them left out), none when
				 * there is no entry */
				rec h5, h6;

				rec_init(&h5, m.dims[0]);
				rec_init(&h6, m.dims[0]);
				vx_boxpick pk = { { q[0], q[1] }, NULL, NULL, 0, 0, 0 };

				ok &= vx_macro_traverse_boxes(&m, &g, &mk, sbx, NULL,
				    nsbx, &pk, o, d, vals, nv, collect, &h5, NULL) == 0;
				for (int i = 0; i < h.n; i++)
					if (in_boxes(h.v[i].i, fb, nf))
						h6.v[h6.n++] = h.v[i];
				ok &= tq < INFINITY || h6.n == 0;
				ok &= h5.n == h6.n && same_prefix(&h5, &h6, 1);
				/* the same with the footprints as bits of the
				 * 8 x 8 pixels around q and the lbs kept per
				 * entry (raycast's bins): the same walk */
				{
					int32_t x0 = q[0] < 0 ? -8 : q[0] / 8 * 8;
					int32_t y0 = q[1] < 0 ? -8 : q[1] / 8 * 8;
					uint64_t *pix = calloc(nsbx, sizeof *pix);
					double *lbs = malloc(nsbx * sizeof *lbs);
					uint32_t *id = malloc(nsbx * sizeof *id);
					rec h7;

					assert_true(pix && lbs && id);
					for (size_t i = 0; i < nsbx; i++) {
						id[i] = (uint32_t)i;
						lbs[i] = sbx[i].lb;
						for (int y = 0; y < 8; y++)
							for (int x = 0; x < 8; x++)
								if (x0 + x >= sbx[i].fp[0] &&
								    x0 + x <= sbx[i].fp[2] &&
								    y0 + y >= sbx[i].fp[1] &&
								    y0 + y <= sbx[i].fp[3])
									pix[i] |= (uint64_t)1 <<
									    (8 * y + x);
					}
					pk.lb = lbs;
					pk.pix = pix;
					pk.bit = 8 * (q[1] - y0) + q[0] - x0;
					rec_init(&h7, m.dims[0]);
					ok &= vx_macro_traverse_boxes(&m, &g, &mk, sbx,
					    id, nsbx, &pk, o, d, vals, nv, collect,
					    &h7, NULL) == 0;
					ok &= h7.n == h5.n && same_prefix(&h7, &h5, 0);
					/* and with q's entries as a mask (raycast's
					 * lists of at most 64): the same walk */
					if (nsbx <= 64) {
						rec h8;

						pk.use_em = 1;
						pk.em = 0;
						for (size_t i = 0; i < nsbx; i++)
							pk.em |= (pix[i] >> pk.bit & 1) << i;
						rec_init(&h8, m.dims[0]);
						ok &= vx_macro_traverse_boxes(&m, &g, &mk,
						    sbx, id, nsbx, &pk, o, d, vals, nv,
						    collect, &h8, NULL) == 0;
						ok &= h8.n == h5.n &&
						    same_prefix(&h8, &h5, 0);
						free(h8.v);
						/* with lbs that are this ray's entry
						 * times (less a margin), the list sorted
						 * by them: the scan stops early and goes
						 * on after each box, both ways */
						em_sorted(sbx, nsbx, o, d, id, lbs, pix);
						pk.em = 0;
						for (size_t i = 0; i < nsbx; i++)
							pk.em |= (pix[i] >> pk.bit & 1) << i;
						for (int w = 0; w < 2; w++) {
							rec_init(&h8, m.dims[0]);
							pk.use_em = w;
							ok &= vx_macro_traverse_boxes(&m, &g,
							    &mk, sbx, id, nsbx, &pk, o, d,
							    vals, nv, collect, &h8, NULL) == 0;
							ok &= h8.n == h5.n &&
							    same_prefix(&h8, &h5, 0);
							free(h8.v);
						}
						pk.use_em = 0;
						em_tested++;
					}
					free(h7.v);
					free(pix);
					free(lbs);
					free(id);
				}
				free(h5.v);
				free(h6.v);
				/* the same boxes through an index list, in
				 * reverse (lb all -Inf: any order is sorted) */
				uint32_t *ix = malloc(nsbx * sizeof *ix);

				assert_non_null(ix);
				for (size_t i = 0; i < nsbx; i++)
					ix[i] = (uint32_t)(nsbx - 1 - i);
				double tr = vx_macro_boxes_entry(&m, sbx, ix, nsbx, o,
				    d, q);
				ok &= memcmp(&tq, &tr, sizeof tq) == 0;
				free(ix);
				free(fb);
			}
			if (!ok)
				fprintf(stderr, "# grid %d ray %d: entry %.17g, "
				    "blocks %.17g, %d visits from 0, %d from there\n",
				    k, j, te, tb, h.n, h2.n);
			assert_true(ok);
			free(h.v);
			free(h2.v);
		}
		free(bx);
		free(sbx);
		vx_cellmask_free(&mk);
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
	assert_true(entered > 200 && none > 50 && em_tested > 200);
}

/* stop_at: a visitor that records and stops at visit number r->cap */
static int
stop_at(void *ctx, const vx_leaf_visit *v)
{
	rec *r = ctx;

	r->v[r->n++] = *v;
	return r->n == r->cap ? 7 : 0;
}

/* vx_macro_traverse_boxes through many boxes: a checkerboard (every leaf
 * brackets) in a long thin grid, each leaf its own box (blocks of 1^3),
 * rays along the long axis entering up to 149 boxes, more than the walk's
 * list of pending boxes holds (64): the visits are the walk's from 0,
 * same data and order, whatever the boxes' order (lb -Inf, given forwards
 * and backwards) or with true lower bounds sorted; rays along the axes
 * through leaf edges and corners (ties), from inside, both ways; a
 * visitor that stops at visit k stops the walk there with its value.
 * Oracle: the walk from 0 (vx_macro_traverse). */
static void
boxes_walk_many_boxes(void **state)
{
	int64_t dims[3] = { 150, 4, 4 };
	int sz[2][3] = { { 4, 2, 2 }, { 4, 2, 2 } };
	float val = 0.5f;
	uint64_t s = 4242;
	vx_grid g;
	vx_macro m;
	vx_cellmask mk;
	vx_cellbox *bx;
	uint32_t *fw, *bw;
	size_t nbx = 0;
	int64_t most = 0;
	vx_err e = { 0, "" };

	(void)state;
	assert_int_equal(vx_grid_alloc(&g, dims, VX_F32, NULL, &e), 0);
	for (int z = 0; z < 4; z++)
		for (int y = 0; y < 4; y++)
			for (int x = 0; x < 150; x++)
				vx_grid_set(&g, x, y, z, (x + y + z) % 2);
	vx_grid_range(&g);
	assert_int_equal(vx_macro_build(&m, &g, 2, sz, 1, &e), 0);
	assert_int_equal(vx_cellmask_build(&mk, &m, &g, &val, 1, 1, 1, &e),
	    0);
	bx = calloc(149 * 3 * 3, sizeof *bx);
	fw = malloc(149 * 3 * 3 * sizeof *fw);
	bw = malloc(149 * 3 * 3 * sizeof *bw);
	assert_true(bx && fw && bw);
	for (int64_t b = 0; b < m.dims[1][0] * m.dims[1][1] * m.dims[1][2];
	    b++)
		nbx += vx_cellmask_boxes(&mk, b, 1, bx + nbx);
	assert_int_equal(nbx, 149 * 3 * 3);
	for (size_t i = 0; i < nbx; i++) {
		bx[i].lb = -INFINITY;
		fw[i] = (uint32_t)i;
		bw[i] = (uint32_t)(nbx - 1 - i);
	}
	for (int j = 0; j < 300; j++) {
		double o[3], d[3];
		int sg = j % 2 ? -1 : 1, ok = 1;
		rec h, h1, h2, h3, h4;

		o[0] = sg > 0 ? -1 - 3 * urand(&s) : 151 + 3 * urand(&s);
		o[1] = 3 * urand(&s);
		o[2] = 3 * urand(&s);
		d[0] = sg;
		d[1] = (urand(&s) - 0.5) * 0.03;
		d[2] = (urand(&s) - 0.5) * 0.03;
		if (j % 5 == 1) {
			/* along x, on leaf edges and corners */
			o[1] = irand(&s, 4);
			o[2] = irand(&s, 4);
			d[1] = d[2] = 0;
		}
		if (j % 5 == 2) {
			/* diagonal steps through leaf corners */
			o[1] = 0;
			o[2] = irand(&s, 2);
			d[1] = d[2] = 1.0 / 64;
		}
		if (j % 5 == 3)   /* from inside */
			o[0] = 149 * urand(&s);
		rec_init(&h, m.dims[0]);
		ok &= vx_macro_traverse(&m, &g, o, d, 0, INFINITY, &val, 1,
		    collect, &h, NULL) == 0;
		for (int w = 0; w < 3; w++) {
			rec *hw = w == 0 ? &h1 : w == 1 ? &h2 : &h3;

			rec_init(hw, m.dims[0]);
			ok &= vx_macro_traverse_boxes(&m, &g, &mk, bx,
			    w == 0 ? NULL : w == 1 ? fw : bw, nbx, NULL, o, d,
			    &val, 1, collect, hw, NULL) == 0;
			ok &= hw->n == h.n && same_prefix(hw, &h, 1);
		}
		/* true lower bounds, sorted: the same */
		{
			vx_cellbox *sb = malloc(nbx * sizeof *sb);
			rec hs;

			assert_non_null(sb);
			memcpy(sb, bx, nbx * sizeof *sb);
			for (size_t i = 0; i < nbx; i++) {
				double t = vx_macro_boxes_entry(&m, &bx[i], NULL,
				    1, o, d, NULL);

				sb[i].lb = t < INFINITY ? t : 1e300;
			}
			qsort(sb, nbx, sizeof *sb, lb_cmp);
			rec_init(&hs, m.dims[0]);
			ok &= vx_macro_traverse_boxes(&m, &g, &mk, sb, NULL, nbx,
			    NULL, o, d, &val, 1, collect, &hs, NULL) == 0;
			ok &= hs.n == h.n && same_prefix(&hs, &h, 0);
			free(hs.v);
			free(sb);
		}
		/* stopped at visit k: its value, k visits */
		if (h.n > 0) {
			rec_init(&h4, m.dims[0]);
			h4.cap = 1 + irand(&s, h.n);
			ok &= vx_macro_traverse_boxes(&m, &g, &mk, bx, bw, nbx,
			    NULL, o, d, &val, 1, stop_at, &h4, NULL) == 7;
			ok &= h4.n == h4.cap && same_prefix(&h4, &h, 0);
			free(h4.v);
		}
		if (!ok)
			fprintf(stderr, "# ray %d: o %.17g %.17g %.17g d %.17g "
			    "%.17g %.17g: %d visits\n", j, o[0], o[1], o[2],
			    d[0], d[1], d[2], h.n);
		assert_true(ok);
		most = h.n > most ? h.n : most;
		free(h.v);
		free(h1.v);
		free(h2.v);
		free(h3.v);
	}
	assert_true(most > 140);   /* past the pending list, twice */
	free(bx);
	free(fw);
	free(bw);
	vx_cellmask_free(&mk);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* The visitor's nonzero value stops the walk and is returned. */
static int
stop_at_third(void *ctx, const vx_leaf_visit *v)
{
	int *k = ctx;

	(void)v;
	return ++*k == 3 ? 42 : 0;
}

static void
visitor_stops(void **state)
{
	int64_t n[3] = { 9, 2, 2 };
	double o[3] = { -1, 0.5, 0.5 }, d[3] = { 1, 0, 0 };
	int k = 0;
	vx_macro m;

	(void)state;
	unit_leaves(&m, n, 0, NULL);
	assert_int_equal(vx_macro_traverse(&m, NULL, o, d, 0, INFINITY, NULL,
	    0, stop_at_third, &k, NULL), 42);
	assert_int_equal(k, 3);
	vx_macro_free(&m);
}

/* Explicit leaves: only leaves whose stored range brackets the value are
 * visited, and the macrocells skip the rest (oracle: hand-made leaf grid
 * with one interesting leaf). */
static void
explicit_leaves(void **state)
{
	int64_t n[3] = { 16, 1, 1 };
	static const int sz[][3] = { { 4, 1, 1 } };
	float mm[32];
	double o[3] = { -1, 0.5, 0.5 }, d[3] = { 1, 0, 0 };
	float val = 3;
	vx_macro m;
	vx_err e = { 0, "" };
	vx_trav_stats st;
	rec r;

	(void)state;
	for (int k = 0; k < 16; k++) {
		mm[2 * k] = 0;
		mm[2 * k + 1] = k == 9 ? 5 : 1;
	}
	assert_int_equal(vx_macro_build_explicit(&m, n, mm, 1, sz, 1, &e), 0);
	assert_true(m.root[0] == 0 && m.root[1] == 5);
	rec_init(&r, n);
	memset(&st, 0, sizeof st);
	assert_int_equal(vx_macro_traverse(&m, NULL, o, d, 0, INFINITY, &val, 1,
	    collect, &r, &st), 0);
	assert_int_equal(r.n, 1);
	assert_int_equal(r.v[0].leaf, 9);
	assert_true(r.v[0].t0 == 10 && r.v[0].t1 == 11);
	assert_int_equal(st.macro[1], 4);   /* 4 macrocells, one entered */
	assert_int_equal(st.culled, 3);     /* leaves 8, 10, 11 */
	free(r.v);
	vx_macro_free(&m);
}

/* ---- defaults and sizes ---- */

static void
default_sizes_overhead(void **state)
{
	int sz[VX_MACRO_MAXLEV][3];
	int64_t dims[3] = { 257, 257, 129 };
	static const vx_type types[] = { VX_U8, VX_U16, VX_I16, VX_F32 };

	(void)state;
	for (size_t i = 0; i < 4; i++) {
		vx_macro m;
		vx_grid g;
		vx_err e = { 0, "" };
		double data;

		assert_int_equal(vx_macro_default_sizes(types[i],
		    VX_MACRO_DEFAULT_LEVELS, sz), 2);
		/* level-1 macrocells cover 2 KiB of samples, level 2 64^3 */
		assert_int_equal(sz[0][0] * sz[0][1] * sz[0][2] *
		    (int)vx_type_size(types[i]), 2048);
		for (int a = 0; a < 3; a++)
			assert_int_equal(sz[0][a] * sz[1][a], 64);
		assert_int_equal(vx_grid_alloc(&g, dims, types[i], NULL, &e), 0);
		assert_int_equal(vx_macro_build(&m, &g, 2, sz, 1, &e), 0);
		data = (double)(dims[0] * dims[1] * dims[2]) *
		    (double)vx_type_size(types[i]);
		assert_true((double)vx_macro_bytes(&m) / data < 0.005);
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
	assert_int_equal(vx_macro_default_sizes(VX_TYPE_UNKNOWN, 2, sz), 0);
	assert_int_equal(vx_macro_default_sizes(VX_U8, 0, sz), 0);
}

static void
parse_sizes(void **state)
{
	int sz[VX_MACRO_MAXLEV][3];
	vx_err e = { 0, "" };
	static const char *bad[] = { "", "8", "8x8", "8x8x8,", ",8x8x8",
	    "8x8x0", "8x8x2000", "8x8x8 4x4x4", "8x8x8,,4x4x4", "-1x2x2",
	    "1x1x1,1x1x1,1x1x1,1x1x1,1x1x1,1x1x1,1x1x1", "8x8x8x" };

	(void)state;
	assert_int_equal(vx_macro_parse_sizes("8x8x8", sz, &e), 1);
	assert_int_equal(vx_macro_parse_sizes("16x8x4,3x5x7", sz, &e), 2);
	assert_true(sz[0][0] == 16 && sz[0][2] == 4 && sz[1][1] == 5);
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		vx_err_clear(&e);
		assert_int_equal(vx_macro_parse_sizes(bad[i], sz, &e), -1);
		assert_int_equal(e.code, VX_EUSAGE);
	}
}

/* ---- the MCEL chunk ---- */

static void
chunk_roundtrip_and_staleness(void **state)
{
	int64_t dims[3] = { 10, 7, 5 };
	static const int sz[][3] = { { 3, 3, 2 }, { 2, 2, 2 } };
	vx_grid g, gb, g2;
	vx_macro m, m2;
	vx_chunk c;
	vx_stream s;
	vx_err e = { 0, "" };
	int status;
	long idx;

	(void)state;
	rand_grid(&g, dims, VX_I16, NULL, 5, 0);
	assert_int_equal(vx_macro_build(&m, &g, 2, sz, 1, &e), 0);
	for (int z = 0; z < 2; z++) {
		memset(&c, 0, sizeof c);
		assert_int_equal(vx_macro_to_chunk(&m, z ? 6 : 0, &c, &e), 0);
		assert_string_equal(c.type, "MCEL");
		assert_int_equal(vx_macro_from_chunk(&m2, &c, &e), 0);
		assert_int_equal(m2.nlev, 2);
		assert_memory_equal(m2.dims, m.dims, sizeof m.dims);
		assert_memory_equal(m2.size, m.size, sizeof m.size);
		assert_memory_equal(m2.mm[1], m.mm[1], vx_macro_bytes(&m) -
		    2 * sizeof(float) * 2);
		assert_true(m2.root[0] == m.root[0] && m2.root[1] == m.root[1]);
		assert_int_equal(m2.vcrc, m.vcrc);
		assert_true(vx_macro_matches(&m2, &g, NULL));
		vx_macro_free(&m2);
		vx_chunk_free(&c);
	}
	/* the CRC does not depend on the layout: a bricked copy matches */
	assert_int_equal(vx_grid_relayout(&gb, &g, "bricked 4x4x2", &e), 0);
	assert_int_equal(vx_macro_grid_crc(&gb), m.vcrc);
	assert_true(vx_macro_matches(&m, &gb, NULL));
	/* one changed sample makes it stale; another name is absent */
	vx_stream_init(&s);
	memset(&c, 0, sizeof c);
	assert_int_equal(vx_macro_to_chunk(&m, 0, &c, &e), 0);
	assert_int_equal(vx_stream_append(&s, &c, &e), 0);
	assert_int_equal(vx_macro_from_stream(&m2, &s, &gb, -1, &status, &idx, &e),
	    0);
	assert_int_equal(status, VX_MACRO_LOADED);
	assert_int_equal(idx, 0);
	vx_macro_free(&m2);
	assert_int_equal(vx_grid_relayout(&g2, &g, "linear", &e), 0);
	vx_grid_set(&g2, 3, 3, 3, vx_grid_get(&g2, 3, 3, 3) + 1);
	assert_int_equal(vx_macro_from_stream(&m2, &s, &g2, -1, &status, &idx, &e),
	    0);
	assert_int_equal(status, VX_MACRO_STALE);
	snprintf(g2.name, sizeof g2.name, "other");
	assert_int_equal(vx_macro_from_stream(&m2, &s, &g2, -1, &status, &idx, &e),
	    0);
	assert_int_equal(status, VX_MACRO_ABSENT);
	assert_int_equal(idx, -1);
	vx_stream_free(&s);
	vx_macro_free(&m);
	vx_grid_free(&g);
	vx_grid_free(&gb);
	vx_grid_free(&g2);
}

/* The MCEL chunk's volume-chunk-crc32 names the VOLM chunk's bytes: a
 * reader holding that very chunk (its CRC read with it) takes the match
 * without the pass over the samples; otherwise the sample CRC decides.
 * Oracle for which path was taken: an MCEL whose volume-crc32 is wrong
 * loads on the fast path only, and one whose volume-chunk-crc32 is wrong
 * still loads through the samples. */
static void
chunk_crc_fast_path(void **state)
{
	int64_t dims[3] = { 9, 6, 5 };
	static const int sz[][3] = { { 4, 2, 2 } };
	vx_grid g, gv;
	vx_macro m, m2;
	vx_chunk c;
	vx_stream s;
	vx_err e = { 0, "" };
	int status, k;
	long idx, gi;
	uint32_t vc;

	(void)state;
	rand_grid(&g, dims, VX_U16, "bricked 2x2x2", 11, 0);
	assert_int_equal(vx_macro_build(&m, &g, 1, sz, 1, &e), 0);
	assert_int_equal(m.has_vchunk_crc, 0);
	vx_stream_init(&s);
	assert_int_equal(vx_grid_to_chunk(&g, 0, &c, &e), 0);
	assert_int_equal(vx_stream_append(&s, &c, &e), 0);
	/* as read: the chunk's CRC known */
	vc = vx_chunk_crc(s.chunk[0].type, s.chunk[0].data, s.chunk[0].len);
	s.chunk[0].crc = vc;
	s.chunk[0].crc_known = 1;
	assert_int_equal(vx_grid_view_stream(&gv, &s, NULL, &gi, &e), 0);
	assert_int_equal(gi, 0);
	for (k = 0; k < 6; k++) {
		/* k: 0 right keys; 1 wrong volume-crc32; 2 wrong chunk CRC;
		 * 3 like 1 without src; 4 like 1 with the CRC not known;
		 * 5 like 1, src naming the MCEL chunk */
		static const int want[] = { VX_MACRO_LOADED, VX_MACRO_LOADED,
		    VX_MACRO_LOADED, VX_MACRO_STALE, VX_MACRO_STALE,
		    VX_MACRO_STALE };
		long src = k == 3 ? -1 : k == 5 ? 1 : gi;

		m.vchunk_crc = k == 2 ? vc ^ 0x10u : vc;
		m.has_vchunk_crc = 1;
		if (k == 1)
			m.vcrc ^= 1;
		memset(&c, 0, sizeof c);
		assert_int_equal(vx_macro_to_chunk(&m, 0, &c, &e), 0);
		if (k == 1)
			m.vcrc ^= 1;
		if (k == 0) {
			/* the key round-trips */
			assert_int_equal(vx_macro_from_chunk(&m2, &c, &e), 0);
			assert_int_equal(m2.has_vchunk_crc, 1);
			assert_int_equal(m2.vchunk_crc, vc);
			vx_macro_free(&m2);
		}
		if (s.n > 1)
			vx_stream_replace(&s, 1, &c);
		else
			assert_int_equal(vx_stream_append(&s, &c, &e), 0);
		if (k >= 3) {   /* the tampered MCEL of case 1 */
			memset(&c, 0, sizeof c);
			m.vcrc ^= 1;
			assert_int_equal(vx_macro_to_chunk(&m, 0, &c, &e), 0);
			m.vcrc ^= 1;
			vx_stream_replace(&s, 1, &c);
		}
		s.chunk[0].crc_known = k != 4;
		assert_int_equal(vx_macro_from_stream(&m2, &s, &gv, src, &status,
		    &idx, &e), 0);
		if (status != want[k])
			fail_msg("case %d: status %d, want %d", k, status,
			    want[k]);
		assert_int_equal(idx, 1);
		if (status == VX_MACRO_LOADED)
			assert_memory_equal(m2.mm[1], m.mm[1], 2 * sizeof(float) *
			    (size_t)(m.dims[1][0] * m.dims[1][1] * m.dims[1][2]));
		vx_macro_free(&m2);
	}
	/* the other checks still run on the fast path: another name is
	 * absent, and the key's value is checked */
	snprintf(gv.name, sizeof gv.name, "other");
	assert_int_equal(vx_macro_from_stream(&m2, &s, &gv, gi, &status, &idx,
	    &e), 0);
	assert_int_equal(status, VX_MACRO_ABSENT);
	vx_grid_free(&gv);
	vx_stream_free(&s);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* Explicit leaves survive the chunk too (level 0 is stored). */
static void
chunk_explicit(void **state)
{
	int64_t n[3] = { 5, 3, 2 };
	static const int sz[][3] = { { 2, 2, 2 } };
	vx_macro m, m2;
	vx_chunk c;
	vx_err e = { 0, "" };

	(void)state;
	unit_leaves(&m, n, 1, sz);
	memset(&c, 0, sizeof c);
	assert_int_equal(vx_macro_to_chunk(&m, 0, &c, &e), 0);
	assert_int_equal(vx_macro_from_chunk(&m2, &c, &e), 0);
	assert_int_equal(m2.explicit_leaves, 1);
	assert_memory_equal(m2.mm[0], m.mm[0], vx_macro_bytes(&m));
	vx_chunk_free(&c);
	vx_macro_free(&m);
	vx_macro_free(&m2);
}

/* Malformed MCEL chunks: each is refused with VX_EDATA and a message naming
 * what is wrong, before any allocation on the header's word. */
static void
chunk_errors(void **state)
{
	static const struct { const char *hdr; const char *msg; size_t body; } t[] = {
		{ "levels: 1\n", "leaves", 0 },
		{ "leaves: cells\n", "leaf-dims", 0 },
		{ "leaves: cells\nleaf-dims: 1 1 1\n", "levels", 0 },
		{ "leaves: nodes\nlevels: 0\n", "leaves", 0 },
		{ "leaves: explicit\nlevels: 7\nsizes:\nleaf-dims: 2 2 2\n",
		  "levels", 0 },
		{ "leaves: explicit\nlevels: 1\nsizes: 2x2\nleaf-dims: 2 2 2\n",
		  "sizes", 0 },
		{ "leaves: explicit\nlevels: 1\nsizes: 2x2x2\nleaf-dims: 2 2 2\n"
		  "dims-1: 2 1 1\nrange: 0 1\n", "dims-1", 0 },
		{ "leaves: explicit\nlevels: 1\nsizes: 2x2x2\nleaf-dims: 2 2 2\n"
		  "dims-1: 1 1 1\nrange: 0 1\nencoding: raw\n", "body", 8 },
		{ "leaves: explicit\nlevels: 0\nsizes:\n"
		  "leaf-dims: 1048576 1048576 1048576\nrange: 0 1\n"
		  "encoding: zlib\n", "zlib", 8 },
		{ "leaves: explicit\nlevels: 0\nsizes:\n"
		  "leaf-dims: 2000000 1 1\nrange: 0 1\n", "leaf-dims", 0 },
		{ "leaves: explicit\nlevels: 1\nsizes: 0x2x2\nleaf-dims: 2 2 2\n"
		  "dims-1: 1 1 1\nrange: 0 1\n", "sizes", 0 },
		{ "leaves: cells\nlevels: 0\nsizes:\nleaf-dims: 1 1 1\n"
		  "volume: v\nvolume-dims: 3 2 2\nvolume-type: u8\n"
		  "volume-crc32: 00000000\nrange: 0 1\n", "volume-dims", 0 },
		{ "leaves: cells\nlevels: 0\nsizes:\nleaf-dims: 1 1 1\n"
		  "volume: v\nvolume-dims: 2 2 2\nvolume-type: u9\n"
		  "volume-crc32: 00000000\nrange: 0 1\n", "volume-type", 0 },
		{ "leaves: cells\nlevels: 0\nsizes:\nleaf-dims: 1 1 1\n"
		  "volume: v\nvolume-dims: 2 2 2\nvolume-type: u8\n"
		  "volume-crc32: 0xabcdef\nrange: 0 1\n", "crc32", 0 },
		{ "leaves: cells\nlevels: 0\nsizes:\nleaf-dims: 1 1 1\n"
		  "volume: v\nvolume-dims: 2 2 2\nvolume-type: u8\n"
		  "volume-crc32: 00000000\nrange: 1 0\n", "range", 0 },
		{ "leaves: cells\nlevels: 0\nsizes:\nleaf-dims: 1 1 1\n"
		  "volume: v\nvolume-dims: 2 2 2\nvolume-type: u8\n"
		  "volume-crc32: 00000000\nvolume-chunk-crc32: 0ABCDEF0\n"
		  "range: 0 1\n", "volume-chunk-crc32", 0 },
		{ "leaves: explicit\nlevels: 0\nsizes:\nleaf-dims: 1 1 1\n"
		  "range: 0 1\n", "body", 0 },
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		size_t hl = strlen(t[i].hdr);
		vx_chunk c;
		vx_macro m;
		vx_err e = { 0, "" };

		memcpy(c.type, "MCEL", 5);
		c.offset = 0;
		c.len = hl + 1 + t[i].body;
		c.data = calloc(c.len, 1);
		memcpy(c.data, t[i].hdr, hl);
		c.data[hl] = '\n';
		assert_int_equal(vx_macro_from_chunk(&m, &c, &e), VX_EDATA);
		if (strstr(e.msg, t[i].msg) == NULL)
			print_message("case %zu: '%s'\n", i, e.msg);
		assert_non_null(strstr(e.msg, t[i].msg));
		assert_non_null(strstr(e.msg, "macrocells"));
		vx_macro_free(&m);
		free(c.data);
	}
}

/* A volume with a dimension of 1 has no cells: an empty hierarchy that
 * visits nothing, and that survives the chunk. */
static void
degenerate_volume(void **state)
{
	int64_t dims[3] = { 1, 5, 5 };
	int sz[2][3];
	double o[3] = { 0, 0.5, -1 }, d[3] = { 0, 0, 1 };
	vx_grid g;
	vx_macro m, m2;
	vx_chunk c;
	vx_err e = { 0, "" };
	rec r;

	(void)state;
	vx_macro_default_sizes(VX_U8, 2, sz);
	assert_int_equal(vx_grid_alloc(&g, dims, VX_U8, NULL, &e), 0);
	assert_int_equal(vx_macro_build(&m, &g, 2, sz, 1, &e), 0);
	assert_int_equal(vx_macro_bytes(&m), 0);
	r.cap = 4;
	r.n = 0;
	r.v = calloc(4, sizeof *r.v);
	assert_int_equal(vx_macro_traverse(&m, &g, o, d, 0, INFINITY, NULL, 0,
	    collect, &r, NULL), 0);
	assert_int_equal(vx_macro_traverse_flat(NULL, &g, o, d, 0, INFINITY,
	    NULL, 0, collect, &r, NULL), 0);
	assert_int_equal(r.n, 0);
	memset(&c, 0, sizeof c);
	assert_int_equal(vx_macro_to_chunk(&m, 0, &c, &e), 0);
	assert_int_equal(vx_macro_from_chunk(&m2, &c, &e), 0);
	assert_true(vx_macro_matches(&m2, &g, NULL));
	free(r.v);
	vx_chunk_free(&c);
	vx_macro_free(&m);
	vx_macro_free(&m2);
	vx_grid_free(&g);
}

/* A grid whose cells are not the hierarchy's leaves is refused (-1) and
 * nothing is visited. */
static void
mismatched_grid(void **state)
{
	int64_t d1[3] = { 5, 5, 5 }, d2[3] = { 5, 6, 5 };
	double o[3] = { 0.5, 0.5, -1 }, d[3] = { 0, 0, 1 };
	vx_grid g1, g2;
	vx_macro m;
	vx_err e = { 0, "" };
	rec r;

	(void)state;
	assert_int_equal(vx_grid_alloc(&g1, d1, VX_U8, NULL, &e), 0);
	assert_int_equal(vx_grid_alloc(&g2, d2, VX_U8, NULL, &e), 0);
	assert_int_equal(vx_macro_build(&m, &g1, 0, NULL, 1, &e), 0);
	rec_init(&r, d2);
	assert_int_equal(vx_macro_traverse(&m, &g2, o, d, 0, INFINITY, NULL, 0,
	    collect, &r, NULL), -1);
	assert_int_equal(vx_macro_traverse_flat(&m, &g2, o, d, 0, INFINITY,
	    NULL, 0, collect, &r, NULL), -1);
	assert_int_equal(r.n, 0);
	assert_false(vx_macro_matches(&m, &g2, NULL));
	assert_true(vx_macro_matches(&m, &g1, NULL));
	free(r.v);
	vx_macro_free(&m);
	vx_grid_free(&g1);
	vx_grid_free(&g2);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(walk_hard_cases),
		cmocka_unit_test(walk_nonfinite_input),
		cmocka_unit_test(walk_random_oracle),
		cmocka_unit_test(build_matches_brute_force),
		cmocka_unit_test(nonfinite_policy),
		cmocka_unit_test(hierarchy_equals_filtered_flat),
		cmocka_unit_test(cellmask_bits_brute_force),
		cmocka_unit_test(cellmask_chunks_brute_force),
		cmocka_unit_test(cellmask_equals_plain_walk),
		cmocka_unit_test(cellmask_boxes_cover_bits),
		cmocka_unit_test(boxes_entry_keeps_visits),
		cmocka_unit_test(boxes_walk_many_boxes),
		cmocka_unit_test(visitor_stops),
		cmocka_unit_test(explicit_leaves),
		cmocka_unit_test(default_sizes_overhead),
		cmocka_unit_test(parse_sizes),
		cmocka_unit_test(chunk_roundtrip_and_staleness),
		cmocka_unit_test(chunk_crc_fast_path),
		cmocka_unit_test(chunk_explicit),
		cmocka_unit_test(chunk_errors),
		cmocka_unit_test(degenerate_volume),
		cmocka_unit_test(mismatched_grid),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
