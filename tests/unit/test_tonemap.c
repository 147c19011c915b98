/* test_tonemap.c: tone operators, transfer functions, alpha handling,
 * repair of NaN / inf / negative values, dither, determinism. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "vx_tonemap.h"

#define TOL 1e-6

static void
close_to(double got, double want, const char *what, int i)
{
	if (!(fabs(got - want) <= TOL))
		fail_msg("%s case %d: got %.9g, want %.9g", what, i, got, want);
}

/* One gray value through exposure 0, the operator, and no transfer
 * function.  Oracle: the formulas written out by hand per row
 * (reinhard: x/(1+x), with white W: x(1+x/W^2)/(1+x); aces:
 * x(2.51x+0.03)/(x(2.43x+0.59)+0.14); all clamped to [0,1]; NaN, negative,
 * -inf give 0, +inf gives 1). */
static void
operators_gray(void **state)
{
	static const struct { int op; double white; float x; double want; } t[] = {
		{ VX_TM_CLAMP, 0, 0.0f, 0 },
		{ VX_TM_CLAMP, 0, 0.5f, 0.5 },
		{ VX_TM_CLAMP, 0, 1.0f, 1 },
		{ VX_TM_CLAMP, 0, 1e30f, 1 },
		{ VX_TM_CLAMP, 0, -1.0f, 0 },
		{ VX_TM_CLAMP, 0, NAN, 0 },
		{ VX_TM_CLAMP, 0, INFINITY, 1 },
		{ VX_TM_CLAMP, 0, -INFINITY, 0 },
		{ VX_TM_REINHARD, 0, 0.0f, 0 },
		{ VX_TM_REINHARD, 0, 1.0f, 0.5 },
		{ VX_TM_REINHARD, 0, 3.0f, 0.75 },
		{ VX_TM_REINHARD, 0, 0.25f, 0.2 },
		{ VX_TM_REINHARD, 0, 1e30f, 1 },
		{ VX_TM_REINHARD, 0, -1.0f, 0 },
		{ VX_TM_REINHARD, 0, NAN, 0 },
		{ VX_TM_REINHARD, 0, INFINITY, 1 },
		{ VX_TM_REINHARD, 0, -INFINITY, 0 },
		{ VX_TM_REINHARD, 2, 1.0f, 1.25 / 2 },
		{ VX_TM_REINHARD, 2, 0.5f, 0.5 * 1.125 / 1.5 },
		{ VX_TM_REINHARD, 2, 2.0f, 1 },           /* the white point */
		{ VX_TM_REINHARD, 2, 4.0f, 1 },           /* 1.6, clamped */
		{ VX_TM_REINHARD, 2, INFINITY, 1 },
		{ VX_TM_REINHARD, INFINITY, 1.0f, 0.5 },  /* no white point */
		{ VX_TM_ACES, 0, 0.0f, 0 },
		{ VX_TM_ACES, 0, 0.1f, 0.1 * 0.281 / (0.1 * 0.833 + 0.14) },
		{ VX_TM_ACES, 0, 0.5f, 0.6425 / 1.0425 },
		{ VX_TM_ACES, 0, 1.0f, 2.54 / 3.16 },
		{ VX_TM_ACES, 0, 10.0f, 1 },              /* 251.3/249.04, clamped */
		{ VX_TM_ACES, 0, 1e30f, 1 },
		{ VX_TM_ACES, 0, -1.0f, 0 },
		{ VX_TM_ACES, 0, NAN, 0 },
		{ VX_TM_ACES, 0, INFINITY, 1 },
		{ VX_TM_ACES, 0, -INFINITY, 0 },
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_tonemap_opts o;
		float out;

		vx_tonemap_defaults(&o);
		o.op = t[i].op;
		o.white = t[i].white;
		o.transfer = VX_TF_LINEAR;
		vx_tonemap_pixel(&o, &t[i].x, 1, &out, NULL);
		close_to(out, t[i].want, vx_enum_str(&vx_tonemap_op_enum,
		    t[i].op), (int)i);
	}
	/* the curve itself, below the final clamp (reinhard above white) */
	close_to(vx_tonemap_curve(VX_TM_REINHARD, 4, 2), 4 * 2.0 / 5, "curve",
	    0);
	close_to(vx_tonemap_curve(VX_TM_ACES, 1e300, 0), 1, "curve", 1);
}

