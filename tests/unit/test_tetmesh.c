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

#include "vx_tetmesh.h"

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

static int
xing_cmp(const void *a, const void *b)
{
	const xing *x = a, *y = b;
	return (x->t > y->t) - (x->t < y->t);
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
 * and through edge midpoints.  Oracle (parity): the line starts and ends
 * outside (f < iso at the mesh boundary), so over all tets the crossings
 * alternate enter/exit along t, starting with an entry, and their number is
 * even; a line passing within 0.5 of the centre crosses at least twice.
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
					assert_int_equal(n % 2, 0);
					for (size_t i = 0; i < n; i++)
						assert_int_equal(x[i].enter, i % 2 == 0);
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
			assert_int_equal(n % 2, 0);
			for (size_t i = 0; i < n; i++)
				assert_int_equal(x[i].enter, i % 2 == 0);
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
			if (vx_tet_segment(&m, t, &ray, &t0, &f0, &t1, &f1))
				assert_true(isfinite(t0) && isfinite(t1) &&
				    isfinite(f0) && isfinite(f1) && t0 <= t1);
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

/* Oracle (brute force): on a jittered mesh (no coordinate ties), tet t is
 * in leaf l iff its bounding box padded by VX_TETLEAF_PAD leaf widths
 * overlaps the leaf's box; lists ascend; lmin/lmax are the min/max over the
 * listed tets' vertex values; about one leaf per tet. */
static void
leaf_grid_brute(void **state)
{
	int64_t nc[3] = { 4, 3, 5 };
	double lo[3] = { 0, -1, 2 }, hi[3] = { 4, 0.5, 7 }, c[3] = { 2, 0, 4 };
	vx_tetmesh m;
	vx_tetleaf lg;
	vx_err e = { 0, "" };

	(void)state;
	assert_int_equal(vx_tetsynth_grid(&m, nc, lo, hi, 5, bowl_fn, c, &e), 0);
	for (size_t p = 0; p < m.npoint; p++)
		for (int a = 0; a < 3; a++)
			m.pts[3 * p + a] += 0.1 * u01(70 + (uint64_t)a, p);
	assert_int_equal(vx_tetmesh_validate(&m, &e), 0);
	for (double dens = 0.5; dens <= 4; dens *= 2) {
		assert_int_equal(vx_tetleaf_build(&lg, &m, dens, &e), 0);
		double ratio = (double)lg.nleaf / ((double)m.ntet * dens);
		assert_true(ratio > 0.4 && ratio < 2.5);
		for (size_t l = 0; l < lg.nleaf; l++) {
			int64_t ix[3] = { (int64_t)l % lg.dims[0],
			    (int64_t)l / lg.dims[0] % lg.dims[1],
			    (int64_t)l / lg.dims[0] / lg.dims[1] };
			size_t k = lg.off[l];
			float vmin = INFINITY, vmax = -INFINITY;
			for (uint32_t t = 0; t < m.ntet; t++) {
				int ov = 1;
				for (int a = 0; a < 3; a++) {
					double bl = INFINITY, bh = -INFINITY;
					for (int q = 0; q < 4; q++) {
						double x = m.pts[3 * m.tet[4 * t + q] + a];
						bl = fmin(bl, x);
						bh = fmax(bh, x);
					}
					double pad = VX_TETLEAF_PAD * lg.cell[a];
					double l0 = lg.bmin[a] + (double)ix[a] * lg.cell[a];
					double l1 = l0 + lg.cell[a];
					if (ix[a] == 0)
						l0 = -INFINITY;
					if (ix[a] == lg.dims[a] - 1)
						l1 = INFINITY;
					ov &= bl - pad < l1 && bh + pad > l0;
				}
				if (!ov)
					continue;
				assert_true(k < lg.off[l + 1]);
				assert_int_equal(lg.idx[k], t);
				k++;
				for (int q = 0; q < 4; q++) {
					vmin = fminf(vmin, m.val[m.tet[4 * t + q]]);
					vmax = fmaxf(vmax, m.val[m.tet[4 * t + q]]);
				}
			}
			assert_int_equal(k, lg.off[l + 1]);
			float rlo, rhi;
			vx_tetleaf_range(&lg, l, &rlo, &rhi);
			assert_true(rlo == vmin && rhi == vmax);
		}
		assert_true(vx_tetleaf_bytes(&lg) > 0);
		vx_tetleaf_free(&lg);
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
			    nlev % 3, sizes, 1, &e), 0);
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
		cmocka_unit_test(slivers_and_flat),
		cmocka_unit_test(nearest_multi_iso),
		cmocka_unit_test(chunk_roundtrip),
		cmocka_unit_test(chunk_malformed),
		cmocka_unit_test(leaf_grid_brute),
		cmocka_unit_test(leaf_grid_nearest),
		cmocka_unit_test(leaf_dims_shape),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
