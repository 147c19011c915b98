/* shrot.c: rotations of the sphere and of SH coefficients: Ivanic and
 * Ruedenberg's recurrence, and the ZYZ product as its independent check
 * (see vx_sh.h). */
#include "vx_sh.h"

#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846
#define SIDE_MAX (2 * VX_SH_MAX_ORDER - 1)

/* element (m, n) of band l's block b (rows and columns -l .. l) */
#define EL(b, l, m, n) ((b)[((m) + (l)) * (2 * (l) + 1) + (n) + (l)])

/* ---- 3x3 rotations ---- */

static void
mul3(const double a[3][3], const double b[3][3], double c[3][3])
{
	double t[3][3];

	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			t[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] +
			    a[i][2] * b[2][j];
	memcpy(c, t, sizeof t);
}

void
vx_rot3_zyz(double alpha, double beta, double gamma, double r[3][3])
{
	double ca = cos(alpha), sa = sin(alpha), cb = cos(beta),
	    sb = sin(beta), cg = cos(gamma), sg = sin(gamma);
	double za[3][3] = { { ca, -sa, 0 }, { sa, ca, 0 }, { 0, 0, 1 } };
	double yb[3][3] = { { cb, 0, sb }, { 0, 1, 0 }, { -sb, 0, cb } };
	double zg[3][3] = { { cg, -sg, 0 }, { sg, cg, 0 }, { 0, 0, 1 } };

	mul3(yb, zg, r);
	mul3(za, r, r);
}

void
vx_rot3_axis(const double axis[3], double angle, double r[3][3])
{
	double l = sqrt(axis[0] * axis[0] + axis[1] * axis[1] +
	    axis[2] * axis[2]);
	double x, y, z, c = cos(angle), s = sin(angle), t = 1 - c;

	if (!(l > 0)) {
		static const double id[3][3] = { { 1, 0, 0 }, { 0, 1, 0 },
		    { 0, 0, 1 } };

		memcpy(r, id, sizeof id);
		return;
	}
	x = axis[0] / l;
	y = axis[1] / l;
	z = axis[2] / l;
	/* Rodrigues: c I + s [k]x + (1 - c) k k^T */
	r[0][0] = c + t * x * x;
	r[0][1] = t * x * y - s * z;
	r[0][2] = t * x * z + s * y;
	r[1][0] = t * x * y + s * z;
	r[1][1] = c + t * y * y;
	r[1][2] = t * y * z - s * x;
	r[2][0] = t * x * z - s * y;
	r[2][1] = t * y * z + s * x;
	r[2][2] = c + t * z * z;
}

void
vx_rot3_to_zyz(const double r[3][3], double *alpha, double *beta,
    double *gamma)
{
	/* r = Rz(a) Ry(b) Rz(g): r22 = cos b, (r02, r12) = sin b (cos a,
	 * sin a).  Near gimbal lock a is ill-determined (a ratio of tiny
	 * numbers), so g is not taken from r's third row but from
	 * Rz(-a) r = Ry(b) Rz(g), whose second row is (sin g, cos g, 0)
	 * whatever b: the three angles then rebuild r to rounding even where
	 * a itself is arbitrary. */
	double sb = hypot(r[0][2], r[1][2]), ca, sa;

	*beta = atan2(sb, r[2][2]);
	*alpha = sb > 0 ? atan2(r[1][2], r[0][2]) : 0;
	ca = cos(*alpha);
	sa = sin(*alpha);
	*gamma = atan2(ca * r[1][0] - sa * r[0][0],
	    ca * r[1][1] - sa * r[0][1]);
}

