/* test_raycast_tet.c: isosurfaces of tet meshes: the multi-hit trace
 * (every crossing once, in order: against brute force over all tets and
 * against the nearest-hit query; parity through shared edges and
 * vertices), the TLEF chunk, and the renderer's mesh path (a split grid
 * covers exactly the pixels the grid renderer covers, a Kuhn-split linear
 * field renders the plane's analytic depth, thread / leaf-grid
 * invariance, transparent-layer parity, shadows through a transparent
 * shell).  Each case names its oracle. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "vx_camera.h"
#include "vx_import.h"
#include "vx_raycast.h"
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

/* 2 - |p - c|^2: closed isosurfaces around c */
static double
bowl_fn(const double p[3], void *ctx)
{
	const double *c = ctx;
	double s = 0;
	for (int a = 0; a < 3; a++)
		s += (p[a] - c[a]) * (p[a] - c[a]);
	return 2 - s;
}

static void
build_lg(vx_tetleaf *lg, const vx_tetmesh *m, double density, int flags,
    int nlev)
{
	int sizes[VX_MACRO_MAXLEV][3];
	vx_err e = { 0, "" };

	vx_macro_default_sizes(VX_F32, nlev > 0 ? nlev : 1, sizes);
	if (vx_tetleaf_build_levels(lg, m, density, flags, nlev,
	    (const int (*)[3])sizes, 1, &e) != 0)
		fail_msg("leaf grid: %s", e.msg);
}

/* the samples of f = |x| + |y| + |z| on [-1,1]^3, n odd: 0 is a sample
 * plane on every axis, so f is affine in every cell and both trilinear
 * interpolation and any tet split reproduce it exactly */
static void
l1_grid(vx_grid *g, int n)
{
	int64_t d[3] = { n, n, n };
	vx_err e = { 0, "" };
	double h = 2.0 / (n - 1);

	assert_int_equal(vx_grid_alloc(g, d, VX_F32, NULL, &e), 0);
	for (int a = 0; a < 3; a++) {
		g->origin[a] = -1;
		g->spacing[a] = h;
	}
	for (int z = 0; z < n; z++)
		for (int y = 0; y < n; y++)
			for (int x = 0; x < n; x++)
				vx_grid_set(g, x, y, z, fabs(-1 + x * h) +
				    fabs(-1 + y * h) + fabs(-1 + z * h));
	vx_grid_range(g);
}

/* test_raycast.c's scene: distance from the centre, or with a floor the
 * smaller of that and the height above z = zf plus r (index = world) */
static void
scene_grid(vx_grid *g, int n, double r, int floor_on, double zf)
{
	int64_t d[3] = { n, n, n };
	vx_err e = { 0, "" };
	double c = (n - 1) / 2.0;

	assert_int_equal(vx_grid_alloc(g, d, VX_F32, NULL, &e), 0);
	for (int z = 0; z < n; z++)
		for (int y = 0; y < n; y++)
			for (int x = 0; x < n; x++) {
				double f = sqrt((x - c) * (x - c) + (y - c) * (y - c) +
				    (z - c) * (z - c));
				if (floor_on && (z - zf) + r < f)
					f = (z - zf) + r;
				vx_grid_set(g, x, y, z, f);
			}
	vx_grid_range(g);
}

static void
split(vx_tetmesh *m, const vx_grid *g, int how)
{
	vx_err e = { 0, "" };

	if (vx_tetsynth_from_grid(m, g, how, &e) != 0)
		fail_msg("split: %s", e.msg);
}

static void
base_scene(vx_scene *s, int w, int h, const double *iso, int niso)
{
	vx_err e = { 0, "" };

	vx_scene_init(s);
	s->camera.w = w;
	s->camera.h = h;
	assert_int_equal(vx_scene_set_iso(s, iso, niso, &e), 0);
}

static void
set_camera(vx_scene *s, vx_projection pr, const double eye[3],
    const double look[3], double fov_or_width)
{
	s->camera.is_auto = 0;
	s->camera.projection = pr;
	memcpy(s->camera.eye, eye, 3 * sizeof *eye);
	memcpy(s->camera.look, look, 3 * sizeof *look);
	s->camera.up[0] = s->camera.up[1] = 0;
	s->camera.up[2] = 1;
	if (pr == VX_PERSPECTIVE)
		s->camera.fov = fov_or_width;
	else
		s->camera.view_width = fov_or_width;
}

typedef struct imgs { vx_image c, d, n; } imgs;

static void
imgs_free(imgs *x)
{
	vx_image_free(&x->c);
	vx_image_free(&x->d);
	vx_image_free(&x->n);
}

/* render_grid / render_mesh: the picture of g (hierarchy built here) or of
 * m through lg, camera resolved over the source's box. */
static void
render_grid(const vx_scene *s0, const vx_grid *g, int threads, imgs *out)
{
	vx_scene s = *s0;
	vx_plan p;
	vx_raycast_opts o;
	vx_macro mc;
	vx_err e = { 0, "" };
	int sizes[VX_MACRO_MAXLEV][3] = { { 4, 4, 4 }, { 2, 2, 2 } };
	double lo[3], hi[3];

	assert_int_equal(vx_macro_build(&mc, g, 2, (const int (*)[3])sizes, 1,
	    &e), 0);
	vx_grid_box(g, lo, hi);
	assert_int_equal(vx_camera_resolve(&s.camera, lo, hi, &e), 0);
	vx_scene_plan_isosurface(&s, &p);
	vx_raycast_opts_init(&o);
	o.nthreads = threads;
	vx_image_init(&out->c);
	vx_image_init(&out->d);
	vx_image_init(&out->n);
	if (vx_raycast_render(&s, &p, g, &mc, NULL, &o, &out->c, &out->d,
	    &out->n, NULL, &e) != 0)
		fail_msg("render: %s", e.msg);
	vx_macro_free(&mc);
}

