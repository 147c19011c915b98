/* macro_ray.h: the walk's ray and its steps over the leaf grid, shared by
 * the hierarchical walk (macrowalk.c) and the boxes' walk (macrobox.c) so
 * that both cross the same planes at bit-identical times and visit leaves
 * by one loop (leaves).  The helpers are inline in each walk, as they were
 * in one file; leaves and ray_axes stay out of line, as they were there.
 * Not installed. */
#ifndef MACRO_RAY_H
#define MACRO_RAY_H

#include <float.h>
#include <math.h>
#include <stdint.h>

#include "macro_priv.h"
#include "vx_cellmask.h"
#include "vx_grid.h"
#include "vx_macro.h"
#include "vx_macrowalk.h"

/* SSE2 where the platform has it: a visit's corners (corners_i,
 * corners_f) */
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

typedef struct ray {
	double o[3], d[3], inv[3];
	int s[3];              /* direction sign per axis: 1, -1 or 0 */
	int div[3];            /* 1: crossing times by division */
	int up[3];             /* 1 where s >= 0: the far plane is the upper */
	int flip;              /* bit a set where s[a] < 0 (see leaves) */
	int64_t fixed[3];      /* leaf index along axes with s == 0 */
	int64_t n[3];          /* leaf grid dims */
	const int64_t (*w)[3];  /* w[l]: level-l cell edge in leaves */
	const double (*iw)[3];  /* 1 / w: only for guesses */
} ray;

/* the edges of a flat walk without a hierarchy: one leaf */
static const int64_t unit_w[1][3] = { { 1, 1, 1 } };
static const double unit_iw[1][3] = { { 1.0, 1.0, 1.0 } };

/* tcross: the time the ray crosses plane x_a = p.  One formula for every
 * level and walk, so equal planes give bit-identical times. */
static inline double
tcross(const ray *r, int a, int64_t p)
{
	double x = (double)p - r->o[a];

	return r->div[a] ? x / r->d[a] : x * r->inv[a];
}

/* the planes bounding level-l cell c along a, in leaves (the last cell of
 * a level may be partial: its upper plane is the grid's) */
static inline int64_t
plane_lo(const ray *r, int l, int a, int64_t c)
{
	return c * r->w[l][a];
}

static inline int64_t
plane_hi(const ray *r, int l, int a, int64_t c)
{
	int64_t p = (c + 1) * r->w[l][a];

	return p < r->n[a] ? p : r->n[a];
}

/* t_exit_of: crossing time of the face level-l cell c leaves through. */
static inline double
t_exit_of(const ray *r, int l, int a, int64_t c)
{
	if (r->s[a] == 0)
		return INFINITY;
	return tcross(r, a, r->up[a] ? plane_hi(r, l, a, c) :
	    plane_lo(r, l, a, c));
}

/* The walk's loops keep a cell's per-axis state in three variables (in
 * registers: a step picks its axis with selects, no store and reload
 * through an indexed array).  AXIS: the one of axis ax; SET_AXIS: it set
 * to v. */
#define AXIS(ax, v0, v1, v2) ((ax) == 0 ? (v0) : (ax) == 1 ? (v1) : (v2))
#define SET_AXIS(ax, v0, v1, v2, v)                                      \
	do {                                                             \
		(v0) = (ax) == 0 ? (v) : (v0);                           \
		(v1) = (ax) == 1 ? (v) : (v1);                           \
		(v2) = (ax) == 2 ? (v) : (v2);                           \
	} while (0)

/* min_axis: the axis whose next crossing comes first (the lowest on a
 * tie, the walk's order), its time in *t */
static inline int
min_axis(double n0, double n1, double n2, double *t)
{
	int ax = n1 < n0;

	*t = ax ? n1 : n0;
	if (n2 < *t) {
		ax = 2;
		*t = n2;
	}
	return ax;
}

/* find_cell: among level-l cells k0..k1-1 along axis a (s != 0), the one
 * the ray is in at time t: the last one in walking order whose entry face
 * is crossed at or before t (post != 0) or strictly before t (post == 0);
 * the first one if none is.  Crossing times are monotone in the plane, so
 * that test is monotone in the cell index: start from the cell holding the
 * point o + t d (right or one off, whatever the rounding) and walk to the
 * answer; the result is the same as a binary search's, in one or two
 * crossing times instead of log2(k1 - k0). */
