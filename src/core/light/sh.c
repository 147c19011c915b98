/* sh.c: real spherical harmonics: evaluation by recurrence, projection,
 * the clamped-cosine convolution (see vx_sh.h; rotations in shrot.c). */
#include "vx_sh.h"

#include <math.h>
#include <pthread.h>
#include <string.h>

#include "vx_rng.h"
#include "vx_warp.h"

#define PI 3.14159265358979323846
#define SQRT2 1.41421356237309504880
#define L_MAX (VX_SH_MAX_ORDER - 1)

/* The fully normalized associated Legendre functions divided by sin^m:
 * Q_l^m(z) = N_l^m P_l^m(z) / sin^m theta, a polynomial in z, obeys
 *   Q_0^0 = 1 / sqrt(4 pi)
 *   Q_m^m = -sqrt((2m + 1) / (2m)) Q_{m-1}^{m-1}    (the - is (-1)^m's)
 *   Q_l^m = a_lm (z Q_{l-1}^m - Q_{l-2}^m / a_{l-1,m})    l > m
 *   a_lm  = sqrt((4 l^2 - 1) / (l^2 - m^2))
 * (a_{m+1,m} = sqrt(2m + 3), and the Q_{m-1}^m term is 0).  This is the
 * recurrence whose terms stay of the size of the result, stable to far
 * beyond L_MAX; the products with sin^m cos(m phi) and sin^m sin(m phi) are
 * the real and imaginary parts of (x + i y)^m. */
static double tab_a[VX_SH_MAX_ORDER][VX_SH_MAX_ORDER];	/* [l][m], l > m */
static double tab_inva[VX_SH_MAX_ORDER][VX_SH_MAX_ORDER];	/* 1 / a_lm */
static double tab_diag[VX_SH_MAX_ORDER];	/* Q_m^m / Q_{m-1}^{m-1} */
static pthread_once_t tab_once = PTHREAD_ONCE_INIT;

static void
tab_init(void)
{
	for (int m = 0; m <= L_MAX; m++) {
		tab_diag[m] = m ? -sqrt((2.0 * m + 1) / (2.0 * m)) : 0;
		for (int l = m + 1; l <= L_MAX; l++) {
			double a = sqrt((4.0 * l * l - 1) /
			    ((double)l * l - (double)m * m));

			tab_a[l][m] = a;
			tab_inva[l][m] = 1 / a;
		}
	}
}

void
vx_sh_eval(int order, const double w[3], double *y)
{
	const double x = w[0], yy = w[1], z = w[2];
	/* p1[m] = Q_{l-1}^m, p2[m] = Q_{l-2}^m as band l is made */
	double p1[VX_SH_MAX_ORDER], p2[VX_SH_MAX_ORDER];
	double cs[VX_SH_MAX_ORDER], sn[VX_SH_MAX_ORDER], qd[VX_SH_MAX_ORDER];
	double cm = 1, sm = 0;
	int lmax = order - 1;

	pthread_once(&tab_once, tab_init);
	/* the diagonal Q_m^m and sqrt(2) (x + i y)^m */
	qd[0] = 0.28209479177387814347;	/* 1 / sqrt(4 pi) */
	for (int m = 1; m <= lmax; m++) {
		double t = cm * x - sm * yy;

		sm = cm * yy + sm * x;
		cm = t;
		cs[m] = SQRT2 * cm;
		sn[m] = SQRT2 * sm;
		qd[m] = qd[m - 1] * tab_diag[m];
	}
	/* band by band, so that the recurrences of different m (each a chain
	 * of dependent steps) run side by side */
	y[0] = p1[0] = qd[0];
	for (int l = 1; l <= lmax; l++) {
		const double *a = tab_a[l], *ia = tab_inva[l - 1];
		double *yl = y + l * l + l;

		for (int m = 0; m < l - 1; m++) {
			double q = a[m] * (z * p1[m] - p2[m] * ia[m]);

			p2[m] = p1[m];
			p1[m] = q;
		}
		p2[l - 1] = p1[l - 1];
		p1[l - 1] = a[l - 1] * z * p1[l - 1];
		p1[l] = qd[l];
		yl[0] = p1[0];
		for (int m = 1; m <= l; m++) {
			yl[m] = p1[m] * cs[m];
			yl[-m] = p1[m] * sn[m];
		}
	}
}

double
vx_sh_eval_sum(int order, const double *c, const double w[3])
{
	double y[VX_SH_MAX_COEF], s = 0;

	vx_sh_eval(order, w, y);
	for (int i = 0; i < order * order; i++)
		s += c[i] * y[i];
	return s;
}

void
vx_sh_flip_phase(int order, int nchan, double *c)
{
	for (int k = 0; k < nchan; k++, c += order * order)
		for (int l = 1; l < order; l++)
			for (int m = 1; m <= l; m += 2) {
				c[vx_sh_index(l, m)] = -c[vx_sh_index(l, m)];
				c[vx_sh_index(l, -m)] = -c[vx_sh_index(l, -m)];
			}
}

void
vx_sh_accumulate(int order, const double w[3], double weight,
    const double *val, int nchan, double *c)
{
	double y[VX_SH_MAX_COEF];
	int n = order * order;

	vx_sh_eval(order, w, y);
	for (int k = 0; k < nchan; k++, c += n) {
		double f = weight * val[k];

		for (int i = 0; i < n; i++)
			c[i] += f * y[i];
	}
}

