/* test_bake.c: irradiance baking against closed forms (vx_bake.h,
 * vx_gi.h), each case built on purpose:
 *  - white furnace: a convex surface under a sky of radiance L has
 *    E = pi L at every texel, at any bounce count (nothing to bounce off);
 *  - a plane under a directional light, half shadowed by a box: E = pi I
 *    in the light and 0 in the umbra, the penumbra within one texel;
 *  - the bottom of a hemispherical bowl under a sky sees a cap of
 *    half-angle theta: E = pi L sin^2 theta (the irradiance of a uniform
 *    cap about the normal);
 *  - determinism: thread counts, resumed samples, texel order.
 * The fixed-point rounding of the accumulators (2^-24) is the only error
 * where the estimator is exact. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "vx_bake.h"
#include "vx_gi.h"
#include "vx_irrvol.h"
#include "vx_macro.h"
#include "vx_scene.h"
#include "vx_sh.h"

/* room for one texel's accumulators of any size */
typedef union accbuf {
	vx_irr_acc a;
	int64_t w[3 + VX_IRR_MAX_COMP];
} accbuf;

#define PI 3.14159265358979323846

typedef double (*field_fn)(double x, double y, double z);

static void
make_box(vx_grid *g, vx_macro *m, int64_t n, int64_t nz, field_fn f)
{
	int64_t d[3] = { n, n, nz };
	int sizes[4][3];
	vx_err e = { 0, "" };
	int nlev;

	vx_grid_init(g);
	assert_int_equal(vx_grid_alloc(g, d, VX_F32, NULL, &e), 0);
	snprintf(g->name, sizeof g->name, "density");
	for (int64_t z = 0; z < nz; z++)
		for (int64_t y = 0; y < n; y++)
			for (int64_t x = 0; x < n; x++)
				vx_grid_set(g, x, y, z, f((double)x, (double)y,
				    (double)z));
	vx_grid_range(g);
	vx_macro_init(m);
	nlev = vx_macro_default_sizes(VX_F32, 2, sizes);
	assert_int_equal(vx_macro_build(m, g, nlev,
	    (const int (*)[3])sizes, 1, &e), 0);
}

static void
make(vx_grid *g, vx_macro *m, int64_t n, field_fn f)
{
	make_box(g, m, n, n, f);
}

static void
scene_with(vx_scene *s, const char *const *lines)
{
	vx_err e = { 0, "" };

	vx_scene_init(s);
	for (; *lines; lines++)
		assert_int_equal(vx_scene_apply(s, *lines, &e), 0);
}

/* distance from (12, 12, 12): a ball of lower values, lit from outside
 * when the higher side is lit */
static double
ball_dist(double x, double y, double z)
{
	return sqrt((x - 12) * (x - 12) + (y - 12) * (y - 12) +
	    (z - 12) * (z - 12));
}

/* density of a ball: higher inside, lit on the (default) lower side */
static double
ball_density(double x, double y, double z)
{
	return 20 - ball_dist(x, y, z);
}

static void
bake_all(vx_irrvol *v, const vx_grid *g, const vx_gi *gi,
    vx_bake_opts *o)
{
	vx_bake_stats st;
	vx_err e = { 0, "" };

	memset(&st, 0, sizeof st);
	vx_irr_init(v);
	assert_int_equal(vx_irr_setup(v, g, 0, o->scale, VX_IRR_ACCUM, &e), 0);
	assert_int_equal(vx_bake_plan(v, g, o, &st, &e), 0);
	assert_int_equal(vx_bake_run(v, gi, g, o, &st, &e), 0);
	assert_true(st.baked > 0);
}

/* White furnace: E = pi L for every usable texel of a convex surface,
 * bounces 0, 1 and 3, either lit side, albedo 0.5 and 1. */
