/* tetsynth.c: synthetic tet meshes for tests and demos: rectilinear grids
 * split into 5 (alternating) or 6 (Kuhn) tets per cell, with values from a
 * function or from a volume. */
#include "vx_tetimport.h"

#include <string.h>

/* Cell corners by bits: corner c is (c & 1, (c >> 1) & 1, (c >> 2) & 1). */

/* 6 Kuhn tets: 0, e_a, e_a + e_b, 7 for each permutation (a, b, c). */
static const int kuhn[6][4] = {
	{ 0, 1, 3, 7 }, { 0, 1, 5, 7 }, { 0, 2, 3, 7 },
	{ 0, 2, 6, 7 }, { 0, 4, 5, 7 }, { 0, 4, 6, 7 },
};

/* 5 tets, after /work/shared/data's README: with v0..v7 = corners 0 1 3 2
 * 4 5 7 6, even cells (i+j+k) use (0,1,3,4) (1,2,3,6) (1,4,5,6) (3,4,6,7)
 * (1,3,4,6), odd cells (0,1,2,5) (0,2,3,7) (0,4,5,7) (2,5,6,7) (0,2,5,7). */
static const int five[2][5][4] = {
	{ { 0, 1, 2, 4 }, { 1, 3, 2, 7 }, { 1, 4, 5, 7 }, { 2, 4, 7, 6 },
	  { 1, 2, 4, 7 } },
	{ { 0, 1, 3, 5 }, { 0, 3, 2, 6 }, { 0, 4, 5, 6 }, { 3, 5, 7, 6 },
	  { 0, 3, 5, 6 } },
};

/* Sign of the template tet's volume in the unit cube. */
static int
corner_orient(const int c[4])
{
	double u[3][3];
	int i, a;

	for (i = 0; i < 3; i++)
		for (a = 0; a < 3; a++)
			u[i][a] = ((c[i + 1] >> a) & 1) - ((c[0] >> a) & 1);
	double det = u[0][0] * (u[1][1] * u[2][2] - u[1][2] * u[2][1]) -
	    u[0][1] * (u[1][0] * u[2][2] - u[1][2] * u[2][0]) +
	    u[0][2] * (u[1][0] * u[2][1] - u[1][1] * u[2][0]);
	return det > 0 ? 1 : det < 0 ? -1 : 0;
}

/* Point source: coordinates and value of lattice point (i, j, k). */
typedef void (*point_fn)(int64_t i, int64_t j, int64_t k, double p[3],
    double *v, void *ctx);

