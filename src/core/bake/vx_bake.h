/* vx_bake.h: baking an irradiance volume (Wyman et al. 2006, §4.1.1): for
 * each wanted texel t of the lattice (vx_irrvol.h), the value rho(x_t) of
 * the volume at the texel's point, the outward normal n_t (minus the
 * gradient smoothed by the cubic B-spline over 4x4x4 samples, vx_smooth.h),
 * the start point x_t + offset n_t, and samples of the irradiance estimator
 * (vx_gi.h) on the isosurface of value rho(x_t).
 *
 * A texel's samples are a pure function of (the settings, the texel's
 * index, the sample index): baking samples [a, b) and then [b, c) gives
 * the accumulators of [a, c) bit for bit, at any thread count, in any
 * order of texels, and a lazily baked texel equals the full bake's.
 *
 * Texels without a usable surface get a flag and no samples:
 *   VX_TEXEL_NAN   the texel's value or a sample of its support (vx_smooth.h) is
 *                  not finite;
 *   VX_TEXEL_FLAT  the smoothed gradient's length is at most 2^-30 times
 *                  the volume's value range (or 0): no direction to
 *                  light from;
 *   VX_TEXEL_BORDER (informative) its support reached past the volume's
 *                  edge, where the edge samples were repeated.
 * Renderers skip NAN and FLAT texels when they interpolate. */
#ifndef VX_BAKE_H
#define VX_BAKE_H

#include <stdint.h>

#include "vx_gi.h"
#include "vx_grid.h"
#include "vx_irrvol.h"
#include "vx_macro.h"

#define VX_BAKE_MAX_BANDS 16

typedef void (*vx_bake_progress_fn)(void *ctx, uint64_t done,
    uint64_t total);

typedef struct vx_bake_opts {
	double scale;             /* lattice scale per axis (1: the samples) */
	double offset;            /* start offset along the normal, in voxels */
	uint32_t samples;         /* samples per texel this run (with a
	                             target: the most a texel may reach) */
	double target;            /* > 0: sample in rounds until the relative
	                             standard error of the texel's mean
	                             luminance is at most this */
	uint32_t round;           /* samples per round with a target */
	uint32_t min_samples;     /* with a target: at least this many */
	int all;                  /* 1: every texel; 0: the bands' */
	int nband;
	double band[VX_BAKE_MAX_BANDS][2];   /* value intervals [lo, hi] */
	int topup;                /* 1: bring each texel to `samples` in all
	                             (lazy texels) instead of adding
	                             `samples` more (resumed bakes) */
	const uint8_t *only;      /* NULL, or one byte a texel of the lattice
	                             (i + n0 (j + n1 k)): bake only the wanted
	                             texels whose byte is nonzero */
	uint64_t max_bytes;       /* > 0: the plan refuses (VX_ENOMEM, before
	                             allocating) a bake that would take more
	                             bytes of memory (see vx_bake_plan) */
	uint64_t held_bytes;      /* memory the caller holds besides (its
	                             input stream), counted against it */
	int threads;              /* 0: OpenMP's default */
	vx_bake_progress_fn progress;        /* called from one thread */
	void *progress_ctx;
} vx_bake_opts;

void vx_bake_opts_init(vx_bake_opts *o);

typedef struct vx_bake_stats {
	uint64_t lattice;         /* texels of the lattice */
	uint64_t wanted;          /* texels the bands ask for */
	uint64_t baked;           /* texels that got samples this run */
	uint64_t flat, nan, border;
	uint64_t samples;         /* samples taken this run */
	uint64_t bricks;          /* bricks stored */
	uint64_t need_bytes;      /* the plan's peak memory: the texels'
	                             storage (bricks it stores, existing ones
	                             included), the chunk made of them (its
	                             body and its payload: twice the stream's
	                             bytes), and o->held_bytes */
	vx_gi_stats gi;
	double plan_s, bake_s;    /* wall seconds */
} vx_bake_stats;

/* vx_bake_plan: mark the texels of v (set up for g with vx_irr_setup)
 * that the options ask for: all, or those at a corner of a lattice cell
 * whose volume samples' [min, max] meets a band; their bricks are
 * allocated.  Counts wanted texels into st.  The memory the bake will
 * take at its peak is counted first (st->need_bytes: the bricks' storage,
 * the chunk written from them, what the caller holds); above o->max_bytes
 * the plan stops there with VX_ENOMEM and allocates nothing. */
int vx_bake_plan(vx_irrvol *v, const vx_grid *g, const vx_bake_opts *o,
    vx_bake_stats *st, vx_err *e);

/* vx_bake_texel_setup: texel (i,j,k)'s value, start point (index space)
 * and unit world normal toward the lit side (high: that of higher values,
 * vx_gi.high); returns its VX_TEXEL_* flags (NAN or FLAT: nothing to
 * bake). */
uint32_t vx_bake_texel_setup(const vx_irrvol *v, const vx_grid *g,
    double offset, int high, int64_t i, int64_t j, int64_t k, double *rho,
    double start[3], double n[3]);

/* vx_bake_texel: add samples to texel (i,j,k)'s accumulators a (whose
 * count says how many it has: it continues at v->first + a->count) as the
 * options say (a fixed count, or rounds up to a target); the pure function
 * behind bakes, resumes and lazy texels. */
void vx_bake_texel(const vx_irrvol *v, const vx_gi *gi, const vx_grid *g,
    const vx_bake_opts *o, int64_t i, int64_t j, int64_t k, vx_irr_acc *a,
    vx_gi_stats *st);

/* vx_bake_run: vx_bake_texel for every wanted texel of v, in parallel;
 * then vx_irr_finish.  Stats added to st. */
int vx_bake_run(vx_irrvol *v, const vx_gi *gi, const vx_grid *g,
    const vx_bake_opts *o, vx_bake_stats *st, vx_err *e);

/* vx_bake_settings: the settings text of a bake of v's lattice with gi and
 * o: everything that determines a sample's value (scale, offset, seed,
 * bounces, ray offset, solver, fixed point, lit side, lights, albedo), as
 * one line (formats/irradiance.md, key `settings`). */
void vx_bake_settings(const vx_irrvol *v, const vx_gi *gi,
    const vx_bake_opts *o, char *buf, size_t n);

/* vx_bake_key: the 16-hex-digit key of a bake: FNV-1a 64 of the settings
 * text, into key[17]. */
void vx_bake_key(const char *settings, char key[17]);

/* vx_bake_sign: set v's settings, key, offset, seed and side from gi and
 * o (a new bake). */
void vx_bake_sign(vx_irrvol *v, const vx_gi *gi, const vx_bake_opts *o);

#endif