static void
render_mesh(const vx_scene *s0, const vx_tetmesh *m, const vx_tetleaf *lg,
    int threads, imgs *out, vx_raycast_stats *st)
{
	vx_scene s = *s0;
	vx_plan p;
	vx_raycast_opts o;
	vx_err e = { 0, "" };

	assert_int_equal(vx_camera_resolve(&s.camera, m->bmin, m->bmax, &e), 0);
	vx_scene_plan_isosurface(&s, &p);
	vx_raycast_opts_init(&o);
	o.nthreads = threads;
	vx_image_init(&out->c);
	vx_image_init(&out->d);
	vx_image_init(&out->n);
	if (vx_raycast_render_mesh(&s, &p, m, lg, NULL, &o, &out->c, &out->d,
	    &out->n, st, &e) != 0)
		fail_msg("render: %s", e.msg);
}

static int
same(const vx_image *a, const vx_image *b)
{
	return a->w == b->w && a->h == b->h && a->nc == b->nc &&
	    memcmp(a->px, b->px, vx_image_nvalue(a) * sizeof(float)) == 0;
}

/* ---- the multi-hit trace ---- */

typedef struct xing {
	double t;
	uint32_t tet;
	int iso, enter;
	double n[3];
} xing;

static int
xing_cmp(const void *pa, const void *pb)
{
	const xing *a = pa, *b = pb;

	if (a->t != b->t)
		return (a->t > b->t) - (a->t < b->t);
	if (a->tet != b->tet)
		return (a->tet > b->tet) - (a->tet < b->tet);
	return (a->iso > b->iso) - (a->iso < b->iso);
}

/* brute force: every crossing in [tmin, tmax) of every tet, computed as
 * vx_tet_nearest's contract says (segment, linear interpolation clamped
 * into it, flat tets and non-finite values never), sorted. */
static size_t
brute(const vx_tetmesh *m, const double o[3], const double d[3],
    const double *iso, int niso, double tmin, double tmax, xing *x,
    size_t cap)
{
	vx_tetray r;
	size_t n = 0;

	vx_tetray_init(&r, o, d);
	for (uint32_t t = 0; t < m->ntet; t++) {
		double t0, f0, t1, f1;
		int ok = 1;

		for (int k = 0; k < 4; k++)
			ok &= isfinite(m->val[m->tet[4 * (size_t)t + k]]);
		if (!ok || vx_tetmesh_degenerate(m, t) ||
		    !vx_tet_segment(m, t, &r, &t0, &f0, &t1, &f1))
			continue;
		for (int k = 0; k < niso; k++) {
			int s0 = f0 >= iso[k], s1 = f1 >= iso[k];
			if (s0 == s1)
				continue;
			double th = t0 + (t1 - t0) * ((iso[k] - f0) / (f1 - f0));
			if (!(th >= t0))
				th = t0;
			if (!(th <= t1))
				th = t1;
			if (th < tmin || th >= tmax)
				continue;
			assert_true(n < cap);
			x[n].t = th;
			x[n].tet = t;
			x[n].iso = k;
			x[n].enter = s1;
			n++;
		}
	}
	qsort(x, n, sizeof *x, xing_cmp);
	return n;
}

typedef struct collect { xing *x; size_t n, cap; int stop_after; } collect;

static int
collect_hit(void *ctx, const vx_tethit *h)
{
	collect *c = ctx;

	assert_true(c->n < c->cap);
	c->x[c->n].t = h->t;
	c->x[c->n].tet = h->tet;
	c->x[c->n].iso = h->iso;
	c->x[c->n].enter = h->enter;
	memcpy(c->x[c->n].n, h->n, sizeof h->n);
	c->n++;
	/* the normal is the unit gradient: no NaN, ever */
	assert_true(isfinite(h->n[0]) && isfinite(h->n[1]) &&
	    isfinite(h->n[2]));
	return c->stop_after > 0 && (int)c->n >= c->stop_after;
}

/* compare a trace with brute force; returns the crossing count */
static size_t
check_ray(const vx_tetleaf *lg, const vx_tetmesh *m, const double o[3],
    const double d[3], const double *iso, int niso, double tmin,
    double tmax)
{
	static xing bx[4096], tx[4096];
	collect c = { tx, 0, 4096, 0 };
	size_t nb = brute(m, o, d, iso, niso, tmin, tmax, bx, 4096);

	vx_tetleaf_trace(lg, m, o, d, iso, niso, tmin, tmax, collect_hit, &c,
	    NULL);
	if (c.n != nb)
		fail_msg("trace found %zu crossings, brute force %zu (ray %g %g %g"
		    " dir %g %g %g)", c.n, nb, o[0], o[1], o[2], d[0], d[1], d[2]);
	for (size_t i = 0; i < nb; i++)
		if (memcmp(&tx[i].t, &bx[i].t, sizeof(double)) != 0 ||
		    tx[i].tet != bx[i].tet || tx[i].iso != bx[i].iso ||
		    tx[i].enter != bx[i].enter)
			fail_msg("crossing %zu differs: t %.17g / %.17g tet %u / "
			    "%u", i, tx[i].t, bx[i].t, tx[i].tet, bx[i].tet);
	/* the first one is the nearest-hit query's, normal included */
	vx_tethit h;
	int got = vx_tetleaf_nearest(lg, m, o, d, iso, niso, tmin, tmax, &h,
	    NULL);
	assert_int_equal(got, nb > 0);
	if (got)
		assert_true(h.t == tx[0].t && h.tet == tx[0].tet &&
		    h.iso == tx[0].iso && memcmp(h.n, tx[0].n,
		    sizeof h.n) == 0);
	/* stopping after k crossings hands over exactly the first k */
	if (nb >= 2) {
		collect c2 = { tx, 0, 4096, 1 };
		assert_int_equal(vx_tetleaf_trace(lg, m, o, d, iso, niso, tmin,
		    tmax, collect_hit, &c2, NULL), 1);
		assert_int_equal(c2.n, 1);
	}
	return nb;
}

