/* macrobox.c: boxes of leaves: a macrocell's box, a ray's earliest entry
 * into a list of boxes, the walk through the boxes a ray enters, and the
 * boxes of a cell mask's set bits (vx_macrobox.h). */
#include "vx_macrobox.h"

#include <math.h>
#include <string.h>

#include "macro_priv.h"
#include "macro_ray.h"

void
vx_macro_cell_box(const vx_macro *m, int l, int64_t b, int64_t lo[3],
    int64_t hi[3])
{
	int64_t c[3] = { b % m->dims[l][0], (b / m->dims[l][0]) % m->dims[l][1],
	    b / (m->dims[l][0] * m->dims[l][1]) };
	ray r;

	/* the walk's own planes: the last cell's upper one is the grid's */
	r.w = (const int64_t (*)[3])m->width;
	for (int a = 0; a < 3; a++) {
		r.n[a] = m->dims[0][a];
		lo[a] = plane_lo(&r, l, a, c[a]);
		hi[a] = plane_hi(&r, l, a, c[a]);
	}
}

int
vx_macro_cell_brackets(const vx_macro *m, int l, int64_t b,
    const float *vals, int nvals)
{
	return brackets(m->mm[l][2 * b], m->mm[l][2 * b + 1], vals, nvals);
}

/* box_times: ray r's entry time *tin into box bx, the axis *e of the
 * crossing that enters it, and its exit time *tout; 0 when the ray runs
 * beside it along an axis it does not move on */
static inline __attribute__((always_inline)) int
box_times(const ray *r, const vx_cellbox *bx, double *tin, double *tout,
    int *e)
{
	double ti = -INFINITY, to = INFINITY;
	int a, ea = -1;

	for (a = 0; a < 3; a++) {
		int64_t lo = bx->lo[a], hi = bx->hi[a];

		if (r->s[a] == 0) {
			if (r->fixed[a] < lo || r->fixed[a] >= hi)
				return 0;
		} else {
			double tn = tcross(r, a, r->up[a] ? lo : hi);
			double tf = tcross(r, a, r->up[a] ? hi : lo);

			if (tn >= ti) {
				ti = tn;
				ea = a;
			}
			if (tf < to)
				to = tf;
		}
	}
	*tin = ti;
	*tout = to;
	*e = ea;
	return 1;
}

/* fp_holds: 1 when box bx's footprint holds query point q (NULL: every
 * point) */
static inline int
fp_holds(const vx_cellbox *bx, const int32_t *q)
{
	return q == NULL || (q[0] >= bx->fp[0] && q[0] <= bx->fp[2] &&
	    q[1] >= bx->fp[1] && q[1] <= bx->fp[3]);
}

double
vx_macro_boxes_entry(const vx_macro *m, const vx_cellbox *box,
    const uint32_t *ix, size_t nbox, const double o[3], const double d[3],
    const int32_t q[2])
{
	double best = INFINITY, tin, tout;
	int e;
	ray r;

	/* set up by ray_axes as for the walk: the same crossing times */
	if (!ray_axes(&r, m->dims[0], o, d))
		return INFINITY;
	for (size_t k = 0; k < nbox; k++) {
		const vx_cellbox *bx = ix != NULL ? box + ix[k] : box + k;

		if (bx->lb > best)
			break;
		if (fp_holds(bx, q) && box_times(&r, bx, &tin, &tout, &e) &&
		    !(tin > tout) && tin < best)
			best = tin;
	}
	/* +0 for -0: the same time whatever the boxes' order */
	return best + 0.0;
}

/* row_bits: n <= 64 bits of array v from bit position p */
static inline uint64_t
row_bits(const uint64_t *v, int64_t p, int n)
{
	int sh = (int)(p & 63);
	uint64_t r = v[p >> 6] >> sh;

	if (sh + n > 64)
		r |= v[(p >> 6) + 1] << (64 - sh);
	return n >= 64 ? r : r & (((uint64_t)1 << n) - 1);
}

