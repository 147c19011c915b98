/* test_rng.c: counter-based random numbers and scrambled Sobol points:
 * determinism, statistical uniformity (chi-squared), the net property,
 * convergence rates, and independence of streams.
 *
 * Every test runs at fixed seeds, so its outcome is fixed; the thresholds are
 * chosen so that a correct generator passes with a wide margin (quantiles at
 * p = 0.001 or beyond), and a broken one (a dimension or stream reused, a
 * scramble that is not a digit permutation, a sequence without
 * stratification) fails. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "vx_rng.h"

/* Upper quantiles of the chi-squared distribution at p = 0.999 (computed
 * from the regularized incomplete gamma function; 148.23 for 99 degrees of
 * freedom as in the usual tables). */
#define CHI2_127_999 181.99
#define CHI2_255_999 330.52

/* Pure functions: the same arguments give the same bits whatever was drawn
 * before, and these values are pinned (a bake resumed by a later build must
 * draw the same numbers; a change of the hash is a change of every
 * picture). */
static void
determinism(void **state)
{
	static const struct {
		uint64_t seed, stream, index;
		uint32_t dim;
		uint64_t hash;
	} pin[] = {
		{ 0, 0, 0, 0, UINT64_C(0xaaffdc6c8cf7420b) },
		{ 1, 0, 0, 0, UINT64_C(0xa8f31631d149b158) },
		{ 0, 1, 0, 0, UINT64_C(0xcd9afd5adfcc3b94) },
		{ 0, 0, 1, 0, UINT64_C(0x3ea748640977555c) },
		{ 0, 0, 0, 1, UINT64_C(0xf93f48998c4e4d9e) },
		{ 12345, 678, 91011, 12, UINT64_C(0xa4221d7a4d78de76) },
		{ UINT64_MAX, UINT64_MAX, UINT64_MAX, UINT32_MAX,
		  UINT64_C(0x1e0f56e781cfd3a9) },
	};
	static const double ld_pin[][2] = {
		{ 0x1.c0be7fd1763p-5, 0x1.dc56860168236p-2 },
		{ 0x1.8dc0a97ee4902p-1, 0x1.589aff4d0899fp-1 },
		{ 0x1.b4383f49025b1p-1, 0x1.1ddd06769232cp-3 },
	};
	double a[64], u[2];

	(void)state;
	for (size_t i = 0; i < sizeof pin / sizeof pin[0]; i++)
		assert_true(vx_rng_hash(pin[i].seed, pin[i].stream,
		    pin[i].index, pin[i].dim) == pin[i].hash);
	for (int k = 0; k < 3; k++) {
		vx_rng_ld2(7, 3, (uint64_t)k * 1000, 2, u);
		assert_true(u[0] == ld_pin[k][0] && u[1] == ld_pin[k][1]);
	}
	/* drawn forwards and backwards, interleaved with other streams */
	for (int i = 0; i < 64; i++)
		a[i] = vx_rng_uniform(9, 4, (uint64_t)i, 3);
	for (int i = 63; i >= 0; i--) {
		(void)vx_rng_uniform(9, 5, (uint64_t)i, 3);
		assert_true(vx_rng_uniform(9, 4, (uint64_t)i, 3) == a[i]);
	}
}

/* Each argument avalanches: flipping any one input bit of any argument flips
 * each of the 64 output bits in about half of 1000 random cases.  The count
 * is binomial(1000, 1/2), sd 15.8; [400, 600] is 6.3 sd wide on each side,
 * so 16384 counts all fall inside unless some bit is badly mixed. */
