/* vx_smooth.h: the volume smoothed by the cubic B-spline (Wyman et al.
 * 2006, §4.1.1: texel normals from the gradient smoothed over 4x4x4
 * samples).  The smoothed field is sum f[i,j,k] B(x-i) B(y-j) B(z-k) with
 * B the uniform cubic B-spline (support [-2, 2]); at a point it reads the
 * 4x4x4 samples around it (3 along an axis where the point sits on a
 * sample: the fourth has weight 0), indices clamped to the volume (edge
 * samples repeated). */
#ifndef VX_SMOOTH_H
#define VX_SMOOTH_H

#include "vx_grid.h"

enum {
	VX_SMOOTH_NAN    = 1,    /* a sample of the support is not finite:
	                            the gradient is 0 */
	VX_SMOOTH_BORDER = 2     /* the support reached past an edge */
};

/* vx_bspline_gradient: the smoothed field's gradient at index-space point
 * p, in index units (value per sample spacing); returns VX_SMOOTH_* bits. */
int vx_bspline_gradient(const vx_grid *g, const double p[3], double grad[3]);


#endif