static inline int64_t
find_cell(const ray *r, int l, int a, int64_t k0, int64_t k1, double t,
    int post)
{
	double td = t * r->d[a], x = r->o[a] + td, q = x * r->iw[l][a], tc;
	int64_t k;

	/* the guess, clamped into [k0, k1 - 1] (NaN goes to k0) */
	if (!(q > (double)k0))
		k = k0;
	else if (q >= (double)(k1 - 1))
		k = k1 - 1;
	else
		k = (int64_t)q;
	/* Most guesses are far inside their cell: if x lies inside the
	 * guess's slab by more than mg, the tests below keep k, whatever the
	 * rounding.  Proof: a plane p's crossing time T = (p - o) / d is
	 * computed with an error under 4 ulp(|p| + |o|) / |d|, x = o + t d
	 * under 3 ulp(|o| + |t d|), while |x - p| > mg = 2^-40 (|o| + |t d|
	 * + |hi|) puts T at least (mg - that) / |d| from t, 2^11 times more:
	 * the computed crossing is on the same side of t as the true one,
	 * and never equal to it (so post does not matter).  Rays whose
	 * crossing times are divided (d near under- or overflow) and
	 * non-finite x take the tests. */
	if (!r->div[a]) {
		double lo = (double)plane_lo(r, l, a, k);
		double hi = (double)plane_hi(r, l, a, k);
		double mg = 0x1p-40 * (fabs(r->o[a]) + fabs(td) + hi);

		if ((k == k0 || x - lo > mg) && (k == k1 - 1 || hi - x > mg))
			return k;
	}
#define ENTERED(p) (tc = tcross(r, a, (p)), post ? tc <= t : tc < t)
	if (r->s[a] > 0) {
		/* entered(k): k's entry face, its lower plane, crossed by t */
		while (k < k1 - 1 && ENTERED(plane_lo(r, l, a, k + 1)))
			k++;
		while (k > k0 && !ENTERED(plane_lo(r, l, a, k)))
			k--;
	} else {
		while (k > k0 && ENTERED(plane_hi(r, l, a, k - 1)))
			k--;
		while (k < k1 - 1 && !ENTERED(plane_hi(r, l, a, k)))
			k++;
	}
#undef ENTERED
	return k;
}

/* ---- the leaf loop over volume leaves ----
 * A leaf's 8 samples are loaded, from the layout offsets of its lower and
 * upper sample planes per axis, in vx_grid_cell's order, and written to
 * the visit as floats by two 16-byte stores: the visitor reads them with
 * wide loads (finite8, the hit's copy), and a wide load of narrow stores
 * waits for them to retire. */

/* min and max keeping the first of equal values, as a left-to-right scan
 * with a strict comparison does */
static inline float
min_first(float a, float b)
{
	return b < a ? b : a;
}

static inline float
max_first(float a, float b)
{
	return b > a ? b : a;
}

static inline int32_t
imin(int32_t a, int32_t b)
{
	return b < a ? b : a;
}

static inline int32_t
imax(int32_t a, int32_t b)
{
	return b > a ? b : a;
}

/* corners: c[0..8) = a0..a7, two 16-byte stores where SSE2 has them
 * (integer samples, exact in float, or floats) */
static inline void
corners_i(float c[8], int32_t a0, int32_t a1, int32_t a2, int32_t a3,
    int32_t a4, int32_t a5, int32_t a6, int32_t a7)
{
#if defined(__SSE2__)
	_mm_storeu_ps(c, _mm_cvtepi32_ps(_mm_setr_epi32(a0, a1, a2, a3)));
	_mm_storeu_ps(c + 4, _mm_cvtepi32_ps(_mm_setr_epi32(a4, a5, a6, a7)));
#else
	c[0] = (float)a0; c[1] = (float)a1; c[2] = (float)a2;
	c[3] = (float)a3; c[4] = (float)a4; c[5] = (float)a5;
	c[6] = (float)a6; c[7] = (float)a7;
#endif
}

static inline void
corners_f(float c[8], float a0, float a1, float a2, float a3, float a4,
    float a5, float a6, float a7)
{
#if defined(__SSE2__)
	_mm_storeu_ps(c, _mm_setr_ps(a0, a1, a2, a3));
	_mm_storeu_ps(c + 4, _mm_setr_ps(a4, a5, a6, a7));
#else
	c[0] = a0; c[1] = a1; c[2] = a2; c[3] = a3;
	c[4] = a4; c[5] = a5; c[6] = a6; c[7] = a7;
#endif
}

