/* test_tetmesh.c: tet meshes: synthetic splits, the watertight ray/tet
 * isosurface test (planarity, no holes and no double hits through shared
 * faces, edges and vertices, slivers and flat tets), the TETM chunk, the
 * leaf grid, and the VTK and gmsh importers.  Each case names its oracle. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>
#include <unistd.h>
#include <zlib.h>

#include "vx_tetimport.h"
#include "vx_tetleaf.h"

/* ---- helpers ---- */

static uint64_t
mix64(uint64_t x)
{
	x += 0x9e3779b97f4a7c15ull;
	x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
	x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
	return x ^ (x >> 31);
}

/* uniform in [0, 1) from (seed, i) */
static double
u01(uint64_t seed, uint64_t i)
{
	return (double)(mix64(seed * 0x100000001b3ull + i) >> 11) * 0x1p-53;
}

typedef struct lin { double a[3], b; } lin;

static double
lin_fn(const double p[3], void *ctx)
{
	const lin *l = ctx;
	return l->a[0] * p[0] + l->a[1] * p[1] + l->a[2] * p[2] + l->b;
}

/* 2 - |p - c|^2: a closed isosurface around c for iso < 2 */
static double
bowl_fn(const double p[3], void *ctx)
{
	const double *c = ctx;
	double s = 0;
	for (int a = 0; a < 3; a++)
		s += (p[a] - c[a]) * (p[a] - c[a]);
	return 2 - s;
}

typedef struct xing { double t; int enter; uint32_t tet; } xing;

/* By t; at equal t (a surface touching iso at a point, met from outside:
 * sign(0) = + makes that point inside) the entry first. */
static int
xing_cmp(const void *a, const void *b)
{
	const xing *x = a, *y = b;
	if (x->t != y->t)
		return (x->t > y->t) - (x->t < y->t);
	return y->enter - x->enter;
}

/* All crossings of the whole line o + t d with iso, tet by tet (no
 * acceleration), sorted by t.  Returns the count; at most cap stored. */
static size_t
all_crossings(const vx_tetmesh *m, const double o[3], const double d[3],
    double iso, xing *x, size_t cap)
{
	vx_tetray r;
	size_t n = 0;

	vx_tetray_init(&r, o, d);
	for (uint32_t t = 0; t < m->ntet; t++) {
		vx_tethit h;
		if (!vx_tet_nearest(m, &t, 1, &r, &iso, 1, -1e300, 1e300, &h))
			continue;
		assert_true(isfinite(h.t));
		for (int a = 0; a < 3; a++)
			assert_true(isfinite(h.n[a]));
		if (n < cap) {
			x[n].t = h.t;
			x[n].enter = h.enter;
			x[n].tet = t;
		}
		n++;
	}
	assert_true(n <= cap);
	qsort(x, n, sizeof *x, xing_cmp);
	return n;
}

/* Oracle (parity) for the crossings x[0..n) of a line that starts and ends
 * outside (f < iso): along t they alternate entry, exit, entry, ..., and
 * their number is even.  Crossings within 1e-12 of each other form a
 * cluster whose order is rounding's: a ray through a vertex or an edge at
 * an isovalue equal to the value there may cross back and forth there.
 * Each cluster must then leave the state unchanged or toggle it the right
 * way. */
static void
check_alternation(const xing *x, size_t n)
{
	int inside = 0;

	assert_int_equal(n % 2, 0);
	for (size_t i = 0; i < n;) {
		size_t j = i;
		int delta = 0;
		while (j < n && x[j].t - x[i].t <= 1e-12 * (1 + fabs(x[i].t)))
			delta += x[j++].enter ? 1 : -1;
		if (inside)
			assert_true(delta == 0 || delta == -1);
		else
			assert_true(delta == 0 || delta == 1);
		inside ^= delta != 0;
		i = j;
	}
	assert_int_equal(inside, 0);
}

/* ---- synthetic meshes ---- */

/* Oracle: the split covers each cell exactly: tet volumes are positive and
 * sum to the box volume; every interior face is shared by exactly two tets
 * and boundary faces number 2 per boundary cell face (face-conforming). */
static int
face_cmp(const void *a, const void *b)
{
	const uint32_t *x = a, *y = b;
	for (int i = 0; i < 3; i++)
		if (x[i] != y[i])
			return x[i] < y[i] ? -1 : 1;
	return 0;
}

static void
synth_conforming(void **state)
{
	static const int64_t nc[][3] = { { 1, 1, 1 }, { 3, 2, 4 }, { 2, 5, 1 } };
	double lo[3] = { -1, 0, 2 }, hi[3] = { 2, 1, 3.5 };
	lin l = { { 1, 2, 3 }, 0 };

	(void)state;
	for (size_t c = 0; c < sizeof nc / sizeof nc[0]; c++)
		for (int split = 5; split <= 6; split++) {
			vx_tetmesh m;
			vx_err e = { 0, "" };
			assert_int_equal(vx_tetsynth_grid(&m, nc[c], lo, hi, split,
			    lin_fn, &l, &e), 0);
			size_t ncell = (size_t)(nc[c][0] * nc[c][1] * nc[c][2]);
			assert_int_equal(m.ntet, ncell * (size_t)split);
			assert_int_equal(m.npoint, (size_t)((nc[c][0] + 1) *
			    (nc[c][1] + 1) * (nc[c][2] + 1)));
			double vol = 0;
			for (size_t t = 0; t < m.ntet; t++) {
				double v = vx_tetmesh_volume(&m, t);
				assert_true(v > 0);
				assert_false(vx_tetmesh_degenerate(&m, t));
				vol += v;
			}
			assert_true(fabs(vol - 3 * 1 * 1.5) < 1e-12);
			uint32_t *f = malloc(m.ntet * 4 * 3 * sizeof *f);
			for (size_t t = 0; t < m.ntet; t++)
				for (int k = 0; k < 4; k++) {
					uint32_t *q = f + 3 * (4 * t + (size_t)k), s;
					int n = 0;
					for (int i = 0; i < 4; i++)
						if (i != k)
							q[n++] = m.tet[4 * t + (size_t)i];
					for (int i = 0; i < 3; i++)
						for (int j = 0; j < 2 - i; j++)
							if (q[j] > q[j + 1]) {
								s = q[j];
								q[j] = q[j + 1];
								q[j + 1] = s;
							}
				}
			qsort(f, 4 * m.ntet, 3 * sizeof *f, face_cmp);
			size_t nb = 0;
			for (size_t i = 0; i < 4 * m.ntet;) {
				size_t j = i + 1;
				while (j < 4 * m.ntet && face_cmp(f + 3 * i,
				    f + 3 * j) == 0)
					j++;
				assert_true(j - i <= 2);
				nb += j - i == 1;
				i = j;
			}
			size_t bf = 2 * (size_t)(nc[c][0] * nc[c][1] +
			    nc[c][1] * nc[c][2] + nc[c][0] * nc[c][2]);
			assert_int_equal(nb, 2 * bf);
			/* values are the function at the vertices */
			for (size_t p = 0; p < m.npoint; p++)
				assert_true(m.val[p] ==
				    (float)lin_fn(m.pts + 3 * p, &l));
			free(f);
			vx_tetmesh_free(&m);
		}
}

/* Oracle: vx_tetsynth_from_grid puts sample (i,j,k) at origin + ijk *
 * spacing with the sample's value, in the same lattice order. */
static void
synth_from_grid(void **state)
{
	int64_t d[3] = { 4, 3, 5 };
	vx_grid g;
	vx_tetmesh m;
	vx_err e = { 0, "" };

	(void)state;
	assert_int_equal(vx_grid_alloc(&g, d, VX_I16, "bricked 2x2x2", &e), 0);
	snprintf(g.name, sizeof g.name, "%s", "q5");
	for (int a = 0; a < 3; a++) {
		g.spacing[a] = 0.5 + a;
		g.origin[a] = -1.0 * a;
	}
	for (int64_t k = 0; k < d[2]; k++)
		for (int64_t j = 0; j < d[1]; j++)
			for (int64_t i = 0; i < d[0]; i++)
				vx_grid_set(&g, i, j, k, (double)(i * 7 - j * 3 +
				    k * 11));
	assert_int_equal(vx_tetsynth_from_grid(&m, &g, 5, &e), 0);
	assert_string_equal(m.scalar, "q5");
	assert_int_equal(m.ntet, 3 * 2 * 4 * 5);
	for (int64_t k = 0; k < d[2]; k++)
		for (int64_t j = 0; j < d[1]; j++)
			for (int64_t i = 0; i < d[0]; i++) {
				size_t p = (size_t)(i + 4 * (j + 3 * k));
				assert_true(m.val[p] == vx_grid_get(&g, i, j, k));
				assert_true(m.pts[3 * p] == 0.5 * (double)i);
				assert_true(m.pts[3 * p + 1] == -1 + 1.5 * (double)j);
				assert_true(m.pts[3 * p + 2] == -2 + 2.5 * (double)k);
			}
	assert_true(m.has_range && m.vmin == -6 && m.vmax == 3 * 7 + 4 * 11);
	vx_tetmesh_free(&m);
	vx_grid_free(&g);
}

/* ---- intersection ---- */

/* Oracle: a linear field is linear in every tet, so the isosurface is the
 * plane a.p + b = iso: every hit satisfies it to 1e-12, its normal is
 * a / |a|, and a ray hits (exactly once, over all tets) iff the analytic
 * ray/plane point lies inside the box.  Vertex values are dyadic, so float
 * storage keeps the field exactly linear. */
