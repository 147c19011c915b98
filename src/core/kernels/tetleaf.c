/* tetleaf.c: the leaf grid of a tet mesh (Parker et al. 1999, §4.2): a
 * rectilinear grid with about one leaf per tet, each leaf listing the tets
 * whose (slightly padded) bounding box overlaps it, CSR-style, with the
 * min/max of the scalar over its tets as level 0 of a vx_macro hierarchy;
 * and the nearest-hit query that walks it. */
#include "vx_tetleaf.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#define LEAF_AXIS_MAX ((int64_t)1 << 20)

void
vx_tetleaf_init(vx_tetleaf *lg)
{
	memset(lg, 0, sizeof *lg);
	vx_macro_init(&lg->mc);
}

void
vx_tetleaf_free(vx_tetleaf *lg)
{
	free(lg->off);
	free(lg->idx);
	vx_macro_free(&lg->mc);
	vx_tetleaf_init(lg);
}

size_t
vx_tetleaf_bytes(const vx_tetleaf *lg)
{
	if (lg->off == NULL)
		return 0;
	return (lg->nleaf + 1) * sizeof *lg->off +
	    (size_t)lg->off[lg->nleaf] * sizeof *lg->idx +
	    vx_macro_bytes(&lg->mc);
}

void
vx_tetleaf_dims(const double ext[3], size_t ntet, double density,
    int64_t dims[3])
{
	double target, lh;
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
	 * axes; an axis shorter than h gets one leaf and leaves the set.  In
	 * logarithms, so that tiny or huge extents neither underflow nor
	 * overflow. */
	do {
		double lsum = 0;
		changed = 0;
		nact = 0;
		for (a = 0; a < 3; a++)
			if (active[a]) {
				nact++;
				lsum += log(ext[a]);
			}
		if (nact == 0)
			return;
		lh = (lsum - log(target)) / nact;
		for (a = 0; a < 3; a++)
			if (active[a] && log(ext[a]) < lh) {
				active[a] = 0;
				changed = 1;
			}
	} while (changed);
	for (a = 0; a < 3; a++) {
		if (!active[a])
			continue;
		double n = floor(exp(log(ext[a]) - lh) + 0.5);
		dims[a] = n < 1 ? 1 : n > (double)LEAF_AXIS_MAX ? LEAF_AXIS_MAX :
		    (int64_t)n;
	}
	/* rounding three axes may overshoot: shrink the largest axis until
	 * the count is within 8 times the target */
	while ((double)dims[0] * (double)dims[1] * (double)dims[2] >
	    8 * target + 8) {
		a = dims[1] > dims[0] ? 1 : 0;
		if (dims[2] > dims[a])
			a = 2;
		dims[a] = (dims[a] + 1) / 2;
	}
}

/* Exact tet/leaf overlap by separating axes.  The bounding-box test has
 * already covered the 3 box axes; the others are the tet's 4 face normals
 * and the 18 products of a box axis with a tet edge.  Per tet: the axes,
 * the tet's interval on each (relative to its vertex 0) and the padded
 * leaf's half-width on each (leaves all have the same size); per leaf: one
 * dot product per axis with the leaf's centre.  The leaf is padded by
 * VX_TETLEAF_PAD widths, far above the rounding here, so a tet touching a
 * leaf is never separated from it. */
#define NAXIS 22

typedef struct tetsat {
	double p0[3];
	double n[NAXIS][3];
	double lo[NAXIS], hi[NAXIS], r[NAXIS];
} tetsat;

