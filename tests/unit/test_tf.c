/* test_tf.c: transfer-function containers (vx_tf.h): list evaluation
 * (clamping, linear interpolation, steps at equal abscissae, NaN), the
 * setters' refusals, and the usability check. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

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

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(eval),
		cmocka_unit_test(refusals),
		cmocka_unit_test(check),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