static void
linear_planar(void **state)
{
	static const int64_t nc[][3] = { { 1, 1, 1 }, { 4, 4, 4 }, { 2, 8, 4 } };
	lin l = { { 0.5, -1.25, 2 }, 0.125 };
	double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
	double al = sqrt(0.25 + 1.5625 + 4);

	(void)state;
	for (size_t c = 0; c < sizeof nc / sizeof nc[0]; c++)
		for (int split = 5; split <= 6; split++) {
			vx_tetmesh m;
			vx_err e = { 0, "" };
			assert_int_equal(vx_tetsynth_grid(&m, nc[c], lo, hi, split,
			    lin_fn, &l, &e), 0);
			for (uint64_t r = 0; r < 300; r++) {
				double o[3], d[3], iso = -1 + 2.5 * u01(1, r);
				for (int a = 0; a < 3; a++) {
					double tgt = u01(2 + (uint64_t)a, r);
					o[a] = 3 * u01(5 + (uint64_t)a, r) - 1;
					if (r % 3 == 0)
						o[a] = a == 2 ? -1 : 1.5 * u01(8, r);
					d[a] = tgt - o[a];
				}
				double ad = l.a[0] * d[0] + l.a[1] * d[1] + l.a[2] * d[2];
				double ao = l.a[0] * o[0] + l.a[1] * o[1] + l.a[2] * o[2];
				double ts = (iso - l.b - ao) / ad, ps[3];
				int inside = 1, margin = 1;
				for (int a = 0; a < 3; a++) {
					ps[a] = o[a] + ts * d[a];
					inside &= ps[a] >= 0 && ps[a] <= 1;
					margin &= ps[a] > 1e-9 && ps[a] < 1 - 1e-9;
				}
				xing x[8];
				size_t n = all_crossings(&m, o, d, iso, x, 8);
				if (inside && margin)
					assert_int_equal(n, 1);
				if (!inside)
					assert_int_equal(n, 0);
				for (size_t i = 0; i < n; i++) {
					double p[3], f;
					for (int a = 0; a < 3; a++)
						p[a] = o[a] + x[i].t * d[a];
					f = lin_fn(p, &l);
					assert_true(fabs(f - iso) < 1e-12);
					assert_int_equal(x[i].enter, ad > 0);
				}
				if (n == 1) {
					double t, nn[3];
					assert_int_equal(vx_tet_intersect(&m, x[0].tet,
					    o, d, iso, -1e300, 1e300, &t, nn), 1);
					assert_true(t == x[0].t);
					for (int a = 0; a < 3; a++)
						assert_true(fabs(nn[a] - l.a[a] / al) <
						    1e-12);
					/* [tmin, tmax) is honoured, half-open */
					assert_int_equal(vx_tet_intersect(&m, x[0].tet,
					    o, d, iso, t, 1e300, &t, NULL), 1);
					assert_int_equal(vx_tet_intersect(&m, x[0].tet,
					    o, d, iso, -1e300, x[0].t, &t, NULL), 0);
				}
			}
			vx_tetmesh_free(&m);
		}
}

/* Rays aimed exactly at shared vertices, edges and faces of a Kuhn cube:
 * directions with power-of-two ratios and dyadic origins, so lattice points
 * on the ray project exactly onto it in ray space (true degeneracies).
 * Oracle: over the 6 tets, a linear field crossing the cube's interior on
 * the ray is reported exactly once (no hole, no double hit), on the plane. */
static void
kuhn_exact_aim(void **state)
{
	static const double dirs[][3] = {
		{ 1, 1, 1 }, { -1, -1, -1 }, { 1, 1, 0 }, { 0, 0, 1 },
		{ 1, 0, 0 }, { 0, -1, 0 }, { 1, 2, 4 }, { -2, 1, 0.5 },
		{ 1, -1, 1 }, { 0.25, 1, 1 },
	};
	/* target points: the centre (on the main diagonal shared by all six
	 * tets), face centres, edge midpoints, interior points of face and
	 * interior diagonals */
	static const double tgt[][3] = {
		{ 0.5, 0.5, 0.5 }, { 0.25, 0.25, 0.25 }, { 0.75, 0.75, 0.75 },
		{ 0.5, 0.5, 0 }, { 0.5, 0.25, 0.25 }, { 0.25, 0.5, 0.75 },
		{ 0.5, 0, 0.5 }, { 0.75, 0.5, 0.25 }, { 0.5, 0.25, 0.5 },
		{ 0.125, 0.25, 0.75 },
	};
	lin ls[] = {
		{ { 1, 1, 1 }, 0 }, { { 1, -2, 0.5 }, 0.25 }, { { 0, 0, 1 }, 0 },
		{ { 4, 1, -1 }, 0 },
	};
	double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };

	(void)state;
	for (size_t li = 0; li < sizeof ls / sizeof ls[0]; li++) {
		vx_tetmesh m;
		vx_err e = { 0, "" };
		assert_int_equal(vx_tetsynth_cube(&m, lo, hi, lin_fn, &ls[li], &e),
		    0);
		for (size_t di = 0; di < sizeof dirs / sizeof dirs[0]; di++)
			for (size_t ti = 0; ti < sizeof tgt / sizeof tgt[0]; ti++) {
				const double *d = dirs[di];
				double o[3], iso = lin_fn(tgt[ti], &ls[li]);
				for (int a = 0; a < 3; a++)
					o[a] = tgt[ti][a] - 4 * d[a];
				/* does the ray pass through the open cube near
				 * the target?  (then the plane point is the
				 * target, strictly inside or on the boundary) */
				int interior = 1;
				for (int a = 0; a < 3; a++)
					interior &= tgt[ti][a] > 0 && tgt[ti][a] < 1;
				double ad = 0;
				for (int a = 0; a < 3; a++)
					ad += ls[li].a[a] * d[a];
				xing x[8];
				size_t n = all_crossings(&m, o, d, iso, x, 8);
				if (interior && ad != 0) {
					assert_int_equal(n, 1);
					assert_true(fabs(x[0].t - 4) < 1e-12);
				}
				if (ad == 0)
					assert_int_equal(n, 0);
				assert_true(n <= 1);
			}
		vx_tetmesh_free(&m);
	}
}

/* Closed isosurface of 2 - |p - c|^2 over a split grid; rays through lattice
 * vertices, along grid lines and cell diagonals (exactly representable),
 * and through edge midpoints.  Oracle (parity, check_alternation): the
 * line starts and ends outside (f < iso at the mesh boundary), so over all
 * tets the crossings alternate entry/exit along t and their number is even;
 * a line passing within 0.5 of the centre crosses at least twice.
 * Isovalues include values equal to vertex values (sign(0) = + policy). */
static void
closed_surface_parity(void **state)
{
	static const double dirs[][3] = {
		{ 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 1, 1 }, { 1, 1, 0 },
		{ 1, -1, 1 }, { 1, 2, 0 }, { 2, 1, 4 }, { -1, 0.5, 0.25 },
		{ 0, 1, -1 },
	};
	static const double isos[] = { 0.8, 1.0, 1.25, 0.5 };
	double c[3] = { 0, 0, 0 }, lo[3] = { -1.5, -1.5, -1.5 };
	double hi[3] = { 1.5, 1.5, 1.5 };
	int64_t nc[3] = { 6, 6, 6 };

	(void)state;
	for (int split = 5; split <= 6; split++) {
		vx_tetmesh m;
		vx_err e = { 0, "" };
		assert_int_equal(vx_tetsynth_grid(&m, nc, lo, hi, split, bowl_fn,
		    c, &e), 0);
		size_t total = 0;
		for (size_t ii = 0; ii < sizeof isos / sizeof isos[0]; ii++)
			for (size_t di = 0; di < sizeof dirs / sizeof dirs[0]; di++)
				for (int pi = 0; pi < 27; pi++) {
					/* through lattice points (half-steps) near the
					 * centre: vertices, edge midpoints, face and cell
					 * centres */
					double p[3] = { 0.25 * (pi % 3 - 1),
					    0.25 * ((pi / 3) % 3 - 1),
					    0.25 * (pi / 9 - 1) };
					double o[3], dist2 = 0, dd = 0, pd = 0;
					const double *d = dirs[di];
					for (int a = 0; a < 3; a++) {
						o[a] = p[a] - 8 * d[a];
						dd += d[a] * d[a];
						pd += p[a] * d[a];
					}
					for (int a = 0; a < 3; a++) {
						double q = p[a] - pd / dd * d[a];
						dist2 += q * q;
					}
					xing x[64];
					size_t n = all_crossings(&m, o, d, isos[ii], x,
					    64);
					check_alternation(x, n);
					if (dist2 < 0.25 && isos[ii] < 1.5)
						assert_true(n >= 2);
					total += n;
				}
		assert_true(total > 0);
		vx_tetmesh_free(&m);
	}
}

/* Same parity oracle with random rays through a jittered split grid (the
 * generic case) and rays aimed at random vertices of it (exact vertex
 * hits in general position). */
static void
jittered_parity(void **state)
{
	double c[3] = { 0.1, -0.05, 0.02 }, lo[3] = { -1.5, -1.5, -1.5 };
	double hi[3] = { 1.5, 1.5, 1.5 };
	int64_t nc[3] = { 5, 6, 5 };

	(void)state;
	for (int split = 5; split <= 6; split++) {
		vx_tetmesh m;
		vx_err e = { 0, "" };
		assert_int_equal(vx_tetsynth_grid(&m, nc, lo, hi, split, bowl_fn,
		    c, &e), 0);
		/* jitter interior vertices by up to 0.15 cells */
		for (size_t p = 0; p < m.npoint; p++) {
			int interior = 1;
			for (int a = 0; a < 3; a++)
				interior &= m.pts[3 * p + a] > lo[a] &&
				    m.pts[3 * p + a] < hi[a];
			if (!interior)
				continue;
			for (int a = 0; a < 3; a++)
				m.pts[3 * p + a] += 0.03 *
				    (2 * u01(20 + (uint64_t)a, p) - 1);
			m.val[p] = (float)bowl_fn(m.pts + 3 * p, c);
		}
		assert_int_equal(vx_tetmesh_validate(&m, &e), 0);
		for (size_t t = 0; t < m.ntet; t++)
			assert_true(vx_tetmesh_volume(&m, t) > 0);
		for (uint64_t r = 0; r < 200; r++) {
			double o[3], d[3], p[3];
			size_t v = (size_t)(u01(30, r) * (double)m.npoint);
			for (int a = 0; a < 3; a++) {
				p[a] = r % 2 ? m.pts[3 * v + a] :
				    2 * u01(31 + (uint64_t)a, r) - 1;
				d[a] = 2 * u01(40 + (uint64_t)a, r) - 1;
				o[a] = p[a] - 4 * d[a];
			}
			xing x[64];
			size_t n = all_crossings(&m, o, d, 0.8, x, 64);
			check_alternation(x, n);
		}
		vx_tetmesh_free(&m);
	}
}

