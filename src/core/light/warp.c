/* warp.c: warps of the unit square and orthonormal frames (see vx_warp.h). */
#include "vx_warp.h"

#include <math.h>

#define PI 3.14159265358979323846

void
vx_warp_concentric_disk(const double u[2], double d[2])
{
	double a = 2 * u[0] - 1, b = 2 * u[1] - 1, r, phi;

	if (a == 0 && b == 0) {
		d[0] = d[1] = 0;
		return;
	}
	/* the square ring of half-width r maps to the circle of radius r;
	 * the angle runs linearly along each side of the ring */
	if (fabs(a) > fabs(b)) {
		r = a;
		phi = (PI / 4) * (b / a);
	} else {
		r = b;
		phi = PI / 2 - (PI / 4) * (a / b);
	}
	d[0] = r * cos(phi);
	d[1] = r * sin(phi);
}

double
vx_warp_cosine_hemisphere(const double u[2], double w[3])
{
	double d[2];

	vx_warp_concentric_disk(u, d);
	w[0] = d[0];
	w[1] = d[1];
	w[2] = sqrt(fmax(0.0, 1 - d[0] * d[0] - d[1] * d[1]));
	return w[2] / PI;
}

/* at_height: the unit vector w of height z (in [-1, 1]) and azimuth
 * 2 pi v */
static void
at_height(double z, double v, double w[3])
{
	double r = sqrt(fmax(0.0, 1 - z * z)), phi = 2 * PI * v;

	w[0] = r * cos(phi);
	w[1] = r * sin(phi);
	w[2] = z;
}

double
vx_warp_uniform_hemisphere(const double u[2], double w[3])
{
	at_height(1 - u[0], u[1], w);
	return 1 / (2 * PI);
}

double
vx_warp_uniform_sphere(const double u[2], double w[3])
{
	at_height(1 - 2 * u[0], u[1], w);
	return 1 / (4 * PI);
}

double
vx_warp_cosine_hemisphere_pdf(const double w[3])
{
	return w[2] > 0 ? w[2] / PI : 0;
}

double
vx_warp_uniform_hemisphere_pdf(const double w[3])
{
	return w[2] > 0 ? 1 / (2 * PI) : 0;
}

double
vx_warp_uniform_sphere_pdf(const double w[3])
{
	(void)w;
	return 1 / (4 * PI);
}

void
vx_onb(const double n[3], double t[3], double b[3])
{
	double s = copysign(1.0, n[2]);
	double a = -1 / (s + n[2]);
	double c = n[0] * n[1] * a;

	t[0] = 1 + s * n[0] * n[0] * a;
	t[1] = s * c;
	t[2] = -s * n[0];
	b[0] = c;
	b[1] = s + n[1] * n[1] * a;
	b[2] = -n[1];
}

void
vx_onb_to_world(const double n[3], const double t[3], const double b[3],
    const double l[3], double w[3])
{
	double l0 = l[0], l1 = l[1], l2 = l[2];

	for (int i = 0; i < 3; i++)
		w[i] = l0 * t[i] + l1 * b[i] + l2 * n[i];
}
