/* camera.c: camera frames, automatic framing of a box, rays from pixels,
 * projection of points, and world <-> index transforms of grids. */
#include "vx_camera.h"
#include "vx_vec.h"

#include <math.h>
#include <string.h>

#define DEG (3.14159265358979323846 / 180.0)

static const vx_enum_name view_names[] = {
	{ "front", VX_VIEW_FRONT }, { "back", VX_VIEW_BACK },
	{ "left", VX_VIEW_LEFT }, { "right", VX_VIEW_RIGHT },
	{ "top", VX_VIEW_TOP }, { "bottom", VX_VIEW_BOTTOM },
	{ "angles", VX_VIEW_ANGLES }, { NULL, VX_VIEW_UNKNOWN }
};
const vx_enum vx_view_enum = { "view", view_names, "unknown", 0 };

static const vx_enum_name projection_names[] = {
	{ "perspective", VX_PERSPECTIVE }, { "orthographic", VX_ORTHOGRAPHIC },
	{ NULL, VX_PROJECTION_UNKNOWN }
};
const vx_enum vx_projection_enum = { "projection", projection_names,
    "unknown", 0 };

void
vx_camera_init(vx_camera *c)
{
	memset(c, 0, sizeof *c);
	c->projection = VX_PERSPECTIVE;
	c->is_auto = 1;
	c->view = VX_VIEW_FRONT;
	c->distance = 1.1;
	c->up[2] = 1;
	c->fov = 30;
	c->w = 512;
	c->h = 512;
}

/* Named views as (azimuth, elevation); the table keeps them exact (cos 90
 * degrees is not 0 in floating point). */
void
vx_camera_view_dir(vx_view v, double azimuth, double elevation,
    double dir[3], double up[3])
{
	static const double named[VX_VIEW_ANGLES][2][3] = {
		{ { 0, 1, 0 }, { 0, 0, 1 } },     /* unknown: as front */
		{ { 0, 1, 0 }, { 0, 0, 1 } },     /* front */
		{ { 0, -1, 0 }, { 0, 0, 1 } },    /* back */
		{ { -1, 0, 0 }, { 0, 0, 1 } },    /* left */
		{ { 1, 0, 0 }, { 0, 0, 1 } },     /* right */
		{ { 0, 0, 1 }, { 0, -1, 0 } },    /* top: azimuth 0, elevation 90 */
		{ { 0, 0, -1 }, { 0, 1, 0 } },    /* bottom: elevation -90 */
	};
	double a, el, ca, sa, ce, se;

	if (v != VX_VIEW_ANGLES) {
		if (v < VX_VIEW_UNKNOWN || v >= VX_VIEW_ANGLES)
			v = VX_VIEW_UNKNOWN;
		memcpy(dir, named[v][0], 3 * sizeof *dir);
		memcpy(up, named[v][1], 3 * sizeof *up);
		return;
	}
	a = azimuth * DEG;
	el = elevation * DEG;
	ca = cos(a);
	sa = sin(a);
	ce = cos(el);
	se = sin(el);
	if (elevation == 90 || elevation == -90)
		ce = 0;
	dir[0] = sa * ce;
	dir[1] = ca * ce;
	dir[2] = se;
	up[0] = 0;
	up[1] = 0;
	up[2] = 1;
	if (ce == 0) {           /* straight down or up: the limit of +z */
		double sgn = elevation > 0 ? -1 : 1;

		up[0] = sgn * sa;
		up[1] = sgn * ca;
		up[2] = 0;
	}
}

/* frame: forward, right, upward from a view direction and an up hint; falls
 * back to a world axis when up is (nearly) parallel to forward. */
static void
frame(const double fwd_in[3], const double up_in[3], double fwd[3],
    double right[3], double upv[3])
{
	double u[3];

	memcpy(fwd, fwd_in, 3 * sizeof *fwd);
	vx_unit3(fwd);
	memcpy(u, up_in, sizeof u);
	vx_unit3(u);
	vx_cross3(fwd, u, right);
	if (!(sqrt(vx_dot3(right, right)) > 1e-9)) {
		/* the world axis least aligned with forward: z, else y */
		double z[3] = { 0, 0, 1 }, y[3] = { 0, 1, 0 };

		vx_cross3(fwd, fabs(fwd[2]) < 0.9 ? z : y, right);
	}
	vx_unit3(right);
	vx_cross3(right, fwd, upv);
	vx_unit3(upv);
}

