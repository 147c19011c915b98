/* mkseed.c: writes the stream seeds of the fuzz corpus with the library's
 * own writers (tests/fuzz/mkcorpus.sh builds and runs it):
 *   mkseed DIR   ->  DIR/volume-mcel.vxs  u8 5x4x3 VOLM + its MCEL (2 levels)
 *                    DIR/bricked-zlib.vxs i16 6x5x4 bricked 2x2x2, zlib
 *                    DIR/tetm.vxs         TETM of the 6-tet unit cube
 *                    DIR/imag.vxs         IMAG 3x2 RGBA + hist + note
 *                    DIR/explicit.vxs     MCEL with explicit leaves
 *                    DIR/scene.vxs        SCNE (two surfaces, a light) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vx_grid.h"
#include "vx_image.h"
#include "vx_macro.h"
#include "vx_macroio.h"
#include "vx_scene.h"
#include "vx_stream.h"
#include "vx_tetimport.h"
#include "vx_tetleaf.h"

static vx_err err;

static void
die(int rc)
{
	if (rc) {
		fprintf(stderr, "mkseed: %s\n", err.msg);
		exit(rc);
	}
}

static void
save(const char *dir, const char *name, vx_stream *s)
{
	char path[4096];
	FILE *f;

	snprintf(path, sizeof path, "%s/%s", dir, name);
	if ((f = fopen(path, "wb")) == NULL) {
		perror(path);
		exit(73);
	}
	die(vx_stream_write(s, f, &err));
	fclose(f);
	vx_stream_free(s);
}

static double
fn(const double p[3], void *ctx)
{
	(void)ctx;
	return p[0] + 2 * p[1] + 3 * p[2];
}

int
main(int argc, char **argv)
{
	int sizes[2][3] = { { 2, 2, 2 }, { 2, 2, 1 } };
	int64_t d1[3] = { 5, 4, 3 }, d2[3] = { 6, 5, 4 }, n[3] = { 2, 2, 1 };
	float leaf[8] = { 0, 1, 2, 3, 1, 1, 5, 4 };
	double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
	vx_stream s;
	vx_chunk c;
	vx_grid g;
	vx_macro m;
	vx_tetmesh t;
	vx_image img;
	vx_scene sc;

	if (argc != 2) {
		fprintf(stderr, "usage: mkseed DIR\n");
		return 64;
	}
	vx_stream_init(&s);
	die(vx_grid_alloc(&g, d1, VX_U8, NULL, &err));
	for (int64_t z = 0; z < d1[2]; z++)
		for (int64_t y = 0; y < d1[1]; y++)
			for (int64_t x = 0; x < d1[0]; x++)
				vx_grid_set(&g, x, y, z, (double)(x + 5 * y + 20 * z));
	vx_grid_range(&g);
	die(vx_grid_to_chunk(&g, 0, &c, &err));
	die(vx_stream_append(&s, &c, &err));
	die(vx_macro_build(&m, &g, 2, sizes, 1, &err));
	die(vx_macro_to_chunk(&m, 0, &c, &err));
	die(vx_stream_append(&s, &c, &err));
	vx_macro_free(&m);
	vx_grid_free(&g);
	save(argv[1], "volume-mcel.vxs", &s);

	die(vx_grid_alloc(&g, d2, VX_I16, "bricked 2x2x2", &err));
	for (int64_t z = 0; z < d2[2]; z++)
		for (int64_t y = 0; y < d2[1]; y++)
			for (int64_t x = 0; x < d2[0]; x++)
				vx_grid_set(&g, x, y, z, (double)(x - 7 * y + z));
	vx_grid_range(&g);
	die(vx_grid_to_chunk(&g, 6, &c, &err));
	die(vx_stream_append(&s, &c, &err));
	vx_grid_free(&g);
	save(argv[1], "bricked-zlib.vxs", &s);

	die(vx_tetsynth_cube(&t, lo, hi, fn, NULL, &err));
	die(vx_tetmesh_to_chunk(&t, 0, &c, &err));
	die(vx_stream_append(&s, &c, &err));
	vx_tetmesh_free(&t);
	save(argv[1], "tetm.vxs", &s);

	die(vx_image_alloc(&img, 3, 2, 4, &err));
	for (size_t i = 0; i < vx_image_nvalue(&img); i++)
		img.px[i] = (float)i / 24;
	die(vx_image_to_chunk(&img, 0, &c, &err));
	die(vx_stream_append(&s, &c, &err));
	vx_image_free(&img);
	die(vx_stream_history_add(&s, "mkseed 1", &err));
	memcpy(c.type, "note", 5);
	c.data = (unsigned char *)strdup("free text");
	c.len = 9;
	c.offset = 0;
	die(vx_stream_append(&s, &c, &err));
	save(argv[1], "imag.vxs", &s);

	die(vx_macro_build_explicit(&m, n, leaf, 1, sizes, 1, &err));
	die(vx_macro_to_chunk(&m, 0, &c, &err));
	die(vx_stream_append(&s, &c, &err));
	vx_macro_free(&m);
	save(argv[1], "explicit.vxs", &s);

	vx_scene_init(&sc);
	die(vx_scene_apply(&sc, "surface iso 0.5 color 1 0 0 opacity 0.5", &err));
	die(vx_scene_apply(&sc, "surface iso 2", &err));
	die(vx_scene_apply(&sc, "light point position 1 2 3", &err));
	die(vx_scene_to_chunk(&sc, 0, &c, &err));
	die(vx_stream_append(&s, &c, &err));
	save(argv[1], "scene.vxs", &s);
	return 0;
}
