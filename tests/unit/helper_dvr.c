/* helper_dvr.c: the slab scenes of the direct-volume-rendering tests. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "helper_dvr.h"

void
dvr_prepare(const char *text, const vx_grid *g, const vx_dvr_opts *o,
    vx_scene *s, vx_tf *tf, vx_dvr_decide *d, vx_plan *p)
{
	vx_err e = { 0, "" };
	double lo[3], hi[3];

	if (vx_scene_parse(s, text, strlen(text), &e) != 0)
		fail_msg("%s", e.msg);
	vx_tf_init(tf);
	if (vx_tf_apply_scene(tf, s, &e) != 0 || vx_tf_check(tf, &e) != 0)
		fail_msg("%s", e.msg);
	vx_dvr_plan(s, tf, o, d, p);
	if (g != NULL) {
		vx_grid_box(g, lo, hi);
		if (vx_camera_resolve(&s->camera, lo, hi, &e) != 0)
			fail_msg("%s", e.msg);
	}
}

void
zgrid(vx_grid *g, int nx, int ny, int nz, double (*f)(int))
{
	int64_t dims[3] = { nx, ny, nz };
	vx_err e = { 0, "" };

	vx_grid_init(g);
	assert_int_equal(vx_grid_alloc(g, dims, VX_F32, NULL, &e), 0);
	for (int z = 0; z < nz; z++)
		for (int y = 0; y < ny; y++)
			for (int x = 0; x < nx; x++)
				vx_grid_set(g, x, y, z, f(z));
	vx_grid_range(g);
}

double
z_one(int z)
{
	(void)z;
	return 1;
}

double
z_slabs(int z)
{
	return z_receiver(z) + z_occluder(z);
}

double
z_receiver(int z)
{
	return z >= 6 && z <= 13 ? 1 : 0;
}

double
z_occluder(int z)
{
	return z >= 24 && z <= 29 ? 1 : 0;
}

void
wide_slab(vx_grid *g)
{
	int64_t dims[3] = { 400, 400, 40 };
	vx_err e = { 0, "" };

	vx_grid_init(g);
	assert_int_equal(vx_grid_alloc(g, dims, VX_U8, NULL, &e), 0);
	memset(g->data, 1, g->nsample);
	vx_grid_range(g);
}

void
wide_slab_scene(char *buf, size_t n, double alpha)
{
	double c = cos(30 * M_PI / 180), s = sin(30 * M_PI / 180);

	snprintf(buf, n, "camera orthographic eye %.17g 199.5 %.17g look "
	    "199.5 199.5 19.5 up 0 1 0 width 4\nimage width 4 height 4\n"
	    "light none\nambient intensity 1\neffects none\n"
	    "transfer opacity 0 %.17g\n", 199.5 + 100 * s, 19.5 + 100 * c,
	    alpha);
}
