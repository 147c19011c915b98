/* vx_mip.h: exact maximum-intensity projection (Parker et al. 1999 §4.3).
 *
 * For each ray, a priority queue of macrocells keyed by their stored maximum
 * (largest first) is refined level by level; a level-1 macrocell pulled
 * from the queue has its data cells walked along the ray, and each cell
 * whose corner maximum can still beat the best value gives the exact
 * maximum of the trilinear field on the ray's segment in it (the field
 * along the ray is a cubic: its maximum can lie strictly inside a cell, so
 * face values alone are not enough: vx_cell_max).  The walk stops as soon as
 * the queue's head cannot beat the best value found.
 *
 * "Use last t": a trilinear sample at the t where the previous ray of the
 * same tile found its maximum (the segment's midpoint when there is none)
 * is a lower bound on this ray's maximum; macrocells whose maximum is below
 * it are never pushed.  The bound only prunes cells that could never be
 * pulled from the queue, so the result (value and depth) is bit-identical
 * with the bound on or off; only the queue work differs.
 *
 * Rays are in index space (vx_world_to_index*).  Non-finite samples are
 * ignored (a cell with a non-finite corner contributes nothing): no NaN key
 * and no NaN result.
 *
 * The result is fixed by a rule, not by the order of the work: each cell
 * on the ray gives the exact maximum of its cubic on its segment, rounded
 * down (vx_cell_max: never above the cubic's exact maximum, below it by at
 * most Horner's error bound), clamped into the range of its 8 corners (the
 * trilinear field never leaves it; rounding in the cubic could), with the
 * smallest t where it is reached;
 * the ray's result is the largest of these values and, among cells that
 * reach it, the smallest t.  A cell or macrocell is skipped only when its
 * maximum is below the best value, or equal to it with a segment starting
 * no earlier than the best t, so value and depth are bit-identical
 * whatever the order of the work: for any hierarchy, layout, thread count,
 * last-t bound, for the queue and for the column walk (rays along an axis:
 * the axis-aligned views, integer samples: no queue, see mip.c), and
 * equal to vx_mip_ray_exhaustive's.
 *
 * Bounds.  So the value is never above the exact maximum of the computed
 * cubics, and never above the field's exact maximum where they are exact
 * (samples, ray origin and direction whose arithmetic is exact in double);
 * elsewhere their coefficients are within rounding of the field's: at most
 * 2^-39 of the cell's largest |corner| (the analysis of iso.c's
 * ends_certain, iso 0, W < 1024), the bound on how far above the field's
 * maximum the value can be.
 *
 * A volume with an axis of one sample (dims 1 there) has no cells: its
 * samples span a plane, line or point, the field there is their bilinear
 * (linear) interpolation, and a ray with d nonzero along a one-sample axis
 * meets it at the one t where that coordinate is 0 (two such axes must
 * agree on t exactly, else a miss): the value is the field there.  A ray
 * inside the span (o and d zero on every one-sample axis) gets the rule
 * above over the cells of the other axes.  The hierarchy m is not used
 * for such volumes; the result is the same for vx_mip_ray_exhaustive.  */
#ifndef VX_MIP_H
#define VX_MIP_H

#include <stdint.h>

#include "vx_camera.h"
#include "vx_err.h"
#include "vx_grid.h"
#include "vx_image.h"
#include "vx_macro.h"

typedef struct vx_mip_stats {
	uint64_t rays;
	uint64_t pushes, pops;       /* priority-queue operations */
	uint64_t macro_opened;       /* macrocells split or walked */
	uint64_t cells;              /* data cells whose maximum was solved */
	uint64_t cells_skipped;      /* data cells pruned by their corners (or
	                                their face values: column walk) */
	uint64_t bound_pruned;       /* pushes avoided by the last-t bound */
	uint64_t max_queue;          /* largest queue length seen */
	/* vx_mip_render only: */
	int threads;                 /* threads the picture ran on */
	double seconds;              /* wall time of its tiles */
	double thread_seconds;       /* the threads' time in them, summed */
} vx_mip_stats;