/* Oracle (chain): on a jittered box mesh whose tets list their vertices in
 * shuffled orders, the segments of a line through the box join end to end:
 * every segment end (t, f) other than the line's entry into and exit from
 * the box is shared, bit for bit, with exactly one other tet's segment. */
static int
tf_cmp(const void *a, const void *b)
{
	const double *x = a, *y = b;
	if (x[0] != y[0])
		return x[0] < y[0] ? -1 : 1;
	return (x[1] > y[1]) - (x[1] < y[1]);
}

static void
chain_bit_identical(void **state)
{
	double c[3] = { 0.1, 0.2, 0.3 }, lo[3] = { -1, -1, -1 }, hi[3] = { 1, 1, 1 };
	int64_t nc[3] = { 4, 4, 4 };

	(void)state;
	for (int split = 5; split <= 6; split++) {
		vx_tetmesh m;
		vx_err e = { 0, "" };
		assert_int_equal(vx_tetsynth_grid(&m, nc, lo, hi, split, bowl_fn,
		    c, &e), 0);
		for (size_t p = 0; p < m.npoint; p++) {
			for (int a = 0; a < 3; a++)
				if (m.pts[3 * p + a] > -1 && m.pts[3 * p + a] < 1)
					m.pts[3 * p + a] += 0.04 *
					    (2 * u01(90 + (uint64_t)a, p) - 1);
			m.val[p] = (float)(1 + 3 * u01(93, p));
		}
		for (size_t t = 0; t < m.ntet; t++)
			for (int k = 3; k > 0; k--) {
				int j = (int)(u01(94, 4 * t + (size_t)k) * (k + 1));
				uint32_t s = m.tet[4 * t + (size_t)k];
				m.tet[4 * t + (size_t)k] = m.tet[4 * t + (size_t)j];
				m.tet[4 * t + (size_t)j] = s;
			}
		assert_int_equal(vx_tetmesh_validate(&m, &e), 0);
		double (*tf)[2] = malloc(2 * m.ntet * sizeof *tf);
		for (uint64_t r = 0; r < 100; r++) {
			double o[3], d[3];
			vx_tetray ray;
			size_t n = 0;
			for (int a = 0; a < 3; a++) {
				d[a] = 2 * u01(95 + (uint64_t)a, r) - 1;
				o[a] = 0.8 * (2 * u01(98 + (uint64_t)a, r) - 1) -
				    3 * d[a];
			}
			vx_tetray_init(&ray, o, d);
			for (size_t t = 0; t < m.ntet; t++) {
				double t0, f0, t1, f1;
				if (!vx_tet_segment(&m, t, &ray, &t0, &f0, &t1, &f1))
					continue;
				tf[n][0] = t0;
				tf[n++][1] = f0;
				tf[n][0] = t1;
				tf[n++][1] = f1;
			}
			qsort(tf, n, sizeof *tf, tf_cmp);
			size_t single = 0;
			for (size_t i = 0; i < n;) {
				size_t j = i + 1;
				while (j < n && tf_cmp(tf[i], tf[j]) == 0)
					j++;
				assert_true(j - i <= 2);
				single += j - i == 1;
				i = j;
			}
			/* the line starts inside the box's shadow: enters
			 * and leaves once (or misses it) */
			assert_true(single == 2 || (single == 0 && n == 0));
		}
		free(tf);
		vx_tetmesh_free(&m);
	}
}

/* An unmerged seam (as in post_tets' O-grid): the points of the plane
 * x = 0 are duplicated, in reversed index order, for the tets on the x > 0
 * side, with equal values.  Oracles: the chain property (segment ends pair
 * up bit for bit across the seam: each (t, f) occurs an even number of
 * times except the line's entry into and exit from the box) and the
 * parity/alternation of crossings, for random rays and rays through seam
 * vertices. */
static void
seam_watertight(void **state)
{
	double c[3] = { 0, 0.1, -0.05 }, lo[3] = { -1.5, -1.5, -1.5 };
	double hi[3] = { 1.5, 1.5, 1.5 };
	int64_t nc[3] = { 6, 6, 6 };
	vx_tetmesh g, m;
	vx_err e = { 0, "" };

	(void)state;
	assert_int_equal(vx_tetsynth_grid(&g, nc, lo, hi, 5, bowl_fn, c, &e), 0);
	size_t nseam = 0, *dup = calloc(g.npoint, sizeof *dup);
	for (size_t p = 0; p < g.npoint; p++)
		nseam += g.pts[3 * p] == 0;
	assert_int_equal(nseam, 49);
	assert_int_equal(vx_tetmesh_alloc(&m, g.npoint + nseam, g.ntet, &e), 0);
	memcpy(m.pts, g.pts, 24 * g.npoint);
	memcpy(m.val, g.val, 4 * g.npoint);
	memcpy(m.tet, g.tet, 16 * g.ntet);
	for (size_t p = g.npoint, k = 0; p-- > 0;)
		if (g.pts[3 * p] == 0) {
			dup[p] = g.npoint + k++;
			memcpy(m.pts + 3 * dup[p], g.pts + 3 * p, 24);
			m.val[dup[p]] = g.val[p];
		}
	for (size_t t = 0; t < m.ntet; t++) {
		double cx = 0;
		for (int k = 0; k < 4; k++)
			cx += m.pts[3 * m.tet[4 * t + (size_t)k]];
		if (cx > 0)
			for (int k = 0; k < 4; k++)
				if (dup[m.tet[4 * t + (size_t)k]])
					m.tet[4 * t + (size_t)k] =
					    (uint32_t)dup[m.tet[4 * t + (size_t)k]];
	}
	assert_int_equal(vx_tetmesh_validate(&m, &e), 0);
	double (*tf)[2] = malloc(2 * m.ntet * sizeof *tf);
	for (uint64_t r = 0; r < 300; r++) {
		double o[3], d[3], p[3];
		for (int a = 0; a < 3; a++) {
			d[a] = 2 * u01(110 + (uint64_t)a, r) - 1;
			p[a] = 1.6 * u01(113 + (uint64_t)a, r) - 0.8;
		}
		if (r % 2 == 0) {
			/* through a seam vertex (y, z on the lattice) */
			p[0] = 0;
			p[1] = 0.5 * (double)(int)(u01(116, r) * 5 - 2);
			p[2] = 0.5 * (double)(int)(u01(117, r) * 5 - 2);
		}
		for (int a = 0; a < 3; a++)
			o[a] = p[a] - 4 * d[a];
		vx_tetray ray;
		size_t n = 0, single = 0;
		vx_tetray_init(&ray, o, d);
		for (size_t t = 0; t < m.ntet; t++) {
			double t0, f0, t1, f1;
			if (!vx_tet_segment(&m, t, &ray, &t0, &f0, &t1, &f1))
				continue;
			tf[n][0] = t0;
			tf[n++][1] = f0;
			tf[n][0] = t1;
			tf[n++][1] = f1;
		}
		qsort(tf, n, sizeof *tf, tf_cmp);
		for (size_t i = 0; i < n;) {
			size_t j = i + 1;
			while (j < n && tf_cmp(tf[i], tf[j]) == 0)
				j++;
			/* zero-length links at a vertex the ray meets
			 * exactly repeat its value: count parities */
			single += (j - i) % 2;
			i = j;
		}
		assert_true(single == 2 || (single == 0 && n == 0));
		xing x[64];
		/* 1, or the value of a vertex near the centre (above every
		 * boundary value, so lines start and end outside) */
		double q[3] = { 0.5 * (double)(int)(u01(118, r) * 3 - 1),
		    0.5 * (double)(int)(u01(119, r) * 3 - 1),
		    0.5 * (double)(int)(u01(120, r) * 3 - 1) };
		double iso = r % 3 ? 1.0 : (float)bowl_fn(q, c);
		n = all_crossings(&m, o, d, iso, x, 64);
		check_alternation(x, n);
	}
	free(tf);
	free(dup);
	vx_tetmesh_free(&m);
	vx_tetmesh_free(&g);
}

/* Slivers and flat tets.  Oracles: a flat tet (exactly coplanar vertices,
 * repeated index, coincident points) never hits and never yields NaN; a
 * sliver of height 1e-13 whose field crosses iso at half height is hit
 * exactly by the rays that pass over its base, at a point inside the
 * sliver, with a finite unit normal along +z (its gradient). */
