/* mipcolumn.c: MIP rays along an axis, the column walk (vx_mip.h).
 *
 * A ray along axis A only (the other components of d zero: the
 * axis-aligned orthographic views) stays in one column of data cells, and
 * the trilinear field on it is linear between the sample planes it
 * crosses: on each plane it is the bilinear "face value" of the column's 4
 * samples there, with weights fixed for the whole ray.  Because the result
 * does not depend on the order in which cells are looked at (beats()),
 * such a ray needs no queue:
 *   1. a lower bound M of the result: the face values of the planes
 *      crossed inside the segment (and the last-t bound), the column's
 *      level-1 macrocells in order, leaving out those whose maximum is
 *      below M;
 *   2. the exact maximum (solve_cell) of each cell whose face values can
 *      come within E of M, and only of those.
 * E bounds, generously, how far a cell's computed maximum (the cubic at
 * the segment's ends, which lie within 2^-30 of a cell of the planes when
 * |o[A]| <= 2^20 and 2^-20 <= |d[A]| <= 2^20) can be from the computed
 * face values: 2^-20 of the type's largest magnitude (plus 2^-20).  A cell
 * left out has a maximum below M - E <= the result, so it could not have
 * won.  The cells, their segments and their solves are those of walk(), so
 * the result is the queue's, bit for bit (test_mip). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mip_priv.h"

/* The column walk's cache: for CC_WAYS columns of data cells (a column:
 * the cells along axis A at one (U, V) cell position), the largest of the
 * 4 samples on each sample plane of the column, and per level-1 macrocell
 * along the column ("chunk") the largest of those, filled a chunk at a
 * time when a ray first needs it.  These are exact maxima of samples, so
 * they bound the column's face values as tightly as anything cheap can,
 * far tighter than the chunk's macrocell (16 x 8 cells across); the rays
 * of a tile (16x16 pixels, a row at a time) come back to the same columns.
 * Direct-mapped on the column position. */
#define CC_WAYS 32

typedef struct ccent {
	const void *data;           /* key: the volume's samples, */
	const vx_macro *m;          /* the hierarchy, */
	int A;                      /* the axis and */
	int64_t cu, cv;             /* the column */
	int32_t *pmax;              /* per plane along A */
	int32_t *cmax;              /* per chunk */
	uint8_t *known;             /* per chunk: pmax, cmax filled */
} ccent;

typedef struct colcache {
	int64_t P, C;               /* planes, chunks at most (any axis) */
	uint32_t looks, hits;       /* recent look-ups, of which hits */
	ccent e[CC_WAYS];
} colcache;

/* vx_mip_colcache_new: see mip_priv.h */
void *
vx_mip_colcache_new(const vx_macro *m)
{
	int64_t P = 0, C = 0;
	colcache *cc;
	char *b;

	if (m == NULL || m->nlev < 1)
		return NULL;
	for (int a = 0; a < 3; a++) {
		if (m->dims[0][a] + 1 > P)
			P = m->dims[0][a] + 1;
		if (m->dims[1][a] > C)
			C = m->dims[1][a];
	}
	if (P > 1 << 16 || C > 1 << 16)
		return NULL;
	C = (C + 7) / 8 * 8;        /* keeps the int32 arrays aligned */
	cc = calloc(1, sizeof *cc + CC_WAYS * (size_t)(4 * P + 5 * C));
	if (cc == NULL)
		return NULL;
	cc->P = P;
	cc->C = C;
	b = (char *)(cc + 1);
	for (int i = 0; i < CC_WAYS; i++) {
		cc->e[i].pmax = (int32_t *)(void *)b;
		b += 4 * P;
		cc->e[i].cmax = (int32_t *)(void *)b;
		b += 4 * C;
		cc->e[i].known = (uint8_t *)b;
		b += C;
	}
	return cc;
}

