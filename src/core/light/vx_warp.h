/* vx_warp.h: warps of the unit square [0,1)^2 onto disks, hemispheres and
 * the sphere, their densities, and orthonormal frames.
 *
 * A warp takes u in [0,1)^2 (vx_rng_ld2's or two vx_rng_uniform's) and
 * returns a point whose density, with u uniform, is the pdf it returns: in
 * area for the disk, in solid angle (per steradian) for directions.  Each
 * warp is continuous in u (stratification of u carries over) and costs no
 * rejection.  Directions are unit vectors in a local frame whose z axis is
 * the normal; vx_onb and vx_onb_to_world take them to the world. */
#ifndef VX_WARP_H
#define VX_WARP_H

/* vx_warp_concentric_disk: Shirley and Chiu's map of [0,1)^2 onto the unit
 * disk (concentric squares to concentric circles), area-preserving up to
 * the factor pi: density 1/pi in area.  d[0]^2 + d[1]^2 <= 1. */
void vx_warp_concentric_disk(const double u[2], double d[2]);

/* vx_warp_cosine_hemisphere: Malley's method, a concentric-disk point
 * lifted to the hemisphere z >= 0: density cos(theta)/pi = w[2]/pi in solid
 * angle, which it returns (0 only on the rim). */
double vx_warp_cosine_hemisphere(const double u[2], double w[3]);

/* vx_warp_uniform_hemisphere: z = 1 - u[0] in (0, 1], phi = 2 pi u[1];
 * returns the density 1/(2 pi). */
double vx_warp_uniform_hemisphere(const double u[2], double w[3]);

/* vx_warp_uniform_sphere: z = 1 - 2 u[0] in (-1, 1], phi = 2 pi u[1] (the
 * area-preserving cylinder map); returns the density 1/(4 pi). */
double vx_warp_uniform_sphere(const double u[2], double w[3]);

/* The densities of the warps above at a unit direction w in the local frame
 * (zero outside their domain): for the weights of multiple importance
 * sampling, where a direction comes from another strategy. */
double vx_warp_cosine_hemisphere_pdf(const double w[3]);
double vx_warp_uniform_hemisphere_pdf(const double w[3]);
double vx_warp_uniform_sphere_pdf(const double w[3]);

/* vx_onb: t and b such that (t, b, n) is a right-handed orthonormal basis
 * (t x b = n) around the unit vector n, without branches on a threshold and
 * continuous except across n[2] = 0 (Duff et al. 2017, "Building an
 * orthonormal basis, revisited"; their sign(n.z) variant). */
void vx_onb(const double n[3], double t[3], double b[3]);

/* vx_onb_to_world: w = l[0] t + l[1] b + l[2] n, the local direction l in
 * the world (w may alias l). */
void vx_onb_to_world(const double n[3], const double t[3], const double b[3],
    const double l[3], double w[3]);

#endif
