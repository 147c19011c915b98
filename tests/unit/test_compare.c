/* test_compare.c: error metrics on tiny images with answers worked by hand,
 * NaN and infinity bookkeeping, and the false-color difference maps. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "vx_compare.h"

static void
make(vx_image *img, int w, int h, int nc, const float *v)
{
	vx_err e = { 0, "" };

	assert_int_equal(vx_image_alloc(img, w, h, nc, &e), 0);
	memcpy(img->px, v, vx_image_nvalue(img) * sizeof(float));
}

static void
near(double got, double want)
{
	if (!(fabs(got - want) <= 1e-9 * (1 + fabs(want))))
		fail_msg("got %.12g, want %.12g", got, want);
}

static void
metrics_known(void **state)
{
	/* Oracle per row: the definitions evaluated by hand.
	 * mse = mean (a-b)^2; relmse = mean (a-b)^2 / (b^2 + 0.01);
	 * psnr = 10 log10(peak^2 / mse). */
	static const struct {
		int w, h, nc;
		float a[8], b[8];
		double peak;
		size_t n, nan_a, nan_b, inf;
		double mse, relmse, psnr, max_abs;
		int mx, my, mc;
	} t[] = {
		/* one value off by 0.5: mse .25/4, relmse (.25/.26)/4,
		 * psnr 10 log10(16) = 12.0412 */
		{ 2, 2, 1, { 0, 0, 0, 0 }, { 0, 0, 0, 0.5f }, 1, 4, 0, 0, 0,
		  0.0625, 0.25 / 0.26 / 4, 12.041199826559248, 0.5, 1, 1, 0 },
		/* every value off by 1 with peak 255: psnr 20 log10(255),
		 * the largest error first met at (0,0) channel 0 */
		{ 2, 1, 3, { 1, 2, 3, 4, 5, 6 }, { 0, 1, 2, 3, 4, 5 }, 255, 6,
		  0, 0, 0, 1, (1 / 0.01 + 1 / 1.01 + 1 / 4.01 + 1 / 9.01 +
		  1 / 16.01 + 1 / 25.01) / 6, 48.1308036086791, 1, 0, 0, 0 },
		/* a NaN in a is skipped and counted: 3 pairs, one off by 1 */
		{ 4, 1, 1, { NAN, 1, 2, 3 }, { 0, 1, 2, 4 }, 1, 3, 1, 0, 0,
		  1.0 / 3, 1 / 16.01 / 3, 4.771212547196624 /* 10 log10 3 */, 1, 3, 0, 0 },
		/* NaN in both at one place, in b at another */
		{ 4, 1, 1, { NAN, 1, 2, 3 }, { NAN, NAN, 2, 3 }, 1, 2, 1, 2, 0,
		  0, 0, INFINITY, 0, 0, 0, 0 },
		/* equal infinities are equal; an unequal one is skipped */
		{ 3, 1, 1, { INFINITY, INFINITY, 1 }, { INFINITY, 5, 1.5f }, 1,
		  2, 0, 0, 1, 0.125, 0.25 / 2.26 / 2, 9.030899869919436 /* 10 log10 8 */, 0.5, 2,
		  0, 0 },
		/* the second channel of the second pixel is worst: (1, 0, 1) */
		{ 2, 1, 2, { 0.5f, 0.5f, 0.5f, 0.25f }, { 0.5f, 0.5f, 0.5f, 1 },
		  1, 4, 0, 0, 0, 0.5625 / 4, 0.5625 / 1.01 / 4,
		  8.519374645445623 /* 10 log10(4/.5625) */, 0.75, 1, 0, 1 },
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_image a, b;
		vx_compare r;
		vx_err e = { 0, "" };

		make(&a, t[i].w, t[i].h, t[i].nc, t[i].a);
		make(&b, t[i].w, t[i].h, t[i].nc, t[i].b);
		assert_int_equal(vx_image_compare(&r, &a, &b, t[i].peak, &e), 0);
		assert_int_equal(r.n, t[i].n);
		assert_int_equal(r.nan_a, t[i].nan_a);
		assert_int_equal(r.nan_b, t[i].nan_b);
		assert_int_equal(r.inf_mismatch, t[i].inf);
		near(r.mse, t[i].mse);
		near(r.rmse, sqrt(t[i].mse));
		near(r.relmse, t[i].relmse);
		if (isinf(t[i].psnr))
			assert_true(isinf(r.psnr) && r.psnr > 0);
		else
			near(r.psnr, t[i].psnr);
		near(r.max_abs, t[i].max_abs);
		assert_int_equal(r.max_x, t[i].mx);
		assert_int_equal(r.max_y, t[i].my);
		assert_int_equal(r.max_c, t[i].mc);
		near(r.peak, t[i].peak);
		vx_image_free(&a);
		vx_image_free(&b);
	}
}

