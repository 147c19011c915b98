/* vx_macro.h: the multilevel min/max grid (Parker et al. 1999, §3.2), its
 * geometry and its build.  Walks over it (vx_macrowalk.h) descend into a
 * macrocell only when its [min, max] brackets a value they look for.
 *
 * Leaves.  The hierarchy sits over an abstract "leaf grid" of n[0] x n[1] x
 * n[2] unit cells: leaf (i,j,k) is the closed box [i,i+1] x [j,j+1] x
 * [k,k+1] of leaf index space, and the whole grid is the closed box
 * [0,n[0]] x [0,n[1]] x [0,n[2]].
 *   - For a volume (vx_grid), the leaves are its data cells: n = dims - 1,
 *     and leaf index space is the grid's index space (sample (i,j,k) at
 *     (i,j,k)).  Leaf min/max are not stored (they would cost more than the
 *     data): the traversal fetches the cell's 8 corners (vx_grid_cell) and
 *     tests them on the fly, and hands the corners to the visitor.
 *   - For explicit leaves (the tetrahedral mesh's leaf grid of tet lists),
 *     the caller gives one (min, max) pair per leaf; the visitor gets the
 *     leaf's linear index.
 *
 * Levels.  Level 0 is the leaves.  Level l (1..nlev) groups size[l] cells
 * of level l-1 per axis into one macrocell holding the min and max of the
 * data it covers; the last macrocell along an axis may be partial.  The
 * top is one implicit root cell over all level-nlev macrocells.  Parker's
 * "trilevel" hierarchy is nlev = 2 (two macrocell levels, the data cells
 * and the root).  Macrocells are stored linearly (x fastest): Parker found
 * bricking them not worth it.
 *
 * Non-finite samples (NaN, +-Inf) are ignored by every min/max: a cell's
 * range is that of its finite corners, a cell with no finite corner has
 * the empty range (min = +Inf, max = -Inf) and brackets nothing.  So a cell
 * with a non-finite corner is still visited when its finite corners bracket
 * the value; the cell kernel must then reject what it cannot interpolate.
 *
 * The hierarchy's modules, a header each:
 *   vx_macro.h      the hierarchy and its build (macro.c)
 *   vx_macrowalk.h  the hierarchical 3D-DDA over it (macrowalk.c)
 *   vx_cellmask.h   a bit per leaf for a list of values, built with SIMD
 *                   (cellmask.c)
 *   vx_macrobox.h   walks through lists of boxes of leaves, and the boxes
 *                   of a mask's bits: the renderer's bins (macrobox.c)
 *   vx_macroio.h    the stream form, the MCEL chunk (macroio.c,
 *                   formats/macrocell.md) */
#ifndef VX_MACRO_H
#define VX_MACRO_H

#include <stddef.h>
#include <stdint.h>

#include "vx_err.h"
#include "vx_grid.h"

#define VX_MACRO_MAXLEV 6        /* macrocell levels above the leaves */
#define VX_MACRO_MAXSIZE 1024    /* largest macrocell edge, in cells below */

typedef struct vx_macro {
	int nlev;                /* macrocell levels, 0..VX_MACRO_MAXLEV */
	int size[VX_MACRO_MAXLEV + 1][3];     /* size[l]: level-l edge in
	                                         level-(l-1) cells; size[0] 1 */
	int64_t width[VX_MACRO_MAXLEV + 1][3];/* level-l edge in leaves */
	double iwidth[VX_MACRO_MAXLEV + 1][3];/* 1 / width (walk's guesses) */
	int64_t dims[VX_MACRO_MAXLEV + 1][3]; /* cells per axis; dims[0] = n */
	float *mm[VX_MACRO_MAXLEV + 1];       /* mm[l][2c], mm[l][2c+1]: min,
	                                         max of level-l cell c (x
	                                         fastest); mm[0] only for
	                                         explicit leaves */
	float root[2];           /* min, max of everything (empty: +Inf -Inf) */
	int explicit_leaves;     /* 1: leaves carry stored min/max (mm[0]) */
	/* the volume this hierarchy belongs to (volume leaves only) */
	char name[64];
	int64_t vdims[3];
	vx_type vtype;
	uint32_t vcrc;           /* vx_macro_grid_crc of the volume */
	uint32_t vchunk_crc;     /* CRC of the volume's chunk as stored, when */
	int has_vchunk_crc;      /* known: a reader holding that very chunk
	                            has proven the match without a pass */
	void *block_;            /* private: one allocation for all mm[] */
} vx_macro;

