/* test_perturb.c: volume perturbation (vx_perturb.h), the surface ramp
 * (vx_tf_surface_ramp) and the perturb and surface-gradient scene lines.
 *
 * Oracles:
 *  - no perturbation: vx_perturb_field is vx_grid_trilinear and dvr's
 *    central differences, bit for bit; so is a perturbation forced on
 *    with amplitude 0 (every term is then + 0 or x 1);
 *  - a displaced constant field is the constant, its gradient 0;
 *  - on the linear field F = x (world), coordinate perturbation gives
 *    F' = x + A n1(x) and value perturbation F' = x + A n(x), with n the
 *    module's own fBm (vx_noise_fbm_eval, an independent evaluation); the
 *    returned gradient matches central differences of F' itself (the
 *    chain rule);
 *  - density m: alpha' = 1 - (1 - alpha)^m, transport' = transport^m; m 0
 *    gives alpha 0, transport 1; m 1 leaves the sample's bits;
 *  - the erosion of the clear mask: a cell stays clear only when every
 *    cell within the displacement's reach is clear (by brute force);
 *  - the surface ramp at gradient magnitudes below, inside and above
 *    [G0, G1] by (g - G0) / (G1 - G0), times the surface list;
 *  - scene lines: parse(format(s)) == s; bad knobs refused with the line. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "vx_perturb.h"

static void
scene(vx_scene *s, const char *text)
{
	vx_err e = { 0, "" };

	if (vx_scene_parse(s, text, strlen(text), &e) != 0)
		fail_msg("%s", e.msg);
}

/* a 9^3 grid over [0, 2]^3 of f(world x, y, z) */
static void
grid(vx_grid *g, double (*f)(double, double, double))
{
	int64_t dims[3] = { 9, 9, 9 };
	vx_err e = { 0, "" };

	vx_grid_init(g);
	assert_int_equal(vx_grid_alloc(g, dims, VX_F32, NULL, &e), 0);
	for (int a = 0; a < 3; a++) {
		g->spacing[a] = 0.25;
		g->origin[a] = 0;
	}
	for (int z = 0; z < 9; z++)
		for (int y = 0; y < 9; y++)
			for (int x = 0; x < 9; x++)
				vx_grid_set(g, x, y, z, f(x * 0.25, y * 0.25, z * 0.25));
	vx_grid_range(g);
}

static double fconst(double x, double y, double z) { (void)x; (void)y;
    (void)z; return 0.375; }
static double flinx(double x, double y, double z) { (void)y; (void)z;
    return x; }
static double fwave(double x, double y, double z) { return sin(3 * x) +
    y * y - 0.5 * z; }

/* points well inside the grid (index space) */
static const double pts[][3] = {
	{ 4, 4, 4 }, { 2.3, 5.7, 3.1 }, { 6.05, 1.95, 4.5 }, { 3.5, 3.5, 5.25 },
};
#define NPTS (sizeof pts / sizeof pts[0])

static void
none_is_plain(void **state)
{
	vx_scene s;
	vx_perturb pt;
	vx_grid g;
	vx_err e = { 0, "" };

	(void)state;
	grid(&g, fwave);
	/* no line, and lines of amplitude 0: off */
	for (int k = 0; k < 2; k++) {
		scene(&s, k == 0 ? "" : "perturb coordinates scale 1 amplitude 0\n"
		    "perturb value scale 1 amplitude 0\n"
		    "perturb density scale 1 amplitude 0\n");
		assert_int_equal(vx_perturb_init(&pt, &s, &e), 0);
		assert_int_equal(pt.any, 0);
	}
	/* forced on with amplitude 0: the same bits (oracle: + 0, x 1) */
	scene(&s, "perturb coordinates scale 0.5 amplitude 1\n"
	    "perturb value scale 0.5 amplitude 1\n"
	    "perturb density scale 0.5 amplitude 1\n");
	assert_int_equal(vx_perturb_init(&pt, &s, &e), 0);
	assert_int_equal(pt.any, 1);
	pt.amp[0] = pt.amp[1] = pt.amp[2] = 0;
	for (size_t i = 0; i < NPTS; i++) {
		vx_perturb off;
		double v0, v1, v2, g0[3], g1[3], g2[3], m = -1;

		vx_perturb_none(&off);
		v0 = vx_grid_trilinear(&g, pts[i]);
		for (int a = 0; a < 3; a++) {
			double q[3] = { pts[i][0], pts[i][1], pts[i][2] }, hi;

			q[a] += 1;
			hi = vx_grid_trilinear(&g, q);
			q[a] -= 2;
			g0[a] = (hi - vx_grid_trilinear(&g, q)) / (2 * 0.25);
		}
		v1 = vx_perturb_field(&off, &g, pts[i], g1, NULL);
		v2 = vx_perturb_field(&pt, &g, pts[i], g2, &m);
		assert_memory_equal(&v0, &v1, sizeof v0);
		assert_memory_equal(&v0, &v2, sizeof v0);
		assert_memory_equal(g0, g1, sizeof g0);
		assert_memory_equal(g0, g2, sizeof g0);
		assert_true(m == 1);
	}
	vx_grid_free(&g);
}