/* ---- Ivanic and Ruedenberg ----
 *
 * In the basis without the Condon-Shortley phase, band 1's functions are
 * (y, z, x) times sqrt(3 / (4 pi)) for m = -1, 0, 1, so band 1's matrix is
 * r with rows and columns reordered (y, z, x): R1(m, n) = r[ax(m)][ax(n)].
 * Band l follows from band l-1 (Rp) and band 1 by
 *
 *   R(m, n) = u U + v V + w W
 *
 *   d   = (l + n)(l - n) for |n| < l,  2l (2l - 1) for |n| = l
 *   u   = sqrt((l + m)(l - m) / d)
 *   v   = 1/2 sqrt((1 + [m = 0]) (l + |m| - 1)(l + |m|) / d) (1 - 2 [m = 0])
 *   w   = -1/2 sqrt((l - |m| - 1)(l - |m|) / d) (1 - [m = 0])
 *
 *   P(i, a, n) = R1(i, 0) Rp(a, n)                              |n| < l
 *                R1(i, 1) Rp(a, l-1) - R1(i, -1) Rp(a, -l+1)     n = l
 *                R1(i, 1) Rp(a, -l+1) + R1(i, -1) Rp(a, l-1)     n = -l
 *   U = P(0, m, n)
 *   V = P(1, 1, n) + P(-1, -1, n)                                m = 0
 *       P(1, m-1, n) sqrt(1 + [m = 1]) - P(-1, -m+1, n) (1 - [m = 1])   m > 0
 *       P(1, m+1, n) (1 - [m = -1]) + P(-1, -m-1, n) sqrt(1 + [m = -1]) m < 0
 *   W = P(1, m+1, n) + P(-1, -m-1, n)                            m > 0
 *       P(1, m-1, n) - P(-1, -m+1, n)                            m < 0
 *
 * These are the 1996 paper's equations with the 1998 corrections, and with
 * the one place where implementers of the corrections found them wrong put
 * right: V for m = -1 takes sqrt(1 + [m = -1]) = sqrt(2) on P(-1, 0, n)
 * (with 1 - [m = -1] that term vanishes and the matrices are not
 * orthogonal).  Table 3 of Wyman et al. 2006, as our copy of the paper
 * reads (the PDF conversion garbled it), has P(-1, -m+1, n) in V for m < 0
 * and a + in W for m < 0: each of the two gives matrices that are not
 * rotations (W's only from l = 3 on, where w first is nonzero for m < 0).
 * test_sh.c checks every element against the definition (eq. 16, by exact
 * quadrature) and against the ZYZ product to 1e-12.
 *
 * Where a coefficient is zero its term is skipped, not evaluated: u = 0 at
 * |m| = l, where U would read Rp(+-l, n), outside band l-1; w = 0 at
 * |m| >= l - 1, where W would read Rp(+-l, n). */

static int
ax(int m)	/* the Cartesian axis of band-1 index m: y, z, x */
{
	return m == -1 ? 1 : m == 0 ? 2 : 0;
}

static double
irP(int i, int l, int a, int n, const double *r1, const double *rp)
{
	if (n == l)
		return EL(r1, 1, i, 1) * EL(rp, l - 1, a, l - 1) -
		    EL(r1, 1, i, -1) * EL(rp, l - 1, a, -l + 1);
	if (n == -l)
		return EL(r1, 1, i, 1) * EL(rp, l - 1, a, -l + 1) +
		    EL(r1, 1, i, -1) * EL(rp, l - 1, a, l - 1);
	return EL(r1, 1, i, 0) * EL(rp, l - 1, a, n);
}

