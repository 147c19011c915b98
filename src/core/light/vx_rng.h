/* vx_rng.h: counter-based random numbers and low-discrepancy points.
 *
 * Every number is a pure function of (seed, stream, index, dim): there is no
 * generator state, so a result never depends on threads, processes or the
 * order of work, and sample `index` of stream `stream` can be drawn alone
 * (resumed bakes, lazy texels and merged partial bakes rely on it).
 *   seed    the run's seed (a command-line option; 0 is a fine seed)
 *   stream  what is being sampled: a texel, a pixel
 *   index   the sample number within the stream
 *   dim     which dimension of that sample (its first bounce's direction,
 *           its light choice, ...); callers number their dimensions
 * Only 64-bit integer arithmetic is used: the same bits on every platform.
 *
 * vx_rng_uniform and vx_rng_ld2 use separate hash domains: uniform(.., d) and
 * ld2(.., d) are independent for every d. */
#ifndef VX_RNG_H
#define VX_RNG_H

#include <stdint.h>

/* vx_rng_hash: 64 well-mixed bits of (seed, stream, index, dim): four
 * rounds of a bijective 64-bit finalizer (multiply, xor-shift), one per
 * argument.  Changing any one argument changes each output bit with
 * probability 1/2. */
uint64_t vx_rng_hash(uint64_t seed, uint64_t stream, uint64_t index,
    uint32_t dim);

/* vx_rng_uniform: a uniform number in [0, 1) with 53 random bits (a
 * multiple of 2^-53), the top bits of vx_rng_hash. */
double vx_rng_uniform(uint64_t seed, uint64_t stream, uint64_t index,
    uint32_t dim);

/* vx_rng_ld2: point `index` of a low-discrepancy sequence in [0,1)^2 for the
 * pair of dimensions `dim` of this stream: the first two dimensions of
 * Sobol's sequence (a (0,2)-sequence in base 2), Owen-scrambled per
 * coordinate and shuffled in order, both by hashing (Burley 2020's
 * construction: each digit is flipped by a hash of the digits above it), with
 * keys drawn from (seed, stream, dim, index >> 32).
 *
 * Contract:
 *  - for every k and every c, the points with index in [c 2^k, (c+1) 2^k)
 *    (in particular the first 2^k) form a (0,k,2)-net: every elementary box
 *    [i 2^-a, (i+1) 2^-a) x [j 2^-b, (j+1) 2^-b) with a + b = k holds exactly
 *    one point;
 *  - each point is uniformly distributed over [0,1)^2 (the scramble is a
 *    random digit permutation), so estimates are unbiased, and different
 *    streams, dims or seeds are scrambled independently and do not correlate;
 *  - the top 32 bits of each coordinate carry the net, the next 21 are
 *    random (the scramble's tail), so u is a multiple of 2^-53 in [0, 1);
 *  - the sequence has 2^32 points; index >> 32 selects another scramble,
 *    so larger indices stay deterministic but no longer stratify with the
 *    first 2^32.
 * Smooth integrands converge at about N^-1.5 in RMS error (N a power of
 * two), against N^-0.5 for vx_rng_uniform. */
void vx_rng_ld2(uint64_t seed, uint64_t stream, uint64_t index, uint32_t dim,
    double u[2]);

/* vx_rng_owen32: x with each bit, from the top, flipped by a hash of `key`
 * and the bits above it (a hash-based Owen scramble of the binary fraction
 * x / 2^32).  A bijection of 32-bit words that maps every dyadic interval
 * [i 2^-k, (i+1) 2^-k) onto one of the same length. */
uint32_t vx_rng_owen32(uint32_t x, uint32_t key);

/* vx_rng_sobol2: the two coordinates (as 32-bit fractions) of point i of the
 * unscrambled Sobol sequence: x[0] the van der Corput radical inverse of i,
 * x[1] Sobol's second dimension (direction numbers of the polynomial
 * x + 1). */
void vx_rng_sobol2(uint32_t i, uint32_t x[2]);

#endif