/* Per-thread workspace: the fixed-capacity queue (no allocation per ray). */
typedef struct vx_mip_work {
	void *q;
	size_t cap;
	double last_t;               /* previous ray's t of the maximum, or NaN */
	void *cc;                    /* private: the column walk's cache of
	                                sample maxima per column (mip.c) */
	int plain;                   /* 1: the plain walk, a generic cell walk
	                                with a visitor per cell (the reference
	                                the tests compare the specialized walks
	                                with: the same bits, slower); 0 (what
	                                vx_mip_work_init sets): the fast one */
} vx_mip_work;

/* vx_mip_work_init: size the queue for hierarchy m (its capacity bound is
 * derived from the level dims: no ray can need more), and a cache of
 * exact sample maxima for rays along an axis, kept from ray to ray and
 * keyed by the volume's data pointer and the hierarchy: a workspace
 * serves one volume and hierarchy; after changing samples in place, free
 * and init it again.  Free with vx_mip_work_free. */
int vx_mip_work_init(vx_mip_work *w, const vx_macro *m, vx_err *e);
void vx_mip_work_free(vx_mip_work *w);

/* vx_mip_ray: the exact maximum of volume g along o + t d, t in
 * [tmin, tmax], with hierarchy m built over g (vx_macro_build).
 * use_last_t: 1 to use (and update) w->last_t as the lower bound.
 * Returns 1 and sets *vmax and *tmax (the rule above) if the ray meets a
 * finite sample, else 0 (*vmax = -Inf, *tmax = +Inf).  st may be NULL (a
 * ray taking the column walk makes no queue pushes or pops). */
int vx_mip_ray(const vx_grid *g, const vx_macro *m, vx_mip_work *w,
    const double o[3], const double d[3], double tmin, double tmax,
    int use_last_t, double *vmax, double *tmaxp, vx_mip_stats *st);

/* vx_mip_ray_exhaustive: the same maximum and t by solving every cell
 * along the ray (no queue, no pruning): the reference the tests compare
 * against, bit for bit. */
int vx_mip_ray_exhaustive(const vx_grid *g, const double o[3],
    const double d[3], double tmin, double tmax, double *vmax,
    double *tmaxp);

/* ---- the picture ---- */

typedef struct vx_mip_opts {
	int nthreads;            /* <= 0: OpenMP's default (vx_par_threads) */
	int tile;                /* tile edge in pixels (default 16): the
	                            last-t bound starts afresh in each tile,
	                            whose rays go row by row */
	int last_t;              /* 1 (default): the last-t bound */
	int exhaustive;          /* 1: every cell along every ray solved
	                            (vx_mip_ray_exhaustive: the reference) */
} vx_mip_opts;

void vx_mip_opts_init(vx_mip_opts *o);

/* vx_mip_render: the MIP picture of volume g, with hierarchy m built over
 * it, through the pixel centres of camera cam (resolved over g's box):
 * val (allocated w x h x 1, named "mip") gets each ray's maximum, or the
 * volume's minimum (0 without a known range) where the ray meets no finite
 * sample; depth (NULL, or allocated w x h x 1, "depth") the distance along
 * the unit camera ray to the first point where the maximum is reached
 * (+Inf: none).  Tiles run in parallel (vx_par.h), each thread with a
 * workspace of its own; the pictures are the same bits at any thread
 * count, tile size and last-t setting.  st (may be NULL) gets the rays'
 * work summed over the threads and the tiles' times.  Errors: VX_ENOMEM.
 * On error no image is allocated. */
int vx_mip_render(const vx_camera *cam, const vx_grid *g, const vx_macro *m,
    const vx_mip_opts *o, vx_image *val, vx_image *depth, vx_mip_stats *st,
    vx_err *e);

#endif
