/* iso.c: rays against isosurfaces of a volume: traversal + cell kernel. */
#include "vx_iso.h"

#include <math.h>
#include <string.h>
#include <time.h>

#include "vx_camera.h"

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

uint64_t
vx_cycles(void)
{
#if defined(__x86_64__) || defined(__i386__)
	return (uint64_t)__rdtsc();
#else
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
#endif
}

typedef struct iso_ctx {
	const vx_iso_tracer *tr;
	const double *o, *d;
	const double *iso;       /* the isovalues, as given */
	float fiso[VX_ISO_MAX];  /* each rounded to float, for the walk's
	                            bracket tests (a superset: vx_iso.h) */
	double pend[VX_ISO_MAX]; /* per isovalue: the t where the last cell
	                            visited ended at a face value exactly
	                            iso reached from above (a touch there if
	                            the next cell leaves it upward), or NaN */
	int niso;
	unsigned exact;          /* signs decided exactly (the slow path) */
	vx_iso_hit_fn fn;
	void *ctx;
	vx_iso_stats *st;
	double xs0, dmag;        /* 2 sum |o_a| + 16, sum |d_a|
	                            (ends_certain) */
} iso_ctx;

/* The two axes other than a, lower first: u runs along the first. */
static const int other[3][2] = { { 1, 2 }, { 0, 2 }, { 0, 1 } };

/* face_field: the field on face (axis, side) of leaf v where the ray is at
 * t.  The point o + t d is computed exactly as the neighbouring cell
 * computes it (same o, d, t), and so are the in-face coordinates: both cells
 * get the same bits. */
static double
face_field(const vx_leaf_visit *v, const double *o, const double *d,
    double t, int axis, int side)
{
	int b = other[axis][0], c = other[axis][1];
	double u = (o[b] + t * d[b]) - (double)v->i[b];
	double w = (o[c] + t * d[c]) - (double)v->i[c];

	return vx_cell_face_value_fin(v->c, axis, side, u, w);   /* finite8 */
}

static double
inner_field(const vx_leaf_visit *v, const double *o, const double *d,
    double t)
{
	double p[3];
	int a;

	for (a = 0; a < 3; a++)
		p[a] = (o[a] + t * d[a]) - (double)v->i[a];
	return vx_cell_trilinear(v->c, p);
}

#define MAXROOTS 3   /* a cubic crosses a value at most 3 times */

/* finite8: 1 if all 8 corners are finite, as vx_cell_finite, without a
 * call or a branch per corner: x * 0 is 0 for finite x, NaN otherwise. */
static inline int
finite8(const float c[8])
{
	float z = (c[0] * 0.0f + c[1] * 0.0f) + (c[2] * 0.0f + c[3] * 0.0f) +
	    ((c[4] * 0.0f + c[5] * 0.0f) + (c[6] * 0.0f + c[7] * 0.0f));

	return z == 0.0f;
}

/* fill: the hit at local root r (kind, entering) of surface s in leaf v. */
static void
fill(vx_iso_hit *h, const iso_ctx *x, const vx_leaf_visit *v, double r,
    int s, int kind, int entering)
{
	int a;

	h->t = v->t0 + r;
	if (h->t > v->t1)     /* rounding of t0 + r */
		h->t = v->t1;
	h->surface = s;
	h->kind = kind;
	h->entering = entering;
	memcpy(h->cell, v->i, sizeof h->cell);
	memcpy(h->c, v->c, sizeof h->c);
	for (a = 0; a < 3; a++)
		h->p[a] = x->o[a] + h->t * x->d[a];
}

/* face_sgn: the sign (+1, -1) of face_field - iso on face (axis, side)
 * from the face's four corners alone, when they decide it: all above iso
 * or all below (vx_cell_face_value clamps into their [min, max], and a
 * difference of doubles has the sign of a - b).  0 when they do not (one
 * of them equals iso, or they straddle it). */