static int
check_common(const vx_camera *c, vx_err *e)
{
	if (c->w < 1 || c->h < 1 || c->w > VX_CAMERA_MAX_PIXELS ||
	    c->h > VX_CAMERA_MAX_PIXELS)
		return vx_err_set(e, VX_EDATA, "camera: image size %dx%d outside "
		    "1..%d", c->w, c->h, VX_CAMERA_MAX_PIXELS);
	if (c->projection == VX_PERSPECTIVE &&
	    !(c->fov > 0 && c->fov < 180))
		return vx_err_set(e, VX_EDATA, "camera: fov %g outside (0, 180)",
		    c->fov);
	if (c->projection != VX_PERSPECTIVE &&
	    c->projection != VX_ORTHOGRAPHIC)
		return vx_err_set(e, VX_EDATA, "camera: unknown projection");
	if (!vx_finite3(c->up) || ((c->has_up || !c->is_auto) &&
	    c->up[0] == 0 && c->up[1] == 0 && c->up[2] == 0))
		return vx_err_set(e, VX_EDATA, "camera: up must be a finite "
		    "nonzero vector");
	return 0;
}

/* auto_frame: eye, look, up (and the orthographic width) for box lo..hi. */
static int
auto_frame(vx_camera *c, const double lo[3], const double hi[3], vx_err *e)
{
	double ctr[3], dir[3], up[3], r = 0, tv, th;
	double dmax = 0, zmax = -HUGE_VAL, xmax = 0, ymax = 0;
	int i, k;

	if (lo == NULL || hi == NULL)
		return vx_err_set(e, VX_EDATA, "camera: auto framing needs the "
		    "volume's box");
	for (k = 0; k < 3; k++) {
		if (!isfinite(lo[k]) || !isfinite(hi[k]) || lo[k] > hi[k])
			return vx_err_set(e, VX_EDATA, "camera: bad box on axis "
			    "%d: [%g, %g]", k, lo[k], hi[k]);
		ctr[k] = 0.5 * (lo[k] + hi[k]);
		r += (hi[k] - lo[k]) * (hi[k] - lo[k]);
	}
	r = 0.5 * sqrt(r);
	if (!(r > 0))
		r = 1;   /* a single point: frame a unit sphere around it */
	if (!(c->distance > 0) || !isfinite(c->distance))
		return vx_err_set(e, VX_EDATA, "camera: distance factor %g must "
		    "be > 0", c->distance);
	if (c->view == VX_VIEW_ANGLES &&
	    (!isfinite(c->azimuth) || !isfinite(c->elevation) ||
	    c->elevation < -90 || c->elevation > 90))
		return vx_err_set(e, VX_EDATA, "camera: elevation must be in "
		    "[-90, 90]");
	vx_camera_view_dir(c->view, c->azimuth, c->elevation, dir, up);
	if (c->has_up)
		memcpy(up, c->up, sizeof up);
	{
		double back[3] = { -dir[0], -dir[1], -dir[2] };

		frame(back, up, c->fwd, c->right, c->upv);
	}
	/* Each corner in camera coordinates: x right, y up, z toward the eye. */
	tv = tan(0.5 * c->fov * DEG);
	th = tv * c->w / c->h;
	for (i = 0; i < 8; i++) {
		double p[3], x, y, z, d;

		p[0] = (i & 1 ? hi[0] : lo[0]) - ctr[0];
		p[1] = (i & 2 ? hi[1] : lo[1]) - ctr[1];
		p[2] = (i & 4 ? hi[2] : lo[2]) - ctr[2];
		x = fabs(vx_dot3(p, c->right));
		y = fabs(vx_dot3(p, c->upv));
		z = -vx_dot3(p, c->fwd);
		if (x > xmax)
			xmax = x;
		if (y > ymax)
			ymax = y;
		if (z > zmax)
			zmax = z;
		if (c->projection == VX_PERSPECTIVE) {
			/* the eye at distance d sees the corner inside the image
			 * iff x <= th (d - z) and y <= tv (d - z) */
			d = z + (x / th > y / tv ? x / th : y / tv);
			if (d > dmax)
				dmax = d;
		}
	}
	if (c->projection == VX_PERSPECTIVE) {
		/* never at or inside the box's near corner when the box is flat
		 * toward the eye */
		if (!(dmax > zmax))
			dmax = zmax + r;
		dmax *= c->distance;
		c->width_used = 0;
	} else {
		double wneed = 2 * xmax, hneed = 2 * ymax * c->w / c->h;

		c->width_used = (wneed > hneed ? wneed : hneed) * c->distance;
		if (!(c->width_used > 0))
			c->width_used = 2 * r * c->distance;
		dmax = 2 * r;   /* outside the bounding sphere */
	}
	for (k = 0; k < 3; k++) {
		c->at[k] = ctr[k];
		c->o[k] = ctr[k] - dmax * c->fwd[k];
	}
	return 0;
}