/* Rays through the shared vertices, edges and faces of Kuhn- and 5-split
 * grids (exact vertex-to-vertex directions, rays lying in face planes and
 * along grid lines) and random rays: the trace hands over exactly the
 * brute-force crossings over all tets, bit for bit and in order, the
 * first one being vx_tetleaf_nearest's (oracle: brute force, no
 * acceleration); a closed surface is crossed an even number of times by a
 * ray that starts and ends outside it (oracle: parity), here 0 or 2 for a
 * ball, 0, 2 or 4 for two nested balls. */
static void
trace_equals_brute_force(void **state)
{
	double c[3] = { 0.5, 0.5, 0.5 };
	double iso2[2] = { 1.86, 1.95 };   /* radii 0.374, 0.224 */
	int64_t nc[3] = { 6, 6, 6 };
	double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
	vx_err e = { 0, "" };

	(void)state;
	for (int how = 5; how <= 6; how++) {
		vx_tetmesh m;
		vx_tetleaf lg;
		size_t nray = 0, nhit = 0;

		assert_int_equal(vx_tetsynth_grid(&m, nc, lo, hi, how, bowl_fn, c,
		    &e), 0);
		build_lg(&lg, &m, 1, 0, 2);
		/* vertex to vertex, from outside the box */
		for (int i = 0; i < 400; i++) {
			double p[3], q[3], o[3], d[3];
			for (int a = 0; a < 3; a++) {
				p[a] = (double)(mix64(7 * i + a) % 7) / 6;
				q[a] = (double)(mix64(1000 + 7 * i + a) % 7) / 6;
				d[a] = q[a] - p[a];
			}
			if (d[0] == 0 && d[1] == 0 && d[2] == 0)
				continue;
			for (int a = 0; a < 3; a++)
				o[a] = p[a] - 4 * d[a];
			size_t k = check_ray(&lg, &m, o, d, iso2, 1, 0, INFINITY);
			assert_true(k % 2 == 0);
			k = check_ray(&lg, &m, o, d, iso2, 2, 0, INFINITY);
			assert_true(k % 2 == 0);
			nray++;
			nhit += k > 0;
		}
		/* along grid lines and in face planes (rays lying in shared
		 * faces), through the surface */
		for (int i = 0; i <= 6; i++)
			for (int j = 0; j <= 6; j++) {
				double o[3] = { i / 6.0, j / 6.0, -1 };
				double d[3] = { 0, 0, 1 };
				double o2[3] = { -1, i / 6.0, (j + 0.37) / 6.0 };
				double d2[3] = { 1, 0, 0.25 };
				size_t k = check_ray(&lg, &m, o, d, iso2, 2, 0,
				    INFINITY);
				assert_true(k % 2 == 0);
				k = check_ray(&lg, &m, o2, d2, iso2, 2, 0, INFINITY);
				assert_true(k % 2 == 0);
				nray += 2;
			}
		/* random rays and random segments [tmin, tmax) */
		for (int i = 0; i < 300; i++) {
			double o[3], d[3];
			for (int a = 0; a < 3; a++) {
				o[a] = -0.5 + 2 * u01(how, 6 * i + a);
				d[a] = u01(how, 6 * i + 3 + a) - 0.5;
			}
			double t0 = u01(how + 9, i), t1 = t0 + 3 * u01(how + 11, i);
			check_ray(&lg, &m, o, d, iso2, 2, t0, t1);
			nray++;
		}
		assert_true(nhit > 20);
		(void)nray;
		vx_tetleaf_free(&lg);
		/* 40 nested surfaces and leaves holding many tets: leaves with
		 * more crossings than one scan keeps (the rescan path) */
		{
			double many[40];
			size_t most = 0;

			for (int k = 0; k < 40; k++)
				many[k] = 1.3 + 0.0175 * k;
			build_lg(&lg, &m, 0.02, 0, 1);
			for (int i = 0; i < 60; i++) {
				double o[3], d[3];
				for (int a = 0; a < 3; a++) {
					o[a] = 0.5 + 1.5 * (u01(how + 20, 6 * i + a) - 0.5);
					d[a] = 0.5 + 0.2 * (u01(how + 21, 6 * i + a) -
					    0.5) - o[a];
				}
				size_t k = check_ray(&lg, &m, o, d, many, 40, 0,
				    INFINITY);
				most = k > most ? k : most;
			}
			assert_true(most > 32);
			vx_tetleaf_free(&lg);
		}
		vx_tetmesh_free(&m);
	}
}

/* Slivers, flat tets and non-finite values: a grid whose interior vertices
 * are moved onto the planes of their neighbours makes zero-volume and
 * near-zero-volume tets, and some vertices get NaN or -Inf; the trace
 * still equals brute force (which skips flat and non-finite tets), and no
 * normal is NaN (oracle: brute force over all tets). */
