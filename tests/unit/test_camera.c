/* test_camera.c: cameras: the documented conventions (pixel origin, vertical
 * fov, right-handed frame, orthographic width), auto framing of boxes from
 * every view, degenerate up vectors, projection as the inverse of rays, and
 * grid world <-> index transforms. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <string.h>
#include <cmocka.h>

#include "vx_camera.h"

#define DEG (3.14159265358979323846 / 180.0)

static double
dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void
check_close(double got, double want, double tol, const char *what)
{
	if (!(fabs(got - want) <= tol))
		fail_msg("%s: got %.17g, want %.17g (tol %g)", what, got, want,
		    tol);
}

static void
explicit_cam(vx_camera *c, vx_projection p, const double eye[3],
    const double look[3], const double up[3], int w, int h)
{
	vx_camera_init(c);
	c->is_auto = 0;
	c->projection = p;
	memcpy(c->eye, eye, sizeof c->eye);
	memcpy(c->look, look, sizeof c->look);
	memcpy(c->up, up, sizeof c->up);
	c->w = w;
	c->h = h;
}

/* The centre of the image looks exactly at the look point (oracle: the
 * definition, forward = unit(look - eye)). */
static void
pinhole_centre(void **state)
{
	static const struct { double eye[3], look[3], up[3]; int w, h; } t[] = {
		{ { 0, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, 64, 64 },
		{ { 1, 2, 3 }, { -4, 5, 0.5 }, { 0, 0, 1 }, 101, 37 },
		{ { 100, -50, 7 }, { 0, 0, 0 }, { 0.3, 1, 0.2 }, 640, 480 },
	};
	vx_err e = { 0, "" };
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_camera c;
		double o[3], d[3], v[3], len;
		int k;

		explicit_cam(&c, VX_PERSPECTIVE, t[i].eye, t[i].look, t[i].up,
		    t[i].w, t[i].h);
		c.fov = 40;
		assert_int_equal(vx_camera_resolve(&c, NULL, NULL, &e), 0);
		vx_camera_ray(&c, t[i].w / 2.0, t[i].h / 2.0, o, d);
		for (k = 0; k < 3; k++)
			v[k] = t[i].look[k] - t[i].eye[k];
		len = sqrt(dot(v, v));
		for (k = 0; k < 3; k++) {
			check_close(o[k], t[i].eye[k], 0, "origin is the eye");
			check_close(o[k] + len * d[k], t[i].look[k],
			    1e-12 * (1 + len), "centre ray reaches look");
		}
		check_close(dot(d, d), 1, 1e-15, "unit direction");
	}
}

/* Edge and corner rays make the fov angles (oracle: fov is the full
 * vertical angle; the horizontal half-angle is atan(tan(fov/2) w/h)), and
 * (0,0) is the top-left corner: up and to the left. */
static void
pinhole_fov(void **state)
{
	static const double eye[3] = { 0, 0, 0 }, look[3] = { 0, 1, 0 },
	    up[3] = { 0, 0, 1 };
	static const struct { double fov; int w, h; } t[] = {
		{ 30, 512, 512 }, { 60, 640, 480 }, { 90, 200, 800 },
		{ 170, 3, 1 },
	};
	vx_err e = { 0, "" };
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_camera c;
		double o[3], d[3], tv = tan(0.5 * t[i].fov * DEG);
		double th = tv * t[i].w / t[i].h;

		explicit_cam(&c, VX_PERSPECTIVE, eye, look, up, t[i].w, t[i].h);
		c.fov = t[i].fov;
		assert_int_equal(vx_camera_resolve(&c, NULL, NULL, &e), 0);
		/* top edge, middle: straight up by fov/2 */
		vx_camera_ray(&c, t[i].w / 2.0, 0, o, d);
		check_close(acos(d[1]) / DEG, t[i].fov / 2, 1e-9, "vertical angle");
		assert_true(d[2] > 0);
		check_close(d[0], 0, 1e-15, "no sideways part");
		/* left edge, middle: horizontal half-angle, to the left (-x) */
		vx_camera_ray(&c, 0, t[i].h / 2.0, o, d);
		check_close(atan2(-d[0], d[1]), atan(th), 1e-12,
		    "horizontal angle");
		/* top-left corner: the pinhole model's tangent ratios */
		vx_camera_ray(&c, 0, 0, o, d);
		check_close(d[0] / d[1], -th, 1e-12, "corner x");
		check_close(d[2] / d[1], tv, 1e-12, "corner z");
		/* bottom-right corner */
		vx_camera_ray(&c, t[i].w, t[i].h, o, d);
		check_close(d[0] / d[1], th, 1e-12, "far corner x");
		check_close(d[2] / d[1], -tv, 1e-12, "far corner z");
	}
}