static int
face_sgn(const float *c, int axis, int side, double iso)
{
	int base = side << axis, bu = 1 << other[axis][0];
	int bv = 1 << other[axis][1];
	double c00 = c[base], c10 = c[base | bu], c01 = c[base | bv];
	double c11 = c[base | bu | bv];

	if (c00 > iso && c10 > iso && c01 > iso && c11 > iso)
		return 1;
	if (c00 < iso && c10 < iso && c01 < iso && c11 < iso)
		return -1;
	return 0;
}

/* ends: the field at the segment's entry (0) and exit (1), computed once,
 * on demand. */
typedef struct ends {
	double e[2];
	int have[2];
} ends;

static double
end_field(ends *E, const iso_ctx *x, const vx_leaf_visit *v, int w)
{
	if (!E->have[w]) {
		int axis = w ? v->exit_axis : v->entry_axis;
		int side = w ? v->exit_side : v->entry_side;
		double t = w ? v->t1 : v->t0;

		E->e[w] = axis >= 0 ? face_field(v, x->o, x->d, t, axis, side) :
		    inner_field(v, x->o, x->d, t);
		E->have[w] = 1;
	}
	return E->e[w];
}

/* end_sgn: the sign (+1, 0, -1) of end_field - iso, from the face
 * corners when they decide. */
static int
end_sgn(ends *E, const iso_ctx *x, const vx_leaf_visit *v, int w,
    double iso)
{
	int axis = w ? v->exit_axis : v->entry_axis;
	int p = 0;
	double f;

	if (axis >= 0 && !E->have[w])
		p = face_sgn(v->c, axis, w ? v->exit_side : v->entry_side, iso);
	if (p == 0) {
		f = end_field(E, x, v, w) - iso;
		p = f > 0 ? 1 : f < 0 ? -1 : 0;
	}
	return p;
}

/* outside: the distance from q to [0, 1] (q not NaN), without a branch
 * where SSE2 has a max (q near a face is on either side of it by
 * rounding, at random) */
static inline double
outside(double q)
{
#if defined(__SSE2__)
	__m128d v = _mm_set_sd(q);

	return _mm_cvtsd_f64(_mm_max_sd(_mm_max_sd(_mm_sub_sd(_mm_setzero_pd(),
	    v), _mm_sub_sd(v, _mm_set_sd(1.0))), _mm_setzero_pd()));
#else
	double a = -q > q - 1 ? -q : q - 1;

	return a > 0 ? a : 0;
#endif
}

/* onehot[a + 1][b]: 1.0 where b == a (a = -1: none) */
static const double onehot[4][3] = {
	{ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }
};