static void
trace_slivers(void **state)
{
	double c[3] = { 0.5, 0.5, 0.5 }, iso = 1.88;
	int64_t nc[3] = { 5, 5, 5 };
	double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
	vx_err e = { 0, "" };
	vx_tetmesh m;
	vx_tetleaf lg;

	(void)state;
	assert_int_equal(vx_tetsynth_grid(&m, nc, lo, hi, 5, bowl_fn, c, &e), 0);
	/* collapse every third interior vertex onto its x-neighbour's plane
	 * (flat tets), nudge others by 1e-13 (slivers) */
	for (size_t v = 0; v < m.npoint; v++) {
		double *p = m.pts + 3 * v;
		int inner = p[0] > 0 && p[0] < 1 && p[1] > 0 && p[1] < 1 &&
		    p[2] > 0 && p[2] < 1;
		if (!inner)
			continue;
		if (v % 3 == 0)
			p[0] -= 0.2 - 1e-13 * (double)(v % 2);
		else if (v % 3 == 1)
			p[1] += 1e-13;
	}
	/* and non-finite values: those tets never hit */
	for (size_t v = 0; v < m.npoint; v += 17)
		m.val[v] = v % 2 ? NAN : -INFINITY;
	assert_int_equal(vx_tetmesh_validate(&m, &e), 0);
	build_lg(&lg, &m, 1, 0, 2);
	for (int i = 0; i < 300; i++) {
		double o[3], d[3];
		for (int a = 0; a < 3; a++) {
			o[a] = 0.5 + 2 * (u01(3, 6 * i + a) - 0.5) * 3;
			d[a] = 0.5 + 0.3 * (u01(3, 6 * i + 3 + a) - 0.5) - o[a];
		}
		size_t k = check_ray(&lg, &m, o, d, &iso, 1, 0, INFINITY);
		(void)k;
	}
	vx_tetleaf_free(&lg);
	vx_tetmesh_free(&m);
}

/* ---- the TLEF chunk ---- */

/* Round trip: the chunk gives back the same grid (geometry, lists,
 * levels, root), which traces the same crossings; the stream lookup finds
 * it for its mesh and calls it stale once the mesh changes; corrupted
 * chunks are refused with VX_EDATA (oracle: the grid that was written). */
static void
tlef_chunk(void **state)
{
	double c[3] = { 0.5, 0.5, 0.5 }, iso = 1.9;
	int64_t nc[3] = { 4, 5, 3 };
	double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1.5, 0.7 };
	vx_err e = { 0, "" };
	vx_tetmesh m;
	vx_tetleaf lg, lg2;
	vx_tetleaf_ident id;
	vx_chunk ch;
	vx_stream s;
	int status;
	long idx;

	(void)state;
	assert_int_equal(vx_tetsynth_grid(&m, nc, lo, hi, 6, bowl_fn, c, &e), 0);
	vx_tetmesh_set_name(&m, "bowl");
	build_lg(&lg, &m, 1.5, 0, 2);
	for (int z = 0; z <= 1; z++) {
		memset(&ch, 0, sizeof ch);
		assert_int_equal(vx_tetleaf_to_chunk(&lg, &m, z ? 6 : 0, &ch, &e),
		    0);
		assert_int_equal(vx_tetleaf_from_chunk(&lg2, &id, &ch, &e), 0);
		assert_string_equal(id.mesh, "bowl");
		assert_true(id.npoint == m.npoint && id.ntet == m.ntet &&
		    id.crc == vx_tetmesh_crc(&m));
		assert_true(memcmp(lg.dims, lg2.dims, sizeof lg.dims) == 0);
		assert_true(memcmp(lg.bmin, lg2.bmin, sizeof lg.bmin) == 0);
		assert_true(memcmp(lg.cell, lg2.cell, sizeof lg.cell) == 0);
		assert_true(memcmp(lg.off, lg2.off, (lg.nleaf + 1) *
		    sizeof *lg.off) == 0);
		assert_true(memcmp(lg.idx, lg2.idx, lg.off[lg.nleaf] *
		    sizeof *lg.idx) == 0);
		assert_int_equal(lg.mc.nlev, lg2.mc.nlev);
		for (int l = 0; l <= lg.mc.nlev; l++) {
			size_t ncell = (size_t)(lg.mc.dims[l][0] * lg.mc.dims[l][1] *
			    lg.mc.dims[l][2]);
			assert_true(memcmp(lg.mc.mm[l], lg2.mc.mm[l], 2 * ncell *
			    sizeof(float)) == 0);
		}
		assert_true(lg.mc.root[0] == lg2.mc.root[0] &&
		    lg.mc.root[1] == lg2.mc.root[1]);
		for (int i = 0; i < 50; i++) {
			double o[3], d[3];
			for (int a = 0; a < 3; a++) {
				o[a] = -1 + 3 * u01(17, 6 * i + a);
				d[a] = 0.5 - o[a];
			}
			check_ray(&lg2, &m, o, d, &iso, 1, 0, INFINITY);
		}
		vx_tetleaf_free(&lg2);
		vx_chunk_free(&ch);
	}
	/* in a stream: found for its mesh, stale after a change */
	vx_stream_init(&s);
	assert_int_equal(vx_tetmesh_to_chunk(&m, 0, &ch, &e), 0);
	assert_int_equal(vx_stream_append(&s, &ch, &e), 0);
	assert_int_equal(vx_tetleaf_to_chunk(&lg, &m, 0, &ch, &e), 0);
	assert_int_equal(vx_stream_append(&s, &ch, &e), 0);
	assert_int_equal(vx_tetleaf_from_stream(&lg2, &s, &m, &status, &idx,
	    &e), 0);
	assert_int_equal(status, VX_MACRO_LOADED);
	assert_int_equal(idx, 1);
	vx_tetleaf_free(&lg2);
	m.val[3] += 0.25f;
	assert_int_equal(vx_tetleaf_from_stream(&lg2, &s, &m, &status, &idx,
	    &e), 0);
	assert_int_equal(status, VX_MACRO_STALE);
	vx_tetmesh_set_name(&m, "other");
	assert_int_equal(vx_tetleaf_from_stream(&lg2, &s, &m, &status, &idx,
	    &e), 0);
	assert_int_equal(status, VX_MACRO_ABSENT);
	assert_int_equal(idx, -1);
	/* corruptions of a raw chunk's body (offsets at the start, lists
	 * after them, levels last) and header */
	{
		const vx_chunk *good = &s.chunk[1];
		const unsigned char *body;
		size_t bl, boff;
		vx_hdr h;

		vx_hdr_init(&h);
		assert_int_equal(vx_payload_parse(good, &h, &body, &bl, &e), 0);
		vx_hdr_free(&h);
		boff = (size_t)(body - good->data);
		size_t noff = lg.nleaf + 1, nidx = lg.off[lg.nleaf];
		struct { size_t at; uint32_t v; const char *why; } bad[] = {
			{ 0, 1, "offsets must run from 0" },
			{ 4 * 2, 0xffffff, "decrease" },
			{ 4 * (noff + 1), (uint32_t)m.ntet, "out of range or out "
			    "of order" },
			{ 4 * (noff + nidx), 0x7fc00000u, "NaN" },
		};
		for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
			vx_chunk cc = *good;
			unsigned char *p = malloc(good->len);
			memcpy(p, good->data, good->len);
			vx_put_le32(p + boff + bad[i].at, bad[i].v);
			cc.data = p;
			assert_int_equal(vx_tetleaf_from_chunk(&lg2, NULL, &cc, &e),
			    VX_EDATA);
			if (strstr(e.msg, bad[i].why) == NULL)
				fail_msg("case %zu: '%s' lacks '%s'", i, e.msg,
				    bad[i].why);
			/* a short body */
			cc.len = good->len - 4;
			assert_int_equal(vx_tetleaf_from_chunk(&lg2, NULL, &cc, &e),
			    VX_EDATA);
			free(p);
		}
		/* header words out of range */
		static const char *const hdr_bad[] = {
			"leaf-dims: 0 1 1", "leaf-dims: 2000000 1 1", "levels: 9",
			"leaf-size: 0 1 1", "entries: -1", "mesh-crc32: 12",
		};
		for (size_t i = 0; i < sizeof hdr_bad / sizeof hdr_bad[0]; i++) {
			vx_hdr hh;
			const unsigned char *b;
			size_t n;
			vx_chunk cc;
			char key[32];
			const char *colon = strchr(hdr_bad[i], ':');

			vx_hdr_init(&hh);
			assert_int_equal(vx_payload_parse(good, &hh, &b, &n, &e), 0);
			memcpy(key, hdr_bad[i], (size_t)(colon - hdr_bad[i]));
			key[colon - hdr_bad[i]] = '\0';
			assert_int_equal(vx_hdr_set(&hh, key, &e, "%s", colon + 2),
			    0);
			memset(&cc, 0, sizeof cc);
			assert_int_equal(vx_payload_make(&cc, VX_CHUNK_TETLEAF, &hh,
			    b, n, 0, &e), 0);
			assert_int_equal(vx_tetleaf_from_chunk(&lg2, NULL, &cc, &e),
			    VX_EDATA);
			vx_chunk_free(&cc);
			vx_hdr_free(&hh);
		}
	}
	vx_stream_free(&s);
	vx_tetleaf_free(&lg);
	vx_tetmesh_free(&m);
}

