/* test_surface.c: the surfaces as renderers and bakers see them
 * (vx_surface.h): hit records of a volume and of its tet split against the
 * geometry, visibility through opaque and translucent layers, lights at a
 * point, shading with the lights and with an irradiance in their place. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "vx_plan.h"
#include "vx_surface.h"
#include "vx_tetimport.h"

#define N 24
#define C ((N - 1) / 2.0)

/* the distance from the volume's centre: the isosurface r is a sphere of
 * radius r about (C, C, C) in world space (spacing 1, origin 0) */
static void
make_sphere(vx_grid *g)
{
	int64_t d[3] = { N, N, N };
	vx_err e = { 0, "" };

	assert_int_equal(vx_grid_alloc(g, d, VX_F32, "linear", &e), 0);
	for (int z = 0; z < N; z++)
		for (int y = 0; y < N; y++)
			for (int x = 0; x < N; x++)
				vx_grid_set(g, x, y, z, sqrt((x - C) * (x - C) +
				    (y - C) * (y - C) + (z - C) * (z - C)));
	vx_grid_range(g);
}

typedef struct hits {
	int n;
	vx_hit h[8];
} hits;

static int
collect(void *ctx, const vx_hit *h)
{
	hits *x = ctx;

	if (x->n < 8)
		x->h[x->n++] = *h;
	return 0;
}

/* check_sphere_hits: the ray from (C, C, -10) up +z through the centre
 * crosses the spheres r = 5 and r = 8 at z = C -+ r.  Oracle: the hits in
 * order of t, t the distance from the origin, P on the ray at |P - c| = r
 * to the interpolation's error (the ray runs half a cell from the samples
 * along x and y: the field there is about sqrt(r^2 + 0.5), so the
 * crossing moves by about 0.5 / 2r; under 0.1 for r >= 5), n unit and
 * against the ray, entering as f rises. */
static void
check_sphere_hits(const hits *x)
{
	static const double want_z[4] = { C - 8, C - 5, C + 5, C + 8 };
	static const int want_iso[4] = { 1, 0, 0, 1 };   /* iso 5 first */

	assert_int_equal(x->n, 4);
	for (int i = 0; i < 4; i++) {
		const vx_hit *h = &x->h[i];
		double nl = sqrt(h->n[0] * h->n[0] + h->n[1] * h->n[1] +
		    h->n[2] * h->n[2]);

		assert_int_equal(h->iso, want_iso[i]);
		assert_int_equal(h->entering, i >= 2);
		assert_true(fabs(h->P[2] - want_z[i]) < 0.1);
		assert_true(fabs(h->t - (h->P[2] + 10)) < 1e-9);
		assert_true(fabs(h->P[0] - C) < 1e-9 && fabs(h->P[1] - C) < 1e-9);
		assert_true(fabs(nl - 1) < 1e-9);
		assert_true(h->n[2] < -0.99);          /* against +z */
		if (i > 0)
			assert_true(h->t > x->h[i - 1].t);
	}
}

static void
add_two(vx_surfaces *sf, double op5, double op8)
{
	vx_err e = { 0, "" };

	assert_int_equal(vx_surfaces_add(sf, 5, 0, op5, &e), 0);
	assert_int_equal(vx_surfaces_add(sf, 8, 1, op8, &e), 1);
}

/* trace_volume_and_mesh: vx_surf_trace over the volume (with and without
 * a hierarchy) and over its tet split gives the same crossings (see
 * check_sphere_hits). */
static void
trace_volume_and_mesh(void **state)
{
	static const double o[3] = { C, C, -10 }, d[3] = { 0, 0, 1 };
	vx_grid g;
	vx_macro m;
	vx_tetmesh mesh;
	vx_tetleaf lg;
	vx_err e = { 0, "" };
	int sizes[VX_MACRO_MAXLEV][3];

	(void)state;
	make_sphere(&g);
	vx_macro_default_sizes(VX_F32, 2, sizes);
	assert_int_equal(vx_macro_build(&m, &g, 2, (const int (*)[3])sizes, 1,
	    &e), 0);
	for (int src = 0; src < 3; src++) {
		vx_surfaces sf;
		vx_surf_stats st;
		hits x;

		memset(&st, 0, sizeof st);
		memset(&x, 0, sizeof x);
		vx_surfaces_init(&sf);
		if (src < 2)
			vx_surfaces_volume(&sf, &g, src ? &m : NULL,
			    VX_CELL_EXACT, 0, 1e-3);
		else {
			assert_int_equal(vx_tetsynth_from_grid(&mesh, &g, 6, &e),
			    0);
			assert_int_equal(vx_tetleaf_build(&lg, &mesh, 1, &e), 0);
			vx_surfaces_mesh(&sf, &mesh, &lg, 1e-3);
		}
		add_two(&sf, 1, 1);
		assert_int_equal(vx_surf_trace(&sf, o, d, INFINITY, collect, &x,
		    &st), 0);
		check_sphere_hits(&x);
		assert_true(src < 2 ? st.iso.hits == 4 : st.tet.hits == 4);
		if (src == 2) {
			vx_tetleaf_free(&lg);
			vx_tetmesh_free(&mesh);
		}
	}
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* visibility, from hits whose normals face the eye (-z), toward -z: from
 * the outer sphere's near side the sky is open; from its far side the ray
 * crosses the inner sphere twice and the outer one's near side (it starts
 * just off its own surface, on the lit side, inside).  Oracle: 1; and 0
 * with opaque spheres, else the product of (1 - opacity) over the
 * crossings: with opacities 0.5 (r 5) and 0.25 (r 8), 0.5 0.5 0.75. */