/* Right-handed: looking along +y with up +z, the right of the image is +x
 * (oracle: right = forward x up). */
static void
handedness(void **state)
{
	static const double eye[3] = { 0, 0, 0 }, look[3] = { 0, 1, 0 },
	    up[3] = { 0, 0, 1 };
	vx_err e = { 0, "" };
	vx_camera c;
	double o[3], d[3];

	(void)state;
	explicit_cam(&c, VX_PERSPECTIVE, eye, look, up, 10, 10);
	assert_int_equal(vx_camera_resolve(&c, NULL, NULL, &e), 0);
	check_close(c.right[0], 1, 0, "right is +x");
	check_close(c.upv[2], 1, 0, "upward is +z");
	vx_camera_ray(&c, 9.5, 5, o, d);
	assert_true(d[0] > 0);
}

/* Orthographic rays are parallel to forward and their origins span the
 * view width horizontally and width*h/w vertically (oracle: definition). */
static void
orthographic(void **state)
{
	static const double eye[3] = { 1, 2, 3 }, look[3] = { 1, 2, -7 },
	    up[3] = { 0, 1, 0 };
	vx_err e = { 0, "" };
	vx_camera c;
	double o0[3], d0[3], o1[3], d1[3], o2[3], d2[3];
	int k;

	(void)state;
	explicit_cam(&c, VX_ORTHOGRAPHIC, eye, look, up, 300, 100);
	c.view_width = 6;
	assert_int_equal(vx_camera_resolve(&c, NULL, NULL, &e), 0);
	vx_camera_ray(&c, 0, 0, o0, d0);
	vx_camera_ray(&c, 300, 0, o1, d1);
	vx_camera_ray(&c, 0, 100, o2, d2);
	for (k = 0; k < 3; k++) {
		check_close(d0[k], c.fwd[k], 0, "parallel");
		check_close(d1[k], c.fwd[k], 0, "parallel");
	}
	check_close(d0[2], -1, 0, "forward is -z");
	/* forward -z, up +y: right = (-z) x y = +x */
	check_close(o1[0] - o0[0], 6, 1e-12, "width along +x");
	check_close(o0[1] - o2[1], 2, 1e-12, "height = width * h / w");
	check_close(o0[2], 3, 1e-12, "origins on the eye plane");
	/* the centre ray starts at the eye */
	vx_camera_ray(&c, 150, 50, o0, d0);
	for (k = 0; k < 3; k++)
		check_close(o0[k], eye[k], 1e-12, "centre origin");
}

/* Every corner of the box projects inside the image, for every view,
 * projection and aspect (oracle: vx_camera_project, itself checked as the
 * inverse of vx_camera_ray below); with distance factor 1 the fit is tight
 * (some corner touches an edge). */