/* integer samples: the range from the loaded values themselves */
#define LEAF_INT(T)                                                      \
	do {                                                             \
		const T *d = (const T *)g->data;                         \
		int32_t a0 = d[x0 + yz00], a1 = d[x1 + yz00];            \
		int32_t a2 = d[x0 + yz10], a3 = d[x1 + yz10];            \
		int32_t a4 = d[x0 + yz01], a5 = d[x1 + yz01];            \
		int32_t a6 = d[x0 + yz11], a7 = d[x1 + yz11];            \
		corners_i(c, a0, a1, a2, a3, a4, a5, a6, a7);            \
		mn = imin(imin(imin(a0, a1), imin(a2, a3)),              \
		    imin(imin(a4, a5), imin(a6, a7)));                   \
		mx = imax(imax(imax(a0, a1), imax(a2, a3)),              \
		    imax(imax(a4, a5), imax(a6, a7)));                   \
	} while (0)

/* flo: v if finite, else +Inf (the min's identity); fhi: -Inf */
static inline float
flo(float v)
{
	return fabsf(v) <= FLT_MAX ? v : INFINITY;
}

static inline float
fhi(float v)
{
	return fabsf(v) <= FLT_MAX ? v : -INFINITY;
}

/* leaf_load: the 8 samples of the leaf whose lower and upper sample
 * planes are at layout offsets lo, hi, into c in vx_grid_cell's order,
 * and their range: integer types in *imn..*imx (all finite, exact in
 * float); f32 in *flop..*fhip over the finite ones (empty: +Inf, -Inf;
 * NaN and +-Inf left out) */
static inline void
leaf_load(const vx_grid *g, const int64_t lo[3], const int64_t hi[3],
    float c[8], int32_t *imn, int32_t *imx, float *flop, float *fhip)
{
	int64_t x0 = lo[0], x1 = hi[0];
	int64_t yz00 = lo[1] + lo[2], yz10 = hi[1] + lo[2];
	int64_t yz01 = lo[1] + hi[2], yz11 = hi[1] + hi[2];
	int32_t mn = 0, mx = 0;

	switch (g->type) {
	case VX_U8: LEAF_INT(uint8_t); break;
	case VX_U16: LEAF_INT(uint16_t); break;
	case VX_I16: LEAF_INT(int16_t); break;
	case VX_F32: {
		const float *d = (const float *)g->data;
		float a0 = d[x0 + yz00], a1 = d[x1 + yz00];
		float a2 = d[x0 + yz10], a3 = d[x1 + yz10];
		float a4 = d[x0 + yz01], a5 = d[x1 + yz01];
		float a6 = d[x0 + yz11], a7 = d[x1 + yz11];

		corners_f(c, a0, a1, a2, a3, a4, a5, a6, a7);
		*flop = min_first(min_first(min_first(flo(a0), flo(a1)),
		    min_first(flo(a2), flo(a3))), min_first(min_first(flo(a4),
		    flo(a5)), min_first(flo(a6), flo(a7))));
		*fhip = max_first(max_first(max_first(fhi(a0), fhi(a1)),
		    max_first(fhi(a2), fhi(a3))), max_first(max_first(fhi(a4),
		    fhi(a5)), max_first(fhi(a6), fhi(a7))));
		return;
	}
	default:
		corners_i(c, 0, 0, 0, 0, 0, 0, 0, 0);
		break;
	}
	*imn = mn;
	*imx = mx;
}

/* leaves: the level-0 part of the walk over volume leaves: from leaf c
 * (entered at *t through axis *e), visit and step leaf to leaf while the
 * next leaf stays in the sibling range (lim: the first index past it in
 * walking order) and the segment goes on.  Does exactly what the walk does
 * at level 0 for explicit leaves, leaf after leaf (the same tests, crossing
 * times and visits).  Returns the visitor's nonzero value, or 0 with *ax,
 * *texit the face and time through which the last leaf (c, entered at *t
 * through *e) is left: beyond tb, or into a leaf outside the range. */
