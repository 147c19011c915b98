/* tetleaf.c: the leaf grid of a tet mesh (Parker et al. 1999, §4.2): a
 * rectilinear grid with about one leaf per tet, each leaf listing the tets
 * whose (slightly padded) bounding box overlaps it, CSR-style, with the
 * min/max of the scalar over its tets. */
#include "vx_tetmesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LEAF_AXIS_MAX ((int64_t)1 << 20)

void
vx_tetleaf_init(vx_tetleaf *lg)
{
	memset(lg, 0, sizeof *lg);
}

void
vx_tetleaf_free(vx_tetleaf *lg)
{
	free(lg->off);
	free(lg->idx);
	free(lg->lmin);
	free(lg->lmax);
	vx_tetleaf_init(lg);
}

size_t
vx_tetleaf_bytes(const vx_tetleaf *lg)
{
	if (lg->off == NULL)
		return 0;
	return (lg->nleaf + 1) * sizeof *lg->off +
	    (size_t)lg->off[lg->nleaf] * sizeof *lg->idx +
	    2 * lg->nleaf * sizeof *lg->lmin;
}

void
vx_tetleaf_dims(const double ext[3], size_t ntet, double density,
    int64_t dims[3])
{
	double target, vol, h;
	int a, active[3], nact, changed;

	if (!(density > 0))
		density = 1;
	target = (double)ntet * density;
	if (target < 1)
		target = 1;
	if (target > (double)VX_TETLEAF_MAX_LEAVES / 2)
		target = (double)VX_TETLEAF_MAX_LEAVES / 2;
	for (a = 0; a < 3; a++) {
		dims[a] = 1;
		active[a] = ext[a] > 0 && isfinite(ext[a]);
	}
	/* Cubical leaves of edge h with prod(ext / h) = target over the active
	 * axes; an axis shorter than h gets one leaf and leaves the set. */
	do {
		changed = 0;
		nact = 0;
		vol = 1;
		for (a = 0; a < 3; a++)
			if (active[a]) {
				nact++;
				vol *= ext[a];
			}
		if (nact == 0)
			return;
		h = pow(vol / target, 1.0 / nact);
		for (a = 0; a < 3; a++)
			if (active[a] && ext[a] < h) {
				active[a] = 0;
				changed = 1;
			}
	} while (changed);
	for (a = 0; a < 3; a++) {
		if (!active[a])
			continue;
		double n = floor(ext[a] / h + 0.5);
		dims[a] = n < 1 ? 1 : n > (double)LEAF_AXIS_MAX ? LEAF_AXIS_MAX :
		    (int64_t)n;
	}
	/* rounding up three axes may overshoot the cap: shrink the largest */
	while ((uint64_t)dims[0] * (uint64_t)dims[1] * (uint64_t)dims[2] >
	    VX_TETLEAF_MAX_LEAVES) {
		a = dims[1] > dims[0] ? 1 : 0;
		if (dims[2] > dims[a])
			a = 2;
		dims[a] = (dims[a] + 1) / 2;
	}
}

/* Leaf range [lo, hi] of tet t on each axis; 0 if the tet can never hit
 * (non-finite value or zero volume) and so is not listed. */
static int
tet_range(const vx_tetleaf *lg, const vx_tetmesh *m, size_t t,
    int64_t lo[3], int64_t hi[3], float *vmin, float *vmax)
{
	const uint32_t *q = m->tet + 4 * t;
	double bl[3], bh[3];
	int a, k;

	*vmin = *vmax = m->val[q[0]];
	for (k = 0; k < 4; k++) {
		float v = m->val[q[k]];
		if (!isfinite(v))
			return 0;
		if (v < *vmin)
			*vmin = v;
		if (v > *vmax)
			*vmax = v;
	}
	if (vx_tetmesh_degenerate(m, t))
		return 0;
	for (a = 0; a < 3; a++) {
		bl[a] = bh[a] = m->pts[3 * (size_t)q[0] + a];
		for (k = 1; k < 4; k++) {
			double x = m->pts[3 * (size_t)q[k] + a];
			if (x < bl[a])
				bl[a] = x;
			if (x > bh[a])
				bh[a] = x;
		}
		double pad = VX_TETLEAF_PAD * lg->cell[a];
		double l = floor((bl[a] - pad - lg->bmin[a]) / lg->cell[a]);
		double h = floor((bh[a] + pad - lg->bmin[a]) / lg->cell[a]);
		double top = (double)(lg->dims[a] - 1);
		lo[a] = l < 0 ? 0 : l > top ? (int64_t)top : (int64_t)l;
		hi[a] = h < 0 ? 0 : h > top ? (int64_t)top : (int64_t)h;
	}
	return 1;
}

