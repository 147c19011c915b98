/* test_sh.c: real spherical harmonics: the basis against closed forms and
 * the addition theorem, orthonormality by exact quadrature, projection,
 * the clamped-cosine convolution and irradiance, and rotations (Ivanic-
 * Ruedenberg against the definition, the ZYZ product, and each other).
 * Each test names its oracle. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "vx_rng.h"
#include "vx_sh.h"
#include "vx_warp.h"

#define PI 3.14159265358979323846
#define NMAX VX_SH_MAX_ORDER
#define ROT_MAX (NMAX * (4 * NMAX * NMAX - 1) / 3)

static double rot_a[ROT_MAX], rot_b[ROT_MAX], rot_c[ROT_MAX];

/* a direction: unit vectors from scrambled Sobol points */
static void
direction(uint64_t stream, uint64_t i, double w[3])
{
	double u[2];

	vx_rng_ld2(17, stream, i, 0, u);
	vx_warp_uniform_sphere(u, w);
}

/* random_rotation: a rotation uniform over SO(3) (Shoemake's quaternion
 * from three uniforms), numbered by i. */
static void
random_rotation(uint64_t i, double r[3][3])
{
	double u1 = vx_rng_uniform(23, i, 0, 0);
	double u2 = vx_rng_uniform(23, i, 0, 1);
	double u3 = vx_rng_uniform(23, i, 0, 2);
	double a = sqrt(1 - u1), b = sqrt(u1);
	double x = a * sin(2 * PI * u2), y = a * cos(2 * PI * u2),
	    z = b * sin(2 * PI * u3), w = b * cos(2 * PI * u3);

	r[0][0] = 1 - 2 * (y * y + z * z);
	r[0][1] = 2 * (x * y - z * w);
	r[0][2] = 2 * (x * z + y * w);
	r[1][0] = 2 * (x * y + z * w);
	r[1][1] = 1 - 2 * (x * x + z * z);
	r[1][2] = 2 * (y * z - x * w);
	r[2][0] = 2 * (x * z - y * w);
	r[2][1] = 2 * (y * z + x * w);
	r[2][2] = 1 - 2 * (x * x + y * y);
}

static void
mul3(const double a[3][3], const double b[3][3], double c[3][3])
{
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] +
			    a[i][2] * b[2][j];
}

/* ---- the basis ---- */

/* The real SH of bands 0-3 without the Condon-Shortley phase in Cartesian
 * form (the standard table, e.g. Ramamoorthi and Hanrahan 2001 for l <= 2;
 * exact constants).  vx_sh has the phase: Y_lm = (-1)^m times these. */
static double
closed_form(int l, int m, const double w[3])
{
	double x = w[0], y = w[1], z = w[2];

	switch (l * 10 + m + 3) {
	case 3: return 0.5 / sqrt(PI);
	case 12: return sqrt(3 / (4 * PI)) * y;
	case 13: return sqrt(3 / (4 * PI)) * z;
	case 14: return sqrt(3 / (4 * PI)) * x;
	case 21: return 0.5 * sqrt(15 / PI) * x * y;
	case 22: return 0.5 * sqrt(15 / PI) * y * z;
	case 23: return 0.25 * sqrt(5 / PI) * (3 * z * z - 1);
	case 24: return 0.5 * sqrt(15 / PI) * x * z;
	case 25: return 0.25 * sqrt(15 / PI) * (x * x - y * y);
	case 30: return 0.25 * sqrt(35 / (2 * PI)) * y * (3 * x * x - y * y);
	case 31: return 0.5 * sqrt(105 / PI) * x * y * z;
	case 32: return 0.25 * sqrt(21 / (2 * PI)) * y * (5 * z * z - 1);
	case 33: return 0.25 * sqrt(7 / PI) * (5 * z * z * z - 3 * z);
	case 34: return 0.25 * sqrt(21 / (2 * PI)) * x * (5 * z * z - 1);
	case 35: return 0.25 * sqrt(105 / PI) * z * (x * x - y * y);
	case 36: return 0.25 * sqrt(35 / (2 * PI)) * x * (x * x - 3 * y * y);
	}
	return NAN;
}

/* Bands 0-3 against the closed forms times (-1)^m (the phase the header
 * states: Y_1^1 = -0.4886 x), at the poles, on the equator and at 256
 * directions: to 1e-15.  At the poles every m != 0 function is 0 and
 * Y_l0 = (+-1)^l sqrt((2l + 1) / (4 pi)), for every band. */