static __attribute__((noinline)) int
leaves(const ray *r, const vx_grid *g, int64_t c[3], const int64_t lim[3],
    double tn[3], double *tp, int *ep, double tb, const float *vals,
    int nvals, const uint64_t *bits, int64_t li, const int64_t dl[3],
    vx_visit_fn fn, void *ctx, vx_trav_stats *s, int *axp, double *texitp)
{
	const int64_t *off[3] = { g->lay.off[0], g->lay.off[1], g->lay.off[2] };
	const int *up = r->up;
	int64_t fl = 0, ce = 0, culled = 0;
	/* the leaf and its exit times in registers: a step picks its axis
	 * with selects, not a store and reload through an indexed array */
	int64_t c0 = c[0], c1 = c[1], c2 = c[2];
	double n0 = tn[0], n1 = tn[1], n2 = tn[2];
	/* the crossing after the next one per axis, computed a step ahead:
	 * a step then only selects it, and the next step's choice of axis
	 * does not wait for a conversion, a subtraction and a product (the
	 * same tcross of the same plane: the same bits) */
	double m0 = r->s[0] ? tcross(r, 0, c0 + r->s[0] + up[0]) : INFINITY;
	double m1 = r->s[1] ? tcross(r, 1, c1 + r->s[1] + up[1]) : INFINITY;
	double m2 = r->s[2] ? tcross(r, 2, c2 + r->s[2] + up[2]) : INFINITY;
	int isf = g->type == VX_F32, ithr = 0;
	vx_leaf_visit v;
	double t = *tp, texit;
	int ax, e = *ep, rc = 0;

	/* integer samples and one value v: (float)min <= v <= (float)max is
	 * min <= floor(v) and max >= ceil(v) (v clamped far beyond the 16-bit
	 * range first; NaN brackets nothing and takes the float test) */
	if (!isf && nvals == 1 && vals[0] == vals[0]) {
		double w = vals[0] < -0x1p40 ? -0x1p40 : vals[0] > 0x1p40 ?
		    0x1p40 : vals[0];

		ithr = 1;
		fl = (int64_t)floor(w);
		ce = (int64_t)ceil(w);
	}
	for (;;) {
		int64_t nc, p;
		double tv;

		ax = min_axis(n0, n1, n2, &texit);
		/* with a mask, a clear bit is this very test's answer: the
		 * samples are loaded only for a leaf to visit */
		if (bits != NULL && !(bits[li >> 6] >> (li & 63) & 1))
			culled++;
		else {
			float lo = 0, hi = 0;
			int32_t imn = 0, imx = 0;
			int64_t pl[3], ph[3];
			int in;

			pl[0] = off[0][c0];
			ph[0] = off[0][c0 + 1];
			pl[1] = off[1][c1];
			ph[1] = off[1][c1 + 1];
			pl[2] = off[2][c2];
			ph[2] = off[2][c2 + 1];
			leaf_load(g, pl, ph, v.c, &imn, &imx, &lo, &hi);
			if (ithr)
				in = imn <= fl && imx >= ce;
			else {
				if (!isf) {
					lo = (float)imn;
					hi = (float)imx;
				}
				in = brackets(lo, hi, vals, nvals);
			}
			if (in) {
				v.i[0] = c0;
				v.i[1] = c1;
				v.i[2] = c2;
				v.leaf = c0 + (r->n[0] * (c1 + r->n[1] * c2));
				v.t0 = t;
				v.t1 = texit < tb ? texit : tb;
				v.entry_axis = e;
				v.entry_side = e >= 0 && r->s[e] < 0;
				v.exit_axis = texit <= tb && r->s[ax] ? ax : -1;
				v.exit_side = v.exit_axis >= 0 && r->s[ax] > 0;
				v.lo = isf ? lo : (float)imn;
				v.hi = isf ? hi : (float)imx;
				s->leaves++;
				if ((rc = fn(ctx, &v)) != 0)
					break;
			} else
				culled++;
		}
		if (!(texit < tb))
			break;
		nc = AXIS(ax, c0, c1, c2) + r->s[ax];
		if (nc == lim[ax])
			break;
		/* the far plane of the next leaf, and its crossing time as
		 * t_exit_of gives it at level 0 (inside the grid: no clamp) */
		p = nc + r->s[ax] + up[ax];
		tv = AXIS(ax, m0, m1, m2);
		SET_AXIS(ax, c0, c1, c2, nc);
		SET_AXIS(ax, n0, n1, n2, tv);
		SET_AXIS(ax, m0, m1, m2, tcross(r, ax, p));
		li += dl[ax];
		t = texit;
		e = ax;
	}
	s->culled += (uint64_t)culled;
	c[0] = c0;
	c[1] = c1;
	c[2] = c2;
	tn[0] = n0;
	tn[1] = n1;
	tn[2] = n2;
	*tp = t;
	*ep = e;
	*axp = ax;
	*texitp = texit;
	return rc;
}