/* ---- the renderer ---- */

/* compare_coverage: count pixels whose coverage differs between a and b,
 * and of those the ones on a's outline (a 4-neighbour with the other
 * coverage in a). */
static void
compare_coverage(const vx_image *a, const vx_image *b, int *ndiff,
    int *noutline_diff, int *noutline)
{
	*ndiff = *noutline_diff = *noutline = 0;
	for (int y = 0; y < a->h; y++)
		for (int x = 0; x < a->w; x++) {
			int ca = vx_image_get(a, x, y, 3) > 0;
			int cb = vx_image_get(b, x, y, 3) > 0;
			int edge = 0;
			static const int dx[4] = { 1, -1, 0, 0 },
			    dy[4] = { 0, 0, 1, -1 };
			for (int k = 0; k < 4; k++) {
				int u = x + dx[k], v = y + dy[k];
				if (u >= 0 && v >= 0 && u < a->w && v < a->h &&
				    (vx_image_get(a, u, v, 3) > 0) != ca)
					edge = 1;
			}
			*noutline += edge;
			if (ca != cb) {
				(*ndiff)++;
				*noutline_diff += edge;
			}
		}
}

/* An octahedron |x| + |y| + |z| = 0.7 sampled on a grid with 0 on a
 * sample plane: the field is affine in every cell, so trilinear
 * interpolation (the grid renderer) and the 5- and 6-tet splits (the mesh
 * renderer) describe the same surface.  Coverage agrees pixel for pixel,
 * depth to 1e-9 and normals to 1e-6, in perspective and orthographic views
 * (oracle: the grid renderer on the same samples). */