static void
closed_forms(void **state)
{
	double ws[260][3] = { { 0, 0, 1 }, { 0, 0, -1 }, { 1, 0, 0 },
	    { 0, 1, 0 } };
	double y[VX_SH_MAX_COEF];

	(void)state;
	for (int i = 4; i < 260; i++)
		direction(1, (uint64_t)i, ws[i]);
	for (int i = 0; i < 260; i++) {
		vx_sh_eval(4, ws[i], y);
		for (int l = 0; l < 4; l++)
			for (int m = -l; m <= l; m++) {
				double want = (m & 1 ? -1 : 1) *
				    closed_form(l, m, ws[i]);

				if (!(fabs(y[vx_sh_index(l, m)] - want) < 1e-15))
					fail_msg("Y_%d^%d at %d: %.17g, want "
					    "%.17g", l, m, i,
					    y[vx_sh_index(l, m)], want);
			}
	}
	for (int p = 0; p < 2; p++) {
		vx_sh_eval(VX_SH_MAX_ORDER, ws[p], y);
		for (int l = 0; l < VX_SH_MAX_ORDER; l++)
			for (int m = -l; m <= l; m++) {
				double want = m ? 0 : (p && (l & 1) ? -1 : 1) *
				    sqrt((2 * l + 1) / (4 * PI));

				assert_true(fabs(y[vx_sh_index(l, m)] - want) <
				    1e-13);
			}
	}
}

/* The addition theorem, for every band to 31 (phase-independent, and a
 * check on the whole band at once): sum over m of Y_lm(a) Y_lm(b) =
 * (2l + 1) / (4 pi) P_l(a.b), with P_l by Bonnet's recurrence.  Relative to
 * (2l + 1) / (4 pi): 1e-13. */
static void
addition_theorem(void **state)
{
	double ya[VX_SH_MAX_COEF], yb[VX_SH_MAX_COEF];

	(void)state;
	for (int i = 0; i < 200; i++) {
		double a[3], b[3];

		direction(2, (uint64_t)i, a);
		direction(3, (uint64_t)i, b);
		if (i == 0)	/* the same direction: P_l(1) = 1 */
			memcpy(b, a, sizeof b);
		if (i == 1)	/* opposite: P_l(-1) = (-1)^l */
			for (int k = 0; k < 3; k++)
				b[k] = -a[k];
		vx_sh_eval(VX_SH_MAX_ORDER, a, ya);
		vx_sh_eval(VX_SH_MAX_ORDER, b, yb);
		double t = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
		double p0 = 1, p1;

		/* a.a is 1 only to rounding, and P_31'(1) = 496 */
		t = i == 0 ? 1 : i == 1 ? -1 : t;
		p1 = t;

		for (int l = 0; l < VX_SH_MAX_ORDER; l++) {
			double s = 0, pl;

			for (int m = -l; m <= l; m++)
				s += ya[vx_sh_index(l, m)] * yb[vx_sh_index(l, m)];
			if (l == 0)
				pl = 1;
			else if (l == 1)
				pl = t;
			else {
				pl = ((2 * l - 1) * t * p1 - (l - 1) * p0) / l;
				p0 = p1;
				p1 = pl;
			}
			double k = (2 * l + 1) / (4 * PI);

			if (!(fabs(s / k - pl) < 1e-13))
				fail_msg("l %d at %d: %.17g vs %.17g", l, i,
				    s / k, pl);
		}
	}
}

/* Orthonormality by the exact product rule (order Gauss-Legendre nodes in z,
 * 2 order angles in phi: exact for Y_i Y_j of bands < order): the Gram
 * matrix is the identity to 1e-12.  Order 16: the whole matrix.  Order 32
 * (stability of the recurrence to band 31): the blocks of equal m, where
 * the recurrence in z is what is tested (functions of different m are
 * orthogonal by the phi rule whatever their z part). */
static void
orthonormal(void **state)
{
	static double g16[256][256], g32[VX_SH_MAX_COEF][32];
	double z[32], wt[32], y[VX_SH_MAX_COEF];

	(void)state;
	memset(g16, 0, sizeof g16);
	memset(g32, 0, sizeof g32);
	for (int pass = 0; pass < 2; pass++) {
		int order = pass ? 32 : 16, nphi = 2 * order;
		double worst = 0;

		vx_sh_gauss_legendre(order, z, wt);
		for (int i = 0; i < order; i++)
			for (int j = 0; j < nphi; j++) {
				double s = sqrt(1 - z[i] * z[i]);
				double phi = 2 * PI * (j + 0.5) / nphi;
				double w[3] = { s * cos(phi), s * sin(phi),
				    z[i] };
				double q = wt[i] * 2 * PI / nphi;

				vx_sh_eval(order, w, y);
				if (!pass) {
					for (int a = 0; a < 256; a++)
						for (int b = a; b < 256; b++)
							g16[a][b] += q * y[a] * y[b];
					continue;
				}
				for (int l1 = 0; l1 < 32; l1++)
					for (int m = -l1; m <= l1; m++) {
						int a = vx_sh_index(l1, m);

						for (int l2 = l1; l2 < 32; l2++)
							g32[a][l2] += q * y[a] *
							    y[vx_sh_index(l2, m)];
					}
			}
		for (int l1 = 0; l1 < order; l1++)
			for (int m = -l1; m <= l1; m++)
				for (int l2 = 0; l2 < order; l2++)
					for (int m2 = -l2; m2 <= l2; m2++) {
						int a = vx_sh_index(l1, m);
						int b = vx_sh_index(l2, m2);
						double g;

						if (b < a || (pass && m != m2))
							continue;
						g = pass ? g32[a][l2] : g16[a][b];
						worst = fmax(worst, fabs(g - (a == b)));
					}
		if (!(worst < 1e-12))
			fail_msg("order %d: |G - I| = %.3g", order, worst);
	}
}