/* ends_certain: 1 when both end values minus iso (end_sgn: face values,
 * or the trilinear where an end lies inside the cell) certainly have the
 * signs of k0 and of k's value at len, the cubic's own ends, so that a
 * grazed cell (vx_cell_sign_bound) needs neither face.  Notation: u =
 * 2^-53, gamma_n = n u / (1 - n u); F the trilinear interpolant of the
 * corners c (exact, over all of R^3); M = max |c_i| <= max(|lo|, |hi|);
 * P(t) = o + t d - i exactly; the segment's ends as computed, q0 = ol
 * and q1 = fl(ol + fl(len d)); out(q) the distance from q to [0, 1].
 * The test asks out(q0_a), out(q1_a) < 1/4 on every axis (D0, D1 below
 * are at least their sums): then R_a = |ol_a| + len |d_a| <= 1.25 + 1.5
 * and W = prod_a (3 + 2 R_a) <= 8.5^3 < 1024.  X = 2 sum |o_a| + (2 |t0|
 * + |t1|) sum |d_a| + 16 bounds sum_a (|o_a| + (|t0| + |t1|) |d_a| +
 * |i_a| + 2), as |i_a| <= |o_a| + |t0 d_a| + |ol_a| + 1.
 * 1. The cubic.  vx_cell_poly's k_i are sums of products of c, iso, ol and
 *    d, each through at most 12 roundings, so |K(s) - (F(ol + s d) - iso)|
 *    <= gamma_12 A(s) for K(s) = sum k_i s^i evaluated exactly, where A(s)
 *    is the same nested interpolation with every quantity made absolute:
 *    A(s) <= M prod_a (1 + 2 (|ol_a| + s |d_a|)) + |iso| <= M W + |iso|
 *    for 0 <= s <= len (each level at most (1 + 2 R) times the one below,
 *    as |D| <= 2 M).  k0 = K(0) exactly; b3, vx_cell_sign_bound's last
 *    Bernstein coefficient, is within 8 u S <= 8 u (1 + gamma_12)(M W +
 *    |iso|) of K(len) (S = sum |k_i| len^i).
 * 2. The points.  ol_a = fl(fl(o_a + fl(t0 d_a)) - i_a) is within 3 u X of
 *    P_a(t0); face_field's in-face coordinates at t0 are the same
 *    expression; at t1 they are within 3 u X of P(t1), and q1 within 9 u X
 *    of it (len = fl(t1 - t0), and the roundings of ol + len d).  A face
 *    value takes its in-face coordinates clamped to [0, 1] and the face
 *    axis at its side (0 or 1): its point lies within D + 12 u X (1-norm)
 *    of the computed q, D = |q_e - side| on the face's axis e plus out(q_b)
 *    on the other two (D0, D1 add out on the face's axis too); inside (no
 *    face) it is within 6 u X of q.
 * 3. Lipschitz.  On the box of coordinates |z_a| <= R_a + 1 that holds
 *    both points, |dF/dz_a| <= 2 M (3 + 2 R_b)(3 + 2 R_c) <= M W.
 * 4. The value.  A face value is the bilinear interpolation of its four
 *    corners at in-face coordinates in [0, 1] (within gamma_4 3 M of the
 *    exact one, and its clamp into the corners' range only moves it
 *    towards the exact value); the trilinear inside is within gamma_9 M W
 *    of F at its computed point.  So |(end value - iso) - k0| and
 *    |(end value - iso) - b3| are at most (gamma_12 + 8 u + 2 gamma_9)
 *    (M W + |iso|) + M W (D + 24 u X) < 2^-47 (M W + |iso|) X + M W D,
 *    below e + 4 M W D, e = 2^-40 (1024 M + |iso|) X + 2^-1000 (the last
 *    term covers gradual underflow, at most 2^-1074 an operation), with
 *    room for the roundings of e itself.  Where |k0| and |b3| exceed
 *    their bounds, the end values minus iso are nonzero and of k0's and
 *    b3's signs, which vx_cell_sign_bound's nonzero answer says are its
 *    own (its b0 is k0, its b3 is b3).  end_sgn is the sign of the end
 *    value minus iso (face_sgn answers only where the corners decide it),
 *    so the answer is that of end_sgn at both ends.  Overflow or NaN
 *    anywhere fails the test. */
static inline int
ends_certain(const iso_ctx *x, const vx_leaf_visit *v, const double ol[3],
    double len, double k0, double b3, double iso)
{
	/* lo..hi holds every corner (a leaf's min and max; +-Inf fails) */
	double m = fabs((double)v->lo) > fabs((double)v->hi) ?
	    fabs((double)v->lo) : fabs((double)v->hi);
	double d0 = 0, d1 = 0, e, lip;
	int a;

	/* the face's axis picked by a product, not a branch on the axis
	 * (which varies from cell to cell) */
	for (a = 0; a < 3; a++) {
		double q1 = ol[a] + len * x->d[a];

		d0 += outside(ol[a]) + onehot[v->entry_axis + 1][a] *
		    fabs(ol[a] - v->entry_side);
		d1 += outside(q1) + onehot[v->exit_axis + 1][a] *
		    fabs(q1 - v->exit_side);
	}
	e = 0x1p-40 * (1024 * m + fabs(iso)) * (x->xs0 + (2 * fabs(v->t0) +
	    fabs(v->t1)) * x->dmag) + 0x1p-1000;
	lip = 4096 * m;   /* 4 M W, W < 1024 */
	return d0 < 0.25 && d1 < 0.25 && fabs(k0) > e + lip * d0 &&
	    fabs(b3) > e + lip * d1;
}

/* no_root: nonzero when vx_cell_first_root(k, 0, len, f0, f1, any solver)
 * is certainly a miss and neither end value is exactly iso (no touch on
 * a face either): vx_cell_sign_bound, and both ends strictly of that
 * sign, from the cubic where ends_certain vouches for it (2), else from
 * the faces (1); so the call and perhaps the end values can be skipped. */