static void
avalanche(void **state)
{
	static int cnt[4][64][64];
	enum { NCASE = 1000 };

	(void)state;
	memset(cnt, 0, sizeof cnt);
	for (uint64_t c = 0; c < NCASE; c++) {
		uint64_t in[4], h0;

		for (int a = 0; a < 4; a++)
			in[a] = vx_rng_hash(0xabc, c, (uint64_t)a, 99);
		in[3] &= 0xffffffffu;
		h0 = vx_rng_hash(in[0], in[1], in[2], (uint32_t)in[3]);
		for (int a = 0; a < 4; a++)
			for (int b = 0; b < (a == 3 ? 32 : 64); b++) {
				uint64_t v[4], d;

				memcpy(v, in, sizeof v);

				v[a] ^= UINT64_C(1) << b;
				d = h0 ^ vx_rng_hash(v[0], v[1], v[2],
				    (uint32_t)v[3]);
				for (int o = 0; o < 64; o++)
					cnt[a][b][o] += (int)(d >> o & 1);
			}
	}
	for (int a = 0; a < 4; a++)
		for (int b = 0; b < (a == 3 ? 32 : 64); b++)
			for (int o = 0; o < 64; o++) {
				int c = cnt[a][b][o];

				if (c < 400 || c > 600)
					fail_msg("argument %d bit %d -> bit %d "
					    "flips %d/1000", a, b, o, c);
			}
}

static double
chi2(const long *obs, int nbin, double expect)
{
	double s = 0;

	for (int i = 0; i < nbin; i++)
		s += (obs[i] - expect) * (obs[i] - expect) / expect;
	return s;
}

/* Uniformity: 2^17 numbers in 128 equal bins (chi-squared, 127 degrees of
 * freedom, below its 0.999 quantile 181.99), for consecutive indices of one
 * dimension, for consecutive dimensions of one index, and for consecutive
 * streams; pairs of dimensions in 16 x 16 bins (255 degrees of freedom,
 * 330.52).  Every value lies in [0, 1). */
static void
uniform_chi2(void **state)
{
	enum { N = 1 << 17 };
	static long bin[256];

	(void)state;
	for (int walk = 0; walk < 3; walk++) {
		memset(bin, 0, sizeof bin);
		for (uint64_t i = 0; i < N; i++) {
			double u = walk == 0 ? vx_rng_uniform(42, 7, i, 0) :
			    walk == 1 ? vx_rng_uniform(42, 7, 3, (uint32_t)i) :
			    vx_rng_uniform(42, i, 3, 0);

			assert_true(u >= 0 && u < 1);
			bin[(int)(u * 128)]++;
		}
		double c = chi2(bin, 128, N / 128.0);

		if (!(c < CHI2_127_999))
			fail_msg("walk %d: chi2 %.1f", walk, c);
	}
	memset(bin, 0, sizeof bin);
	for (uint64_t i = 0; i < N; i++) {
		double u = vx_rng_uniform(42, 7, i, 0);
		double v = vx_rng_uniform(42, 7, i, 1);

		bin[(int)(u * 16) * 16 + (int)(v * 16)]++;
	}
	double c = chi2(bin, 256, N / 256.0);

	if (!(c < CHI2_255_999))
		fail_msg("pairs of dimensions: chi2 %.1f", c);
}

/* The same point of 2^14 different streams (or seeds) is uniform over the
 * square: the scramble is random per stream.  Chi-squared as above, per
 * coordinate and in 16 x 16 cells, at points 0 and 77. */
static void
ld2_across_streams(void **state)
{
	enum { N = 1 << 14 };
	static long bx[128], by[128], bxy[256];

	(void)state;
	for (int which = 0; which < 3; which++) {
		memset(bx, 0, sizeof bx);
		memset(by, 0, sizeof by);
		memset(bxy, 0, sizeof bxy);
		for (uint64_t s = 0; s < N; s++) {
			double u[2];

			if (which == 2)
				vx_rng_ld2(s, 5, 0, 0, u);	/* seeds */
			else
				vx_rng_ld2(3, s, which ? 77 : 0, 1, u);
			assert_true(u[0] >= 0 && u[0] < 1 && u[1] >= 0 &&
			    u[1] < 1);
			bx[(int)(u[0] * 128)]++;
			by[(int)(u[1] * 128)]++;
			bxy[(int)(u[0] * 16) * 16 + (int)(u[1] * 16)]++;
		}
		double cx = chi2(bx, 128, N / 128.0);
		double cy = chi2(by, 128, N / 128.0);
		double cxy = chi2(bxy, 256, N / 256.0);

		if (!(cx < CHI2_127_999 && cy < CHI2_127_999 &&
		    cxy < CHI2_255_999))
			fail_msg("case %d: chi2 %.1f %.1f %.1f", which, cx, cy,
			    cxy);
	}
}

