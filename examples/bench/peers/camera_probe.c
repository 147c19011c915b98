/* camera_probe.c: print voxlux's own rays (vx_camera_ray) for a few pixels, so
 * that selftest.py can hold the peers' camera code (and the scenes camera.py
 * writes) against the library's. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vx_camera.h"
#include "vx_err.h"
#include "vx_scene.h"

/* print_rays: "px py ox oy oz dx dy dz" for the centre of each pixel given as
 * pairs in argv[first..argc). */
static void
print_rays(const vx_camera *c, int argc, char **argv, int first)
{
	int i;

	for (i = first; i + 1 < argc; i += 2) {
		int px = atoi(argv[i]), py = atoi(argv[i + 1]);
		double o[3], d[3];

		vx_camera_ray(c, px + 0.5, py + 0.5, o, d);
		printf("%d %d %.17g %.17g %.17g %.17g %.17g %.17g\n", px, py,
		    o[0], o[1], o[2], d[0], d[1], d[2]);
	}
}

/* scene_rays: camera_probe scene FILE PX PY ...: the rays of a scene file's
 * (explicit) camera; also prints "surfaces N iso V" on stderr. */
static int
scene_rays(int argc, char **argv)
{
	static vx_scene s;
	vx_err e;
	FILE *f = fopen(argv[2], "r");

	memset(&e, 0, sizeof e);
	if (!f) {
		perror(argv[2]);
		return 66;
	}
	if (vx_scene_read(&s, f, &e) != 0 ||
	    vx_camera_resolve(&s.camera, NULL, NULL, &e) != 0) {
		fprintf(stderr, "camera_probe: %s: %s\n", argv[2], e.msg);
		fclose(f);
		return 65;
	}
	fclose(f);
	fprintf(stderr, "surfaces %d", s.nsurface);
	if (s.nsurface > 0)
		fprintf(stderr, " iso %.17g", s.surface[0].iso);
	fprintf(stderr, "\n");
	print_rays(&s.camera, argc, argv, 3);
	return 0;
}

/* usage: camera_probe persp|ortho FOV_OR_WIDTH W H EX EY EZ LX LY LZ UX UY UZ PX PY ...
 *        camera_probe scene FILE PX PY ...
 * prints "px py ox oy oz dx dy dz" for the centre of each pixel (px, py). */
int
main(int argc, char **argv)
{
	vx_camera c;
	vx_err e;
	int i;

	if (argc >= 3 && strcmp(argv[1], "scene") == 0 && (argc - 3) % 2 == 0)
		return scene_rays(argc, argv);
	if (argc < 14 || (argc - 14) % 2 != 0) {
		fprintf(stderr, "usage: camera_probe persp|ortho FOV_OR_WIDTH W H "
		    "EX EY EZ LX LY LZ UX UY UZ [PX PY]...\n"
		    "       camera_probe scene FILE [PX PY]...\n");
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
	print_rays(&c, argc, argv, 14);
	return 0;
}