static void
auto_framing(void **state)
{
	static const double box[][2][3] = {
		{ { 0, 0, 0 }, { 180, 216, 180 } },
		{ { -1, -1, -1 }, { 1, 1, 1 } },
		{ { 10, 20, 30 }, { 10.5, 90, 31 } },
		{ { 0, 0, 0 }, { 5, 5, 0 } },          /* flat */
		{ { 2, 2, 2 }, { 2, 2, 2 } },          /* a point */
	};
	static const struct { vx_view v; double az, el; } views[] = {
		{ VX_VIEW_FRONT, 0, 0 }, { VX_VIEW_BACK, 0, 0 },
		{ VX_VIEW_LEFT, 0, 0 }, { VX_VIEW_RIGHT, 0, 0 },
		{ VX_VIEW_TOP, 0, 0 }, { VX_VIEW_BOTTOM, 0, 0 },
		{ VX_VIEW_ANGLES, 30, 20 }, { VX_VIEW_ANGLES, -135, -60 },
		{ VX_VIEW_ANGLES, 77, 90 }, { VX_VIEW_ANGLES, 0, 89.9999 },
	};
	static const int size[][2] = { { 512, 512 }, { 640, 360 }, { 90, 400 } };
	static const double dist[] = { 1, 1.1, 3 };
	vx_err e = { 0, "" };
	size_t b, v, s, f;
	int p;

	(void)state;
	for (b = 0; b < sizeof box / sizeof box[0]; b++)
	for (v = 0; v < sizeof views / sizeof views[0]; v++)
	for (s = 0; s < 3; s++)
	for (f = 0; f < 3; f++)
	for (p = VX_PERSPECTIVE; p <= VX_ORTHOGRAPHIC; p++) {
		vx_camera c;
		double worst = 0;
		int i;

		vx_camera_init(&c);
		c.projection = (vx_projection)p;
		c.view = views[v].v;
		c.azimuth = views[v].az;
		c.elevation = views[v].el;
		c.w = size[s][0];
		c.h = size[s][1];
		c.distance = dist[f];
		c.fov = 35;
		assert_int_equal(vx_camera_resolve(&c, box[b][0], box[b][1], &e),
		    0);
		for (i = 0; i < 8; i++) {
			double q[3], px, py, depth, m;

			q[0] = box[b][i & 1][0];
			q[1] = box[b][(i >> 1) & 1][1];
			q[2] = box[b][(i >> 2) & 1][2];
			if (!vx_camera_project(&c, q, &px, &py, &depth))
				fail_msg("box %zu view %zu: corner %d behind the "
				    "eye", b, v, i);
			/* distance from the centre in half-image units */
			m = fmax(fabs(2 * px / c.w - 1), fabs(2 * py / c.h - 1));
			if (m > 1 + 1e-9)
				fail_msg("box %zu view %zu size %zu dist %g proj %d:"
				    " corner %d at (%g, %g) outside %dx%d", b, v,
				    s, dist[f], p, i, px, py, c.w, c.h);
			worst = fmax(worst, m);
		}
		/* tight: factor 1 touches an edge; factor 3 leaves a margin */
		if (dist[f] == 1 && b < 4)
			check_close(worst, 1, 1e-9, "tight framing");
		if (dist[f] == 3)
			assert_true(worst < 0.5 || b == 4);
	}
}

/* Named views look at the face of the box they name (oracle: the table in
 * formats/scene.md): front sees +y, right sees +x, top sees +z with +y
 * (the back) at the top of the image, bottom has +y at the top. */