/* Transfer functions.  Oracle: the IEC 61966-2-1 formula evaluated in
 * python3 (values pasted), and pow(0.5, 1/2.2) likewise. */
static void
transfer_functions(void **state)
{
	static const struct { double x, want; } srgb[] = {
		{ 0, 0 },
		{ 0.001, 0.012920000000000001 },
		{ 0.0031308, 0.040449936 },
		{ 0.18, 0.46135612950044164 },
		{ 0.5, 0.7353569830524495 },
		{ 0.9, 0.9546871718858662 },
		{ 1, 1 },
		{ 2, 1 },
		{ -1, 0 },
	};

	(void)state;
	for (size_t i = 0; i < sizeof srgb / sizeof srgb[0]; i++) {
		close_to(vx_srgb_oetf(srgb[i].x), srgb[i].want, "srgb", (int)i);
		if (srgb[i].x >= 0 && srgb[i].x <= 1)
			close_to(vx_srgb_eotf(srgb[i].want), srgb[i].x, "eotf",
			    (int)i);
	}
	assert_true(vx_srgb_oetf(NAN) == 0);
	/* through the pixel pipeline: clamp, then each transfer */
	{
		vx_tonemap_opts o;
		float in = 0.5f, out;

		vx_tonemap_defaults(&o);
		vx_tonemap_pixel(&o, &in, 1, &out, NULL);
		close_to(out, 0.7353569830524495, "pixel srgb", 0);
		o.transfer = VX_TF_GAMMA;
		o.gamma = 2.2;
		vx_tonemap_pixel(&o, &in, 1, &out, NULL);
		close_to(out, 0.7297400528407231, "pixel gamma", 0);
		o.transfer = VX_TF_LINEAR;
		vx_tonemap_pixel(&o, &in, 1, &out, NULL);
		close_to(out, 0.5, "pixel linear", 0);
		/* exposure: +2 stops is x4, -1 stop is x0.5 */
		in = 0.125f;
		o.exposure = 2;
		vx_tonemap_pixel(&o, &in, 1, &out, NULL);
		close_to(out, 0.5, "exposure +2", 0);
		o.exposure = -1;
		vx_tonemap_pixel(&o, &in, 1, &out, NULL);
		close_to(out, 0.0625, "exposure -1", 0);
	}
}

/* Reinhard on RGB works on Rec. 709 luminance L = .2126 R + .7152 G +
 * .0722 B and scales all channels by L_d / L, so hue and saturation stay
 * until a channel clips.  Oracle: the arithmetic done by hand per row. */
static void
reinhard_rgb(void **state)
{
	static const struct { float in[3]; double want[3]; } t[] = {
		/* L = .2126, scale 1 / 1.2126 */
		{ { 1, 0, 0 }, { 1 / 1.2126, 0, 0 } },
		/* L = .5 * .7152 + .5 * .0722 = .3937, scale 1 / 1.3937 */
		{ { 0, 0.5f, 0.5f }, { 0, 0.5 / 1.3937, 0.5 / 1.3937 } },
		/* NaN red counts as 0: same as the row above */
		{ { NAN, 0.5f, 0.5f }, { 0, 0.5 / 1.3937, 0.5 / 1.3937 } },
		/* L = 4 * .0722 = .2888: blue 4 / 1.2888 = 3.10 clips to 1 */
		{ { 0, 0, 4 }, { 0, 0, 1 } },
		/* gray stays gray: L = 1 -> 0.5 each */
		{ { 1, 1, 1 }, { 0.5, 0.5, 0.5 } },
		/* an infinite channel: the limit, (1, 0, 0) */
		{ { INFINITY, 1, 0 }, { 1, 0, 0 } },
		{ { INFINITY, INFINITY, -INFINITY }, { 1, 1, 0 } },
		{ { -1, -2, 0 }, { 0, 0, 0 } },
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_tonemap_opts o;
		float out[3];

		vx_tonemap_defaults(&o);
		o.op = VX_TM_REINHARD;
		o.transfer = VX_TF_LINEAR;
		vx_tonemap_pixel(&o, t[i].in, 3, out, NULL);
		for (int c = 0; c < 3; c++)
			close_to(out[c], t[i].want[c], "reinhard rgb", (int)i);
	}
}

