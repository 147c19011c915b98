/* test_env.c: environment lights (vx_env.h): the orientation of both
 * layouts, the rotation, exact solid angles, lookups, the pixel iterator,
 * importance sampling (pdf and histogram), Monte Carlo irradiance against
 * quadrature, the sky, the content hash, the pixel rules, and loading a
 * scene's environment from a file with its hash. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <math.h>
#include <cmocka.h>

#include "vx_env.h"
#include "vx_imageio.h"
#include "vx_rng.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- helpers ---- */

/* unif: the tests' uniform numbers, pure functions of (seed, index)
 * (vx_rng.h); ld2: point k of a scrambled Sobol sequence. */
static double
unif(uint64_t seed, uint64_t i)
{
	return vx_rng_uniform(seed, 0, i, 0);
}

static void
ld2(uint64_t k, uint64_t seed, double u[2])
{
	vx_rng_ld2(seed, 0, k, 0, u);
}

static double
dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double
lum(const double c[3])
{
	return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

/* test_map: a sky with a gradient, noise and a small bright "sun". */
static void
test_map(vx_image *img, int w, int h, uint64_t seed)
{
	vx_err e = { 0, "" };

	assert_int_equal(vx_image_alloc(img, w, h, 3, &e), 0);
	for (int y = 0; y < h; y++)
		for (int x = 0; x < w; x++)
			for (int c = 0; c < 3; c++) {
				double v = 0.2 + 0.6 * (h - y) / h + 0.1 * c +
				    0.3 * unif(seed, (uint64_t)(3 * (y * w + x) + c));

				if (abs(x - w / 3) <= 1 && abs(y - h / 4) <= 1)
					v = 60 + 10 * c;
				vx_image_set(img, x, y, c, (float)v);
			}
}

static void
make_env(vx_env *env, int w, int h, vx_env_layout layout,
    const double rot[3], uint64_t seed)
{
	vx_image img;
	vx_err e = { 0, "" };

	test_map(&img, w, h, seed);
	if (vx_env_init(env, &img, layout, (const double[3]){ 1, 0.5, 2 }, rot,
	    &e) != 0)
		fail_msg("vx_env_init: %s", e.msg);
	vx_image_free(&img);
}

/* near3: |a - b| <= tol in each component. */
static int
near3(const double a[3], const double b[3], double tol)
{
	return fabs(a[0] - b[0]) <= tol && fabs(a[1] - b[1]) <= tol &&
	    fabs(a[2] - b[2]) <= tol;
}

/* ---- the orientation (formats/scene.md, "Environment maps") ---- */

static void
orientation(void **state)
{
	/* oracle: the convention as written in formats/scene.md, point by
	 * point (w = 8, h = 4 for lat-long; 8 x 8 angular) */
	static const struct { vx_env_layout l; double x, y, d[3]; int rc; } t[] = {
		{ VX_ENV_LATLONG, 4, 2, { 1, 0, 0 }, 0 },   /* centre: +x */
		{ VX_ENV_LATLONG, 2, 2, { 0, 1, 0 }, 0 },   /* s = 1/4: +y */
		{ VX_ENV_LATLONG, 6, 2, { 0, -1, 0 }, 0 },  /* s = 3/4: -y */
		{ VX_ENV_LATLONG, 0, 2, { -1, 0, 0 }, 0 },  /* left edge: -x */
		{ VX_ENV_LATLONG, 8, 2, { -1, 0, 0 }, 0 },  /* right edge: -x */
		{ VX_ENV_LATLONG, 3, 0, { 0, 0, 1 }, 0 },   /* top: +z */
		{ VX_ENV_LATLONG, 5, 4, { 0, 0, -1 }, 0 },  /* bottom: -z */
		{ VX_ENV_LATLONG, 4, 1, { 0.70710678118654752, 0,
		    0.70710678118654752 }, 0 },             /* 45 degrees up */
		{ VX_ENV_ANGULAR, 4, 4, { 1, 0, 0 }, 0 },   /* centre: +x */
		{ VX_ENV_ANGULAR, 6, 4, { 0, -1, 0 }, 0 },  /* right: -y */
		{ VX_ENV_ANGULAR, 2, 4, { 0, 1, 0 }, 0 },   /* left: +y */
		{ VX_ENV_ANGULAR, 4, 2, { 0, 0, 1 }, 0 },   /* up: +z */
		{ VX_ENV_ANGULAR, 4, 6, { 0, 0, -1 }, 0 },  /* down: -z */
		{ VX_ENV_ANGULAR, 8, 4, { -1, 0, 0 }, 0 },  /* rim: -x */
		{ VX_ENV_ANGULAR, 0.5, 0.5, { -1, 0, 0 }, -1 },  /* corner */
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		int h = t[i].l == VX_ENV_LATLONG ? 4 : 8;
		double d[3], x, y;

		assert_int_equal(vx_env_image_to_dir(t[i].l, 8, h, t[i].x, t[i].y,
		    d), t[i].rc);
		if (!near3(d, t[i].d, 1e-15))
			fail_msg("case %zu: (%g %g %g)", i, d[0], d[1], d[2]);
		if (t[i].rc != 0 || t[i].y == 0 || t[i].y == h ||
		    (t[i].l == VX_ENV_LATLONG && t[i].x == 8) ||
		    (t[i].l == VX_ENV_ANGULAR && t[i].x == 8))
			continue;
		vx_env_dir_to_image(t[i].l, 8, h, t[i].d, &x, &y);
		if (fabs(x - t[i].x) > 1e-13 || fabs(y - t[i].y) > 1e-13)
			fail_msg("case %zu: back to (%g, %g)", i, x, y);
	}
	/* random round trips, both layouts */
	for (int k = 0; k < 2000; k++) {
		vx_env_layout l = k & 1 ? VX_ENV_ANGULAR : VX_ENV_LATLONG;
		double z = 2 * unif(1, (uint64_t)k) - 1, p = 2 * M_PI * unif(2,
		    (uint64_t)k), r = sqrt(1 - z * z);
		double d[3] = { r * cos(p), r * sin(p), z }, b[3], x, y;

		vx_env_dir_to_image(l, 64, l == VX_ENV_LATLONG ? 32 : 64, d, &x,
		    &y);
		assert_int_equal(vx_env_image_to_dir(l, 64, l == VX_ENV_LATLONG ?
		    32 : 64, x, y, b), 0);
		assert_true(near3(d, b, 1e-12));
	}
}

/* rot_oracle: Rz(c) Ry(b) Rx(a) from the elementary matrices. */
static void
rot_oracle(const double deg[3], double R[3][3])
{
	double a = deg[0] * M_PI / 180, b = deg[1] * M_PI / 180;
	double c = deg[2] * M_PI / 180;
	double X[3][3] = { { 1, 0, 0 }, { 0, cos(a), -sin(a) },
	    { 0, sin(a), cos(a) } };
	double Y[3][3] = { { cos(b), 0, sin(b) }, { 0, 1, 0 },
	    { -sin(b), 0, cos(b) } };
	double Z[3][3] = { { cos(c), -sin(c), 0 }, { sin(c), cos(c), 0 },
	    { 0, 0, 1 } };
	double YX[3][3];

	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++) {
			YX[i][j] = 0;
			for (int k = 0; k < 3; k++)
				YX[i][j] += Y[i][k] * X[k][j];
		}
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++) {
			R[i][j] = 0;
			for (int k = 0; k < 3; k++)
				R[i][j] += Z[i][k] * YX[k][j];
		}
}