static void
visibility(void **state)
{
	static const double o[3] = { C, C, -10 }, d[3] = { 0, 0, 1 };
	static const double down[3] = { 0, 0, -1 };
	vx_grid g;
	vx_err e = { 0, "" };

	(void)state;
	make_sphere(&g);
	for (int k = 0; k < 2; k++) {
		vx_surfaces sf;
		vx_surf_stats st;
		hits x;
		double v;

		memset(&st, 0, sizeof st);
		memset(&x, 0, sizeof x);
		vx_surfaces_init(&sf);
		vx_surfaces_volume(&sf, &g, NULL, VX_CELL_EXACT, 0, 1e-3);
		add_two(&sf, k ? 0.5 : 1, k ? 0.25 : 1);
		vx_surf_trace(&sf, o, d, INFINITY, collect, &x, &st);
		assert_int_equal(x.n, 4);
		/* the last hit: the outer sphere's far side */
		v = vx_surf_visibility(&sf, &x.h[3], down, INFINITY, &st);
		assert_true(k ? fabs(v - 0.5 * 0.5 * 0.75) < 1e-12 : v == 0);
		/* the first: its near side */
		assert_true(vx_surf_visibility(&sf, &x.h[0], down, INFINITY,
		    &st) == 1);
		/* a point light nearer than the inner sphere: nothing
		 * between */
		assert_true(vx_surf_visibility(&sf, &x.h[3], down, 2, &st) == 1);
		assert_int_equal(st.shadow, 3);
		(void)e;
	}
	vx_grid_free(&g);
}

/* lights: a point light with inverse-square falloff, a directional one,
 * a headlight of each camera kind.  Oracle: the definitions of vx_scene.h
 * (direction toward the light, radiance color x intensity / dist^2). */
static void
lights(void **state)
{
	static const double P[3] = { 1, 2, 3 };
	vx_scene s;
	double L[3], dist, rad[3], lo[3] = { 0, 0, 0 }, hi[3] = { 4, 4, 4 };
	vx_err e = { 0, "" };

	(void)state;
	vx_scene_init(&s);
	s.nlight = 3;
	memset(s.light, 0, 3 * sizeof s.light[0]);
	s.light[0].type = VX_LIGHT_POINT;
	s.light[0].position[0] = 1;
	s.light[0].position[1] = 2;
	s.light[0].position[2] = 7;
	s.light[0].color[0] = s.light[0].color[1] = s.light[0].color[2] = 1;
	s.light[0].color[1] = 0.5;
	s.light[0].intensity = 8;
	s.light[0].falloff = VX_FALLOFF_INVERSE_SQUARE;
	s.light[1].type = VX_LIGHT_DIRECTIONAL;
	s.light[1].direction[0] = 0;
	s.light[1].direction[1] = -3;
	s.light[1].direction[2] = 0;
	s.light[1].color[0] = s.light[1].color[1] = s.light[1].color[2] = 1;
	s.light[1].intensity = 2;
	s.light[2].type = VX_LIGHT_HEADLIGHT;
	s.light[2].color[0] = s.light[2].color[1] = s.light[2].color[2] = 1;
	s.light[2].intensity = 1;
	s.light[2].falloff = VX_FALLOFF_NONE;

	vx_surf_light(&s, 0, P, L, &dist, rad);
	assert_true(dist == 4 && L[0] == 0 && L[1] == 0 && L[2] == 1);
	assert_true(rad[0] == 0.5 && rad[1] == 0.25 && rad[2] == 0.5);
	vx_surf_light(&s, 1, P, L, &dist, rad);
	assert_true(isinf(dist) && L[0] == 0 && L[1] == 1 && L[2] == 0);
	assert_true(rad[0] == 2 && rad[1] == 2 && rad[2] == 2);
	/* headlight: toward the eye (perspective), against forward
	 * (orthographic, no distance) */
	assert_int_equal(vx_camera_resolve(&s.camera, lo, hi, &e), 0);
	vx_surf_light(&s, 2, P, L, &dist, rad);
	for (int a = 0; a < 3; a++)
		assert_true(fabs(L[a] * dist - (s.camera.o[a] - P[a])) < 1e-9);
	s.camera.projection = VX_ORTHOGRAPHIC;
	s.camera.ready = 0;
	assert_int_equal(vx_camera_resolve(&s.camera, lo, hi, &e), 0);
	vx_surf_light(&s, 2, P, L, &dist, rad);
	assert_true(isinf(dist));
	for (int a = 0; a < 3; a++)
		assert_true(L[a] == -s.camera.fwd[a]);
}