/* net_boxes: the largest count of points in one elementary box of shape
 * 2^-a x 2^-(k-a) among points [block 2^k, (block+1) 2^k) of the sequence
 * (seed, stream, dim). */
static int
net_boxes(uint64_t seed, uint64_t stream, uint32_t dim, uint64_t block,
    int k, int a)
{
	static unsigned char hit[1 << 12];
	int b = k - a, most = 0;

	memset(hit, 0, (size_t)1 << k);
	for (uint64_t j = 0; j < (UINT64_C(1) << k); j++) {
		double u[2];

		vx_rng_ld2(seed, stream, (block << k) + j, dim, u);
		int x = (int)floor(u[0] * (1 << a));
		int y = (int)floor(u[1] * (1 << b));

		hit[(x << b) | y]++;
	}
	for (int c = 0; c < (1 << k); c++)
		most = hit[c] > most ? hit[c] : most;
	return most;
}

/* The (0,k,2)-net property, the defining property of the sequence: every
 * aligned block of 2^k points (the first, and the c-th) has exactly one
 * point in each elementary box of area 2^-k, for every shape a + b = k
 * (2^k points in 2^k boxes: at most one in each means one in each).  The
 * oracle is the count itself. */
static void
ld2_nets(void **state)
{
	static const struct {
		uint64_t seed, stream;
		uint32_t dim;
		uint64_t block;
	} cases[] = {
		{ 0, 0, 0, 0 }, { 1, 99, 3, 0 }, { 77, 123456789, 17, 1 },
		{ 5, 2, 0, 5 }, { UINT64_MAX, 1, 1000, 3 },
	};

	(void)state;
	for (size_t ci = 0; ci < sizeof cases / sizeof cases[0]; ci++)
		for (int k = 0; k <= 12; k++)
			for (int a = 0; a <= k; a++) {
				int most = net_boxes(cases[ci].seed,
				    cases[ci].stream, cases[ci].dim,
				    cases[ci].block, k, a);

				if (most != 1)
					fail_msg("case %zu k %d a %d: a box "
					    "holds %d", ci, k, a, most);
			}
}

/* vx_rng_owen32 is a bijection that keeps dyadic intervals together: words
 * sharing their top k bits map to words sharing their top k bits, and the
 * 2^16 words x << 16 map to 2^16 different top halves. */
static void
owen32_digits(void **state)
{
	static unsigned char seen[1 << 16];
	const uint32_t keys[] = { 0, 1, 0xdeadbeefu, 0x80000000u };

	(void)state;
	for (size_t ki = 0; ki < 4; ki++) {
		memset(seen, 0, sizeof seen);
		for (uint32_t x = 0; x < (1u << 16); x++) {
			uint32_t y = vx_rng_owen32(x << 16, keys[ki]) >> 16;

			assert_int_equal(seen[y], 0);
			seen[y] = 1;
		}
		for (uint64_t c = 0; c < 2000; c++) {
			uint32_t x = (uint32_t)vx_rng_hash(1, c, 0, 0);
			uint32_t r = (uint32_t)vx_rng_hash(1, c, 1, 0);
			int k = (int)(c % 32);
			uint32_t mask = k ? ~0u << (32 - k) : 0;
			uint32_t y = (x & mask) | (r & ~mask);

			assert_true(((vx_rng_owen32(x, keys[ki]) ^
			    vx_rng_owen32(y, keys[ki])) & mask) == 0);
		}
	}
}

