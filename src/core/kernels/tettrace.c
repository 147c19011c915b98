/* tettrace.c: every isosurface crossing along a ray through a tet mesh, in
 * order, each once: the multi-hit form of vx_tetleaf_nearest that
 * transparent layers and shadow rays need (vx_tetmesh.h). */
#include "vx_tetleaf.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "vx_iso.h"

#ifdef __clang__
#pragma STDC FP_CONTRACT OFF   /* the same t as tetisect.c, bit for bit */
#endif

/* A crossing waiting to be handed over; ordered by (t, tet, iso). */
typedef struct cand {
	double t;
	uint32_t tet;
	int iso;
	int enter;
} cand;

/* Crossings kept per scan of a leaf.  A leaf with more (several surfaces
 * folded into one leaf, or a leaf listing many tets) is scanned again for
 * the crossings after the last one handed over. */
#define NCAND 16

static int
cand_less(const cand *a, const cand *b)
{
	if (a->t != b->t)
		return a->t < b->t;
	if (a->tet != b->tet)
		return a->tet < b->tet;
	return a->iso < b->iso;
}

/* Segments computed for this ray, by tet (direct-mapped): a tet listed by
 * several leaves along the ray is tested once.  The cached values are the
 * computed ones, so results do not change. */
#define NSEG 64

typedef struct seg {
	uint32_t tet;            /* valid when its bit of trace_ctx.valid is */
	int ok;                  /* vx_tet_segment's answer */
	double t0, f0, t1, f1;
} seg;

typedef struct trace_ctx {
	const vx_tetleaf *lg;
	const vx_tetmesh *m;
	vx_tetray ray;
	const double *iso;
	int niso;
	double tmin, tmax;
	vx_tethit_fn fn;
	void *ctx;
	vx_tettrace_stats *st;
	uint64_t nvisit;         /* leaves visited so far */
	int64_t last;            /* the last one, and where it ended */
	double last_t1;
	uint64_t valid;          /* bit k: cache[k] holds a segment */
	seg cache[NSEG];
} trace_ctx;

/* misses: 1 when the ray certainly misses tet q: in ray space (the ray is
 * the z axis) all four vertices lie strictly on one side of x = 0 or of
 * y = 0.  The images are computed as vx_tet_segment computes them
 * (tetisect.c's to_ray, operation for operation), and its exact edge signs
 * on those images then find no face around the origin, nor around the
 * perturbed origin (eps, eps^2): skipping the tet changes nothing. */
static int
misses(const vx_tetmesh *m, const uint32_t *q, const vx_tetray *r)
{
	int neg_x = 0, pos_x = 0, neg_y = 0, pos_y = 0;

	for (int k = 0; k < 4; k++) {
		const double *p = m->pts + 3 * (size_t)q[k];
		double az = p[r->kz] - r->o[r->kz];
		double x = (p[r->kx] - r->o[r->kx]) - r->sx * az;
		double y = (p[r->ky] - r->o[r->ky]) - r->sy * az;

		neg_x |= !(x > 0);
		pos_x |= !(x < 0);
		neg_y |= !(y > 0);
		pos_y |= !(y < 0);
	}
	/* neg_x: some vertex has x <= 0; pos_x: some has x >= 0 */
	return !neg_x || !pos_x || !neg_y || !pos_y;
}

/* keep: insert c into the sorted kept[0..*n) (at most NCAND); *more is set
 * when a crossing is dropped. */
static void
keep(cand *kept, int *n, const cand *c, int *more)
{
	int i;

	if (*n == NCAND) {
		*more = 1;
		if (!cand_less(c, &kept[NCAND - 1]))
			return;
		(*n)--;
	}
	for (i = *n; i > 0 && cand_less(c, &kept[i - 1]); i--)
		kept[i] = kept[i - 1];
	kept[i] = *c;
	(*n)++;
}

/* scan: the crossings of the tets list[0..n) with t in [a, b) and, when
 * after is given, a key beyond *after; the smallest NCAND of them into
 * kept (sorted), their number returned, *more set when there were more.
 * The crossing of a tet is computed as tetisect.c's tet_cross computes it,
 * operation for operation. */
