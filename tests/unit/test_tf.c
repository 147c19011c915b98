/* test_tf.c: transfer-function containers (vx_tf.h): list evaluation
 * (clamping, linear interpolation, steps at equal abscissae, NaN), the
 * setters' refusals, the usability check; classification (defaults,
 * gradient factor, table), opacity correction, the clear-range test that
 * empty-space skipping relies on, and the scene's transfer lines. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "vx_scene.h"
#include "vx_tf.h"

/* A list with a ramp and a step; the oracle is the definition in vx_tf.h
 * worked by hand. */
static void
eval(void **state)
{
	static const double x[] = { 0, 10, 20, 20, 30 };
	static const double y[] = { 0, 1, 0.5, 0.25, 0.75 };
	static const struct { double t, want; } t[] = {
		{ -5, 0 },          /* clamped below */
		{ 0, 0 }, { 5, 0.5 }, { 10, 1 }, { 15, 0.75 },
		{ 19.999999999999996, 0.50000000000000022 },
		{ 20, 0.25 },       /* the step: the second point's value */
		{ 25, 0.5 }, { 30, 0.75 }, { 1e300, 0.75 },
		{ NAN, 0 },         /* NaN: the first point's value */
	};
	vx_tf_list l = { 0 };
	vx_err e = { 0 };

	(void)state;
	assert_int_equal(vx_tf_list_set(&l, 5, 1, x, y, &e), 0);
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		double out = -1;

		vx_tf_list_eval(&l, t[i].t, &out);
		assert_true(fabs(out - t[i].want) <= 1e-15);
	}
	vx_tf_list_free(&l);
	assert_int_equal(l.n, 0);
}

static void
refusals(void **state)
{
	static const double xs[] = { 0, 1, 2 }, xdown[] = { 0, 2, 1 };
	static const double xnan[] = { 0, NAN, 2 };
	static const double ok[] = { 0, 0.5, 1 }, big[] = { 0, 1.5, 1 };
	static const double ynan[] = { 0, NAN, 1 };
	static const struct {
		const char *what;
		int n, dim;
		const double *x, *y;
		const char *msg;        /* a part of the message */
	} t[] = {
		{ "no points", 0, 1, xs, ok, "0 control points" },
		{ "dim 2", 3, 2, xs, ok, "2 values per point" },
		{ "decreasing", 3, 1, xdown, ok, "point 3" },
		{ "NaN abscissa", 3, 1, xnan, ok, "not finite" },
		{ "value > 1", 3, 1, xs, big, "outside [0, 1]" },
		{ "NaN value", 3, 1, xs, ynan, "outside [0, 1]" },
	};
	double x1[] = { 7 }, y1[] = { 0.5 };
	vx_tf_list l = { 0 };
	vx_err e;

	(void)state;
	assert_int_equal(vx_tf_list_set(&l, 1, 1, x1, y1, &e), 0);
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_err_clear(&e);
		assert_int_equal(vx_tf_list_set(&l, t[i].n, t[i].dim, t[i].x,
		    t[i].y, &e), VX_EDATA);
		assert_non_null(strstr(e.msg, t[i].msg));
		assert_int_equal(l.n, 1);   /* unchanged */
		assert_true(l.x[0] == 7);
	}
	vx_tf_list_free(&l);
}