/* Premultiplied alpha in, straight alpha out; or flattened over a linear
 * background.  Oracle: straight = color / alpha, flat = straight * alpha +
 * bg * (1 - alpha), worked by hand. */
static void
alpha_handling(void **state)
{
	static const struct {
		int nc, flatten;
		float in[4];
		double bg[3];
		int nco;
		double want[4];
	} t[] = {
		{ 4, 0, { 0.4f, 0.2f, 0, 0.5f }, { 0, 0, 0 }, 4,
		    { 0.8, 0.4, 0, 0.5 } },
		{ 4, 1, { 0.4f, 0.2f, 0, 0.5f }, { 1, 1, 1 }, 3,
		    { 0.9, 0.7, 0.5 } },
		{ 4, 1, { 0.4f, 0.2f, 0, 0.5f }, { 0, 0, 0 }, 3,
		    { 0.4, 0.2, 0 } },
		/* color over 1 clamps before compositing: 3 / 1 -> 1 */
		{ 4, 1, { 3, 0, 0, 1 }, { 0, 1, 0 }, 3, { 1, 0, 0 } },
		/* no coverage: color 0 whatever was stored */
		{ 4, 0, { 0.3f, 0.3f, 0.3f, 0 }, { 0, 0, 0 }, 4, { 0, 0, 0, 0 } },
		{ 4, 0, { 0.3f, 0.3f, 0.3f, NAN }, { 0, 0, 0 }, 4, { 0, 0, 0, 0 } },
		{ 4, 0, { 0.3f, 0.3f, 0.3f, -1 }, { 0, 0, 0 }, 4, { 0, 0, 0, 0 } },
		/* alpha above 1 clamps to 1 */
		{ 4, 0, { 0.3f, 0.3f, 0.3f, 2 }, { 0, 0, 0 }, 4,
		    { 0.3, 0.3, 0.3, 1 } },
		/* gray + alpha over red: background gray = .2126 */
		{ 2, 1, { 0.25f, 0.5f }, { 1, 0, 0 }, 1,
		    { 0.5 * 0.5 + 0.2126 * 0.5 } },
		{ 2, 0, { 0.25f, 0.5f }, { 1, 0, 0 }, 2, { 0.5, 0.5 } },
		/* no alpha channel: flattening changes nothing */
		{ 3, 1, { 0.25f, 0.5f, 0.75f }, { 1, 1, 1 }, 3,
		    { 0.25, 0.5, 0.75 } },
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_tonemap_opts o;
		float out[4];

		vx_tonemap_defaults(&o);
		o.transfer = VX_TF_LINEAR;
		o.flatten = t[i].flatten;
		memcpy(o.background, t[i].bg, sizeof o.background);
		assert_int_equal(vx_tonemap_nc_out(&o, t[i].nc), t[i].nco);
		vx_tonemap_pixel(&o, t[i].in, t[i].nc, out, NULL);
		for (int c = 0; c < t[i].nco; c++)
			close_to(out[c], t[i].want[c], "alpha", (int)i);
	}
}