/* ---- projection ---- */

struct expansion {
	int order;
	const double *c;
};

static void
eval_expansion(const double w[3], void *user, double *val)
{
	const struct expansion *e = user;

	val[0] = vx_sh_eval_sum(e->order, e->c, w);
	val[1] = 2 - val[0];
}

/* A function made of known SH projects back to its coefficients: a random
 * order-6 expansion (and, on a second channel, 2 minus it).  Exactly (to
 * 1e-13) by the product rule with 7 nodes (degree 5 + 7 <= 13); to 2e-3 by
 * 2^14 scrambled Sobol directions (vx_sh_project_mc), whose error also falls
 * at least 16-fold from 2^10 to 2^14 (N^-1; N^-1/2 would be 4-fold); and
 * vx_sh_project_samples on those same directions gives the same numbers.
 * Bands 6 and 7, absent from the function, come back as 0. */
static void
projection(void **state)
{
	enum { ORDER = 6, N = 1 << 14 };
	double c[ORDER * ORDER], got[2 * 64], mc[2 * 64], fs[2 * 64];
	struct expansion e = { ORDER, c };
	static double w[3 * N], pdf[N], val[2 * N];

	(void)state;
	for (int i = 0; i < ORDER * ORDER; i++)
		c[i] = vx_rng_uniform(5, 0, (uint64_t)i, 0) - 0.5;
	vx_sh_project_gauss(8, 7, eval_expansion, &e, 2, got);
	for (int l = 0; l < 8; l++)
		for (int m = -l; m <= l; m++) {
			int i = vx_sh_index(l, m);
			double want = l < ORDER ? c[i] : 0;
			double want2 = (i == 0 ? 2 * sqrt(4 * PI) : 0) - want;

			assert_true(fabs(got[i] - want) < 1e-13);
			assert_true(fabs(got[64 + i] - want2) < 1e-13);
		}
	double err[2] = { 0, 0 };

	for (int pass = 0; pass < 2; pass++) {
		uint64_t n = pass ? N : 1024;

		vx_sh_project_mc(ORDER, eval_expansion, &e, 2, n, 9, 4, 0, mc);
		for (int i = 0; i < ORDER * ORDER; i++)
			err[pass] = fmax(err[pass], fabs(mc[i] - c[i]));
	}
	if (!(err[1] < 2e-3 && err[1] * 16 < err[0]))
		fail_msg("Monte Carlo: error %.3g at 1024, %.3g at %d", err[0],
		    err[1], N);
	for (int s = 0; s < N; s++) {
		double u[2];

		vx_rng_ld2(9, 4, (uint64_t)s, 0, u);
		pdf[s] = vx_warp_uniform_sphere(u, w + 3 * s);
		eval_expansion(w + 3 * s, &e, val + 2 * s);
	}
	vx_sh_project_samples(ORDER, N, w, pdf, val, 2, fs);
	for (int i = 0; i < 2 * ORDER * ORDER; i++)
		assert_true(fabs(fs[i] - mc[i]) < 1e-14);
}

/* The bases with and without the Condon-Shortley phase: a function given
 * by Ramamoorthi and Hanrahan's basis (the closed forms above, no phase)
 * with coefficients k projects (product rule) onto coefficients that
 * vx_sh_flip_phase turns into k, to 1e-14; flipping twice is the identity. */
static void
phase(void **state)
{
	static double k[16];
	double got[16], back[16];

	(void)state;
	for (int i = 0; i < 16; i++)
		k[i] = cos(1.7 * i + 0.3);
	{
		double x[4], wt[4];

		memset(got, 0, sizeof got);
		vx_sh_gauss_legendre(4, x, wt);
		for (int i = 0; i < 4; i++)
			for (int j = 0; j < 8; j++) {
				double s = sqrt(1 - x[i] * x[i]);
				double phi = 2 * PI * (j + 0.5) / 8;
				double w[3] = { s * cos(phi), s * sin(phi), x[i] };
				double f = 0;

				for (int l = 0; l < 4; l++)
					for (int m = -l; m <= l; m++)
						f += k[vx_sh_index(l, m)] *
						    closed_form(l, m, w);
				vx_sh_accumulate(4, w, wt[i] * 2 * PI / 8, &f, 1,
				    got);
			}
	}
	memcpy(back, got, sizeof got);
	vx_sh_flip_phase(4, 1, got);
	for (int i = 0; i < 16; i++)
		assert_true(fabs(got[i] - k[i]) < 1e-14);
	vx_sh_flip_phase(4, 1, got);
	for (int i = 0; i < 16; i++)
		assert_true(got[i] == back[i]);
}

/* ---- the clamped cosine ---- */

/* The convolution factors: A_0..A_6 against their closed values (pi,
 * 2 pi/3, pi/4, 0, -pi/24, 0, pi/64), and every band to 40 against the
 * zonal coefficients of max(cos theta, 0) computed by Gauss-Legendre
 * quadrature on [0, 1] (exact: a polynomial of degree l + 1),
 * A_l = sqrt(4 pi / (2l + 1)) 2 pi integral of z Y_l0(z) dz: to 1e-14. */