/* ray_axes: the ray's per-axis set-up over n leaves (direction signs,
 * crossing-time factors, the leaf kept along an axis the ray does not
 * move on).  Returns 0 when the ray is not finite or runs parallel to an
 * axis outside the grid (it visits nothing). */
static __attribute__((noinline)) int
ray_axes(ray *r, const int64_t n[3], const double o[3], const double d[3])
{
	for (int a = 0; a < 3; a++) {
		double ad = fabs(d[a]);

		if (!isfinite(o[a]) || !isfinite(d[a]))
			return 0;
		r->o[a] = o[a];
		r->d[a] = d[a];
		r->s[a] = d[a] > 0 ? 1 : d[a] < 0 ? -1 : 0;
		r->up[a] = r->s[a] >= 0;
		r->div[a] = !(ad >= 0x1p-1000 && ad <= 0x1p1000);
		r->inv[a] = r->s[a] ? 1.0 / d[a] : 0.0;
		r->fixed[a] = 0;
		r->n[a] = n[a];
		if (r->s[a] == 0) {
			if (!(o[a] >= 0 && o[a] <= (double)n[a]))
				return 0;
			r->fixed[a] = (int64_t)floor(o[a]);
			if (r->fixed[a] > n[a] - 1)
				r->fixed[a] = n[a] - 1;
		}
	}
	return 1;
}

/* ray_clip: the set-up of ray r (ray_axes done, over n leaves) for a walk
 * from level top: the segment [*ta, *tb] clipped to the grid.  Returns 0
 * when nothing is to be walked (the ray misses, or the root range
 * brackets none of the values). */
static inline __attribute__((always_inline)) int
ray_clip(ray *r, const vx_macro *m, int top, const float *vals, int nvals,
    double *tap, double *tbp)
{
	const int64_t *n = r->n;
	double ta = *tap, tb = *tbp;
	int a;

	for (a = 0; a < 3; a++) {
		if (r->s[a] != 0) {
			double t0 = tcross(r, a, r->s[a] > 0 ? 0 : n[a]);
			double t1 = tcross(r, a, r->s[a] > 0 ? n[a] : 0);

			if (t0 > ta)
				ta = t0;
			if (t1 < tb)
				tb = t1;
		}
	}
	if (!(ta <= tb))
		return 0;
	if (top > 0 && nvals > 0 && !brackets(m->root[0], m->root[1], vals,
	    nvals))
		return 0;
	r->flip = (!r->up[0]) | (!r->up[1]) << 1 | (!r->up[2]) << 2;
	/* a hierarchy's level 0 is the leaf: width 1 */
	r->w = top > 0 ? (const int64_t (*)[3])m->width : unit_w;
	r->iw = top > 0 ? (const double (*)[3])m->iwidth : unit_iw;
	*tap = ta;
	*tbp = tb;
	return 1;
}

/* start_leaf: the leaf ray r is in just after ta (the segment's start)
 * and its entry axis *e (-1: ta is on no face of it) */
static inline void
start_leaf(const ray *r, double ta, int64_t leaf[3], int *e)
{
	*e = -1;
	for (int a = 0; a < 3; a++) {
		if (r->s[a] == 0) {
			leaf[a] = r->fixed[a];
			continue;
		}
		leaf[a] = find_cell(r, 0, a, 0, r->n[a], ta, 1);
		if (tcross(r, a, r->s[a] > 0 ? leaf[a] : leaf[a] + 1) == ta)
			*e = a;
	}
}

/* leaf_bits: the mask bits of level-1 cell c1 (NULL: none), the index li
 * of leaf c0 in them and the index steps dl per axis in walking order */
static inline const uint64_t *
leaf_bits(vx_cellmask *mk, const vx_macro *m, const vx_grid *g,
    const ray *r, const int64_t c1[3], const int64_t c0[3], int64_t *li,
    int64_t dl[3])
{
	const int64_t *w = m->width[1];
	int64_t b = c1[0] + m->dims[1][0] * (c1[1] + m->dims[1][1] * c1[2]);
	const uint64_t *bits = mask_get(mk, m, g, b);

	if (bits != NULL) {
		*li = (c0[0] - c1[0] * w[0]) + w[0] * ((c0[1] - c1[1] * w[1]) +
		    w[1] * (c0[2] - c1[2] * w[2]));
		dl[0] = r->s[0];
		dl[1] = r->s[1] * w[0];
		dl[2] = r->s[2] * w[0] * w[1];
	}
	return bits;
}

#endif
