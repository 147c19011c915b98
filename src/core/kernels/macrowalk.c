/* macrowalk.c: the hierarchical 3D-DDA over the min/max hierarchy, with
 * or without a cell mask, and the flat walk (vx_macrowalk.h). */
#include "vx_macrowalk.h"

#include <math.h>
#include <string.h>

#include "macro_priv.h"
#include "macro_ray.h"

/* ray_finish: ray_clip, and the start leaf and its entry axis *e
 * (start_leaf) */
static inline __attribute__((always_inline)) int
ray_finish(ray *r, const vx_macro *m, int top, const float *vals,
    int nvals, double *tap, double *tbp, int64_t leaf[3], int *e)
{
	if (!ray_clip(r, m, top, vals, nvals, tap, tbp))
		return 0;
	start_leaf(r, *tap, leaf, e);
	return 1;
}

/* children: the children [*k0, *k1) along axis a of level-l cell cl
 * (l >= 1; n: leaf dims, for the last, partial cells of level 0) */
static inline void
children(const vx_macro *m, int l, int a, int64_t cl, const int64_t n[3],
    int64_t *k0, int64_t *k1)
{
	int64_t dk = l > 1 ? m->dims[l - 1][a] : n[a];
	int64_t lo = cl * m->size[l][a], hi = lo + m->size[l][a];

	if (hi > dk)
		hi = dk;
	*k0 = lo;
	*k1 = hi;
}

/* top_level: the walk's state at its start level top: the range of its
 * cell c[top] (lim, in walking order: the whole level) and the cell's exit
 * time per axis (tn) */
static void
top_level(const ray *r, const vx_macro *m, int top, const int64_t n[3],
    int64_t c[][3], int64_t lim[][3], double tn[][3])
{
	for (int a = 0; a < 3; a++) {
		lim[top][a] = r->up[a] ? (top ? m->dims[top][a] : n[a]) : -1;
		tn[top][a] = t_exit_of(r, top, a, c[top][a]);
	}
}

/* walk: the traversal behind the public entry points.  top is the level
 * whose DDA starts the walk (0: flat).  n: leaf dims.  g: the volume whose
 * cells are the leaves, or NULL; mm0: stored leaf ranges or NULL. */
