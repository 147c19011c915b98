/* vx_bspline.h: the uniform cubic B-spline's weights, shared by the
 * smoothed gradient (texel normals, vx_smooth.h) and tricubic lookups
 * (vx_irrvol.h). */
#ifndef VX_BSPLINE_H
#define VX_BSPLINE_H

/* vx_bspline_weights: the four weights of samples floor(u)-1 .. floor(u)+2
 * at fraction t = u - floor(u) in [0, 1], and, when dw is not NULL, their
 * derivatives with respect to u. */
static inline void
vx_bspline_weights(double t, double w[4], double dw[4])
{
	double s = 1 - t, t2 = t * t;

	w[0] = s * s * s / 6;
	w[1] = (3 * t2 * t - 6 * t2 + 4) / 6;
	w[2] = (-3 * t2 * t + 3 * t2 + 3 * t + 1) / 6;
	w[3] = t2 * t / 6;
	if (dw != 0) {
		dw[0] = -s * s / 2;
		dw[1] = 1.5 * t2 - 2 * t;
		dw[2] = -1.5 * t2 + t + 0.5;
		dw[3] = t2 / 2;
	}
}

#endif
