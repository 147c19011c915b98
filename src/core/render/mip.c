/* mip.c: exact maximum-intensity projection with a priority queue of
 * macrocells (see vx_mip.h).
 *
 * Three implementations of the same answer: the plain one (walk() with a
 * visitor per cell: emit_macro, emit_cell/solve); by default the
 * specialized one (macro_walk, cells_walk_t), which repeats the plain
 * one's arithmetic operation for operation (crossing times, segment ends,
 * the cubic and its maximum, the comparisons) and so gives the same bits
 * and the same counts, measured 1.35 to 1.55 times faster on the ch2 and
 * Visible Human heads; and for rays along an axis through integer samples
 * the column walk (column_t), which needs no queue (the rule of vx_mip.h
 * makes the order free) and solves about one cell per ray
 * (examples/bench/RESULTS-mip.md; mipcolumn.c).  test_mip checks them
 * against each other and against the exhaustive walk ray by ray. */
#include "vx_mip.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mip_priv.h"
#include "vx_cell.h"

typedef struct qent {
	float key;          /* the cell's stored maximum */
	int32_t level;      /* 1..nlev */
	int32_t c[3];       /* cell index at that level (dims <= 2^20) */
	double t0, t1;      /* the ray's segment in the cell */
} qent;

/* before: the strict total order of the queue: larger key first, then
 * smaller t0, lower level, smaller index.  Strict, so the pop order depends
 * only on the set of entries, not on the heap's history: that is what makes
 * the result independent of the last-t bound. */
static int
before(const qent *a, const qent *b)
{
	if (a->key != b->key)
		return a->key > b->key;
	if (a->t0 != b->t0)
		return a->t0 < b->t0;
	if (a->level != b->level)
		return a->level < b->level;
	for (int i = 2; i >= 0; i--)
		if (a->c[i] != b->c[i])
			return a->c[i] < b->c[i];
	return 0;
}

typedef struct heap {
	qent *e;
	size_t n, cap;
} heap;

static void
heap_push(heap *h, const qent *x)
{
	size_t i = h->n++;

	while (i > 0) {
		size_t p = (i - 1) / 2;

		if (!before(x, &h->e[p]))
			break;
		h->e[i] = h->e[p];
		i = p;
	}
	h->e[i] = *x;
}

static qent
heap_pop(heap *h)
{
	qent top = h->e[0], x = h->e[--h->n];
	size_t i = 0;

	for (;;) {
		size_t l = 2 * i + 1, r = l + 1, b = l;

		if (l >= h->n)
			break;
		if (r < h->n && before(&h->e[r], &h->e[l]))
			b = r;
		if (!before(&h->e[b], &x))
			break;
		h->e[i] = h->e[b];
		i = b;
	}
	if (h->n > 0)
		h->e[i] = x;
	return top;
}

int
vx_mip_work_init(vx_mip_work *w, const vx_macro *m, vx_err *e)
{
	size_t cap = 16;
	int l;

	memset(w, 0, sizeof *w);
	w->last_t = NAN;
	for (l = 1; m != NULL && l <= m->nlev; l++)
		cap += (size_t)(m->dims[l][0] + m->dims[l][1] + m->dims[l][2]) + 3;
	if ((w->q = calloc(cap, sizeof(qent))) == NULL)
		return vx_err_set(e, VX_ENOMEM, "mip: out of memory for the queue");
	w->cap = cap;
	w->cc = vx_mip_colcache_new(m);
	return 0;
}

void
vx_mip_work_free(vx_mip_work *w)
{
	free(w->q);
	free(w->cc);
	memset(w, 0, sizeof *w);
}


/* clip: the ray's parameter interval inside the box [0, n] (leaf space);
 * returns 0 when empty. */
static int
clip(const int64_t n[3], const double o[3], const double d[3], double *ta,
    double *tb)
{
	for (int a = 0; a < 3; a++) {
		if (d[a] == 0) {
			if (!(o[a] >= 0 && o[a] <= (double)n[a]))
				return 0;
			continue;
		}
		double t0 = (0 - o[a]) / d[a], t1 = ((double)n[a] - o[a]) / d[a];

		if (t0 > t1) {
			double s = t0;
			t0 = t1;
			t1 = s;
		}
		if (t0 > *ta)
			*ta = t0;
		if (t1 < *tb)
			*tb = t1;
	}
	return *ta <= *tb;
}