static void
cosine_bands(void **state)
{
	static const double want[] = { PI, 2 * PI / 3, PI / 4, 0, -PI / 24, 0,
	    PI / 64 };
	double x[32], wt[32];

	(void)state;
	for (int l = 0; l < 7; l++)
		assert_true(fabs(vx_sh_cosine_band(l) - want[l]) < 1e-15);
	vx_sh_gauss_legendre(32, x, wt);
	for (int l = 0; l < 41; l++) {
		double k = 0;

		for (int i = 0; i < 32; i++) {
			double z = 0.5 * (x[i] + 1), p0 = 0, p1 = 1;

			/* Y_l0 = sqrt((2l + 1) / (4 pi)) P_l(z); P_l by
			 * Bonnet's recurrence, p1 = P_j, p0 = P_j-1 */
			for (int j = 0; j < l; j++) {
				double p2 = ((2 * j + 1) * z * p1 - j * p0) /
				    (j + 1);

				p0 = p1;
				p1 = p2;
			}
			k += 0.5 * wt[i] * z * p1;
		}
		k *= 2 * PI;	/* times sqrt((2l+1)/4pi) sqrt(4pi/(2l+1)) */
		if (!(fabs(vx_sh_cosine_band(l) - k) < 1e-14))
			fail_msg("A_%d = %.17g, quadrature %.17g", l,
			    vx_sh_cosine_band(l), k);
	}
}

struct sky {
	double l;
};

static void
constant_sky(const double w[3], void *user, double *val)
{
	(void)w;
	val[0] = ((struct sky *)user)->l;
}

/* A constant sky of radiance L projects onto c_00 = L sqrt(4 pi) alone, and
 * its irradiance is pi L in every direction, at every order 1..16: 1e-13
 * relative, at 64 normals. */
static void
sky_irradiance(void **state)
{
	struct sky sky = { 1.7 };
	double c[256], e;

	(void)state;
	for (int order = 1; order <= 16; order++) {
		vx_sh_project_gauss(order, order, constant_sky, &sky, 1, c);
		assert_true(fabs(c[0] - 1.7 * sqrt(4 * PI)) < 1e-13);
		for (int i = 1; i < order * order; i++)
			assert_true(fabs(c[i]) < 1e-14);
		for (int i = 0; i < 64; i++) {
			double n[3];

			direction(6, (uint64_t)i, n);
			vx_sh_irradiance(order, 1, c, n, &e);
			if (!(fabs(e / (PI * 1.7) - 1) < 1e-13))
				fail_msg("order %d normal %d: E = %.17g", order,
				    i, e);
		}
	}
}

/* Irradiance of band-limited lighting by SH (one call) against direct
 * quadrature of the integral of L(w) max(n.w, 0) over the hemisphere around
 * n (Gauss-Legendre in n.w on [0, 1] times 16 angles, in the frame of
 * vx_onb: exact for this polynomial): lighting of bands 0-3, 3 channels,
 * 32 normals, 1e-13.  vx_sh_convolve_cosine then vx_sh_eval_sum agrees.
 * Ramamoorthi and Hanrahan's eq. 13 (their 9 coefficients, constants
 * c1..c5 to 6 digits) gives the same order-3 irradiance to 1e-5. */
static void
irradiance(void **state)
{
	double c[3 * 16], conv[3 * 16], rh[9], x[8], wt[8];

	(void)state;
	for (int i = 0; i < 3 * 16; i++)
		c[i] = (i % 16 == 0 ? 2 : 0) + sin(0.9 * i + 0.4) * 0.5;
	vx_sh_convolve_cosine(4, 3, c, conv);
	vx_sh_gauss_legendre(8, x, wt);
	for (int i = 0; i < 32; i++) {
		double n[3], t[3], b[3], e[3], want[3] = { 0, 0, 0 };

		direction(7, (uint64_t)i, n);
		vx_onb(n, t, b);
		for (int a = 0; a < 8; a++) {
			double ct = 0.5 * (x[a] + 1), st = sqrt(1 - ct * ct);

			for (int j = 0; j < 16; j++) {
				double phi = 2 * PI * j / 16, l[3] = { st * cos(phi),
				    st * sin(phi), ct }, w[3];

				vx_onb_to_world(n, t, b, l, w);
				for (int k = 0; k < 3; k++)
					want[k] += vx_sh_eval_sum(4, c + 16 * k,
					    w) * ct * 0.5 * wt[a] * (2 * PI / 16);
			}
		}
		vx_sh_irradiance(4, 3, c, n, e);
		for (int k = 0; k < 3; k++) {
			assert_true(fabs(e[k] - want[k]) < 1e-13);
			assert_true(fabs(vx_sh_eval_sum(4, conv + 16 * k, n) -
			    want[k]) < 1e-13);
		}
		/* Ramamoorthi and Hanrahan 2001, eq. 13, on channel 0's
		 * first 9 coefficients in their basis */
		const double c1 = 0.429043, c2 = 0.511664, c3 = 0.743125,
		    c4 = 0.886227, c5 = 0.247708;
		double X = n[0], Y = n[1], Z = n[2], e9;

		memcpy(rh, c, sizeof rh);
		vx_sh_flip_phase(3, 1, rh);
		double rhe = c1 * rh[8] * (X * X - Y * Y) + c3 * rh[6] * Z * Z +
		    c4 * rh[0] - c5 * rh[6] + 2 * c1 * (rh[4] * X * Y +
		    rh[7] * X * Z + rh[5] * Y * Z) + 2 * c2 * (rh[3] * X +
		    rh[1] * Y + rh[2] * Z);

		vx_sh_irradiance(3, 1, c, n, &e9);
		if (!(fabs(rhe - e9) < 1e-5))
			fail_msg("normal %d: %.9g vs R&H %.9g", i, e9, rhe);
	}
}

