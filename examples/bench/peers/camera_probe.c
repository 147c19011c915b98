/* camera_probe.c: print voxlux's own rays (vx_camera_ray) for a few pixels, so
 * that selftest.py can hold the peers' camera code against the library's. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vx_camera.h"
#include "vx_err.h"

/* usage: camera_probe persp|ortho FOV_OR_WIDTH W H EX EY EZ LX LY LZ UX UY UZ PX PY ...
 * prints "px py ox oy oz dx dy dz" for the centre of each pixel (px, py). */
int
main(int argc, char **argv)
{
	vx_camera c;
	vx_err e;
	int i;

	if (argc < 14 || (argc - 14) % 2 != 0) {
		fprintf(stderr, "usage: camera_probe persp|ortho FOV_OR_WIDTH W H "
		    "EX EY EZ LX LY LZ UX UY UZ [PX PY]...\n");
		return 64;
	}
	memset(&e, 0, sizeof e);
	vx_camera_init(&c);
	c.is_auto = 0;
	if (strcmp(argv[1], "ortho") == 0) {
		c.projection = VX_ORTHOGRAPHIC;
		c.view_width = atof(argv[2]);
	} else {
		c.projection = VX_PERSPECTIVE;
		c.fov = atof(argv[2]);
	}
	c.w = atoi(argv[3]);
	c.h = atoi(argv[4]);
	for (i = 0; i < 3; i++) {
		c.eye[i] = atof(argv[5 + i]);
		c.look[i] = atof(argv[8 + i]);
		c.up[i] = atof(argv[11 + i]);
	}
	c.has_up = 1;
	if (vx_camera_resolve(&c, NULL, NULL, &e) != 0) {
		fprintf(stderr, "camera_probe: %s\n", e.msg);
		return 65;
	}
	for (i = 14; i + 1 < argc; i += 2) {
		int px = atoi(argv[i]), py = atoi(argv[i + 1]);
		double o[3], d[3];

		vx_camera_ray(&c, px + 0.5, py + 0.5, o, d);
		printf("%d %d %.17g %.17g %.17g %.17g %.17g %.17g\n", px, py,
		    o[0], o[1], o[2], d[0], d[1], d[2]);
	}
	return 0;
}