static void
white_furnace(void **state)
{
	static const struct { field_fn f; int high; int bounces;
	    const char *albedo; } t[] = {
		{ ball_dist, 1, 0, "surface iso 7 color 1 1 1" },
		{ ball_dist, 1, 3, "surface iso 7 color 0.5 0.5 0.5" },
		{ ball_density, 0, 1, "surface iso 13 color 1 1 1" },
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof *t; i++) {
		const char *lines[] = { "light sky color 1 0.5 2",
		    t[i].albedo, NULL };
		vx_grid g;
		vx_macro m;
		vx_scene s;
		vx_gi gi;
		vx_irrvol v;
		vx_bake_opts o;
		vx_err e = { 0, "" };
		int usable = 0;

		make(&g, &m, 25, t[i].f);
		scene_with(&s, lines);
		assert_int_equal(vx_gi_setup(&gi, &s, &g, &m, &e), 0);
		gi.high = t[i].high;
		gi.bounces = t[i].bounces;
		vx_bake_opts_init(&o);
		o.samples = 8;
		o.all = 0;
		o.nband = 1;
		o.band[0][0] = 5;
		o.band[0][1] = 9;
		if (!t[i].high) {
			o.band[0][0] = 11;
			o.band[0][1] = 15;
		}
		o.threads = 1;
		bake_all(&v, &g, &gi, &o);
		for (size_t q = 0; q < v.nslot * VX_IRR_BRICK3; q++) {
			if (!vx_irr_usable(&v, (int64_t)q))
				continue;
			usable++;
			assert_true(fabs(v.mean[3 * q] - PI) < 1e-6);
			assert_true(fabs(v.mean[3 * q + 1] - PI * 0.5) < 1e-6);
			assert_true(fabs(v.mean[3 * q + 2] - PI * 2) < 1e-6);
		}
		assert_true(usable > 500);
		vx_irr_free(&v);
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
}

/* a floor (solid below z = 8) and a box (solid over x, y in [10, 22],
 * z in [14, 18]); density: higher inside */
static double
floor_box(double x, double y, double z)
{
	double fl = 0.5 + (8 - z);
	double bx = 0.5 + fmin(fmin(6 - fabs(x - 16), 6 - fabs(y - 16)),
	    2 - fabs(z - 16));

	return fmax(fl, bx);
}

/* A directional light straight down: texels on the floor (value 0.5
 * exactly on the sample plane z = 8) have E = pi I unshadowed, 0 under the
 * box; every texel at least 1.5 voxels from the shadow's edge is fully lit
 * or dark (the umbra's edge blurred by at most a texel). */
static void
plane_shadow(void **state)
{
	const char *lines[] = { "light directional direction 0 0 -1 "
	    "intensity 2", NULL };
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_gi gi;
	vx_irrvol v;
	vx_bake_opts o;
	vx_err e = { 0, "" };
	int lit = 0, dark = 0;

	(void)state;
	make(&g, &m, 32, floor_box);
	scene_with(&s, lines);
	assert_int_equal(vx_gi_setup(&gi, &s, &g, &m, &e), 0);
	vx_bake_opts_init(&o);
	o.samples = 4;
	o.nband = 1;
	o.all = 0;
	o.band[0][0] = o.band[0][1] = 0.5;
	o.threads = 2;
	bake_all(&v, &g, &gi, &o);
	for (int64_t y = 3; y < 29; y++)
		for (int64_t x = 3; x < 29; x++) {
			int64_t q = vx_irr_texel(&v, x, y, 8);
			double d = fmax(fabs((double)x - 16),
			    fabs((double)y - 16));

			assert_true(q >= 0 && vx_irr_usable(&v, q));
			if (d <= 6 - 1.5) {
				assert_true(v.mean[3 * q] < 1e-6);
				dark++;
			} else if (d >= 6 + 1.5) {
				assert_true(fabs(v.mean[3 * q] - 2 * PI) < 1e-5);
				lit++;
			}
		}
	assert_true(lit > 200 && dark > 50);
	vx_irr_free(&v);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* a bowl: solid outside the sphere of radius 10 about (16, 16, 24) in a
 * volume whose top face is z = 24, so the rim is the sphere's circle on the
 * sample plane z = 24, where rays leave the volume (a sharp rim: the
 * trilinear field on that plane moves it by ~h^2 / 8R = 0.0125 voxels);
 * its bottom (16, 16, 14) has value 0.5 */
static double
bowl(double x, double y, double z)
{
	double r = sqrt((x - 16) * (x - 16) + (y - 16) * (y - 16) +
	    (z - 24) * (z - 24));

	return 0.5 + r - 10;
}

/* The bowl's bottom under a sky of radiance 1, no bounces: from the start
 * point h = 0.5 voxels above the bottom the opening (radius R = 10 at
 * height R - h) subtends a cap of half-angle theta, tan theta = R/(R - h),
 * so E = pi sin^2 theta = pi R^2 / (R^2 + (R - h)^2) (0.5256 pi).  Each
 * sample is pi or 0 (escape or not): at 4096 scrambled-Sobol samples the
 * error is well below the 1% allowed (the Bernoulli bound of plain Monte
 * Carlo would be 1.5% at 2 sigma); the rim's trilinear error is 0.25% of
 * sin^2. */
static void
bowl_cap(void **state)
{
	const char *lines[] = { "light sky", NULL };
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_gi gi;
	vx_irrvol v;
	vx_bake_opts o;
	accbuf ua;
	vx_irr_acc *a = &ua.a;
	vx_err e = { 0, "" };
	double R = 10, h = 0.5, want, got[3];

	(void)state;
	make_box(&g, &m, 33, 25, bowl);
	scene_with(&s, lines);
	assert_int_equal(vx_gi_setup(&gi, &s, &g, &m, &e), 0);
	vx_bake_opts_init(&o);
	o.samples = 4096;
	o.offset = h;
	vx_irr_init(&v);
	assert_int_equal(vx_irr_setup(&v, &g, 0, 1, VX_IRR_ACCUM, &e), 0);
	memset(&ua, 0, sizeof ua);
	vx_bake_texel(&v, &gi, &g, &o, 16, 16, 14, a, NULL);
	assert_int_equal(a->count, 4096);
	vx_irr_acc_mean(&v, a, got);
	want = PI * R * R / (R * R + (R - h) * (R - h));
	assert_true(fabs(got[0] - want) < 0.01 * want);
	vx_irr_free(&v);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* The same bits whatever the threads, the order of texels, and whether
 * the samples were taken in one run or two. */
static void
determinism(void **state)
{
	const char *lines[] = { "light sky color 0.3 0.4 0.5",
	    "light point position 30 30 40 intensity 3",
	    "surface iso 0.5 color 0.7 0.6 0.5", NULL };
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_gi gi;
	vx_irrvol a, b, c;
	vx_bake_opts o;
	vx_err e = { 0, "" };

	(void)state;
	make_box(&g, &m, 33, 25, bowl);
	scene_with(&s, lines);
	assert_int_equal(vx_gi_setup(&gi, &s, &g, &m, &e), 0);
	gi.bounces = 2;
	gi.seed = 9;
	vx_bake_opts_init(&o);
	o.all = 0;
	o.nband = 1;
	o.band[0][0] = o.band[0][1] = 0.5;
	o.samples = 12;
	o.threads = 1;
	bake_all(&a, &g, &gi, &o);
	o.threads = 2;
	bake_all(&b, &g, &gi, &o);
	assert_int_equal(a.nslot, b.nslot);
	assert_memory_equal(a.acc, b.acc, a.nslot * VX_IRR_BRICK3 *
	    vx_irr_acc_bytes(a.ncomp));
	/* 5 then 7 samples: the 12-sample accumulators */
	{
		vx_bake_stats st;

		memset(&st, 0, sizeof st);
		o.samples = 5;
		bake_all(&c, &g, &gi, &o);
		o.samples = 7;
		assert_int_equal(vx_bake_run(&c, &gi, &g, &o, &st, &e), 0);
		assert_memory_equal(a.acc, c.acc, a.nslot * VX_IRR_BRICK3 *
		    vx_irr_acc_bytes(a.ncomp));
	}
	/* one texel alone (lazy) equals the bake's */
	{
		accbuf ut;
		vx_irr_acc *t = &ut.a;
		int64_t q = -1, i = 0, j = 0, k = 0;

		for (k = 0; k < 32 && q < 0; k++)
			for (j = 0; j < 32 && q < 0; j++)
				for (i = 0; i < 32 && q < 0; i++) {
					int64_t s2 = vx_irr_texel(&a, i, j, k);

					if (s2 >= 0 && vx_irr_accp(&a, s2)->count > 0)
						q = s2;
				}
		assert_true(q >= 0);
		memset(&ut, 0, sizeof ut);
		o.samples = 12;
		vx_bake_texel(&a, &gi, &g, &o, i - 1, j - 1, k - 1, t, NULL);
		t->flags |= VX_TEXEL_WANTED;
		assert_memory_equal(t, vx_irr_accp(&a, q),
		    vx_irr_acc_bytes(a.ncomp));
	}
	vx_irr_free(&a);
	vx_irr_free(&b);
	vx_irr_free(&c);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* Texel rules: a NaN sample flags every texel whose support holds it (at
 * scale 1 the 3x3x3 samples around the texel: the fourth weight is 0) (VX_TEXEL_NAN, no samples, never drawn); a constant region has no
 * gradient (VX_TEXEL_FLAT); texels at the volume's edge are baked with the
 * edge samples repeated (VX_TEXEL_BORDER); no mean is NaN. */
static double
ramp_z(double x, double y, double z)
{
	(void)x;
	(void)y;
	return z < 10 ? z : 10;        /* flat above z = 10 */
}

static void
texel_rules(void **state)
{
	const char *lines[] = { "light sky", NULL };
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_gi gi;
	vx_irrvol v;
	vx_bake_opts o;
	vx_err e = { 0, "" };
	int64_t q;

	(void)state;
	make(&g, &m, 16, ramp_z);
	vx_grid_set(&g, 8, 8, 4, NAN);
	vx_grid_range(&g);
	vx_macro_free(&m);
	vx_macro_init(&m);
	{
		int sizes[4][3], nlev = vx_macro_default_sizes(VX_F32, 2, sizes);

		assert_int_equal(vx_macro_build(&m, &g, nlev,
		    (const int (*)[3])sizes, 1, &e), 0);
	}
	scene_with(&s, lines);
	assert_int_equal(vx_gi_setup(&gi, &s, &g, &m, &e), 0);
	vx_bake_opts_init(&o);
	o.samples = 2;
	bake_all(&v, &g, &gi, &o);
	/* the NaN's neighbours within the support (|d| <= 1 on each axis) */
	for (int dz = -1; dz <= 1; dz++)
		for (int dx = -1; dx <= 1; dx++) {
			q = vx_irr_texel(&v, 8 + dx, 8, 4 + dz);
			assert_true(v.flags[q] & VX_TEXEL_NAN);
			assert_false(vx_irr_usable(&v, q));
			assert_int_equal(vx_irr_accp(&v, q)->count, 0);
		}
	q = vx_irr_texel(&v, 10, 8, 4);         /* 2 away: baked */
	assert_false(v.flags[q] & VX_TEXEL_NAN);
	assert_int_equal(vx_irr_accp(&v, q)->count, 2);
	q = vx_irr_texel(&v, 8, 8, 8);          /* 4 away: baked */
	assert_false(v.flags[q] & VX_TEXEL_NAN);
	assert_int_equal(vx_irr_accp(&v, q)->count, 2);
	q = vx_irr_texel(&v, 4, 4, 14);         /* constant region */
	assert_true(v.flags[q] & VX_TEXEL_FLAT);
	q = vx_irr_texel(&v, 0, 5, 5);          /* the x = 0 face */
	assert_true(v.flags[q] & VX_TEXEL_BORDER);
	assert_true(vx_irr_usable(&v, q));
	for (size_t t = 0; t < 3 * v.nslot * VX_IRR_BRICK3; t++)
		assert_false(isnan(v.mean[t]));
	vx_irr_free(&v);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* SH transfer of unoccluded texels (a convex ball, no bounces): the
 * clamped cosine about the texel's normal, whose coefficients are A_l
 * Y_l^m(n) (the zonal lobe rotated to n; oracle: vx_sh_cosine_band, the
 * Funk-Hecke theorem).  The estimator's error: each sample adds
 * pi Y_i(w) with |pi Y_i| < 3 at order 4, and the 2048 scrambled Sobol
 * points of a smooth integrand bring it well under 1e-2; the constant
 * term is exact (pi Y_0^0 every sample).  Also: one channel with a grey
 * albedo and bounces that end on no surface leave the texel unchanged. */
static void
sh_unoccluded(void **state)
{
	static const struct { field_fn f; int high; int order; } t[] = {
		{ ball_dist, 1, 4 },
		{ ball_density, 0, 3 },
		{ ball_dist, 1, 1 },
	};

	(void)state;
	for (size_t c = 0; c < sizeof t / sizeof *t; c++) {
		const char *lines[] = { "surface iso 7 color 1 1 1", NULL };
		int order = t[c].order, nn = order * order, checked = 0;
		vx_grid g;
		vx_macro m;
		vx_scene s;
		vx_gi gi;
		vx_irrvol v;
		vx_bake_opts o;
		vx_err e = { 0, "" };
		double worst = 0;

		make(&g, &m, 25, t[c].f);
		scene_with(&s, lines);
		assert_int_equal(vx_gi_setup(&gi, &s, &g, &m, &e), 0);
		gi.high = t[c].high;
		gi.bounces = 2;          /* a convex ball: no path returns */
		vx_bake_opts_init(&o);
		o.samples = 2048;
		vx_irr_init(&v);
		assert_int_equal(vx_irr_setup_sh(&v, &g, 0, 1, VX_IRR_ACCUM,
		    order, 1, &e), 0);
		for (int q = 0; q < 6; q++) {
			/* texels on the six axes of the ball, 5 from its
			 * centre, and one off the axes */
			static const int at[6][3] = { { 17, 12, 12 },
			    { 7, 12, 12 }, { 12, 17, 12 }, { 12, 12, 7 },
			    { 15, 16, 9 }, { 9, 10, 16 } };
			accbuf u;
			double rho, start[3], n[3], y[256], got[256];

			memset(&u, 0, sizeof u);
			vx_bake_texel(&v, &gi, &g, &o, at[q][0], at[q][1],
			    at[q][2], &u.a, NULL);
			assert_int_equal(u.a.count, 2048);
			vx_bake_texel_setup(&v, &g, o.offset, gi.high, at[q][0],
			    at[q][1], at[q][2], &rho, start, n);
			vx_irr_acc_mean(&v, &u.a, got);
			vx_sh_eval(order, n, y);
			for (int l = 0; l < order; l++)
				for (int mm = -l; mm <= l; mm++) {
					int i = vx_sh_index(l, mm);
					double want = vx_sh_cosine_band(l) * y[i];

					if (fabs(got[i] - want) > worst)
						worst = fabs(got[i] - want);
					checked++;
				}
			assert_true(fabs(got[0] - vx_sh_cosine_band(0) *
			    y[0]) < 1e-6);
		}
		assert_int_equal(checked, 6 * nn);
		assert_true(worst < 1e-2);
		vx_irr_free(&v);
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
}

/* distance from the plane z = 12: the isosurface of value 4 is the two
 * planes z = 8 and z = 16 bounding a gap of lower values (the lit side) */
static double
gap(double x, double y, double z)
{
	(void)x;
	(void)y;
	return fabs(z - 12);
}

/* Vicinity shading (the scene's occlusion directive): a texel on the
 * gap's floor facing the ceiling H above its start point.  A
 * cosine-weighted ray at angle theta meets the ceiling after H / cos
 * theta; with the vicinity D it counts as open when that exceeds D, so
 * E / pi is the cosine-weighted fraction of directions with cos theta <
 * H / D: (H / D)^2 (D >= H; 1 for D < H).  Oracle:
 * that integral; the texel's start lies `offset` voxels above the floor
 * and the rays eps above it.  Also: the lights of the scene play no part. */
static void
vicinity(void **state)
{
	/* D <= 16: a ray that meets the ceiling within D has gone at most
	 * sqrt(D^2 - H^2) < 16 sideways, so none leaves through the
	 * volume's sides (the texel is 16 from them) */
	static const struct { double D; } t[] = { { 12 }, { 16 }, { 6 } };
	const double off = 0.5, eps = 1e-3, H = 8 - off - eps;

	(void)state;
	for (size_t c = 0; c < sizeof t / sizeof *t; c++) {
		char occ[64];
		const char *lines[] = { "light point position 16 16 12 "
		    "intensity 50", "surface iso 4 color 1 1 1", occ, NULL };
		accbuf u;
		vx_grid g;
		vx_macro m;
		vx_scene s;
		vx_gi gi;
		vx_irrvol v;
		vx_bake_opts o;
		vx_err e = { 0, "" };
		double got[3], want, r;

		snprintf(occ, sizeof occ, "occlusion distance %g", t[c].D);
		make_box(&g, &m, 33, 25, gap);
		scene_with(&s, lines);
		assert_int_equal(vx_gi_setup(&gi, &s, &g, &m, &e), 0);
		assert_int_equal(gi.nlight, 0);
		assert_int_equal(gi.bounces, 0);
		vx_bake_opts_init(&o);
		o.samples = 4096;
		o.offset = off;
		vx_irr_init(&v);
		assert_int_equal(vx_irr_setup(&v, &g, 0, 1, VX_IRR_ACCUM, &e),
		    0);
		memset(&u, 0, sizeof u);
		vx_bake_texel(&v, &gi, &g, &o, 16, 16, 8, &u.a, NULL);
		vx_irr_acc_mean(&v, &u.a, got);
		r = H / t[c].D;
		want = PI * (r >= 1 ? 1 : r * r);
		if (!(fabs(got[0] - want) < 0.01 * PI))
			fail_msg("D %g: E %.6f, want %.6f", t[c].D, got[0], want);
		assert_true(got[0] == got[1] && got[1] == got[2]);
		vx_irr_free(&v);
		vx_macro_free(&m);
		vx_grid_free(&g);
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(white_furnace),
		cmocka_unit_test(plane_shadow),
		cmocka_unit_test(bowl_cap),
		cmocka_unit_test(determinism),
		cmocka_unit_test(texel_rules),
		cmocka_unit_test(sh_unoccluded),
		cmocka_unit_test(vicinity),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