/* ---- rotations ---- */

/* band_err: the largest |a - b| over all elements of two rotations */
static double
band_err(int order, const double *a, const double *b)
{
	double m = 0;

	for (size_t i = 0; i < vx_sh_rot_size(order); i++)
		m = fmax(m, fabs(a[i] - b[i]));
	return m;
}

/* ortho_err: the largest |M M^T - I| over the bands of rot */
static double
ortho_err(int order, const double *rot)
{
	double worst = 0;

	for (int l = 0; l < order; l++) {
		const double *b = rot + vx_sh_rot_offset(l);
		int s = 2 * l + 1;

		for (int i = 0; i < s; i++)
			for (int j = 0; j < s; j++) {
				double d = -(i == j);

				for (int k = 0; k < s; k++)
					d += b[i * s + k] * b[j * s + k];
				worst = fmax(worst, fabs(d));
			}
	}
	return worst;
}

/* compose: c = a b, band by band */
static void
compose(int order, const double *a, const double *b, double *c)
{
	for (int l = 0; l < order; l++) {
		size_t o = vx_sh_rot_offset(l);
		int s = 2 * l + 1;

		for (int i = 0; i < s; i++)
			for (int j = 0; j < s; j++) {
				double d = 0;

				for (int k = 0; k < s; k++)
					d += a[o + i * s + k] * b[o + k * s + j];
				c[o + i * s + j] = d;
			}
	}
}

/* The hard cases: ZYZ angles (degrees) including gimbal lock (beta = 0,
 * beta = 180), half turns, and generic ones. */
static const double cases[][3] = {
	{ 0, 0, 0 }, { 30, 0, 40 }, { -100, 0, 100 }, { 30, 180, 40 },
	{ 0, 180, 0 }, { 180, 0, 0 }, { 90, 180, -90 }, { 0, 90, 0 },
	{ 90, 90, 90 }, { 12.5, 77.25, -130 }, { -170, 3, 171 },
	{ 179.9, 179.9, 179.9 }, { 45, 1e-9, 45 }, { 33, 180 - 1e-9, -12 },
};
#define NCASE (sizeof cases / sizeof cases[0])
#define RAD(d) ((d) * PI / 180)

/* Ivanic-Ruedenberg (from the ZYZ angles' 3x3 matrix) equals the ZYZ
 * product (closed-form z turns, quadrature X(90)) to 1e-12, order 16, for
 * the hard cases and 8 random rotations (their angles from
 * vx_rot3_to_zyz).  Both are orthogonal to 1e-12. */
static void
ir_equals_zyz(void **state)
{
	(void)state;
	for (size_t k = 0; k < NCASE + 8; k++) {
		double r[3][3], a, b, g;

		if (k < NCASE) {
			a = RAD(cases[k][0]);
			b = RAD(cases[k][1]);
			g = RAD(cases[k][2]);
			vx_rot3_zyz(a, b, g, r);
		} else {
			random_rotation(k, r);
			vx_rot3_to_zyz(r, &a, &b, &g);
		}
		vx_sh_rot_from_matrix(16, r, rot_a);
		vx_sh_rot_from_zyz(16, a, b, g, rot_b);
		double d = band_err(16, rot_a, rot_b);
		double oa = ortho_err(16, rot_a), ob = ortho_err(16, rot_b);

		if (!(d < 1e-12 && oa < 1e-12 && ob < 1e-12))
			fail_msg("case %zu: |IR - ZYZ| %.3g, orthogonality "
			    "%.3g %.3g", k, d, oa, ob);
	}
}

/* definition: the SH rotation of r straight from eq. 16, element (s, t) =
 * integral of Y_s(r w) Y_t(w), by the product rule of 8 Gauss-Legendre
 * nodes x 16 angles (exact for bands < 8), into rot (order 8). */