static void
named_views(void **state)
{
	static const struct { vx_view v; double eye_dir[3], img_up[3]; } t[] = {
		{ VX_VIEW_FRONT, { 0, 1, 0 }, { 0, 0, 1 } },
		{ VX_VIEW_BACK, { 0, -1, 0 }, { 0, 0, 1 } },
		{ VX_VIEW_RIGHT, { 1, 0, 0 }, { 0, 0, 1 } },
		{ VX_VIEW_LEFT, { -1, 0, 0 }, { 0, 0, 1 } },
		{ VX_VIEW_TOP, { 0, 0, 1 }, { 0, -1, 0 } },
		{ VX_VIEW_BOTTOM, { 0, 0, -1 }, { 0, 1, 0 } },
	};
	static const double lo[3] = { -1, -2, -3 }, hi[3] = { 1, 2, 3 };
	vx_err e = { 0, "" };
	size_t i;
	int k;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_camera c, a;
		double dir[3], up[3];

		vx_camera_init(&c);
		c.view = t[i].v;
		assert_int_equal(vx_camera_resolve(&c, lo, hi, &e), 0);
		for (k = 0; k < 3; k++) {
			check_close(-c.fwd[k], t[i].eye_dir[k], 1e-15, "eye side");
			check_close(c.upv[k], t[i].img_up[k], 1e-15, "image up");
			check_close(c.at[k], 0, 0, "looks at the centre");
		}
		/* the same view by angles gives the same frame */
		vx_camera_view_dir(t[i].v, 0, 0, dir, up);
		a = c;
		a.view = VX_VIEW_ANGLES;
		a.azimuth = t[i].v == VX_VIEW_RIGHT ? 90 :
		    t[i].v == VX_VIEW_LEFT ? -90 : t[i].v == VX_VIEW_BACK ? 180 : 0;
		a.elevation = t[i].v == VX_VIEW_TOP ? 90 :
		    t[i].v == VX_VIEW_BOTTOM ? -90 : 0;
		assert_int_equal(vx_camera_resolve(&a, lo, hi, &e), 0);
		for (k = 0; k < 3; k++) {
			check_close(a.fwd[k], c.fwd[k], 1e-15, "angles = named");
			check_close(a.upv[k], c.upv[k], 1e-15, "angles = named up");
		}
	}
}

/* An up vector parallel to the view direction still gives an orthonormal
 * frame without NaN (oracle: orthonormality and the documented fallback);
 * elevation 90 is continuous with elevation just below it. */
static void
degenerate_up(void **state)
{
	static const struct { double eye[3], look[3], up[3]; } t[] = {
		{ { 0, 0, 10 }, { 0, 0, 0 }, { 0, 0, 1 } },
		{ { 0, 0, 10 }, { 0, 0, 0 }, { 0, 0, -5 } },
		{ { 0, 3, 0 }, { 0, 0, 0 }, { 0, 1, 0 } },
		{ { 1, 1, 1 }, { 2, 2, 2 }, { 1, 1, 1 } },
		{ { 0, 0, 0 }, { 0, 0, 1e-300 }, { 0, 0, 1 } },
	};
	static const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
	vx_err e = { 0, "" };
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_camera c;
		double o[3], d[3];
		int k, px;

		explicit_cam(&c, VX_PERSPECTIVE, t[i].eye, t[i].look, t[i].up,
		    16, 16);
		assert_int_equal(vx_camera_resolve(&c, NULL, NULL, &e), 0);
		check_close(dot(c.fwd, c.fwd), 1, 1e-15, "fwd unit");
		check_close(dot(c.right, c.right), 1, 1e-15, "right unit");
		check_close(dot(c.upv, c.upv), 1, 1e-15, "up unit");
		check_close(dot(c.fwd, c.right), 0, 1e-15, "fwd.right");
		check_close(dot(c.fwd, c.upv), 0, 1e-15, "fwd.up");
		check_close(dot(c.right, c.upv), 0, 1e-15, "right.up");
		for (px = 0; px <= 16; px += 4) {
			vx_camera_ray(&c, px, 16 - px, o, d);
			for (k = 0; k < 3; k++)
				assert_true(isfinite(o[k]) && isfinite(d[k]));
		}
	}
	/* auto with an up along the view direction */
	{
		vx_camera c;

		vx_camera_init(&c);
		c.has_up = 1;
		c.up[0] = 0; c.up[1] = 1; c.up[2] = 0;   /* front looks along -y */
		assert_int_equal(vx_camera_resolve(&c, lo, hi, &e), 0);
		assert_true(isfinite(c.right[0]) && isfinite(c.upv[2]));
		check_close(dot(c.right, c.right), 1, 1e-15, "auto right unit");
	}
	/* continuity at the pole */
	{
		vx_camera a, b;

		vx_camera_init(&a);
		a.view = VX_VIEW_ANGLES;
		a.azimuth = 40;
		a.elevation = 90;
		b = a;
		b.elevation = 89.99;
		assert_int_equal(vx_camera_resolve(&a, lo, hi, &e), 0);
		assert_int_equal(vx_camera_resolve(&b, lo, hi, &e), 0);
		assert_true(dot(a.upv, b.upv) > 0.999);
		assert_true(dot(a.right, b.right) > 0.999);
	}
}