static void
split_grid_same_picture(void **state)
{
	double iso[2] = { 0.7, 1.3 };
	vx_grid g;
	vx_err e = { 0, "" };

	(void)state;
	l1_grid(&g, 17);
	for (int view = 0; view < 2; view++) {
		vx_scene s;
		imgs gi;

		base_scene(&s, 72, 60, iso, view == 0 ? 1 : 2);
		if (view == 1) {
			/* two surfaces, the outer one transparent */
			s.surface[1].m.opacity = 0.4;
			s.camera.projection = VX_ORTHOGRAPHIC;
		}
		assert_int_equal(vx_scene_set_view(&s, VX_VIEW_ANGLES,
		    view ? -50 : 30, view ? 35 : 20, &e), 0);
		render_grid(&s, &g, 2, &gi);
		for (int how = 5; how <= 6; how++) {
			vx_tetmesh m;
			vx_tetleaf lg;
			imgs mi;
			int nd, nod, no, ncov = 0;

			split(&m, &g, how);
			build_lg(&lg, &m, 1, 0, 2);
			render_mesh(&s, &m, &lg, 2, &mi, NULL);
			compare_coverage(&gi.c, &mi.c, &nd, &nod, &no);
			if (nd != 0)
				fail_msg("view %d split %d: %d pixels differ in "
				    "coverage", view, how, nd);
			for (int y = 0; y < 60; y++)
				for (int x = 0; x < 72; x++) {
					double dg = vx_image_get(&gi.d, x, y, 0);
					double dm = vx_image_get(&mi.d, x, y, 0);
					double ag = vx_image_get(&gi.c, x, y, 3);
					double am = vx_image_get(&mi.c, x, y, 3);
					assert_true(fabs(ag - am) < 1e-6);
					if (isinf(dg)) {
						assert_true(isinf(dm));
						continue;
					}
					ncov++;
					assert_true(fabs(dg - dm) <= 1e-6 * dg);
					double dot = 0;
					for (int a = 0; a < 3; a++)
						dot += vx_image_get(&gi.n, x, y, a) *
						    vx_image_get(&mi.n, x, y, a);
					assert_true(dot > 1 - 1e-6);
				}
			if (ncov < 150)
				fail_msg("view %d split %d: %d covered", view, how,
				    ncov);
			imgs_free(&mi);
			vx_tetleaf_free(&lg);
			vx_tetmesh_free(&m);
		}
		imgs_free(&gi);
	}
	vx_grid_free(&g);
}

/* A sampled sphere (distance field, 24^3, radius 7 voxels): trilinear and
 * piecewise-linear interpolation differ inside cells by at most h^2/8
 * times the field's second derivative (1/r), under 0.02 voxel here, while
 * a pixel spans 0.5 voxel: the silhouettes lie within 0.04 pixel of each
 * other, so coverage may differ only at pixels whose centre is that close
 * to the grid's outline, which all have a 4-neighbour of the other
 * coverage (oracle: the grid renderer on the same samples; tolerance: the
 * interpolation bound, asserted as "every differing pixel is an outline
 * pixel and they are at most 1/8 of the outline").  In practice: 0. */
static void
split_grid_same_silhouette(void **state)
{
	double iso = 7;
	vx_grid g;
	vx_err e = { 0, "" };
	vx_scene s;
	imgs gi;

	(void)state;
	scene_grid(&g, 24, 0, 0, 0);
	base_scene(&s, 64, 64, &iso, 1);
	assert_int_equal(vx_scene_set_view(&s, VX_VIEW_ANGLES, 30, 20, &e), 0);
	render_grid(&s, &g, 2, &gi);
	for (int how = 5; how <= 6; how++) {
		vx_tetmesh m;
		vx_tetleaf lg;
		imgs mi;
		int nd, nod, no;

		split(&m, &g, how);
		build_lg(&lg, &m, 1, 0, 2);
		render_mesh(&s, &m, &lg, 2, &mi, NULL);
		compare_coverage(&gi.c, &mi.c, &nd, &nod, &no);
		assert_int_equal(nd, nod);
		assert_true(8 * nd <= no);
		assert_true(no > 50);
		imgs_free(&mi);
		vx_tetleaf_free(&lg);
		vx_tetmesh_free(&m);
	}
	imgs_free(&gi);
	vx_grid_free(&g);
}

/* A linear field x + 2y + 3z - 1 on the Kuhn-split unit cube and on 3x3x3
 * grids split 5 and 6: the isosurface 1.5 is the plane x + 2y + 3z = 2.5,
 * exactly.  Every pixel whose ray meets the plane inside the box (more than
 * 1e-9 from its faces) is covered, with the analytic depth (to the depth
 * image's float precision) and the plane's normal; every ray meeting it
 * outside misses (oracle: ray/plane intersection by hand).  No holes at
 * the shared edges and vertices the plane passes through. */
static void
kuhn_plane_depth(void **state)
{
	lin f = { { 1, 2, 3 }, -1 };
	double iso = 1.5, lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
	double an[3] = { 1 / sqrt(14.0), 2 / sqrt(14.0), 3 / sqrt(14.0) };
	vx_err e = { 0, "" };

	(void)state;
	for (int kind = 0; kind < 3; kind++) {
		vx_tetmesh m;
		vx_tetleaf lg;
		int64_t nc[3] = { 3, 3, 3 };

		if (kind == 0)
			assert_int_equal(vx_tetsynth_cube(&m, lo, hi, lin_fn, &f, &e),
			    0);
		else
			assert_int_equal(vx_tetsynth_grid(&m, nc, lo, hi,
			    kind == 1 ? 5 : 6, lin_fn, &f, &e), 0);
		build_lg(&lg, &m, 1, 0, 2);
		for (int pr = 0; pr < 2; pr++) {
			vx_scene s;
			imgs mi;
			double eye[3] = { 2.6, -1.7, 2.2 }, look[3] = { 0.5, 0.45,
			    0.55 };
			int ncov = 0;

			base_scene(&s, 61, 53, &iso, 1);
			set_camera(&s, pr ? VX_ORTHOGRAPHIC : VX_PERSPECTIVE, eye,
			    look, pr ? 1.9 : 38);
			render_mesh(&s, &m, &lg, 2, &mi, NULL);
			vx_scene sr = s;
			assert_int_equal(vx_camera_resolve(&sr.camera, m.bmin,
			    m.bmax, &e), 0);
			for (int y = 0; y < 53; y++)
				for (int x = 0; x < 61; x++) {
					double o[3], d[3], ad = 0, ao = 0, p[3];
					vx_camera_ray(&sr.camera, x + 0.5, y + 0.5, o, d);
					for (int a = 0; a < 3; a++) {
						ad += f.a[a] * d[a];
						ao += f.a[a] * o[a];
					}
					double t = (iso - f.b - ao) / ad;
					int in = t > 0, out = !(t > 0);
					for (int a = 0; a < 3; a++) {
						p[a] = o[a] + t * d[a];
						in &= p[a] > 1e-9 && p[a] < 1 - 1e-9;
						out |= p[a] < -1e-9 || p[a] > 1 + 1e-9;
					}
					double dep = vx_image_get(&mi.d, x, y, 0);
					if (in) {
						ncov++;
						if (!(fabs(dep - t) <= 2e-7 * t))
							fail_msg("kind %d proj %d pixel %d %d: "
							    "depth %.9g, plane %.9g", kind, pr,
							    x, y, dep, t);
						double sg = ad > 0 ? -1 : 1;
						for (int a = 0; a < 3; a++)
							assert_true(fabs(vx_image_get(&mi.n, x,
							    y, a) - sg * an[a]) < 1e-6);
						assert_true(vx_image_get(&mi.c, x, y, 3) == 1);
					} else if (out) {
						assert_true(isinf(dep));
						assert_true(vx_image_get(&mi.c, x, y, 3) == 0);
					}
				}
			if (ncov < 100)
				fail_msg("kind %d proj %d: %d covered", kind, pr,
				    ncov);
			imgs_free(&mi);
		}
		vx_tetleaf_free(&lg);
		vx_tetmesh_free(&m);
	}
}

