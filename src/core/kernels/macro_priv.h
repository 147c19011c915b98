/* macro_priv.h: what the hierarchy's modules (macro.c, macrowalk.c,
 * cellmask.c, macrobox.c, macroio.c) share and no one else uses: level
 * sizes, the walk's range test, whether a volume's cells are a
 * hierarchy's leaves, and a cell mask's bits as a walk asks for them.
 * Not installed. */
#ifndef MACRO_PRIV_H
#define MACRO_PRIV_H

#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "vx_cellmask.h"
#include "vx_grid.h"
#include "vx_macro.h"
#include "vx_par.h"

/* ncells: level l's cell count */
static inline size_t
ncells(const vx_macro *m, int l)
{
	return (size_t)m->dims[l][0] * (size_t)m->dims[l][1] *
	    (size_t)m->dims[l][2];
}

/* brackets: the walk's test, lo <= v <= hi for one of vals (every range
 * brackets an empty list) */
static inline int
brackets(float lo, float hi, const float *vals, int nvals)
{
	int k;

	if (nvals <= 0)
		return 1;
	if (nvals == 1)
		return lo <= vals[0] && vals[0] <= hi;
	for (k = 0; k < nvals; k++)
		if (lo <= vals[k] && vals[k] <= hi)
			return 1;
	return 0;
}

/* leaf_dims: the leaf grid of volume g, its cells (none at all when a
 * dimension has a single sample) */
static inline void
leaf_dims(const vx_grid *g, int64_t n[3])
{
	for (int a = 0; a < 3; a++)
		n[a] = g->dims[a] > 1 ? g->dims[a] - 1 : 0;
	if (n[0] == 0 || n[1] == 0 || n[2] == 0)
		n[0] = n[1] = n[2] = 0;
}

/* fits: 1 if g's cells are m's leaves */
static inline int
fits(const vx_macro *m, const vx_grid *g)
{
	int64_t n[3];

	leaf_dims(g, n);
	return n[0] == m->dims[0][0] && n[1] == m->dims[0][1] &&
	    n[2] == m->dims[0][2];
}

/* vx_macro_setup (macro.c): the geometry of every level over an n[0] x
 * n[1] x n[2] leaf grid with nlev levels of the given sizes, and one zeroed
 * allocation for the stored levels (level 0 too when leaf0); m is
 * initialized here.  Errors: VX_EDATA (sizes, dims), VX_ENOMEM. */
int vx_macro_setup(vx_macro *m, const int64_t n[3], int nlev,
    const int sizes[][3], int leaf0, vx_err *e);

/* vx_cellmask_block_bits (cellmask.c): the bits of level-1 macrocell b of
 * mask k (built over m, walked over g), built now from g's samples if no
 * one has (out of line: once per block); NULL when another thread is
 * building them */
const uint64_t *vx_cellmask_block_bits(vx_cellmask *k, const vx_macro *m,
    const vx_grid *g, int64_t b);

/* mask_get: the bits of level-1 macrocell b, built now if no one has; NULL
 * when b has none (it does not bracket) or another thread is building them
 * (the test for built bits inline, for the walk) */
static inline const uint64_t *
mask_get(vx_cellmask *k, const vx_macro *m, const vx_grid *g, int64_t b)
{
	int64_t s = k->slot[b];

	if (s < 0)
		return NULL;
	if (atomic_load_explicit(&k->state[b], memory_order_acquire) == 2)
		return k->bits + s;
	return vx_cellmask_block_bits(k, m, g, b);
}

/* mask_matches: vx_cellmask_matches, inline for the walks' entry points */
static inline int
mask_matches(const vx_cellmask *k, const vx_macro *m, const float *vals,
    int nvals)
{
	int i;

	if (k == NULL || !k->ready || k->m != m || m->nlev < 1 ||
	    k->nvals != nvals)
		return 0;
	/* bit for bit, as memcmp would (a NaN value matches itself), without
	 * its call on every ray */
	for (i = 0; i < nvals; i++) {
		uint32_t a, b;

		memcpy(&a, &k->vals[i], sizeof a);
		memcpy(&b, &vals[i], sizeof b);
		if (a != b)
			return 0;
	}
	return 1;
}

/* mask_walk: -1 when volume g does not fit m; else 0, with *k NULL when
 * the mask is not for m and these values (the walk then tests samples) */
static inline int
mask_walk(const vx_macro *m, const vx_grid *g, vx_cellmask **k,
    const float *vals, int nvals)
{
	/* a mask built over this very m and g has checked that g fits m */
	if (g != NULL && mask_matches(*k, m, vals, nvals) && (*k)->g == g)
		return 0;
	if (g == NULL || !fits(m, g))
		return -1;
	if (!mask_matches(*k, m, vals, nvals))
		*k = NULL;
	return 0;
}

#endif