static void
sat_setup(tetsat *s, const vx_tetleaf *lg, const vx_tetmesh *m, size_t t)
{
	static const int E[6][2] = {
		{ 0, 1 }, { 0, 2 }, { 0, 3 }, { 1, 2 }, { 1, 3 }, { 2, 3 },
	};
	static const int F[4][3] = {
		{ 1, 2, 3 }, { 0, 2, 3 }, { 0, 1, 3 }, { 0, 1, 2 },
	};
	const uint32_t *v = m->tet + 4 * t;
	double q[4][3], e[6][3], h[3];
	int i, k, a, na = 0;

	for (a = 0; a < 3; a++) {
		s->p0[a] = m->pts[3 * (size_t)v[0] + a];
		h[a] = (0.5 + VX_TETLEAF_PAD) * lg->cell[a];
	}
	for (k = 0; k < 4; k++)
		for (a = 0; a < 3; a++)
			q[k][a] = m->pts[3 * (size_t)v[k] + a] - s->p0[a];
	for (i = 0; i < 6; i++)
		for (a = 0; a < 3; a++)
			e[i][a] = q[E[i][1]][a] - q[E[i][0]][a];
	for (i = 0; i < 4; i++) {
		double u[3], w[3];
		for (a = 0; a < 3; a++) {
			u[a] = q[F[i][1]][a] - q[F[i][0]][a];
			w[a] = q[F[i][2]][a] - q[F[i][0]][a];
		}
		s->n[na][0] = u[1] * w[2] - u[2] * w[1];
		s->n[na][1] = u[2] * w[0] - u[0] * w[2];
		s->n[na][2] = u[0] * w[1] - u[1] * w[0];
		na++;
	}
	for (a = 0; a < 3; a++)
		for (i = 0; i < 6; i++) {
			int b = (a + 1) % 3, c = (a + 2) % 3;
			s->n[na][a] = 0;
			s->n[na][b] = -e[i][c];
			s->n[na][c] = e[i][b];
			na++;
		}
	for (i = 0; i < NAXIS; i++) {
		s->r[i] = fabs(s->n[i][0]) * h[0] + fabs(s->n[i][1]) * h[1] +
		    fabs(s->n[i][2]) * h[2];
		s->lo[i] = INFINITY;
		s->hi[i] = -INFINITY;
		for (k = 0; k < 4; k++) {
			double d = s->n[i][0] * q[k][0] + s->n[i][1] * q[k][1] +
			    s->n[i][2] * q[k][2];
			s->lo[i] = d < s->lo[i] ? d : s->lo[i];
			s->hi[i] = d > s->hi[i] ? d : s->hi[i];
		}
	}
}