static int
scan(trace_ctx *x, const uint32_t *list, size_t n, double a, double b,
    const cand *after, cand *kept, int *more)
{
	const vx_tetmesh *m = x->m;
	int nk = 0;

	*more = 0;
	for (size_t i = 0; i < n; i++) {
		uint32_t t = list[i];
		const uint32_t *q;
		double t0, f0, t1, f1;
		int k, flat = -1;

		if (t >= m->ntet)
			continue;
		q = m->tet + 4 * (size_t)t;
		float v0 = m->val[q[0]], v1 = m->val[q[1]], v2 = m->val[q[2]],
		    v3 = m->val[q[3]];
		/* f0 and f1 lie within the vertex values: a crossing needs
		 * lo < iso <= hi for some isovalue (skips most tets of a leaf
		 * before the costly segment); then tets with a non-finite
		 * value, which never hit, whatever this test said of them */
		float lo = v0 < v1 ? v0 : v1, hi = v0 < v1 ? v1 : v0;
		lo = v2 < lo ? v2 : lo;
		hi = v2 > hi ? v2 : hi;
		lo = v3 < lo ? v3 : lo;
		hi = v3 > hi ? v3 : hi;
		for (k = 0; k < x->niso; k++)
			if (lo < x->iso[k] && x->iso[k] <= hi)
				break;
		if (k == x->niso)
			continue;
		if (!isfinite(v0) || !isfinite(v1) || !isfinite(v2) ||
		    !isfinite(v3))
			continue;
		seg *sg = &x->cache[t % NSEG];
		uint64_t bit = (uint64_t)1 << (t % NSEG);
		if (!(x->valid & bit) || sg->tet != t) {
			x->valid |= bit;
			sg->tet = t;
			sg->ok = 0;
			if (misses(m, q, &x->ray))
				continue;
			if (x->st != NULL)
				x->st->tets++;
			sg->ok = vx_tet_segment(m, t, &x->ray, &sg->t0, &sg->f0,
			    &sg->t1, &sg->f1);
		}
		if (!sg->ok)
			continue;
		t0 = sg->t0;
		f0 = sg->f0;
		t1 = sg->t1;
		f1 = sg->f1;
		if (t1 < a || t0 >= b)
			continue;
		for (k = 0; k < x->niso; k++) {
			double iso = x->iso[k];
			int s0 = f0 >= iso, s1 = f1 >= iso;
			cand c;

			if (s0 == s1)
				continue;
			double th = t0 + (t1 - t0) * ((iso - f0) / (f1 - f0));
			if (!(th >= t0))
				th = t0;
			if (!(th <= t1))
				th = t1;
			if (th < a || th >= b)
				continue;
			c.t = th;
			c.tet = t;
			c.iso = k;
			c.enter = s1;
			if (after != NULL && !cand_less(after, &c))
				continue;
			/* flat tets never hit (lists built here leave them out,
			 * a stored list might not) */
			if (flat < 0)
				flat = vx_tetmesh_degenerate(m, t);
			if (flat)
				break;
			keep(kept, &nk, &c, more);
		}
	}
	if (x->st != NULL)
		x->st->entries += n;
	return nk;
}

/* leaf_trace: hand over the crossings of leaf l's tets in [a, b) (clipped
 * to [tmin, tmax)), in order. */
static int
leaf_trace(trace_ctx *x, int64_t l, double a, double b)
{
	const vx_tetleaf *lg = x->lg;
	const uint32_t *list = lg->idx + lg->off[l];
	size_t n = lg->off[l + 1] - lg->off[l];
	cand kept[NCAND], last;
	const cand *after = NULL;
	uint64_t c0 = 0;
	int nk, more, i, rc;

	if (a < x->tmin)
		a = x->tmin;
	if (b > x->tmax)
		b = x->tmax;
	if (!(a < b) || n == 0)
		return 0;
	if (x->st != NULL) {
		x->st->leaves++;
		if (x->st->timing)
			c0 = vx_cycles();
	}
	do {
		nk = scan(x, list, n, a, b, after, kept, &more);
		if (x->st != NULL && x->st->timing) {
			x->st->cyc_isect += vx_cycles() - c0;
			c0 = vx_cycles();
		}
		for (i = 0; i < nk; i++) {
			vx_tethit h;

			h.t = kept[i].t;
			h.tet = kept[i].tet;
			h.iso = kept[i].iso;
			h.enter = kept[i].enter;
			vx_tet_normal(x->m, h.tet, &x->ray, h.enter ? 1 : -1, h.n);
			if (x->st != NULL)
				x->st->hits++;
			if ((rc = x->fn(x->ctx, &h)) != 0)
				return rc;
		}
		if (nk > 0) {
			last = kept[nk - 1];
			after = &last;
		}
		if (x->st != NULL && x->st->timing)
			c0 = vx_cycles();
	} while (more);
	return 0;
}

/* As vx_tetleaf_nearest's visitor: each leaf over its own [t0, t1), the
 * first one from tmin. */
static int
trace_visit(void *p, const vx_leaf_visit *v)
{
	trace_ctx *x = p;
	double t0 = x->nvisit == 0 ? x->tmin : v->t0;

	x->nvisit++;
	x->last = v->leaf;
	x->last_t1 = v->t1;
	return leaf_trace(x, v->leaf, t0, v->t1);
}

int
vx_tetleaf_trace(const vx_tetleaf *lg, const vx_tetmesh *m,
    const double o[3], const double d[3], const double *iso, int niso,
    double tmin, double tmax, vx_tethit_fn fn, void *ctx,
    vx_tettrace_stats *st)
{
	float vals[64];
	double lo[3], ld[3];
	trace_ctx x;
	int nv, rc;

	if (st != NULL)
		st->rays++;
	if (lg->off == NULL || niso <= 0)
		return 0;
	_Static_assert(NSEG == 64, "the valid mask has 64 bits");
	nv = vx_tetleaf_walk_setup(lg, o, d, iso, niso, lo, ld, vals);
	/* everything but the cache, which is marked empty by x.valid */
	memset(&x, 0, offsetof(trace_ctx, cache));
	x.lg = lg;
	x.m = m;
	vx_tetray_init(&x.ray, o, d);
	x.iso = iso;
	x.niso = niso;
	x.tmin = tmin;
	x.tmax = tmax;
	x.fn = fn;
	x.ctx = ctx;
	x.st = st;
	x.valid = 0;
	rc = vx_macro_traverse(&lg->mc, NULL, lo, ld, tmin, tmax, vals, nv,
	    trace_visit, &x, st != NULL ? &st->trav : NULL);
	if (rc != 0)
		return rc;
	/* the last leaf again, up to tmax: a crossing that rounding puts past
	 * the walk's end (nothing before last_t1 is reported twice) */
	if (x.nvisit > 0)
		return leaf_trace(&x, x.last, x.last_t1, tmax);
	return 0;
}