/* shade_irradiance: one unshadowed light, no highlight, no ambient:
 * vx_surf_shade's color equals vx_surf_shade_irradiance's with E the
 * irradiance the light delivers, pi rad n.L (vx_gi.h's units; the same
 * product in another order: to 1e-12); with an ambient term, a light
 * behind the surface adds nothing (ambient times albedo, exactly); a
 * texture-less surface's albedo is its color. */
static void
shade_irradiance(void **state)
{
	static const double o[3] = { C, C, -10 }, d[3] = { 0, 0, 1 };
	vx_grid g;
	vx_scene s;
	vx_plan p;
	vx_surfaces sf;
	vx_surf_stats st;
	vx_err e = { 0, "" };
	double iso = 5, col[3], col2[3], E[3], alb[3], L[3], dist, rad[3];
	hits x;

	(void)state;
	make_sphere(&g);
	vx_scene_init(&s);
	assert_int_equal(vx_scene_set_iso(&s, &iso, 1, &e), 0);
	s.surface[0].m.color[0] = 0.8;
	s.surface[0].m.color[1] = 0.4;
	s.surface[0].m.color[2] = 0.2;
	s.surface[0].m.ks = 0;
	s.ambient[0] = s.ambient[1] = s.ambient[2] = 0;
	s.ambient_intensity = 1;
	s.effects = 0;                    /* no shadows, no highlights */
	s.default_lights = 0;
	s.nlight = 1;
	memset(&s.light[0], 0, sizeof s.light[0]);
	s.light[0].type = VX_LIGHT_DIRECTIONAL;
	s.light[0].direction[0] = 1;
	s.light[0].direction[1] = 0.5;
	s.light[0].direction[2] = 2;       /* toward +z: lights the -z side */
	s.light[0].color[0] = s.light[0].color[1] = s.light[0].color[2] = 1;
	s.light[0].intensity = 1.5;
	vx_scene_plan_isosurface(&s, &p);
	vx_surfaces_init(&sf);
	vx_surfaces_volume(&sf, &g, NULL, VX_CELL_EXACT, 0, 1e-3);
	assert_int_equal(vx_surfaces_scene(&sf, &s, &p, NULL, &e), 0);
	assert_int_equal(sf.niso, 1);
	memset(&st, 0, sizeof st);
	memset(&x, 0, sizeof x);
	vx_surf_trace(&sf, o, d, INFINITY, collect, &x, &st);
	assert_int_equal(x.n, 2);
	vx_surf_albedo(&sf, &x.h[0], alb);
	assert_true(alb[0] == 0.8 && alb[1] == 0.4 && alb[2] == 0.2);
	/* the near side faces the light */
	vx_surf_shade(&sf, &x.h[0], d, col, &st);
	vx_surf_light(&s, 0, x.h[0].P, L, &dist, rad);
	for (int a = 0; a < 3; a++)
		E[a] = 3.14159265358979323846 * rad[a] * (x.h[0].n[0] * L[0] +
		    x.h[0].n[1] * L[1] + x.h[0].n[2] * L[2]);
	assert_true(E[0] > 0);
	vx_surf_shade_irradiance(&sf, &x.h[0], E, col2);
	for (int a = 0; a < 3; a++)
		assert_true(fabs(col[a] - col2[a]) < 1e-12);
	assert_true(col[0] > 0.01);
	/* the light turned round, behind the surface: ambient only */
	s.light[0].direction[2] = -2;
	s.ambient[0] = s.ambient[1] = s.ambient[2] = 0.1;
	vx_surf_shade(&sf, &x.h[0], d, col, &st);
	for (int a = 0; a < 3; a++)
		assert_true(col[a] == 0.1 * alb[a]);
	assert_int_equal(st.shaded, 2);
	assert_int_equal(st.shadow, 0);
	vx_grid_free(&g);
}

/* no_surface: a plan that draws nothing is an error (VX_EDATA); more than
 * VX_ISO_MAX isovalues are refused one by one. */
static void
no_surface(void **state)
{
	vx_surfaces sf;
	vx_scene s;
	vx_plan p;
	vx_err e = { 0, "" };

	(void)state;
	vx_scene_init(&s);
	s.nsurface = 0;
	vx_scene_plan_isosurface(&s, &p);
	vx_surfaces_init(&sf);
	assert_int_equal(vx_surfaces_scene(&sf, &s, &p, NULL, &e), VX_EDATA);
	vx_surfaces_init(&sf);
	for (int i = 0; i < VX_ISO_MAX; i++)
		assert_int_equal(vx_surfaces_add(&sf, i, 0, 1, &e), i);
	assert_int_equal(vx_surfaces_add(&sf, 99, 0, 1, &e), -1);
	assert_int_equal(e.code, VX_EDATA);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(trace_volume_and_mesh),
		cmocka_unit_test(visibility),
		cmocka_unit_test(lights),
		cmocka_unit_test(shade_irradiance),
		cmocka_unit_test(no_surface),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
