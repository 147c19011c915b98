/* smooth.c: the B-spline-smoothed gradient (vx_smooth.h). */
#include "vx_smooth.h"
#include "vx_bspline.h"

#include <math.h>

int
vx_bspline_gradient(const vx_grid *g, const double p[3], double grad[3])
{
	double w[3][4], dw[3][4];
	int64_t idx[3][4];
	int flags = 0, nk[3];

	for (int a = 0; a < 3; a++) {
		double u = p[a], fl;

		if (!(u > 0))
			u = 0;
		if (u > (double)(g->dims[a] - 1))
			u = (double)(g->dims[a] - 1);
		fl = floor(u);
		vx_bspline_weights(u - fl, w[a], dw[a]);
		/* at a sample (t = 0) the fourth weight and its derivative are
		 * 0: that sample is not in the support */
		nk[a] = u - fl > 0 ? 4 : 3;
		for (int k = 0; k < nk[a]; k++) {
			int64_t i = (int64_t)fl - 1 + k;

			if (i < 0 || i > g->dims[a] - 1) {
				flags |= VX_SMOOTH_BORDER;
				i = i < 0 ? 0 : g->dims[a] - 1;
			}
			idx[a][k] = i;
		}
	}
	grad[0] = grad[1] = grad[2] = 0;
	for (int z = 0; z < nk[2]; z++)
		for (int y = 0; y < nk[1]; y++) {
			double gx = 0, gy = 0, gz = 0;

			for (int x = 0; x < nk[0]; x++) {
				double f = vx_grid_get(g, idx[0][x], idx[1][y],
				    idx[2][z]);

				if (!isfinite(f)) {
					grad[0] = grad[1] = grad[2] = 0;
					return flags | VX_SMOOTH_NAN;
				}
				gx += dw[0][x] * f;
				gy += w[0][x] * f;
			}
			gz = gy;
			grad[0] += gx * w[1][y] * w[2][z];
			grad[1] += gy * dw[1][y] * w[2][z];
			grad[2] += gz * w[1][y] * dw[2][z];
		}
	return flags;
}
