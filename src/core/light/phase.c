/* phase.c: phase functions (vx_phase.h). */
#include <math.h>

#include "vx_phase.h"

#define FOUR_PI 12.566370614359172954

double
vx_phase_iso(void)
{
	return 1 / FOUR_PI;
}

double
vx_phase_hg(double g, double c)
{
	double d;

	if (c > 1)
		c = 1;
	if (c < -1)
		c = -1;
	d = 1 + g * g - 2 * g * c;
	return (1 - g * g) / (FOUR_PI * d * sqrt(d));
}

/* frame: two unit vectors a, b with (a, b, w) orthonormal and
 * right-handed (Duff et al. 2017's branchless construction). */
static void
frame(const double w[3], double a[3], double b[3])
{
	double s = copysign(1.0, w[2]);
	double p = -1 / (s + w[2]);
	double q = w[0] * w[1] * p;

	a[0] = 1 + s * w[0] * w[0] * p;
	a[1] = s * q;
	a[2] = -s * w[0];
	b[0] = q;
	b[1] = s + w[1] * w[1] * p;
	b[2] = -w[1];
}

double
vx_phase_hg_sample(double g, const double w_in[3], double u1, double u2,
    double w_out[3])
{
	double c, s, phi, a[3], b[3];

	if (fabs(g) < 1e-3)
		c = 1 - 2 * u1;
	else {
		double t = (1 - g * g) / (1 - g + 2 * g * u1);

		c = (1 + g * g - t * t) / (2 * g);
	}
	if (c > 1)
		c = 1;
	if (c < -1)
		c = -1;
	s = sqrt(fmax(0, 1 - c * c));
	phi = 2 * M_PI * u2;
	frame(w_in, a, b);
	for (int k = 0; k < 3; k++)
		w_out[k] = s * cos(phi) * a[k] + s * sin(phi) * b[k] +
		    c * w_in[k];
	return vx_phase_hg_pdf(g, w_in, w_out);
}

double
vx_phase_hg_pdf(double g, const double w_in[3], const double w_out[3])
{
	return vx_phase_hg(g, w_in[0] * w_out[0] + w_in[1] * w_out[1] +
	    w_in[2] * w_out[2]);
}

void
vx_phase_table_hg(vx_phase_table *t, double g)
{
	for (int i = 0; i < VX_PHASE_TABLE_N; i++)
		t->v[i] = (float)(FOUR_PI * vx_phase_hg(g,
		    2.0 * i / (VX_PHASE_TABLE_N - 1) - 1));
}