static void
definition(const double r[3][3], double *rot)
{
	double y1[64], y2[64], x[8], wt[8];

	vx_sh_gauss_legendre(8, x, wt);
	memset(rot, 0, sizeof *rot * vx_sh_rot_size(8));
	for (int i = 0; i < 8; i++)
		for (int j = 0; j < 16; j++) {
			double s = sqrt(1 - x[i] * x[i]);
			double phi = 2 * PI * (j + 0.5) / 16;
			double w[3] = { s * cos(phi), s * sin(phi), x[i] }, rw[3];
			double q = wt[i] * (2 * PI / 16);

			for (int c = 0; c < 3; c++)
				rw[c] = r[c][0] * w[0] + r[c][1] * w[1] +
				    r[c][2] * w[2];
			vx_sh_eval(8, w, y1);
			vx_sh_eval(8, rw, y2);
			for (int l = 0; l < 8; l++) {
				double *b = rot + vx_sh_rot_offset(l);
				int n = 2 * l + 1;

				for (int m = 0; m < n; m++)
					for (int k = 0; k < n; k++)
						b[m * n + k] += q * y2[l * l + m] *
						    y1[l * l + k];
			}
		}
}

/* The definition, eq. 16, element by element, for 4 random rotations at
 * order 8: Ivanic-Ruedenberg agrees to 1e-13. */
static void
ir_is_definition(void **state)
{
	(void)state;
	for (uint64_t k = 0; k < 4; k++) {
		double r[3][3];

		random_rotation(100 + k, r);
		definition(r, rot_b);
		vx_sh_rot_from_matrix(8, r, rot_a);
		double d = band_err(8, rot_a, rot_b);

		if (!(d < 1e-13))
			fail_msg("rotation %d: |IR - eq. 16| = %.3g", (int)k,
			    d);
	}
}

/* Composition: matrix(a) matrix(b) = matrix(a b) to 1e-12 at order 16, for
 * pairs of random rotations and pairs from the hard cases. */
static void
composition(void **state)
{
	(void)state;
	for (uint64_t k = 0; k < 6; k++) {
		double ra[3][3], rb[3][3], rab[3][3];

		if (k < 4) {
			random_rotation(200 + 2 * k, ra);
			random_rotation(201 + 2 * k, rb);
		} else {
			const double *p = cases[k == 4 ? 3 : 12];
			const double *q = cases[k == 4 ? 9 : 6];

			vx_rot3_zyz(RAD(p[0]), RAD(p[1]), RAD(p[2]), ra);
			vx_rot3_zyz(RAD(q[0]), RAD(q[1]), RAD(q[2]), rb);
		}
		mul3(ra, rb, rab);
		vx_sh_rot_from_matrix(16, ra, rot_a);
		vx_sh_rot_from_matrix(16, rb, rot_b);
		compose(16, rot_a, rot_b, rot_c);
		vx_sh_rot_from_matrix(16, rab, rot_a);
		double d = band_err(16, rot_a, rot_c);

		if (!(d < 1e-12))
			fail_msg("pair %d: |R(a)R(b) - R(ab)| = %.3g", (int)k,
			    d);
	}
}

/* What a rotation means: the rotated coefficients evaluated at w equal the
 * original expansion at r^-1 w = r^T w, to 1e-10, order 10, for 16 random
 * rotations x 32 directions, 3 channels (vx_sh_rot_apply in place), by the
 * recurrence and by the ZYZ product.  Also the irradiance: the irradiance
 * of the rotated lighting at n is the original's at r^T n. */
static void
rotated_evaluation(void **state)
{
	enum { ORDER = 10, NC = ORDER * ORDER };
	double c[3 * NC], g[3 * NC], h[3 * NC];

	(void)state;
	for (int i = 0; i < 3 * NC; i++)
		c[i] = vx_rng_uniform(31, 0, (uint64_t)i, 0) * 2 - 1;
	for (uint64_t k = 0; k < 16; k++) {
		double r[3][3], a, b, gm;

		random_rotation(300 + k, r);
		vx_rot3_to_zyz(r, &a, &b, &gm);
		vx_sh_rot_from_matrix(ORDER, r, rot_a);
		vx_sh_rot_from_zyz(ORDER, a, b, gm, rot_b);
		memcpy(g, c, sizeof g);
		vx_sh_rot_apply(ORDER, rot_a, 3, g, g);
		vx_sh_rot_apply(ORDER, rot_b, 3, c, h);
		for (int i = 0; i < 32; i++) {
			double w[3], rw[3], e0[3], e1[3];

			direction(8, (uint64_t)i, w);
			for (int j = 0; j < 3; j++)
				rw[j] = r[0][j] * w[0] + r[1][j] * w[1] +
				    r[2][j] * w[2];
			for (int ch = 0; ch < 3; ch++) {
				double want = vx_sh_eval_sum(ORDER, c + ch * NC, rw);
				double got = vx_sh_eval_sum(ORDER, g + ch * NC, w);
				double got2 = vx_sh_eval_sum(ORDER, h + ch * NC, w);

				if (!(fabs(got - want) < 1e-10 &&
				    fabs(got2 - want) < 1e-10))
					fail_msg("rotation %d dir %d: %.17g %.17g "
					    "want %.17g", (int)k, i, got, got2,
					    want);
			}
			vx_sh_irradiance(ORDER, 3, g, w, e0);
			vx_sh_irradiance(ORDER, 3, c, rw, e1);
			for (int ch = 0; ch < 3; ch++)
				assert_true(fabs(e0[ch] - e1[ch]) < 1e-10);
		}
	}
}