/* axis_span: the cells walk() visits for a ray along axis A over clo..chi
 * on [ta, tb] (walk_start's first cell c): kstart, kstart + s, ..., kend
 * (s = step[A]).  exit_t() is monotone along the walk (one division of
 * increasing plane offsets), so walk()'s bookkeeping comes down to:
 *   - walk() stops after the first cell whose exit is not before tb, or at
 *     the end of clo..chi: kend;
 *   - a cell whose exit is before ta (only at the start, by rounding) is
 *     not visited (walk()'s t1 >= t): kstart;
 *   - a visited cell's segment is [t0, t1] (axis_seg).
 * Returns 0 when no cell is visited. */
MIP_INLINE int
axis_span(const double o[3], const double d[3], double ta, double tb,
    const int64_t n[3], const int64_t clo[3], const int64_t chi[3], int A,
    int64_t c[3], int step[3], int64_t *kstart, int64_t *kend)
{
	static const int64_t one[3] = { 1, 1, 1 };
	double tn[3], tq[3], lo = (double)clo[A] - 2, hi = (double)chi[A] + 2;
	double pe = o[A] + tb * d[A];
	int64_t kb, ke, k;

	walk_start(o, d, ta, one, n, clo, chi, c, step, tn, tq);
	kb = step[A] > 0 ? chi[A] : clo[A];
	/* a guess (within a cell), then exact steps */
	pe = pe < lo ? lo : pe > hi ? hi : pe;
	if (step[A] > 0) {
		ke = (int64_t)ceil(pe) - 1;
		ke = ke < c[A] ? c[A] : ke > kb ? kb : ke;
		while (ke < kb && exit_t(o, d, step, one, n, A, ke) < tb)
			ke++;
		while (ke > c[A] && !(exit_t(o, d, step, one, n, A, ke - 1) < tb))
			ke--;
	} else {
		ke = (int64_t)floor(pe);
		ke = ke > c[A] ? c[A] : ke < kb ? kb : ke;
		while (ke > kb && exit_t(o, d, step, one, n, A, ke) < tb)
			ke--;
		while (ke < c[A] && !(exit_t(o, d, step, one, n, A, ke + 1) < tb))
			ke++;
	}
	for (k = c[A]; exit_t(o, d, step, one, n, A, k) < ta; k += step[A])
		if (k == ke)
			return 0;
	*kstart = k;
	*kend = ke;
	return 1;
}

/* axis_seg: walk()'s segment [*t0, *t1] of cell k of axis_span's walk:
 * t0 is ta for the first cell, else the previous cell's exit when that is
 * later than ta (walk()'s running t); t1 is the cell's exit, and
 * min(exit, tb) for the last cell. */
MIP_INLINE void
axis_seg(const double o[3], const double d[3], const int step[3],
    const int64_t n[3], int A, int64_t k, int64_t kstart, int64_t kend,
    double ta, double tb, double *t0, double *t1)
{
	static const int64_t one[3] = { 1, 1, 1 };

	*t0 = ta;
	if (k != kstart) {
		double tp = exit_t(o, d, step, one, n, A, k - step[A]);

		if (tp > ta)
			*t0 = tp;
	}
	*t1 = exit_t(o, d, step, one, n, A, k);
	if (k == kend && !(*t1 < tb))
		*t1 = tb;
}

/* sample: sample i of an integer-typed volume's data. */
MIP_INLINE double
sample(const void *data, vx_type ty, int64_t i)
{
	switch (ty) {
	case VX_U8: return ((const uint8_t *)data)[i];
	case VX_U16: return ((const uint16_t *)data)[i];
	default: return ((const int16_t *)data)[i];
	}
}

/* isample: sample i of an integer-typed volume's data. */
MIP_INLINE int32_t
isample(const void *data, vx_type ty, int64_t i)
{
	switch (ty) {
	case VX_U8: return ((const uint8_t *)data)[i];
	case VX_U16: return ((const uint16_t *)data)[i];
	default: return ((const int16_t *)data)[i];
	}
}

/* column_t: the maximum on a ray along axis A (tame_axis) through an
 * integer-typed volume, [ta, tb] clipped, lb a lower bound of the result
 * (or -Inf); see above.  Returns 1 (found) or 0 and sets *best, *tbest;
 * returns -1, having done nothing, when the column has more than
 * COLUMN_MAXCHUNK level-1 macrocells or they are longer than COLUMN_MAXW
 * cells (the caller takes the queue). */
