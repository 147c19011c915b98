/* rng.c: counter-based random numbers and scrambled Sobol points (see
 * vx_rng.h). */
#include "vx_rng.h"

/* The golden-ratio increment: consecutive inputs land far apart before
 * mixing, and a zero input does not stay zero. */
#define GAMMA 0x9e3779b97f4a7c15ULL
/* Domain separation of vx_rng_ld2's keys from vx_rng_uniform's numbers. */
#define LD_SALT 0x5851f42d4c957f2dULL

/* mix64: a bijection of 64-bit words with full avalanche (the finalizer of
 * SplitMix64, Stafford's "mix13" constants). */
static uint64_t
mix64(uint64_t z)
{
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	return z ^ (z >> 31);
}

uint64_t
vx_rng_hash(uint64_t seed, uint64_t stream, uint64_t index, uint32_t dim)
{
	uint64_t h;

	h = mix64(seed + GAMMA);
	h = mix64(h ^ (stream + 2 * GAMMA));
	h = mix64(h ^ (index + 3 * GAMMA));
	return mix64(h ^ ((uint64_t)dim + 4 * GAMMA));
}

double
vx_rng_uniform(uint64_t seed, uint64_t stream, uint64_t index, uint32_t dim)
{
	return (double)(vx_rng_hash(seed, stream, index, dim) >> 11) * 0x1p-53;
}

static uint32_t
reverse32(uint32_t x)
{
	x = (x >> 16) | (x << 16);
	x = ((x & 0xff00ff00u) >> 8) | ((x & 0x00ff00ffu) << 8);
	x = ((x & 0xf0f0f0f0u) >> 4) | ((x & 0x0f0f0f0fu) << 4);
	x = ((x & 0xccccccccu) >> 2) | ((x & 0x33333333u) << 2);
	return ((x & 0xaaaaaaaau) >> 1) | ((x & 0x55555555u) << 1);
}

/* lowmix: a bijection of 32-bit words whose output bit k is input bit k
 * xor a function of the key and of input bits 0..k-1 only (Laine and
 * Karras's observation): adding a constant, multiplying by an odd number,
 * and x ^= x * even all have that form, and so has their composition.  The
 * key enters as an addend and as an odd multiplier so that different keys
 * give unrelated permutations. */
static uint32_t
lowmix(uint32_t x, uint32_t key)
{
	x ^= x * 0x3a9c7d5eu;
	x += key;
	x *= (key >> 15) * 2u + 0x2f5b1a3du;	/* odd: 2n + odd */
	x ^= x * 0x9e6c63d0u;
	x += key ^ 0x7f4a7c15u;
	x ^= x * 0xa2d5b1c4u;
	return x;
}

uint32_t
vx_rng_owen32(uint32_t x, uint32_t key)
{
	/* reversed, the bits above a digit are the bits below it */
	return reverse32(lowmix(reverse32(x), key));
}

/* supersets: Sobol's second dimension of i with its bits reversed (bit j
 * holds digit j + 1).  That dimension is the xor of the direction numbers
 * v_k of i's set bits k, v_0 = 2^31, v_k = v_{k-1} ^ (v_{k-1} >> 1) (the
 * polynomial x + 1, all initial m_k = 1).  Digit j + 1 of v_k is
 * binomial(k, j) mod 2, which by Lucas's theorem is 1 exactly when the bits
 * of j are among those of k: digit j + 1 of the result is the xor of i's
 * bits k over the supersets k of j, a transform of five shifts (one per
 * bit of j) instead of a loop over i's bits. */
static uint32_t
supersets(uint32_t i)
{
	i ^= (i >> 1) & 0x55555555u;
	i ^= (i >> 2) & 0x33333333u;
	i ^= (i >> 4) & 0x0f0f0f0fu;
	i ^= (i >> 8) & 0x00ff00ffu;
	return i ^ ((i >> 16) & 0x0000ffffu);
}

void
vx_rng_sobol2(uint32_t i, uint32_t x[2])
{
	x[0] = reverse32(i);
	x[1] = reverse32(supersets(i));
}

void
vx_rng_ld2(uint64_t seed, uint64_t stream, uint64_t index, uint32_t dim,
    double u[2])
{
	uint64_t k = vx_rng_hash(seed ^ LD_SALT, stream, index >> 32, dim);
	uint64_t k2 = mix64(k + GAMMA);
	uint32_t i, x[2];
	uint64_t tail;

	/* shuffle the order: an Owen scramble of the index itself, each bit
	 * flipped by the bits above it, maps every aligned block of 2^k
	 * indices onto another aligned block, which is a net again */
	i = vx_rng_owen32((uint32_t)index, (uint32_t)k);
	/* vx_rng_owen32 of vx_rng_sobol2(i), the reversals that meet
	 * cancelled */
	x[0] = reverse32(lowmix(i, (uint32_t)(k >> 32)));
	x[1] = reverse32(lowmix(supersets(i), (uint32_t)k2));
	/* 21 random digits below the 32 of the net in each coordinate */
	tail = mix64((k2 >> 32 | k2 << 32) ^ (index * GAMMA));
	u[0] = (double)(((uint64_t)x[0] << 21) | (tail & 0x1fffff)) * 0x1p-53;
	u[1] = (double)(((uint64_t)x[1] << 21) | (tail >> 43)) * 0x1p-53;
}