static void
metrics_errors(void **state)
{
	static const float v[4] = { NAN, NAN, 1, 2 };
	vx_image a, b, c;
	vx_compare r;
	vx_err e = { 0, "" };

	(void)state;
	make(&a, 2, 2, 1, v);
	make(&b, 2, 2, 1, v);
	b.px[2] = NAN;
	b.px[3] = NAN;
	/* nothing left to compare */
	assert_int_equal(vx_image_compare(&r, &a, &b, 1, &e), VX_EDATA);
	assert_non_null(strstr(e.msg, "no pair"));
	/* sizes and channels must match */
	make(&c, 4, 1, 1, v);
	assert_int_equal(vx_image_compare(&r, &a, &c, 1, &e), VX_EDATA);
	vx_image_free(&c);
	make(&c, 1, 2, 2, v);
	assert_int_equal(vx_image_compare(&r, &a, &c, 1, &e), VX_EDATA);
	assert_int_equal(vx_image_compare(&r, &a, &a, 0, &e), VX_EUSAGE);
	assert_int_equal(vx_image_compare(&r, &a, &a, NAN, &e), VX_EUSAGE);
	vx_image_free(&a);
	vx_image_free(&b);
	vx_image_free(&c);
}

/* rgb_is: a float pixel against 8-bit color codes (float precision) */
static void
rgb_is(const float *p, double r, double g, double b)
{
	if (fabs(p[0] - r / 255) > 1e-6 || fabs(p[1] - g / 255) > 1e-6 ||
	    fabs(p[2] - b / 255) > 1e-6)
		fail_msg("got %g %g %g, want %g %g %g", p[0] * 255, p[1] * 255,
		    p[2] * 255, r, g, b);
}

static void
diff_maps(void **state)
{
	/* a - b per pixel: 0, 0.5, 1, -1, NaN.  Oracle: the colormap stops
	 * (viridis #440154 at 0, #21918c at 1/2, #fde725 at 1; white at 0
	 * and #3b4cc0 / #b40426 at -1 / +1 for the signed map; magenta for a
	 * skipped pair). */
	static const float av[5] = { 1, 1.5f, 2, 0, NAN };
	static const float bv[5] = { 1, 1, 1, 1, 0 };
	vx_image a, b, d;
	vx_err e = { 0, "" };
	double scale = 0;

	(void)state;
	make(&a, 5, 1, 1, av);
	make(&b, 5, 1, 1, bv);
	assert_int_equal(vx_image_diff(&d, &a, &b, VX_DIFF_ABS, &scale, &e), 0);
	near(scale, 1);
	assert_int_equal(d.nc, 3);
	rgb_is(vx_image_pixel(&d, 0, 0), 0x44, 0x01, 0x54);
	rgb_is(vx_image_pixel(&d, 1, 0), 0x21, 0x91, 0x8c);
	rgb_is(vx_image_pixel(&d, 2, 0), 0xfd, 0xe7, 0x25);
	rgb_is(vx_image_pixel(&d, 3, 0), 0xfd, 0xe7, 0x25);
	rgb_is(vx_image_pixel(&d, 4, 0), 255, 0, 255);
	vx_image_free(&d);
	scale = 0;
	assert_int_equal(vx_image_diff(&d, &a, &b, VX_DIFF_SIGNED, &scale, &e),
	    0);
	rgb_is(vx_image_pixel(&d, 0, 0), 255, 255, 255);
	rgb_is(vx_image_pixel(&d, 1, 0), (255 + 0xb4) / 2.0,
	    (255 + 0x04) / 2.0, (255 + 0x26) / 2.0);
	rgb_is(vx_image_pixel(&d, 2, 0), 0xb4, 0x04, 0x26);
	rgb_is(vx_image_pixel(&d, 3, 0), 0x3b, 0x4c, 0xc0);
	vx_image_free(&d);
	/* a given scale: 0.5 in a scale of 2 is a quarter: stop 2, #3b528b */
	scale = 2;
	assert_int_equal(vx_image_diff(&d, &a, &b, VX_DIFF_ABS, &scale, &e), 0);
	near(scale, 2);
	rgb_is(vx_image_pixel(&d, 1, 0), 0x3b, 0x52, 0x8b);
	vx_image_free(&d);
	assert_int_equal(vx_image_diff(&d, &a, &b, 9, &scale, &e), VX_EUSAGE);
	vx_image_free(&a);
	vx_image_free(&b);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(metrics_known),
		cmocka_unit_test(metrics_errors),
		cmocka_unit_test(diff_maps),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