#define COLUMN_MAXCHUNK 256
#define COLUMN_MAXW 64
MIP_INLINE int
column_t(const vx_grid *g, const vx_macro *m, colcache *cc,
    const double o[3], const double d[3], double ta, double tb, double lb,
    int A, double *bestp, double *tbestp, vx_mip_stats *st, const vx_type ty)
{
	static const int64_t zero[3] = { 0, 0, 0 };
	const int64_t *n = m->dims[0];
	const int64_t *off[3] = { g->lay.off[0], g->lay.off[1], g->lay.off[2] };
	const int U = A == 0 ? 1 : 0, V = A == 2 ? 1 : 2;
	const double E = ((ty == VX_U8 ? 255.0 : 65535.0) + 1) * 0x1p-20;
	const void *data = g->data;
	int64_t chi[3] = { n[0] - 1, n[1] - 1, n[2] - 1 }, c[3], ks, ke, k;
	int64_t wA, mi0 = 0, mstride = 0, buv, du, dv, kp, j0, nch, nc, i, q;
	int64_t ib, qq, np;
	ccent *ce;
	const float *mm = NULL;
	float chmax[COLUMN_MAXCHUNK];
	int16_t order[COLUMN_MAXCHUNK];
	int32_t pmax[COLUMN_MAXW + 1], cpm;
	double pval[COLUMN_MAXW + 1];
	double fu, fv, M = lb, best = -INFINITY, tbest = INFINITY;
	int step[3], s, found = 0, usec, hit;
	uint64_t solved = 0, skipped = 0, opened = 0;

	if (!axis_span(o, d, ta, tb, n, zero, chi, A, c, step, &ks, &ke))
		return 0;
	s = step[A];
	fu = o[U] - (double)c[U];
	fv = o[V] - (double)c[V];
	buv = off[U][c[U]] + off[V][c[V]];
	du = off[U][c[U] + 1] - off[U][c[U]];
	dv = off[V][c[V] + 1] - off[V][c[V]];
	/* this column's cache entry */
	ce = &cc->e[(c[U] + 8 * c[V] + 5 * A) & (CC_WAYS - 1)];
	hit = ce->data == data && ce->m == m && ce->A == A &&
	    ce->cu == c[U] && ce->cv == c[V];
	/* the cache pays where rays come back to their columns (pixels
	 * narrower than cells): used while at least half of the recent
	 * rays found their column there, else samples are read directly */
	cc->looks++;
	cc->hits += (uint32_t)hit;
	if (cc->looks >= 256) {
		cc->looks /= 2;
		cc->hits /= 2;
	}
	usec = 2 * cc->hits >= cc->looks;
	if (!hit) {
		ce->data = data;
		ce->m = m;
		ce->A = A;
		ce->cu = c[U];
		ce->cv = c[V];
		memset(ce->known, 0, (size_t)m->dims[1][A]);
	}
	/* the column's level-1 macrocells along the walk ("chunks" of wA
	 * cells), ordered by decreasing maximum, then by the walk's order */
	wA = n[A] + 1;
	if (m->nlev >= 1) {
		int64_t sd[3] = { 1, m->dims[1][0], m->dims[1][0] * m->dims[1][1] };

		wA = m->width[1][A];
		mm = m->mm[1];
		mi0 = sd[U] * (c[U] / m->width[1][U]) +
		    sd[V] * (c[V] / m->width[1][V]);
		mstride = sd[A];
	}
	j0 = ks / wA;
	nch = (ke / wA - j0) * s + 1;
	if (nch > COLUMN_MAXCHUNK ||
	    (wA > COLUMN_MAXW && (ke - ks) * s + 1 > COLUMN_MAXW))
		return -1;
	/* the chunks that can reach M - E (M: the last-t bound), and the
	 * first with the largest maximum: that one goes first, to raise M */
	for (i = 0, nc = 0, ib = -1; i < nch; i++) {
		float h = mm ? mm[2 * (mi0 + mstride * (j0 + s * i)) + 1] :
		    INFINITY;

		if (!((double)h < M - E)) {
			if (ib < 0 || h > chmax[ib])
				ib = nc;
			chmax[nc] = h;
			order[nc++] = (int16_t)i;
		}
	}
#define FACE(p)                                                           \
	(kp = buv + off[A][p],                                            \
	    (sample(data, ty, kp) + (sample(data, ty, kp + du) -          \
	    sample(data, ty, kp)) * fu) * (1 - fv) +                      \
	    (sample(data, ty, kp + dv) + (sample(data, ty, kp + du + dv) -\
	    sample(data, ty, kp + dv)) * fu) * fv)
	/* Each chunk in that order: unless it cannot reach M - E or cannot
	 * beat the best (beats()), the face values of its cells' planes raise
	 * M (planes crossed inside [ta, tb] only), and each cell whose larger
	 * face value can reach M - E and the best, and whose corner maximum
	 * beats the best, is solved.  A cell left out cannot reach the
	 * result or cannot change it. */
	for (q = -1; q < nc; q++) {
		int64_t j, k0, k1, ci = q < 0 ? ib : q;
		double hi, f0, f1, t0, t1;

		if (ci < 0 || (q >= 0 && q == ib))
			continue;
		hi = chmax[ci];
		if (hi < M - E)
			continue;
		j = j0 + s * order[ci];
		k0 = s > 0 ? (j * wA > ks ? j * wA : ks) :
		    (j * wA + wA - 1 < ks ? j * wA + wA - 1 : ks);
		k1 = s > 0 ? (j * wA + wA - 1 < ke ? j * wA + wA - 1 : ke) :
		    (j * wA > ke ? j * wA : ke);
		if (found && hi < best)
			continue;
		/* the column's own maximum over the chunk: the cache's */
		if (usec && !ce->known[j]) {
			int64_t p0 = j * wA, p1 = p0 + wA < n[A] ? p0 + wA : n[A];
			int32_t cm = INT32_MIN;

			for (int64_t pl = p0; pl <= p1; pl++) {
				const int64_t b0 = buv + off[A][pl];
				int32_t a0 = isample(data, ty, b0);
				int32_t a1 = isample(data, ty, b0 + du);
				int32_t a2 = isample(data, ty, b0 + dv);
				int32_t a3 = isample(data, ty, b0 + du + dv);
				int32_t mx = a0 > a1 ? a0 : a1, my = a2 > a3 ? a2 : a3;

				mx = mx > my ? mx : my;
				ce->pmax[pl] = mx;
				cm = mx > cm ? mx : cm;
			}
			ce->cmax[j] = cm;
			ce->known[j] = 1;
		}
		if (usec && (double)ce->cmax[j] < hi)
			hi = ce->cmax[j];
		if (hi < M - E)
			continue;
		if (found && !(hi > best)) {
			if (hi < best)
				continue;
			axis_seg(o, d, step, n, A, k0, ks, ke, ta, tb, &t0, &t1);
			if (!(t0 < tbest))
				continue;
		}
		opened++;
		/* the planes k0 .. k1 + s (in the walk's order): each one's
		 * largest sample, and its face value where that can raise M
		 * (planes crossed inside [ta, tb] only) */
		np = (k1 - k0) * s + 1;
		cpm = INT32_MIN;
		for (qq = 0; qq <= np; qq++) {
			const int64_t pl = k0 + s * qq + (s < 0);
			int32_t mx;

			if (usec) {
				mx = ce->pmax[pl];
			} else {
				const int64_t b0 = buv + off[A][pl];
				int32_t a0 = isample(data, ty, b0);
				int32_t a1 = isample(data, ty, b0 + du);
				int32_t a2 = isample(data, ty, b0 + dv);
				int32_t a3 = isample(data, ty, b0 + du + dv);
				int32_t my = a2 > a3 ? a2 : a3;

				mx = a0 > a1 ? a0 : a1;
				mx = mx > my ? mx : my;
			}

			pmax[qq] = mx;
			cpm = mx > cpm ? mx : cpm;
			pval[qq] = NAN;
			if ((double)mx > M) {
				double f = FACE(pl);

				pval[qq] = f;
				/* the first plane is crossed inside when the
				 * chunk does not start the walk; the last when
				 * it does not end it */
				if ((qq > 0 || k0 != ks) && (qq < np || k1 != ke))
					M = f > M ? f : M;
			}
		}
		if ((double)cpm + E < M - E) {
			/* no cell here can reach M - E */
			skipped += (uint64_t)np;
			continue;
		}
		/* the cells */
		for (k = k0, qq = 0;; k += s, qq++) {
			double ub, cmax;
			float v[8];

			if ((double)(pmax[qq] > pmax[qq + 1] ? pmax[qq] :
			    pmax[qq + 1]) + E < M - E) {
				skipped++;
				goto next_cell;
			}
			if (isnan(pval[qq]))
				pval[qq] = FACE(k0 + s * qq + (s < 0));
			if (isnan(pval[qq + 1]))
				pval[qq + 1] = FACE(k0 + s * (qq + 1) + (s < 0));
			f0 = pval[qq];
			f1 = pval[qq + 1];
			ub = (f0 > f1 ? f0 : f1) + E;
			if (ub < M - E || (found && ub < best)) {
				skipped++;
			} else {
				const int64_t p = buv + off[A][k];
				int64_t dd[3], dx, dy, dz;

				dd[U] = du;
				dd[V] = dv;
				dd[A] = off[A][k + 1] - off[A][k];
				dx = dd[0];
				dy = dd[1];
				dz = dd[2];
				v[0] = (float)sample(data, ty, p);
				v[1] = (float)sample(data, ty, p + dx);
				v[2] = (float)sample(data, ty, p + dy);
				v[3] = (float)sample(data, ty, p + dx + dy);
				v[4] = (float)sample(data, ty, p + dz);
				v[5] = (float)sample(data, ty, p + dx + dz);
				v[6] = (float)sample(data, ty, p + dy + dz);
				v[7] = (float)sample(data, ty, p + dx + dy + dz);
				cmax = v[0];
				for (int h = 1; h < 8; h++)
					cmax = v[h] > cmax ? v[h] : cmax;
				axis_seg(o, d, step, n, A, k, ks, ke, ta, tb, &t0,
				    &t1);
				if (!beats(found, cmax, t0, best, tbest)) {
					skipped++;
				} else {
					c[A] = k;
					solve_cell(v, c, o, d, t0, t1, &best, &tbest,
					    &found);
					solved++;
				}
			}
		next_cell:
			if (k == k1)
				break;
		}
	}
#undef FACE
	if (st) {
		st->cells += solved;
		st->cells_skipped += skipped;
		st->macro_opened += opened;
	}
	*bestp = best;
	*tbestp = tbest;
	return found;
}