static double
irElement(int l, int m, int n, const double *r1, const double *rp)
{
	int am = m < 0 ? -m : m;
	double d = n == l || n == -l ? 2.0 * l * (2 * l - 1) :
	    (double)(l + n) * (l - n);
	double u = sqrt((double)(l + m) * (l - m) / d);
	double v = 0.5 * sqrt((m == 0 ? 2.0 : 1.0) * (l + am - 1) *
	    (l + am) / d) * (m == 0 ? -1 : 1);
	double w = m == 0 ? 0 : -0.5 * sqrt((double)(l - am - 1) *
	    (l - am) / d);
	double s = 0, V;

	if (u != 0)
		s += u * irP(0, l, m, n, r1, rp);
	if (m == 0)
		V = irP(1, l, 1, n, r1, rp) + irP(-1, l, -1, n, r1, rp);
	else if (m > 0)
		V = m == 1 ? irP(1, l, 0, n, r1, rp) * sqrt(2.0) :
		    irP(1, l, m - 1, n, r1, rp) - irP(-1, l, -m + 1, n, r1, rp);
	else
		V = m == -1 ? irP(-1, l, 0, n, r1, rp) * sqrt(2.0) :
		    irP(1, l, m + 1, n, r1, rp) + irP(-1, l, -m - 1, n, r1, rp);
	s += v * V;
	if (w != 0) {
		if (m > 0)
			s += w * (irP(1, l, m + 1, n, r1, rp) +
			    irP(-1, l, -m - 1, n, r1, rp));
		else
			s += w * (irP(1, l, m - 1, n, r1, rp) -
			    irP(-1, l, -m + 1, n, r1, rp));
	}
	return s;
}

void
vx_sh_rot_from_matrix(int order, const double r[3][3], double *rot)
{
	rot[0] = 1;
	if (order < 2)
		return;
	double *r1 = rot + vx_sh_rot_offset(1);

	for (int m = -1; m <= 1; m++)
		for (int n = -1; n <= 1; n++)
			EL(r1, 1, m, n) = r[ax(m)][ax(n)];
	for (int l = 2; l < order; l++) {
		double *b = rot + vx_sh_rot_offset(l);
		const double *rp = rot + vx_sh_rot_offset(l - 1);

		for (int m = -l; m <= l; m++)
			for (int n = -l; n <= l; n++)
				EL(b, l, m, n) = irElement(l, m, n, r1, rp);
	}
	/* to the basis with the phase: Y = (-1)^m Y', so element (m, n)
	 * takes (-1)^(m + n) */
	for (int l = 1; l < order; l++) {
		double *b = rot + vx_sh_rot_offset(l);

		for (int m = -l; m <= l; m++)
			for (int n = -l; n <= l; n++)
				if ((m + n) & 1)
					EL(b, l, m, n) = -EL(b, l, m, n);
	}
}

void
vx_sh_rot_from_axis(int order, const double axis[3], double angle,
    double *rot)
{
	double r[3][3];

	vx_rot3_axis(axis, angle, r);
	vx_sh_rot_from_matrix(order, r, rot);
}

/* ---- rotations about z, closed form ----
 * Turning f by alpha about z shifts phi by alpha: on the pair (m, -m), m > 0,
 *   g_m = cos(m alpha) f_m - sin(m alpha) f_-m
 *   g_-m = sin(m alpha) f_m + cos(m alpha) f_-m
 * (the Condon-Shortley phase is the same on both, so it does not enter). */

/* zleft: band block b (side 2l+1) <- Z(alpha) b (mixes rows m, -m) */
static void
zleft(int l, double alpha, double *b)
{
	for (int m = 1; m <= l; m++) {
		double c = cos(m * alpha), s = sin(m * alpha);

		for (int n = -l; n <= l; n++) {
			double p = EL(b, l, m, n), q = EL(b, l, -m, n);

			EL(b, l, m, n) = c * p - s * q;
			EL(b, l, -m, n) = s * p + c * q;
		}
	}
}

/* zright: b <- b Z(alpha) (mixes columns n, -n) */
static void
zright(int l, double alpha, double *b)
{
	for (int n = 1; n <= l; n++) {
		double c = cos(n * alpha), s = sin(n * alpha);

		for (int m = -l; m <= l; m++) {
			double p = EL(b, l, m, n), q = EL(b, l, m, -n);

			EL(b, l, m, n) = c * p + s * q;
			EL(b, l, m, -n) = -s * p + c * q;
		}
	}
}

