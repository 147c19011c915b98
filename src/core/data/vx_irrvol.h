/* vx_irrvol.h: the irradiance volume of Wyman et al. 2006: RGB irradiance
 * on a lattice of texels laid over a volume's index space, for the
 * isosurface through each texel, and its stream chunk IRRV
 * (formats/irradiance.md is the spec).
 *
 * Lattice.  Texel (i,j,k) sits at index-space point (i*step[0], j*step[1],
 * k*step[2]) of the volume it belongs to; step[a] = (vdims[a]-1) /
 * (dims[a]-1) so the first and last texels sit on the volume's first and
 * last samples (an axis of one texel, or a volume axis of one sample, has
 * step 1 and its texel at 0).  vx_irr_lattice() gives the dims for a scale
 * S: dims = round((vdims-1) * S) + 1 per axis, at least 2 where vdims > 1.
 * At S = 1 the texels are the samples.
 *
 * Storage.  Texels are grouped in bricks of VX_IRR_BRICK^3; only bricks
 * holding a texel that was asked for are stored (a band of isovalues needs
 * few).  Each stored texel keeps exact accumulators: the sample count, the
 * sum of the per-sample RGB estimates and the sum of the squares of their
 * luminance, in fixed point (integers: 2^-fixed units), so adding samples
 * in any grouping (threads, resumed bakes, merged bakes) gives the same
 * bits.  A final bake may drop them and keep only the mean irradiance as
 * binary32 or binary16 (VX_IRR_F32, VX_IRR_F16); such a bake can be drawn
 * but not resumed or merged.
 *
 * Rendering reads the mean E (W/m^2-like linear units: the integral of
 * incident radiance times cosine) of every usable texel: baked (count > 0,
 * or final), and not flagged FLAT or NAN.  Interpolation ignores unusable
 * and absent texels and renormalizes the weights of the others. */
#ifndef VX_IRRVOL_H
#define VX_IRRVOL_H

#include <stddef.h>
#include <stdint.h>

#include "vx_enum.h"
#include "vx_err.h"
#include "vx_grid.h"
#include "vx_stream.h"

#define VX_IRR_BRICK       8                 /* texels per brick edge */
#define VX_IRR_BRICK3      (VX_IRR_BRICK * VX_IRR_BRICK * VX_IRR_BRICK)
#define VX_IRR_MAX_TEXELS  ((uint64_t)1 << 34)
#define VX_IRR_FIXED       24                /* default fraction bits */
#define VX_IRR_NAME        64

/* per-texel flags */
enum {
	VX_TEXEL_FLAT     = 1u << 0,   /* the smoothed gradient vanishes: no
	                                  surface direction; not baked */
	VX_TEXEL_NAN      = 1u << 1,   /* a non-finite sample in its support;
	                                  not baked */
	VX_TEXEL_BORDER   = 1u << 2,   /* its support reached past the
	                                  volume's edge (samples clamped) */
	VX_TEXEL_OVERFLOW = 1u << 3,   /* an accumulator saturated, or an f16
	                                  mean was kept as +-65504: the mean
	                                  is a lower bound of its magnitude
	                                  (use fewer samples or fewer
	                                  fixed-point bits; f32) */
	VX_TEXEL_WANTED   = 1u << 4,   /* asked for by the bake's band */
	VX_TEXEL_SAMPLED  = 1u << 31   /* in memory only (flags[], never
	                                  stored): the accumulators hold
	                                  samples (set by vx_irr_finish), so a
	                                  lookup reads no accumulator */
};

typedef enum vx_irr_store {
	VX_IRR_ACCUM = 0,              /* exact accumulators (resumable) */
	VX_IRR_F32,                    /* final: mean RGB as binary32 */
	VX_IRR_F16,                    /* final: mean RGB as binary16 */
	VX_IRR_STORE_LAST
} vx_irr_store;

/* One texel's accumulators: 24 bytes and ncomp sums (48 bytes for an
 * irradiance volume).  Records lie vx_irr_acc_bytes(ncomp) apart: use
 * vx_irr_accp, never index an array of vx_irr_acc. */
