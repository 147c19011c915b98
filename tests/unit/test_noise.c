/* test_noise.c: the counter-based gradient noise (vx_noise.h):
 * determinism, the stated bounds, zero at lattice points and zero mean,
 * continuity and the exact gradient against differences, the same bits
 * on two threads, and the octave spectrum (each octave's gradient energy
 * grows as its frequency squared, its variance as its weight squared);
 * prepared sums the same bits as unprepared, and the turbulence gradient
 * against differences. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "vx_noise.h"
#include "vx_rng.h"

/* a point spread over a wide box, from the sampler's uniform numbers */
static void
point(uint64_t i, double span, double p[3])
{
	for (uint32_t a = 0; a < 3; a++)
		p[a] = span * (vx_rng_uniform(7, 99, i, a) - 0.5);
}

/* Same seed, same bits; another seed, another field (values differ at
 * almost every point and do not correlate). */
static void
deterministic(void **state)
{
	double sxy = 0, sxx = 0, syy = 0;
	int differ = 0, n = 20000;

	(void)state;
	for (int i = 0; i < n; i++) {
		double p[3], a, b, c;

		point((uint64_t)i, 1000, p);
		a = vx_noise3(1, p);
		b = vx_noise3(1, p);
		c = vx_noise3(2, p);
		assert_memory_equal(&a, &b, sizeof a);
		differ += a != c;
		sxy += a * c;
		sxx += a * a;
		syy += c * c;
	}
	assert_true(differ > n * 99 / 100);
	/* independent fields: correlation within 5 standard errors of 0 */
	assert_true(fabs(sxy / sqrt(sxx * syy)) < 5 / sqrt((double)n));
}

/* |noise| <= 1, fBm in [-1, 1], turbulence in [0, 1]; 0 at lattice points
 * (the oracle: every corner term there is g . 0). */
static void
bounded(void **state)
{
	vx_noise_fbm f;
	double worst = 0;

	(void)state;
	vx_noise_fbm_init(&f);
	f.octaves = 6;
	for (int i = 0; i < 200000; i++) {
		double p[3], v, t, s;

		point((uint64_t)i, 64, p);
		v = vx_noise3((uint64_t)i % 5, p);
		s = vx_noise_fbm_eval(&f, p, NULL);
		t = vx_noise_turbulence(&f, p);
		assert_true(fabs(v) <= 1 && fabs(s) <= 1 && t >= 0 && t <= 1);
		worst = fmax(worst, fabs(v));
	}
	assert_true(worst > 0.3);       /* not a degenerate field */
	for (int i = -3; i <= 3; i++) {
		double p[3] = { i, 2 * i - 1, 7 - i };

		assert_true(vx_noise3(11, p) == 0);
	}
	{
		double p[3] = { NAN, 0.5, 0.5 }, g[3];

		assert_true(vx_noise3_grad(3, p, g) == 0 && g[0] == 0);
	}
}

/* Mean 0 within 6 standard errors over 200000 points spread over
 * 10^9 lattice cells (nearly independent samples). */
static void
zero_mean(void **state)
{
	double s = 0, ss = 0, m, se;
	int n = 200000;

	(void)state;
	for (int i = 0; i < n; i++) {
		double p[3];

		point((uint64_t)i + 1000000, 1000, p);
		double v = vx_noise3(42, p);
		s += v;
		ss += v * v;
	}
	m = s / n;
	se = sqrt((ss / n - m * m) / n);
	assert_true(fabs(m) < 6 * se);
	assert_true(se < 1e-3);
}

/* Continuity: a step of 1e-7 changes the value by at most 10 times the
 * step (a loose Lipschitz bound: each corner term's slope is at most
 * |g| + |fade'| |g . d| <= sqrt(2) + 15/8 * 2, and the scaled blend's
 * gradient stays near 2.2 at most over 2e6 random points), and the exact
 * gradients of the noise and of the fBm agree with central differences. */
static void
continuity(void **state)
{
	vx_noise_fbm f;

	(void)state;
	vx_noise_fbm_init(&f);
	f.frequency = 0.37;
	for (int i = 0; i < 5000; i++) {
		double p[3], g[3], fg[3], v = 0, h = 1e-5;

		point((uint64_t)i, 50, p);
		v = vx_noise3_grad(5, p, g);
		for (int a = 0; a < 3; a++) {
			double q[3], r[3], step = 1e-7;

			memcpy(q, p, sizeof q);
			memcpy(r, p, sizeof r);
			q[a] += step;
			assert_true(fabs(vx_noise3(5, q) - v) <= 10 * step);
			q[a] = p[a] + h;
			r[a] = p[a] - h;
			assert_true(fabs((vx_noise3(5, q) - vx_noise3(5, r)) /
			    (2 * h) - g[a]) < 1e-5);
		}
		vx_noise_fbm_eval(&f, p, fg);
		for (int a = 0; a < 3; a++) {
			double q[3], r[3];

			memcpy(q, p, sizeof q);
			memcpy(r, p, sizeof r);
			q[a] += h;
			r[a] -= h;
			assert_true(fabs((vx_noise_fbm_eval(&f, q, NULL) -
			    vx_noise_fbm_eval(&f, r, NULL)) / (2 * h) - fg[a]) <
			    1e-4);
		}
	}
}

/* Spectrum: octave o of lacunarity 2 has 4^o times octave 0's mean
 * squared gradient (the field is stationary, so scaling space by 2 scales
 * the gradient by 2), within 10%; and a two-octave sum minus one octave,
 * times the weight sum, is the second octave: its variance is gain^2 times
 * the first's, within 10%. */