static int
column_u8(const vx_grid *g, const vx_macro *m, colcache *cc,
    const double o[3], const double d[3], double ta, double tb, double lb,
    int A, double *best, double *tbest, vx_mip_stats *st)
{
	return column_t(g, m, cc, o, d, ta, tb, lb, A, best, tbest, st, VX_U8);
}

static int
column_u16(const vx_grid *g, const vx_macro *m, colcache *cc,
    const double o[3], const double d[3], double ta, double tb, double lb,
    int A, double *best, double *tbest, vx_mip_stats *st)
{
	return column_t(g, m, cc, o, d, ta, tb, lb, A, best, tbest, st, VX_U16);
}

static int
column_i16(const vx_grid *g, const vx_macro *m, colcache *cc,
    const double o[3], const double d[3], double ta, double tb, double lb,
    int A, double *best, double *tbest, vx_mip_stats *st)
{
	return column_t(g, m, cc, o, d, ta, tb, lb, A, best, tbest, st, VX_I16);
}

int
vx_mip_column(const vx_grid *g, const vx_macro *m, void *cc,
    const double o[3], const double d[3], double ta, double tb, double lb,
    int A, double *best, double *tbest, vx_mip_stats *st)
{
	switch (g->type) {
	case VX_U8:
		return column_u8(g, m, cc, o, d, ta, tb, lb, A, best, tbest, st);
	case VX_U16:
		return column_u16(g, m, cc, o, d, ta, tb, lb, A, best, tbest, st);
	default:
		return column_i16(g, m, cc, o, d, ta, tb, lb, A, best, tbest, st);
	}
}