static void
slivers_and_flat(void **state)
{
	static const double P[][3] = {
		{ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0.3, 0.3, 1e-13 },
		{ 0.3, 0.3, 0 }, { 1, 0, 0 }, { 0.5, 0.5, 0 },
	};
	static const float V[] = { 0, 0, 0, 1, 1, 5, 1 };
	static const uint32_t T[][4] = {
		{ 0, 1, 2, 3 },   /* sliver */
		{ 0, 1, 2, 4 },   /* flat: coplanar */
		{ 0, 1, 1, 3 },   /* repeated index */
		{ 1, 5, 2, 3 },   /* point 5 coincides with point 1 */
		{ 1, 2, 6, 3 },   /* three collinear points (1, 6, 2) */
	};
	vx_tetmesh m;
	vx_err e = { 0, "" };

	(void)state;
	assert_int_equal(vx_tetmesh_alloc(&m, 7, 5, &e), 0);
	memcpy(m.pts, P, sizeof P);
	memcpy(m.val, V, sizeof V);
	memcpy(m.tet, T, sizeof T);
	assert_int_equal(vx_tetmesh_validate(&m, &e), 0);
	assert_false(vx_tetmesh_degenerate(&m, 0));
	for (size_t t = 1; t < 5; t++)
		assert_true(vx_tetmesh_degenerate(&m, t));
	for (uint64_t r = 0; r < 2000; r++) {
		double o[3], d[3], tgt[3];
		tgt[0] = 1.2 * u01(50, r) - 0.1;
		tgt[1] = 1.2 * u01(51, r) - 0.1;
		tgt[2] = r % 4 == 0 ? 0 : 2e-13 * u01(52, r) - 0.5e-13;
		for (int a = 0; a < 3; a++) {
			d[a] = 2 * u01(53 + (uint64_t)a, r) - 1;
			o[a] = tgt[a] - 3 * d[a];
		}
		if (r % 5 == 0) {
			/* straight down, and through the vertices */
			d[0] = d[1] = 0;
			d[2] = -1;
			if (r % 10 == 0)
				memcpy(tgt, P[r / 10 % 7], sizeof tgt);
			for (int a = 0; a < 3; a++)
				o[a] = tgt[a] - 3 * d[a];
		}
		for (uint32_t t = 0; t < 5; t++) {
			double th = NAN, n[3] = { NAN, NAN, NAN };
			double t0, f0, t1, f1;
			vx_tetray ray;
			int hit = vx_tet_intersect(&m, t, o, d, 0.5, -1e300, 1e300,
			    &th, n);
			vx_tetray_init(&ray, o, d);
			if (vx_tet_segment(&m, t, &ray, &t0, &f0, &t1, &f1)) {
				assert_true(isfinite(t0) && isfinite(t1) &&
				    isfinite(f0) && isfinite(f1) &&
				    t0 <= t1 + 1e-12);
			}
			if (t > 0) {
				assert_int_equal(hit, 0);
				continue;
			}
			/* the sliver: f = z / 1e-13, so hit iff the ray meets
			 * z = 0.5e-13 inside the tet's cross-section there, the
			 * triangle (0.15,0.15) (0.65,0.15) (0.15,0.65) */
			double tz = (0.5e-13 - o[2]) / d[2], bx = o[0] + tz * d[0];
			double by = o[1] + tz * d[1];
			int in = bx > 0.15 + 1e-9 && by > 0.15 + 1e-9 &&
			    bx + by < 0.8 - 1e-9;
			int out = bx < 0.15 - 1e-9 || by < 0.15 - 1e-9 ||
			    bx + by > 0.8 + 1e-9;
			if (in)
				assert_int_equal(hit, 1);
			if (out)
				assert_int_equal(hit, 0);
			if (hit) {
				double z = o[2] + th * d[2];
				assert_true(z >= -1e-14 && z <= 1.1e-13);
				assert_true(isfinite(n[0]) && isfinite(n[1]) &&
				    isfinite(n[2]));
				assert_true(fabs(n[0] * n[0] + n[1] * n[1] + n[2] *
				    n[2] - 1) < 1e-12);
				assert_true(n[2] > 0.99);
			}
		}
	}
	/* non-finite values: the tet never hits */
	m.val[3] = NAN;
	double o[3] = { 0.2, 0.2, 1 }, d[3] = { 0, 0, -1 }, th;
	assert_int_equal(vx_tet_intersect(&m, 0, o, d, 0.5, -1e300, 1e300, &th,
	    NULL), 0);
	vx_tetmesh_free(&m);
}

/* Oracle: for several isovalues at once, vx_tet_nearest returns the
 * smallest t over all (tet, iso) pairs found one by one, independent of
 * the list's order. */
static void
nearest_multi_iso(void **state)
{
	double c[3] = { 0, 0, 0 }, lo[3] = { -1.5, -1.5, -1.5 };
	double hi[3] = { 1.5, 1.5, 1.5 }, iso[3] = { 1.5, 0.8, 1.2 };
	int64_t nc[3] = { 4, 4, 4 };
	vx_tetmesh m;
	vx_err e = { 0, "" };

	(void)state;
	assert_int_equal(vx_tetsynth_grid(&m, nc, lo, hi, 6, bowl_fn, c, &e),
	    0);
	uint32_t *fwd = malloc(m.ntet * sizeof *fwd);
	uint32_t *rev = malloc(m.ntet * sizeof *rev);
	for (size_t t = 0; t < m.ntet; t++) {
		fwd[t] = (uint32_t)t;
		rev[t] = (uint32_t)(m.ntet - 1 - t);
	}
	for (uint64_t r = 0; r < 50; r++) {
		double o[3], d[3], tmin = u01(60, r) * 3;
		for (int a = 0; a < 3; a++) {
			d[a] = 2 * u01(61 + (uint64_t)a, r) - 1;
			o[a] = 0.3 * u01(64 + (uint64_t)a, r) - 3 * d[a];
		}
		vx_tetray ray;
		vx_tethit h1, h2;
		vx_tetray_init(&ray, o, d);
		int f1 = vx_tet_nearest(&m, fwd, m.ntet, &ray, iso, 3, tmin, 1e300,
		    &h1);
		int f2 = vx_tet_nearest(&m, rev, m.ntet, &ray, iso, 3, tmin, 1e300,
		    &h2);
		assert_int_equal(f1, f2);
		double best = INFINITY;
		for (uint32_t t = 0; t < m.ntet; t++)
			for (int k = 0; k < 3; k++) {
				double th;
				if (vx_tet_intersect(&m, t, o, d, iso[k], tmin, 1e300,
				    &th, NULL) && th < best)
					best = th;
			}
		if (!f1) {
			assert_true(isinf(best));
			continue;
		}
		assert_true(h1.t == best && h2.t == best);
		assert_int_equal(h1.tet, h2.tet);
		assert_int_equal(h1.iso, h2.iso);
		assert_true(memcmp(h1.n, h2.n, sizeof h1.n) == 0);
	}
	free(fwd);
	free(rev);
	vx_tetmesh_free(&m);
}

/* ---- the TETM chunk ---- */

static void
small_mesh(vx_tetmesh *m)
{
	int64_t nc[3] = { 2, 1, 3 };
	double lo[3] = { 0, 0, 0 }, hi[3] = { 2, 1, 3 }, c[3] = { 1, 0.5, 1.5 };
	vx_err e = { 0, "" };

	assert_int_equal(vx_tetsynth_grid(m, nc, lo, hi, 5, bowl_fn, c, &e), 0);
	vx_tetmesh_set_name(m, "small one");
	vx_tetmesh_set_scalar(m, "dens:ity\n");
}

/* Oracle: to_chunk then from_chunk gives back the same bytes, raw and zlib;
 * names travel (sanitized). */
static void
chunk_roundtrip(void **state)
{
	(void)state;
	for (int z = 0; z <= 6; z += 6) {
		vx_tetmesh m, b;
		vx_chunk c;
		vx_err e = { 0, "" };
		small_mesh(&m);
		assert_int_equal(vx_tetmesh_to_chunk(&m, z, &c, &e), 0);
		assert_memory_equal(c.type, "TETM", 4);
		assert_int_equal(vx_tetmesh_from_chunk(&b, &c, &e), 0);
		assert_string_equal(b.name, "small one");
		assert_string_equal(b.scalar, "dens_ity_");
		assert_int_equal(b.npoint, m.npoint);
		assert_int_equal(b.ntet, m.ntet);
		assert_memory_equal(b.pts, m.pts, 24 * m.npoint);
		assert_memory_equal(b.tet, m.tet, 16 * m.ntet);
		assert_memory_equal(b.val, m.val, 4 * m.npoint);
		assert_true(b.vmin == m.vmin && b.vmax == m.vmax);
		for (int a = 0; a < 3; a++)
			assert_true(b.bmin[a] == m.bmin[a] && b.bmax[a] == m.bmax[a]);
		/* in a stream, by name */
		vx_stream s;
		vx_stream_init(&s);
		vx_chunk c2;
		vx_tetmesh_set_name(&b, "other");
		assert_int_equal(vx_tetmesh_to_chunk(&b, z, &c2, &e), 0);
		assert_int_equal(vx_stream_append(&s, &c2, &e), 0);
		assert_int_equal(vx_stream_append(&s, &c, &e), 0);
		vx_tetmesh_free(&b);
		long idx = -1;
		assert_int_equal(vx_tetmesh_from_stream(&b, &s, "small one", &idx,
		    &e), 0);
		assert_int_equal(idx, 1);
		vx_tetmesh_free(&b);
		assert_int_equal(vx_tetmesh_from_stream(&b, &s, NULL, &idx, &e), 0);
		assert_int_equal(idx, 0);
		assert_string_equal(b.name, "other");
		vx_tetmesh_free(&b);
		assert_int_equal(vx_tetmesh_from_stream(&b, &s, "nope", NULL, &e),
		    VX_EDATA);
		assert_non_null(strstr(e.msg, "no tet mesh named 'nope'"));
		vx_stream_free(&s);
		vx_tetmesh_free(&m);
	}
}

/* A TETM chunk from a header text and a raw body. */
static void
make_chunk(vx_chunk *c, const char *hdr, const void *body, size_t n)
{
	size_t hl = strlen(hdr);
	memcpy(c->type, "TETM", 5);
	c->len = hl + n;
	c->data = malloc(c->len + 1);
	memcpy(c->data, hdr, hl);
	if (n)
		memcpy(c->data + hl, body, n);
	c->offset = 0;
}

/* Oracle: each malformed chunk is refused with VX_EDATA and a message
 * naming the problem, before allocating on the header's word. */