static void
rotation_key(void **state)
{
	/* a pixel's world direction is R times its map direction, and a
	 * lookup from R d reads what d reads in the unrotated map; rotation
	 * 0 0 90 turns the map's centre (+x) to +y (right-handed about z) */
	static const double rots[][3] = {
		{ 0, 0, 90 }, { 30, -45, 120 }, { 90, 0, 0 }, { 0, 180, 0 },
	};

	(void)state;
	for (size_t r = 0; r < sizeof rots / sizeof rots[0]; r++)
		for (int l = VX_ENV_LATLONG; l <= VX_ENV_ANGULAR; l++) {
			vx_env a, b;
			double R[3][3];
			int w = 16, h = l == VX_ENV_LATLONG ? 8 : 16;

			make_env(&a, w, h, (vx_env_layout)l, NULL, 5);
			make_env(&b, w, h, (vx_env_layout)l, rots[r], 5);
			rot_oracle(rots[r], R);
			assert_true(a.hash == b.hash);
			for (size_t i = 0; i < vx_env_npixel(&a); i++) {
				double da[3], db[3], rd[3], ca[3], cb[3], oa, ob;
				double u = 2 * (i % (size_t)w + 0.5) / w - 1;
				double v = 1 - 2 * (i / (size_t)w + 0.5) / h;

				vx_env_pixel(&a, i, da, &oa, ca);
				vx_env_pixel(&b, i, db, &ob, cb);
				for (int k = 0; k < 3; k++)
					rd[k] = R[k][0] * da[0] + R[k][1] * da[1] +
					    R[k][2] * da[2];
				assert_true(near3(rd, db, 1e-14));
				assert_true(oa == ob);
				if (l == VX_ENV_ANGULAR && u * u + v * v >= 0.99)
					continue;   /* -x, the rim: any angle */
				vx_env_lookup(&a, da, 1, ca);
				vx_env_lookup(&b, rd, 1, cb);
				assert_true(near3(ca, cb, 1e-9));
			}
			if (r == 0) {
				double c[3], y[3] = { 0, 1, 0 }, ctr[3];

				vx_env_lookup(&b, y, 0, c);
				vx_env_lookup(&a, (const double[3]){ 1, 0, 0 }, 0,
				    ctr);
				assert_true(near3(c, ctr, 0));
			}
			vx_env_free(&a);
			vx_env_free(&b);
		}
}