typedef void (*emit_fn)(void *ctx, const int64_t c[3], double t0,
    double t1);

/* walk: the cells (index c, covering leaves [c w, min((c+1) w, n)) per axis)
 * with clo <= c <= chi that o + t d passes through for t in [ta, tb], in
 * order.  Crossing times are computed directly from the integer plane
 * position, never accumulated, so every walk over the same planes gets the
 * same bits. */
static void
walk(const double o[3], const double d[3], double ta, double tb,
    const int64_t w[3], const int64_t n[3], const int64_t clo[3],
    const int64_t chi[3], emit_fn fn, void *ctx)
{
	int64_t c[3];
	double tn[3], tq[3], t = ta;
	int a, step[3];
	long guard;

	walk_start(o, d, ta, w, n, clo, chi, c, step, tn, tq);
	for (guard = 0; guard < 1L << 40; guard++) {
		a = tn[0] <= tn[1] ? (tn[0] <= tn[2] ? 0 : 2) :
		    (tn[1] <= tn[2] ? 1 : 2);
		double t1 = tn[a] < tb ? tn[a] : tb;

		if (t1 >= t)
			fn(ctx, c, t, t1);
		if (!(tn[a] < tb))
			break;
		c[a] += step[a];
		if (c[a] < clo[a] || c[a] > chi[a])
			break;
		if (t1 > t)
			t = t1;
		tn[a] = exit_t(o, d, step, w, n, a, c[a]);
	}
}

typedef struct mip_ctx {
	const vx_grid *g;
	const vx_macro *m;
	const double *o, *d;
	heap h;
	int level;            /* level of the cells being emitted */
	double lb;            /* push threshold (last-t bound), or -Inf */
	double best, tbest;
	int found;
	int prune;            /* 1: skip cells that cannot beat best */
	int axis;             /* 0..2: d is zero but along this axis (and the
	                         ray is tame: tame_axis); -1: any other */
	vx_mip_stats *st;
} mip_ctx;

/* solve: the exact maximum of data cell c on [t0, t1]. */
static void
solve(mip_ctx *x, const int64_t c[3], double t0, double t1)
{
	float v[8], cmax, cmin;
	double ol[3], k[4], tm, fm;
	int i;

	vx_grid_cell(x->g, c[0], c[1], c[2], v);
	if (!vx_cell_finite(v))
		return;
	cmax = cmin = v[0];
	for (i = 1; i < 8; i++) {
		if (v[i] > cmax)
			cmax = v[i];
		if (v[i] < cmin)
			cmin = v[i];
	}
	if (x->prune && !beats(x->found, cmax, t0, x->best, x->tbest)) {
		if (x->st)
			x->st->cells_skipped++;
		return;
	}
	for (i = 0; i < 3; i++)
		ol[i] = (x->o[i] + t0 * x->d[i]) - (double)c[i];
	vx_cell_poly(v, ol, x->d, 0, k);
	if (x->st)
		x->st->cells++;
	if (!vx_cell_max(k, 0, t1 - t0, &tm, &fm))
		return;
	clamp_fold(fm, t0 + tm, cmin, cmax, &x->best, &x->tbest, &x->found);
}

static void
emit_cell(void *ctx, const int64_t c[3], double t0, double t1)
{
	solve(ctx, c, t0, t1);
}

/* emit_macro: walk()'s visitor for level-x->level macrocells (the plain
 * path): push the cell unless the last-t bound or the best value rules it
 * out. */
static void
emit_macro(void *ctx, const int64_t c[3], double t0, double t1)
{
	mip_ctx *x = ctx;
	float lo, hi;
	qent q;

	vx_macro_cell_range(x->m, x->level, c[0], c[1], c[2], &lo, &hi);
	if (!(hi >= lo))          /* empty: no finite sample */
		return;
	if ((double)hi < x->lb) {
		if (x->st)
			x->st->bound_pruned++;
		return;
	}
	if (!beats(x->found, hi, t0, x->best, x->tbest))
		return;
	q.key = hi;
	q.level = x->level;
	for (int i = 0; i < 3; i++)
		q.c[i] = (int32_t)c[i];
	q.t0 = t0;
	q.t1 = t1;
	if (x->h.n < x->h.cap) {
		heap_push(&x->h, &q);
		if (x->st) {
			x->st->pushes++;
			if (x->h.n > x->st->max_queue)
				x->st->max_queue = x->h.n;
		}
	}
}

