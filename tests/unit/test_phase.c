/* test_phase.c: phase functions (vx_phase.h).  Oracles: the definitions
 * integrated by quadrature (normalization over the sphere = 1, mean
 * cosine = g: Henyey and Greenstein's defining property), a chi-squared
 * test of the sampled cosines against the pdf's bin integrals, the pdf
 * returned by the sampler equal to the evaluation, unit sampled
 * directions, and the 1D table (the paper's approximation) against the
 * function. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "vx_phase.h"
#include "vx_rng.h"

static const double gs[] = { 0, -0.7, -0.3, 0.0005, 0.2, 0.5, 0.8, 0.95 };
#define NG (sizeof gs / sizeof gs[0])

/* simpson: 2 pi times the integral over cos in [-1, 1] of f(cos) p(cos)
 * with n (even) intervals. */
static double
simpson(double g, int moment, int n)
{
	double h = 2.0 / n, s = 0;

	for (int i = 0; i <= n; i++) {
		double c = -1 + i * h;
		double w = (i == 0 || i == n) ? 1 : (i % 2) ? 4 : 2;

		s += w * vx_phase_hg(g, c) * (moment ? c : 1);
	}
	return 2 * M_PI * s * h / 3;
}

static void
normalized(void **state)
{
	(void)state;
	assert_true(fabs(vx_phase_iso() * 4 * M_PI - 1) < 1e-15);
	assert_true(vx_phase_hg(0, 0.3) == vx_phase_iso());
	for (size_t i = 0; i < NG; i++) {
		/* 2e5 intervals: Simpson's error at g = 0.95 (peak 1/(1-g)^2
		 * sharp) is far below 1e-6 */
		assert_true(fabs(simpson(gs[i], 0, 200000) - 1) < 1e-6);
		assert_true(fabs(simpson(gs[i], 1, 200000) - gs[i]) < 1e-6);
	}
}

/* Sampling: 2^17 cosines into 32 bins of equal width; the expected count
 * of a bin is N times the integral of 2 pi p over it (Simpson).  With 31
 * degrees of freedom, chi-squared above 70 has probability below 1e-4 for
 * a correct sampler; the numbers are fixed (seeded), so the test is
 * deterministic. */
static void
sampling(void **state)
{
	enum { N = 1 << 17, B = 32 };
	static const double w_in[3] = { 0.48, -0.6, 0.64 };   /* unit */

	(void)state;
	for (size_t i = 0; i < NG; i++) {
		double g = gs[i], chi = 0, mean = 0;
		long count[B] = { 0 };

		for (uint64_t k = 0; k < N; k++) {
			double w[3], c, pdf, len;
			int b;

			pdf = vx_phase_hg_sample(g, w_in,
			    vx_rng_uniform(7, i, k, 0),
			    vx_rng_uniform(7, i, k, 1), w);
			len = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
			assert_true(fabs(len - 1) < 1e-12);
			assert_true(pdf == vx_phase_hg_pdf(g, w_in, w));
			c = w[0] * w_in[0] + w[1] * w_in[1] + w[2] * w_in[2];
			assert_true(fabs(pdf - vx_phase_hg(g, c)) <=
			    1e-9 * pdf);
			mean += c;
			b = (int)((c + 1) / 2 * B);
			count[b < 0 ? 0 : b >= B ? B - 1 : b]++;
		}
		for (int b = 0; b < B; b++) {
			/* integral of 2 pi p over the bin, Simpson, 64 steps */
			double lo = -1 + 2.0 * b / B, h = 2.0 / B / 64, s = 0;

			for (int j = 0; j <= 64; j++)
				s += ((j == 0 || j == 64) ? 1 : (j % 2) ? 4 : 2) *
				    vx_phase_hg(g, lo + j * h);
			s *= 2 * M_PI * h / 3 * N;
			chi += (count[b] - s) * (count[b] - s) / s;
		}
		assert_true(chi < 70);
		/* the sample mean cosine: g within 5 standard errors (the
		 * variance of cos is below 1) */
		assert_true(fabs(mean / N - g) < 5 / sqrt(N));
	}
}

/* The table: between its nodes within the linear-interpolation bound
 * h^2/8 max|p''| relative to p (7e-3 at g = 0.7, 5e-2 at g = 0.8 on 256
 * entries), checked on a fine grid; its ends exact. */
static void
table(void **state)
{
	vx_phase_table t;

	(void)state;
	for (size_t i = 0; i < NG; i++) {
		/* p''/p = 15 g^2 / d^2 with d = 1 + g^2 - 2 g c, largest at the
		 * peak, d = (1 - |g|)^2; h = 2 / 255 in cos */
		double h = 2.0 / (VX_PHASE_TABLE_N - 1), a = 1 - fabs(gs[i]);
		double bound = h * h / 8 * 15 * gs[i] * gs[i] / (a * a * a * a);
		double worst = 0;

		if (fabs(gs[i]) > 0.8)
			continue;
		vx_phase_table_hg(&t, gs[i]);
		for (int k = 0; k <= 100000; k++) {
			double c = -1 + 2.0 * k / 100000;
			double want = 4 * M_PI * vx_phase_hg(gs[i], c);
			double r = fabs(vx_phase_table_eval(&t, c) - want) / want;

			if (r > worst)
				worst = r;
		}
		assert_true(worst <= bound * 1.001 + 1e-6);
	}
	vx_phase_table_hg(&t, 0);
	assert_true(vx_phase_table_eval(&t, 0.37) == 1);
	assert_true(vx_phase_table_eval(&t, NAN) == 1);
	vx_phase_table_hg(&t, 0.5);
	assert_true(fabs(vx_phase_table_eval(&t, 1) - 6) < 1e-6);
	assert_true(fabs(vx_phase_table_eval(&t, 7) - 6) < 1e-6);
	assert_true(fabs(vx_phase_table_eval(&t, -1) - 0.75 / 3.375) < 1e-6);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(normalized),
		cmocka_unit_test(sampling),
		cmocka_unit_test(table),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