/* ---- solid angles ---- */

/* gl_square: the angular map's solid angle over the square [a0,a1] x
 * [b0,b1] inside the disc by a 24 x 24 Gauss-Legendre product rule on
 * pi sin(pi r) / r (an independent oracle for pixels the rim misses). */
static double
gl_square(double a0, double a1, double b0, double b1)
{
	double x[24], wt[24], s = 0;

	/* Legendre nodes by Newton's method on P_24 */
	for (int i = 0; i < 24; i++) {
		double z = cos(M_PI * (i + 0.75) / 24.5), pp = 0;

		for (int it = 0; it < 100; it++) {
			double p1 = 1, p2 = 0, z1;

			for (int j = 0; j < 24; j++) {
				double p3 = p2;

				p2 = p1;
				p1 = ((2 * j + 1) * z * p2 - j * p3) / (j + 1);
			}
			pp = 24 * (z * p1 - p2) / (z * z - 1);
			z1 = z;
			z = z1 - p1 / pp;
			if (fabs(z - z1) < 1e-16)
				break;
		}
		x[i] = z;
		wt[i] = 2 / ((1 - z * z) * pp * pp);
	}
	for (int i = 0; i < 24; i++)
		for (int j = 0; j < 24; j++) {
			double u = (a0 + a1) / 2 + (a1 - a0) / 2 * x[i];
			double v = (b0 + b1) / 2 + (b1 - b0) / 2 * x[j];
			double r = sqrt(u * u + v * v);

			s += wt[i] * wt[j] * M_PI * sin(M_PI * r) / r;
		}
	return s * (a1 - a0) / 2 * (b1 - b0) / 2;
}