/* The same mesh picture (a transparent sphere over a floor, a shadowing
 * light, two surfaces) for 1 and 3 threads, with and without macrocell
 * levels, for leaf grids of 0.3, 1 and 3 leaves per tet and with
 * bounding-box lists: bit for bit in color, depth and normal (oracle: the
 * single-threaded render; the trace reports the same crossings whatever
 * grid carries them). */
static void
mesh_invariance(void **state)
{
	double iso[2] = { 6, 3 };
	vx_grid g;
	vx_tetmesh m;
	vx_err e = { 0, "" };
	vx_scene s;
	vx_tetleaf lg;
	imgs ref;

	(void)state;
	scene_grid(&g, 20, 6, 1, 3);
	split(&m, &g, 5);
	base_scene(&s, 48, 40, iso, 2);
	s.surface[0].m.opacity = 0.5;
	assert_int_equal(vx_scene_apply(&s, "light directional direction 0.3 "
	    "0.2 -1 shadows on", &e), 0);
	assert_int_equal(vx_scene_set_view(&s, VX_VIEW_ANGLES, 20, 35, &e), 0);
	build_lg(&lg, &m, 1, 0, 2);
	render_mesh(&s, &m, &lg, 1, &ref, NULL);
	vx_tetleaf_free(&lg);
	struct { int th, nlev, flags; double dens; } t[] = {
		{ 3, 2, 0, 1 }, { 2, 0, 0, 1 }, { 2, 2, 0, 0.3 }, { 2, 1, 0, 3 },
		{ 1, 2, VX_TETLEAF_BBOX, 1 },
	};
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		imgs x;

		build_lg(&lg, &m, t[i].dens, t[i].flags, t[i].nlev);
		render_mesh(&s, &m, &lg, t[i].th, &x, NULL);
		if (!same(&ref.c, &x.c) || !same(&ref.d, &x.d) ||
		    !same(&ref.n, &x.n))
			fail_msg("configuration %zu differs from the reference", i);
		imgs_free(&x);
		vx_tetleaf_free(&lg);
	}
	imgs_free(&ref);
	vx_tetmesh_free(&m);
	vx_grid_free(&g);
}

/* Transparent layers see each crossing once: a closed sphere of opacity
 * a = 0.3, seen through: every pixel's coverage is 1 - (1 - a)^k for an
 * even k (0 outside, 2 through it; never odd: no hole, no double hit),
 * and the centre pixel's k is 2 (oracle: front-to-back compositing and
 * the parity of a closed surface).  Also with the grid's lines in the
 * picture's pixel centres (axis-aligned orthographic view). */