static void
check(void **state)
{
	static const double x[] = { 0, 1 }, a[] = { 0, 1 };
	static const double rgb[] = { 0, 0, 0, 1, 1, 1 };
	static const float cell[8] = { 1, 0, 0, 0.5, 0, 1, 0, 1 };
	int size[2] = { 2, 1 }, bad[2] = { 0, 1 };
	double vr[2] = { 0, 1 }, gr[2] = { 0, 4 }, empty[2] = { 1, 1 };
	vx_tf tf;
	vx_err e;

	(void)state;
	vx_tf_init(&tf);
	assert_int_equal(vx_tf_check(&tf, &e), VX_EDATA);   /* no opacity */
	assert_non_null(strstr(e.msg, "no opacity"));
	assert_int_equal(vx_tf_list_set(&tf.opacity, 2, 1, x, a, &e), 0);
	assert_int_equal(vx_tf_check(&tf, &e), 0);
	assert_int_equal(vx_tf_list_set(&tf.surface, 2, 3, x, rgb, &e), 0);
	assert_int_equal(vx_tf_check(&tf, &e), VX_EDATA);   /* wrong dim */
	vx_tf_list_free(&tf.surface);
	tf.ref_step = -1;
	assert_int_equal(vx_tf_check(&tf, &e), VX_EDATA);
	tf.ref_step = 0.5;
	assert_int_equal(vx_tf_table_set(&tf, bad, vr, gr, cell, &e),
	    VX_EDATA);
	assert_int_equal(vx_tf_table_set(&tf, size, empty, gr, cell, &e),
	    VX_EDATA);
	assert_int_equal(tf.has_table, 0);
	assert_int_equal(vx_tf_table_set(&tf, size, vr, gr, cell, &e), 0);
	assert_int_equal(vx_tf_check(&tf, &e), VX_EDATA);   /* table + list */
	vx_tf_list_free(&tf.opacity);
	assert_int_equal(vx_tf_check(&tf, &e), 0);
	assert_true(tf.rgba[3] == 0.5f);
	vx_tf_free(&tf);
	assert_int_equal(tf.has_table, 0);
	assert_null(tf.rgba);
}

/* A function from the scene text; the oracles are vx_tf.h's rules. */
static void
tf_from(vx_tf *tf, const char *text)
{
	vx_scene s;
	vx_err e = { 0 };

	assert_int_equal(vx_scene_parse(&s, text, strlen(text), &e), 0);
	vx_tf_init(tf);
	assert_int_equal(vx_tf_apply_scene(tf, &s, &e), 0);
	assert_int_equal(vx_tf_check(tf, &e), 0);
}

static void
classify(void **state)
{
	vx_tf tf;
	vx_tf_sample o;

	(void)state;
	/* defaults: white, transport 1 - alpha, surface 0 */
	tf_from(&tf, "transfer opacity 0 0 10 0.5\n");
	vx_tf_classify(&tf, 5, 0, &o);
	assert_true(o.color[0] == 1 && o.color[1] == 1 && o.color[2] == 1);
	assert_true(o.alpha == 0.25);
	assert_true(o.transport[0] == 0.75 && o.transport[2] == 0.75);
	assert_true(o.surface == 0);
	assert_false(vx_tf_needs_gradient(&tf));
	/* NaN: empty */
	vx_tf_classify(&tf, NAN, 0, &o);
	assert_true(o.alpha == 0 && o.transport[1] == 1 && o.color[0] == 0);
	vx_tf_free(&tf);
	/* gradient factor scales alpha (and so the default transport); the
	 * transport list, the surface list and the step from the scene */
	tf_from(&tf, "transfer opacity 0 0.5\ntransfer gradient 0 0 4 1\n"
	    "transfer transport 0 1 0.5 0.25\ntransfer surface 0 0 8 1\n"
	    "transfer step 0.5\ntransfer color 0 0.2 0.4 0.6\n");
	assert_true(vx_tf_needs_gradient(&tf));
	assert_true(tf.ref_step == 0.5);
	vx_tf_classify(&tf, 2, 1, &o);
	assert_true(o.alpha == 0.125);
	assert_true(o.transport[0] == 1 && o.transport[1] == 0.5 &&
	    o.transport[2] == 0.25);
	assert_true(o.surface == 0.25);
	assert_true(o.color[1] == 0.4);
	vx_tf_free(&tf);
}

/* The table: bilinear between cell centres, clamped at the edges; a
 * scene opacity list replaces it. */