size_t
vx_cellmask_boxes(vx_cellmask *k, int64_t b, int sub, vx_cellbox *out)
{
	const vx_macro *m = k->m;
	const uint64_t *bits;
	const int64_t *w;
	int64_t lo[3], hi[3], nl[3], jy, jz, j, y, z;
	uint64_t full, ry[VX_MACRO_MAXSIZE], rz[VX_MACRO_MAXSIZE];
	size_t n = 0;

	if (!k->ready || k->slot[b] < 0)
		return 0;
	vx_macro_cell_box(m, 1, b, lo, hi);
	if (sub < 1 || (bits = mask_get(k, m, k->g, b)) == NULL) {
		if (out != NULL) {
			memcpy(out[0].lo, lo, sizeof lo);
			memcpy(out[0].hi, hi, sizeof hi);
		}
		return 1;
	}
	w = m->width[1];
	for (int a = 0; a < 3; a++)
		nl[a] = hi[a] - lo[a];
	full = sub < 64 ? ((uint64_t)1 << sub) - 1 : ~(uint64_t)0;
	/* per row of blocks along x: the rows of leaf bits of its planes
	 * of leaves OR-ed per y (ry) and per z (rz), and all of them (rx):
	 * a block's leaves whose bits are set span, along x, its sub bits
	 * of rx and along y (z), the first to the last ry (rz) that has any
	 * of those bits (a row is at most 64 leaves, so at most 64 blocks) */
	for (jz = 0; jz < nl[2]; jz += sub)
		for (jy = 0; jy < nl[1]; jy += sub) {
			uint64_t rx = 0;
			int64_t ny = nl[1] - jy < sub ? nl[1] - jy : sub;
			int64_t nz = nl[2] - jz < sub ? nl[2] - jz : sub;

			for (z = 0; z < nz; z++) {
				uint64_t oz = 0;

				for (y = 0; y < ny; y++) {
					uint64_t r = row_bits(bits, w[0] * (jy + y +
					    w[1] * (jz + z)), (int)nl[0]);

					ry[y] = z > 0 ? ry[y] | r : r;
					oz |= r;
				}
				rz[z] = oz;
				rx |= oz;
			}
			for (uint64_t rr = rx; rr != 0;
			    rr &= ~(full << (j * sub))) {
				uint64_t bm, xm;
				int64_t y0 = 0, y1 = ny - 1, z0 = 0, z1 = nz - 1;

				j = __builtin_ctzll(rr) / sub;
				if (out == NULL) {
					n++;
					continue;
				}
				bm = full << (j * sub);
				xm = rx >> (j * sub) & full;
				while (!(ry[y0] & bm))
					y0++;
				while (!(ry[y1] & bm))
					y1--;
				while (!(rz[z0] & bm))
					z0++;
				while (!(rz[z1] & bm))
					z1--;
				/* the box of the block's set bits */
				out[n].lo[0] = lo[0] + j * sub + __builtin_ctzll(xm);
				out[n].hi[0] = lo[0] + j * sub + 64 -
				    __builtin_clzll(xm);
				out[n].lo[1] = lo[1] + jy + y0;
				out[n].hi[1] = lo[1] + jy + y1 + 1;
				out[n].lo[2] = lo[2] + jz + z0;
				out[n].hi[2] = lo[2] + jz + z1 + 1;
				n++;
			}
		}
	return n;
}

