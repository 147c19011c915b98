/* fuzz.h: helpers shared by the libFuzzer targets (tests/fuzz/fuzz_*.c):
 * touch every element of a decoded object so ASan sees any out-of-bounds
 * read, and check the invariants a successful decode promises (abort() on a
 * broken one, which libFuzzer reports as a crash). */
#ifndef VX_FUZZ_H
#define VX_FUZZ_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vx_err.h"
#include "vx_grid.h"
#include "vx_image.h"
#include "vx_imageio.h"
#include "vx_stream.h"
#include "vx_tetimport.h"
#include "vx_tetleaf.h"

/* fuzz_fail: an invariant did not hold: say which and abort. */
static inline void
fuzz_fail(const char *what)
{
	fprintf(stderr, "fuzz invariant broken: %s\n", what);
	abort();
}

/* fuzz_err_check: a failed call must leave a nonempty message and a
 * sysexits code; a successful one must return 0. */
static inline void
fuzz_err_check(int rc, const vx_err *e)
{
	if (rc == 0)
		return;
	if (rc != e->code)
		fuzz_fail("returned code differs from e->code");
	if (rc < 64 || rc > 78)
		fuzz_fail("error code is not a sysexits value");
	if (e->msg[0] == '\0' || strlen(e->msg) >= VX_ERR_MSG)
		fuzz_fail("empty or unterminated error message");
	if (strchr(e->msg, '\n') != NULL)
		fuzz_fail("newline in error message");
}

/* fuzz_grid_touch: read every real sample through the offset tables (each
 * index must lie inside the allocation), fetch every cell's corners, and
 * check vx_grid_range against the samples. */
static inline double
fuzz_grid_touch(vx_grid *g)
{
	double sum = 0, lo = INFINITY, hi = -INFINITY;
	int64_t x, y, z;
	float c[8];

	for (int a = 0; a < 3; a++)
		if (g->dims[a] < 1 || !(g->spacing[a] > 0) ||
		    !isfinite(g->spacing[a]) || !isfinite(g->origin[a]))
			fuzz_fail("grid: bad dims, spacing or origin");
	if (g->nsample != vx_layout_nsample(&g->lay))
		fuzz_fail("grid: nsample differs from the layout's");
	for (z = 0; z < g->dims[2]; z++)
		for (y = 0; y < g->dims[1]; y++)
			for (x = 0; x < g->dims[0]; x++) {
				double v;

				if (vx_grid_index(g, x, y, z) >= g->nsample)
					fuzz_fail("grid: index beyond nsample");
				v = vx_grid_get(g, x, y, z);
				if (isfinite(v)) {
					sum += v;
					lo = v < lo ? v : lo;
					hi = v > hi ? v : hi;
				}
			}
	for (z = 0; z + 1 < g->dims[2]; z++)
		for (y = 0; y + 1 < g->dims[1]; y++)
			for (x = 0; x + 1 < g->dims[0]; x++) {
				vx_grid_cell(g, x, y, z, c);
				sum += c[7];
			}
	/* a header's range is taken on trust (formats/stream.md), so only the
	 * recomputed one is checked */
	vx_grid_range(g);
	if (isfinite(lo) != g->has_range ||
	    (g->has_range && (g->vmin != lo || g->vmax != hi)))
		fuzz_fail("grid: vx_grid_range disagrees with the samples");
	return sum;
}

/* fuzz_image_touch: read every value of a decoded image. */
static inline double
fuzz_image_touch(const vx_image *img)
{
	double sum = 0;
	size_t n;

	if (img->w < 1 || img->h < 1 || img->nc < 1 || img->nc > 4 ||
	    img->px == NULL)
		fuzz_fail("image: bad size or no pixels");
	n = vx_image_nvalue(img);
	if (n / (size_t)img->nc / (size_t)img->w != (size_t)img->h)
		fuzz_fail("image: nvalue overflows");
	for (size_t i = 0; i < n; i++)
		if (isfinite(img->px[i]))
			sum += img->px[i];
	return sum;
}

/* fuzz_tetmesh_touch: read every point, index and value of a validated
 * mesh; with deep set, also round-trip it through a TETM chunk (it must
 * come back identical), build its leaf grid and cast one ray through it. */
static inline double
fuzz_tetmesh_touch(const vx_tetmesh *m, int deep)
{
	double sum = 0;
	vx_err e;

	for (size_t i = 0; i < 3 * m->npoint; i++) {
		if (!isfinite(m->pts[i]) || fabs(m->pts[i]) > VX_TETMESH_COORD_MAX)
			fuzz_fail("tetmesh: coordinate beyond the limit");
		sum += m->pts[i];
	}
	for (size_t i = 0; i < 4 * m->ntet; i++) {
		if (m->tet[i] >= m->npoint)
			fuzz_fail("tetmesh: index beyond npoint after validate");
		sum += m->val[m->tet[i]] == m->val[m->tet[i]];
	}
	for (size_t t = 0; t < m->ntet && t < 64; t++)
		sum += vx_tetmesh_degenerate(m, t);
	if (!deep)
		return sum;
	vx_err_clear(&e);
	{
		vx_chunk c;
		vx_tetmesh b;

		if (vx_tetmesh_to_chunk(m, 0, &c, &e) != 0)
			fuzz_fail("tetmesh: a valid mesh cannot be written");
		if (vx_tetmesh_from_chunk(&b, &c, &e) != 0)
			fuzz_fail("tetmesh: a written mesh does not read back");
		if (b.npoint != m->npoint || b.ntet != m->ntet ||
		    memcmp(b.pts, m->pts, 3 * m->npoint * sizeof *m->pts) ||
		    memcmp(b.tet, m->tet, 4 * m->ntet * sizeof *m->tet) ||
		    memcmp(b.val, m->val, m->npoint * sizeof *m->val))
			fuzz_fail("tetmesh: chunk round trip changed the mesh");
		vx_tetmesh_free(&b);
		vx_chunk_free(&c);
	}
	if (m->ntet > 0 && m->ntet <= 4096) {
		vx_tetleaf lg;
		vx_tethit hit;
		double o[3], d[3] = { 0.3, 0.2, 1 }, iso[2];
		int rc;

		rc = vx_tetleaf_build(&lg, m, 1, &e);
		fuzz_err_check(rc, &e);
		if (rc == 0) {
			for (int a = 0; a < 3; a++)
				o[a] = (m->bmin[a] + m->bmax[a]) / 2 - d[a] *
				    (m->bmax[2] - m->bmin[2] + 1);
			iso[0] = m->has_range ? (m->vmin + m->vmax) / 2 : 0;
			iso[1] = m->has_range ? m->vmin : 1;
			sum += vx_tetleaf_nearest(&lg, m, o, d, iso, 2, 0,
			    INFINITY, &hit, NULL);
			vx_tetleaf_free(&lg);
		}
	}
	return sum;
}

#endif