static void
solid_angles(void **state)
{
	/* oracle: they sum to 4 pi (the sphere) to 1e-12; lat-long rows are
	 * (2 pi / w)(cos t0 - cos t1); a 2 x 2 angular map's pixels are the
	 * four quadrants, pi each; pixels the rim misses equal a Gauss-Legendre
	 * product rule; pixels outside the disc are 0 */
	static const struct { vx_env_layout l; int w, h; } t[] = {
		{ VX_ENV_LATLONG, 1, 1 }, { VX_ENV_LATLONG, 2, 1 },
		{ VX_ENV_LATLONG, 3, 7 }, { VX_ENV_LATLONG, 64, 32 },
		{ VX_ENV_LATLONG, 1024, 512 }, { VX_ENV_ANGULAR, 1, 1 },
		{ VX_ENV_ANGULAR, 2, 2 }, { VX_ENV_ANGULAR, 3, 3 },
		{ VX_ENV_ANGULAR, 4, 4 }, { VX_ENV_ANGULAR, 33, 33 },
		{ VX_ENV_ANGULAR, 256, 256 }, { VX_ENV_ANGULAR, 1000, 1000 },
	};

	(void)state;
	for (size_t k = 0; k < sizeof t / sizeof t[0]; k++) {
		vx_image img;
		vx_env env;
		vx_err e = { 0, "" };
		double sum = 0, comp = 0, worst = 0;
		int w = t[k].w, h = t[k].h;

		assert_int_equal(vx_image_alloc(&img, w, h, 1, &e), 0);
		assert_int_equal(vx_env_init(&env, &img, t[k].l, NULL, NULL, &e),
		    0);
		for (size_t i = 0; i < vx_env_npixel(&env); i++) {
			int x = (int)(i % (size_t)w), y = (int)(i / (size_t)w);
			double d[3], om, c[3], want = -1;

			vx_env_pixel(&env, i, d, &om, c);
			assert_true(om >= 0);
			{   /* Neumaier's sum: the test's own rounding stays out */
				double t2 = sum + om;

				comp += fabs(sum) >= fabs(om) ? (sum - t2) + om :
				    (om - t2) + sum;
				sum = t2;
			}
			if (t[k].l == VX_ENV_LATLONG) {
				want = 2 * M_PI / w * (cos(M_PI * y / h) -
				    cos(M_PI * (y + 1) / h));
			} else {
				double a0 = 2.0 * x / w - 1, a1 = 2.0 * (x + 1) / w - 1;
				double b1 = 1 - 2.0 * y / h, b0 = 1 - 2.0 * (y + 1) / h;
				double fx = fmax(fabs(a0), fabs(a1));
				double fy = fmax(fabs(b0), fabs(b1));
				double nx = a0 > 0 ? a0 : a1 < 0 ? a1 : 0;
				double ny = b0 > 0 ? b0 : b1 < 0 ? b1 : 0;

				if (w == 2)
					want = M_PI;
				else if (nx * nx + ny * ny >= 1)
					want = 0;
				else if (fx * fx + fy * fy <= 1 && w <= 64)
					want = gl_square(a0, a1, b0, b1);
			}
			if (want >= 0)
				worst = fmax(worst, fabs(om - want));
		}
		sum += comp;
		if (fabs(sum - 4 * M_PI) > 1e-12 || worst > 1e-14)
			fail_msg("%s %d x %d: sum - 4 pi = %g, worst pixel %g",
			    vx_enum_str(&vx_env_layout_enum, t[k].l), w, h, sum - 4 * M_PI,
			    worst);
		vx_env_free(&env);
		vx_image_free(&img);
	}
}

/* ---- lookups ---- */

static void
lookups(void **state)
{
	/* at a pixel's centre both lookups give the pixel; halfway between
	 * two pixel centres bilinear gives their mean; lat-long wraps across
	 * the -x seam */
	(void)state;
	for (int l = VX_ENV_LATLONG; l <= VX_ENV_ANGULAR; l++) {
		vx_env env;
		int w = 12, h = l == VX_ENV_LATLONG ? 6 : 12;

		make_env(&env, w, h, (vx_env_layout)l, NULL, 9);
		for (size_t i = 0; i < vx_env_npixel(&env); i++) {
			double d[3], om, c[3], n[3], b[3];
			int x = (int)(i % (size_t)w), y = (int)(i / (size_t)w);
			double a = 2.0 * (x + 0.5) / w - 1, bb = 1 - 2.0 * (y + 0.5) / h;

			if (l == VX_ENV_ANGULAR && a * a + bb * bb >= 0.99)
				continue;   /* centre at or beyond the rim */
			vx_env_pixel(&env, i, d, &om, c);
			vx_env_lookup(&env, d, 0, n);
			vx_env_lookup(&env, d, 1, b);
			assert_true(near3(n, c, 0));
			assert_true(near3(b, c, 1e-9 * (1 + lum(c))));
		}
		{
			double d[3], m[3], c0[3], c1[3], om;
			const float *p0, *p1;

			/* between pixels (2, 1) and (3, 1) */
			vx_env_image_to_dir((vx_env_layout)l, w, h, 3.0, 1.5, d);
			vx_env_lookup(&env, d, 1, m);
			vx_env_pixel(&env, (size_t)w + 2, d, &om, c0);
			vx_env_pixel(&env, (size_t)w + 3, d, &om, c1);
			p0 = env.px + 3 * (w + 2);
			p1 = env.px + 3 * (w + 3);
			for (int c = 0; c < 3; c++)
				assert_true(fabs(m[c] - env.scale[c] * ((double)p0[c] +
				    p1[c]) / 2) < 1e-12);
		}
		if (l == VX_ENV_LATLONG) {
			double d[3], m[3];
			const float *p0 = env.px + 3 * (2 * w), *p1 = env.px +
			    3 * (2 * w + w - 1);

			/* x = 0 is the seam: half the first and last pixels */
			vx_env_image_to_dir(VX_ENV_LATLONG, w, h, 0, 2.5, d);
			vx_env_lookup(&env, d, 1, m);
			for (int c = 0; c < 3; c++)
				assert_true(fabs(m[c] - env.scale[c] * ((double)p0[c] +
				    p1[c]) / 2) < 1e-12);
		}
		vx_env_free(&env);
	}
}