int
vx_tetleaf_build(vx_tetleaf *lg, const vx_tetmesh *m, double density,
    vx_err *e)
{
	double ext[3];
	uint32_t *cur = NULL;
	uint64_t total = 0;
	size_t t, l;
	int a;

	vx_tetleaf_init(lg);
	for (a = 0; a < 3; a++)
		ext[a] = m->npoint ? m->bmax[a] - m->bmin[a] : 0;
	vx_tetleaf_dims(ext, m->ntet, density, lg->dims);
	for (a = 0; a < 3; a++) {
		lg->bmin[a] = m->npoint ? m->bmin[a] : 0;
		lg->cell[a] = ext[a] > 0 ? ext[a] / (double)lg->dims[a] : 1;
	}
	lg->nleaf = (size_t)(lg->dims[0] * lg->dims[1] * lg->dims[2]);
	lg->off = vx_calloc(lg->nleaf + 1, sizeof *lg->off, e);
	lg->lmin = lg->off ? vx_malloc(lg->nleaf * sizeof *lg->lmin, e) : NULL;
	lg->lmax = lg->lmin ? vx_malloc(lg->nleaf * sizeof *lg->lmax, e) : NULL;
	if (lg->lmax == NULL)
		goto nomem;
	for (l = 0; l < lg->nleaf; l++) {
		lg->lmin[l] = INFINITY;
		lg->lmax[l] = -INFINITY;
	}

	/* pass 1: count (in off[l + 1]) and min/max */
	for (t = 0; t < m->ntet; t++) {
		int64_t lo[3], hi[3], i, j, k;
		float vmin, vmax;
		if (!tet_range(lg, m, t, lo, hi, &vmin, &vmax))
			continue;
		total += (uint64_t)(hi[0] - lo[0] + 1) * (uint64_t)(hi[1] -
		    lo[1] + 1) * (uint64_t)(hi[2] - lo[2] + 1);
		if (total > UINT32_MAX) {
			vx_tetleaf_free(lg);
			return vx_err_set(e, VX_EDATA, "leaf grid: the tet lists "
			    "would exceed 2^32 - 1 entries");
		}
		for (k = lo[2]; k <= hi[2]; k++)
			for (j = lo[1]; j <= hi[1]; j++)
				for (i = lo[0]; i <= hi[0]; i++) {
					l = (size_t)(i + lg->dims[0] * (j +
					    lg->dims[1] * k));
					lg->off[l + 1]++;
					if (vmin < lg->lmin[l])
						lg->lmin[l] = vmin;
					if (vmax > lg->lmax[l])
						lg->lmax[l] = vmax;
				}
	}
	for (l = 0; l < lg->nleaf; l++)
		lg->off[l + 1] += lg->off[l];

	/* pass 2: fill, tets in ascending order */
	lg->idx = vx_malloc((size_t)total * sizeof *lg->idx, e);
	cur = lg->idx ? vx_malloc(lg->nleaf * sizeof *cur, e) : NULL;
	if (cur == NULL)
		goto nomem;
	memcpy(cur, lg->off, lg->nleaf * sizeof *cur);
	for (t = 0; t < m->ntet; t++) {
		int64_t lo[3], hi[3], i, j, k;
		float vmin, vmax;
		if (!tet_range(lg, m, t, lo, hi, &vmin, &vmax))
			continue;
		for (k = lo[2]; k <= hi[2]; k++)
			for (j = lo[1]; j <= hi[1]; j++)
				for (i = lo[0]; i <= hi[0]; i++) {
					l = (size_t)(i + lg->dims[0] * (j +
					    lg->dims[1] * k));
					lg->idx[cur[l]++] = (uint32_t)t;
				}
	}
	free(cur);
	return 0;
nomem:
	free(cur);
	vx_tetleaf_free(lg);
	return VX_ENOMEM;
}
