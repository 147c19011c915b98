/* test_warp.c: warps of the unit square and orthonormal frames: every
 * direction unit and in its domain, each returned density equal to the
 * warp's actual density (its Jacobian, by finite differences), densities
 * that integrate to 1, histograms of warped samples against the integral of
 * the density over each bin (chi-squared), and frames that are orthonormal
 * and right-handed. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "vx_rng.h"
#include "vx_warp.h"

#define PI 3.14159265358979323846
/* chi-squared, 127 degrees of freedom, upper 0.999 quantile */
#define CHI2_127_999 181.99

static const struct warp {
	const char *name;
	double (*warp)(const double u[2], double w[3]);
	double (*pdf)(const double w[3]);
	double zmin;	/* the domain is z >= zmin */
} warps[] = {
	{ "cosine hemisphere", vx_warp_cosine_hemisphere,
	  vx_warp_cosine_hemisphere_pdf, 0 },
	{ "uniform hemisphere", vx_warp_uniform_hemisphere,
	  vx_warp_uniform_hemisphere_pdf, 0 },
	{ "uniform sphere", vx_warp_uniform_sphere,
	  vx_warp_uniform_sphere_pdf, -1 },
};
#define NWARP (sizeof warps / sizeof warps[0])

/* the corners and edges of the square, then scrambled Sobol points */
static void
point(int i, double u[2])
{
	static const double edge[][2] = {
		{ 0, 0 }, { 0, 0x1.fffffffffffffp-1 },
		{ 0x1.fffffffffffffp-1, 0 },
		{ 0x1.fffffffffffffp-1, 0x1.fffffffffffffp-1 }, { 0.5, 0.5 },
		{ 0.5, 0 }, { 0, 0.5 }, { 0.25, 0.25 }, { 0.75, 0.25 },
	};
	if (i < (int)(sizeof edge / sizeof edge[0])) {
		u[0] = edge[i][0];
		u[1] = edge[i][1];
	} else
		vx_rng_ld2(1, 2, (uint64_t)i, 0, u);
}

/* Unit directions in the domain; the returned density equals the density
 * function's at that direction; the disk's points lie in the unit disk and
 * the square's boundary goes to the circle. */
static void
domain(void **state)
{
	(void)state;
	for (size_t k = 0; k < NWARP; k++)
		for (int i = 0; i < 4096; i++) {
			double u[2], w[3];

			point(i, u);
			double p = warps[k].warp(u, w);
			double n = sqrt(w[0] * w[0] + w[1] * w[1] +
			    w[2] * w[2]);

			if (!(fabs(n - 1) < 1e-14 && w[2] >= warps[k].zmin &&
			    isfinite(p) && p >= 0 && p == warps[k].pdf(w)))
				fail_msg("%s at (%g, %g): |w| - 1 = %g, "
				    "z = %g, pdf %g vs %g", warps[k].name,
				    u[0], u[1], n - 1, w[2], p,
				    warps[k].pdf(w));
		}
	for (int i = 0; i < 4096; i++) {
		double u[2], d[2];

		point(i, u);
		vx_warp_concentric_disk(u, d);
		assert_true(d[0] * d[0] + d[1] * d[1] <= 1 + 1e-15);
	}
	for (int i = 0; i <= 64; i++) {
		double e = i / 64.0, sides[4][2] = { { 0, e }, { 1, e },
		    { e, 0 }, { e, 1 } }, d[2];

		for (int s = 0; s < 4; s++) {
			vx_warp_concentric_disk(sides[s], d);
			assert_true(fabs(hypot(d[0], d[1]) - 1) < 1e-15);
		}
	}
	/* the uniform hemisphere never reaches its rim */
	for (int i = 0; i < 4096; i++) {
		double u[2], w[3];

		point(i, u);
		vx_warp_uniform_hemisphere(u, w);
		assert_true(w[2] > 0);
	}
}

/* jacobian: |dw/du0 x dw/du1| at u by central differences (step h). */
static double
jacobian(const struct warp *wp, const double u[2], double h)
{
	double d[2][3];

	for (int a = 0; a < 2; a++) {
		double up[2] = { u[0], u[1] }, um[2] = { u[0], u[1] };
		double wp3[3], wm3[3];

		up[a] += h;
		um[a] -= h;
		wp->warp(up, wp3);
		wp->warp(um, wm3);
		for (int c = 0; c < 3; c++)
			d[a][c] = (wp3[c] - wm3[c]) / (2 * h);
	}
	double x = d[0][1] * d[1][2] - d[0][2] * d[1][1];
	double y = d[0][2] * d[1][0] - d[0][0] * d[1][2];
	double z = d[0][0] * d[1][1] - d[0][1] * d[1][0];

	return sqrt(x * x + y * y + z * z);
}