/* The walks below repeat walk()'s arithmetic exactly (the same cells, the
 * same crossing times), fused with what is done per cell, and compute the
 * next crossing time along an axis one step ahead, so that the division
 * is off the loop's critical path. */

/* macro_walk: walk() over level-l macrocells clo..chi of [ta, tb] with
 * emit_macro(): push each one whose maximum can beat both the last-t bound
 * and the best value. */
static void
macro_walk(mip_ctx *x, int l, double ta, double tb, const int64_t clo[3],
    const int64_t chi[3])
{
	const vx_macro *m = x->m;
	const int64_t *w = m->width[l], *n = m->dims[0];
	const double o[3] = { x->o[0], x->o[1], x->o[2] };
	const double d[3] = { x->d[0], x->d[1], x->d[2] };
	const float *mm = m->mm[l];
	int64_t c[3], stride[3], idx;
	double tn[3], tq[3], t = ta, lb = x->lb, best = x->best;
	double tbest = x->tbest;
	int a, step[3], found = x->found;
	uint64_t pushes = 0, pruned = 0, maxq = 0;
	long guard;

	walk_start(o, d, ta, w, n, clo, chi, c, step, tn, tq);
	stride[0] = 1;
	stride[1] = m->dims[l][0];
	stride[2] = m->dims[l][0] * m->dims[l][1];
	idx = c[0] + stride[1] * c[1] + stride[2] * c[2];
	for (guard = 0; guard < 1L << 40; guard++) {
		a = tn[0] <= tn[1] ? (tn[0] <= tn[2] ? 0 : 2) :
		    (tn[1] <= tn[2] ? 1 : 2);
		double ta1 = tn[a], t1 = ta1 < tb ? ta1 : tb;

		if (t1 >= t) {
			float lo = mm[2 * idx], hi = mm[2 * idx + 1];

			if (!(hi >= lo)) {
				/* empty: no finite sample */
			} else if ((double)hi < lb) {
				pruned++;
			} else if (!beats(found, hi, t, best, tbest)) {
				/* cannot beat the best value */
			} else if (x->h.n < x->h.cap) {
				qent q;

				q.key = hi;
				q.level = l;
				for (int i = 0; i < 3; i++)
					q.c[i] = (int32_t)c[i];
				q.t0 = t;
				q.t1 = t1;
				heap_push(&x->h, &q);
				pushes++;
				if (x->h.n > maxq)
					maxq = x->h.n;
			}
		}
		if (!(ta1 < tb))
			break;
		c[a] += step[a];
		if (c[a] < clo[a] || c[a] > chi[a])
			break;
		if (t1 > t)
			t = t1;
		idx += step[a] * stride[a];
		tn[a] = tq[a];
		tq[a] = exit_t(o, d, step, w, n, a, c[a] + step[a]);
	}
	if (x->st) {
		x->st->pushes += pushes;
		x->st->bound_pruned += pruned;
		if (maxq > x->st->max_queue)
			x->st->max_queue = maxq;
	}
}

/* cells_walk_t: walk() over the data cells clo..chi of [ta, tb] with
 * solve(), specialized by sample type: the same decisions in the same
 * order, so the same bits.  The corners are read straight through the
 * layout's offset tables (only the stepped axis's offsets change), their
 * maximum is taken in the sample type and converted only for a cell that
 * is solved, integer samples skip the finiteness test (always finite), the
 * cubic and its maximum are vx_cell_poly_inline() and max0(), and the best
 * value lives in registers. */
