/* vx_macrobox.h: boxes of leaves of the min/max hierarchy (vx_macro.h):
 * a macrocell's box, the earliest entry of a ray into a list of boxes, the
 * walk through the boxes a ray enters (the DDA of vx_macrowalk.h, leaf by
 * leaf inside each box), and the boxes that hold a cell mask's set bits
 * (vx_cellmask.h).  A renderer bins these boxes by the pixels whose rays
 * may enter them (raycast's bins). */
#ifndef VX_MACROBOX_H
#define VX_MACROBOX_H

#include <stddef.h>
#include <stdint.h>

#include "vx_cellmask.h"
#include "vx_macro.h"
#include "vx_macrowalk.h"

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

#endif