static void
table(void **state)
{
	static const float rgba[2 * 2 * 4] = {
		0, 0, 0, 0,    1, 1, 1, 1,       /* g row 0: v cells 0, 1 */
		0, 0, 0, 0.5f, 0, 0, 0, 0.5f,    /* g row 1 */
	};
	static const int size[2] = { 2, 2 };
	static const double vr[2] = { 0, 2 }, gr[2] = { 0, 1 };
	vx_tf tf;
	vx_tf_sample o;
	vx_scene s;
	vx_err e = { 0 };

	(void)state;
	vx_tf_init(&tf);
	assert_int_equal(vx_tf_table_set(&tf, size, vr, gr, rgba, &e), 0);
	vx_tf_classify(&tf, 1, 0.25, &o);     /* midway in v, row 0 */
	assert_true(o.alpha == 0.5 && o.color[0] == 0.5);
	vx_tf_classify(&tf, 1, 0.5, &o);      /* midway in both */
	assert_true(o.alpha == 0.5 && o.color[0] == 0.25);
	vx_tf_classify(&tf, -9, -9, &o);      /* clamped to cell (0,0) */
	assert_true(o.alpha == 0 && o.transport[0] == 1);
	/* no column is clear (row 1 has alpha 0.5 throughout) */
	assert_false(vx_tf_range_clear(&tf, 0, 0.4));
	assert_false(vx_tf_range_clear(&tf, 1.5, 2));
	assert_true(vx_tf_range_clear(&tf, 3, 2));   /* empty range */
	s = (vx_scene){ 0 };
	vx_scene_init(&s);
	s.ntf_opacity = 1;
	s.tf_opacity[0][0] = 0;
	s.tf_opacity[0][1] = 0.5;
	assert_int_equal(vx_tf_apply_scene(&tf, &s, &e), 0);
	assert_false(tf.has_table);
	assert_int_equal(vx_tf_check(&tf, &e), 0);
	vx_tf_free(&tf);
}

/* vx_tf_range_clear on lists: exact (the maximum of a piecewise-linear
 * function over an interval is at an end or a control point inside). */
static void
clear(void **state)
{
	static const struct { double lo, hi; int want; } t[] = {
		{ 0, 10, 1 },       /* opacity 0 up to 10 */
		{ 0, 10.5, 0 },     /* the ramp starts */
		{ 25, 30, 1 },      /* a hat between 10 and 20 only */
		{ 12, 13, 0 },
		{ -1e300, 9, 1 },
		{ 5, 4, 1 },        /* empty */
		{ NAN, 4, 0 },
		{ 21, 1e300, 0 },   /* transport < 1 beyond 40 */
	};
	vx_tf tf;

	(void)state;
	tf_from(&tf, "transfer opacity 10 0 15 0.5 20 0\n"
	    "transfer transport 0 1 1 1 40 1 1 1 41 1 0.5 1\n");
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++)
		assert_int_equal(vx_tf_range_clear(&tf, t[i].lo, t[i].hi),
		    t[i].want);
	vx_tf_free(&tf);
}

/* Opacity correction: two half steps make one reference step; the ends
 * are exact. */
static void
correct(void **state)
{
	static const double a[] = { 0.01, 0.3, 0.5, 0.9, 0.999 };

	(void)state;
	for (size_t i = 0; i < sizeof a / sizeof a[0]; i++) {
		double h = vx_tf_correct(a[i], 0.5);

		assert_true(fabs(1 - (1 - h) * (1 - h) - a[i]) < 1e-14);
		assert_true(fabs(vx_tf_correct(a[i], 1) - a[i]) < 1e-15);
	}
	assert_true(vx_tf_correct(0, 3) == 0);
	assert_true(vx_tf_correct(1, 0.01) == 1);
}

/* lut_eval: vx_tf_lut_at's quads as the optical form (the oracle's
 * terms). */
static void
lut_eval(const vx_tf_lut *t, double v, vx_tf_optic *o)
{
	vx_f4 q[2];

	vx_tf_lut_at(t, v, q);
	o->sigma = q[0][0];
	for (int c = 0; c < 3; c++) {
		o->color[c] = q[0][1 + c];
		o->ltr[c] = q[1][c];
	}
	o->surface = q[1][3];
}

/* The classification table (vx_tf_lut): exact at its nodes (to single
 * precision); between nodes within the largest slope of each list times
 * the node spacing (both the table and the function lie between the
 * function's extremes over the spacing); NaN the empty sample; outside
 * [lo, hi] the end nodes; a gradient-dependent function refused. */