/* The repair counts and the whole-image path. */
static void
image_stats(void **state)
{
	static const float v[8] = { NAN, -1, -INFINITY, INFINITY, 0.5f, NAN,
	    2, 0 };
	vx_image src, dst;
	vx_tonemap_opts o;
	vx_tonemap_stats st;
	vx_err e = { 0, "" };

	(void)state;
	assert_int_equal(vx_image_alloc(&src, 4, 2, 1, &e), 0);
	memcpy(src.px, v, sizeof v);
	snprintf(src.name, sizeof src.name, "color");
	vx_tonemap_defaults(&o);
	o.transfer = VX_TF_LINEAR;
	assert_int_equal(vx_tonemap_image(&dst, &src, &o, &st, &e), 0);
	assert_int_equal(st.nan, 2);
	assert_int_equal(st.neg, 2);
	assert_int_equal(st.posinf, 1);
	assert_string_equal(dst.name, "color");
	static const float want[8] = { 0, 0, 0, 1, 0.5f, 0, 1, 0 };
	for (int i = 0; i < 8; i++)
		assert_true(dst.px[i] == want[i]);
	vx_image_free(&dst);
	/* bad options are refused */
	o.transfer = VX_TF_GAMMA;
	o.gamma = 0;
	assert_int_equal(vx_tonemap_image(&dst, &src, &o, NULL, &e), VX_EUSAGE);
	vx_tonemap_defaults(&o);
	o.op = 17;
	assert_int_equal(vx_tonemap_image(&dst, &src, &o, NULL, &e), VX_EUSAGE);
	vx_image_free(&src);
}

/* Dither: a flat field at code k + 0.25 quantizes to k everywhere without
 * dither, and to k + 1 on about a quarter of the pixels with it (the
 * threshold is uniform); 0 and 1 stay exact; results are the same with 1
 * and 4 threads. */
static void
dither_and_threads(void **state)
{
	vx_image src, a, b;
	vx_tonemap_opts o;
	vx_err e = { 0, "" };
	size_t i, n, up = 0;

	(void)state;
	assert_int_equal(vx_image_alloc(&src, 64, 64, 1, &e), 0);
	n = vx_image_nvalue(&src);
	for (i = 0; i < n; i++)
		src.px[i] = (float)((100 + 0.25) / 255);
	src.px[0] = 0;
	src.px[1] = 1;
	vx_tonemap_defaults(&o);
	o.transfer = VX_TF_LINEAR;
	assert_int_equal(vx_tonemap_image(&a, &src, &o, NULL, &e), 0);
	vx_image_quantize(&a, 8);
	for (i = 2; i < n; i++)
		assert_true(a.px[i] == (float)(100 / 255.0));
	vx_image_free(&a);
	o.dither_bits = 8;
	o.seed = 7;
#ifdef _OPENMP
	omp_set_num_threads(1);
#endif
	assert_int_equal(vx_tonemap_image(&a, &src, &o, NULL, &e), 0);
#ifdef _OPENMP
	omp_set_num_threads(4);
#endif
	assert_int_equal(vx_tonemap_image(&b, &src, &o, NULL, &e), 0);
	assert_memory_equal(a.px, b.px, n * sizeof(float));
	vx_image_quantize(&a, 8);
	assert_true(a.px[0] == 0);
	assert_true(a.px[1] == 1);
	for (i = 2; i < n; i++) {
		assert_true(a.px[i] == (float)(100 / 255.0) ||
		    a.px[i] == (float)(101 / 255.0));
		up += a.px[i] == (float)(101 / 255.0);
	}
	/* 4094 Bernoulli(1/4) draws: mean 1023.5, sd 27.7; allow 5 sd */
	assert_true(up > 885 && up < 1162);
	vx_image_free(&a);
	vx_image_free(&b);
	vx_image_free(&src);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(operators_gray),
		cmocka_unit_test(transfer_functions),
		cmocka_unit_test(reinhard_rgb),
		cmocka_unit_test(alpha_handling),
		cmocka_unit_test(image_stats),
		cmocka_unit_test(dither_and_threads),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