static void
chunk_malformed(void **state)
{
	vx_tetmesh m;
	small_mesh(&m);
	size_t np = m.npoint, nt = m.ntet;
	size_t bl = 28 * np + 16 * nt;
	unsigned char *body = malloc(bl);
	memcpy(body, m.pts, 24 * np);
	memcpy(body + 24 * np, m.tet, 16 * nt);
	memcpy(body + 24 * np + 16 * nt, m.val, 4 * np);
	char hdr[256];
	struct { const char *what; int mutate; const char *msg; } t[] = {
		{ "ok", 0, NULL },
		{ "huge counts", 1, "cannot hold them" },
		{ "truncated body", 2, "(1149 bytes)" },
		{ "index out of range", 3, "refers to point" },
		{ "NaN coordinate", 4, "NaN coordinate" },
		{ "negative count", 5, "out of range" },
		{ "missing tets", 6, "tets" },
		{ "zlib bomb claim", 7, "cannot hold them" },
		{ "infinite coordinate", 8, "limit" },
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_chunk c;
		vx_tetmesh b;
		vx_err e = { 0, "" };
		unsigned char *bb = malloc(bl);
		size_t n = bl;
		memcpy(bb, body, bl);
		snprintf(hdr, sizeof hdr, "name: x\npoints: %zu\ntets: %zu\n"
		    "scalar: s\nencoding: raw\n\n", np, nt);
		switch (t[i].mutate) {
		case 1:
			snprintf(hdr, sizeof hdr, "points: 4000000000\ntets: "
			    "2000000000\n\n");
			break;
		case 2:
			n -= 3;
			break;
		case 3:
			((uint32_t *)(void *)(bb + 24 * np))[5] = (uint32_t)np;
			break;
		case 4: {
			double q = NAN;
			memcpy(bb + 8 * 7, &q, 8);
			break;
		}
		case 5:
			snprintf(hdr, sizeof hdr, "points: -1\ntets: 0\n\n");
			break;
		case 6:
			snprintf(hdr, sizeof hdr, "points: %zu\n\n", np);
			break;
		case 7:
			snprintf(hdr, sizeof hdr, "points: 100000000\ntets: 0\n"
			    "encoding: zlib\n\n");
			n = 16;
			break;
		case 8: {
			double q = INFINITY;
			memcpy(bb + 8 * 4, &q, 8);
			break;
		}
		}
		make_chunk(&c, hdr, bb, n);
		int rc = vx_tetmesh_from_chunk(&b, &c, &e);
		if (t[i].msg == NULL) {
			assert_int_equal(rc, 0);
			vx_tetmesh_free(&b);
		} else {
			if (rc != VX_EDATA || strstr(e.msg, t[i].msg) == NULL)
				fail_msg("%s: rc %d msg '%s'", t[i].what, rc, e.msg);
			assert_null(b.pts);
		}
		free(c.data);
		free(bb);
	}
	free(body);
	vx_tetmesh_free(&m);
}

/* ---- the leaf grid ---- */

/* Leaf grid oracles, on a jittered and sheared mesh (skewed tets, no
 * coordinate ties).  Bounding-box mode (brute force): tet t is in leaf l
 * iff its bounding box padded by VX_TETLEAF_PAD leaf widths overlaps the
 * leaf's box.  Exact mode: its lists are subsets of those, and complete: a
 * leaf containing any of 400 sample points of a tet (vertices, random
 * barycentric points) lists it.  Both: lists ascend, leaf ranges are the
 * min/max over the listed tets' vertex values, about one leaf per tet. */
static void
leaf_grid_brute(void **state)
{
	int64_t nc[3] = { 4, 3, 5 };
	double lo[3] = { 0, -1, 2 }, hi[3] = { 4, 0.5, 7 }, c[3] = { 2, 0, 4 };
	vx_tetmesh m;
	vx_err e = { 0, "" };

	(void)state;
	assert_int_equal(vx_tetsynth_grid(&m, nc, lo, hi, 5, bowl_fn, c, &e), 0);
	for (size_t p = 0; p < m.npoint; p++) {
		for (int a = 0; a < 3; a++)
			m.pts[3 * p + a] += 0.1 * u01(70 + (uint64_t)a, p);
		m.pts[3 * p] += 0.9 * m.pts[3 * p + 1] + 0.4 * m.pts[3 * p + 2];
	}
	assert_int_equal(vx_tetmesh_validate(&m, &e), 0);
	for (double dens = 0.5; dens <= 4; dens *= 2) {
		vx_tetleaf bb, ex;
		int sizes[1][3] = { { 2, 2, 2 } };
		assert_int_equal(vx_tetleaf_build_levels(&bb, &m, dens,
		    VX_TETLEAF_BBOX, 1, sizes, 1, &e), 0);
		assert_int_equal(vx_tetleaf_build_levels(&ex, &m, dens, 0, 1,
		    sizes, 2, &e), 0);
		double ratio = (double)bb.nleaf / ((double)m.ntet * dens);
		assert_true(ratio > 0.4 && ratio < 2.5);
		assert_int_equal(bb.nleaf, ex.nleaf);
		assert_true(ex.off[ex.nleaf] < bb.off[bb.nleaf]);
		for (size_t l = 0; l < bb.nleaf; l++) {
			int64_t ix[3] = { (int64_t)l % bb.dims[0],
			    (int64_t)l / bb.dims[0] % bb.dims[1],
			    (int64_t)l / bb.dims[0] / bb.dims[1] };
			size_t k = bb.off[l];
			for (uint32_t t = 0; t < m.ntet; t++) {
				int ov = 1;
				for (int a = 0; a < 3; a++) {
					double bl = INFINITY, bh = -INFINITY;
					for (int q = 0; q < 4; q++) {
						double x = m.pts[3 * m.tet[4 * t + q] + a];
						bl = fmin(bl, x);
						bh = fmax(bh, x);
					}
					double pad = VX_TETLEAF_PAD * bb.cell[a];
					double l0 = bb.bmin[a] + (double)ix[a] * bb.cell[a];
					double l1 = l0 + bb.cell[a];
					if (ix[a] == 0)
						l0 = -INFINITY;
					if (ix[a] == bb.dims[a] - 1)
						l1 = INFINITY;
					ov &= bl - pad < l1 && bh + pad > l0;
				}
				if (!ov)
					continue;
				assert_true(k < bb.off[l + 1]);
				assert_int_equal(bb.idx[k], t);
				k++;
			}
			assert_int_equal(k, bb.off[l + 1]);
			/* exact: a subsequence of the bounding-box list */
			size_t j = bb.off[l];
			for (k = ex.off[l]; k < ex.off[l + 1]; k++) {
				while (j < bb.off[l + 1] && bb.idx[j] != ex.idx[k])
					j++;
				assert_true(j < bb.off[l + 1]);
			}
			/* ranges from the lists */
			const vx_tetleaf *g2[2] = { &bb, &ex };
			for (int gi = 0; gi < 2; gi++) {
				const vx_tetleaf *g = g2[gi];
				float vmin = INFINITY, vmax = -INFINITY, rlo, rhi;
				for (k = g->off[l]; k < g->off[l + 1]; k++) {
					if (k > g->off[l])
						assert_true(g->idx[k] > g->idx[k - 1]);
					for (int q = 0; q < 4; q++) {
						float v = m.val[m.tet[4 * g->idx[k] + q]];
						vmin = fminf(vmin, v);
						vmax = fmaxf(vmax, v);
					}
				}
				vx_tetleaf_range(g, l, &rlo, &rhi);
				assert_true(rlo == vmin && rhi == vmax);
			}
		}
		/* completeness of the exact lists by sampling */
		for (uint32_t t = 0; t < m.ntet; t++)
			for (uint64_t sidx = 0; sidx < 400; sidx++) {
				double w[4], sum = 0, p[3] = { 0, 0, 0 };
				for (int q = 0; q < 4; q++) {
					w[q] = sidx < 4 ? (double)(q == (int)sidx) :
					    -log(1 - u01(75 + (uint64_t)q,
					    t * 400 + sidx));
					sum += w[q];
				}
				for (int q = 0; q < 4; q++)
					for (int a = 0; a < 3; a++)
						p[a] += w[q] / sum *
						    m.pts[3 * m.tet[4 * t + q] + a];
				int64_t ix[3];
				for (int a = 0; a < 3; a++) {
					double f = (p[a] - ex.bmin[a]) / ex.cell[a];
					ix[a] = (int64_t)floor(f);
					if (ix[a] >= ex.dims[a])
						ix[a] = ex.dims[a] - 1;
				}
				size_t l = (size_t)(ix[0] + ex.dims[0] * (ix[1] +
				    ex.dims[1] * ix[2]));
				size_t k = ex.off[l];
				while (k < ex.off[l + 1] && ex.idx[k] != t)
					k++;
				assert_true(k < ex.off[l + 1]);
			}
		assert_true(vx_tetleaf_bytes(&ex) > 0);
		/* the same on one thread (determinism) */
		vx_tetleaf one;
		assert_int_equal(vx_tetleaf_build_levels(&one, &m, dens, 0, 1,
		    sizes, 1, &e), 0);
		assert_memory_equal(one.off, ex.off, (ex.nleaf + 1) * 4);
		assert_memory_equal(one.idx, ex.idx, ex.off[ex.nleaf] * 4);
		assert_memory_equal(one.mc.mm[0], ex.mc.mm[0], ex.nleaf * 8);
		vx_tetleaf_free(&one);
		vx_tetleaf_free(&bb);
		vx_tetleaf_free(&ex);
	}
	vx_tetmesh_free(&m);
}

/* Oracle: the nearest hit found by walking the hierarchy (any number of
 * levels) is the nearest hit over all tets, bit for bit (t, tet, isovalue,
 * normal): nothing is lost at leaf boundaries, by culling or by stopping
 * at the first leaf that hits.  Rays: random, along leaf-grid planes and
 * through leaf corners, and through mesh vertices; ray origins inside and
 * outside the mesh, several isovalues. */