static int
walk(const vx_macro *m, int top, const int64_t n[3], const vx_grid *g,
    const float *mm0, vx_cellmask *mk, const double o[3],
    const double d[3], double tmin, double tmax, const float *vals,
    int nvals, vx_visit_fn fn, void *ctx, vx_trav_stats *st)
{
	int64_t c[VX_MACRO_MAXLEV + 1][3];     /* current cell per level */
	int64_t lim[VX_MACRO_MAXLEV + 1][3];   /* first index past its
	                                          siblings, walking order */
	double tn[VX_MACRO_MAXLEV + 1][3];     /* next face crossing per axis */
	int64_t leaf[3];
	vx_trav_stats s;
	vx_leaf_visit v;
	double ta = tmin, tb = tmax, t, texit;
	int a, l, e, ax, start, cont = 0, rc = 0;
	ray r;

	memset(&s, 0, sizeof s);
	s.rays = 1;
	if (n[0] <= 0 || n[1] <= 0 || n[2] <= 0 || !(ta <= tb) ||
	    !ray_axes(&r, n, o, d))
		goto done;
	if (!ray_finish(&r, m, top, vals, nvals, &ta, &tb, leaf, &e))
		goto done;
	for (l = 0; l <= top; l++)
		for (a = 0; a < 3; a++)
			c[l][a] = leaf[a] / r.w[l][a];
	l = top;
	top_level(&r, m, top, n, c, lim, tn);
	t = ta;
	start = 1;

	for (;;) {
		if (l == 0 && g != NULL) {
			const uint64_t *bits = NULL;
			int64_t li = 0, dl[3] = { 0, 0, 0 };

			if (mk != NULL && top >= 1)
				bits = leaf_bits(mk, m, g, &r, c[1], c[0], &li, dl);
			if ((rc = leaves(&r, g, c[0], lim[0], tn[0], &t, &e, tb,
			    vals, nvals, bits, li, dl, fn, ctx, &s, &ax,
			    &texit)) != 0)
				goto done;
		} else if (l == 0) {
			float lo, hi;

			if (mm0 != NULL) {
				size_t k = 2 * (size_t)(c[0][0] + n[0] *
				    (c[0][1] + n[1] * c[0][2]));

				lo = mm0[k];
				hi = mm0[k + 1];
			} else {
				lo = -INFINITY;
				hi = INFINITY;
			}
			ax = min_axis(tn[0][0], tn[0][1], tn[0][2], &texit);
			if (brackets(lo, hi, vals, nvals)) {
				memcpy(v.i, c[0], sizeof v.i);
				v.leaf = c[0][0] + n[0] * (c[0][1] + n[1] *
				    c[0][2]);
				v.t0 = t;
				v.t1 = texit < tb ? texit : tb;
				v.entry_axis = e;
				v.entry_side = e >= 0 && r.s[e] < 0;
				v.exit_axis = texit <= tb && r.s[ax] ? ax : -1;
				v.exit_side = v.exit_axis >= 0 && r.s[ax] > 0;
				v.lo = lo;
				v.hi = hi;
				s.leaves++;
				if ((rc = fn(ctx, &v)) != 0)
					goto done;
			} else
				s.culled++;
		} else {
			/* a level-l macrocell (l >= 1).  Those that bracket
			 * nothing are stepped through here with the cell, its
			 * index into mm[l] and its exit times in registers:
			 * the same tests, steps and crossing times as the
			 * stepping below, which takes over when the ray
			 * leaves the parent or the segment ends */
			const float *mm = m->mm[l];
			const int64_t d0 = m->dims[l][0];
			const int64_t d01 = d0 * m->dims[l][1];
			int64_t x0 = c[l][0], x1 = c[l][1], x2 = c[l][2];
			int64_t q = x0 + d0 * x1 + d01 * x2, nc;
			int in;

			s.macro[l]++;
			in = brackets(mm[2 * q], mm[2 * q + 1], vals, nvals);
			if (!in) {
				const int64_t dq[3] = { r.s[0], r.s[1] * d0,
				    r.s[2] * d01 };
				double n0 = tn[l][0], n1 = tn[l][1], n2 = tn[l][2];
				double tv;

				for (;;) {
					ax = min_axis(n0, n1, n2, &texit);
					if (!(texit < tb))
						break;
					nc = AXIS(ax, x0, x1, x2) + r.s[ax];
					if (nc == lim[l][ax])
						break;
					tv = t_exit_of(&r, l, ax, nc);
					SET_AXIS(ax, x0, x1, x2, nc);
					SET_AXIS(ax, n0, n1, n2, tv);
					q += dq[ax];
					t = texit;
					e = ax;
					start = 0;
					cont = l;
					s.macro[l]++;
					if ((in = brackets(mm[2 * q], mm[2 * q + 1],
					    vals, nvals)) != 0)
						break;
				}
				c[l][0] = x0;
				c[l][1] = x1;
				c[l][2] = x2;
				tn[l][0] = n0;
				tn[l][1] = n1;
				tn[l][2] = n2;
			}
			if (in && !start && l - 1 >= cont) {
				/* the child the ray is in at t is where the last
				 * step left level l - 1: its index along e is the
				 * first in the new parent, the others and their
				 * crossing times those of the cell it left */
				int k = l - 1;
				int64_t k0, k1;

				children(m, l, e, c[l][e], n, &k0, &k1);
				lim[k][e] = r.up[e] ? k1 : k0 - 1;
				c[k][e] = r.up[e] ? k0 : k1 - 1;
				tn[k][e] = t_exit_of(&r, k, e, c[k][e]);
				l = k;
				continue;
			}
			if (in) {
				/* descend into the child the ray is in at t */
				int k = l - 1;

				cont = k;   /* what was below is left behind */
				for (a = 0; a < 3; a++) {
					int64_t k0, k1;

					children(m, l, a, c[l][a], n, &k0, &k1);
					lim[k][a] = r.up[a] ? k1 : k0 - 1;
					if (start)
						;  /* c[k] set from the start leaf */
					else if (r.s[a] == 0)
						c[k][a] = r.fixed[a] / r.w[k][a];
					else if (a == e)
						c[k][a] = r.up[a] ? k0 : k1 - 1;
					else
						/* tied axes before e were
						 * crossed first, after e not */
						c[k][a] = find_cell(&r, k, a, k0, k1,
						    t, a < e);
					tn[k][a] = t_exit_of(&r, k, a, c[k][a]);
				}
				l = k;
				continue;
			}
		}
		/* leave this cell through face ax at texit */
		if (!(texit < tb))
			break;
		start = 0;
		cont = l;   /* below l: left behind, unless l is 0; from l up
		               to where the step stops: left through face ax */
		for (;;) {
			c[l][ax] += r.s[ax];
			if (c[l][ax] != lim[l][ax])
				break;
			if (l == top)
				goto done;
			l++;   /* left the parent too, through the same face */
		}
		tn[l][ax] = t_exit_of(&r, l, ax, c[l][ax]);
		t = texit;
		e = ax;
	}
done:
	if (st != NULL) {
		for (l = 0; l <= VX_MACRO_MAXLEV; l++)
			st->macro[l] += s.macro[l];
		st->leaves += s.leaves;
		st->culled += s.culled;
		st->rays += s.rays;
	}
	return rc;
}

int
vx_macro_traverse(const vx_macro *m, const vx_grid *g, const double o[3],
    const double d[3], double tmin, double tmax, const float *vals,
    int nvals, vx_visit_fn fn, void *ctx, vx_trav_stats *st)
{
	if (g != NULL && !fits(m, g))
		return -1;
	return walk(m, m->nlev, m->dims[0], g, g ? NULL : m->mm[0], NULL, o,
	    d, tmin, tmax, vals, nvals, fn, ctx, st);
}


int
vx_macro_traverse_masked(const vx_macro *m, const vx_grid *g,
    vx_cellmask *k, const double o[3], const double d[3], double tmin,
    double tmax, const float *vals, int nvals, vx_visit_fn fn, void *ctx,
    vx_trav_stats *st)
{
	if (mask_walk(m, g, &k, vals, nvals) != 0)
		return -1;
	return walk(m, m->nlev, m->dims[0], g, NULL, k, o, d, tmin, tmax,
	    vals, nvals, fn, ctx, st);
}


int
vx_macro_traverse_flat(const vx_macro *m, const vx_grid *g,
    const double o[3], const double d[3], double tmin, double tmax,
    const float *vals, int nvals, vx_visit_fn fn, void *ctx,
    vx_trav_stats *st)
{
	int64_t n[3];

	if (m == NULL) {
		if (g == NULL)
			return -1;
		leaf_dims(g, n);
		return walk(NULL, 0, n, g, NULL, NULL, o, d, tmin, tmax, vals,
		    nvals, fn, ctx, st);
	}
	if (g != NULL && !fits(m, g))
		return -1;
	return walk(m, 0, m->dims[0], g, g ? NULL : m->mm[0], NULL, o, d,
	    tmin, tmax, vals, nvals, fn, ctx, st);
}