static int
no_root(ends *E, const iso_ctx *x, const vx_leaf_visit *v,
    const double ol[3], const double k[4], double len, double iso)
{
	double b3;
	int sg = vx_cell_sign_bound_b3(k, len, &b3);

	if (sg == 0)
		return 0;
	if (!x->tr->face_ends && ends_certain(x, v, ol, len, k[0], b3, iso))
		return 2;
	return end_sgn(E, x, v, 0, iso) == sg && end_sgn(E, x, v, 1, iso) == sg;
}

/* emit: hit (local root r, surface s, kind, entering) of leaf v: appended
 * to out[*nh], or (out NULL) handed to the hit function at once, whose
 * nonzero value is returned */
static inline int
emit(iso_ctx *x, const vx_leaf_visit *v, double r, int s, int kind,
    int entering, vx_iso_hit *out, int *nh, uint64_t *c0)
{
	vx_iso_stats *st = x->st;
	vx_iso_hit h;
	int rc;

	if (out != NULL) {
		fill(&out[(*nh)++], x, v, r, s, kind, entering);
		return 0;
	}
	fill(&h, x, v, r, s, kind, entering);
	if (st) {
		st->hits++;
		if (st->timing)
			st->cyc_isect += vx_cycles() - *c0;
	}
	if ((rc = x->fn(x->ctx, &h)) != 0)
		return rc;
	if (st && st->timing)
		*c0 = vx_cycles();
	return 0;
}

/* iso_roots: the roots of isovalue s in leaf v, in order of t (ol, len:
 * the local parameterization).  out == NULL (one isovalue): each root is
 * handed to the hit function as soon as it is found, so a hit that ends
 * the ray costs no further root; else they are appended to out[*nh], for
 * the caller to merge.  Returns the hit function's nonzero value, or 0.
 * *c0: the intersection clock's start (timing on). */
static inline int
iso_roots(ends *E, iso_ctx *x, const vx_leaf_visit *v, const double ol[3],
    double len, int s, vx_iso_hit *out, int *nh, uint64_t *c0)
{
	vx_iso_stats *st = x->st;
	double iso = x->iso[s], sa = 0, fa, f1, r, k[4];
	int n, kind, rc, nr, touch0;

	/* a touch pending at this cell's entry (the face the last cell
	 * ended on); only this cell can claim it */
	touch0 = x->pend[s] == v->t0;
	x->pend[s] = NAN;
	if (!(v->lo <= iso && iso <= v->hi))
		return 0;
	vx_cell_poly(v->c, ol, x->d, iso, k);
	if ((nr = no_root(E, x, v, ol, k, len, iso)) != 0) {
		if (st) {
			st->roots++;   /* a root query, missed */
			st->bounded++;
			st->certified += nr == 2;
		}
		return 0;
	}
	fa = end_field(E, x, v, 0) - iso;
	f1 = end_field(E, x, v, 1) - iso;
	/* the face touch: f came down to exactly iso at the entry face
	 * (the last cell's end) and does not cross it here (the field is
	 * not iso all along: a plateau at iso is inside, no touch) */
	touch0 = touch0 && fa == 0 && (k[0] != 0 || k[1] != 0 || k[2] != 0 ||
	    k[3] != 0);
	for (n = 0; n < MAXROOTS; n++) {
		if (st)
			st->roots++;
		kind = vx_cell_first_root_x(k, sa, len, fa, f1, x->tr->solver,
		    &r, NULL, &x->exact);
		if (touch0) {
			touch0 = 0;
			/* leaving downward at the face is the crossing this
			 * cell claims anyway; upward, f only touched iso */
			if (!(kind == VX_CELL_CROSS && r == 0) &&
			    (rc = emit(x, v, 0, s, VX_CELL_TOUCH, 0, out, nh,
			    c0)) != 0)
				return rc;
		}
		if (kind == VX_CELL_MISS || (n > 0 && !(r > sa)))
			break;
		if ((rc = emit(x, v, r, s, kind, fa < 0, out, nh, c0)) != 0)
			return rc;
		sa = r;
		if (kind == VX_CELL_CROSS)
			fa = fa >= 0 ? -1.0 : 1.0;
	}
	/* this cell ends exactly at iso, reached from above with no hit
	 * left on the way: the next cell decides whether that is a touch */
	if (f1 == 0 && n < MAXROOTS && kind == VX_CELL_MISS &&
	    vx_cell_end_sign(k, sa, len, fa) > 0)
		x->pend[s] = v->t1;
	return 0;
}