MIP_INLINE void
cells_walk_t(mip_ctx *x, double ta, double tb, const int64_t clo[3],
    const int64_t chi[3], const vx_type ty)
{
	static const int64_t one[3] = { 1, 1, 1 };
	const vx_grid *g = x->g;
	const int64_t *n = x->m->dims[0], *off[3] = { g->lay.off[0],
	    g->lay.off[1], g->lay.off[2] };
	const double o[3] = { x->o[0], x->o[1], x->o[2] };
	const double d[3] = { x->d[0], x->d[1], x->d[2] };
	int64_t c[3], base, dx, dy, dz;
	double tn[3], tq[3], t = ta, best = x->best, tbest = x->tbest;
	int a, step[3], found = x->found;
	uint64_t solved = 0, skipped = 0;
	long guard;

	walk_start(o, d, ta, one, n, clo, chi, c, step, tn, tq);
	/* the cell's corner 0 in the layout, and the steps to the others */
	base = off[0][c[0]] + off[1][c[1]] + off[2][c[2]];
	dx = off[0][c[0] + 1] - off[0][c[0]];
	dy = off[1][c[1] + 1] - off[1][c[1]];
	dz = off[2][c[2] + 1] - off[2][c[2]];
	for (guard = 0; guard < 1L << 40; guard++) {
		a = tn[0] <= tn[1] ? (tn[0] <= tn[2] ? 0 : 2) :
		    (tn[1] <= tn[2] ? 1 : 2);
		double ta1 = tn[a], t1 = ta1 < tb ? ta1 : tb;

		if (t1 >= t) {
			float v[8], cmax;
			int i, fin = 1;

			/* FETCH: the corners' maximum, and the corners as
			 * floats unless it prunes the cell (the break leaves
			 * the do-while; the test below then prunes) */
#define FETCH(T)                                                           \
	do {                                                               \
		const T *p = (const T *)g->data + base;                    \
		T w0 = p[0], w1 = p[dx], w2 = p[dy], w3 = p[dx + dy];      \
		T w4 = p[dz], w5 = p[dx + dz], w6 = p[dy + dz];            \
		T w7 = p[dx + dy + dz];                                    \
		T m01 = w1 > w0 ? w1 : w0, m23 = w3 > w2 ? w3 : w2;        \
		T m45 = w5 > w4 ? w5 : w4, m67 = w7 > w6 ? w7 : w6;        \
		T ma = m23 > m01 ? m23 : m01, mb = m67 > m45 ? m67 : m45;  \
		cmax = (float)(mb > ma ? mb : ma);                         \
		if (!beats(found, cmax, t, best, tbest))                   \
			break;                                             \
		v[0] = (float)w0; v[1] = (float)w1; v[2] = (float)w2;      \
		v[3] = (float)w3; v[4] = (float)w4; v[5] = (float)w5;      \
		v[6] = (float)w6; v[7] = (float)w7;                        \
	} while (0)
			switch (ty) {
			case VX_U8: FETCH(uint8_t); break;
			case VX_U16: FETCH(uint16_t); break;
			case VX_I16: FETCH(int16_t); break;
			default: {
				const float *p = (const float *)g->data + base;

				v[0] = p[0];
				v[1] = p[dx];
				v[2] = p[dy];
				v[3] = p[dx + dy];
				v[4] = p[dz];
				v[5] = p[dx + dz];
				v[6] = p[dy + dz];
				v[7] = p[dx + dy + dz];
				fin = vx_cell_finite(v);
				/* solve()'s order: the first corner, then
				 * strictly larger ones */
				cmax = v[0];
				for (i = 1; i < 8; i++)
					if (v[i] > cmax)
						cmax = v[i];
				break;
			}
			}
#undef FETCH
			if (!fin) {
				/* no value from this cell */
			} else if (!beats(found, cmax, t, best, tbest)) {
				skipped++;
			} else {
				solve_cell(v, c, o, d, t, t1, &best, &tbest,
				    &found);
				solved++;
			}
		}
		if (!(ta1 < tb))
			break;
		c[a] += step[a];
		if (c[a] < clo[a] || c[a] > chi[a])
			break;
		if (t1 > t)
			t = t1;
		{
			int64_t l0 = off[a][c[a] - step[a]], l1 = off[a][c[a]];
			int64_t h1 = off[a][c[a] + 1];

			base += l1 - l0;
			if (a == 0)
				dx = h1 - l1;
			else if (a == 1)
				dy = h1 - l1;
			else
				dz = h1 - l1;
		}
		tn[a] = tq[a];
		tq[a] = exit_t(o, d, step, one, n, a, c[a] + step[a]);
	}
	x->best = best;
	x->tbest = tbest;
	x->found = found;
	if (x->st) {
		x->st->cells += solved;
		x->st->cells_skipped += skipped;
	}
}