static void
leaf_grid_nearest(void **state)
{
	int64_t nc[3] = { 5, 4, 6 };
	double lo[3] = { -1.5, -1.2, -1.5 }, hi[3] = { 1.5, 1.2, 1.8 };
	double c[3] = { 0, 0.1, 0 }, isos[3] = { 1.0, 0.25, 1.6 };
	int sizes[2][3] = { { 2, 3, 2 }, { 2, 2, 2 } };
	vx_tetmesh m;
	vx_err e = { 0, "" };

	(void)state;
	for (int split = 5; split <= 6; split++) {
		assert_int_equal(vx_tetsynth_grid(&m, nc, lo, hi, split, bowl_fn,
		    c, &e), 0);
		uint32_t *all = malloc(m.ntet * sizeof *all);
		for (size_t t = 0; t < m.ntet; t++)
			all[t] = (uint32_t)t;
		for (int nlev = 0; nlev <= 3; nlev++) {
			vx_tetleaf lg;
			vx_trav_stats st;
			/* level 3: one leaf per grid cell, so leaf planes are
			 * mesh planes (tet boxes end on them) */
			double dens = nlev == 3 ? 1.0 / split : 1;
			memset(&st, 0, sizeof st);
			assert_int_equal(vx_tetleaf_build_levels(&lg, &m, dens,
			    (int)(nlev == 1), nlev % 3, sizes, 1, &e), 0);
			if (nlev == 3)
				for (int a = 0; a < 3; a++)
					assert_int_equal(lg.dims[a], nc[a]);
			for (uint64_t r = 0; r < 1000; r++) {
				double o[3], d[3], tmin = r % 5 == 1 ? 2.5 : 0;
				int niso = 1 + (int)(r % 3);
				for (int a = 0; a < 3; a++) {
					d[a] = 2 * u01(80 + (uint64_t)a, r) - 1;
					o[a] = 0.5 * u01(83 + (uint64_t)a, r) - 4 * d[a];
				}
				if (r % 4 == 0) {
					/* along leaf planes, through leaf corners */
					for (int a = 0; a < 3; a++) {
						d[a] = a == (int)(r / 4 % 3);
						o[a] = lg.bmin[a] + lg.cell[a] *
						    (double)(r % 3 + 1) - 4 * d[a];
					}
				} else if (r % 4 == 2) {
					/* through a mesh vertex (on leaf planes at
					 * level 3), at its own value */
					size_t v = (size_t)(u01(86, r) *
					    (double)m.npoint);
					for (int a = 0; a < 3; a++)
						o[a] = m.pts[3 * v + a] - 4 * d[a];
					isos[0] = m.val[v];
				}
				vx_tetray ray;
				vx_tethit hb, hl;
				vx_tetray_init(&ray, o, d);
				int fb = vx_tet_nearest(&m, all, m.ntet, &ray, isos,
				    niso, tmin, 1e300, &hb);
				int fl = vx_tetleaf_nearest(&lg, &m, o, d, isos, niso,
				    tmin, 1e300, &hl, &st);
				isos[0] = 1.0;
				if (fb != fl)
					fprintf(stderr, "split %d nlev %d r %d: fb %d "
					    "(t %.17g tet %u) fl %d (t %.17g tet %u)\n",
					    split, nlev, (int)r, fb, hb.t, hb.tet, fl,
					    hl.t, hl.tet);
				assert_int_equal(fb, fl);
				if (!fb)
					continue;
				assert_true(hb.t == hl.t);
				assert_int_equal(hb.tet, hl.tet);
				assert_int_equal(hb.iso, hl.iso);
				assert_memory_equal(hb.n, hl.n, sizeof hb.n);
			}
			assert_true(st.leaves > 0);
			vx_tetleaf_free(&lg);
		}
		free(all);
		vx_tetmesh_free(&m);
	}
}

/* Oracle: the leaf counts follow the box's shape and the cap. */
static void
leaf_dims_shape(void **state)
{
	int64_t d[3];

	(void)state;
	vx_tetleaf_dims((double[3]){ 1, 1, 1 }, 1000, 1, d);
	assert_true(d[0] == 10 && d[1] == 10 && d[2] == 10);
	vx_tetleaf_dims((double[3]){ 8, 1, 1 }, 512, 1, d);
	assert_true(d[0] == 32 && d[1] == 4 && d[2] == 4);
	vx_tetleaf_dims((double[3]){ 1, 1, 0 }, 100, 1, d);
	assert_true(d[0] == 10 && d[1] == 10 && d[2] == 1);
	vx_tetleaf_dims((double[3]){ 1000, 1, 1e-6 }, 1000, 1, d);
	assert_true(d[0] == 1000 && d[1] == 1 && d[2] == 1);
	vx_tetleaf_dims((double[3]){ 0, 0, 0 }, 5, 1, d);
	assert_true(d[0] == 1 && d[1] == 1 && d[2] == 1);
	vx_tetleaf_dims((double[3]){ 1, 1, 1 }, 0, 1, d);
	assert_true(d[0] == 1 && d[1] == 1 && d[2] == 1);
	/* extents whose product underflows or overflows a double */
	vx_tetleaf_dims((double[3]){ 1e-300, 1e-300, 1e-300 }, 1000, 1, d);
	assert_true(d[0] == 10 && d[1] == 10 && d[2] == 10);
	vx_tetleaf_dims((double[3]){ 1e-200, 1e-200, 1 }, 100, 1, d);
	assert_true(d[0] == 1 && d[1] == 1 && d[2] == 100);
	vx_tetleaf_dims((double[3]){ 1e300, 1e300, 1e300 }, 8, 1, d);
	assert_true(d[0] == 2 && d[1] == 2 && d[2] == 2);
	/* fuzz_tetvtk's input: one tet with extents 1.2e-38, 2.7e-312, 1
	 * (subnormal) asked for 2^31 leaves (8 GiB) before the fix above.
	 * Oracle: one tet, one leaf */
	vx_tetleaf_dims((double[3]){ 1.1754943508222874e-38,
	    2.73671144666e-312, 1 }, 1, 1, d);
	assert_true(d[0] == 1 && d[1] == 1 && d[2] == 1);
}

/* ---- importers ---- */

/* Two tets sharing face (1,2,3), a triangle (skipped), point scalars with a
 * lookup table, other attributes around them. */
static const char vtk_ascii[] =
    "# vtk DataFile Version 3.0\n"
    "two tets\n"
    "ASCII\n"
    "DATASET UNSTRUCTURED_GRID\n"
    "FIELD FieldData 1\n"
    "TIME 1 1 double\n"
    "0.5\n"
    "POINTS 5 float\n"
    "0 0 0  1 0 0  0 1 0\n"
    "0 0 1  1 1 1\n"
    "CELLS 3 14\n"
    "4 0 1 2 3\n"
    "4 1 2 3 4\n"
    "3 0 1 2\n"
    "CELL_TYPES 3\n"
    "10\n10\n5\n"
    "CELL_DATA 3\n"
    "SCALARS id int 1\n"
    "LOOKUP_TABLE default\n"
    "7 8 9\n"
    "POINT_DATA 5\n"
    "VECTORS vel float\n"
    "1 0 0 1 0 0 1 0 0 1 0 0 1 0 0\n"
    "SCALARS dens%20ity double\n"
    "LOOKUP_TABLE default\n"
    "0.5 1.5 -2 3e2 4.25\n"
    "FIELD more 1\n"
    "temp 1 5 float\n"
    "10 11 12 13 14\n";

static const float vtk_vals[5] = { 0.5f, 1.5f, -2, 300, 4.25f };
static const uint32_t vtk_tets[8] = { 0, 1, 2, 3, 1, 2, 3, 4 };
static const double vtk_pts[15] = {
	0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1,
};

static void
check_two_tets(const vx_tetmesh *m)
{
	assert_int_equal(m->npoint, 5);
	assert_int_equal(m->ntet, 2);
	assert_memory_equal(m->tet, vtk_tets, sizeof vtk_tets);
	for (int i = 0; i < 15; i++)
		assert_true(m->pts[i] == vtk_pts[i]);
}

/* big-endian writers for the binary file */
typedef struct bbuf { unsigned char *p; size_t n; } bbuf;

static void
bput(bbuf *b, const void *q, size_t n)
{
	b->p = realloc(b->p, b->n + n + 1);
	memcpy(b->p + b->n, q, n);
	b->n += n;
}

static void
bstr(bbuf *b, const char *s)
{
	bput(b, s, strlen(s));
}

static void
bbe(bbuf *b, uint64_t v, int n)
{
	unsigned char x[8];
	for (int i = 0; i < n; i++)
		x[i] = (unsigned char)(v >> (8 * (n - 1 - i)));
	bput(b, x, (size_t)n);
}

static void
bf64(bbuf *b, double d)
{
	uint64_t u;
	memcpy(&u, &d, 8);
	bbe(b, u, 8);
}

static void
bf32(bbuf *b, float f)
{
	uint32_t u;
	memcpy(&u, &f, 4);
	bbe(b, u, 4);
}

/* The ASCII file's content as BINARY: points double, cells int32, scalars
 * float, an unsigned_char point array before them. */
static bbuf
vtk_binary(void)
{
	bbuf b = { NULL, 0 };
	bstr(&b, "# vtk DataFile Version 4.2\ntwo tets\nBINARY\n"
	    "DATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n");
	for (int i = 0; i < 15; i++)
		bf64(&b, vtk_pts[i]);
	bstr(&b, "\nCELLS 3 14\n");
	static const int cl[14] = { 4, 0, 1, 2, 3, 4, 1, 2, 3, 4, 3, 0, 1, 2 };
	for (int i = 0; i < 14; i++)
		bbe(&b, (uint32_t)cl[i], 4);
	bstr(&b, "\nCELL_TYPES 3\n");
	bbe(&b, 10, 4);
	bbe(&b, 10, 4);
	bbe(&b, 5, 4);
	bstr(&b, "\nPOINT_DATA 5\nSCALARS flag unsigned_char 2\n"
	    "LOOKUP_TABLE default\n");
	for (int i = 0; i < 10; i++)
		bbe(&b, (uint64_t)i, 1);
	bstr(&b, "\nSCALARS density float\nLOOKUP_TABLE default\n");
	for (int i = 0; i < 5; i++)
		bf32(&b, vtk_vals[i]);
	bstr(&b, "\n");
	return b;
}

static const char *edit(const char *src, const char *from, const char *to);

/* Oracle: the hand-written files decode to the counts and values written
 * into them, whatever the encoding (ASCII, BINARY, 5.1 offsets). */