typedef struct vx_irr_acc {
	uint32_t count;                /* samples taken */
	uint32_t flags;                /* VX_TEXEL_* */
	uint64_t sq[2];                /* sum of squared luminance estimates,
	                                  2^-2fixed units, 128 bits (lo, hi) */
	int64_t sum[];                 /* per component: sum of the
	                                  estimates, 2^-fixed units */
} vx_irr_acc;

#define VX_IRR_MAX_COMP  (3 * 16 * 16)   /* RGB SH of order 16 */

static inline size_t
vx_irr_acc_bytes(int ncomp)
{
	return sizeof(vx_irr_acc) + (size_t)ncomp * sizeof(int64_t);
}

typedef struct vx_irrvol {
	/* the volume it belongs to */
	char volume[VX_IRR_NAME];
	int64_t vdims[3];
	uint32_t vcrc;                 /* vx_macro_grid_crc of its samples */
	/* the lattice */
	int64_t dims[3];               /* texels per axis */
	double step[3];                /* index-space distance between texels */
	double scale;                  /* the scale the dims came from */
	int64_t bdims[3];              /* bricks per axis */
	uint32_t *slot;                /* per brick: 0 absent, else 1 + index of
	                                  its storage */
	size_t nslot;                  /* bricks stored */
	size_t cap;                    /* bricks the storage has room for */
	vx_irr_store store;
	/* what a texel holds: irradiance (sh_order 0: RGB, ncomp 3), or the
	 * SH transfer vector of order sh_order (n^2 coefficients a channel,
	 * channels 1 or 3, channel k's coefficient i at k n^2 + i; the SHTV
	 * chunk; values may be negative) */
	int sh_order;
	int channels;
	int ncomp;                     /* values a texel: 3, or channels n^2 */
	int fixed;                     /* fraction bits of the accumulators */
	uint32_t first;                /* the first sample index of this bake's
	                                  range (each texel: [first, first+count)) */
	/* storage, nslot * VX_IRR_BRICK3 texels, brick by brick, x fastest
	 * inside a brick: acc for VX_IRR_ACCUM; mean (3 floats a texel) and
	 * flags for every store (mean derived from acc by vx_irr_finish);
	 * mean holds ncomp floats a texel */
	unsigned char *acc;            /* records of vx_irr_acc_bytes(ncomp) */
	float *mean;
	uint32_t *flags;
	/* how it was baked: text kept verbatim (formats/irradiance.md);
	 * key is the 16-hex-digit hash of every setting that determines a
	 * sample's value: bakes merge only when their keys are equal */
	char key[17];
	char settings[2048];
	/* the bake's knobs a lazy renderer needs to bake more texels alike
	 * (header keys offset, seed, side, samples) */
	double offset;
	uint64_t seed;
	int high;
	uint32_t samples;              /* the samples the bake asked of each
	                                  wanted texel (with a target: the
	                                  most); a lazy renderer brings new
	                                  texels to it */
} vx_irrvol;

void vx_irr_init(vx_irrvol *v);
void vx_irr_free(vx_irrvol *v);

/* vx_irr_lattice: texel dims for volume dims vdims at scale s (> 0). */
int vx_irr_lattice(const int64_t vdims[3], double s, int64_t dims[3],
    vx_err *e);

/* vx_irr_setup: set v's lattice for volume g (its name, dims; crc given)
 * at scale s with no brick stored yet. */
int vx_irr_setup(vx_irrvol *v, const vx_grid *g, uint32_t vcrc, double s,
    vx_irr_store store, vx_err *e);

/* vx_irr_setup_sh: vx_irr_setup for an SH transfer volume of order n
 * (1..VX_SHLIGHT_MAX_ORDER, 16) with 1 or 3 channels. */
int vx_irr_setup_sh(vx_irrvol *v, const vx_grid *g, uint32_t vcrc, double s,
    vx_irr_store store, int order, int channels, vx_err *e);

/* vx_irr_accp: the accumulators of storage index s (ACCUM store). */
static inline vx_irr_acc *
vx_irr_accp(const vx_irrvol *v, int64_t s)
{
	return (vx_irr_acc *)(void *)(v->acc + (size_t)s *
	    vx_irr_acc_bytes(v->ncomp));
}

