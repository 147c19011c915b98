/* test_raycast.c: the isosurface renderer as a whole: depth against the
 * geometry, thread count / hierarchy / bricking invariance bit for bit,
 * non-finite voxels, shadows and transparent layers against hand-worked
 * values. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "vx_camera.h"
#include "vx_raycast.h"

/* A sphere (distance from c) and, optionally, a floor: the field is the
 * smaller of the distance to the centre and the height above z = zf plus
 * r, so the isosurface r is the sphere and the plane z = zf. */
static void
make_scene_volume(vx_grid *g, int n, const char *layout, double r,
    int floor_on, double zf)
{
	int64_t d[3] = { n, n, n };
	vx_err e = { 0, "" };
	double c = (n - 1) / 2.0;

	assert_int_equal(vx_grid_alloc(g, d, VX_F32, layout, &e), 0);
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
base_scene(vx_scene *s, int w, int h, double iso)
{
	vx_err e = { 0, "" };

	vx_scene_init(s);
	s->camera.w = w;
	s->camera.h = h;
	assert_int_equal(vx_scene_set_iso(s, &iso, 1, &e), 0);
}

static void
render(const vx_scene *s0, const vx_grid *g, const vx_macro *m, int threads,
    int flat, vx_image *color, vx_image *depth, vx_image *normal)
{
	vx_scene s = *s0;
	vx_plan p;
	vx_raycast_opts o;
	vx_err e = { 0, "" };
	double lo[3], hi[3];

	vx_grid_box(g, lo, hi);
	assert_int_equal(vx_camera_resolve(&s.camera, lo, hi, &e), 0);
	vx_scene_plan_isosurface(&s, &p);
	vx_raycast_opts_init(&o);
	o.nthreads = threads;
	o.flat = flat;
	vx_image_init(color);
	vx_image_init(depth);
	vx_image_init(normal);
	if (vx_raycast_render(&s, &p, g, m, NULL, &o, color, depth, normal, NULL,
	    &e) != 0)
		fail_msg("render: %s", e.msg);
}

static void
build(vx_macro *m, const vx_grid *g)
{
	int sizes[VX_MACRO_MAXLEV][3] = { { 4, 4, 4 }, { 2, 2, 2 } };
	vx_err e = { 0, "" };

	assert_int_equal(vx_macro_build(m, g, 2, (const int (*)[3])sizes, 1,
	    &e), 0);
}

static int
same(const vx_image *a, const vx_image *b)
{
	return a->w == b->w && a->h == b->h && a->nc == b->nc &&
	    memcmp(a->px, b->px, vx_image_nvalue(a) * sizeof(float)) == 0;
}

static void
free3(vx_image *a, vx_image *b, vx_image *c)
{
	vx_image_free(a);
	vx_image_free(b);
	vx_image_free(c);
}

/* render_into: colour, depth and normals of s over g, m with options o
 * into c, dd, nn (initialized here), counters into *st */
static void
render_into(const vx_scene *s, const vx_plan *p, const vx_grid *g,
    const vx_macro *m, const vx_raycast_opts *o, vx_image *c, vx_image *dd,
    vx_image *nn, vx_raycast_stats *st)
{
	vx_err e = { 0, "" };

	vx_image_init(c);
	vx_image_init(dd);
	vx_image_init(nn);
	memset(st, 0, sizeof *st);
	assert_int_equal(vx_raycast_render(s, p, g, m, NULL, o, c, dd, nn, st,
	    &e), 0);
}

/* same_render: render k is render 0's pictures and cell work */
static void
same_render(const vx_image *c, const vx_image *dd, const vx_image *nn,
    const vx_raycast_stats *st, int k)
{
	assert_true(same(&c[0], &c[k]));
	assert_true(same(&dd[0], &dd[k]));
	assert_true(same(&nn[0], &nn[k]));
	assert_int_equal(st[0].cells, st[k].cells);
	assert_int_equal(st[0].roots, st[k].roots);
}

/* sine_field: g = sin(f0 x) sin(f1 y) sin(f2 z) over d samples (a field of
 * many small closed surfaces about 0), f32, and m its hierarchy of 16^3
 * macrocells under l2^3 of them */
static void
sine_field(vx_grid *g, vx_macro *m, const int64_t d[3], const double f[3],
    int l2)
{
	int sizes[VX_MACRO_MAXLEV][3] = { { 16, 16, 16 }, { l2, l2, l2 } };
	double *sx = malloc((size_t)(d[0] + d[1] + d[2]) * sizeof *sx);
	double *sy = sx + d[0], *sz = sy + d[1];
	vx_err e = { 0, "" };

	assert_non_null(sx);
	assert_int_equal(vx_grid_alloc(g, d, VX_F32, NULL, &e), 0);
	for (int64_t i = 0; i < d[0]; i++)
		sx[i] = sin(f[0] * (double)i);
	for (int64_t i = 0; i < d[1]; i++)
		sy[i] = sin(f[1] * (double)i);
	for (int64_t i = 0; i < d[2]; i++)
		sz[i] = sin(f[2] * (double)i);
	for (int64_t z = 0; z < d[2]; z++)
		for (int64_t y = 0; y < d[1]; y++)
			for (int64_t x = 0; x < d[0]; x++)
				vx_grid_set(g, x, y, z, sx[x] * sy[y] * sz[z]);
	free(sx);
	vx_grid_range(g);
	assert_int_equal(vx_macro_build(m, g, 2, (const int (*)[3])sizes, 1,
	    &e), 0);
}

/* look_from: an explicit perspective camera at eye looking at look, z up */
static void
look_from(vx_scene *s, const double eye[3], const double look[3],
    double fov)
{
	static const double up[3] = { 0, 0, 1 };

	s->camera.is_auto = 0;
	s->camera.projection = VX_PERSPECTIVE;
	memcpy(s->camera.eye, eye, sizeof s->camera.eye);
	memcpy(s->camera.look, look, sizeof s->camera.look);
	memcpy(s->camera.up, up, sizeof s->camera.up);
	s->camera.fov = fov;
}

/* Depth of the centre pixel: an explicit camera on the +y axis looking at
 * the centre sees the sphere at distance |eye - c| - r (oracle: geometry;
 * the trilinear isosurface of a sampled distance field lies within 0.05
 * voxel of the sphere at this radius). */
static void
depth_matches_geometry(void **state)
{
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_image c, d, n;
	double cc = 15.5;

	(void)state;
	make_scene_volume(&g, 32, NULL, 9, 0, 0);
	build(&m, &g);
	base_scene(&s, 65, 65, 9);
	look_from(&s, (const double[3]){ cc, cc + 60, cc },
	    (const double[3]){ cc, cc, cc }, 30);
	render(&s, &g, &m, 2, 0, &c, &d, &n);
	double dep = vx_image_get(&d, 32, 32, 0);
	assert_true(fabs(dep - (60 - 9)) < 0.05);
	/* the normal there faces the eye: (0, 1, 0) */
	assert_true(vx_image_get(&n, 32, 32, 1) > 0.999);
	/* a corner pixel misses: depth +Inf, alpha 0 */
	assert_true(isinf(vx_image_get(&d, 0, 0, 0)));
	assert_true(vx_image_get(&c, 0, 0, 3) == 0);
	assert_true(vx_image_get(&c, 32, 32, 3) == 1);
	free3(&c, &d, &n);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* 1 thread = 3 threads, hierarchical = flat, bricked = linear, bit for
 * bit in color, depth and normal (oracle: the single-threaded flat render
 * of the linear volume), with a shadow-casting light and two surfaces. */
static void
invariance(void **state)
{
	vx_grid g, b;
	vx_macro m, mb;
	vx_scene s;
	vx_err e = { 0, "" };
	vx_image c1, d1, n1, c2, d2, n2;
	double iso[2] = { 9, 4 };

	(void)state;
	make_scene_volume(&g, 29, NULL, 9, 1, 6);
	make_scene_volume(&b, 29, "bricked 4x2x2 4x4x4", 9, 1, 6);
	build(&m, &g);
	build(&mb, &b);
	base_scene(&s, 48, 40, 9);
	assert_int_equal(vx_scene_set_iso(&s, iso, 2, &e), 0);
	s.surface[0].m.opacity = 0.5;
	assert_int_equal(vx_scene_apply(&s, "light directional direction 0.3 0.2 -1",
	    &e), 0);
	render(&s, &g, NULL, 1, 1, &c1, &d1, &n1);
	struct { const vx_grid *g; const vx_macro *m; int th, flat; } t[] = {
		{ &g, &m, 1, 0 }, { &g, &m, 3, 0 }, { &g, NULL, 3, 1 },
		{ &b, &mb, 2, 0 }, { &b, NULL, 1, 1 },
	};
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		render(&s, t[i].g, t[i].m, t[i].th, t[i].flat, &c2, &d2, &n2);
		if (!same(&c1, &c2) || !same(&d1, &d2) || !same(&n1, &n2))
			fail_msg("configuration %zu differs from the reference", i);
		free3(&c2, &d2, &n2);
	}
	free3(&c1, &d1, &n1);
	vx_macro_free(&m);
	vx_macro_free(&mb);
	vx_grid_free(&g);
	vx_grid_free(&b);
}

/* NaN and infinite voxels: no NaN anywhere in the color, depth or normal
 * images (oracle: the policy: cells with non-finite corners have no
 * surface). */
static void
nonfinite_pixels(void **state)
{
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_image c, d, n;

	(void)state;
	make_scene_volume(&g, 24, NULL, 8, 0, 0);
	for (int k = 0; k < 24; k++) {
		vx_grid_set(&g, k, 12, 12, NAN);
		vx_grid_set(&g, 12, k, 5, INFINITY);
		vx_grid_set(&g, 5, 12, k, -INFINITY);
	}
	vx_grid_range(&g);
	build(&m, &g);
	base_scene(&s, 40, 40, 8);
	render(&s, &g, &m, 2, 0, &c, &d, &n);
	for (size_t i = 0; i < vx_image_nvalue(&c); i++)
		assert_false(isnan(c.px[i]));
	for (size_t i = 0; i < vx_image_nvalue(&d); i++)
		assert_false(isnan(d.px[i]));
	for (size_t i = 0; i < vx_image_nvalue(&n); i++)
		assert_false(isnan(n.px[i]));
	free3(&c, &d, &n);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* Shadows: a sphere above a floor, lit straight from above.  The floor
 * point under the sphere's centre receives only the ambient term; a floor
 * point far from it gets ambient + kd * albedo * 1 (oracle: the shading
 * formula with n = l = (0,0,1)).  With the shadows effect off both get the
 * full light. */
static void
shadow_under_sphere(void **state)
{
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_err e = { 0, "" };
	vx_image c, d, n;
	double zf = 4, cc = 15.5, lo[3], hi[3];

	(void)state;
	make_scene_volume(&g, 32, NULL, 6, 1, zf);
	build(&m, &g);
	for (int fx = 0; fx < 2; fx++) {
		base_scene(&s, 96, 96, 6);
		s.surface[0].m.ks = 0;
		s.surface[0].m.kd = 1;
		s.surface[0].m.color[0] = s.surface[0].m.color[1] =
		    s.surface[0].m.color[2] = 0.5;
		s.ambient_intensity = 0.1;
		s.ambient[0] = s.ambient[1] = s.ambient[2] = 1;
		assert_int_equal(vx_scene_apply(&s,
		    "light directional direction 0 0 -1 shadows on", &e), 0);
		if (fx == 1)
			assert_int_equal(vx_scene_apply(&s, "effects -shadows", &e), 0);
		/* from high above, a little tilted, so the floor under the
		 * sphere is not hidden by it */
		assert_int_equal(vx_scene_set_view(&s, VX_VIEW_ANGLES, 0, 60, &e), 0);
		render(&s, &g, &m, 2, 0, &c, &d, &n);
		vx_scene sr = s;
		vx_grid_box(&g, lo, hi);
		assert_int_equal(vx_camera_resolve(&sr.camera, lo, hi, &e), 0);
		double under[3] = { cc, cc + 3, zf }, far[3] = { cc, cc + 12, zf };
		double px, py, dep;
		assert_true(vx_camera_project(&sr.camera, under, &px, &py, &dep));
		double v_under = vx_image_get(&c, (int)px, (int)py, 0);
		assert_true(vx_camera_project(&sr.camera, far, &px, &py, &dep));
		double v_far = vx_image_get(&c, (int)px, (int)py, 0);
		if (fx == 0) {
			assert_true(fabs(v_under - 0.05) < 1e-3);  /* ambient only */
			assert_true(fabs(v_far - 0.55) < 1e-2);
		} else {
			assert_true(fabs(v_under - 0.55) < 1e-2);
			assert_true(fabs(v_far - 0.55) < 1e-2);
		}
		free3(&c, &d, &n);
	}
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* Transparent layers: a shell of opacity a seen where the ray passes
 * through it but misses the opaque inner sphere is crossed twice (in and
 * out): coverage 1 - (1 - a)^2 (oracle: front-to-back compositing); where
 * it hits the inner sphere, coverage 1. */
static void
transparent_shell(void **state)
{
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_err e = { 0, "" };
	vx_image c, d, n;
	double iso[2] = { 11, 5 };

	(void)state;
	make_scene_volume(&g, 32, NULL, 11, 0, 0);
	build(&m, &g);
	base_scene(&s, 64, 64, 11);
	assert_int_equal(vx_scene_set_iso(&s, iso, 2, &e), 0);
	s.surface[0].m.opacity = 0.4;
	s.surface[1].m.opacity = 1;
	render(&s, &g, &m, 2, 0, &c, &d, &n);
	/* the centre pixel hits the inner sphere; find a pixel whose
	 * coverage is that of the shell alone */
	assert_true(fabs(vx_image_get(&c, 32, 32, 3) - 1) < 1e-6);
	int shell = 0;
	for (int x = 32; x < 64; x++) {
		double a = vx_image_get(&c, x, 32, 3);
		if (fabs(a - (1 - 0.6 * 0.6)) < 1e-6)
			shell++;
	}
	assert_true(shell >= 3);
	free3(&c, &d, &n);
	vx_macro_free(&m);
	vx_grid_free(&g);
}


/* No self-shadowing whatever the root solver: with the one-step LINEAR
 * solver a hit can land a fraction of a voxel inside the surface, and a
 * shadow ray from there must not be shadowed by its own surface (oracle:
 * the EXACT render, which such errors move by far less than a light's full
 * contribution: every pixel within 0.1 of it). */
static void
no_self_shadow_any_solver(void **state)
{
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_err e = { 0, "" };
	vx_image c1, d1, n1, c2, d2, n2;
	double lo[3], hi[3];

	(void)state;
	make_scene_volume(&g, 20, NULL, 6.3, 0, 0);
	build(&m, &g);
	base_scene(&s, 48, 48, 6.3);
	s.surface[0].m.ks = 0;
	assert_int_equal(vx_scene_apply(&s,
	    "light directional direction 0.3 -0.2 -1 shadows on", &e), 0);
	vx_grid_box(&g, lo, hi);
	for (int solver = VX_CELL_NEUBAUER; solver <= VX_CELL_LINEAR; solver++) {
		vx_scene sr = s;
		vx_plan p;
		vx_raycast_opts o;

		render(&s, &g, &m, 2, 0, &c1, &d1, &n1);
		assert_int_equal(vx_camera_resolve(&sr.camera, lo, hi, &e), 0);
		vx_scene_plan_isosurface(&sr, &p);
		vx_raycast_opts_init(&o);
		o.solver = solver;
		vx_image_init(&c2);
		vx_image_init(&d2);
		vx_image_init(&n2);
		assert_int_equal(vx_raycast_render(&sr, &p, &g, &m, NULL, &o, &c2,
		    &d2, &n2, NULL, &e), 0);
		double worst = 0;
		for (size_t i = 0; i < vx_image_nvalue(&c1); i++) {
			double dd = fabs(c1.px[i] - c2.px[i]);
			if (dd > worst)
				worst = dd;
		}
		if (!(worst < 0.1))
			fail_msg("solver %d: a pixel differs by %g", solver, worst);
		free3(&c1, &d1, &n1);
		free3(&c2, &d2, &n2);
	}
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* The bins' three modes give the picture of rays walked from the eye
 * (no binning), bit for bit, with the same cells visited: blocks of 4^3
 * cells (bin_block 4) for the macrocells whose mask bits the first rays
 * built (a fresh
 * mask), whole macrocells when every bracketing macrocell's bits are
 * built but the blocks' lists would pass 8 entries a pixel (an eye inside
 * a field of many small surfaces: blocks behind it span the image), and
 * the modes are told apart by the stats.  Oracle: o.no_binning. */
static void
binning_modes(void **state)
{
	const int64_t d[3] = { 96, 96, 96 };
	float iso = 0.05f;
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_plan p;
	vx_cellmask full;
	vx_err e = { 0, "" };
	double lo[3], hi[3];
	vx_image c[3], dd[3], nn[3];
	vx_raycast_stats st[3];

	(void)state;
	sine_field(&g, &m, d, (const double[3]){ 0.9, 0.7, 0.8 }, 2);
	base_scene(&s, 40, 30, iso);
	look_from(&s, (const double[3]){ 50.3, 44.1, 47.7 },
	    (const double[3]){ 90, 80, 70 }, 90);
	vx_grid_box(&g, lo, hi);
	assert_int_equal(vx_camera_resolve(&s.camera, lo, hi, &e), 0);
	vx_scene_plan_isosurface(&s, &p);
	assert_int_equal(vx_cellmask_build(&full, &m, &g, &iso, 1, 0, 1, &e),
	    0);
	for (int k = 0; k < 3; k++) {
		vx_raycast_opts o;

		vx_raycast_opts_init(&o);
		o.nthreads = 2;
		o.no_binning = k == 0;
		o.bin_block = 4;
		o.mask_keep = k == 2 ? &full : NULL;
		render_into(&s, &p, &g, &m, &o, &c[k], &dd[k], &nn[k], &st[k]);
	}
	assert_int_equal(st[0].bins, 0);
	assert_int_equal(st[1].bins, 1);
	assert_int_equal(st[1].bin_block, 4);
	assert_int_equal(st[2].bins, 1);
	assert_int_equal(st[2].bin_block, 0);
	for (int k = 1; k < 3; k++)
		same_render(c, dd, nn, st, k);
	assert_true(st[0].covered > 1000);
	for (int k = 0; k < 3; k++)
		free3(&c[k], &dd[k], &nn[k]);
	vx_cellmask_free(&full);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* A lazily built mask kept from frame to frame while the camera turns
 * round: the first frame (no bits built yet) draws the bins' centre pixels
 * first to build the bits of what is in sight; a later frame with the
 * kept mask does not, and walks the macrocells it sees for the first time
 * whole, building their bits as it goes.  The turned camera's picture,
 * depth, normals, cells and roots are those of rays walked from the eye,
 * and those of a mask made for that frame alone.  Oracle: o.no_binning. */
static void
binning_kept_mask_turn(void **state)
{
	const int64_t d[3] = { 96, 96, 96 };
	const double eye[3] = { 50.3, 44.1, 47.7 };
	float iso = 0.05f;
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_plan p;
	vx_cellmask keep;
	vx_err e = { 0, "" };
	double lo[3], hi[3];
	vx_image c[3], dd[3], nn[3], c0, d0, n0;
	vx_raycast_stats st[3], s0;
	vx_raycast_opts o;
	int64_t before;

	(void)state;
	sine_field(&g, &m, d, (const double[3]){ 0.9, 0.7, 0.8 }, 2);
	base_scene(&s, 40, 30, iso);
	vx_grid_box(&g, lo, hi);
	vx_scene_plan_isosurface(&s, &p);
	vx_cellmask_init(&keep);
	/* frame 1: looking one way; the mask is made (lazily) and kept */
	look_from(&s, eye, (const double[3]){ 90, 80, 70 }, 60);
	assert_int_equal(vx_camera_resolve(&s.camera, lo, hi, &e), 0);
	vx_raycast_opts_init(&o);
	o.nthreads = 2;
	o.bin_block = 4;
	o.mask_keep = &keep;
	render_into(&s, &p, &g, &m, &o, &c0, &d0, &n0, &s0);
	before = vx_cellmask_built(&keep);
	assert_true(before > 0 && before < keep.nset);
	/* its bins' centres first: 40 x 30 pixels, 5 x 4 bins of 8 x 8
	 * (the last row's centre, y 28, is on the image) */
	assert_int_equal(s0.first_pass, 5 * 4);
	/* the camera turned round: the oracle, the kept mask, a fresh one */
	look_from(&s, eye, (const double[3]){ 10, 8, 20 }, 60);
	assert_int_equal(vx_camera_resolve(&s.camera, lo, hi, &e), 0);
	for (int k = 0; k < 3; k++) {
		vx_raycast_opts_init(&o);
		o.nthreads = 2;
		o.bin_block = 4;
		o.no_binning = k == 0;
		o.mask_keep = k == 1 ? &keep : NULL;
		render_into(&s, &p, &g, &m, &o, &c[k], &dd[k], &nn[k], &st[k]);
	}
	assert_int_equal(st[1].bins, 1);
	assert_int_equal(st[2].bins, 1);
	/* the kept mask's frame walked newly seen macrocells whole and built
	 * their bits on the way */
	assert_true(st[1].bin_whole > 0);
	assert_true(vx_cellmask_built(&keep) > before);
	assert_int_equal(st[1].first_pass, 0);
	assert_int_equal(st[2].first_pass, 5 * 4);
	for (int k = 1; k < 3; k++)
		same_render(c, dd, nn, st, k);
	assert_true(st[0].covered > 300);
	for (int k = 0; k < 3; k++)
		free3(&c[k], &dd[k], &nn[k]);
	free3(&c0, &d0, &n0);
	vx_cellmask_free(&keep);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* More blocks of 4^3 cells (bin_block 4) in view than the bins take (8 a
 * pixel and 65536: a field of small surfaces filling a 200 x 200 x 136 volume,
 * about 85,000 blocks, every mask bit built, a 40 x 30 picture): the
 * bins fall back to whole macrocells, and the picture, depth, normals and
 * cells visited are those of rays walked from the eye, at 1 and 2
 * threads.  Oracle: o.no_binning. */
static void
binning_block_bound(void **state)
{
	const int64_t d[3] = { 200, 200, 136 };
	float iso = 0.05f;
	double lo[3], hi[3];
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_plan p;
	vx_cellmask full;
	vx_err e = { 0, "" };
	vx_image c[3], dd[3], nn[3];
	vx_raycast_stats st[3];

	(void)state;
	sine_field(&g, &m, d, (const double[3]){ 0.9, 0.7, 0.8 }, 4);
	base_scene(&s, 40, 30, iso);
	vx_grid_box(&g, lo, hi);
	assert_int_equal(vx_camera_resolve(&s.camera, lo, hi, &e), 0);
	vx_scene_plan_isosurface(&s, &p);
	assert_int_equal(vx_cellmask_build(&full, &m, &g, &iso, 1, 0, 2, &e),
	    0);
	for (int k = 0; k < 3; k++) {
		vx_raycast_opts o;

		vx_raycast_opts_init(&o);
		o.nthreads = k == 2 ? 1 : 2;
		o.no_binning = k == 0;
		o.bin_block = 4;
		o.mask_keep = k > 0 ? &full : NULL;
		render_into(&s, &p, &g, &m, &o, &c[k], &dd[k], &nn[k], &st[k]);
	}
	assert_int_equal(st[0].bins, 0);
	for (int k = 1; k < 3; k++) {
		assert_int_equal(st[k].bins, 1);
		assert_int_equal(st[k].bin_block, 0);
		assert_true(st[k].bin_boxes > 1000);
		assert_int_equal(st[k].bin_boxes, st[k].bin_whole);
		same_render(c, dd, nn, st, k);
	}
	assert_true(st[0].covered > 500);
	for (int k = 0; k < 3; k++)
		free3(&c[k], &dd[k], &nn[k]);
	vx_cellmask_free(&full);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* Any block edge gives the picture of rays walked from the eye, bit for
 * bit, with the same cells visited and roots solved: edges 1 (a box a
 * bracketing cell), 2, 3 and 5 (blocks that do not divide the 16^3
 * macrocells: short last blocks), 8 (the default), 16 (a macrocell's
 * box of bracketing cells) and 64 (past the macrocell), on a field of
 * many small surfaces seen from outside and from inside it (rays that
 * start in a box), at 1 and 2 threads; an edge past the largest is
 * refused.  Oracle: o.no_binning. */
static void
binning_any_block(void **state)
{
	static const int edge[] = { 1, 2, 3, 5, 8, 16, 64 };
	const int64_t d[3] = { 48, 40, 36 };
	float iso = 0.05f;
	vx_grid g;
	vx_macro m;
	vx_err e = { 0, "" };
	double lo[3], hi[3];

	(void)state;
	sine_field(&g, &m, d, (const double[3]){ 0.5, 0.45, 0.55 }, 2);
	vx_grid_box(&g, lo, hi);
	for (int view = 0; view < 2; view++) {
		vx_scene s;
		vx_plan p;
		vx_image c[2], dd[2], nn[2];
		vx_raycast_stats st[2];

		base_scene(&s, 48, 40, iso);
		if (view == 1)   /* inside the field */
			look_from(&s, (const double[3]){ 20.3, 17.1, 15.7 },
			    (const double[3]){ 40, 30, 30 }, 70);
		assert_int_equal(vx_camera_resolve(&s.camera, lo, hi, &e), 0);
		vx_scene_plan_isosurface(&s, &p);
		for (size_t i = 0; i < sizeof edge / sizeof *edge; i++) {
			for (int k = 0; k < 2; k++) {
				vx_raycast_opts o;

				vx_raycast_opts_init(&o);
				o.nthreads = 1 + (int)(i % 2);
				o.no_binning = k == 0;
				o.bin_block = edge[i];
				render_into(&s, &p, &g, &m, &o, &c[k], &dd[k],
				    &nn[k], &st[k]);
			}
			assert_int_equal(st[1].bins, 1);
			assert_int_equal(st[1].bin_block, edge[i]);
			same_render(c, dd, nn, st, 1);
			assert_true(st[0].covered > 300);
			for (int k = 0; k < 2; k++)
				free3(&c[k], &dd[k], &nn[k]);
		}
		/* past the largest edge: refused */
		{
			vx_raycast_opts o;
			vx_image ci;

			vx_raycast_opts_init(&o);
			o.bin_block = VX_RAYCAST_BLOCK_MAX + 1;
			vx_image_init(&ci);
			assert_int_equal(vx_raycast_render(&s, &p, &g, &m, NULL,
			    &o, &ci, NULL, NULL, NULL, &e), VX_EUSAGE);
			vx_image_free(&ci);
		}
	}
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* The frame's time split (vx_raycast_stats): the threads it ran on, the
 * tiles' wall time within the frame's, and the threads' time in the tiles
 * within threads x that wall time (each thread's tiles lie inside the
 * tiles' span), at 1, 2 and 3 threads.  Invariants, not speed. */
static void
stats_time_split(void **state)
{
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_plan p;

	(void)state;
	make_scene_volume(&g, 32, NULL, 9, 0, 0);
	build(&m, &g);
	base_scene(&s, 48, 40, 9);
	for (int t = 1; t <= 3; t++) {
		vx_raycast_opts o;
		vx_raycast_stats st;
		vx_image c, dd, nn;
		double lo[3], hi[3];
		vx_err e = { 0, "" };

		vx_grid_box(&g, lo, hi);
		assert_int_equal(vx_camera_resolve(&s.camera, lo, hi, &e), 0);
		vx_scene_plan_isosurface(&s, &p);
		vx_raycast_opts_init(&o);
		o.nthreads = t;
		render_into(&s, &p, &g, &m, &o, &c, &dd, &nn, &st);
		assert_int_equal(st.threads, t);
		assert_true(st.tile_seconds > 0);
		assert_true(st.tile_seconds <= st.seconds);
		assert_true(st.thread_seconds > 0);
		assert_true(st.thread_seconds <= t * st.tile_seconds * (1 + 1e-9));
		free3(&c, &dd, &nn);
	}
	vx_macro_free(&m);
	vx_grid_free(&g);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(depth_matches_geometry),
		cmocka_unit_test(invariance),
		cmocka_unit_test(nonfinite_pixels),
		cmocka_unit_test(shadow_under_sphere),
		cmocka_unit_test(transparent_shell),
		cmocka_unit_test(no_self_shadow_any_solver),
		cmocka_unit_test(binning_modes),
		cmocka_unit_test(binning_kept_mask_turn),
		cmocka_unit_test(binning_block_bound),
		cmocka_unit_test(binning_any_block),
		cmocka_unit_test(stats_time_split),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