static void
vtk_import_good(void **state)
{
	vx_tetmesh m;
	vx_tetimport_info info;
	vx_tetimport_opt opt = { NULL, 0 };
	vx_err e = { 0, "" };

	(void)state;
	/* ASCII, first one-component point array ("dens ity", escaped) */
	assert_int_equal(vx_tetmesh_import_mem(&m, vtk_ascii,
	    sizeof vtk_ascii - 1, NULL, &info, &e), 0);
	check_two_tets(&m);
	assert_memory_equal(m.val, vtk_vals, sizeof vtk_vals);
	assert_string_equal(m.scalar, "dens ity");
	assert_int_equal(info.format, VX_TETFMT_VTK_ASCII);
	assert_int_equal(info.ncell, 3);
	assert_int_equal(info.nskip_lower, 1);
	assert_int_equal(info.narray, 2);
	assert_true(m.vmin == -2 && m.vmax == 300);
	vx_tetmesh_free(&m);
	/* a FIELD array by name */
	opt.scalar = "temp";
	assert_int_equal(vx_tetmesh_import_vtk(&m, vtk_ascii,
	    sizeof vtk_ascii - 1, &opt, NULL, &e), 0);
	for (int i = 0; i < 5; i++)
		assert_true(m.val[i] == 10 + i);
	vx_tetmesh_free(&m);
	/* BINARY: the multi-component array is passed over */
	bbuf b = vtk_binary();
	assert_int_equal(vx_tetmesh_import_mem(&m, b.p, b.n, NULL, &info, &e),
	    0);
	check_two_tets(&m);
	assert_memory_equal(m.val, vtk_vals, sizeof vtk_vals);
	assert_string_equal(m.scalar, "density");
	assert_int_equal(info.format, VX_TETFMT_VTK_BINARY);
	vx_tetmesh_free(&m);
	free(b.p);
	/* 5.1: OFFSETS and CONNECTIVITY */
	static const char v51[] =
	    "# vtk DataFile Version 5.1\nx\nASCII\nDATASET UNSTRUCTURED_GRID\n"
	    "POINTS 5 float\n0 0 0 1 0 0 0 1 0 0 0 1 1 1 1\n"
	    "METADATA\nINFORMATION 0\n\n"
	    "CELLS 4 11\nOFFSETS vtktypeint64\n0 4 8 11\n"
	    "CONNECTIVITY vtktypeint64\n0 1 2 3 1 2 3 4 0 1 2\n"
	    "CELL_TYPES 3\n10 10 5\n"
	    "POINT_DATA 5\nSCALARS s float 1\nLOOKUP_TABLE default\n"
	    "0.5 1.5 -2 300 4.25\n";
	assert_int_equal(vx_tetmesh_import_mem(&m, v51, sizeof v51 - 1, NULL,
	    &info, &e), 0);
	check_two_tets(&m);
	assert_memory_equal(m.val, vtk_vals, sizeof vtk_vals);
	assert_int_equal(info.nskip_lower, 1);
	vx_tetmesh_free(&m);
	/* its arrays' errors, named after the array (oracle: the text) */
	static const struct { const char *from, *to, *msg; } bad51[] = {
		{ "OFFSETS vtktypeint64", "OFFSET vtktypeint64",
		  "expected OFFSETS after CELLS" },
		{ "CONNECTIVITY vtktypeint64", "CONNECTIVITY vtkbit",
		  "data type 'vtkbit' is not supported" },
		{ "CONNECTIVITY vtktypeint64\n0 1 2 3 1 2 3 4 0 1 2\n"
		  "CELL_TYPES", "CONNECTIVITY vtktypeint64\n0 1 2 3 1 2 3 4 0 "
		  "1.5 2\nCELL_TYPES",
		  "CONNECTIVITY: '1.5' is not an integer" },
		{ "CELLS 4 11", "CELLS 4 11000", "truncated: CONNECTIVITY" },
	};
	for (size_t i = 0; i < sizeof bad51 / sizeof bad51[0]; i++) {
		const char *t = edit(v51, bad51[i].from, bad51[i].to);

		if (vx_tetmesh_import_mem(&m, t, strlen(t), NULL, NULL, &e) !=
		    VX_EDATA || strstr(e.msg, bad51[i].msg) == NULL)
			fail_msg("%s: '%s'", bad51[i].msg, e.msg);
	}
}

/* Replace the first occurrence of `from` in src by `to`; the result lives
 * in one of 32 static buffers used in turn. */
static const char *
edit(const char *src, const char *from, const char *to)
{
	static char out[32][4096];
	static int next;
	char *o = out[next++ % 32];
	const char *p = strstr(src, from);
	assert_non_null(p);
	snprintf(o, sizeof out[0], "%.*s%s%s", (int)(p - src), src, to,
	    p + strlen(from));
	return o;
}

/* Oracle: each malformed or unsupported file is refused with VX_EDATA and a
 * message naming the problem; the skip option turns the unsupported volume
 * cell into a counted skip. */
static void
vtk_import_bad(void **state)
{
	struct { const char *what, *text; size_t cut; const char *msg; } t[] = {
		{ "truncated points", vtk_ascii, 150, "truncated" },
		{ "index out of range", NULL, 0, "refers to point 9 of 5" },
		{ "count larger than the data", NULL, 0, "truncated: POINTS" },
		{ "hexahedron", NULL, 0, "hexahedron (type 12)" },
		{ "unknown cell type", NULL, 0, "unknown cell type 200" },
		{ "no scalars", NULL, 0, "no point array named 'nope'" },
		{ "polydata", NULL, 0, "dataset POLYDATA is not supported" },
		{ "NaN coordinate", NULL, 0, "point 1 has a NaN coordinate" },
		{ "cell list overrun", NULL, 0, "runs past" },
		{ "cell size mismatch", NULL, 0, "CELLS claims 15 entries" },
		{ "not vtk", "hello", 0, "unknown mesh format" },
		{ "tetra with 3 points", NULL, 0, "a tetra with 3 points" },
		{ "bad number", NULL, 0, "'1x' is not a number" },
		{ "point data count", NULL, 0, "POINT_DATA has a count" },
		{ "huge cells", NULL, 0, "truncated: CELLS" },
		/* vx_scan.h's grammar: overflow is not an infinity (issue
		 * 19.7), hexadecimal is not a number */
		{ "overflowing value", NULL, 0, "'1e999' is not a number" },
		{ "hexadecimal value", NULL, 0, "'0x3' is not a number" },
		{ "overflowing integer", NULL, 0,
		  "'99999999999999999999' is not an integer" },
	};
	vx_tetimport_opt opt = { NULL, 0 };

	(void)state;
	t[1].text = edit(vtk_ascii, "4 1 2 3 4", "4 1 2 3 9");
	t[2].text = edit(vtk_ascii, "POINTS 5 float", "POINTS 50000 float");
	t[3].text = edit(vtk_ascii, "10\n10\n5", "10\n12\n5");
	t[4].text = edit(vtk_ascii, "10\n10\n5", "10\n200\n5");
	t[5].text = vtk_ascii;
	t[6].text = edit(vtk_ascii, "UNSTRUCTURED_GRID", "POLYDATA");
	t[7].text = edit(vtk_ascii, "0 0 0  1 0 0", "0 0 0  nan 0 0");
	t[8].text = edit(vtk_ascii, "3 0 1 2\n", "9 0 1 2\n");
	t[9].text = edit(vtk_ascii, "CELLS 3 14", "CELLS 3 15");
	t[9].text = edit(t[9].text, "3 0 1 2\n", "3 0 1 2 0\n");
	t[11].text = edit(vtk_ascii, "4 0 1 2 3\n4 1", "3 0 1 2 3\n4 1");
	t[11].text = edit(t[11].text, "CELLS 3 14\n", "CELLS 3 14\n");
	t[12].text = edit(vtk_ascii, "0 1 0\n", "0 1x 0\n");
	t[13].text = edit(vtk_ascii, "POINT_DATA 5", "POINT_DATA 4");
	t[14].text = edit(vtk_ascii, "CELLS 3 14", "CELLS 3 1400000");
	t[15].text = edit(vtk_ascii, "-2 3e2 4.25", "-2 1e999 4.25");
	t[16].text = edit(vtk_ascii, "-2 3e2 4.25", "-2 0x3 4.25");
	t[17].text = edit(vtk_ascii, "4 1 2 3 4",
	    "4 1 2 3 99999999999999999999");
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_tetmesh m;
		vx_err e = { 0, "" };
		size_t n = t[i].cut ? t[i].cut : strlen(t[i].text);
		/* a copy of exactly n bytes, so reading past them is caught */
		char *c = malloc(n);
		memcpy(c, t[i].text, n);
		opt.scalar = i == 5 ? "nope" : NULL;
		int rc = vx_tetmesh_import_mem(&m, c, n, &opt, NULL, &e);
		if (rc != VX_EDATA || strstr(e.msg, t[i].msg) == NULL)
			fail_msg("%s: rc %d, message '%s'", t[i].what, rc, e.msg);
		assert_null(m.pts);
		free(c);
	}
	/* the hexahedron skipped on request */
	vx_tetmesh m;
	vx_tetimport_info info;
	vx_err e = { 0, "" };
	opt.scalar = NULL;
	opt.skip_volume_cells = 1;
	assert_int_equal(vx_tetmesh_import_mem(&m, t[3].text,
	    strlen(t[3].text), &opt, &info, &e), 0);
	assert_int_equal(m.ntet, 1);
	assert_int_equal(info.nskip_volume, 1);
	assert_int_equal(info.nskip_lower, 1);
	vx_tetmesh_free(&m);
	/* binary: every truncation is refused, none reads past the end */
	bbuf b = vtk_binary();
	for (size_t n = 0; n < b.n - 1; n += 7) {
		char *c = malloc(n + 1);
		memcpy(c, b.p, n);
		int rc = vx_tetmesh_import_mem(&m, c, n, NULL, NULL, &e);
		assert_int_equal(rc, VX_EDATA);
		free(c);
	}
	free(b.p);
}