static void
constant_unchanged(void **state)
{
	vx_scene s;
	vx_perturb pt;
	vx_grid g;
	vx_err e = { 0, "" };

	(void)state;
	grid(&g, fconst);
	scene(&s, "perturb coordinates scale 0.3 amplitude 0.4 octaves 6\n");
	assert_int_equal(vx_perturb_init(&pt, &s, &e), 0);
	for (size_t i = 0; i < NPTS; i++) {
		double gr[3], v = vx_perturb_field(&pt, &g, pts[i], gr, NULL);

		assert_true(fabs(v - 0.375) < 1e-12);
		for (int a = 0; a < 3; a++)
			assert_true(fabs(gr[a]) < 1e-9);
	}
	vx_grid_free(&g);
}

/* F = x: F' by the module's own noise, gradient by differences of F' */
static void
linear_field(void **state)
{
	static const char *lines[] = {
		"perturb coordinates scale 0.7 amplitude 0.1 octaves 3\n",
		"perturb coordinates scale 0.7 amplitude 0.1 noise turbulence\n",
		"perturb value scale 0.5 amplitude 0.2 octaves 5 gain 0.6\n",
	};
	vx_grid g;

	(void)state;
	grid(&g, flinx);
	for (size_t k = 0; k < sizeof lines / sizeof lines[0]; k++) {
		vx_scene s;
		vx_perturb pt;
		vx_err e = { 0, "" };
		const vx_noise_fbm *f;
		int turb;

		scene(&s, lines[k]);
		assert_int_equal(vx_perturb_init(&pt, &s, &e), 0);
		f = k < 2 ? &pt.coord[0] : &pt.value;
		turb = k == 1;
		for (size_t i = 0; i < NPTS; i++) {
			double w[3], gr[3], n, v, h = 1e-5;

			for (int a = 0; a < 3; a++)
				w[a] = pts[i][a] * 0.25;
			n = turb ? vx_noise_turbulence(f, w) :
			    vx_noise_fbm_eval(f, w, NULL);
			v = vx_perturb_field(&pt, &g, pts[i], gr, NULL);
			assert_true(fabs(v - (w[0] + (k < 2 ? 0.1 : 0.2) * n)) <
			    1e-6);
			for (int a = 0; a < 3; a++) {
				double q[3] = { pts[i][0], pts[i][1], pts[i][2] };
				double vp, vm;

				q[a] += h / 0.25;
				vp = vx_perturb_field(&pt, &g, q, NULL, NULL);
				q[a] -= 2 * h / 0.25;
				vm = vx_perturb_field(&pt, &g, q, NULL, NULL);
				assert_true(fabs(gr[a] - (vp - vm) / (2 * h)) < 1e-4);
			}
		}
	}
	vx_grid_free(&g);
}

static void
density_optics(void **state)
{
	vx_tf_sample c, d;

	(void)state;
	c.alpha = 0.3;
	c.transport[0] = 0.5;
	c.transport[1] = 0.9;
	c.transport[2] = 1;
	c.surface = 0.25;
	c.color[0] = c.color[1] = c.color[2] = 0.5;
	d = c;
	vx_perturb_optics(&d, 1);
	assert_memory_equal(&c, &d, sizeof c);
	vx_perturb_optics(&d, 2);
	assert_true(fabs(d.alpha - (1 - 0.7 * 0.7)) < 1e-15);
	assert_true(fabs(d.transport[0] - 0.25) < 1e-15);
	assert_true(fabs(d.transport[1] - 0.81) < 1e-15);
	assert_true(d.transport[2] == 1);
	d = c;
	vx_perturb_optics(&d, 0);
	assert_true(d.alpha == 0);
	assert_true(d.transport[0] == 1 && d.transport[1] == 1);
}

