/* mip.c: exact maximum-intensity projection with a priority queue of
 * macrocells (see vx_mip.h). */
#include "vx_mip.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vx_cell.h"

typedef struct qent {
	float key;          /* the cell's stored maximum */
	int level;          /* 1..nlev */
	int64_t c[3];       /* cell index at that level */
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
	return 0;
}

void
vx_mip_work_free(vx_mip_work *w)
{
	free(w->q);
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
	double tn[3], t = ta;
	int a, step[3];
	long guard;

	for (a = 0; a < 3; a++) {
		double p = o[a] + ta * d[a];
		int64_t k = (int64_t)floor(p / (double)w[a]);

		/* on a plane going down: the cell below */
		if (d[a] < 0 && (double)(k * w[a]) == p)
			k--;
		if (k < clo[a])
			k = clo[a];
		if (k > chi[a])
			k = chi[a];
		c[a] = k;
		step[a] = d[a] > 0 ? 1 : d[a] < 0 ? -1 : 0;
	}
	for (a = 0; a < 3; a++) {
		int64_t hi = (c[a] + 1) * w[a] < n[a] ? (c[a] + 1) * w[a] : n[a];

		tn[a] = step[a] > 0 ? ((double)hi - o[a]) / d[a] :
		    step[a] < 0 ? ((double)(c[a] * w[a]) - o[a]) / d[a] :
		    INFINITY;
	}
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
		int64_t hi = (c[a] + 1) * w[a] < n[a] ? (c[a] + 1) * w[a] : n[a];
		tn[a] = step[a] > 0 ? ((double)hi - o[a]) / d[a] :
		    ((double)(c[a] * w[a]) - o[a]) / d[a];
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
	vx_mip_stats *st;
} mip_ctx;

/* solve: the exact maximum of data cell c on [t0, t1]. */
static void
solve(mip_ctx *x, const int64_t c[3], double t0, double t1)
{
	float v[8], cmax;
	double ol[3], k[4], tm, fm, t;
	int i;

	vx_grid_cell(x->g, c[0], c[1], c[2], v);
	if (!vx_cell_finite(v))
		return;
	cmax = v[0];
	for (i = 1; i < 8; i++)
		if (v[i] > cmax)
			cmax = v[i];
	if (x->prune && x->found && !((double)cmax > x->best)) {
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
	t = t0 + tm;
	if (!x->found || fm > x->best || (fm == x->best && t < x->tbest)) {
		x->best = fm;
		x->tbest = t;
		x->found = 1;
	}
}

static void
emit_cell(void *ctx, const int64_t c[3], double t0, double t1)
{
	solve(ctx, c, t0, t1);
}

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
	if (x->found && !((double)hi > x->best))
		return;
	q.key = hi;
	q.level = x->level;
	memcpy(q.c, c, sizeof q.c);
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

/* children: the index range of level-(l-1) cells inside level-l cell c. */
static void
children(const vx_macro *m, int l, const int64_t c[3], int64_t lo[3],
    int64_t hi[3])
{
	for (int a = 0; a < 3; a++) {
		lo[a] = c[a] * m->size[l][a];
		hi[a] = lo[a] + m->size[l][a] - 1;
		if (hi[a] > m->dims[l - 1][a] - 1)
			hi[a] = m->dims[l - 1][a] - 1;
	}
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
	int a, L = m->nlev;

	*vmax = -INFINITY;
	*tmaxp = INFINITY;
	if (st)
		st->rays++;
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
			c[a] = (int64_t)floor(p[a]);
			if (c[a] > n[a] - 1)
				c[a] = n[a] - 1;
			if (c[a] < 0)
				c[a] = 0;
			l[a] = p[a] - (double)c[a];
		}
		vx_grid_cell(g, c[0], c[1], c[2], v);
		if (vx_cell_finite(v)) {
			double s = vx_cell_trilinear(v, l);

			x.lb = s - fabs(s) * 1e-9 - 1e-300;
		}
	}
	if (L == 0) {
		int64_t hi[3] = { n[0] - 1, n[1] - 1, n[2] - 1 };

		walk(o, d, ta, tb, one, n, zero, hi, emit_cell, &x);
	} else {
		for (a = 0; a < 3; a++)
			top[a] = m->dims[L][a] - 1;
		x.level = L;
		walk(o, d, ta, tb, m->width[L], n, zero, top, emit_macro, &x);
		while (x.h.n > 0) {
			qent q;
			int64_t lo[3], hi[3];

			if (x.found && !((double)x.h.e[0].key > x.best))
				break;
			q = heap_pop(&x.h);
			if (st) {
				st->pops++;
				st->macro_opened++;
			}
			children(m, q.level, q.c, lo, hi);
			if (q.level == 1) {
				walk(o, d, q.t0, q.t1, one, n, lo, hi, emit_cell, &x);
			} else {
				x.level = q.level - 1;
				walk(o, d, q.t0, q.t1, m->width[x.level], n, lo, hi,
				    emit_macro, &x);
			}
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