/* ---- sampling ---- */

static void
sampling_pdf_histogram(void **state)
{
	/* pdf(sample(u)) equals the pdf sample returns (to 1e-12, but for
	 * directions that round onto a neighbouring pixel: at most 1 in
	 * 10^4); each pixel is chosen with probability luminance x solid
	 * angle / sum, within 4 sigma + 1 of the binomial count (scrambled
	 * Sobol points are closer than that) */
	const long N = 1L << 17;    /* scrambled Sobol points */

	(void)state;
	for (int l = VX_ENV_LATLONG; l <= VX_ENV_ANGULAR; l++) {
		vx_env env;
		int w = 24, h = l == VX_ENV_LATLONG ? 12 : 24, bad = 0;
		long *count = calloc((size_t)w * h, sizeof *count);
		double *prob = calloc((size_t)w * h, sizeof *prob), total = 0;

		make_env(&env, w, h, (vx_env_layout)l, NULL, 11);
		for (size_t i = 0; i < vx_env_npixel(&env); i++) {
			double d[3], om, c[3];

			vx_env_pixel(&env, i, d, &om, c);
			prob[i] = lum(c) * om;
			total += prob[i];
		}
		for (uint64_t k = 0; k < (uint64_t)N; k++) {
			double u[2], d[3], c[3], pdf, q, x, y;

			ld2(k, 3, u);
			pdf = vx_env_sample(&env, u, d, c);
			if (pdf == 0) {
				assert_int_equal(l, VX_ENV_ANGULAR);
				continue;
			}
			q = vx_env_pdf(&env, d);
			if (fabs(q - pdf) > 1e-12 * pdf)
				bad++;
			assert_true(fabs(dot(d, d) - 1) < 1e-12);
			vx_env_dir_to_image((vx_env_layout)l, w, h, d, &x, &y);
			count[(size_t)fmin(floor(y), h - 1) * w +
			    (size_t)fmin(floor(x), w - 1)]++;
		}
		assert_true(bad <= N / 10000);
		for (size_t i = 0; i < vx_env_npixel(&env); i++) {
			int x = (int)(i % (size_t)w), y = (int)(i / (size_t)w);
			double a = fmax(fabs(2.0 * x / w - 1), fabs(2.0 * (x + 1) / w -
			    1));
			double b = fmax(fabs(1 - 2.0 * y / h), fabs(1 - 2.0 *
			    (y + 1) / h));
			double ex = (double)N * prob[i] / total;

			if (l == VX_ENV_ANGULAR && a * a + b * b > 1)
				continue;   /* the rim: part of it gives no sample */
			if (fabs(count[i] - ex) > 4 * sqrt(ex) + 1)
				fail_msg("%s pixel (%d, %d): %ld samples, expected "
				    "%.1f", vx_enum_str(&vx_env_layout_enum, (vx_env_layout)l), x,
				    y, count[i], ex);
		}
		free(count);
		free(prob);
		vx_env_free(&env);
	}
}

/* ref_irradiance: the irradiance at normal n of the piecewise-constant map:
 * every pixel cut into k x k parts (lat-long parts with their exact solid
 * angles, angular ones by the Jacobian at the part's centre). */