/* The boxes' walk.  A ray is walked through the boxes of a list that it
 * enters, one after the other in order of entry, leaf by leaf inside each
 * box only: what lies between them holds no leaf to visit.  The boxes are
 * disjoint, so their spans along the ray are too (but for shared times
 * where the ray touches one at an edge or a corner), and the walk through
 * them visits exactly the leaves of the walk from 0 that lie in them, in
 * its order, with its data:
 * - a box's entry time is the largest crossing time of its near faces,
 *   and the crossing that enters it the one of the highest axis among
 *   those at that time (the walk crosses planes of equal time in axis
 *   order);
 * - the leaf it enters there is the walk's: along that axis the box's
 *   first, along the others the one whose entry face is crossed by then
 *   (on a lower axis at that very time too, on a higher one not:
 *   find_cell over the whole grid); where that leaf lies outside the box,
 *   the walk is never inside it (it passes an edge or a corner);
 * - a box entered at or before the segment's start holds the walk's start
 *   leaf or is not walked: it starts there, at the start, as the walk
 *   does;
 * - the entry is a crossing time of the walk's own planes, and from there
 *   on the steps are the walk's (leaves), up to the box's far faces;
 * - boxes are taken in order of (entry, axis of the crossing; a start box
 *   first): the walk's order, as one crossing enters one leaf.  The box's
 *   index breaks the remaining ties (boxes that will not be walked).
 * The boxes entered are kept in a list of at most PEND_MAX sorted by that
 * key, filled from the box list while its lower bounds (lb) do not pass
 * the earliest entry in it.  When it is full, the latest key is left out
 * and becomes a horizon: keys from it on wait, and when the list runs dry
 * the box list is read again from the start for them (the boxes walked
 * all lie before the horizon): exact whatever the number of boxes. */

#define PEND_MAX 64

typedef struct bkey {
	double t;     /* entry time (a start box: the segment's start) */
	int e;        /* axis of the entering crossing; -1: a start box */
	uint32_t j;   /* the box */
} bkey;

static inline int
key_lt(const bkey *a, const bkey *b)
{
	return a->t < b->t || (a->t == b->t && (a->e < b->e ||
	    (a->e == b->e && a->j < b->j)));
}

/* box_walk: the leaves of box bx that the walk visits, from the leaf it
 * enters at t through the face of axis e, or (e < 0) from the start leaf
 * sl at the segment's start t, entered through the face of axis se (tb:
 * the segment's end) */
static int
box_walk(const vx_macro *m, const vx_grid *g, vx_cellmask *mk, const ray *r,
    const vx_cellbox *bx, double t, int e, const int64_t sl[3], int se,
    double tb, const float *vals, int nvals, vx_visit_fn fn, void *ctx,
    vx_trav_stats *s)
{
	int64_t c[3], lim[3], c1[3], li = 0, dl[3] = { 0, 0, 0 };
	double tn[3], texit;
	const uint64_t *bits = NULL;
	int a, ax;

	for (a = 0; a < 3; a++) {
		lim[a] = r->up[a] ? bx->hi[a] : bx->lo[a] - 1;
		if (e < 0)
			c[a] = sl[a];
		else if (r->s[a] == 0)
			c[a] = r->fixed[a];
		else if (a == e)
			c[a] = r->up[a] ? bx->lo[a] : bx->hi[a] - 1;
		else
			c[a] = find_cell(r, 0, a, 0, r->n[a], t, a < e);
		if (c[a] < bx->lo[a] || c[a] >= bx->hi[a])
			return 0;   /* past an edge or a corner: not inside */
		tn[a] = r->s[a] ? tcross(r, a, c[a] + r->up[a]) : INFINITY;
	}
	if (e < 0)
		e = se;
	if (mk != NULL) {
		for (a = 0; a < 3; a++)
			c1[a] = c[a] / r->w[1][a];
		bits = leaf_bits(mk, m, g, r, c1, c, &li, dl);
	}
	return leaves(r, g, c, lim, tn, &t, &e, tb, vals, nvals, bits, li, dl,
	    fn, ctx, s, &ax, &texit);
}

/* boxes_walk: the boxes' walk of ray r (ray_axes done) through the boxes
 * the pick selects; the visitor's nonzero value, or 0 */
