/* vx_macro.h: the multilevel min/max grid (Parker et al. 1999, §3.2) and
 * its hierarchical 3D-DDA traversal (Amanatides & Woo 1987, one DDA per
 * level, descending into a macrocell only when its [min, max] brackets a
 * value the caller looks for).
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
 * The stream form is the MCEL chunk (formats/macrocell.md). */
#ifndef VX_MACRO_H
#define VX_MACRO_H

#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>

#include "vx_err.h"
#include "vx_grid.h"
#include "vx_stream.h"

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

/* vx_macro_hdr_levels: the keys that describe m's levels in a chunk header
 * (MCEL and TLEF), in this order: levels, sizes, dims-1 .. dims-L, range. */
int vx_macro_hdr_levels(const vx_macro *m, vx_hdr *h, vx_err *e);

/* vx_macro_sizes_hdr_parse: a chunk header's "sizes" value, exactly nlev
 * space-separated AxBxC (the MCEL and TLEF headers); 0 or VX_EDATA. */
int vx_macro_sizes_hdr_parse(const char *v, int nlev, int sizes[][3],
    vx_err *e);

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

/* ---- traversal ----
 *
 * A ray is o + t d in leaf index space (o, d finite; d need not be unit,
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

/* ---- cell masks ----
 * A cell mask is a bit per leaf for one list of values, kept for the leaves
 * of each level-1 macrocell that brackets one of them: the bit is set where
 * the leaf's own range brackets one (the test the walk makes on its 8
 * loaded samples: the same answer, leaf for leaf).  With a mask the walk
 * decides a leaf it steps through by one bit and loads the samples only of
 * the leaves it visits, so the walk visits the same leaves with the same
 * visits, bit for bit.  Built once per list of values (an isovalue change
 * builds a new one); volume leaves only, hierarchies of 1 or more levels.
 * Memory: a bit per leaf of the bracketing level-1 macrocells. */

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

/* vx_macro_traverse_masked: vx_macro_traverse deciding leaves by mask k
 * (NULL or not ready, or built for other values or another hierarchy: the
 * plain walk).  Same visits, bit for bit.  Reentrant like
 * vx_macro_traverse; it writes k (lazy bits) with atomic hand-over. */
int vx_macro_traverse_masked(const vx_macro *m, const vx_grid *g,
    vx_cellmask *k, const double o[3], const double d[3], double tmin,
    double tmax, const float *vals, int nvals, vx_visit_fn fn, void *ctx,
    vx_trav_stats *st);

/* vx_macro_cell_box: level-l cell b's box of leaves, [lo, hi) per axis
 * (the walk's planes).  vx_macro_cell_brackets: 1 if its stored range
 * brackets one of vals (the walk's test: lo <= v <= hi; l >= 1, or 0 with
 * explicit leaves). */
void vx_macro_cell_box(const vx_macro *m, int l, int64_t b, int64_t lo[3],
    int64_t hi[3]);
int vx_macro_cell_brackets(const vx_macro *m, int l, int64_t b,
    const float *vals, int nvals);

/* A box of leaves [lo, hi) per axis (a macrocell's, or a block of its
 * leaves), lb, a lower bound of the entry time of every ray it will be
 * asked about, and a footprint fp = { x0, y0, x1, y1 }: a query point
 * (qx, qy) outside [x0, x1] x [y0, y1] skips the box (raycast: the pixels
 * whose rays may enter it). */
typedef struct vx_cellbox {
	double lb;
	int64_t lo[3], hi[3];
	int32_t fp[4];
} vx_cellbox;

/* vx_boxpick: which boxes of a list a query looks at beyond lb: those whose
 * footprint holds the query point q, tested either against each box's fp,
 * or (pix non-NULL) by one bit of a set of 64 query points kept per entry of
 * the list (raycast: a bin of 8 x 8 pixels, bit (y % 8) 8 + x % 8 where the
 * entry's footprint holds pixel (x, y); the same answer as the fp test for
 * q in the bin).  lb (with pix): the entries' lb in the list's order, so
 * that a query reads its list front to back and each box only when its
 * footprint holds q.  use_em (with pix, a list of at most 64 entries): em
 * says which entries those are, bit k for the k-th (bit `bit` of pix[k]),
 * and the query reads only them (the same entries in the same order: no
 * other entry's lb, pix or box is read, and no branch on its bit). */
typedef struct vx_boxpick {
	int32_t q[2];
	const double *lb;        /* lb[k] = the k-th entry's box's lb */
	const uint64_t *pix;     /* NULL, or the k-th entry's query points */
	int bit;                 /* q's bit in pix */
	int use_em;              /* 1: em lists q's entries (at most 64) */
	uint64_t em;             /* bit k: the k-th entry's pix holds q */
} vx_boxpick;