/* 1 if the tet of s overlaps leaf (i, j, k) padded. */
static int
sat_leaf(const tetsat *s, const vx_tetleaf *lg, int64_t i, int64_t j,
    int64_t k)
{
	int64_t ix[3] = { i, j, k };
	double c[3];
	int a, x;

	for (a = 0; a < 3; a++)
		c[a] = lg->bmin[a] + ((double)ix[a] + 0.5) * lg->cell[a] -
		    s->p0[a];
	for (x = 0; x < NAXIS; x++) {
		double d = s->n[x][0] * c[0] + s->n[x][1] * c[1] +
		    s->n[x][2] * c[2];
		if (d - s->r[x] > s->hi[x] || d + s->r[x] < s->lo[x])
			return 0;
	}
	return 1;
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

/* The leaves tet t overlaps, into out (room for the bounding-box count):
 * returns how many, or 0 when the tet is not listed.  *vmin, *vmax get its
 * value range. */
static uint32_t
tet_leaves(const vx_tetleaf *lg, const vx_tetmesh *m, size_t t, int exact,
    uint32_t *out, float *vmin, float *vmax)
{
	int64_t lo[3], hi[3], i, j, k;
	uint32_t n = 0;
	tetsat sat;

	if (!tet_range(lg, m, t, lo, hi, vmin, vmax))
		return 0;
	exact = exact && !(lo[0] == hi[0] && lo[1] == hi[1] && lo[2] == hi[2]);
	if (exact)
		sat_setup(&sat, lg, m, t);
	for (k = lo[2]; k <= hi[2]; k++)
		for (j = lo[1]; j <= hi[1]; j++)
			for (i = lo[0]; i <= hi[0]; i++)
				if (!exact || sat_leaf(&sat, lg, i, j, k))
					out[n++] = (uint32_t)(i + lg->dims[0] *
					    (j + lg->dims[1] * k));
	return n;
}

int
vx_tetleaf_build_levels(vx_tetleaf *lg, const vx_tetmesh *m, double density,
    int flags, int nlev, const int sizes[][3], int nthreads, vx_err *e)
{
	double ext[3];
	uint64_t *toff = NULL, total = 0;
	uint32_t *cnt = NULL, *lof = NULL;
	float *mm = NULL;
	size_t t, l;
	int a, rc = VX_ENOMEM, exact = !(flags & VX_TETLEAF_BBOX);
	int nt = nthreads > 0 ? nthreads : omp_get_max_threads();

	vx_tetleaf_init(lg);
	for (a = 0; a < 3; a++)
		ext[a] = m->npoint ? m->bmax[a] - m->bmin[a] : 0;
	vx_tetleaf_dims(ext, m->ntet, density, lg->dims);
	/* The grid's box is the mesh's, grown by VX_TETLEAF_PAD leaves on
	 * every side: a ray that touches the mesh only at its boundary then
	 * still has a segment in the grid after the traversal's rounding. */
	for (a = 0; a < 3; a++) {
		double cell = ext[a] > 0 ? ext[a] / (double)lg->dims[a] : 1;
		double pad = VX_TETLEAF_PAD * cell;
		lg->bmin[a] = (m->npoint ? m->bmin[a] : 0) - pad;
		lg->cell[a] = (ext[a] + 2 * pad) / (double)lg->dims[a];
	}
	lg->nleaf = (size_t)(lg->dims[0] * lg->dims[1] * lg->dims[2]);

	/* 1. bounding-box leaf counts: room for each tet's list */
	toff = vx_malloc((m->ntet + 1) * sizeof *toff, e);
	cnt = toff ? vx_malloc((m->ntet ? m->ntet : 1) * sizeof *cnt, e) : NULL;
	if (cnt == NULL)
		goto fail;
	toff[0] = 0;
	for (t = 0; t < m->ntet; t++) {
		int64_t lo[3], hi[3];
		float vmin, vmax;
		uint64_t k = 0;
		if (tet_range(lg, m, t, lo, hi, &vmin, &vmax))
			k = (uint64_t)(hi[0] - lo[0] + 1) * (uint64_t)(hi[1] -
			    lo[1] + 1) * (uint64_t)(hi[2] - lo[2] + 1);
		toff[t + 1] = toff[t] + k;
	}
	if (toff[m->ntet] > UINT32_MAX ||
	    toff[m->ntet] > SIZE_MAX / sizeof *lof) {
		rc = vx_err_set(e, VX_EDATA, "leaf grid: the tet lists would "
		    "exceed 2^32 - 1 entries; use fewer leaves");
		goto fail;
	}
	if ((lof = vx_malloc((size_t)toff[m->ntet] * sizeof *lof + 1, e)) ==
	    NULL)
		goto fail;

	/* 2. each tet's leaves, exactly (in parallel: tets are independent
	 * and write only their own slots) */
	long long ntl = (long long)m->ntet;
#pragma omp parallel for schedule(dynamic, 1024) num_threads(nt)
	for (long long ti = 0; ti < ntl; ti++) {
		float vmin, vmax;
		cnt[ti] = tet_leaves(lg, m, (size_t)ti, exact, lof + toff[ti],
		    &vmin, &vmax);
	}

	/* 3. counting sort into CSR, tets ascending; leaf ranges */
	lg->off = vx_calloc(lg->nleaf + 1, sizeof *lg->off, e);
	mm = lg->off ? vx_malloc(2 * lg->nleaf * sizeof *mm, e) : NULL;
	if (mm == NULL)
		goto fail;
	for (l = 0; l < lg->nleaf; l++) {
		mm[2 * l] = INFINITY;
		mm[2 * l + 1] = -INFINITY;
	}
	for (t = 0; t < m->ntet; t++) {
		const uint32_t *q = m->tet + 4 * t;
		float vmin = m->val[q[0]], vmax = vmin;
		for (int k = 1; k < 4; k++) {
			vmin = fminf(vmin, m->val[q[k]]);
			vmax = fmaxf(vmax, m->val[q[k]]);
		}
		for (uint32_t k = 0; k < cnt[t]; k++) {
			l = lof[toff[t] + k];
			lg->off[l + 1]++;
			mm[2 * l] = fminf(mm[2 * l], vmin);
			mm[2 * l + 1] = fmaxf(mm[2 * l + 1], vmax);
		}
		total += cnt[t];
	}
	for (l = 0; l < lg->nleaf; l++)
		lg->off[l + 1] += lg->off[l];
	if ((lg->idx = vx_malloc((size_t)total * sizeof *lg->idx + 1, e)) ==
	    NULL)
		goto fail;
	/* fill with a cursor per leaf */
	{
		uint32_t *cur = vx_malloc((lg->nleaf ? lg->nleaf : 1) *
		    sizeof *cur, e);
		if (cur == NULL)
			goto fail;
		memcpy(cur, lg->off, lg->nleaf * sizeof *cur);
		for (t = 0; t < m->ntet; t++)
			for (uint32_t k = 0; k < cnt[t]; k++)
				lg->idx[cur[lof[toff[t] + k]]++] = (uint32_t)t;
		free(cur);
	}
	free(lof);
	free(cnt);
	free(toff);
	lof = NULL;
	cnt = NULL;
	toff = NULL;
	if ((rc = vx_macro_build_explicit(&lg->mc, lg->dims, mm, nlev, sizes,
	    nthreads, e)) != 0) {
		vx_err_push(e, "leaf grid");
		goto fail;
	}
	free(mm);
	return 0;
fail:
	free(lof);
	free(cnt);
	free(toff);
	free(mm);
	vx_tetleaf_free(lg);
	return rc;
}

int
vx_tetleaf_build(vx_tetleaf *lg, const vx_tetmesh *m, double density,
    vx_err *e)
{
	int sizes[VX_MACRO_MAXLEV][3];
	int nlev = vx_macro_default_sizes(VX_F32, VX_MACRO_DEFAULT_LEVELS,
	    sizes);

	return vx_tetleaf_build_levels(lg, m, density, 0, nlev, sizes, 0, e);
}

/* ---- the nearest-hit query ---- */

typedef struct near_ctx {
	const vx_tetleaf *lg;
	const vx_tetmesh *m;
	vx_tetray ray;
	const double *iso;
	int niso;
	double tmin, tmax;
	vx_tethit *hit;
	uint64_t nvisit;       /* leaves visited so far */
	int64_t last;          /* the last one, and where it ended */
	double last_t1;
} near_ctx;

static int
leaf_query(near_ctx *c, int64_t leaf, double t0, double t1)
{
	const vx_tetleaf *lg = c->lg;
	size_t l = (size_t)leaf;

	if (t0 < c->tmin)
		t0 = c->tmin;
	if (t1 > c->tmax)
		t1 = c->tmax;
	if (!(t0 < t1))
		return 0;
	return vx_tet_nearest(c->m, lg->idx + lg->off[l], lg->off[l + 1] -
	    lg->off[l], &c->ray, c->iso, c->niso, t0, t1, c->hit);
}

/* Each visited leaf is searched over [t0, t1): a hit on its far face
 * belongs to the next leaf, whose list has the tet too (padding).  The
 * first visited leaf is searched from tmin, and the last one again up to
 * tmax after the walk: where the ray enters or leaves the grid there is no
 * neighbour to defer to, and a hit that rounding puts just outside the
 * walk's segment is kept.  (A crossing can only lie in a leaf whose range
 * brackets the isovalue, so the extensions find nothing that a culled or
 * earlier leaf should have found.) */
static int
near_visit(void *p, const vx_leaf_visit *v)
{
	near_ctx *c = p;
	double t0 = c->nvisit == 0 ? c->tmin : v->t0;

	c->nvisit++;
	c->last = v->leaf;
	c->last_t1 = v->t1;
	return leaf_query(c, v->leaf, t0, v->t1);
}

int
vx_tetleaf_walk_setup(const vx_tetleaf *lg, const double o[3],
    const double d[3], const double *iso, int niso, double lo[3],
    double ld[3], float vals[64])
{
	int a, k, nv = niso <= 64 ? niso : 0;

	for (k = 0; k < nv; k++)
		vals[k] = (float)iso[k];
	for (a = 0; a < 3; a++) {
		lo[a] = (o[a] - lg->bmin[a]) / lg->cell[a];
		ld[a] = d[a] / lg->cell[a];
	}
	return nv;
}

int
vx_tetleaf_nearest(const vx_tetleaf *lg, const vx_tetmesh *m,
    const double o[3], const double d[3], const double *iso, int niso,
    double tmin, double tmax, vx_tethit *hit, vx_trav_stats *st)
{
	float vals[64];
	double lo[3], ld[3];
	near_ctx c;
	int nv;

	if (lg->off == NULL || niso <= 0)
		return 0;
	/* the interpolated values stay within the vertex values
	 * (vx_tet_segment clamps them) */
	nv = vx_tetleaf_walk_setup(lg, o, d, iso, niso, lo, ld, vals);
	memset(&c, 0, sizeof c);
	c.lg = lg;
	c.m = m;
	vx_tetray_init(&c.ray, o, d);
	c.iso = iso;
	c.niso = niso;
	c.tmin = tmin;
	c.tmax = tmax;
	c.hit = hit;
	if (vx_macro_traverse(&lg->mc, NULL, lo, ld, tmin, tmax, vals, nv,
	    near_visit, &c, st) != 0)
		return 1;
	return c.nvisit > 0 && leaf_query(&c, c.last, c.last_t1, tmax);
}
