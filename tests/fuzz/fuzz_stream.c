/* fuzz_stream.c: libFuzzer target for the stream reader and every chunk
 * decoder: vx_stream_read_mem, then VOLM (vx_grid_from_chunk), IMAG
 * (vx_image_from_chunk), MCEL (vx_macro_from_chunk, and against its volume)
 * TETM (vx_tetmesh_from_chunk, and its TLEF leaf grid, one ray through it),
 * TLEF (vx_tetleaf_from_chunk) and SCNE (vx_scene_from_chunk); a stream
 * that reads is written back and must read back to the same chunks. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "vx_macro.h"
#include "vx_macroio.h"
#include "vx_scene.h"
#include "vx_tetimport.h"
#include "vx_tetleaf.h"

static double
touch_macro(const vx_macro *m)
{
	double sum = 0;

	if (m->nlev < 0 || m->nlev > VX_MACRO_MAXLEV)
		fuzz_fail("macro: nlev out of range");
	for (int l = m->explicit_leaves ? 0 : 1; l <= m->nlev; l++) {
		size_t n = 1;

		for (int a = 0; a < 3; a++) {
			if (m->dims[l][a] < 0)
				fuzz_fail("macro: negative dims");
			n *= (size_t)m->dims[l][a];
		}
		for (size_t i = 0; i < 2 * n; i++)
			sum += m->mm[l][i] == m->mm[l][i];
	}
	return sum + (m->root[0] <= m->root[1]);
}

/* roundtrip: write s to memory, read it back, compare chunk by chunk. */
static void
roundtrip(const vx_stream *s)
{
	char *buf = NULL;
	size_t n = 0;
	vx_stream r;
	vx_err e;
	FILE *f;
	int rc;

	vx_err_clear(&e);
	if ((f = open_memstream(&buf, &n)) == NULL)
		return;
	rc = vx_stream_write(s, f, &e);
	fclose(f);
	if (rc != 0)
		fuzz_fail("a stream that was read cannot be written");
	vx_stream_init(&r);
	if (vx_stream_read_mem(&r, buf, n, &e) != 0)
		fuzz_fail("a written stream does not read back");
	if (r.n != s->n)
		fuzz_fail("roundtrip changed the chunk count");
	for (size_t i = 0; i < r.n; i++)
		if (strcmp(r.chunk[i].type, s->chunk[i].type) != 0 ||
		    r.chunk[i].len != s->chunk[i].len ||
		    (r.chunk[i].len &&
		    memcmp(r.chunk[i].data, s->chunk[i].data, r.chunk[i].len)))
			fuzz_fail("roundtrip changed a chunk");
	vx_stream_free(&r);
	free(buf);
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	volatile double sink = 0;
	vx_stream s;
	vx_err e;
	size_t hl;
	int rc;

	vx_err_clear(&e);
	vx_stream_init(&s);
	rc = vx_stream_read_mem(&s, data, size, &e);
	fuzz_err_check(rc, &e);
	if (rc != 0) {
		vx_stream_free(&s);
		return 0;
	}
	roundtrip(&s);
	if (vx_stream_history(&s, &hl) != NULL)
		sink += (double)hl;
	for (size_t i = 0; i < s.n; i++) {
		const vx_chunk *c = &s.chunk[i];

		if (!vx_chunk_type_valid(c->type))
			fuzz_fail("reader kept an invalid chunk type");
		vx_err_clear(&e);
		if (strcmp(c->type, VX_CHUNK_VOLUME) == 0) {
			vx_grid g;
			vx_macro m;
			int status;
			long idx;

			rc = vx_grid_from_chunk(&g, c, &e);
			fuzz_err_check(rc, &e);
			if (rc == 0) {
				vx_grid gv;
				vx_err ev = { 0, "" };

				sink += fuzz_grid_touch(&g);
				/* the samples in place: the same grid, or the
				 * same error */
				if (vx_grid_view_chunk(&gv, c, &ev) != 0)
					fuzz_fail("view refused what the copy took");
				sink += fuzz_grid_touch(&gv);
				if (gv.nsample != g.nsample || memcmp(gv.data,
				    g.data, g.nsample * vx_type_size(g.type)) != 0)
					fuzz_fail("view and copy differ");
				vx_grid_free(&gv);
				vx_err_clear(&e);
				rc = vx_macro_from_stream(&m, &s, &g, (long)i,
				    &status, &idx, &e);
				fuzz_err_check(rc, &e);
				/* m holds memory only when loaded */
				if (rc == 0 && status == VX_MACRO_LOADED) {
					sink += touch_macro(&m);
					vx_macro_free(&m);
				}
				vx_grid_free(&g);
			} else {
				vx_grid gv;
				vx_err ev = { 0, "" };

				if (vx_grid_view_chunk(&gv, c, &ev) == 0)
					fuzz_fail("view took what the copy refused");
			}
		} else if (strcmp(c->type, VX_CHUNK_IMAGE) == 0) {
			vx_image img;

			rc = vx_image_from_chunk(&img, c, &e);
			fuzz_err_check(rc, &e);
			if (rc == 0) {
				sink += fuzz_image_touch(&img);
				vx_image_free(&img);
			}
		} else if (strcmp(c->type, VX_CHUNK_MACRO) == 0) {
			vx_macro m;

			rc = vx_macro_from_chunk(&m, c, &e);
			fuzz_err_check(rc, &e);
			if (rc == 0) {
				sink += touch_macro(&m);
				vx_macro_free(&m);
			}
		} else if (strcmp(c->type, VX_CHUNK_SCENE) == 0) {
			vx_scene sc;

			rc = vx_scene_from_chunk(&sc, c, &e);
			fuzz_err_check(rc, &e);
			if (rc == 0)
				sink += sc.nsurface + sc.nlight;
		} else if (strcmp(c->type, VX_CHUNK_TETMESH) == 0) {
			vx_tetmesh m;

			rc = vx_tetmesh_from_chunk(&m, c, &e);
			fuzz_err_check(rc, &e);
			if (rc == 0) {
				vx_tetleaf lg;
				int status;
				long idx;

				sink += fuzz_tetmesh_touch(&m, 0);
				/* its leaf grid, when the stream has one that
				 * matches: trace one ray through it */
				vx_err_clear(&e);
				rc = vx_tetleaf_from_stream(&lg, &s, &m, &status,
				    &idx, &e);
				fuzz_err_check(rc, &e);
				if (rc == 0 && status == VX_MACRO_LOADED) {
					double o[3], d[3] = { 0.3, 0.5, 0.8 };
					double iso = (m.vmin + m.vmax) / 2;
					vx_tethit h;
					for (int a = 0; a < 3; a++)
						o[a] = m.bmin[a] - d[a];
					sink += vx_tetleaf_nearest(&lg, &m, o, d, &iso,
					    1, 0, INFINITY, &h, NULL);
					vx_tetleaf_free(&lg);
				}
				vx_tetmesh_free(&m);
			}
		} else if (strcmp(c->type, VX_CHUNK_TETLEAF) == 0) {
			vx_tetleaf lg;
			vx_tetleaf_ident id;

			rc = vx_tetleaf_from_chunk(&lg, &id, c, &e);
			fuzz_err_check(rc, &e);
			if (rc == 0) {
				/* every list entry and every stored range */
				for (size_t l = 0; l < lg.nleaf; l++)
					for (uint32_t k = lg.off[l]; k < lg.off[l + 1];
					    k++)
						if (lg.idx[k] >= id.ntet)
							fuzz_fail("tlef: index out of range");
				sink += touch_macro(&lg.mc);
				vx_tetleaf_free(&lg);
			}
		}
	}
	vx_stream_free(&s);
	(void)sink;
	return 0;
}
