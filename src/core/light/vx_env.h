/* vx_env.h: environment lights: an HDR image around the scene, in the
 * lat-long or Debevec's angular (light-probe) layout, or a constant sky.
 *
 * formats/scene.md (section "Environment maps") is the normative statement
 * of the orientation; in short, with voxlux's world +z up:
 *
 *   lat-long: image point (x, y) in [0, w] x [0, h] (pixel (i, j) covers
 *     [i, i+1) x [j, j+1), y down from the top row), s = x / w, t = y / h:
 *     theta = pi t (from +z), phi = pi - 2 pi s (from +x towards +y),
 *     d = (sin theta cos phi, sin theta sin phi, cos theta).
 *     The top row is +z, the centre column +x, s = 1/4 is +y, s = 3/4 -y,
 *     the left and right edges -x: Blender's (Cycles') mapping.
 *   angular (square): a = 2 x / w - 1, b = 1 - 2 y / h, r = sqrt(a^2 + b^2)
 *     <= 1: d = (cos pi r, -(a / r) sin pi r, (b / r) sin pi r): the centre
 *     is +x, image right -y, image up +z, the disc's rim -x.
 *
 * A light's rotation (degrees rx, ry, rz) turns the map: a map direction d
 * is the world direction R d, R = Rz(rz) Ry(ry) Rx(rx) (right-handed, about
 * the world axes, x first).  Its radiance is color * intensity times the
 * map's linear RGB.
 *
 * Pixels: negative values are set to 0 when a map is made, and counted
 * (lossy codecs such as OpenEXR's DWA leave small negative values); NaN or
 * infinite values make the map an error.  Each pixel has an exact solid
 * angle: lat-long rows (4 pi / w) sin(pi (j + 1/2) / h) sin(pi / (2 h)), the
 * closed form of the row's theta band; angular pixels the integral of the
 * map's Jacobian pi sin(pi r) / r over the pixel's part of the disc, as a
 * boundary integral (8-point Gauss-Legendre on straight edges, closed form on
 * the disc's rim; to rounding, about 1e-14 absolute): 0 outside the disc.
 *
 * Importance sampling is piecewise constant over the pixels: a pixel with
 * probability proportional to its luminance (Rec. 709, of the scaled
 * radiance) times its solid angle (the solid angle alone when the map is
 * black), by a marginal CDF over rows and a conditional CDF in the row; then
 * a point in the pixel: uniform in solid angle (lat-long: uniform in phi and
 * cos theta), or uniform in image area (angular; the pdf in solid angle then
 * varies with r).  An angular pixel's corner outside the disc is sampled too
 * and then gives no direction (pdf 0): the estimator stays unbiased.
 *
 * The content hash is FNV-1a (64 bits) over width and height (u32
 * little-endian) and then the pixels' r, g, b as IEEE binary32
 * little-endian, top row first, after the negative values were set to +0:
 * the same pixels give the same hash whatever the file's format. */
#ifndef VX_ENV_H
#define VX_ENV_H

#include <stddef.h>
#include <stdint.h>

#include "vx_err.h"
#include "vx_image.h"
#include "vx_scene.h"

typedef struct vx_env {
	vx_env_layout layout;     /* VX_ENV_LATLONG or VX_ENV_ANGULAR */
	int w, h;
	float *px;                /* w * h * 3: the map's RGB, finite, >= 0,
	                             top row first (scale not applied) */
	uint64_t hash;            /* vx_env_hash of px */
	size_t nclamped;          /* negative values set to 0 */
	double scale[3];          /* radiance = scale * px (color * intensity) */
	double rot[3][3];         /* map direction -> world direction */
	double *omega;            /* solid angles: lat-long one per row (every
	                             pixel of a row has it), angular per pixel */
	double *cdf_row;          /* h + 1: marginal CDF over rows, 0 .. 1 */
	double *cdf_col;          /* h x (w + 1): each row's conditional CDF */
	double total;             /* sum of the sampling weights */
	int uniform;              /* 1: black map, sampled by solid angle */
} vx_env;