static const char gmsh2[] =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
    "$PhysicalNames\n1\n3 1 \"fluid region\"\n$EndPhysicalNames\n"
    "$Nodes\n5\n"
    "10 0 0 0\n20 1 0 0\n30 0 1 0\n40 0 0 1\n50 1 1 1\n"
    "$EndNodes\n"
    "$Elements\n4\n"
    "1 15 2 0 1 10\n"
    "2 2 2 0 1 10 20 30\n"
    "3 4 2 1 1 10 20 30 40\n"
    "4 4 3 1 1 0 20 30 40 50\n"
    "$EndElements\n"
    "$NodeData\n1\n\"velocity\"\n1\n0.0\n3\n0\n3\n1\n10 1 2 3\n"
    "$EndNodeData\n"
    "$NodeData\n1\n\"pressure\"\n1\n0.0\n3\n0\n1\n5\n"
    "10 0.5\n20 1.5\n30 -2\n40 300\n50 4.25\n"
    "$EndNodeData\n";

static const char gmsh4[] =
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
    "$Entities\n1 0 0 1\n1 0 0 0 0\n1 0 0 0 1 1 1 0 0\n$EndEntities\n"
    "$Nodes\n2 5 1 5\n"
    "0 1 0 1\n1\n0 0 0\n"
    "3 1 1 4\n2\n3\n4\n5\n1 0 0 0.1 0.2 0.3\n0 1 0 0 0 0\n0 0 1 0 0 0\n"
    "1 1 1 0 0 0\n"
    "$EndNodes\n"
    "$Elements\n2 3 1 3\n"
    "2 1 2 1\n1 1 2 3\n"
    "3 1 4 2\n2 1 2 3 4\n3 2 3 4 5\n"
    "$EndElements\n"
    "$NodeData\n1\n\"pressure\"\n1\n0.0\n3\n0\n1\n5\n"
    "1 0.5\n2 1.5\n3 -2\n4 300\n5 4.25\n"
    "$EndNodeData\n";

/* Oracle: the gmsh files (node tags 10..50 in v2, parametric nodes and
 * blocks in v4.1) decode to the mesh of vtk_ascii; points and triangles are
 * skipped and counted; the multi-component view is passed over. */
static void
gmsh_import_good(void **state)
{
	vx_tetmesh m;
	vx_tetimport_info info;
	vx_err e = { 0, "" };

	(void)state;
	assert_int_equal(vx_tetmesh_import_mem(&m, gmsh2, sizeof gmsh2 - 1,
	    NULL, &info, &e), 0);
	check_two_tets(&m);
	assert_memory_equal(m.val, vtk_vals, sizeof vtk_vals);
	assert_string_equal(m.scalar, "pressure");
	assert_int_equal(info.format, VX_TETFMT_GMSH2);
	assert_int_equal(info.ncell, 4);
	assert_int_equal(info.nskip_lower, 2);
	vx_tetmesh_free(&m);
	assert_int_equal(vx_tetmesh_import_mem(&m, gmsh4, sizeof gmsh4 - 1,
	    NULL, &info, &e), 0);
	check_two_tets(&m);
	assert_memory_equal(m.val, vtk_vals, sizeof vtk_vals);
	assert_int_equal(info.format, VX_TETFMT_GMSH4);
	assert_int_equal(info.ncell, 3);
	assert_int_equal(info.nskip_lower, 1);
	vx_tetmesh_free(&m);
}

static void
gmsh_import_bad(void **state)
{
	struct { const char *what, *text; size_t cut; const char *msg; } t[] = {
		{ "truncated", gmsh2, 200, "truncated" },
		{ "undefined node", NULL, 0, "undefined node 60" },
		{ "binary", NULL, 0, "binary .msh files are not supported" },
		{ "version 3", NULL, 0, "version 3 is not supported" },
		{ "hexahedron", NULL, 0, "8-node hexahedron" },
		{ "no node data", NULL, 0, "no one-component $NodeData" },
		{ "missing value", NULL, 0, "node 50 of tetrahedron 1 has no value" },
		{ "count larger than the data", NULL, 0, "count out of range" },
		{ "unknown element type", NULL, 0, "unknown element type 77" },
		{ "duplicate node", NULL, 0, "node 20 is defined twice" },
		{ "v4 block overrun", NULL, 0, "more elements than announced" },
		{ "unterminated section", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
		    "$Comments\nhello\n", 0, "has no end" },
		{ "NaN coordinate", NULL, 0, "point 1 has a NaN coordinate" },
		/* overflow is not an infinity (issue 19.7) */
		{ "overflowing value", NULL, 0,
		  "$NodeData: expected a number" },
		{ "overflowing tag", NULL, 0, "$Nodes: expected an integer" },
	};

	(void)state;
	t[1].text = edit(gmsh2, "1 0 20 30 40 50", "1 0 20 30 40 60");
	t[2].text = edit(gmsh2, "2.2 0 8", "2.2 1 8");
	t[3].text = edit(gmsh2, "2.2 0 8", "3 0 8");
	t[4].text = edit(gmsh2, "2 2 2 0 1 10 20 30", "2 5 2 0 1 10 20 30 40 "
	    "50 10 20 30");
	t[5].text = edit(gmsh2, "\"pressure\"\n1\n0.0\n3\n0\n1\n5\n",
	    "\"pressure\"\n1\n0.0\n3\n0\n2\n5\n");
	t[5].text = edit(t[5].text, "10 0.5\n20 1.5\n30 -2\n40 300\n50 4.25\n",
	    "10 0.5 0\n20 1.5 0\n30 -2 0\n40 300 0\n50 4.25 0\n");
	t[6].text = edit(gmsh2, "1\n5\n10 0.5", "1\n4\n10 0.5");
	t[6].text = edit(t[6].text, "50 4.25\n", "");
	t[7].text = edit(gmsh2, "$Nodes\n5\n", "$Nodes\n5000\n");
	t[8].text = edit(gmsh2, "1 15 2 0 1 10", "1 77 2 0 1 10");
	t[9].text = edit(gmsh2, "30 0 1 0", "20 0 1 0");
	t[10].text = edit(gmsh4, "3 1 4 2\n", "3 1 4 3\n");
	t[12].text = edit(gmsh2, "20 1 0 0", "20 nan 0 0");
	t[13].text = edit(gmsh2, "40 300\n", "40 -1e999\n");
	t[14].text = edit(gmsh2, "20 1 0 0", "9223372036854775807 1 0 0");
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_tetmesh m;
		vx_err e = { 0, "" };
		size_t n = t[i].cut ? t[i].cut : strlen(t[i].text);
		char *c = malloc(n);
		memcpy(c, t[i].text, n);
		int rc = vx_tetmesh_import_mem(&m, c, n, NULL, NULL, &e);
		if (rc != VX_EDATA || strstr(e.msg, t[i].msg) == NULL)
			fail_msg("%s: rc %d, message '%s'", t[i].what, rc, e.msg);
		assert_null(m.pts);
		free(c);
	}
	/* every truncation of both files is refused */
	const char *files[2] = { gmsh2, gmsh4 };
	for (int f = 0; f < 2; f++)
		for (size_t n = 0; n < strlen(files[f]) - 14; n += 5) {
			vx_tetmesh m;
			vx_err e = { 0, "" };
			char *c = malloc(n + 1);
			memcpy(c, files[f], n);
			assert_int_equal(vx_tetmesh_import_mem(&m, c, n, NULL,
			    NULL, &e), VX_EDATA);
			free(c);
		}
}

/* Oracle: a gzip-compressed file on disk imports like the plain buffer,
 * named after the file; a missing file is VX_ENOINPUT; the imported mesh
 * round-trips through its TETM chunk. */
static void
import_path_gzip(void **state)
{
	char dir[] = "/tmp/vxtetXXXXXX", path[256];
	vx_tetmesh m, b;
	vx_err e = { 0, "" };
	vx_chunk c;

	(void)state;
	assert_non_null(mkdtemp(dir));
	snprintf(path, sizeof path, "%s/fin.grid.vtk.gz", dir);
	gzFile z = gzopen(path, "wb9");
	assert_non_null(z);
	assert_int_equal(gzwrite(z, vtk_ascii, sizeof vtk_ascii - 1),
	    (int)(sizeof vtk_ascii - 1));
	assert_int_equal(gzclose(z), Z_OK);
	assert_int_equal(vx_tetmesh_import(&m, path, NULL, NULL, &e), 0);
	check_two_tets(&m);
	assert_string_equal(m.name, "fin");
	assert_int_equal(vx_tetmesh_to_chunk(&m, 6, &c, &e), 0);
	assert_int_equal(vx_tetmesh_from_chunk(&b, &c, &e), 0);
	assert_memory_equal(b.val, m.val, sizeof vtk_vals);
	assert_string_equal(b.name, "fin");
	assert_string_equal(b.scalar, "dens ity");
	vx_chunk_free(&c);
	vx_tetmesh_free(&b);
	vx_tetmesh_free(&m);
	remove(path);
	assert_int_equal(vx_tetmesh_import(&m, path, NULL, NULL, &e),
	    VX_ENOINPUT);
	rmdir(dir);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(synth_conforming),
		cmocka_unit_test(synth_from_grid),
		cmocka_unit_test(linear_planar),
		cmocka_unit_test(kuhn_exact_aim),
		cmocka_unit_test(closed_surface_parity),
		cmocka_unit_test(jittered_parity),
		cmocka_unit_test(chain_bit_identical),
		cmocka_unit_test(seam_watertight),
		cmocka_unit_test(slivers_and_flat),
		cmocka_unit_test(nearest_multi_iso),
		cmocka_unit_test(chunk_roundtrip),
		cmocka_unit_test(chunk_malformed),
		cmocka_unit_test(leaf_grid_brute),
		cmocka_unit_test(leaf_grid_nearest),
		cmocka_unit_test(leaf_dims_shape),
		cmocka_unit_test(vtk_import_good),
		cmocka_unit_test(vtk_import_bad),
		cmocka_unit_test(gmsh_import_good),
		cmocka_unit_test(gmsh_import_bad),
		cmocka_unit_test(import_path_gzip),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