int
vx_camera_resolve(vx_camera *c, const double lo[3], const double hi[3],
    vx_err *e)
{
	int rc;

	c->ready = 0;
	if ((rc = check_common(c, e)) != 0)
		return rc;
	if (c->is_auto) {
		if ((rc = auto_frame(c, lo, hi, e)) != 0)
			return rc;
	} else {
		double f[3];

		if (!vx_finite3(c->eye) || !vx_finite3(c->look))
			return vx_err_set(e, VX_EDATA, "camera: eye and look must "
			    "be finite");
		f[0] = c->look[0] - c->eye[0];
		f[1] = c->look[1] - c->eye[1];
		f[2] = c->look[2] - c->eye[2];
		if (f[0] == 0 && f[1] == 0 && f[2] == 0)
			return vx_err_set(e, VX_EDATA, "camera: eye and look "
			    "coincide");
		if (!vx_finite3(f))
			return vx_err_set(e, VX_EDATA, "camera: eye and look too "
			    "far apart");
		if (c->projection == VX_ORTHOGRAPHIC &&
		    !(c->view_width > 0 && isfinite(c->view_width)))
			return vx_err_set(e, VX_EDATA, "camera: orthographic width "
			    "must be > 0");
		frame(f, c->up, c->fwd, c->right, c->upv);
		memcpy(c->o, c->eye, sizeof c->o);
		memcpy(c->at, c->look, sizeof c->at);
		c->width_used = c->projection == VX_ORTHOGRAPHIC ?
		    c->view_width : 0;
	}
	if (c->projection == VX_PERSPECTIVE) {
		c->half_h = tan(0.5 * c->fov * DEG);
		c->half_w = c->half_h * c->w / c->h;
	} else {
		c->half_w = 0.5 * c->width_used;
		c->half_h = c->half_w * c->h / c->w;
	}
	c->ready = 1;
	return 0;
}

void
vx_camera_ray(const vx_camera *c, double px, double py, double o[3],
    double d[3])
{
	/* screen coordinates in [-1, 1], y up; exactly 0 at the centre */
	double sx = (2 * px - c->w) / c->w, sy = (c->h - 2 * py) / c->h;
	double a = sx * c->half_w, b = sy * c->half_h;
	int k;

	if (c->projection == VX_ORTHOGRAPHIC) {
		for (k = 0; k < 3; k++) {
			o[k] = c->o[k] + a * c->right[k] + b * c->upv[k];
			d[k] = c->fwd[k];
		}
		return;
	}
	for (k = 0; k < 3; k++) {
		o[k] = c->o[k];
		d[k] = c->fwd[k] + a * c->right[k] + b * c->upv[k];
	}
	/* |d| >= 1 (a unit vector plus orthogonal terms): no scaling needed */
	{
		double inv = 1 / sqrt(vx_dot3(d, d));

		d[0] *= inv;
		d[1] *= inv;
		d[2] *= inv;
	}
}

int
vx_camera_project(const vx_camera *c, const double p[3], double *px,
    double *py, double *depth)
{
	double v[3] = { p[0] - c->o[0], p[1] - c->o[1], p[2] - c->o[2] };
	double z = vx_dot3(v, c->fwd), a = vx_dot3(v, c->right), b = vx_dot3(v, c->upv);

	if (depth != NULL)
		*depth = z;
	if (c->projection == VX_PERSPECTIVE) {
		if (!(z > 0))
			return 0;
		a /= z;
		b /= z;
	} else if (!(z > 0)) {
		return 0;
	}
	*px = 0.5 * c->w * (1 + a / c->half_w);
	*py = 0.5 * c->h * (1 - b / c->half_h);
	return 1;
}