/* vx_camera_project inverts vx_camera_ray (oracle: a point on the ray
 * through a pixel projects back to that pixel). */
static void
project_inverts_ray(void **state)
{
	static const double eye[3] = { 3, -4, 5 }, look[3] = { 0, 1, 0.5 },
	    up[3] = { 0, 0, 1 };
	vx_err e = { 0, "" };
	int p;

	(void)state;
	for (p = VX_PERSPECTIVE; p <= VX_ORTHOGRAPHIC; p++) {
		vx_camera c;
		double px, py;

		explicit_cam(&c, (vx_projection)p, eye, look, up, 320, 200);
		c.view_width = 4;
		assert_int_equal(vx_camera_resolve(&c, NULL, NULL, &e), 0);
		for (px = 0; px <= 320; px += 37.5)
			for (py = 0; py <= 200; py += 23.25) {
				double o[3], d[3], q[3], qx, qy, depth;
				int k;

				vx_camera_ray(&c, px, py, o, d);
				for (k = 0; k < 3; k++)
					q[k] = o[k] + 7.5 * d[k];
				assert_true(vx_camera_project(&c, q, &qx, &qy, &depth));
				check_close(qx, px, 1e-9, "px");
				check_close(qy, py, 1e-9, "py");
			}
		/* behind the eye */
		{
			double q[3] = { 2 * eye[0] - look[0], 2 * eye[1] - look[1],
			    2 * eye[2] - look[2] }, qx, qy, depth;

			assert_false(vx_camera_project(&c, q, &qx, &qy, &depth));
			assert_true(depth < 0);
		}
	}
}

/* Bad cameras are errors, not NaN (oracle: the contract). */
static void
resolve_errors(void **state)
{
	static const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
	static const double bad_hi[3] = { 1, -1, 1 };
	const double nan_hi[3] = { 1, NAN, 1 };
	vx_err e = { 0, "" };
	vx_camera c;

	(void)state;
	vx_camera_init(&c);
	assert_int_equal(vx_camera_resolve(&c, NULL, NULL, &e), VX_EDATA);
	assert_non_null(strstr(e.msg, "box"));
	assert_int_equal(vx_camera_resolve(&c, lo, bad_hi, &e), VX_EDATA);
	assert_int_equal(vx_camera_resolve(&c, lo, nan_hi, &e), VX_EDATA);
	c.fov = 180;
	assert_int_equal(vx_camera_resolve(&c, lo, hi, &e), VX_EDATA);
	assert_int_equal(c.ready, 0);
	vx_camera_init(&c);
	c.w = 0;
	assert_int_equal(vx_camera_resolve(&c, lo, hi, &e), VX_EDATA);
	vx_camera_init(&c);
	c.is_auto = 0;      /* eye == look == 0 */
	assert_int_equal(vx_camera_resolve(&c, lo, hi, &e), VX_EDATA);
	assert_non_null(strstr(e.msg, "coincide"));
	c.look[0] = 1;
	c.projection = VX_ORTHOGRAPHIC;   /* width 0 */
	assert_int_equal(vx_camera_resolve(&c, lo, hi, &e), VX_EDATA);
	c.view_width = 2;
	assert_int_equal(vx_camera_resolve(&c, lo, hi, &e), 0);
	assert_int_equal(c.ready, 1);
}

