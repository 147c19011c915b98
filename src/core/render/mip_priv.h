/* mip_priv.h: what the MIP modules share (mip.c: the queue and the cell
 * walks; mipcolumn.c: rays along an axis): a walk's first cell and its
 * crossing times, the rule that decides what can change a ray's result,
 * and the exact maximum of one cell, each the same operations in the same
 * order wherever it is used (the pictures do not depend on which walk ran:
 * vx_mip.h).  Not installed. */
#ifndef MIP_PRIV_H
#define MIP_PRIV_H

#include <math.h>
#include <stdint.h>

#include "vx_cell.h"
#include "vx_grid.h"
#include "vx_macro.h"
#include "vx_mip.h"

#if defined(__GNUC__)
#define MIP_INLINE static inline __attribute__((always_inline))
#else
#define MIP_INLINE static inline
#endif

/* exit_t: the time at which the ray leaves cell k (width w) along
 * axis a. */
MIP_INLINE double
exit_t(const double o[3], const double d[3], const int step[3],
    const int64_t w[3], const int64_t n[3], int a, int64_t k)
{
	if (step[a] > 0) {
		int64_t h = (k + 1) * w[a] < n[a] ? (k + 1) * w[a] : n[a];

		return ((double)h - o[a]) / d[a];
	}
	if (step[a] < 0)
		return ((double)(k * w[a]) - o[a]) / d[a];
	return INFINITY;
}

/* walk_start: a walk's first cell and crossing times. */
MIP_INLINE void
walk_start(const double o[3], const double d[3], double ta,
    const int64_t w[3], const int64_t n[3], const int64_t clo[3],
    const int64_t chi[3], int64_t c[3], int step[3], double tn[3],
    double tq[3])
{
	int a;

	for (a = 0; a < 3; a++) {
		double p = o[a] + ta * d[a], q = floor(p / (double)w[a]);
		/* q clamped before the conversion (NaN too: a far camera's p
		 * can be NaN or beyond int64), to a range the clamps below
		 * map as they would q itself */
		int64_t k = !(q >= (double)(clo[a] - 1)) ? clo[a] - 1 :
		    q > (double)(chi[a] + 1) ? chi[a] + 1 : (int64_t)q;

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
		tn[a] = exit_t(o, d, step, w, n, a, c[a]);
		tq[a] = exit_t(o, d, step, w, n, a, c[a] + step[a]);
	}
}

/* beats: whether a cell or macrocell whose values are at most hi and
 * whose segment starts at t0 can still change the result (best, tbest)
 * under the rule "the largest value; among equal values the smallest t":
 * when nothing is found yet, when hi is larger, or when hi is equal and
 * t0 earlier. */
MIP_INLINE int
beats(int found, double hi, double t0, double best, double tbest)
{
	return !found || hi > best || (hi == best && t0 < tbest);
}

/* clamp_fold: fold a cell's maximum fm at tt, clamped into its corners'
 * range [lo, hi] (the trilinear field never leaves it; the computed cubic
 * can, by rounding), into (best, tbest, found) under beats()'s rule. */
MIP_INLINE void
clamp_fold(double fm, double tt, double lo, double hi, double *best,
    double *tbest, int *found)
{
	fm = fm > hi ? hi : fm < lo ? lo : fm;
	if (!*found || fm > *best || (fm == *best && tt < *tbest)) {
		*best = fm;
		*tbest = tt;
		*found = 1;
	}
}

/* max0: vx_cell_max(k, 0, t1, tm, fm) inlined, the same operations in
 * the same order (vx_cell_argmax) where vx_cell_max does not rescale k (its
 * normalize() is the identity unless some |k| >= 2^400 or all are
 * <= 2^-400: those go to vx_cell_max itself); test_mip checks the bits. */
MIP_INLINE int
max0(const double k[4], double t1, double *tm, double *fm)
{
	int i, big = 0, small = 1;
	double bt;

	if (!(isfinite(k[0]) && isfinite(k[1]) && isfinite(k[2]) &&
	    isfinite(k[3]) && isfinite(t1)) || 0 > t1) {
		*tm = 0;
		*fm = -INFINITY;
		return 0;
	}
	for (i = 0; i < 4; i++) {
		double a = fabs(k[i]);

		big |= a >= 0x1p400;
		small &= a <= 0x1p-400;
	}
	if (big || small)
		return vx_cell_max(k, 0, t1, tm, fm);
	bt = vx_cell_argmax(k, 0, t1);
	*tm = bt;
	*fm = vx_cell_poly_low(k, bt);
	if (!isfinite(*fm)) {
		*tm = 0;
		*fm = -INFINITY;
		return 0;
	}
	return 1;
}

/* solve_cell: solve() for the specialized walks: the exact maximum of the
 * cell at c with (finite) corners v on [t, t1], clamped and folded into
 * (best, tbest, found). */
MIP_INLINE void
solve_cell(const float v[8], const int64_t c[3], const double o[3],
    const double d[3], double t, double t1, double *best, double *tbest,
    int *found)
{
	double ol[3], k[4], tm, fm;
	float lo = v[0], hi = v[0];

	for (int i = 1; i < 8; i++) {
		lo = v[i] < lo ? v[i] : lo;
		hi = v[i] > hi ? v[i] : hi;
	}
	for (int i = 0; i < 3; i++)
		ol[i] = (o[i] + t * d[i]) - (double)c[i];
	vx_cell_poly_inline(v, ol, d, 0, k);
	if (max0(k, t1 - t, &tm, &fm))
		clamp_fold(fm, t + tm, lo, hi, best, tbest, found);
}

/* vx_mip_colcache_new (mipcolumn.c): the column walk's cache for hierarchy
 * m (level 1 needed), or NULL (then rays along an axis take the queue);
 * free() frees it. */
void *vx_mip_colcache_new(const vx_macro *m);

/* vx_mip_column (mipcolumn.c): the maximum on a ray along axis A
 * (tame_axis in mip.c) through an integer-typed volume g, [ta, tb]
 * clipped, lb a lower bound of the result (or -Inf), with cache cc.
 * Returns 1 (found) or 0 and sets *best, *tbest; -1, having done nothing,
 * when the column is too long for it (the caller takes the queue). */
int vx_mip_column(const vx_grid *g, const vx_macro *m, void *cc,
    const double o[3], const double d[3], double ta, double tb, double lb,
    int A, double *best, double *tbest, vx_mip_stats *st);

#endif