/* The density a warp returns is its true density: with u uniform, the
 * density in solid angle is 1 / |dw/du0 x dw/du1|, so pdf * Jacobian = 1
 * (finite differences, step 1e-6: agreement to 1e-6).  The disk's area
 * Jacobian is pi.  Points within 1e-3 of the concentric map's diagonals,
 * where it has a kink, and of the square's edges are left out. */
static void
density_is_jacobian(void **state)
{
	(void)state;
	for (int i = 16; i < 1040; i++) {
		double u[2];

		point(i, u);
		if (fabs(fabs(2 * u[0] - 1) - fabs(2 * u[1] - 1)) < 1e-3 ||
		    fmin(fmin(u[0], u[1]), fmin(1 - u[0], 1 - u[1])) < 1e-3)
			continue;
		for (size_t k = 0; k < NWARP; k++) {
			double w[3], p = warps[k].warp(u, w);
			double j = jacobian(&warps[k], u, 1e-6);

			if (!(fabs(p * j - 1) < 1e-6))
				fail_msg("%s at (%g, %g): pdf %g, 1/|J| %g",
				    warps[k].name, u[0], u[1], p, 1 / j);
		}
		double d[2][2], e[2], f[2];

		for (int a = 0; a < 2; a++) {
			double up[2] = { u[0], u[1] }, um[2] = { u[0], u[1] };

			up[a] += 1e-6;
			um[a] -= 1e-6;
			vx_warp_concentric_disk(up, e);
			vx_warp_concentric_disk(um, f);
			d[a][0] = (e[0] - f[0]) / 2e-6;
			d[a][1] = (e[1] - f[1]) / 2e-6;
		}
		double j = fabs(d[0][0] * d[1][1] - d[0][1] * d[1][0]);

		assert_true(fabs(j / PI - 1) < 1e-6);
	}
}

/* The density functions integrate to 1 over the sphere: they depend on z
 * alone and are linear in z on each side of z = 0, so the midpoint rule
 * over z in [-1, 0] and [0, 1] (and in phi) is exact up to rounding. */
static void
pdf_integrates_to_one(void **state)
{
	enum { NZ = 1000, NP = 16 };

	(void)state;
	for (size_t k = 0; k < NWARP; k++) {
		double s = 0;

		for (int h = 0; h < 2; h++)
			for (int i = 0; i < NZ; i++) {
				double z = (h ? 0 : -1) + (i + 0.5) / NZ;
				double r = sqrt(1 - z * z);

				for (int j = 0; j < NP; j++) {
					double phi = 2 * PI * (j + 0.5) / NP;
					double w[3] = { r * cos(phi),
					    r * sin(phi), z };

					s += warps[k].pdf(w) * (1.0 / NZ) *
					    (2 * PI / NP);
				}
			}
		if (!(fabs(s - 1) < 1e-12))
			fail_msg("%s: integral %.15g", warps[k].name, s);
	}
}

/* Histograms: 2^16 warped pairs of independent uniforms in 8 bands of z
 * (equal in z over the domain) x 16 sectors of phi; the expected count of a
 * bin is N times the integral of the density over it (midpoint rule in z,
 * exact for these densities).  Chi-squared with 127 degrees of freedom,
 * below its 0.999 quantile.  The disk: 8 rings of equal area x 16 sectors,
 * each expected to hold 1/128. */
static void
histograms(void **state)
{
	enum { N = 1 << 16, NB = 8, NS = 16 };
	long cnt[NB * NS];

	(void)state;
	for (size_t k = 0; k < NWARP; k++) {
		double z0 = warps[k].zmin, dz = (1 - z0) / NB, c = 0;

		memset(cnt, 0, sizeof cnt);
		for (uint64_t i = 0; i < N; i++) {
			double u[2] = { vx_rng_uniform(5, k, i, 0),
			    vx_rng_uniform(5, k, i, 1) }, w[3];

			warps[k].warp(u, w);
			int b = (int)((w[2] - z0) / dz);
			double phi = atan2(w[1], w[0]);
			int s = (int)((phi + PI) / (2 * PI) * NS);

			b = b < 0 ? 0 : b >= NB ? NB - 1 : b;
			s = s < 0 ? 0 : s >= NS ? NS - 1 : s;
			cnt[b * NS + s]++;
		}
		for (int b = 0; b < NB; b++) {
			double p = 0;

			for (int i = 0; i < 100; i++) {
				double z = z0 + (b + (i + 0.5) / 100) * dz;
				double w[3] = { sqrt(1 - z * z), 0, z };

				p += warps[k].pdf(w) * dz / 100 * (2 * PI / NS);
			}
			for (int s = 0; s < NS; s++) {
				double e = N * p;

				c += (cnt[b * NS + s] - e) *
				    (cnt[b * NS + s] - e) / e;
			}
		}
		if (!(c < CHI2_127_999))
			fail_msg("%s: chi2 %.1f", warps[k].name, c);
	}
	memset(cnt, 0, sizeof cnt);
	for (uint64_t i = 0; i < N; i++) {
		double u[2] = { vx_rng_uniform(6, 0, i, 0),
		    vx_rng_uniform(6, 0, i, 1) }, d[2];

		vx_warp_concentric_disk(u, d);
		int b = (int)((d[0] * d[0] + d[1] * d[1]) * NB);
		int s = (int)((atan2(d[1], d[0]) + PI) / (2 * PI) * NS);

		b = b >= NB ? NB - 1 : b;
		s = s < 0 ? 0 : s >= NS ? NS - 1 : s;
		cnt[b * NS + s]++;
	}
	double c = 0, e = (double)N / (NB * NS);

	for (int i = 0; i < NB * NS; i++)
		c += (cnt[i] - e) * (cnt[i] - e) / e;
	if (!(c < CHI2_127_999))
		fail_msg("disk: chi2 %.1f", c);
}