static void
ref_irradiance(const vx_env *env, const double n[3], int k, double E[3])
{
	int w = env->w, h = env->h;

	E[0] = E[1] = E[2] = 0;
	for (int y = 0; y < h; y++)
		for (int x = 0; x < w; x++) {
			const float *p = env->px + 3 * ((size_t)y * w + x);
			double s = 0;

			for (int a = 0; a < k; a++)
				for (int b = 0; b < k; b++) {
					double px = x + (b + 0.5) / k, py = y + (a + 0.5) / k;
					double d[3], om;

					if (vx_env_image_to_dir(env->layout, w, h, px, py,
					    d) != 0)
						continue;
					if (env->layout == VX_ENV_LATLONG) {
						om = 2 * M_PI / (w * k) * (cos(M_PI * (y +
						    (double)a / k) / h) - cos(M_PI * (y +
						    (a + 1.0) / k) / h));
					} else {
						double u = 2 * px / w - 1, v = 1 - 2 * py / h;
						double r = sqrt(u * u + v * v);

						om = 4.0 / (w * h * k * k) * (r > 0 ? M_PI *
						    sin(M_PI * r) / r : M_PI * M_PI);
					}
					s += om * fmax(0, dot(n, d));
				}
			for (int c = 0; c < 3; c++)
				E[c] += env->scale[c] * p[c] * s;
		}
}

static void
irradiance_mc_vs_quadrature(void **state)
{
	/* The importance-sampled estimate (2^17 scrambled Sobol points) of
	 * E(n) = integral of L max(0, n.w) agrees with the reference
	 * (ref_irradiance, 16 x 16 parts a pixel) within 4 of its own
	 * standard errors plus 2e-4 relative (the reference's own error);
	 * the centre-rule quadrature over the pixels (vx_env_pixel) within
	 * 1% (a 48 x 24 or 48 x 48 map: the rule's error is O(pixel^2)). */
	static const double normals[][3] = {
		{ 0, 0, 1 }, { 0, 0, -1 }, { 1, 0, 0 }, { -0.6, 0.8, 0 },
		{ 0.3, -0.4, 0.866025403784438 }, { 0.5, 0.5, -0.707106781186548 },
	};
	(void)state;
	for (int l = VX_ENV_LATLONG; l <= VX_ENV_ANGULAR; l++) {
		vx_env env;
		int w = 48, h = l == VX_ENV_LATLONG ? 24 : 48;

		make_env(&env, w, h, (vx_env_layout)l, NULL, 21);
		for (size_t k = 0; k < sizeof normals / sizeof normals[0]; k++) {
			const double *n = normals[k];
			double ref[3], mc[3] = { 0 }, mc2[3] = { 0 }, q[3] = { 0 };
			long N = 1L << 17;

			ref_irradiance(&env, n, 16, ref);
			for (long s = 0; s < N; s++) {
				double u[2], d[3], c[3], pdf;

				ld2((uint64_t)s, 17 + k, u);
				pdf = vx_env_sample(&env, u, d, c);
				for (int ch = 0; ch < 3; ch++) {
					double f = pdf > 0 ? c[ch] * fmax(0, dot(n, d)) /
					    pdf : 0;

					mc[ch] += f;
					mc2[ch] += f * f;
				}
			}
			for (size_t i = 0; i < vx_env_npixel(&env); i++) {
				double d[3], om, c[3];

				vx_env_pixel(&env, i, d, &om, c);
				for (int ch = 0; ch < 3; ch++)
					q[ch] += c[ch] * om * fmax(0, dot(n, d));
			}
			for (int ch = 0; ch < 3; ch++) {
				double mean = mc[ch] / N;
				double se = sqrt(fmax(0, mc2[ch] / N - mean * mean) / N);

				if (fabs(mean - ref[ch]) > 4 * se + 2e-4 * ref[ch] ||
				    fabs(q[ch] - ref[ch]) > 1e-2 * ref[ch])
					fail_msg("%s n %zu ch %d: MC %.6g (se %.2g), "
					    "quadrature %.6g, reference %.6g",
					    vx_enum_str(&vx_env_layout_enum, (vx_env_layout)l), k, ch,
					    mean, se, q[ch], ref[ch]);
			}
		}
		vx_env_free(&env);
	}
}