static int
visit(void *vctx, const vx_leaf_visit *v)
{
	iso_ctx *x = vctx;
	vx_iso_stats *st = x->st;
	vx_iso_hit hits[VX_ISO_MAX * (MAXROOTS + 1)];   /* + a face touch */
	double ol[3], len;
	ends E = { { 0, 0 }, { 0, 0 } };
	uint64_t c0 = 0;
	int nh = 0, s, a, i, j, rc;

	if (!finite8(v->c)) {
		if (st)
			st->nonfinite++;
		return 0;
	}
	if (st) {
		st->cells++;
		if (st->timing)
			c0 = vx_cycles();
	}
	/* Solve in a local parameter s = t - t0 from a point near the cell, so
	 * the cubic is well conditioned however far the ray's origin is. */
	for (a = 0; a < 3; a++)
		ol[a] = (x->o[a] + v->t0 * x->d[a]) - (double)v->i[a];
	len = v->t1 - v->t0;
	if (x->niso == 1) {
		/* the same hits in the same order as the merge below */
		if ((rc = iso_roots(&E, x, v, ol, len, 0, NULL, NULL, &c0)) != 0)
			return rc;
		if (st && st->timing)
			st->cyc_isect += vx_cycles() - c0;
		return 0;
	}
	for (s = 0; s < x->niso; s++)
		(void)iso_roots(&E, x, v, ol, len, s, hits, &nh, &c0);
	if (st && st->timing)
		st->cyc_isect += vx_cycles() - c0;
	/* insertion sort by t, stable: isovalue order breaks ties */
	for (i = 1; i < nh; i++) {
		vx_iso_hit h = hits[i];

		for (j = i; j > 0 && hits[j - 1].t > h.t; j--)
			hits[j] = hits[j - 1];
		hits[j] = h;
	}
	for (i = 0; i < nh; i++) {
		if (st)
			st->hits++;
		if ((rc = x->fn(x->ctx, &hits[i])) != 0)
			return rc;
	}
	return 0;
}

/* iso_start: x for a query (isovalues beyond VX_ISO_MAX left out), the
 * ray counted; 0 when there is nothing to trace */
static int
iso_start(iso_ctx *x, const vx_iso_tracer *tr, const double o[3],
    const double d[3], const double *iso, int niso, vx_iso_hit_fn fn,
    void *ctx, vx_iso_stats *st)
{
	int s;

	x->tr = tr;
	x->o = o;
	x->d = d;
	x->iso = iso;
	x->niso = niso > VX_ISO_MAX ? VX_ISO_MAX : niso;
	for (s = 0; s < x->niso; s++) {
		x->fiso[s] = (float)iso[s];
		x->pend[s] = NAN;
	}
	x->exact = 0;
	x->fn = fn;
	x->ctx = ctx;
	x->st = st;
	x->xs0 = 2 * (fabs(o[0]) + fabs(o[1]) + fabs(o[2])) + 16;
	x->dmag = fabs(d[0]) + fabs(d[1]) + fabs(d[2]);
	if (st)
		st->rays++;
	return x->niso > 0;
}