static void
transparent_parity(void **state)
{
	double iso = 6.5, a = 0.3;
	vx_grid g;
	vx_err e = { 0, "" };

	(void)state;
	scene_grid(&g, 19, 0, 0, 0);
	for (int how = 5; how <= 6; how++) {
		vx_tetmesh m;
		vx_tetleaf lg;

		split(&m, &g, how);
		build_lg(&lg, &m, 1, 0, 2);
		for (int view = 0; view < 2; view++) {
			vx_scene s;
			imgs mi;
			int n2 = 0;

			base_scene(&s, 73, 73, &iso, 1);
			s.surface[0].m.opacity = a;
			if (view == 0)
				assert_int_equal(vx_scene_set_view(&s,
				    VX_VIEW_ANGLES, 25, 15, &e), 0);
			else {
				/* 73 pixels over 18 voxels: every 4th pixel
				 * centre is on a grid line */
				double eye[3] = { 9, -40, 9 }, look[3] = { 9, 9, 9 };
				set_camera(&s, VX_ORTHOGRAPHIC, eye, look, 18.0 *
				    73 / 72);
			}
			render_mesh(&s, &m, &lg, 2, &mi, NULL);
			for (int y = 0; y < 73; y++)
				for (int x = 0; x < 73; x++) {
					double al = vx_image_get(&mi.c, x, y, 3);
					double T = 1 - al;
					int k = T > 0 ? (int)floor(log(T) / log(1 - a) +
					    0.5) : 99;
					if (!(fabs(al - (1 - pow(1 - a, k))) < 1e-5) ||
					    k % 2 != 0)
						fail_msg("split %d view %d pixel %d %d: "
						    "coverage %.7f is not 1-(1-a)^even",
						    how, view, x, y, al);
					n2 += k == 2;
				}
			assert_true(fabs(vx_image_get(&mi.c, 36, 36, 3) -
			    (1 - (1 - a) * (1 - a))) < 1e-6);
			assert_true(n2 > 500);
			imgs_free(&mi);
		}
		vx_tetleaf_free(&lg);
		vx_tetmesh_free(&m);
	}
	vx_grid_free(&g);
	/* An isovalue equal to a vertex value where the field only touches
	 * it: -(|x| + |y| + |z|) peaks at 0 at the centre vertex; with iso 0
	 * the "surface" is that point.  Rays through it, or through the
	 * edges and vertices around it (orthographic, pixel centres on the
	 * grid), see an even number of crossings (the documented policy:
	 * f >= iso is inside), never one. */
	l1_grid(&g, 9);
	for (size_t i = 0; i < 9 * 9 * 9; i++)
		((float *)g.data)[i] = -((float *)g.data)[i];
	vx_grid_range(&g);
	for (int how = 5; how <= 6; how++) {
		vx_tetmesh m;
		vx_tetleaf lg;
		vx_scene s;
		imgs mi;
		double zero = 0, eye[3] = { 0, -5, 0 }, look[3] = { 0, 0, 0 };

		split(&m, &g, how);
		build_lg(&lg, &m, 1, 0, 2);
		base_scene(&s, 33, 33, &zero, 1);
		s.surface[0].m.opacity = a;
		/* 33 pixels over 2.0625: pixel centres every 1/16, the grid's
		 * lines every 1/4, the peak at the centre pixel */
		set_camera(&s, VX_ORTHOGRAPHIC, eye, look, 2.0625);
		render_mesh(&s, &m, &lg, 2, &mi, NULL);
		for (int y = 0; y < 33; y++)
			for (int x = 0; x < 33; x++) {
				double al = vx_image_get(&mi.c, x, y, 3);
				if (!(al == 0 || fabs(al - (1 - (1 - a) * (1 - a))) <
				    1e-6))
					fail_msg("touching vertex, split %d pixel %d %d: "
					    "coverage %.7f", how, x, y, al);
			}
		imgs_free(&mi);
		vx_tetleaf_free(&lg);
		vx_tetmesh_free(&m);
	}
	vx_grid_free(&g);
}

/* Shadow rays see each crossing once: a floor under a sphere, both the
 * isosurface 6 of one field, opacity a, lit straight from above.  A floor
 * point under the sphere gets light through two crossings of the sphere,
 * so its radiance is a * (ambient + (1 - a)^2 kd) * albedo; far from the
 * sphere a * (ambient + kd) * albedo (oracle: the shading and compositing
 * formulas by hand; the floor is the plane z = 3 and its normal exact). */
static void
shadow_through_shell(void **state)
{
	double iso = 6, a = 0.4, zf = 3, cc = 12.5;
	vx_grid g;
	vx_tetmesh m;
	vx_tetleaf lg;
	vx_err e = { 0, "" };
	vx_scene s;
	imgs mi;

	(void)state;
	scene_grid(&g, 26, 6, 1, zf);
	split(&m, &g, 5);
	build_lg(&lg, &m, 1, 0, 2);
	base_scene(&s, 96, 96, &iso, 1);
	s.surface[0].m.ks = 0;
	s.surface[0].m.kd = 1;
	s.surface[0].m.opacity = a;
	s.surface[0].m.color[0] = s.surface[0].m.color[1] =
	    s.surface[0].m.color[2] = 0.5;
	s.ambient_intensity = 0.1;
	s.ambient[0] = s.ambient[1] = s.ambient[2] = 1;
	assert_int_equal(vx_scene_apply(&s, "light directional direction 0 0 -1 "
	    "shadows on", &e), 0);
	assert_int_equal(vx_scene_set_view(&s, VX_VIEW_ANGLES, 0, 60, &e), 0);
	render_mesh(&s, &m, &lg, 2, &mi, NULL);
	vx_scene sr = s;
	assert_int_equal(vx_camera_resolve(&sr.camera, m.bmin, m.bmax, &e), 0);
	double under[3] = { cc, cc + 2, zf }, far[3] = { cc, cc + 11, zf };
	double px, py, dep;
	assert_true(vx_camera_project(&sr.camera, under, &px, &py, &dep));
	double v_under = vx_image_get(&mi.c, (int)px, (int)py, 0);
	assert_true(vx_camera_project(&sr.camera, far, &px, &py, &dep));
	double v_far = vx_image_get(&mi.c, (int)px, (int)py, 0);
	double want_under = a * (0.1 + (1 - a) * (1 - a)) * 0.5;
	double want_far = a * (0.1 + 1) * 0.5;
	if (!(fabs(v_under - want_under) < 1e-4) ||
	    !(fabs(v_far - want_far) < 1e-4))
		fail_msg("under %.6f (want %.6f), far %.6f (want %.6f)", v_under,
		    want_under, v_far, want_far);
	imgs_free(&mi);
	vx_tetleaf_free(&lg);
	vx_tetmesh_free(&m);
	vx_grid_free(&g);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(trace_equals_brute_force),
		cmocka_unit_test(trace_slivers),
		cmocka_unit_test(tlef_chunk),
		cmocka_unit_test(split_grid_same_picture),
		cmocka_unit_test(split_grid_same_silhouette),
		cmocka_unit_test(kuhn_plane_depth),
		cmocka_unit_test(mesh_invariance),
		cmocka_unit_test(transparent_parity),
		cmocka_unit_test(shadow_through_shell),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