static void
lut(void **state)
{
	/* kinks between nodes (0.3 is not a node of 7 intervals over
	 * [-1, 2]); slopes: opacity 0.9 / 0.3 = 3, colour 1 / 0.3, transport
	 * 0.5 / 0.7, surface 1 / 3 */
	static const char text[] = "transfer opacity -1 0 0 0 0.3 0.9 1 0.2\n"
	    "transfer color -1 0 0 0 0.3 1 0.5 1 2 1 1 1\n"
	    "transfer transport 0 1 1 1 0.7 0.5 0.5 1\n"
	    "transfer surface -1 0 2 1\n";
	static const int ns[] = { 7, 64, 4096 };
	const double slope[4] = { 3, 1 / 0.3, 0.5 / 0.7, 1.0 / 3 };
	vx_tf tf, tg;
	vx_tf_lut t;
	vx_tf_optic o, x;
	vx_tf_sample c;
	vx_err e = { 0, "" };

	(void)state;
	tf_from(&tf, text);
	for (size_t k = 0; k < sizeof ns / sizeof ns[0]; k++) {
		double h = 3.0 / ns[k];

		assert_int_equal(vx_tf_lut_build(&t, &tf, -1, 2, ns[k], &e), 0);
		for (int i = 0; i <= 1000; i++) {
			double v = -1 + 3.0 * i / 1000;
			vx_tf_sample cl;

			lut_eval(&t, v, &o);
			vx_tf_classify(&tf, v, 0, &cl);
			/* compare in alpha and transport, as renderers use them */
			assert_true(fabs(-expm1(-o.sigma) - cl.alpha) <=
			    slope[0] * h + 1e-6);
			for (int q = 0; q < 3; q++) {
				assert_true(fabs(o.color[q] - cl.color[q]) <=
				    slope[1] * h + 1e-6);
				assert_true(fabs(exp(o.ltr[q]) - cl.transport[q]) <=
				    slope[2] * h + 1e-6);
			}
			assert_true(fabs(o.surface - cl.surface) <= slope[3] * h +
			    1e-6);
		}
		for (int i = 0; i <= ns[k]; i++) {
			double v = i == ns[k] ? 2 : -1 + i / t.scale;

			lut_eval(&t, v, &o);
			vx_tf_classify(&tf, v, 0, &c);
			vx_tf_optic_of(&c, &x);
			assert_true(fabs(o.sigma - x.sigma) <= 1e-6 * (1 + x.sigma));
			assert_true(fabs(o.color[1] - x.color[1]) <= 1e-6);
			assert_true(fabs(o.ltr[0] - x.ltr[0]) <= 1e-6);
		}
		lut_eval(&t, NAN, &o);
		assert_true(o.sigma == 0 && o.color[0] == 0 && o.ltr[2] == 0 &&
		    o.surface == 0);
		lut_eval(&t, 50, &o);    /* beyond hi: the last node */
		vx_tf_classify(&tf, 2, 0, &c);
		assert_true(fabs(-expm1(-o.sigma) - c.alpha) < 1e-6);
		vx_tf_lut_free(&t);
	}
	/* alpha 1 and transport 0 meet the cap: e^-cap is 0 in double */
	{
		vx_tf_sample s = { { 1, 1, 1 }, 1, { 0, 0.5, 1 }, 0 };

		vx_tf_optic_of(&s, &o);
		assert_true(o.sigma == VX_TF_SIGMA_MAX && exp(-o.sigma) == 0);
		assert_true(o.ltr[0] == -VX_TF_SIGMA_MAX && o.ltr[2] == 0);
		assert_true(fabs(exp(o.ltr[1]) - 0.5) < 1e-15);
	}
	/* one value (lo == hi): every lookup is its node */
	assert_int_equal(vx_tf_lut_build(&t, &tf, 0.3, 0.3, 16, &e), 0);
	lut_eval(&t, -5, &o);
	assert_true(fabs(-expm1(-o.sigma) - 0.9) < 1e-6);
	vx_tf_lut_free(&t);
	assert_int_equal(vx_tf_lut_build(&t, &tf, 1, 0, 16, &e), VX_EDATA);
	assert_int_equal(vx_tf_lut_build(&t, &tf, 0, 1, 0, &e), VX_EDATA);
	assert_int_equal(vx_tf_lut_build(&t, &tf, 0, INFINITY, 8, &e),
	    VX_EDATA);
	tf_from(&tg, "transfer opacity 0 0.5\ntransfer gradient 0 0 1 1\n");
	assert_int_equal(vx_tf_lut_build(&t, &tg, 0, 1, 8, &e), VX_EDATA);
	assert_null(t.node);
	vx_tf_free(&tg);
	vx_tf_free(&tf);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(eval),
		cmocka_unit_test(refusals),
		cmocka_unit_test(check),
		cmocka_unit_test(classify),
		cmocka_unit_test(table),
		cmocka_unit_test(clear),
		cmocka_unit_test(correct),
		cmocka_unit_test(lut),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