/* cells: the walk over data cells clo..chi of [ta, tb]. */
static void
cells(mip_ctx *x, double ta, double tb, const int64_t clo[3],
    const int64_t chi[3])
{
	/* cells_walk_t made for each sample type */
	switch (x->g->type) {
	case VX_U8: cells_walk_t(x, ta, tb, clo, chi, VX_U8); break;
	case VX_U16: cells_walk_t(x, ta, tb, clo, chi, VX_U16); break;
	case VX_I16: cells_walk_t(x, ta, tb, clo, chi, VX_I16); break;
	default: cells_walk_t(x, ta, tb, clo, chi, VX_F32); break;
	}
}

/* tame_axis: the axis a ray runs along when the other two components of
 * d are zero and its numbers are tame (|o[a]| <= 2^20, 2^-20 <= |d[a]| <=
 * 2^20, ta and tb finite: the column walk's margin holds), else -1. */
static int
tame_axis(const double o[3], const double d[3], double ta, double tb)
{
	int a, A = -1;

	for (a = 0; a < 3; a++) {
		if (d[a] == 0)
			continue;
		if (A >= 0)
			return -1;
		A = a;
	}
	if (A < 0 || !(fabs(o[A]) <= 0x1p20) || !(fabs(d[A]) >= 0x1p-20) ||
	    !(fabs(d[A]) <= 0x1p20) || !isfinite(ta) || !isfinite(tb))
		return -1;
	return A;
}

/* children: the index range of level-(l-1) cells inside level-l cell c. */
static void
children(const vx_macro *m, int l, const int32_t c[3], int64_t lo[3],
    int64_t hi[3])
{
	for (int a = 0; a < 3; a++) {
		lo[a] = c[a] * m->size[l][a];
		hi[a] = lo[a] + m->size[l][a] - 1;
		if (hi[a] > m->dims[l - 1][a] - 1)
			hi[a] = m->dims[l - 1][a] - 1;
	}
}

/* ---- volumes with an axis of one sample (no cells) ----
 * The samples span a plane, a line or a point, and the field there is the
 * bilinear (linear) interpolation of its neighbouring samples: the slice
 * itself.  A ray with d nonzero along a one-sample axis meets that span at
 * one t, and its maximum is the field there; a ray inside the span (o and
 * d zero along every one-sample axis) crosses cells of the other axes, and
 * its maximum is vx_mip.h's rule over them (each cell's cubic maximum,
 * clamped into its corners' range, the smallest t among equal values). */

/* flat_cell: the corners of cell c (flat: its one-sample axes duplicated)
 * with their range; 0 when one is not finite */
static int
flat_cell(const vx_grid *g, const int64_t c[3], float v[8], float *lo,
    float *hi)
{
	int i, a;

	for (i = 0; i < 8; i++) {
		int64_t q[3];

		for (a = 0; a < 3; a++)
			q[a] = c[a] + (g->dims[a] >= 2 ? (i >> a & 1) : 0);
		v[i] = (float)vx_grid_get(g, q[0], q[1], q[2]);
	}
	if (!vx_cell_finite(v))
		return 0;
	*lo = *hi = v[0];
	for (i = 1; i < 8; i++) {
		*lo = v[i] < *lo ? v[i] : *lo;
		*hi = v[i] > *hi ? v[i] : *hi;
	}
	return 1;
}

/* flat_index: the cell holding coordinate p along an axis of n >= 1
 * samples, floor(p) in [0, n - 2] (0 for n == 1; NaN: 0), clamped before
 * the conversion */
static int64_t
flat_index(double p, int64_t n)
{
	double f = floor(p);

	return n < 2 || !(f >= 0) ? 0 : f >= (double)(n - 2) ? n - 2 :
	    (int64_t)f;
}

