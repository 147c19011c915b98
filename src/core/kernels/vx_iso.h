/* vx_iso.h: rays against the isosurfaces of a volume: the macrocell
 * traversal (vx_macrowalk.h) feeding the trilinear cell kernel (vx_cell.h).
 * One query serves primary rays, shadow rays, transparent layers and, later,
 * the bakes' path-traced bounces.
 *
 * Rays are in the volume's index space (sample (i,j,k) at (i,j,k)); use
 * vx_world_to_index / vx_world_to_index_dir (vx_camera.h) on world rays: the
 * ray parameter t is then the same in both spaces.
 *
 * Crack-free hits.  For every visited cell the field minus the isovalue is
 * taken at the ray's entry and exit from the face's own four corners
 * (vx_cell_face_value), so two cells sharing a face agree on its sign bit for
 * bit; a sign change (f >= iso counts as inside) is claimed by exactly one
 * cell.  Where the segment starts or ends inside a cell, the trilinear value
 * is used.  Cells with a non-finite corner have no surface.
 *
 * Touches.  Inside a cell a touch (f reaching iso at an extremum without
 * crossing it) is decided exactly (vx_cell_first_root).  On a face, edge
 * or vertex between cells, where the shared face value is exactly iso:
 * f coming down to iso from above and leaving upward is one touch hit, at
 * that t, claimed by the cell the ray enters there (the one before only
 * notes it); from below it is the entry and the exit at that t (the cell
 * before claims the one, the cell after the other), as any crossing
 * through a face.  A stretch where f equals iso along the ray is inside
 * (f >= iso): no touch there.  A face value that misses iso by any amount
 * is no touch. */
#ifndef VX_ISO_H
#define VX_ISO_H

#include <stdint.h>

#include "vx_cell.h"
#include "vx_grid.h"
#include "vx_macrobox.h"

#define VX_ISO_MAX 16            /* isovalues per query */

typedef struct vx_iso_tracer {
	const vx_grid *g;
	const vx_macro *m;       /* NULL or flat: walk every cell */
	int flat;                /* 1: ignore the hierarchy (benchmarks, tests) */
	int solver;              /* vx_cell_solver */
	vx_cellmask *mask;       /* NULL, or m's cell mask for the isovalues
	                            traced (vx_cellmask.h): the same hits,
	                            fewer samples read */
	int face_ends;           /* 1: a grazed cell's end values always
	                            from its faces, never certified from its
	                            cubic (tests: the certificate's
	                            reference; the same hits either way) */
} vx_iso_tracer;

typedef struct vx_iso_hit {
	double t;                /* ray parameter of the hit */
	int surface;             /* index into the isovalue list */
	int kind;                /* VX_CELL_CROSS or VX_CELL_TOUCH */
	int entering;            /* crossing from f < iso to f >= iso */
	int64_t cell[3];         /* the cell that claimed it */
	double p[3];             /* hit point, index space */
	float c[8];              /* the cell's corners (for normals) */
} vx_iso_hit;

typedef struct vx_iso_stats {
	uint64_t rays;           /* queries */
	uint64_t cells;          /* cells handed to the kernel */
	uint64_t roots;          /* root queries: vx_cell_first_root calls
	                            and exact early-outs (vx_cell_sign_bound) */
	uint64_t bounded;        /* of the root queries, misses settled by
	                            the cubic's sign bound */
	uint64_t certified;      /* of those, settled without the face
	                            values (the cubic vouched for its ends) */
	uint64_t exact;          /* signs the cell kernel's filter could not
	                            decide, evaluated exactly (its slow
	                            path: near-touches) */
	uint64_t hits;           /* hits reported */
	uint64_t nonfinite;      /* cells skipped for a non-finite corner */
	uint64_t cyc_isect;      /* clock ticks inside the cell kernel (only
	                            counted when timing is on) */
	int timing;              /* 1: count cyc_isect (costs a clock read per
	                            cell) */
	vx_trav_stats trav;
} vx_iso_stats;

/* vx_iso_hit_fn: called for each hit in order of increasing t (hits at one t
 * in the order of the isovalue list); return nonzero to stop the query. */
typedef int (*vx_iso_hit_fn)(void *ctx, const vx_iso_hit *h);

/* vx_iso_trace: every crossing of the isovalues iso[0..niso) along o + t d
 * for t in [tmin, tmax], in order, handed to fn.  Returns 0 when the ray
 * ended, or fn's nonzero value.  st may be NULL.  Reentrant.
 * The isovalues are doubles and are drawn as given: a cell brackets iso
 * when its corners' min <= iso <= max in double, and every root and touch
 * is of the field minus the double iso.  (The macrocell walk and the cell
 * mask take floats: they are given each iso rounded to the nearest float,
 * which brackets whatever iso does, since rounding is monotone and the
 * ranges' ends are floats: they visit a superset of the cells to solve.) */
int vx_iso_trace(const vx_iso_tracer *tr, const double o[3],
    const double d[3], double tmin, double tmax, const double *iso, int niso,
    vx_iso_hit_fn fn, void *ctx, vx_iso_stats *st);

/* vx_iso_trace_boxes: vx_iso_trace for t >= 0 whose walk goes through the
 * boxes box[0..nbox) (or box[ix[0..nbox)]) whose footprint holds pk's
 * query (vx_boxpick; pk NULL: every box) that the ray enters, one after
 * the other, and nowhere else (vx_macro_traverse_boxes): the hits of the
 * cells of those boxes; all the hits of the ray when every leaf that
 * brackets one of the isovalues lies in one of them.  A tracer without the
 * hierarchy (flat, or no level 1) traces the whole ray.  st->trav.rays
 * counts the ray only when it entered a box. */
int vx_iso_trace_boxes(const vx_iso_tracer *tr, const double o[3],
    const double d[3], const vx_cellbox *box, const uint32_t *ix,
    size_t nbox, const vx_boxpick *pk, const double *iso, int niso,
    vx_iso_hit_fn fn, void *ctx, vx_iso_stats *st);

/* vx_iso_first: the first hit in [tmin, tmax]; returns 1 and fills *hit, or
 * 0 for none. */
int vx_iso_first(const vx_iso_tracer *tr, const double o[3],
    const double d[3], double tmin, double tmax, const double *iso, int niso,
    vx_iso_hit *hit, vx_iso_stats *st);

/* vx_iso_normal: the unit world-space normal at a hit, facing against the
 * world ray direction dw; returns the vx_cell_normal path.  The analytic
 * gradient at the hit, divided by the spacing and normalized once (one
 * square root and one division per component after the spacing's: its
 * latency is a large part of a hit's cost); where that gradient vanishes
 * (vx_cell_normal's threshold) or its world components fall outside
 * [2^-500, 2^500], vx_cell_normal's fallbacks (the centre's gradient, then
 * -dw) with scaling against overflow. */
int vx_iso_normal(const vx_grid *g, const vx_iso_hit *h, const double dw[3],
    double n[3]);

/* vx_cycles: a cheap monotonic tick counter (TSC on x86, else ns). */
uint64_t vx_cycles(void);

#endif