static void
spectrum(void **state)
{
	vx_noise_fbm f1, f2;
	double g0 = 0, g2 = 0, v1 = 0, vd = 0;
	int n = 40000;

	(void)state;
	vx_noise_fbm_init(&f1);
	f1.octaves = 1;
	f1.seed = 9;
	f2 = f1;
	f2.octaves = 2;
	f2.gain = 0.6;
	for (int i = 0; i < n; i++) {
		double p[3], q[3], g[3], a, b;

		point((uint64_t)i, 500, p);
		vx_noise3_grad(3, p, g);
		g0 += g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
		for (int k = 0; k < 3; k++)
			q[k] = 4 * p[k];
		vx_noise3_grad(3, q, g);
		g2 += 16 * (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
		a = vx_noise_fbm_eval(&f1, p, NULL);
		b = vx_noise_fbm_eval(&f2, p, NULL) * (1 + f2.gain) - a;
		v1 += a * a;
		vd += b * b;
	}
	assert_true(fabs(g2 / g0 - 16) < 1.6);
	assert_true(fabs(vd / v1 / (f2.gain * f2.gain) - 1) < 0.1);
}

/* The same field on two threads, in any order, bit for bit (the values
 * are pure functions of seed and point: nothing is shared). */
static void
threads(void **state)
{
	enum { N = 20000 };
	static double a[N], b[N];
	vx_noise_fbm f;

	(void)state;
	vx_noise_fbm_init(&f);
	f.seed = 77;
	f.octaves = 7;
	for (int i = 0; i < N; i++) {
		double p[3];

		point((uint64_t)i, 100, p);
		a[i] = vx_noise_fbm_eval(&f, p, NULL);
	}
#pragma omp parallel for num_threads(2) schedule(dynamic, 7)
	for (int i = N - 1; i >= 0; i--) {
		double p[3];

		point((uint64_t)i, 100, p);
		b[i] = vx_noise_fbm_eval(&f, p, NULL);
	}
	assert_memory_equal(a, b, sizeof a);
}

static void
knobs(void **state)
{
	vx_noise_fbm f;
	vx_err e;

	(void)state;
	vx_noise_fbm_init(&f);
	assert_int_equal(vx_noise_fbm_check(&f, &e), 0);
	f.octaves = 0;
	assert_int_equal(vx_noise_fbm_check(&f, &e), VX_EUSAGE);
	assert_non_null(strstr(e.msg, "octaves"));
	vx_noise_fbm_init(&f);
	f.gain = NAN;
	assert_int_equal(vx_noise_fbm_check(&f, &e), VX_EUSAGE);
	vx_noise_fbm_init(&f);
	f.frequency = INFINITY;
	assert_int_equal(vx_noise_fbm_check(&f, &e), VX_EUSAGE);
	vx_noise_fbm_init(&f);
	f.lacunarity = 0;
	assert_int_equal(vx_noise_fbm_check(&f, &e), VX_EUSAGE);
}

/* Prepared sums are the unprepared ones bit for bit (fBm and its
 * gradient, turbulence and its gradient), also after the octave count
 * grows; a changed seed is noticed (the oracle: a fresh, unprepared sum
 * with that seed); the turbulence gradient matches differences. */
static void
prepared(void **state)
{
	vx_noise_fbm a, b;
	int kinked = 0;

	(void)state;
	vx_noise_fbm_init(&a);
	a.seed = 12345;
	a.octaves = 6;
	a.frequency = 0.37;
	b = a;
	vx_noise_fbm_prepare(&b);
	for (int round = 0; round < 3; round++) {
		if (round == 1) {
			a.octaves = b.octaves = 9;
		} else if (round == 2) {
			a.seed = b.seed = 777;     /* b is now stale */
		}
		for (int i = 0; i < 500; i++) {
			double p[3], ga[3], gb[3], va, vb, h = 1e-6;

			point((uint64_t)i, 50, p);
			va = vx_noise_fbm_eval(&a, p, ga);
			vb = vx_noise_fbm_eval(&b, p, gb);
			assert_memory_equal(&va, &vb, sizeof va);
			assert_memory_equal(ga, gb, sizeof ga);
			va = vx_noise_turbulence_grad(&a, p, ga);
			vb = vx_noise_turbulence_grad(&b, p, gb);
			assert_memory_equal(&va, &vb, sizeof va);
			assert_memory_equal(ga, gb, sizeof ga);
			assert_true(va == vx_noise_turbulence(&a, p));
			for (int c = 0; c < 3; c++) {
				double q[3] = { p[0], p[1], p[2] }, hi, lo;

				q[c] += h;
				hi = vx_noise_turbulence(&a, q);
				q[c] -= 2 * h;
				lo = vx_noise_turbulence(&a, q);
				kinked += fabs((hi - lo) / (2 * h) - ga[c]) > 1e-4;
			}
		}
		/* |noise| has kinks where the noise is 0: a difference
		 * straddling one misses, at the rare point near one */
		assert_true(kinked < 15);
		kinked = 0;
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(deterministic),
		cmocka_unit_test(bounded),
		cmocka_unit_test(zero_mean),
		cmocka_unit_test(continuity),
		cmocka_unit_test(spectrum),
		cmocka_unit_test(threads),
		cmocka_unit_test(knobs),
		cmocka_unit_test(prepared),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
