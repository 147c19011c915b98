/* helper_ray.h: ray helpers shared by the unit tests (helper_ray.c). */
#ifndef HELPER_RAY_H
#define HELPER_RAY_H

#include "vx_grid.h"

/* grid_segment: the part t >= 0 of the ray o + t d inside g's sample box
 * [0, dims - 1] per axis (a zero component: inside or not along that axis),
 * in [*ta, *tb]; returns 0 when the ray misses the box (*ta > *tb). */
int grid_segment(const vx_grid *g, const double o[3], const double d[3],
    double *ta, double *tb);

#endif