/* vx_irr_want_brick: make brick b (index into bdims) stored, texels zeroed
 * (count 0, flags 0).  Idempotent.  Not thread-safe: allocate every brick
 * before a parallel bake. */
int vx_irr_want_brick(vx_irrvol *v, size_t b, vx_err *e);
/* vx_irr_want_texel: store texel (i,j,k)'s brick (vx_irr_want_brick) and
 * mark the texel VX_TEXEL_WANTED; returns its storage index, or -1 with e
 * set (VX_ENOMEM; VX_EINTERNAL outside the lattice). */
int64_t vx_irr_want_texel(vx_irrvol *v, int64_t i, int64_t j, int64_t k,
    vx_err *e);
/* vx_irr_reserve: grow the storage for at least n bricks at once (saves
 * reallocations); optional. */
int vx_irr_reserve(vx_irrvol *v, size_t n, vx_err *e);

/* vx_irr_texel: storage index of texel (i,j,k) or -1 when its brick is
 * absent or (i,j,k) outside the lattice. */
static inline int64_t
vx_irr_texel(const vx_irrvol *v, int64_t i, int64_t j, int64_t k)
{
	int64_t b;
	uint32_t s;

	if (i < 0 || j < 0 || k < 0 || i >= v->dims[0] || j >= v->dims[1] ||
	    k >= v->dims[2])
		return -1;
	b = i / VX_IRR_BRICK + v->bdims[0] * (j / VX_IRR_BRICK + v->bdims[1] *
	    (k / VX_IRR_BRICK));
	if ((s = v->slot[b]) == 0)
		return -1;
	return (int64_t)(s - 1) * VX_IRR_BRICK3 + i % VX_IRR_BRICK +
	    VX_IRR_BRICK * (j % VX_IRR_BRICK + VX_IRR_BRICK * (k % VX_IRR_BRICK));
}

/* vx_irr_texel_point: the texel's index-space point. */
void vx_irr_texel_point(const vx_irrvol *v, int64_t i, int64_t j, int64_t k,
    double p[3]);

/* ---- accumulating ---- */

/* vx_irr_acc_add: add one sample's estimate val[0..ncomp-1] to a, in v's
 * fixed point, saturating (and flagging) on overflow.  Irradiance: values
 * that are not finite or negative are taken as 0; SH: values are signed,
 * a NaN is taken as 0.  The squared sum is of the sample's luminance:
 * irradiance, Rec. 709 weights of its RGB; SH, of its channels' first
 * (constant) coefficient. */
void vx_irr_acc_add(const vx_irrvol *v, vx_irr_acc *a, const double *val);
/* vx_irr_acc_merge: a += b (counts, sums, squares; flags ORed). */
void vx_irr_acc_merge(const vx_irrvol *v, vx_irr_acc *a, const vx_irr_acc *b);
/* vx_irr_acc_mean: the mean of each component (0 without samples);
 * vx_irr_acc_relerr: the standard error of the mean luminance divided by
 * the mean luminance (0 for fewer than 2 samples or a mean luminance that
 * is not positive: callers check count). */
void vx_irr_acc_mean(const vx_irrvol *v, const vx_irr_acc *a, double *out);
double vx_irr_acc_relerr(const vx_irrvol *v, const vx_irr_acc *a);

/* vx_irr_finish: derive mean[] and flags[] (VX_TEXEL_SAMPLED included)
 * from the accumulators (ACCUM store); a no-op for final stores. */
void vx_irr_finish(vx_irrvol *v);

/* vx_irr_settle: give texel s of a final store what vx_irr_finalize
 * would keep of accumulators a: the mean (rounded through binary16 for
 * F16, saturating at +-65504 with VX_TEXEL_OVERFLOW) and the flags (the
 * wanted bit only when a holds samples). */
void vx_irr_settle(vx_irrvol *v, int64_t s, const vx_irr_acc *a);