void
vx_sh_rot_z(int order, double alpha, int nchan, const double *in,
    double *out)
{
	int nc = order * order;

	for (int k = 0; k < nchan; k++, in += nc, out += nc) {
		for (int l = 0; l < order; l++)
			out[vx_sh_index(l, 0)] = in[vx_sh_index(l, 0)];
		for (int m = 1; m < order; m++) {
			double c = cos(m * alpha), s = sin(m * alpha);

			for (int l = m; l < order; l++) {
				double p = in[vx_sh_index(l, m)];
				double q = in[vx_sh_index(l, -m)];

				out[vx_sh_index(l, m)] = c * p - s * q;
				out[vx_sh_index(l, -m)] = s * p + c * q;
			}
		}
	}
}

/* x90: band blocks of the SH rotation of Rx(+90 deg), w -> (x, -z, y),
 * from eq. 16 by the product rule of nz = order Gauss-Legendre nodes in z
 * and 2 order angles in phi, exact for the products Y_s(r w) Y_t(w) (degree
 * <= 2 order - 2 on the sphere). */
static void
x90(int order, double *rot)
{
	double z[VX_SH_MAX_ORDER], wt[VX_SH_MAX_ORDER];
	double ya[VX_SH_MAX_COEF], yb[VX_SH_MAX_COEF];
	int nphi = 2 * order;

	memset(rot, 0, sizeof *rot * vx_sh_rot_size(order));
	vx_sh_gauss_legendre(order, z, wt);
	for (int i = 0; i < order; i++) {
		double s = sqrt(fmax(0.0, 1 - z[i] * z[i]));

		for (int j = 0; j < nphi; j++) {
			double phi = 2 * PI * (j + 0.5) / nphi;
			double w[3] = { s * cos(phi), s * sin(phi), z[i] };
			double rw[3] = { w[0], -w[2], w[1] };
			double q = wt[i] * (2 * PI / nphi);

			vx_sh_eval(order, w, ya);
			vx_sh_eval(order, rw, yb);
			for (int l = 0; l < order; l++) {
				double *b = rot + vx_sh_rot_offset(l);
				const double *a = ya + l * l + l;
				const double *c = yb + l * l + l;

				for (int m = -l; m <= l; m++) {
					double f = q * c[m];

					for (int n = -l; n <= l; n++)
						EL(b, l, m, n) += f * a[n];
				}
			}
		}
	}
}

void
vx_sh_rot_from_zyz(int order, double alpha, double beta, double gamma,
    double *rot)
{
	double x[SIDE_MAX * SIDE_MAX], t[SIDE_MAX * SIDE_MAX];

	x90(order, rot);
	for (int l = 0; l < order; l++) {
		double *b = rot + vx_sh_rot_offset(l);
		int side = 2 * l + 1;

		/* b = Z(alpha) X^T Z(beta) X Z(gamma) */
		memcpy(x, b, sizeof *b * (size_t)(side * side));
		memcpy(t, b, sizeof *b * (size_t)(side * side));
		zright(l, gamma, t);
		zleft(l, beta, t);
		for (int i = 0; i < side; i++)
			for (int j = 0; j < side; j++) {
				double s = 0;

				for (int k = 0; k < side; k++)
					s += x[k * side + i] * t[k * side + j];
				b[i * side + j] = s;
			}
		zleft(l, alpha, b);
	}
}

void
vx_sh_rot_apply(int order, const double *rot, int nchan, const double *in,
    double *out)
{
	double t[SIDE_MAX];
	int nc = order * order;

	for (int k = 0; k < nchan; k++, in += nc, out += nc)
		for (int l = 0; l < order; l++) {
			const double *b = rot + vx_sh_rot_offset(l);
			const double *f = in + l * l;
			int side = 2 * l + 1;

			for (int i = 0; i < side; i++) {
				double s = 0;

				for (int j = 0; j < side; j++)
					s += b[i * side + j] * f[j];
				t[i] = s;
			}
			memcpy(out + l * l, t, sizeof *t * (size_t)side);
		}
}
