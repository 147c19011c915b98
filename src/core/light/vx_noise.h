/* vx_noise.h: deterministic 3D gradient noise and its fractal sums, for
 * perturbing volumes (Kniss et al. 2003, section 5: noise displacing the
 * data coordinates or modulating optical properties to add detail).
 *
 * Counter-based like the samplers of vx_rng.h: the gradient at lattice
 * point (i, j, k) is drawn from vx_rng_hash(seed, i, j, k), so a value is
 * a pure function of (seed, point) with no table and no state: the same
 * bits at any thread count and in any order of evaluation.  (It
 * lives in light/, beside vx_rng.h whose hash it uses; kernels/ is below
 * light/ and may not include it.)
 *
 * vx_noise3 is Perlin's improved gradient noise (2002): at each of the
 * eight corners of the lattice cell around p one of the twelve edge
 * directions (+-1, +-1, 0) (and permutations) is dotted with the offset
 * from the corner; the eight are blended with the quintic fade
 * 6t^5 - 15t^4 + 10t^3, so the field is C2.  It is 0 at lattice points,
 * has mean 0 (each gradient and its opposite are equally likely), and is
 * scaled by 2/3 so that |vx_noise3| <= 1 everywhere: at an offset t from
 * a cell's low corner each axis contributes at most
 * (1 - fade(t)) t + fade(t) (1 - t) <= 1/2 to the blended |g . d|
 * (|g . d| <= |dx| + |dy| + |dz| for an edge direction g), so the blend
 * is at most 3/2 before the scaling.  Non-finite coordinates give 0.
 * Points need |x|, |y|, |z| < 2^31 (lattice indices are 32-bit); beyond,
 * the lattice repeats. */
#ifndef VX_NOISE_H
#define VX_NOISE_H

#include <stdint.h>

#include "vx_err.h"

#define VX_NOISE_MAX_OCTAVES 24

/* vx_noise3: the noise at p, in [-1, 1]. */
double vx_noise3(uint64_t seed, const double p[3]);

/* vx_noise3_grad: the same value, and its gradient (exact derivative of
 * the blend) in grad[3]. */
double vx_noise3_grad(uint64_t seed, const double p[3], double grad[3]);

/* A fractal sum: octave o (0 .. octaves-1) is vx_noise3 at
 * frequency * lacunarity^o, weighted gain^o, seeded apart from the other
 * octaves and shifted by a seed-drawn offset (so that no point, the origin
 * included, is a lattice point of every octave). */
typedef struct vx_noise_fbm {
	uint64_t seed;
	int octaves;          /* 1 .. VX_NOISE_MAX_OCTAVES */
	double frequency;     /* of octave 0: lattice cells per world unit */
	double lacunarity;    /* frequency ratio between octaves, (0, 1000] */
	double gain;          /* amplitude ratio between octaves, (0, 1000] */
	/* private: the octaves' seeds and offsets drawn once by
	 * vx_noise_fbm_prepare (prepared: the seed they were drawn for + 1,
	 * 0 when not drawn) */
	uint64_t prepared;
	uint64_t oseed_[VX_NOISE_MAX_OCTAVES];
	double off_[VX_NOISE_MAX_OCTAVES][3];
} vx_noise_fbm;

/* vx_noise_fbm_init: seed 0, 4 octaves, frequency 1, lacunarity 2,
 * gain 1/2, not prepared. */
void vx_noise_fbm_init(vx_noise_fbm *f);

/* vx_noise_fbm_prepare: draw the octaves' seeds and offsets once, for
 * f's seed (all VX_NOISE_MAX_OCTAVES of them), so that evaluations skip
 * drawing them per point; a sum whose seed has changed since draws them
 * again.  The sums are the same bits prepared or not. */
void vx_noise_fbm_prepare(vx_noise_fbm *f);

/* vx_noise_fbm_check: VX_EUSAGE naming the knob when octaves, frequency
 * (> 0, finite), lacunarity or gain is out of range. */
int vx_noise_fbm_check(const vx_noise_fbm *f, vx_err *e);

/* vx_noise_fbm_eval: the weighted sum divided by the sum of the weights:
 * in [-1, 1], mean 0.  grad (may be NULL) gets its gradient. */
double vx_noise_fbm_eval(const vx_noise_fbm *f, const double p[3],
    double grad[3]);

/* vx_noise_turbulence: Perlin's turbulence, the same sum of |noise|
 * divided by the sum of the weights: in [0, 1]. */
double vx_noise_turbulence(const vx_noise_fbm *f, const double p[3]);

/* vx_noise_turbulence_grad: the same value, and in grad (may be NULL) its
 * gradient where it has one: each octave's |noise| contributes
 * sign(noise) times the noise's gradient (at a zero, the gradient
 * itself). */
double vx_noise_turbulence_grad(const vx_noise_fbm *f, const double p[3],
    double grad[3]);

#endif
