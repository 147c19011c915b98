/* vx_camera.h: cameras (pinhole and orthographic), automatic framing of a
 * volume's box, rays from pixels, and world <-> index transforms of grids.
 *
 * Conventions (formats/scene.md, "Cameras", is the normative text):
 *  - World space is right-handed.  A camera looks from eye toward look; its
 *    frame is forward = unit(look - eye), right = unit(forward x up),
 *    upward = right x forward.  So with forward +y and up +z, right is +x.
 *  - Pixel coordinates (px, py) cover [0,w) x [0,h); (0,0) is the top-left
 *    corner of the top-left pixel, px grows to the right, py downward; the
 *    centre of pixel (i,j) is (i + 0.5, j + 0.5).
 *  - Perspective: fov is the full vertical field of view in degrees; the
 *    horizontal one follows from the aspect w/h.  All rays start at the eye.
 *  - Orthographic: view_width is the horizontal extent of the view in world
 *    units (the vertical one is view_width * h / w); rays are parallel to
 *    forward and start on the plane through the eye perpendicular to it.
 *  - When up is (nearly) parallel to forward, the frame uses the world axis
 *    least aligned with forward as up (z, else y): never a NaN.
 *  - Auto framing (is_auto): the look point is the centre of the box, the eye
 *    lies in a direction given by a named view or azimuth/elevation, at the
 *    closest distance where all 8 corners of the box are inside the image
 *    (perspective), times the distance factor; orthographic auto framing
 *    sizes view_width the same way.  See vx_camera_resolve. */
#ifndef VX_CAMERA_H
#define VX_CAMERA_H

#include "vx_enum.h"
#include "vx_err.h"
#include "vx_grid.h"

typedef enum vx_projection {
	VX_PROJECTION_UNKNOWN = 0,
	VX_PERSPECTIVE,
	VX_ORTHOGRAPHIC,
	VX_PROJECTION_LAST
} vx_projection;

/* Named views for auto framing: the name says which face of the box the
 * camera looks at (front: the +y face, the face of a head stored in RAS
 * order; right: +x; top: +z).  VX_VIEW_ANGLES: azimuth and elevation. */
typedef enum vx_view {
	VX_VIEW_UNKNOWN = 0,
	VX_VIEW_FRONT,
	VX_VIEW_BACK,
	VX_VIEW_LEFT,
	VX_VIEW_RIGHT,
	VX_VIEW_TOP,
	VX_VIEW_BOTTOM,
	VX_VIEW_ANGLES,
	VX_VIEW_LAST
} vx_view;

/* Largest image edge in pixels a camera accepts. */
#define VX_CAMERA_MAX_PIXELS 65536

typedef struct vx_camera {
	/* ---- description (what a scene file says) ---- */
	vx_projection projection;
	int is_auto;             /* 1: framed from the volume's box at render time */
	vx_view view;            /* auto: named view, or VX_VIEW_ANGLES */
	double azimuth;          /* auto, VX_VIEW_ANGLES: degrees about +z, 0 = front,
	                            90 = right */
	double elevation;        /* auto, VX_VIEW_ANGLES: degrees, 90 = top */
	double distance;         /* auto: framing factor, 1 = tight, > 0 */
	int has_up;              /* auto: 1 if up was given (else view's default) */
	double eye[3], look[3];  /* explicit cameras */
	double up[3];            /* explicit cameras; auto when has_up */
	double fov;              /* perspective: vertical field of view, degrees */
	double view_width;       /* explicit orthographic: horizontal extent */
	int w, h;                /* image size in pixels */

	/* ---- derived by vx_camera_resolve; not part of the description ---- */
	int ready;               /* 1 after a successful vx_camera_resolve */
	double o[3];             /* resolved eye */
	double at[3];            /* resolved look point */
	double fwd[3], right[3], upv[3];   /* orthonormal frame */
	double half_w, half_h;   /* perspective: tan of the half angles;
	                            orthographic: half extents in world units */
	double width_used;       /* orthographic: resolved view width */
} vx_camera;

/* vx_camera_init: the default camera: auto, perspective, view front,
 * fov 30, distance factor 1.1, 512 x 512 pixels, not resolved. */
void vx_camera_init(vx_camera *c);

/* vx_camera_resolve: compute the frame (the derived fields) of c.  For an
 * auto camera, lo and hi are the world box of the volume (lo <= hi per axis;
 * a flat box is allowed); for an explicit one they are not used and may be
 * NULL.  Errors (VX_EDATA): an auto camera without a box, a box with
 * non-finite or inverted bounds, eye == look, fov outside (0, 180),
 * view_width <= 0, image size outside [1, VX_CAMERA_MAX_PIXELS]. */
int vx_camera_resolve(vx_camera *c, const double lo[3], const double hi[3],
    vx_err *e);

/* vx_camera_ray: the ray through image point (px, py) of a resolved camera:
 * origin o and unit direction d in world space.  Perspective: o is the eye.
 * Orthographic: o is on the eye's plane and d is the forward axis. */
void vx_camera_ray(const vx_camera *c, double px, double py, double o[3],
    double d[3]);

/* vx_camera_project: the image point (px, py) where world point p appears,
 * and its depth along the forward axis from the eye.  Returns 1 if the point
 * is in front of the eye (depth > 0), else 0 (then px, py are not set; the
 * depth is, either way).
 * Inverse of vx_camera_ray for points on the ray. */
int vx_camera_project(const vx_camera *c, const double p[3], double *px,
    double *py, double *depth);

/* vx_camera_view_dir: unit vector from the box centre toward the eye for a
 * view (named or VX_VIEW_ANGLES with azimuth, elevation in degrees), and the
 * view's default up vector (+z, or for views straight down or up the one
 * that keeps the image continuous with elevations just short of 90). */
void vx_camera_view_dir(vx_view v, double azimuth, double elevation,
    double dir[3], double up[3]);

/* The names (vx_enum.h): views "front" ... "bottom", "angles";
 * projections "perspective", "orthographic".  An unknown name has the
 * UNKNOWN value, an unknown value the name "unknown". */
extern const vx_enum vx_view_enum, vx_projection_enum;

#endif