/* Sobol's first two dimensions, unscrambled, against points worked out by
 * hand: dimension 1 the radical inverse, dimension 2 the xor of the
 * direction numbers 1/2, 3/4, 5/8 (m = 1, 3, 5 in Joe and Kuo's table) of
 * the index's set bits (in index order, not Gray-code order). */
static void
sobol_points(void **state)
{
	static const double want[8][2] = {
		{ 0, 0 }, { 0.5, 0.5 }, { 0.25, 0.75 }, { 0.75, 0.25 },
		{ 0.125, 0.625 }, { 0.625, 0.125 }, { 0.375, 0.375 },
		{ 0.875, 0.875 },
	};

	(void)state;
	for (uint32_t i = 0; i < 8; i++) {
		uint32_t x[2];

		vx_rng_sobol2(i, x);
		assert_true(x[0] * 0x1p-32 == want[i][0]);
		assert_true(x[1] * 0x1p-32 == want[i][1]);
	}
}

/* f(x, y) = e^x cos y over the unit square: (e - 1) sin 1. */
static double
smooth(const double u[2])
{
	return exp(u[0]) * cos(u[1]);
}

/* rms_error: the RMS error, over nstream streams, of the N-point estimate of
 * the integral of smooth(); ld selects vx_rng_ld2 (else two uniforms). */
static double
rms_error(int ld, int n, int nstream, uint64_t seed)
{
	const double truth = (exp(1.0) - 1) * sin(1.0);
	double s2 = 0;

	for (int s = 0; s < nstream; s++) {
		double sum = 0;

		for (int i = 0; i < n; i++) {
			double u[2];

			if (ld)
				vx_rng_ld2(seed, (uint64_t)s, (uint64_t)i, 4,
				    u);
			else {
				u[0] = vx_rng_uniform(seed, (uint64_t)s,
				    (uint64_t)i, 8);
				u[1] = vx_rng_uniform(seed, (uint64_t)s,
				    (uint64_t)i, 9);
			}
			sum += smooth(u);
		}
		s2 += (sum / n - truth) * (sum / n - truth);
	}
	return sqrt(s2 / nstream);
}

/* Convergence rates, by a least-squares slope of log RMS error against
 * log N over N = 64 ... 4096 (64 streams each).  Independent uniforms give
 * N^-1/2 (slope within [-0.7, -0.3]); Owen-scrambled Sobol points give
 * N^-3/2 for a smooth integrand (Owen 1997): slope below -1.2, and at 4096
 * points an error 30 times below the uniforms'. */
static void
convergence(void **state)
{
	static const int ns[] = { 64, 256, 1024, 4096 };
	double slope[2], last[2];

	(void)state;
	for (int ld = 0; ld < 2; ld++) {
		double sx = 0, sy = 0, sxx = 0, sxy = 0;

		for (int k = 0; k < 4; k++) {
			double x = log(ns[k]);
			double y = log(rms_error(ld, ns[k], 64, 2024));

			sx += x;
			sy += y;
			sxx += x * x;
			sxy += x * y;
			last[ld] = exp(y);
		}
		slope[ld] = (4 * sxy - sx * sy) / (4 * sxx - sx * sx);
	}
	if (!(slope[0] > -0.7 && slope[0] < -0.3))
		fail_msg("uniform: slope %.3f", slope[0]);
	if (!(slope[1] < -1.2))
		fail_msg("ld2: slope %.3f", slope[1]);
	if (!(last[1] * 30 < last[0]))
		fail_msg("at 4096 points: ld2 %.3g, uniform %.3g", last[1],
		    last[0]);
}