/* Band 1, where sign conventions show first: the dipole f(w) = d.w
 * (projected exactly) turned by r is the dipole (r d).w, by both methods;
 * and the coefficients of f(w) = x are (0, 0, -k) on m = -1, 0, 1 with
 * k = sqrt(4 pi / 3) (the header's Y_1^1 = -sqrt(3 / (4 pi)) x). */
static void
band_one(void **state)
{
	double d[3] = { 0.3, -0.7, 0.5 }, r[3][3], rd[3], c[4], cr[4], want[4];
	double k = sqrt(4 * PI / 3);

	(void)state;
	random_rotation(400, r);
	for (int i = 0; i < 3; i++)
		rd[i] = r[i][0] * d[0] + r[i][1] * d[1] + r[i][2] * d[2];
	/* d.w = -k d_y Y_1^-1 + k d_z Y_1^0 - k d_x Y_1^1 */
	c[0] = 0;
	c[1] = -k * d[1];
	c[2] = k * d[2];
	c[3] = -k * d[0];
	want[0] = 0;
	want[1] = -k * rd[1];
	want[2] = k * rd[2];
	want[3] = -k * rd[0];
	for (int method = 0; method < 2; method++) {
		double a, b, g;

		vx_rot3_to_zyz(r, &a, &b, &g);
		if (method)
			vx_sh_rot_from_zyz(2, a, b, g, rot_a);
		else
			vx_sh_rot_from_matrix(2, r, rot_a);
		vx_sh_rot_apply(2, rot_a, 1, c, cr);
		for (int i = 0; i < 4; i++)
			assert_true(fabs(cr[i] - want[i]) < 1e-14);
	}
	/* f(w) = x, projected: the definition of the phase */
	for (int i = 0; i < 200; i++) {
		double w[3];

		direction(9, (uint64_t)i, w);
		double f = -k * vx_sh_eval_sum(2, (double[4]){ 0, 0, 0, 1 }, w);

		assert_true(fabs(f - w[0]) < 1e-15);
	}
}

/* half_turn: the diagonal element (l, m) of the SH rotation of a half turn
 * about z (ax 0), x (1) or y (2), from the parity of the closed forms:
 * about z (x, y, z) -> (-x, -y, z) multiplies Y_lm by (-1)^m; about x
 * (x, -y, -z) by (-1)^(l+m), and by one more -1 for m < 0 (the sin(m phi)
 * functions are odd in y); about y (-x, y, -z) by (-1)^l, and -1 more for
 * m < 0. */
static int
half_turn(int ax, int l, int m)
{
	int am = m < 0 ? -m : m, neg = m < 0 ? -1 : 1;

	if (ax == 0)
		return am & 1 ? -1 : 1;
	if (ax == 1)
		return ((l + am) & 1 ? -1 : 1) * neg;
	return (l & 1 ? -1 : 1) * neg;
}

/* diag_err: the largest |rot - D| with D diagonal, D(l, m) = d(ax, l, m) */
static double
diag_err(int order, const double *rot, int ax, int (*d)(int, int, int))
{
	double worst = 0;

	for (int l = 0; l < order; l++) {
		const double *b = rot + vx_sh_rot_offset(l);
		int s = 2 * l + 1;

		for (int m = -l; m <= l; m++)
			for (int n = -l; n <= l; n++) {
				double want = m == n ? d(ax, l, m) : 0;

				worst = fmax(worst,
				    fabs(b[(m + l) * s + n + l] - want));
			}
	}
	return worst;
}

static int
one(int ax, int l, int m)
{
	(void)ax;
	(void)l;
	(void)m;
	return 1;
}

/* Special rotations with known matrices: the identity, and half turns
 * about z, x and y (diagonal, half_turn), to 1e-13 at order 16, by both
 * methods.  A half turn about (1, 1, 0) is its own inverse (M M = I) and
 * symmetric.  Gimbal lock: ZYZ(a, 0, g) is the closed-form z turn by a + g
 * (vx_sh_rot_z), ZYZ(a, 180, g) is Z(a) Y(180) Z(g). */