/* vx_irr_usable: 1 if storage index s holds an irradiance to draw. */
static inline int
vx_irr_usable(const vx_irrvol *v, int64_t s)
{
	uint32_t f = v->flags[s];

	if (f & (VX_TEXEL_FLAT | VX_TEXEL_NAN))
		return 0;
	/* a final store keeps the wanted bit only on texels that were baked
	 * (vx_irr_finalize) */
	return (f & (v->store != VX_IRR_ACCUM ? VX_TEXEL_WANTED :
	    VX_TEXEL_SAMPLED)) != 0;
}

/* ---- lookup ---- */

/* vx_irr_lookup: the texel value (ncomp components: RGB irradiance, or
 * the transfer vector) at index-space point p (of the volume) by
 * interpolation mode m (VX_INTERP_UNKNOWN: trilinear); for NEAREST_ISO, g is the volume (its trilinear
 * value at each texel is the texel's isovalue) and iso the hit's isovalue.
 * Returns 1 with out[0..ncomp-1] set, or 0 when no usable texel is in
 * reach (out 0). */
int vx_irr_lookup(const vx_irrvol *v, const double p[3], vx_interp m,
    const vx_grid *g, double iso, double *out);
/* vx_irr_weights: the texels a lookup combines and their weights (summing
 * to 1): at most 64; returns how many (0: none usable). */
int vx_irr_weights(const vx_irrvol *v, const double p[3], vx_interp m,
    const vx_grid *g, double iso, int64_t idx[64], double w[64]);
/* vx_irr_reach: call fn for every texel the lookup at p by mode m reads
 * (inside the lattice; present or not): what lazy illumination must have
 * baked before the lookup. */
typedef void (*vx_irr_need_fn)(void *ctx, int64_t i, int64_t j, int64_t k);
void vx_irr_reach(const vx_irrvol *v, const double p[3], vx_interp m,
    vx_irr_need_fn fn, void *ctx);

/* ---- merging ---- */

/* vx_irr_merge: add b's samples into a: the same volume, lattice, key and
 * store VX_IRR_ACCUM; for every texel that both hold samples for, b's
 * range must start where a's ends (a.first + a.count == b.first), unless
 * both hold the very same samples (bakes of overlapping texel ranges: kept
 * once); a texel only b holds is taken as it is.  Bricks of b absent from a are
 * added.  Errors name the first mismatch (VX_EDATA). */
int vx_irr_merge(vx_irrvol *a, const vx_irrvol *b, vx_err *e);

/* vx_irr_finalize: convert to a final store (F32 or F16): means kept
 * (F16: as vx_irr_settle rounds them), accumulators dropped. */
int vx_irr_finalize(vx_irrvol *v, vx_irr_store store, vx_err *e);

/* ---- the IRRV and SHTV chunks ----
 * An irradiance volume is written as IRRV, an SH transfer volume as SHTV
 * (the same layout with keys order and channels: formats/irradiance.md).
 * vx_irr_from_chunk reads either. */
int vx_irr_to_chunk(const vx_irrvol *v, int zlevel, vx_chunk *c, vx_err *e);
int vx_irr_from_chunk(vx_irrvol *v, const vx_chunk *c, vx_err *e);
/* vx_irr_from_stream: the IRRV chunk for volume `volume` (NULL: the first);
 * *index gets its position or -1 when there is none (then 0 is returned
 * and v stays empty). */
int vx_irr_from_stream(vx_irrvol *v, const vx_stream *s, const char *volume,
    long *index, vx_err *e);
/* vx_irr_sh_from_stream: the same for the SHTV chunk. */
int vx_irr_sh_from_stream(vx_irrvol *v, const vx_stream *s,
    const char *volume, long *index, vx_err *e);

/* sizes: bytes per stored texel for a store and ncomp components (in the
 * chunk; in memory a final store keeps 4 bytes a component and its flags),
 * and the whole volume's in memory */
size_t vx_irr_texel_bytes(vx_irr_store s, int ncomp);
size_t vx_irr_texel_memory(vx_irr_store s, int ncomp);
size_t vx_irr_bytes(const vx_irrvol *v);

/* The names (vx_enum.h) of the stores: "accum", "f32", "f16"; -1 and "?"
 * for the others. */
extern const vx_enum vx_irr_store_enum;

#endif
