/* vx_vec.h: small 3-vector helpers in double, inline.  Every renderer,
 * baker and camera uses these rather than its own copy, so that the same
 * expression (and so the same rounding) is used everywhere. */
#ifndef VX_VEC_H
#define VX_VEC_H

#include <math.h>

#define VX_PI 3.14159265358979323846

static inline double
vx_dot3(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* vx_cross3: out = a x b (out may alias a or b). */
static inline void
vx_cross3(const double a[3], const double b[3], double out[3])
{
	double t0 = a[1] * b[2] - a[2] * b[1];
	double t1 = a[2] * b[0] - a[0] * b[2];
	double t2 = a[0] * b[1] - a[1] * b[0];

	out[0] = t0;
	out[1] = t1;
	out[2] = t2;
}

/* vx_unit3: normalize v in place, scaled by its largest component first so
 * tiny and huge vectors neither underflow nor overflow; a zero or
 * non-finite vector is left as it is. */
static inline void
vx_unit3(double v[3])
{
	double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2]))), l;

	if (!(m > 0) || !isfinite(m))
		return;
	v[0] /= m;
	v[1] /= m;
	v[2] /= m;
	l = sqrt(vx_dot3(v, v));
	v[0] /= l;
	v[1] /= l;
	v[2] /= l;
}

static inline int
vx_finite3(const double v[3])
{
	return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

#endif