static int
build(vx_tetmesh *m, const int64_t nc[3], int split, point_fn pf, void *ctx,
    vx_err *e)
{
	int64_t np[3], i, j, k;
	size_t npoint, ncell, ntet, t = 0;
	int a, s, c;

	vx_tetmesh_init(m);
	if (split != VX_TETSPLIT_5 && split != VX_TETSPLIT_6)
		return vx_err_set(e, VX_EUSAGE, "tet split must be 5 or 6, "
		    "not %d", split);
	for (a = 0; a < 3; a++) {
		if (nc[a] < 1 || nc[a] > ((int64_t)1 << 20))
			return vx_err_set(e, VX_EDATA, "tet grid: %lld cells on "
			    "axis %d (1 .. 2^20)", (long long)nc[a], a);
		np[a] = nc[a] + 1;
	}
	if (vx_mul_size(&npoint, (size_t)np[0], (size_t)np[1]) ||
	    vx_mul_size(&npoint, npoint, (size_t)np[2]) ||
	    vx_mul_size(&ncell, (size_t)nc[0], (size_t)nc[1]) ||
	    vx_mul_size(&ncell, ncell, (size_t)nc[2]) ||
	    vx_mul_size(&ntet, ncell, (size_t)split))
		return vx_err_set(e, VX_EDATA, "tet grid too large");
	int rc = vx_tetmesh_alloc(m, npoint, ntet, e);
	if (rc != 0)
		return rc;
	for (k = 0; k < np[2]; k++)
		for (j = 0; j < np[1]; j++)
			for (i = 0; i < np[0]; i++) {
				size_t p = (size_t)(i + np[0] * (j + np[1] * k));
				double v;
				pf(i, j, k, m->pts + 3 * p, &v, ctx);
				m->val[p] = (float)v;
			}
	for (k = 0; k < nc[2]; k++)
		for (j = 0; j < nc[1]; j++)
			for (i = 0; i < nc[0]; i++) {
				uint32_t corner[8];
				for (c = 0; c < 8; c++)
					corner[c] = (uint32_t)((i + (c & 1)) +
					    np[0] * ((j + ((c >> 1) & 1)) +
					    np[1] * (k + ((c >> 2) & 1))));
				int par = (int)((i + j + k) & 1);
				for (s = 0; s < split; s++) {
					const int *tc = split == 6 ? kuhn[s] :
					    five[par][s];
					uint32_t *q = m->tet + 4 * t++;
					int swap = corner_orient(tc) < 0;
					q[0] = corner[tc[0]];
					q[1] = corner[tc[swap ? 2 : 1]];
					q[2] = corner[tc[swap ? 1 : 2]];
					q[3] = corner[tc[3]];
				}
			}
	if ((rc = vx_tetmesh_validate(m, e)) != 0)
		vx_tetmesh_free(m);
	return rc;
}

typedef struct fn_ctx {
	const int64_t *nc;
	const double *lo, *hi;
	vx_tetsynth_fn fn;
	void *ctx;
} fn_ctx;

static void
fn_point(int64_t i, int64_t j, int64_t k, double p[3], double *v, void *c)
{
	const fn_ctx *f = c;
	int64_t ix[3] = { i, j, k };
	int a;

	for (a = 0; a < 3; a++)
		p[a] = ix[a] == f->nc[a] ? f->hi[a] : f->lo[a] +
		    (f->hi[a] - f->lo[a]) * (double)ix[a] / (double)f->nc[a];
	*v = f->fn ? f->fn(p, f->ctx) : 0;
}

int
vx_tetsynth_grid(vx_tetmesh *m, const int64_t nc[3], const double lo[3],
    const double hi[3], int split, vx_tetsynth_fn fn, void *ctx, vx_err *e)
{
	fn_ctx f = { nc, lo, hi, fn, ctx };

	for (int a = 0; a < 3; a++)
		if (!(hi[a] > lo[a])) {
			vx_tetmesh_init(m);
			return vx_err_set(e, VX_EUSAGE, "tet grid: empty box on "
			    "axis %d", a);
		}
	return build(m, nc, split, fn_point, &f, e);
}

int
vx_tetsynth_cube(vx_tetmesh *m, const double lo[3], const double hi[3],
    vx_tetsynth_fn fn, void *ctx, vx_err *e)
{
	static const int64_t one[3] = { 1, 1, 1 };

	return vx_tetsynth_grid(m, one, lo, hi, VX_TETSPLIT_6, fn, ctx, e);
}

static void
grid_point(int64_t i, int64_t j, int64_t k, double p[3], double *v, void *c)
{
	const vx_grid *g = c;
	int64_t ix[3] = { i, j, k };

	for (int a = 0; a < 3; a++)
		p[a] = g->origin[a] + (double)ix[a] * g->spacing[a];
	*v = vx_grid_get(g, i, j, k);
}

int
vx_tetsynth_from_grid(vx_tetmesh *m, const vx_grid *g, int split, vx_err *e)
{
	int64_t nc[3];
	int rc;

	for (int a = 0; a < 3; a++)
		nc[a] = g->dims[a] - 1;
	if ((rc = build(m, nc, split, grid_point, (void *)(uintptr_t)g, e)) == 0)
		vx_tetmesh_set_scalar(m, g->name);
	return rc;
}
