/* vx_cellmask.h: cell masks over the min/max hierarchy (vx_macro.h).
 *
 * A cell mask is a bit per leaf for one list of values, kept for the leaves
 * of each level-1 macrocell that brackets one of them: the bit is set where
 * the leaf's own range brackets one (the test the walk makes on its 8
 * loaded samples: the same answer, leaf for leaf).  With a mask the walk
 * decides a leaf it steps through by one bit and loads the samples only of
 * the leaves it visits, so the walk visits the same leaves with the same
 * visits, bit for bit.  Built once per list of values (an isovalue change
 * builds a new one); volume leaves only, hierarchies of 1 or more levels.
 * Memory: a bit per leaf of the bracketing level-1 macrocells. */
#ifndef VX_CELLMASK_H
#define VX_CELLMASK_H

#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>

#include "vx_err.h"
#include "vx_grid.h"
#include "vx_macro.h"

#define VX_CELLMASK_MAXV 16      /* values per mask */
#define VX_CELLMASK_MAXROW 63   /* level-1 macrocell edge along x, leaves */

typedef struct vx_cellmask {
	int ready;               /* 1: prepared (else the walk tests samples) */
	const vx_macro *m;       /* the hierarchy it was built over */
	const vx_grid *g;        /* and the volume (fits m: checked once) */
	float vals[VX_CELLMASK_MAXV];
	int nvals;
	int64_t nblock;          /* level-1 macrocells */
	int64_t nset;            /* of which bracketing (they have bits) */
	int64_t words;           /* 64-bit words per bracketing macrocell */
	int64_t *slot;           /* per level-1 macrocell: its first word in
	                            bits, or -1 */
	_Atomic unsigned char *state;  /* per level-1 macrocell: 0 bits not
	                            built, 1 being built, 2 built */
	_Atomic int64_t built;   /* macrocells in state 2 */
	int64_t *set;            /* the nset bracketing macrocells, ascending
	                            (made with the table: a renderer's frames
	                            need not scan all nblock for them) */
	uint64_t *bits;          /* leaf (x, y, z) of a macrocell, counted
	                            from its low corner: bit x + w0 (y + w1 z),
	                            w = m->width[1] */
} vx_cellmask;

void vx_cellmask_init(vx_cellmask *k);
void vx_cellmask_free(vx_cellmask *k);   /* accepts an initialized or NULL k */

/* vx_cellmask_build: the mask of m (built over volume g) for vals[0..nvals)
 * (k is initialized by the call).  lazy: only the table is made now, and
 * each macrocell's bits are computed by the first walk that enters it
 * (walks in any number of threads; what they visit does not depend on who
 * built what); else every bracketing macrocell's bits are computed here
 * with nthreads threads.  Leaves k->ready 0 and returns 0 when a mask does
 * not apply: no macrocell level, no value or more than VX_CELLMASK_MAXV,
 * level-1 macrocells more than VX_CELLMASK_MAXROW leaves long along x, or
 * g not m's volume.  Errors: VX_ENOMEM. */
int vx_cellmask_build(vx_cellmask *k, const vx_macro *m, const vx_grid *g,
    const float *vals, int nvals, int lazy, int nthreads, vx_err *e);

/* vx_cellmask_bytes: memory the mask holds (bits, whether computed yet or
 * not, and tables).  vx_cellmask_built: macrocells whose bits are built.
 * vx_cellmask_block_built: 1 if level-1 macrocell b's bits are built. */
size_t vx_cellmask_bytes(const vx_cellmask *k);
int64_t vx_cellmask_built(const vx_cellmask *k);
int vx_cellmask_block_built(const vx_cellmask *k, int64_t b);

/* vx_cellmask_matches: 1 if k is ready and was built over m for exactly
 * vals[0..nvals) (bit for bit). */
int vx_cellmask_matches(const vx_cellmask *k, const vx_macro *m,
    const float *vals, int nvals);

#endif