static int
flat_ray(const vx_grid *g, const double o[3], const double d[3], double tmin,
    double tmax, double *vmax, double *tmaxp)
{
	double ts = NAN, ta = tmin, tb = tmax, best = 0, tbest = 0;
	int a, found = 0, pinned = 0;
	int64_t c[3];
	float v[8], lo, hi;

	for (a = 0; a < 3; a++) {
		if (g->dims[a] >= 2)
			continue;
		if (d[a] != 0) {
			double t = -o[a] / d[a];

			/* two one-sample axes crossed at different t: the ray
			 * passes beside the line or point */
			if (pinned && !(t == ts))
				return 0;
			ts = t;
			pinned = 1;
		} else if (o[a] != 0)
			return 0;
	}
	if (pinned) {
		double l[3], f;

		if (!(ts >= tmin && ts <= tmax))
			return 0;
		for (a = 0; a < 3; a++) {
			double p = g->dims[a] >= 2 ? o[a] + ts * d[a] : 0;

			if (!(p >= 0 && p <= (double)(g->dims[a] - 1)))
				return 0;
			c[a] = flat_index(p, g->dims[a]);
			l[a] = p - (double)c[a];
		}
		if (!flat_cell(g, c, v, &lo, &hi))
			return 0;
		f = vx_cell_trilinear(v, l);
		*vmax = f > hi ? hi : f < lo ? lo : f;
		*tmaxp = ts;
		return 1;
	}
	/* inside the span: clip to it, then cell by cell along the axes the
	 * ray moves on (crossing times of their integer planes in order) */
	for (a = 0; a < 3; a++) {
		double t0, t1;

		if (g->dims[a] < 2 || d[a] == 0) {
			if (!(o[a] >= 0 && o[a] <= (double)(g->dims[a] - 1)))
				return 0;
			continue;
		}
		t0 = (0 - o[a]) / d[a];
		t1 = ((double)(g->dims[a] - 1) - o[a]) / d[a];
		if (t0 > t1) {
			double s = t0;
			t0 = t1;
			t1 = s;
		}
		ta = t0 > ta ? t0 : ta;
		tb = t1 < tb ? t1 : tb;
	}
	if (!(ta <= tb) || !isfinite(ta) || !isfinite(tb))
		return 0;
	for (double t0 = ta;;) {
		double t1 = tb, tm, ol[3], k[4], tt, fm;

		/* the next integer plane after t0 on each moving axis */
		for (a = 0; a < 3; a++) {
			double p, q, tp;

			if (g->dims[a] < 2 || d[a] == 0)
				continue;
			p = o[a] + t0 * d[a];
			q = d[a] > 0 ? floor(p) + 1 : ceil(p) - 1;
			tp = (q - o[a]) / d[a];
			if (!(tp > t0))     /* rounding: the plane after */
				tp = ((q + (d[a] > 0 ? 1 : -1)) - o[a]) / d[a];
			t1 = tp < t1 ? tp : t1;
		}
		if (!(t1 > t0))     /* no progress (extreme o, d): the rest */
			t1 = tb;
		tm = t0 + 0.5 * (t1 - t0);
		for (a = 0; a < 3; a++)
			c[a] = g->dims[a] >= 2 ? flat_index(o[a] + tm * d[a],
			    g->dims[a]) : 0;
		if (flat_cell(g, c, v, &lo, &hi)) {
			for (a = 0; a < 3; a++)
				ol[a] = (o[a] + t0 * d[a]) - (double)c[a];
			vx_cell_poly(v, ol, d, 0, k);
			if (vx_cell_max(k, 0, t1 - t0, &tt, &fm))
				clamp_fold(fm, t0 + tt, lo, hi, &best, &tbest,
				    &found);
		}
		if (!(t1 < tb))
			break;
		t0 = t1;
	}
	if (!found)
		return 0;
	*vmax = best;
	*tmaxp = tbest;
	return 1;
}