static void
sky(void **state)
{
	/* a constant sky: every lookup is its radiance, its pdf 1 / (4 pi),
	 * and its irradiance pi times its radiance in every direction: by
	 * importance sampling (2^16 scrambled Sobol points, 1e-3 relative) and by the quadrature of a
	 * 256 x 128 constant lat-long map (1e-4) */
	static const double normals[][3] = {
		{ 0, 0, 1 }, { 1, 0, 0 }, { 0.48, -0.6, 0.64 }, { 0, -1, 0 },
	};
	const double L[3] = { 0.5, 1.25, 3 };
	vx_env s, c;
	vx_image img;
	vx_err e = { 0, "" };

	(void)state;
	assert_int_equal(vx_env_sky(&s, L, &e), 0);
	assert_int_equal(vx_image_alloc(&img, 256, 128, 3, &e), 0);
	for (size_t i = 0; i < vx_image_nvalue(&img); i++)
		img.px[i] = 1;
	assert_int_equal(vx_env_init(&c, &img, VX_ENV_LATLONG, L, NULL, &e), 0);
	vx_image_free(&img);
	for (size_t k = 0; k < sizeof normals / sizeof normals[0]; k++) {
		const double *n = normals[k];
		double mc[3] = { 0 }, q[3] = { 0 }, rgb[3];
		const long N = 1L << 16;

		vx_env_lookup(&s, n, 1, rgb);
		assert_true(near3(rgb, L, 0));
		assert_true(fabs(vx_env_pdf(&s, n) * 4 * M_PI - 1) < 1e-15);
		for (long t = 0; t < N; t++) {
			double u[2], d[3], cc[3], pdf;

			ld2((uint64_t)t, 40 + k, u);
			pdf = vx_env_sample(&s, u, d, cc);
			for (int ch = 0; ch < 3; ch++)
				mc[ch] += cc[ch] * fmax(0, dot(n, d)) / pdf;
		}
		for (size_t i = 0; i < vx_env_npixel(&c); i++) {
			double d[3], om, cc[3];

			vx_env_pixel(&c, i, d, &om, cc);
			for (int ch = 0; ch < 3; ch++)
				q[ch] += cc[ch] * om * fmax(0, dot(n, d));
		}
		for (int ch = 0; ch < 3; ch++) {
			double want = M_PI * L[ch];

			if (fabs(mc[ch] / N - want) > 1e-3 * want ||
			    fabs(q[ch] - want) > 1e-4 * want)
				fail_msg("normal %zu ch %d: MC %.8g, quadrature %.8g, "
				    "pi L %.8g", k, ch, mc[ch] / N,
				    q[ch], want);
		}
	}
	vx_env_free(&s);
	vx_env_free(&c);
}

/* ---- the hash and the pixel rules ---- */

/* fnv_oracle: FNV-1a 64 over the bytes of formats/scene.md's definition,
 * written out byte by byte. */
static uint64_t
fnv_oracle(const unsigned char *b, size_t n)
{
	uint64_t x = 14695981039346656037ULL;

	for (size_t i = 0; i < n; i++) {
		x ^= b[i];
		x *= 1099511628211ULL;
	}
	return x;
}

static void
hash_and_pixel_rules(void **state)
{
	/* a 2 x 1 map (1, 2, 0.5 | -3, 0, -0): width, height and the floats
	 * as little-endian bytes, negatives and -0 hashed as +0 */
	static const unsigned char bytes[] = {
		2, 0, 0, 0, 1, 0, 0, 0,
		0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0x40,
		0x00, 0x00, 0x00, 0x3f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
	};
	const float px[6] = { 1, 2, 0.5f, -3, 0, -0.0f };
	vx_image img;
	vx_env env;
	vx_err e = { 0, "" };
	uint64_t h0;

	(void)state;
	assert_int_equal(vx_image_alloc(&img, 2, 1, 3, &e), 0);
	memcpy(img.px, px, sizeof px);
	assert_int_equal(vx_env_init(&env, &img, VX_ENV_LATLONG, NULL, NULL, &e),
	    0);
	assert_true(env.hash == fnv_oracle(bytes, sizeof bytes));
	assert_true(env.nclamped == 1);
	assert_true(env.px[3] == 0 && !signbit(env.px[5]));
	h0 = env.hash;
	vx_env_free(&env);
	/* one value changed by one ulp changes the hash */
	img.px[2] = nextafterf(0.5f, 1);
	assert_int_equal(vx_env_init(&env, &img, VX_ENV_LATLONG, NULL, NULL, &e),
	    0);
	assert_true(env.hash != h0);
	vx_env_free(&env);
	/* NaN and infinity are refused, naming the pixel */
	img.px[4] = NAN;
	assert_int_equal(vx_env_init(&env, &img, VX_ENV_LATLONG, NULL, NULL, &e),
	    VX_EDATA);
	assert_non_null(strstr(e.msg, "pixel (1, 0) is NaN"));
	assert_null(env.px);
	img.px[4] = -INFINITY;
	assert_int_equal(vx_env_init(&env, &img, VX_ENV_LATLONG, NULL, NULL, &e),
	    VX_EDATA);
	assert_non_null(strstr(e.msg, "infinite"));
	/* an angular map must be square */
	img.px[4] = 0;
	assert_int_equal(vx_env_init(&env, &img, VX_ENV_ANGULAR, NULL, NULL, &e),
	    VX_EDATA);
	assert_non_null(strstr(e.msg, "square"));
	vx_image_free(&img);
	/* a black map is sampled by solid angle */
	assert_int_equal(vx_image_alloc(&img, 4, 2, 3, &e), 0);
	assert_int_equal(vx_env_init(&env, &img, VX_ENV_LATLONG, NULL, NULL, &e),
	    0);
	assert_true(env.uniform);
	assert_true(fabs(vx_env_pdf(&env, (const double[3]){ 0, 0, 1 }) * 4 *
	    M_PI - 1) < 1e-12);
	vx_env_free(&env);
	vx_image_free(&img);
}