/* vx_macro_boxes_entry: the earliest time the ray o + t d (leaf
 * coordinates, as for the walk) enters one of the boxes box[0..nbox) (or,
 * with ix non-NULL, box[ix[0..nbox)]), sorted by lb, in the walk's own
 * arithmetic: a box's entry is the largest
 * crossing time of its near faces; a box whose far faces are crossed before
 * that, or beside which a ray parallel to an axis runs, is not entered; the
 * boxes from the first whose lb exceeds the earliest entry so far are not
 * looked at; with q non-NULL, neither are boxes whose footprint does not
 * hold (q[0], q[1]).  +Inf: none is entered (or the ray is not finite);
 * never -0, so boxes of equal lb give the same bits in any order.
 * Every leaf of those boxes that a walk of this ray visits is entered at
 * or after this time, so a walk started before it visits exactly the
 * leaves a walk from the segment's start does, when every leaf that
 * brackets the values lies in one of the boxes whose footprint holds q
 * (raycast's binning: the level-1 macrocells that bracket, or the blocks
 * of their leaves that hold a bracketing leaf, vx_cellmask_boxes). */
double vx_macro_boxes_entry(const vx_macro *m, const vx_cellbox *box,
    const uint32_t *ix, size_t nbox, const double o[3], const double d[3],
    const int32_t q[2]);

/* vx_macro_traverse_boxes: the walk of vx_macro_traverse_masked (mask k)
 * of the ray o + t d from t = 0 through the boxes box[0..nbox) (or, with
 * ix non-NULL, box[ix[0..nbox)]), sorted by lb, that pk picks (its q, or
 * its bits: pk NULL picks every box) and the ray enters, and nowhere else:
 * one box after the other in order of entry, leaf by leaf inside each.
 * The boxes must be disjoint (vx_cellmask_boxes' blocks and whole
 * level-1 macrocells are), and each lb at most the entry time of every
 * ray that enters its box.  It visits exactly the leaves of the walk from
 * 0 that lie in those boxes, with the same data, in the same order: all
 * of them when every leaf that brackets the values lies in one of those
 * boxes (raycast's bins); a ray that enters none visits nothing.  Any
 * number of boxes: those entered wait in a list of at most 64, by entry
 * time, and the list is read again for the rest when it overflows.  The
 * levels of the hierarchy are not walked (st counts no macrocells).
 * Returns the visitor's nonzero value, 0 (st counts the ray only when it
 * entered a box), or -1 when g does not fit m or m has no level 1.
 * Reentrant (k's lazy bits as for the walk). */
int vx_macro_traverse_boxes(const vx_macro *m, const vx_grid *g,
    vx_cellmask *k, const vx_cellbox *box, const uint32_t *ix, size_t nbox,
    const vx_boxpick *pk, const double o[3], const double d[3],
    const float *vals, int nvals, vx_visit_fn fn, void *ctx,
    vx_trav_stats *st);

/* vx_cellmask_boxes: for each of level-1 macrocell b's blocks of sub x sub
 * x sub leaves (from its low corner; the last ones along an axis may be
 * shorter) that holds a leaf whose bit is set, the box (lo, hi only) of
 * its leaves whose bits are set, the least box that holds them, into out
 * (room for one per block; NULL: only count them), building b's bits if
 * no one has.  Returns
 * their number: 0 when b brackets none of the values or k is not ready;
 * 1, b's whole box, when sub < 1 or another thread is building b's bits
 * (walks on k may run in other threads). */
size_t vx_cellmask_boxes(vx_cellmask *k, int64_t b, int sub,
    vx_cellbox *out);

/* ---- stream form: the MCEL chunk (formats/macrocell.md) ---- */

/* vx_macro_to_chunk: the MCEL chunk of m (zlevel 0 raw, 1..9 zlib). */
int vx_macro_to_chunk(const vx_macro *m, int zlevel, vx_chunk *c,
    vx_err *e);
/* vx_macro_from_chunk: parse an MCEL chunk; m is initialized by the call.
 * Checks every header word and the body's size before allocating. */
int vx_macro_from_chunk(vx_macro *m, const vx_chunk *c, vx_err *e);

/* vx_macro_matches: 1 if m was built over exactly this volume (name, dims,
 * type and sample CRC; the CRC costs one pass over the samples unless crc
 * is given: pass NULL to compute it). */
int vx_macro_matches(const vx_macro *m, const vx_grid *g,
    const uint32_t *crc);

enum {
	VX_MACRO_ABSENT = 0,     /* no MCEL chunk for this volume */
	VX_MACRO_LOADED,         /* found, matches the volume, loaded */
	VX_MACRO_STALE           /* found, but built over other samples */
};

/* vx_macro_from_stream: find the MCEL chunk belonging to volume g (same
 * name) and load it if it matches g (vx_macro_matches).  src: the index in
 * s of the VOLM chunk g was decoded from and not changed since, or -1: when
 * that chunk's CRC is known (read with it) and equals the MCEL chunk's
 * volume-chunk-crc32, the bytes the hierarchy was built from are these, and
 * the pass over the samples is skipped.  *status gets one of the values
 * above and *index the chunk's position (-1 if absent); m is initialized and
 * holds the hierarchy only when LOADED.  A malformed MCEL chunk is an error
 * (VX_EDATA), absence and staleness are not: the caller then builds the
 * hierarchy itself (and may say so). */
int vx_macro_from_stream(vx_macro *m, const vx_stream *s, const vx_grid *g,
    long src, int *status, long *index, vx_err *e);

#endif