int
vx_mip_ray(const vx_grid *g, const vx_macro *m, vx_mip_work *w,
    const double o[3], const double d[3], double tmin, double tmax,
    int use_last_t, double *vmax, double *tmaxp, vx_mip_stats *st)
{
	const int64_t *n = m->dims[0];
	int64_t one[3] = { 1, 1, 1 }, zero[3] = { 0, 0, 0 }, top[3];
	double ta = tmin, tb = tmax;
	mip_ctx x;
	int a, L = m->nlev, col;

	*vmax = -INFINITY;
	*tmaxp = INFINITY;
	if (st)
		st->rays++;
	if (g->dims[0] < 2 || g->dims[1] < 2 || g->dims[2] < 2)
		return flat_ray(g, o, d, tmin, tmax, vmax, tmaxp);
	if (n[0] < 1 || n[1] < 1 || n[2] < 1 || !clip(n, o, d, &ta, &tb))
		return 0;
	memset(&x, 0, sizeof x);
	x.g = g;
	x.m = m;
	x.o = o;
	x.d = d;
	x.h.e = w->q;
	x.h.cap = w->cap;
	x.lb = -INFINITY;
	x.prune = 1;
	x.axis = tame_axis(o, d, ta, tb);
	x.st = st;
	if (use_last_t) {
		/* a trilinear sample: a lower bound on the maximum, relaxed by
		 * far more than rounding so it never prunes the true maximum */
		double ts = w->last_t >= ta && w->last_t <= tb ? w->last_t :
		    0.5 * (ta + tb), p[3], l[3];
		int64_t c[3];
		float v[8];

		for (a = 0; a < 3; a++) {
			p[a] = o[a] + ts * d[a];
			/* floor(p) in [0, n - 1], clamped before the
			 * conversion (a far camera's p can be NaN: cell 0) */
			c[a] = !(p[a] >= 1) ? 0 : p[a] >= (double)(n[a] - 1) ?
			    n[a] - 1 : (int64_t)p[a];
			l[a] = p[a] - (double)c[a];
		}
		vx_grid_cell(g, c[0], c[1], c[2], v);
		if (vx_cell_finite(v)) {
			double s = vx_cell_trilinear(v, l);

			if (isfinite(s))
				x.lb = s - fabs(s) * 1e-9 - 1e-300;
		}
	}
	col = -1;
	if (!w->plain && x.axis >= 0 && w->cc != NULL && (g->type == VX_U8 ||
	    g->type == VX_U16 || g->type == VX_I16)) {
		col = vx_mip_column(g, m, w->cc, o, d, ta, tb, x.lb, x.axis,
		    &x.best, &x.tbest, st);
		x.found = col == 1;
	}
	if (col >= 0) {
		/* done */
	} else if (L == 0) {
		int64_t hi[3] = { n[0] - 1, n[1] - 1, n[2] - 1 };

		if (w->plain)
			walk(o, d, ta, tb, one, n, zero, hi, emit_cell, &x);
		else
			cells(&x, ta, tb, zero, hi);
	} else {
		for (a = 0; a < 3; a++)
			top[a] = m->dims[L][a] - 1;
		x.level = L;
		if (w->plain)
			walk(o, d, ta, tb, m->width[L], n, zero, top, emit_macro,
			    &x);
		else
			macro_walk(&x, L, ta, tb, zero, top);
		while (x.h.n > 0) {
			qent q;
			int64_t lo[3], hi[3];

			if (!beats(x.found, x.h.e[0].key, x.h.e[0].t0, x.best,
			    x.tbest))
				break;
			q = heap_pop(&x.h);
			if (st) {
				st->pops++;
				st->macro_opened++;
			}
			children(m, q.level, q.c, lo, hi);
			x.level = q.level - 1;
			if (w->plain && q.level == 1)
				walk(o, d, q.t0, q.t1, one, n, lo, hi, emit_cell, &x);
			else if (w->plain)
				walk(o, d, q.t0, q.t1, m->width[x.level], n, lo, hi,
				    emit_macro, &x);
			else if (q.level == 1)
				cells(&x, q.t0, q.t1, lo, hi);
			else
				macro_walk(&x, x.level, q.t0, q.t1, lo, hi);
		}
	}
	if (!x.found)
		return 0;
	*vmax = x.best;
	*tmaxp = x.tbest;
	if (use_last_t)
		w->last_t = x.tbest;
	return 1;
}

int
vx_mip_ray_exhaustive(const vx_grid *g, const double o[3],
    const double d[3], double tmin, double tmax, double *vmax,
    double *tmaxp)
{
	int64_t n[3], one[3] = { 1, 1, 1 }, zero[3] = { 0, 0, 0 }, hi[3];
	double ta = tmin, tb = tmax;
	mip_ctx x;
	int a;

	*vmax = -INFINITY;
	*tmaxp = INFINITY;
	if (g->dims[0] < 2 || g->dims[1] < 2 || g->dims[2] < 2)
		return flat_ray(g, o, d, tmin, tmax, vmax, tmaxp);
	for (a = 0; a < 3; a++) {
		n[a] = g->dims[a] - 1;
		hi[a] = n[a] - 1;
	}
	if (n[0] < 1 || n[1] < 1 || n[2] < 1 || !clip(n, o, d, &ta, &tb))
		return 0;
	memset(&x, 0, sizeof x);
	x.g = g;
	x.o = o;
	x.d = d;
	x.lb = -INFINITY;
	walk(o, d, ta, tb, one, n, zero, hi, emit_cell, &x);
	if (!x.found)
		return 0;
	*vmax = x.best;
	*tmaxp = x.tbest;
	return 1;
}