/* ---- a scene's environment light, from a file ---- */

static void
load_light_and_hash(void **state)
{
	char path[] = "/tmp/test_env_XXXXXX";
	vx_scene s;
	vx_image img;
	vx_env env;
	vx_err e = { 0, "" };
	FILE *f;
	int fd;
	char line[2048];

	(void)state;
	fd = mkstemp(path);
	assert_true(fd >= 0);
	test_map(&img, 16, 8, 4);
	for (size_t i = 0; i < vx_image_nvalue(&img); i++)   /* RGBE-exact */
		img.px[i] = ldexpf(roundf(ldexpf(img.px[i], 4)), -4);
	f = fdopen(fd, "wb");
	assert_int_equal(vx_hdr_write(&img, f, 1, &e), 0);
	fclose(f);
	snprintf(line, sizeof line, "light environment file %s rotation 0 0 30 "
	    "intensity 2", path);
	vx_scene_init(&s);
	assert_int_equal(vx_scene_apply(&s, line, &e), 0);
	assert_int_equal(vx_scene_apply(&s, "light sky color 0.1 0.2 0.3", &e),
	    0);
	assert_false(s.light[0].has_hash);
	assert_int_equal(vx_env_scene_resolve(&s, &e), 0);
	assert_true(s.light[0].has_hash);
	assert_true(s.light[0].hash == vx_env_hash(img.px, 16, 8));
	assert_int_equal(vx_env_load_light(&env, &s.light[0], &e), 0);
	assert_true(env.scale[0] == 2 && env.rot[2][2] == 1);
	vx_env_free(&env);
	assert_int_equal(vx_env_load_light(&env, &s.light[1], &e), 0);
	assert_true(env.w == 1 && env.scale[2] == 0.3);
	vx_env_free(&env);
	/* the file changes: the scene's hash refuses it */
	img.px[7] += 1;
	f = fopen(path, "wb");
	assert_int_equal(vx_hdr_write(&img, f, 0, &e), 0);
	fclose(f);
	assert_int_equal(vx_env_load_light(&env, &s.light[0], &e), VX_EDATA);
	assert_non_null(strstr(e.msg, "content hash"));
	assert_int_equal(vx_env_scene_resolve(&s, &e), VX_EDATA);
	assert_non_null(strstr(e.msg, "light 1: "));
	/* a file that is not there */
	unlink(path);
	assert_int_equal(vx_env_load_light(&env, &s.light[0], &e), VX_ENOINPUT);
	vx_image_free(&img);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(orientation),
		cmocka_unit_test(rotation_key),
		cmocka_unit_test(solid_angles),
		cmocka_unit_test(lookups),
		cmocka_unit_test(sampling_pdf_histogram),
		cmocka_unit_test(irradiance_mc_vs_quadrature),
		cmocka_unit_test(sky),
		cmocka_unit_test(hash_and_pixel_rules),
		cmocka_unit_test(load_light_and_hash),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
