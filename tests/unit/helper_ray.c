/* helper_ray.c: ray helpers shared by the unit tests. */
#include "helper_ray.h"

#include <math.h>

int
grid_segment(const vx_grid *g, const double o[3], const double d[3],
    double *ta, double *tb)
{
	double a0 = 0, a1 = INFINITY;

	for (int a = 0; a < 3; a++) {
		double hi = (double)(g->dims[a] - 1);

		if (d[a] == 0) {
			if (!(o[a] >= 0 && o[a] <= hi))
				return 0;
			continue;
		}
		double t0 = -o[a] / d[a], t1 = (hi - o[a]) / d[a];
		if (t0 > t1) {
			double s = t0;
			t0 = t1;
			t1 = s;
		}
		a0 = t0 > a0 ? t0 : a0;
		a1 = t1 < a1 ? t1 : a1;
	}
	*ta = a0;
	*tb = a1;
	return a0 <= a1;
}
