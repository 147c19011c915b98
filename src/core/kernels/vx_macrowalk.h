/* vx_macrowalk.h: the hierarchical 3D-DDA over the min/max hierarchy
 * (vx_macro.h; Amanatides & Woo 1987, one DDA per level, descending into a
 * macrocell only when its [min, max] brackets a value the caller looks
 * for), and the same walk without the hierarchy. */
#ifndef VX_MACROWALK_H
#define VX_MACROWALK_H

#include <stdint.h>

#include "vx_cellmask.h"
#include "vx_grid.h"
#include "vx_macro.h"

/* A ray is o + t d in leaf index space (o, d finite; d need not be unit,
 * components may be 0, -0.0, tiny or huge).  Its segment is
 * [ta, tb] = [max(tmin, t_enter), min(tmax, t_exit)], where t_enter and
 * t_exit bound the part of the ray inside the closed leaf-grid box; nothing
 * is visited when ta > tb (or either is NaN).  The traversal walks the
 * leaves along the segment in order of increasing t, stepping one face at a
 * time (consecutive leaves of the walk are face neighbours), and calls the
 * visitor for each leaf it enters whose range brackets a wanted value.
 *
 * Face crossings.  The ray crosses the plane x_a = p at t(a, p) = (p -
 * o[a]) / d[a], computed the same way everywhere (as (p - o[a]) * (1 /
 * d[a]) when 2^-1000 <= |d[a]| <= 2^1000, else by division), never
 * accumulated: so crossing times are monotone in p, the leaf intervals of
 * one walk tile [ta, tb] exactly (a leaf's t1 is bit-identical to the next
 * leaf's t0), and the hierarchical walk reports bit-identical times to the
 * flat walk.
 *
 * Ties.  When the ray leaves a leaf through an edge or a vertex (several
 * crossing times equal), the walk steps the tied axes one at a time, lowest
 * axis first; each intermediate leaf is entered with a zero-length interval
 * [t, t] (it touches the ray at one point).  A ray lying in a face plane
 * (d[a] == 0 and o[a] an integer) walks the leaves on the upper side of the
 * plane (index floor(o[a])), or the last layer when o[a] == n[a].  The
 * start leaf is the one the ray is in just after ta (the "post-crossing"
 * leaf); a segment that starts on a plane starts beyond it.
 *
 * Values.  vals[0..nvals) are the values looked for (isovalues); a macrocell
 * is entered and a leaf visited only when min <= v <= max for some v.  With
 * nvals == 0 every cell is entered and every leaf visited.
 *
 * Guarantee.  With |o[a]| < 2^40, every leaf whose open box meets the
 * segment in an interval of positive length is visited exactly once (if it
 * brackets a value); the other visited leaves touch the segment only on
 * their boundary.  No allocation, no recursion; at most sum of dims steps
 * per level. */

typedef struct vx_leaf_visit {
	int64_t i[3];      /* leaf index */
	int64_t leaf;      /* linear leaf index i0 + n0 (i1 + n1 i2) */
	double t0, t1;     /* the ray is in this leaf for t in [t0, t1] */
	int entry_axis;    /* axis of the face the ray entered through at t0,
	                      -1 if t0 is not on a face (segment starts inside) */
	int entry_side;    /* 0: face at i[a] (lower), 1: face at i[a] + 1 */
	int exit_axis;     /* axis of the face it leaves through at t1, -1 if
	                      the segment ends inside (t1 = tmax) */
	int exit_side;     /* 0 lower, 1 upper */
	float lo, hi;      /* the leaf's range (finite corners / stored) */
	float c[8];        /* volume leaves: the 8 corners as vx_grid_cell */
} vx_leaf_visit;

/* vx_visit_fn: called once per visited leaf, in order; return nonzero to
 * stop the walk (the traversal then returns that value). */
typedef int (*vx_visit_fn)(void *ctx, const vx_leaf_visit *v);

typedef struct vx_trav_stats {
	uint64_t macro[VX_MACRO_MAXLEV + 1]; /* macrocells examined, level l */
	uint64_t leaves;         /* leaves handed to the visitor */
	uint64_t culled;         /* leaves stepped into but not bracketing */
	uint64_t rays;           /* traversals started */
} vx_trav_stats;

/* vx_macro_traverse: the hierarchical walk.  g: the volume the hierarchy
 * was built over (its cells are the leaves; corners are fetched), or NULL
 * for explicit leaves (their stored ranges are tested when the hierarchy
 * has them).  st: counters added to (may be NULL).  Returns 0 when the walk
 * ended, or the visitor's nonzero value; -1 (nothing visited) when g's
 * cells are not m's leaves (a bug in the caller).  Reentrant: any number
 * of threads may walk one hierarchy at once. */
int vx_macro_traverse(const vx_macro *m, const vx_grid *g, const double o[3],
    const double d[3], double tmin, double tmax, const float *vals,
    int nvals, vx_visit_fn fn, void *ctx, vx_trav_stats *st);

/* vx_macro_traverse_flat: the same walk without the hierarchy: every leaf
 * along the segment is stepped through and tested (only its own range), so
 * it visits exactly the leaves vx_macro_traverse visits, with bit-identical
 * visits.  m may be NULL when g is given (the leaves are g's cells). */
int vx_macro_traverse_flat(const vx_macro *m, const vx_grid *g,
    const double o[3], const double d[3], double tmin, double tmax,
    const float *vals, int nvals, vx_visit_fn fn, void *ctx,
    vx_trav_stats *st);

/* vx_macro_traverse_masked: vx_macro_traverse deciding leaves by mask k
 * (NULL or not ready, or built for other values or another hierarchy: the
 * plain walk).  Same visits, bit for bit.  Reentrant like
 * vx_macro_traverse; it writes k (lazy bits) with atomic hand-over. */
int vx_macro_traverse_masked(const vx_macro *m, const vx_grid *g,
    vx_cellmask *k, const double o[3], const double d[3], double tmin,
    double tmax, const float *vals, int nvals, vx_visit_fn fn, void *ctx,
    vx_trav_stats *st);

#endif