static int
boxes_walk(const vx_macro *m, const vx_grid *g, vx_cellmask *mk, ray *r,
    const vx_cellbox *box, const uint32_t *ix, size_t nbox,
    const vx_boxpick *pk, const float *vals, int nvals, vx_visit_fn fn,
    void *ctx, vx_trav_stats *s)
{
	const double *lbs = pk != NULL && pk->pix != NULL && ix != NULL ?
	    pk->lb : NULL;
	const int32_t *q = pk != NULL && lbs == NULL ? pk->q : NULL;
	bkey pend[PEND_MAX];   /* sorted, the earliest last */
	bkey hz = { INFINITY, 0, 0 }, fl = { -INFINITY, 0, 0 };
	double ta = 0, tb = INFINITY;
	int64_t sl[3] = { 0, 0, 0 };
	int np = 0, walked = 0, have_sl = 0, se = -1, rc = 0;
	size_t k = 0;
	/* with the query's entries as a mask: the entries not yet read */
	int use_em = lbs != NULL && pk->use_em;
	uint64_t rem = use_em ? pk->em : 0;

	if (!ray_clip(r, m, m->nlev, vals, nvals, &ta, &tb))
		return 0;
	for (;;) {
		for (; use_em ? rem != 0 : k < nbox; k++) {
			const vx_cellbox *bx;
			double tin, tout;
			uint32_t j;
			bkey y;
			int e, i;

			if (use_em)
				k = (size_t)__builtin_ctzll(rem);
			j = ix != NULL ? ix[k] : (uint32_t)k;
			bx = box + j;

			if ((lbs != NULL ? lbs[k] : bx->lb) > (np > 0 ?
			    pend[np - 1].t : hz.t))
				break;
			if (use_em)
				rem &= rem - 1;
			else if (lbs != NULL ? !(pk->pix[k] >> pk->bit & 1) :
			    !fp_holds(bx, q))
				continue;
			/* entered (a box entered after the start: before the
			 * end, where the walk still steps) */
			if (!box_times(r, bx, &tin, &tout, &e) || tin > tout ||
			    tout < ta || (tin > ta && !(tin < tb)))
				continue;
			y.t = tin > ta ? tin : ta;
			y.e = tin > ta ? e : -1;
			y.j = j;
			if (key_lt(&y, &fl) || !key_lt(&y, &hz))
				continue;   /* walked, or past the horizon */
			if (np == PEND_MAX) {
				/* full: the latest waits for the next pass */
				if (key_lt(&pend[0], &y)) {
					hz = y;
					continue;
				}
				hz = pend[0];
				memmove(pend, pend + 1, (size_t)(np - 1) *
				    sizeof *pend);
				np--;
			}
			for (i = np; i > 0 && key_lt(&pend[i - 1], &y); i--)
				pend[i] = pend[i - 1];
			pend[i] = y;
			np++;
		}
		if (np == 0) {
			if (hz.t == INFINITY)
				break;
			/* the boxes left at the horizon: a pass for them */
			fl = hz;
			hz.t = INFINITY;
			k = 0;
			rem = use_em ? pk->em : 0;
			continue;
		}
		np--;
		if (pend[np].e < 0 && !have_sl) {
			/* the start leaf, as the walk from the start has it */
			start_leaf(r, ta, sl, &se);
			have_sl = 1;
		}
		if (!walked) {
			walked = 1;
			s->rays++;
		}
		if ((rc = box_walk(m, g, mk, r, box + pend[np].j, pend[np].t,
		    pend[np].e, sl, se, tb, vals, nvals, fn, ctx, s)) != 0)
			break;
	}
	return rc;
}

int
vx_macro_traverse_boxes(const vx_macro *m, const vx_grid *g,
    vx_cellmask *k, const vx_cellbox *box, const uint32_t *ix, size_t nbox,
    const vx_boxpick *pk, const double o[3], const double d[3],
    const float *vals, int nvals, vx_visit_fn fn, void *ctx,
    vx_trav_stats *st)
{
	vx_trav_stats s;
	ray r;
	int rc;

	if (m->nlev < 1 || mask_walk(m, g, &k, vals, nvals) != 0)
		return -1;
	if (!ray_axes(&r, m->dims[0], o, d))
		return 0;
	memset(&s, 0, sizeof s);
	rc = boxes_walk(m, g, k, &r, box, ix, nbox, pk, vals, nvals, fn, ctx,
	    &s);
	if (st != NULL) {
		st->leaves += s.leaves;
		st->culled += s.culled;
		st->rays += s.rays;
	}
	return rc;
}