int
vx_iso_trace(const vx_iso_tracer *tr, const double o[3], const double d[3],
    double tmin, double tmax, const double *iso, int niso, vx_iso_hit_fn fn,
    void *ctx, vx_iso_stats *st)
{
	iso_ctx x;
	int rc;

	if (!iso_start(&x, tr, o, d, iso, niso, fn, ctx, st))
		return 0;
	if (tr->flat || tr->m == NULL)
		rc = vx_macro_traverse_flat(tr->m, tr->g, o, d, tmin, tmax,
		    x.fiso, x.niso, visit, &x, st ? &st->trav : NULL);
	else if (tr->mask != NULL)
		rc = vx_macro_traverse_masked(tr->m, tr->g, tr->mask, o, d,
		    tmin, tmax, x.fiso, x.niso, visit, &x, st ? &st->trav :
		    NULL);
	else
		rc = vx_macro_traverse(tr->m, tr->g, o, d, tmin, tmax, x.fiso,
		    x.niso, visit, &x, st ? &st->trav : NULL);
	if (st)
		st->exact += x.exact;
	return rc;
}

int
vx_iso_trace_boxes(const vx_iso_tracer *tr, const double o[3],
    const double d[3], const vx_cellbox *box, const uint32_t *ix,
    size_t nbox, const vx_boxpick *pk, const double *iso, int niso,
    vx_iso_hit_fn fn, void *ctx, vx_iso_stats *st)
{
	iso_ctx x;
	int rc;

	if (tr->flat || tr->m == NULL || tr->m->nlev < 1)
		return vx_iso_trace(tr, o, d, 0, INFINITY, iso, niso, fn, ctx,
		    st);
	if (!iso_start(&x, tr, o, d, iso, niso, fn, ctx, st))
		return 0;
	rc = vx_macro_traverse_boxes(tr->m, tr->g, tr->mask, box, ix, nbox,
	    pk, o, d, x.fiso, x.niso, visit, &x, st ? &st->trav : NULL);
	if (st)
		st->exact += x.exact;
	return rc;
}

static int
keep_first(void *ctx, const vx_iso_hit *h)
{
	*(vx_iso_hit *)ctx = *h;
	return 1;
}

int
vx_iso_first(const vx_iso_tracer *tr, const double o[3], const double d[3],
    double tmin, double tmax, const double *iso, int niso, vx_iso_hit *hit,
    vx_iso_stats *st)
{
	return vx_iso_trace(tr, o, d, tmin, tmax, iso, niso, keep_first, hit,
	    st) != 0;
}

int
vx_iso_normal(const vx_grid *g, const vx_iso_hit *h, const double dw[3],
    double n[3])
{
	double p[3], gr[3], w[3], thresh = vx_cell_normal_thresh(h->c), m, mw;
	double len;
	int a;

	for (a = 0; a < 3; a++)
		p[a] = h->p[a] - (double)h->cell[a];
	vx_cell_gradient(h->c, p, gr);
	m = fabs(gr[0]);
	m = fabs(gr[1]) > m ? fabs(gr[1]) : m;
	m = fabs(gr[2]) > m ? fabs(gr[2]) : m;
	for (a = 0; a < 3; a++)
		w[a] = gr[a] / g->spacing[a];
	mw = fabs(w[0]);
	mw = fabs(w[1]) > mw ? fabs(w[1]) : mw;
	mw = fabs(w[2]) > mw ? fabs(w[2]) : mw;
	if (!(m > thresh) || !(mw >= 0x1p-500 && mw <= 0x1p500)) {
		/* vanishing or extreme: the careful path */
		double di[3], ni[3];
		int path;

		vx_world_to_index_dir(g, dw, di);
		path = vx_cell_normal(h->c, p, di, ni);
		if (path == VX_NORMAL_RAY) {
			/* no gradient: against the world ray itself (scaled
			 * by its largest component first: no overflow) */
			double s = fabs(dw[0]);

			s = fabs(dw[1]) > s ? fabs(dw[1]) : s;
			s = fabs(dw[2]) > s ? fabs(dw[2]) : s;
			for (a = 0; a < 3; a++)
				n[a] = -dw[a] / s;
		} else
			vx_index_to_world_normal(g, ni, n);
		len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
		if (len > 0 && isfinite(len))
			for (a = 0; a < 3; a++)
				n[a] /= len;
		return path;
	}
	len = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
	if (w[0] * dw[0] + w[1] * dw[1] + w[2] * dw[2] > 0)
		len = -len;
	for (a = 0; a < 3; a++)
		n[a] = w[a] / len;
	return VX_NORMAL_GRADIENT;
}