/* the density factor is max(0, 1 + A n) with the module's own noise */
static void
density_factor(void **state)
{
	vx_scene s;
	vx_perturb pt;
	vx_grid g;
	vx_err e = { 0, "" };
	int clamped = 0;

	(void)state;
	grid(&g, fwave);
	scene(&s, "perturb density scale 0.2 amplitude 8 octaves 2\n");
	assert_int_equal(vx_perturb_init(&pt, &s, &e), 0);
	assert_true(vx_perturb_density_max(&pt) == 9);
	for (int i = 0; i < 200; i++) {
		double p[3] = { 1 + 0.031 * i, 2 + 0.017 * i, 3 }, w[3], m, n;

		for (int a = 0; a < 3; a++)
			w[a] = p[a] * 0.25;
		(void)vx_perturb_field(&pt, &g, p, NULL, &m);
		n = vx_noise_fbm_eval(&pt.density, w, NULL);
		assert_true(m == fmax(0, 1 + 8 * n));
		clamped += m == 0;
	}
	assert_true(clamped > 0);       /* the clamp was exercised */
	vx_grid_free(&g);
}

/* the clear mask eroded by the displacement's reach */
static void
clear_mask(void **state)
{
	vx_grid g;
	vx_macro m;
	vx_tf tf;
	vx_scene s;
	vx_perturb pt;
	vx_err e = { 0, "" };
	uint8_t *c0, *c1;
	size_t n;
	int64_t *d;

	(void)state;
	grid(&g, fwave);
	memset(&m, 0, sizeof m);
	m.nlev = 1;
	for (int a = 0; a < 3; a++) {
		m.width[1][a] = 2;
		m.dims[1][a] = 4;
	}
	d = m.dims[1];
	n = 64;
	m.mm[1] = calloc(2 * n, sizeof(float));
	c0 = malloc(n);
	c1 = malloc(n);
	assert_non_null(m.mm[1]);
	/* a pattern of clear (value 5) and not (0) macrocells */
	for (size_t i = 0; i < n; i++) {
		float v = (i * 7 + i / 5) % 3 == 0 ? 0.0f : 5.0f;

		m.mm[1][2 * i] = m.mm[1][2 * i + 1] = v;
	}
	vx_tf_init(&tf);
	scene(&s, "transfer opacity 0 0.5 1 0\n"
	    "perturb coordinates scale 1 amplitude 0.6\n");
	assert_int_equal(vx_tf_apply_scene(&tf, &s, &e), 0);
	for (size_t i = 0; i < n; i++)
		c0[i] = c1[i] = (uint8_t)vx_tf_range_clear(&tf, m.mm[1][2 * i],
		    m.mm[1][2 * i + 1]);
	assert_int_equal(vx_perturb_init(&pt, &s, &e), 0);
	assert_int_equal(vx_perturb_clear(&pt, &tf, &g, &m, c1, &e), 0);
	/* reach 0.6 world = 2.4 cells = ceil(1.2) = 2 macrocells per axis */
	for (int64_t z = 0; z < d[2]; z++)
		for (int64_t y = 0; y < d[1]; y++)
			for (int64_t x = 0; x < d[0]; x++) {
				int want = 1;

				for (int64_t k = z - 2; k <= z + 2; k++)
					for (int64_t j = y - 2; j <= y + 2; j++)
						for (int64_t i = x - 2; i <= x + 2; i++)
							if (i >= 0 && j >= 0 && k >= 0 &&
							    i < d[0] && j < d[1] && k < d[2])
								want &= c0[i + 4 * (j + 4 * k)];
				assert_int_equal(c1[x + 4 * (y + 4 * z)], want);
			}
	/* value perturbation: ranges widened (5 - 4.5 reaches opacity) */
	scene(&s, "transfer opacity 0 0.5 1 0\n"
	    "perturb value scale 1 amplitude 4.5\n");
	assert_int_equal(vx_perturb_init(&pt, &s, &e), 0);
	assert_int_equal(vx_perturb_clear(&pt, &tf, &g, &m, c1, &e), 0);
	for (size_t i = 0; i < n; i++)
		assert_int_equal(c1[i], 0);
	vx_tf_free(&tf);
	free(m.mm[1]);
	free(c0);
	free(c1);
	vx_grid_free(&g);
}