void vx_macro_init(vx_macro *m);
void vx_macro_free(vx_macro *m);   /* accepts an initialized or NULL m */

/* vx_macro_default_sizes: default sizes for nlev levels (1..VX_MACRO_MAXLEV)
 * over a volume of sample type t; fills sizes[0..nlev) (level 1 first, in
 * cells of the level below) and returns nlev.  Level-1 macrocells cover
 * 2 KiB of samples (u8 16x16x8, u16/i16 16x8x8, f32 8x8x8 cells), so with
 * two f32 per macrocell level 1 costs 1/256 of the data (0.39 %) whatever
 * the type; level-2 macrocells cover 64x64x64 cells (under 0.003 % more);
 * each further level is 4x4x4 of the level below.  Parker's trilevel
 * hierarchy is VX_MACRO_DEFAULT_LEVELS.  For explicit leaves pass VX_F32.
 * Returns 0 for a bad nlev or type. */
#define VX_MACRO_DEFAULT_LEVELS 2
int vx_macro_default_sizes(vx_type t, int nlev, int sizes[][3]);

/* vx_macro_parse_sizes: "AxBxC[,DxExF...]" (level 1 first) into sizes;
 * returns the number of levels (1..VX_MACRO_MAXLEV) or -1 with e set. */
int vx_macro_parse_sizes(const char *s, int sizes[][3], vx_err *e);

/* vx_macro_build: the hierarchy over volume g's data cells, with nlev levels
 * of the given sizes (each 1..VX_MACRO_MAXSIZE; nlev 0 is allowed and
 * gives a flat grid).  nthreads <= 0 means OpenMP's default.  The result is
 * bit-identical for any thread count.  A volume with a dimension of 1 has
 * no cells: the hierarchy is empty and traversals visit nothing.  m is
 * initialized by the call and owns its arrays.  Errors: VX_EDATA (sizes),
 * VX_ENOMEM. */
int vx_macro_build(vx_macro *m, const vx_grid *g, int nlev,
    const int sizes[][3], int nthreads, vx_err *e);

/* vx_macro_build_explicit: the hierarchy over an n[0] x n[1] x n[2] leaf
 * grid whose leaf c (x fastest: c = i + n0 (j + n1 k)) has the range
 * leaf_mm[2c] .. leaf_mm[2c+1] (non-finite bounds: see above; a leaf with
 * min > max is empty).  The pairs are copied.  Each n[a] >= 0. */
int vx_macro_build_explicit(vx_macro *m, const int64_t n[3],
    const float *leaf_mm, int nlev, const int sizes[][3], int nthreads,
    vx_err *e);

/* vx_macro_bytes: bytes of stored min/max (all levels, mm[0] included). */
size_t vx_macro_bytes(const vx_macro *m);

/* vx_macro_cell_range: level-l cell (x,y,z)'s stored min and max (l >= 1,
 * or l == 0 with explicit leaves).  No bounds check. */
static inline void
vx_macro_cell_range(const vx_macro *m, int l, int64_t x, int64_t y,
    int64_t z, float *lo, float *hi)
{
	size_t c = (size_t)(x + m->dims[l][0] * (y + m->dims[l][1] * z));

	*lo = m->mm[l][2 * c];
	*hi = m->mm[l][2 * c + 1];
}

/* vx_macro_grid_crc: CRC-32 of g's samples in logical order (x fastest,
 * little-endian bytes, pads excluded), so the same for every layout;
 * computed in parallel slabs and combined, so the same for every thread
 * count.  Identifies the volume a stored hierarchy belongs to. */
uint32_t vx_macro_grid_crc(const vx_grid *g);

#endif