/* pearson: the sample correlation of a and b (n values). */
static double
pearson(const double *a, const double *b, int n)
{
	double ma = 0, mb = 0, sab = 0, saa = 0, sbb = 0;

	for (int i = 0; i < n; i++) {
		ma += a[i];
		mb += b[i];
	}
	ma /= n;
	mb /= n;
	for (int i = 0; i < n; i++) {
		sab += (a[i] - ma) * (b[i] - mb);
		saa += (a[i] - ma) * (a[i] - ma);
		sbb += (b[i] - mb) * (b[i] - mb);
	}
	return sab / sqrt(saa * sbb);
}

/* Streams, dimensions and seeds do not correlate.  (1) The coordinates of
 * neighbouring streams (and dimensions, seeds) at the same 4096 indices: a
 * sample correlation of independent sequences has sd 1/64, and |r| < 0.07
 * (4.5 sd) holds for each of the pairs.  (2) The integration errors of
 * 256 neighbouring streams, stream s against s + 1: |r| < 0.25 (4 sd).
 * A generator that reused one scramble for every stream would give r = 1. */
static void
streams_uncorrelated(void **state)
{
	enum { N = 4096, S = 256 };
	static double a[N], b[N], ea[S], eb[S];
	static const struct {
		uint64_t seed[2], stream[2];
		uint32_t dim[2];
	} pairs[] = {
		{ { 1, 1 }, { 7, 8 }, { 0, 0 } },
		{ { 1, 1 }, { 0, 1ull << 32 }, { 0, 0 } },
		{ { 1, 1 }, { 7, 7 }, { 0, 1 } },
		{ { 1, 2 }, { 7, 7 }, { 0, 0 } },
	};

	(void)state;
	for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; p++)
		for (int kind = 0; kind < 3; kind++) {
			for (int i = 0; i < N; i++) {
				double u[2], v[2];

				if (kind == 2) {
					a[i] = vx_rng_uniform(pairs[p].seed[0],
					    pairs[p].stream[0], (uint64_t)i,
					    pairs[p].dim[0]);
					b[i] = vx_rng_uniform(pairs[p].seed[1],
					    pairs[p].stream[1], (uint64_t)i,
					    pairs[p].dim[1]);
					continue;
				}
				vx_rng_ld2(pairs[p].seed[0], pairs[p].stream[0],
				    (uint64_t)i, pairs[p].dim[0], u);
				vx_rng_ld2(pairs[p].seed[1], pairs[p].stream[1],
				    (uint64_t)i, pairs[p].dim[1], v);
				a[i] = u[kind];
				b[i] = v[kind];
			}
			double r = pearson(a, b, N);

			if (!(fabs(r) < 0.07))
				fail_msg("pair %zu kind %d: r = %.4f", p, kind,
				    r);
		}
	for (int s = 0; s < S; s++) {
		const double truth = (exp(1.0) - 1) * sin(1.0);
		double su = 0, sv = 0;

		for (int i = 0; i < 64; i++) {
			double u[2], v[2];

			uint64_t t = (uint64_t)(2 * s);

			vx_rng_ld2(11, t, (uint64_t)i, 0, u);
			vx_rng_ld2(11, t + 1, (uint64_t)i, 0, v);
			su += smooth(u);
			sv += smooth(v);
		}
		ea[s] = su / 64 - truth;
		eb[s] = sv / 64 - truth;
	}
	double r = pearson(ea, eb, S);

	if (!(fabs(r) < 0.25))
		fail_msg("errors of neighbouring streams: r = %.3f", r);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(determinism),
		cmocka_unit_test(avalanche),
		cmocka_unit_test(uniform_chi2),
		cmocka_unit_test(ld2_across_streams),
		cmocka_unit_test(ld2_nets),
		cmocka_unit_test(owen32_digits),
		cmocka_unit_test(sobol_points),
		cmocka_unit_test(convergence),
		cmocka_unit_test(streams_uncorrelated),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