/* the surface weight by gradient magnitude */
static void
surface_ramp(void **state)
{
	static const struct { double g, want; } t[] = {
		{ 0, 0 }, { 1, 0 },                 /* at and below G0 */
		{ 1.5, 0.25 }, { 2, 0.5 },          /* (g - 1) / (3 - 1) */
		{ 3, 1 }, { 40, 1 },                /* at and above G1 */
	};
	vx_scene s;
	vx_tf tf;
	vx_tf_sample c;
	vx_err e = { 0, "" };

	(void)state;
	for (int list = 0; list < 2; list++) {
		scene(&s, list ? "transfer opacity 0 0.5\n"
		    "transfer surface 0 0.8\n"
		    "transfer surface gradient 1 3\n" :
		    "transfer opacity 0 0.5\ntransfer surface gradient 1 3\n");
		vx_tf_init(&tf);
		assert_int_equal(vx_tf_apply_scene(&tf, &s, &e), 0);
		assert_int_equal(vx_tf_check(&tf, &e), 0);
		assert_true(vx_tf_has_surface(&tf));
		assert_true(vx_tf_class_gradient(&tf));
		assert_true(vx_tf_needs_gradient(&tf));
		for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
			vx_tf_classify(&tf, 0.2, t[i].g, &c);
			assert_true(fabs(c.surface - (list ? 0.8 : 1) * t[i].want) <
			    1e-15);
			assert_true(c.alpha == 0.5);    /* the ramp is the surface's */
		}
		{
			/* no classification table: it has no gradient axis */
			vx_tf_lut lut;

			assert_int_equal(vx_tf_lut_build(&lut, &tf, 0, 1, 16, &e),
			    VX_EDATA);
		}
		vx_tf_free(&tf);
	}
}

static void
scene_lines(void **state)
{
	static const char *good =
	    "transfer opacity 0 0.5\n"
	    "transfer surface gradient 0.25 2.5\n"
	    "perturb coordinates scale 0.7 amplitude 0.5 octaves 5 gain 0.55\n"
	    "perturb density scale 0.12 amplitude 1.5 noise turbulence "
	    "seed 77 lacunarity 2.5\n";
	static const char *bad[] = {
		"perturb\n", "perturb sideways scale 1 amplitude 1\n",
		"perturb value amplitude 1\n", "perturb value scale 1\n",
		"perturb value scale 0 amplitude 1\n",
		"perturb value scale 1 amplitude -1\n",
		"perturb value scale 1 amplitude 1 octaves 25\n",
		"perturb value scale 1 amplitude 1 octaves 0\n",
		"perturb value scale 1 amplitude 1 gain 0\n",
		"perturb value scale 1 amplitude 1 lacunarity 1001\n",
		"perturb value scale 1 amplitude 1 seed -1\n",
		"perturb value scale 1 amplitude 1 noise perlin\n",
		"perturb value scale 1 amplitude 1 scale 2\n",
		"transfer surface gradient 2 1\n",
		"transfer surface gradient 1 1\n",
		"transfer surface gradient -1 1\n",
		"transfer surface gradient 1\n",
	};
	vx_scene s, t;
	vx_err e = { 0, "" };
	char *text;
	size_t n;

	(void)state;
	scene(&s, good);
	assert_int_equal(s.perturb[0].on, 1);
	assert_int_equal(s.perturb[1].on, 0);
	assert_int_equal(s.perturb[2].seed, 77);
	assert_int_equal(s.perturb[2].octaves, 4);      /* the default */
	assert_int_equal(vx_scene_format(&s, &text, &n, &e), 0);
	scene(&t, text);
	free(text);
	assert_true(vx_scene_equal(&s, &t));
	t.perturb[2].seed = 78;
	assert_false(vx_scene_equal(&s, &t));
	/* removal */
	assert_int_equal(vx_scene_apply(&s, "perturb coordinates none", &e), 0);
	assert_int_equal(s.perturb[0].on, 0);
	assert_int_equal(s.perturb[2].on, 1);
	assert_int_equal(vx_scene_apply(&s, "perturb none", &e), 0);
	assert_int_equal(s.perturb[2].on, 0);
	assert_int_equal(vx_scene_apply(&s, "transfer none", &e), 0);
	assert_int_equal(s.has_tf_surface_ramp, 0);
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		e.msg[0] = '\0';
		if (vx_scene_parse(&s, bad[i], strlen(bad[i]), &e) != VX_EDATA)
			fail_msg("accepted: %s", bad[i]);
		assert_non_null(strstr(e.msg, "line 1"));
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(none_is_plain),
		cmocka_unit_test(constant_unchanged),
		cmocka_unit_test(linear_field),
		cmocka_unit_test(density_optics),
		cmocka_unit_test(density_factor),
		cmocka_unit_test(clear_mask),
		cmocka_unit_test(surface_ramp),
		cmocka_unit_test(scene_lines),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