static void
special_rotations(void **state)
{
	static const double axes[3][3] = { { 0, 0, 1 }, { 1, 0, 0 },
	    { 0, 1, 0 } };
	double r[3][3], c[256], g[256], h[256];

	(void)state;
	vx_rot3_zyz(0, 0, 0, r);
	vx_sh_rot_from_matrix(16, r, rot_a);
	assert_true(diag_err(16, rot_a, 0, one) < 1e-13);
	vx_sh_rot_from_zyz(16, 0, 0, 0, rot_a);
	assert_true(diag_err(16, rot_a, 0, one) < 1e-13);
	for (int ax = 0; ax < 3; ax++) {
		double a, be, ga, e0, e1;

		vx_rot3_axis(axes[ax], PI, r);
		vx_rot3_to_zyz(r, &a, &be, &ga);
		vx_sh_rot_from_axis(16, axes[ax], PI, rot_a);
		vx_sh_rot_from_zyz(16, a, be, ga, rot_b);
		e0 = diag_err(16, rot_a, ax, half_turn);
		e1 = diag_err(16, rot_b, ax, half_turn);
		if (!(e0 < 1e-13 && e1 < 1e-13))
			fail_msg("half turn about axis %d: %.3g %.3g", ax, e0,
			    e1);
	}
	vx_sh_rot_from_axis(16, (double[3]){ 1, 1, 0 }, PI, rot_a);
	compose(16, rot_a, rot_a, rot_b);
	assert_true(diag_err(16, rot_b, 0, one) < 1e-13);
	for (int l = 0; l < 16; l++) {
		const double *b = rot_a + vx_sh_rot_offset(l);
		int s = 2 * l + 1;

		for (int i = 0; i < s; i++)
			for (int j = 0; j < s; j++)
				assert_true(fabs(b[i * s + j] - b[j * s + i]) <
				    1e-13);
	}
	/* gimbal lock */
	for (int i = 0; i < 256; i++)
		c[i] = sin(0.37 * i);
	vx_sh_rot_from_zyz(16, RAD(30), 0, RAD(40), rot_a);
	vx_sh_rot_apply(16, rot_a, 1, c, g);
	vx_sh_rot_z(16, RAD(70), 1, c, h);
	for (int i = 0; i < 256; i++)
		assert_true(fabs(g[i] - h[i]) < 1e-13);
	vx_sh_rot_from_zyz(16, RAD(30), PI, RAD(40), rot_a);
	vx_sh_rot_apply(16, rot_a, 1, c, g);
	vx_sh_rot_z(16, RAD(40), 1, c, h);
	for (int l = 0; l < 16; l++)
		for (int m = -l; m <= l; m++)
			h[vx_sh_index(l, m)] *= half_turn(2, l, m);
	vx_sh_rot_z(16, RAD(30), 1, h, h);
	for (int i = 0; i < 256; i++)
		assert_true(fabs(g[i] - h[i]) < 1e-13);
}

/* 3x3 rotations: ZYZ angles back from the matrix rebuild it (1e-12), at
 * the hard cases (gimbal lock included), at random rotations, and within
 * 1e-12 of gimbal lock with noise of 1e-16 on the entries that carry
 * sin beta (where alpha is a ratio of noise); beta lies in [0, pi].  Rodrigues agrees with the ZYZ form about z, and turns x
 * into y about z, y into z about x. */
static void
rot3(void **state)
{
	double r[3][3], q[3][3];

	(void)state;
	for (size_t k = 0; k < NCASE + 16; k++) {
		double a, b, g, worst = 0;

		if (k < NCASE)
			vx_rot3_zyz(RAD(cases[k][0]), RAD(cases[k][1]),
			    RAD(cases[k][2]), r);
		else
			random_rotation(500 + k, r);
		vx_rot3_to_zyz(r, &a, &b, &g);
		assert_true(b >= 0 && b <= PI);
		vx_rot3_zyz(a, b, g, q);
		for (int i = 0; i < 3; i++)
			for (int j = 0; j < 3; j++)
				worst = fmax(worst, fabs(q[i][j] - r[i][j]));
		if (!(worst < 1e-12))
			fail_msg("case %zu: %.3g", k, worst);
	}
	/* near gimbal lock, with rounding noise where sin beta lives: the
	 * angles still rebuild the matrix */
	for (int k = 0; k < 4; k++) {
		double a, b, g, worst = 0;

		vx_rot3_zyz(0.3, k < 2 ? 1e-12 : PI - 1e-12, 0.5, r);
		r[0][2] += k & 1 ? 1e-16 : -2e-16;
		r[1][2] -= 1e-16;
		vx_rot3_to_zyz(r, &a, &b, &g);
		vx_rot3_zyz(a, b, g, q);
		for (int i = 0; i < 3; i++)
			for (int j = 0; j < 3; j++)
				worst = fmax(worst, fabs(q[i][j] - r[i][j]));
		if (!(worst < 1e-12))
			fail_msg("near gimbal lock %d: %.3g", k, worst);
	}
	vx_rot3_axis((double[3]){ 0, 0, 2 }, 0.8, r);
	vx_rot3_zyz(0.8, 0, 0, q);
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			assert_true(fabs(q[i][j] - r[i][j]) < 1e-15);
	vx_rot3_axis((double[3]){ 0, 0, 1 }, PI / 2, r);
	assert_true(fabs(r[1][0] - 1) < 1e-15);	/* x -> y */
	vx_rot3_axis((double[3]){ 1, 0, 0 }, PI / 2, r);
	assert_true(fabs(r[2][1] - 1) < 1e-15);	/* y -> z */
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(closed_forms),
		cmocka_unit_test(addition_theorem),
		cmocka_unit_test(orthonormal),
		cmocka_unit_test(projection),
		cmocka_unit_test(phase),
		cmocka_unit_test(cosine_bands),
		cmocka_unit_test(sky_irradiance),
		cmocka_unit_test(irradiance),
		cmocka_unit_test(ir_equals_zyz),
		cmocka_unit_test(ir_is_definition),
		cmocka_unit_test(composition),
		cmocka_unit_test(rotated_evaluation),
		cmocka_unit_test(band_one),
		cmocka_unit_test(special_rotations),
		cmocka_unit_test(rot3),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