/* Grid transforms: world = origin + index * spacing (oracle: vx_grid.h);
 * directions scale without normalizing, so ray parameters agree; normals
 * transform by the inverse transpose. */
static void
grid_transforms(void **state)
{
	vx_grid g;
	vx_err e = { 0, "" };
	int64_t dims[3] = { 5, 7, 9 };
	double lo[3], hi[3], w[3], i[3], back[3];
	int k;

	(void)state;
	vx_grid_init(&g);
	assert_int_equal(vx_grid_alloc(&g, dims, VX_U8, NULL, &e), 0);
	g.spacing[0] = 0.5; g.spacing[1] = 2; g.spacing[2] = 0.25;
	g.origin[0] = -1; g.origin[1] = 10; g.origin[2] = 3;
	vx_grid_box(&g, lo, hi);
	check_close(lo[0], -1, 0, "lo");
	check_close(hi[0], 1, 0, "hi x");
	check_close(hi[1], 22, 0, "hi y");
	check_close(hi[2], 5, 0, "hi z");
	{
		double idx[3] = { 4, 6, 8 };

		vx_index_to_world(&g, idx, w);
		for (k = 0; k < 3; k++)
			check_close(w[k], hi[k], 0, "last sample at hi");
	}
	w[0] = 0.3; w[1] = 11; w[2] = 4.5;
	vx_world_to_index(&g, w, i);
	check_close(i[0], 2.6, 1e-15, "ix");
	check_close(i[1], 0.5, 1e-15, "iy");
	check_close(i[2], 6, 1e-15, "iz");
	vx_index_to_world(&g, i, back);
	for (k = 0; k < 3; k++)
		check_close(back[k], w[k], 1e-14, "round trip");
	{
		/* a ray in world and in index space meet the same point at t */
		double o[3] = { 0.3, 11, 4.5 }, d[3] = { 1, -2, 0.5 }, t = 1.75;
		double oi[3], di[3], pw[3], pi[3];

		vx_world_to_index(&g, o, oi);
		vx_world_to_index_dir(&g, d, di);
		for (k = 0; k < 3; k++) {
			pw[k] = o[k] + t * d[k];
			pi[k] = oi[k] + t * di[k];
		}
		vx_index_to_world(&g, pi, back);
		for (k = 0; k < 3; k++)
			check_close(back[k], pw[k], 1e-13, "same t");
		vx_index_to_world_dir(&g, di, back);
		for (k = 0; k < 3; k++)
			check_close(back[k], d[k], 1e-15, "dir round trip");
	}
	{
		/* f = x_world: index gradient is (spacing_x, 0, 0) */
		double gi[3] = { 0.5, 0, 0 }, n[3], z[3] = { 0, 0, 0 };

		vx_index_to_world_normal(&g, gi, n);
		check_close(n[0], 1, 0, "normal x");
		/* f = x + y (world): index gradient (0.5, 2, 0) -> (1,1,0)/sqrt2 */
		gi[1] = 2;
		vx_index_to_world_normal(&g, gi, n);
		check_close(n[0], sqrt(0.5), 1e-15, "normal diag");
		check_close(n[1], sqrt(0.5), 1e-15, "normal diag");
		vx_index_to_world_normal(&g, z, n);
		check_close(n[0], 0, 0, "zero stays zero");
		assert_false(isnan(n[1]));
	}
	vx_grid_free(&g);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(pinhole_centre),
		cmocka_unit_test(pinhole_fov),
		cmocka_unit_test(handedness),
		cmocka_unit_test(orthographic),
		cmocka_unit_test(auto_framing),
		cmocka_unit_test(named_views),
		cmocka_unit_test(degenerate_up),
		cmocka_unit_test(project_inverts_ray),
		cmocka_unit_test(resolve_errors),
		cmocka_unit_test(grid_transforms),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