/* vx_env_init: env (initialized by this call) gets img's pixels (nc 1 or 3;
 * gray is r = g = b) in the given layout, with scale (NULL: 1 1 1) and
 * rotation in degrees (NULL: none); its hash, solid angles and sampling
 * tables are made.  Errors: VX_EDATA for a NaN or infinite value (naming the
 * pixel), an angular map that is not square, another channel count;
 * VX_ENOMEM.  On error env is empty (vx_env_free accepts it). */
int vx_env_init(vx_env *env, const vx_image *img, vx_env_layout layout,
    const double scale[3], const double rotation[3], vx_err *e);

/* vx_env_sky: the constant sky of radiance rgb (each finite, >= 0): a 1 x 1
 * lat-long map of 1 1 1 with scale rgb, so that lookups give rgb, its one
 * pixel covers the sphere (4 pi) and sampling is uniform on the sphere. */
int vx_env_sky(vx_env *env, const double rgb[3], vx_err *e);

/* vx_env_free: release env's memory; env becomes empty.  Accepts NULL. */
void vx_env_free(vx_env *env);

/* vx_env_load_light: the light l of a scene: an environment's file (read
 * with vx_image_read_linear_file, relative to the working directory) with
 * its layout, rotation and color * intensity; or a sky.  When l carries a
 * hash the file's must equal it: VX_EDATA "FILE: content hash ... differs
 * from the scene's ...".  Other light types are VX_EUSAGE. */
int vx_env_load_light(vx_env *env, const vx_light *l, vx_err *e);

/* vx_env_scene_resolve: every environment light of s without a hash gets
 * its file's (the file is read); lights with a hash are checked against
 * their file.  Errors as vx_env_load_light's, with "light N: " before. */
int vx_env_scene_resolve(vx_scene *s, vx_err *e);

/* vx_env_hash: the content hash of w x h RGB pixels (see above; the
 * values hashed as given). */
uint64_t vx_env_hash(const float *px, int w, int h);

/* ---- the mapping, in the map's own frame (no rotation) ---- */

/* vx_env_image_to_dir: the unit direction of image point (x, y) of a w x h
 * map (see above); returns 0, or -1 for a point outside an angular map's
 * disc (dir is then -x, the rim's direction). */
int vx_env_image_to_dir(vx_env_layout layout, int w, int h, double x,
    double y, double dir[3]);

/* vx_env_dir_to_image: the image point of direction dir (any length > 0):
 * lat-long x in [0, w), y in [0, h]; angular x, y in [0, w] x [0, h]. */
void vx_env_dir_to_image(vx_env_layout layout, int w, int h,
    const double dir[3], double *x, double *y);

/* ---- the light ---- */

/* vx_env_lookup: the radiance (scale applied) arriving from world direction
 * dir: the pixel holding it (bilinear 0), or bilinear interpolation between
 * the four pixel centres around it (bilinear 1; lat-long wraps in x and
 * clamps in y, angular clamps at the image's edges and reads the pixels
 * outside the disc as they are stored). */
void vx_env_lookup(const vx_env *env, const double dir[3], int bilinear,
    double rgb[3]);

/* vx_env_npixel: the pixels vx_env_pixel visits, w * h. */
size_t vx_env_npixel(const vx_env *env);

/* vx_env_pixel: pixel i (row-major, top row first): the world direction of
 * its centre (an angular pixel whose centre lies outside the disc: the
 * rim's direction), its exact solid angle, and its radiance.  The sum over
 * all pixels of rgb * omega * f(dir) is the quadrature of f over the map;
 * the solid angles sum to 4 pi. */
void vx_env_pixel(const vx_env *env, size_t i, double dir[3],
    double *omega, double rgb[3]);

/* vx_env_sample: a world direction for u in [0,1)^2 (u[0] picks the row,
 * u[1] the pixel in it; their remainders place the point in the pixel),
 * its radiance, and the return value its pdf in solid angle (a pure
 * function of u).  pdf 0: no direction (an angular pixel's corner outside
 * the disc); dir and rgb are then 0. */
double vx_env_sample(const vx_env *env, const double u[2], double dir[3],
    double rgb[3]);

/* vx_env_pdf: the pdf in solid angle with which vx_env_sample picks world
 * direction dir (any length > 0). */
double vx_env_pdf(const vx_env *env, const double dir[3]);

#endif
