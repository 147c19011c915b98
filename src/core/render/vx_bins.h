/* vx_bins.h: the primary rays' bins.  For a camera and a volume walked
 * through its hierarchy, the image is cut into bins of VX_BIN x VX_BIN
 * pixels, and each bin lists, by a lower bound of their entry time, the
 * boxes of leaves its rays may enter among those that hold every leaf that
 * brackets an isovalue: with a cell mask, the boxes of the set bits of
 * each block of block^3 leaves of the bracketing level-1 macrocells whose
 * bits are built (vx_cellmask_boxes); else those macrocells whole.  A ray
 * then walks only the boxes it enters (vx_macro_traverse_boxes,
 * vx_iso_trace_boxes), the same leaves as a walk from the eye, and a ray
 * whose pixel no box covers is not walked at all.  Conservative: a
 * primary ray that enters a box lies in its footprint (the box's corners'
 * projection widened by a pixel).  The same bins whatever the threads. */
#ifndef VX_BINS_H
#define VX_BINS_H

#include <stdint.h>
#include <string.h>

#include "vx_camera.h"
#include "vx_cellmask.h"
#include "vx_err.h"
#include "vx_grid.h"
#include "vx_macro.h"
#include "vx_macrobox.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#define VX_BIN 8                 /* a bin's edge in pixels: its pixels'
                                    bits are one word */

typedef struct vx_bins {
	int nbx, nby;            /* bins across and down */
	int block;               /* the block edge binned, or 0: whole
	                            level-1 macrocells */
	int64_t nboxes;          /* boxes binned (the bins' entries are
	                            more: a box is in each bin it covers) */
	int64_t nwhole;          /* of them whole level-1 macrocells */
	int64_t *off;            /* bin k's entries: off[k] .. off[k + 1]; NULL:
	                            no bins (more than a few boxes a pixel
	                            with whole macrocells too: the rays walk
	                            from the eye) */
	vx_cellbox *box;         /* the boxes, sorted by lb */
	uint32_t *list;          /* the entries: indices into box */
	double *lb;              /* per entry: its box's lb */
	uint64_t *mk;            /* per entry: the pixels of its bin its
	                            box's footprint holds, as pix */
	uint64_t *pix;           /* per bin: bit (y % VX_BIN) VX_BIN + x %
	                            VX_BIN set where a footprint holds pixel
	                            (x, y) */
	/* kept from one build to the next (the same view and macrocells):
	 * the bracketing level-1 macrocells and their whole boxes, placed
	 * (lb NaN: off the image) */
	int64_t nbr, *brk;
	vx_cellbox *mc;
} vx_bins;

void vx_bins_init(vx_bins *B);

/* vx_bins_build: B's bins for camera cam (resolved) over volume g with
 * hierarchy m (at least one level), for the values vals[0..nvals) (those
 * of mask, when mask is ready), blocks of block^3 leaves (1 ..
 * VX_CELLMASK_MAXROW + 1) where the mask's bits are built, on nthreads
 * threads (vx_par_threads).  Where the boxes or the bins' entries would
 * pass a few a pixel, whole macrocells are binned; where those would too,
 * none (B->off NULL).  The bracketing macrocells and their placed boxes are
 * kept in B for a later build of the same view (vx_bins_drop between the
 * two).  Returns 0, or VX_ENOMEM (B freed). */
int vx_bins_build(vx_bins *B, const vx_camera *cam, const vx_grid *g,
    const vx_macro *m, const float *vals, int nvals, vx_cellmask *mask,
    int block, int nthreads, vx_err *e);

/* vx_bins_drop: no bins (the lists freed, off NULL), what a later build of
 * the same view reuses kept.  vx_bins_free: nothing kept either (accepts
 * an initialized or NULL B). */
void vx_bins_drop(vx_bins *B);
void vx_bins_free(vx_bins *B);

/* vx_bins_row: the pixel bits of bin (bx, by) in its pixel row y (bit
 * x % VX_BIN set where a box's footprint holds pixel (x, y)) */
static inline unsigned
vx_bins_row(const vx_bins *B, int bx, int by, int y)
{
	return (unsigned)(B->pix[(int64_t)by * B->nbx + bx] >>
	    (y - by * VX_BIN) * VX_BIN) & ((1u << VX_BIN) - 1);
}

/* vx_bins_of: the bin of sample point (px, py) in *bin; returns its bit in
 * pix (0: no box's footprint holds the pixel) */
static inline int
vx_bins_of(const vx_bins *B, double px, double py, int64_t *bin)
{
	int bx = (int)px / VX_BIN, by = (int)py / VX_BIN;

	bx = bx < 0 ? 0 : bx >= B->nbx ? B->nbx - 1 : bx;
	by = by < 0 ? 0 : by >= B->nby ? B->nby - 1 : by;
	*bin = (int64_t)by * B->nbx + bx;
	return (int)(vx_bins_row(B, bx, by, (int)py) >> ((int)px -
	    bx * VX_BIN) & 1);
}

/* vx_bins_entry_masks: em[p], bit k set where the k-th entry of a bin's
 * list (of n <= 64 entries, pixel bits mk[0..n): B->mk from the bin's
 * first entry) holds pixel p: the 64 x n bit matrix transposed, 16
 * entries at a time where SSE2 has movemask (a byte of mk per row of the
 * bin; bit x of row y's byte is pixel y VX_BIN + x).  A ray of pixel p
 * then reads only its entries (vx_boxpick's em). */
static inline void
vx_bins_entry_masks(const uint64_t *mk, int64_t n,
    uint64_t em[VX_BIN * VX_BIN])
{
	memset(em, 0, VX_BIN * VX_BIN * sizeof *em);
#if defined(__SSE2__) && VX_BIN == 8
	for (int64_t k0 = 0; k0 < n; k0 += 16) {
		_Alignas(16) unsigned char t[VX_BIN][16];
		int nk = n - k0 < 16 ? (int)(n - k0) : 16;

		memset(t, 0, sizeof t);
		for (int k = 0; k < nk; k++)
			for (int y = 0; y < VX_BIN; y++)
				t[y][k] = (unsigned char)(mk[k0 + k] >>
				    VX_BIN * y);
		for (int y = 0; y < VX_BIN; y++) {
			__m128i v = _mm_load_si128((const __m128i *)(const void *)
			    t[y]);

			/* bit x of each byte to its top, for movemask (a
			 * 64-bit shift: what crosses into the next byte lands
			 * below its top) */
			for (int x = 0; x < VX_BIN; x++)
				em[y * VX_BIN + x] |= (uint64_t)(unsigned)
				    _mm_movemask_epi8(_mm_slli_epi64(v,
				    VX_BIN - 1 - x)) << k0;
		}
	}
#else
	for (int64_t k = 0; k < n; k++)
		for (uint64_t b = mk[k]; b != 0; b &= b - 1)
			em[__builtin_ctzll(b)] |= (uint64_t)1 << k;
#endif
}

#endif