/* Frames: (t, b, n) orthonormal and right-handed to 1e-15 for the axes
 * (both signs, and unit vectors whose z is -0, which take the -z branch),
 * directions near -z where the formula's 1/(1 + z) would blow up without
 * the sign trick, and random directions. */
static void
frames(void **state)
{
	double ns[64][3] = {
		{ 0, 0, 1 }, { 0, 0, -1 }, { 1, 0, -0.0 }, { 0, 1, -0.0 },
		{ 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 },
		{ 1e-9, 0, -1 }, { 0, 1e-9, -1 }, { 1e-300, 1e-300, -1 },
		{ 1, 1, 1 }, { -1, 2, -3 },
	};

	(void)state;
	for (int i = 13; i < 64; i++) {
		double u[2];

		vx_rng_ld2(3, 4, (uint64_t)i, 0, u);
		vx_warp_uniform_sphere(u, ns[i]);
	}
	for (int i = 0; i < 64; i++) {
		double *n = ns[i], t[3], b[3], c[3];
		double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);

		for (int k = 0; k < 3; k++)
			n[k] /= l;
		vx_onb(n, t, b);
		c[0] = t[1] * b[2] - t[2] * b[1];
		c[1] = t[2] * b[0] - t[0] * b[2];
		c[2] = t[0] * b[1] - t[1] * b[0];
		double tt = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
		double bb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
		double tb = t[0] * b[0] + t[1] * b[1] + t[2] * b[2];
		double tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
		double bn = b[0] * n[0] + b[1] * n[1] + b[2] * n[2];
		double dc = fabs(c[0] - n[0]) + fabs(c[1] - n[1]) +
		    fabs(c[2] - n[2]);

		if (!(fabs(tt - 1) < 1e-15 && fabs(bb - 1) < 1e-15 &&
		    fabs(tb) < 1e-15 && fabs(tn) < 1e-15 && fabs(bn) < 1e-15 &&
		    dc < 1e-15))
			fail_msg("normal %d (%g %g %g): |t|^2-1 %g |b|^2-1 %g "
			    "t.b %g t.n %g b.n %g |t x b - n| %g", i, n[0],
			    n[1], n[2], tt - 1, bb - 1, tb, tn, bn, dc);
	}
}

/* Into the world: cosine-weighted directions around n average to (2/3) n
 * (the mean of cos theta under density cos theta / pi), and the uniform
 * hemisphere's estimate of the integral of n.w is pi: 4096 scrambled Sobol
 * points, agreement to 2e-3. */
static void
to_world(void **state)
{
	static const double ns[][3] = {
		{ 0, 0, 1 }, { 0, 0, -1 }, { 0.6, 0, 0.8 }, { 0, -0.8, -0.6 },
		{ 0.48, 0.6, 0.64 },
	};

	(void)state;
	for (size_t k = 0; k < sizeof ns / sizeof ns[0]; k++) {
		double t[3], b[3], m[3] = { 0, 0, 0 }, e = 0;

		vx_onb(ns[k], t, b);
		for (int i = 0; i < 4096; i++) {
			double u[2], l[3], w[3];

			vx_rng_ld2(8, k, (uint64_t)i, 0, u);
			vx_warp_cosine_hemisphere(u, l);
			vx_onb_to_world(ns[k], t, b, l, w);
			for (int c = 0; c < 3; c++)
				m[c] += w[c] / 4096;
			double p = vx_warp_uniform_hemisphere(u, l);

			vx_onb_to_world(ns[k], t, b, l, l);	/* in place */
			e += (l[0] * ns[k][0] + l[1] * ns[k][1] +
			    l[2] * ns[k][2]) / p / 4096;
		}
		for (int c = 0; c < 3; c++)
			assert_true(fabs(m[c] - 2.0 / 3 * ns[k][c]) < 2e-3);
		assert_true(fabs(e - PI) < 2e-3);
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(domain),
		cmocka_unit_test(density_is_jacobian),
		cmocka_unit_test(pdf_integrates_to_one),
		cmocka_unit_test(histograms),
		cmocka_unit_test(frames),
		cmocka_unit_test(to_world),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