void
vx_sh_project_samples(int order, size_t n, const double *w,
    const double *pdf, const double *val, int nchan, double *c)
{
	memset(c, 0, sizeof *c * (size_t)(order * order) * (size_t)nchan);
	for (size_t s = 0; s < n; s++)
		vx_sh_accumulate(order, w + 3 * s, 1 / ((double)n * pdf[s]),
		    val + s * (size_t)nchan, nchan, c);
}

void
vx_sh_project_mc(int order, vx_sh_fn f, void *user, int nchan,
    uint64_t nsample, uint64_t seed, uint64_t stream, uint32_t dim,
    double *c)
{
	double val[VX_SH_MAX_CHAN];

	memset(c, 0, sizeof *c * (size_t)(order * order) * (size_t)nchan);
	for (uint64_t i = 0; i < nsample; i++) {
		double u[2], w[3];

		vx_rng_ld2(seed, stream, i, dim, u);
		double pdf = vx_warp_uniform_sphere(u, w);

		f(w, user, val);
		vx_sh_accumulate(order, w, 1 / ((double)nsample * pdf), val,
		    nchan, c);
	}
}

/* legendre: P_n(r) and P_n'(r) (|r| < 1) by Bonnet's recurrence. */
static void
legendre(int n, double r, double *p, double *dp)
{
	double p0 = 1, p1 = r;

	for (int k = 2; k <= n; k++) {
		double p2 = ((2 * k - 1) * r * p1 - (k - 1) * p0) / k;

		p0 = p1;
		p1 = p2;
	}
	*p = p1;
	*dp = n * (r * p1 - p0) / (r * r - 1);
}

void
vx_sh_gauss_legendre(int n, double *x, double *wt)
{
	/* the roots of P_n, symmetric about 0: Newton's iteration from
	 * Tricomi's first guess for the upper half, mirrored; the weight from
	 * the derivative at the converged root */
	for (int i = 0; i < (n + 1) / 2; i++) {
		double r = cos(PI * (i + 0.75) / (n + 0.5)), p, dp, d;

		for (int it = 0; it < 100; it++) {
			legendre(n, r, &p, &dp);
			d = p / dp;
			r -= d;
			if (fabs(d) <= 2e-16)
				break;
		}
		legendre(n, r, &p, &dp);
		if (2 * i + 1 == n)
			r = 0;
		x[n - 1 - i] = r;
		x[i] = -r;
		wt[i] = wt[n - 1 - i] = 2 / ((1 - r * r) * dp * dp);
	}
}

void
vx_sh_project_gauss(int order, int nz, vx_sh_fn f, void *user, int nchan,
    double *c)
{
	double x[VX_SH_GAUSS_MAX], wt[VX_SH_GAUSS_MAX], val[VX_SH_MAX_CHAN];
	int nphi = 2 * nz;

	memset(c, 0, sizeof *c * (size_t)(order * order) * (size_t)nchan);
	vx_sh_gauss_legendre(nz, x, wt);
	for (int i = 0; i < nz; i++) {
		double s = sqrt(fmax(0.0, 1 - x[i] * x[i]));

		for (int j = 0; j < nphi; j++) {
			double phi = 2 * PI * (j + 0.5) / nphi;
			double w[3] = { s * cos(phi), s * sin(phi), x[i] };

			f(w, user, val);
			vx_sh_accumulate(order, w, wt[i] * (2 * PI / nphi), val,
			    nchan, c);
		}
	}
}

double
vx_sh_cosine_band(int l)
{
	double c = 1;

	if (l == 0)
		return PI;
	if (l == 1)
		return 2 * PI / 3;
	if (l % 2)
		return 0;
	/* l! / (2^l ((l/2)!)^2) = binomial(l, l/2) / 2^l, as a product */
	for (int k = 1; k <= l / 2; k++)
		c *= (2.0 * k - 1) / (2.0 * k);
	return 2 * PI * ((l / 2) % 2 ? 1 : -1) / ((l + 2.0) * (l - 1.0)) * c;
}

void
vx_sh_convolve_cosine(int order, int nchan, const double *in, double *out)
{
	for (int l = 0; l < order; l++) {
		double a = vx_sh_cosine_band(l);

		for (int k = 0; k < nchan; k++)
			for (int m = -l; m <= l; m++) {
				size_t i = (size_t)k * (size_t)(order * order) +
				    (size_t)vx_sh_index(l, m);

				out[i] = a * in[i];
			}
	}
}

void
vx_sh_irradiance(int order, int nchan, const double *c, const double n[3],
    double *e)
{
	double y[VX_SH_MAX_COEF];

	vx_sh_eval(order, n, y);
	for (int l = 0; l < order; l++) {
		double a = vx_sh_cosine_band(l);

		for (int m = -l; m <= l; m++)
			y[vx_sh_index(l, m)] *= a;
	}
	for (int k = 0; k < nchan; k++) {
		const double *ck = c + (size_t)k * (size_t)(order * order);
		double s = 0;

		for (int i = 0; i < order * order; i++)
			s += ck[i] * y[i];
		e[k] = s;
	}
}
