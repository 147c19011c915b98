/* cellmask.c: cell masks, a bit per leaf of the bracketing level-1
 * macrocells for a list of values, and their build: a block's samples a
 * row at a time, with SSE2 kernels per sample type and layout where the
 * platform has them (vx_cellmask.h). */
#include "vx_cellmask.h"

#include <float.h>
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "macro_priv.h"

/* SSE2 where the platform has it: the cell mask's build (MASK_SIMD) */
#if defined(__SSE2__)
#include <emmintrin.h>
#define MASK_SIMD 1
#endif

/* ---- cell masks ----
 * A level-1 macrocell's samples are read once each, a row of samples along
 * x at a time, into two bit masks per value v: below (bit x set when sample
 * x is finite and <= v) and above (finite and >= v).  A leaf brackets v by
 * the walk's test (lo <= v <= hi, lo and hi the least and greatest finite
 * corner) exactly when one of its 8 corners is below and one above: integer
 * samples are exact in float, and the walk's integer test (min <= floor(v),
 * max >= ceil(v)) says the same; NaN v brackets nothing either way.  A
 * leaf row's corners are samples x and x + 1 of four sample rows (two in
 * each of two planes), so its bits are (B | B >> 1) OR-ed over the four
 * rows, the same for A, then B & A.  Rows of up to VX_CELLMASK_MAXROW
 * leaves (one word).
 *
 * Blocks are built lazily, by the first walk that enters one: its state
 * goes 0 (not built) -> 1 (being built, by the thread that won the
 * compare-and-swap) -> 2 (built, bits published with release order).  A
 * walk that finds a block being built by another thread tests samples
 * there instead: the same decisions, so the result never depends on which
 * thread built what. */

/* Where SSE2 is there (every x86-64), a block whose rows' x offsets let it
 * (a linear layout, bricks 16 bytes wide or more; u8 and u16/i16 bricks 4
 * samples wide: every type's default bricks) tests a row W samples at a
 * time (f32 8, the others 16), in chunks of W samples from the row's
 * start, each chunk a few loads (runs of 16, 8 or 4 bytes adjacent in
 * memory: the plan is made once per block, the x offsets being the same
 * for every row) and one compare per test and 16 bytes; one function per
 * type and runs reads the block's planes (block_for).  u8 (u16, i16) in
 * bricks 4 samples wide reads four (two) rows at once, 16 bytes holding a
 * run of each (tile_rows, tile16_rows).  Integer tests are exact in the
 * type's own width: u8 v <= fl as min(v, fl) == v and v >= ce as
 * max(v, ce) == v; u16 and i16 as not v > fl and not ce > v (u16 made
 * signed by flipping its top bit), fl and ce clamped into the type's range
 * (a value that no sample can be below, or none above, brackets nothing
 * and was skipped before).  Floats: the same finiteness test as one at a
 * time.  The row's last samples after the chunks are read as a chunk
 * where they are adjacent and 16 or 32 bytes from them lie within the
 * volume's samples (the bits past the row are never used), else one at a
 * time.  Other blocks test four samples adjacent in memory at once where
 * they are (integers widened to 32 bits, where v <= fl and v >= ce as
 * v > ce - 1 are exact), else one at a time (MASK_ROWS).  The bits are
 * the same every way. */

/* leaf_rows: a plane of leaves' bits into out, n rows of nx leaves from
 * bit p, step bits apart: a leaf row's corners are samples x and x + 1 of
 * rows y and y + 1 of two planes of samples, whose rows' bits, OR-ed over
 * the two planes, are ub (below) and ua (above).  Two rows at a time where
 * SSE2 is there (four put as one word where they are 16 bits apart from a
 * word's start); rows that never straddle two words (step divides 64) put
 * without the test. */
static void
leaf_rows(uint64_t *restrict out, const uint64_t *ub, const uint64_t *ua,
    int64_t n, int64_t p, int64_t step, int nx)
{
	const uint64_t keep = nx >= 64 ? ~(uint64_t)0 :
	    ((uint64_t)1 << nx) - 1;
	const int one = 64 % step == 0 && nx <= step;
	uint64_t v[2];
	int64_t y = 0;
	int i;

#ifdef MASK_SIMD
	const __m128i kp = _mm_set1_epi64x((long long)keep);

	/* rows 16 bits apart from a word's start (u8, u16, i16 macrocells 16
	 * leaves wide): four rows a word */
	if (step == 16 && nx <= 16 && (p & 63) == 0)
		for (; y + 4 <= n; y += 4, p += 64) {
			uint64_t w[4];

			for (i = 0; i < 4; i += 2) {
				__m128i bb = _mm_or_si128(_mm_loadu_si128(
				    (const __m128i *)(const void *)(ub + y + i)),
				    _mm_loadu_si128((const __m128i *)(const
				    void *)(ub + y + i + 1)));
				__m128i aa = _mm_or_si128(_mm_loadu_si128(
				    (const __m128i *)(const void *)(ua + y + i)),
				    _mm_loadu_si128((const __m128i *)(const
				    void *)(ua + y + i + 1)));

				bb = _mm_or_si128(bb, _mm_srli_epi64(bb, 1));
				aa = _mm_or_si128(aa, _mm_srli_epi64(aa, 1));
				_mm_storeu_si128((__m128i *)(void *)(w + i),
				    _mm_and_si128(_mm_and_si128(bb, aa), kp));
			}
			out[p >> 6] |= w[0] | w[1] << 16 | w[2] << 32 |
			    w[3] << 48;
		}
	for (; y + 2 <= n; y += 2) {
		__m128i bb = _mm_or_si128(_mm_loadu_si128((const __m128i *)
		    (const void *)(ub + y)), _mm_loadu_si128((const __m128i *)
		    (const void *)(ub + y + 1)));
		__m128i aa = _mm_or_si128(_mm_loadu_si128((const __m128i *)
		    (const void *)(ua + y)), _mm_loadu_si128((const __m128i *)
		    (const void *)(ua + y + 1)));

		bb = _mm_or_si128(bb, _mm_srli_epi64(bb, 1));
		aa = _mm_or_si128(aa, _mm_srli_epi64(aa, 1));
		_mm_storeu_si128((__m128i *)(void *)v, _mm_and_si128(
		    _mm_and_si128(bb, aa), kp));
		for (i = 0; i < 2; i++, p += step) {
			int sh = (int)(p & 63);

			out[p >> 6] |= v[i] << sh;
			if (!one && sh + nx > 64)
				out[(p >> 6) + 1] |= v[i] >> (64 - sh);
		}
	}
#endif
	for (; y < n; y++, p += step) {
		uint64_t bb = ub[y] | ub[y + 1];
		uint64_t aa = ua[y] | ua[y + 1];
		int sh = (int)(p & 63);

		v[0] = (bb | bb >> 1) & (aa | aa >> 1) & keep;
		out[p >> 6] |= v[0] << sh;
		if (sh + nx > 64)
			out[(p >> 6) + 1] |= v[0] >> (64 - sh);
	}
	(void)one;
	(void)i;
}

/* row_planes: row y's bits of plane z (bb below, aa above) OR-ed with
 * the previous plane's row into ub, ua (a leaf row's corners lie on both
 * planes), and kept in pb, pa for the next plane */
static inline void
row_planes(uint64_t *ub, uint64_t *ua, uint64_t *pb, uint64_t *pa, int64_t y,
    uint64_t bb, uint64_t aa)
{
	ub[y] = pb[y] | bb;
	ua[y] = pa[y] | aa;
	pb[y] = bb;
	pa[y] = aa;
}

#ifdef MASK_SIMD
typedef struct quad_k {
	__m128i fl, cm1;          /* integer thresholds: fl, ce - 1 */
	__m128 val, fmax, abs;    /* f32: the value, FLT_MAX, ~sign */
	__m128i f8, c8;           /* u8: fl, ce (each in 0..255) */
	__m128i f16, c16;         /* u16 (biased), i16: fl, ce in 16 bits */
} quad_k;

static inline void
quad_keys(quad_k *k, vx_type t, int64_t fl, int64_t ce, float val)
{
	/* integer samples lie within 16 bits: clamping far outside keeps
	 * every answer */
	int64_t f = fl < -0x40000000 ? -0x40000000 : fl > 0x40000000 ?
	    0x40000000 : fl;
	int64_t c = ce < -0x40000000 ? -0x40000000 : ce > 0x40000000 ?
	    0x40000000 : ce;
	/* the type's range (fl below it or ce above it: skipped), and the
	 * bias that makes u16 signed */
	int64_t tlo = t == VX_I16 ? -32768 : 0;
	int64_t thi = t == VX_U8 ? 255 : t == VX_I16 ? 32767 : 65535;
	int64_t bias = t == VX_U16 ? 32768 : 0;
	int64_t f1 = f > thi ? thi : f < tlo ? tlo : f;
	int64_t c1 = c < tlo ? tlo : c > thi ? thi : c;

	k->fl = _mm_set1_epi32((int)f);
	k->cm1 = _mm_set1_epi32((int)(c - 1));
	k->val = _mm_set1_ps(val);
	k->fmax = _mm_set1_ps(FLT_MAX);
	k->abs = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
	k->f8 = _mm_set1_epi8((char)(f1 & 255));
	k->c8 = _mm_set1_epi8((char)(c1 & 255));
	k->f16 = _mm_set1_epi16((short)(f1 - bias));
	k->c16 = _mm_set1_epi16((short)(c1 - bias));
}

static inline __m128i
load_u32(const char *p)
{
	uint32_t w;

	memcpy(&w, p, sizeof w);
	return _mm_cvtsi32_si128((int)w);
}

static inline __m128i
load_u64(const char *p)
{
	return _mm_loadl_epi64((const __m128i *)(const void *)p);
}

/* load16: 16 bytes in runs of run bytes (16, 8 or 4) at p + ro[0],
 * p + ro[1], ... */
static inline __m128i
load16(const char *p, const int64_t *ro, int run)
{
	if (run == 16)
		return _mm_loadu_si128((const __m128i *)(const void *)(p +
		    ro[0]));
	if (run == 8)
		return _mm_unpacklo_epi64(load_u64(p + ro[0]),
		    load_u64(p + ro[1]));
	return _mm_unpacklo_epi64(_mm_unpacklo_epi32(load_u32(p + ro[0]),
	    load_u32(p + ro[1])), _mm_unpacklo_epi32(load_u32(p + ro[2]),
	    load_u32(p + ro[3])));
}

/* test_u8: v's 16 samples' below bits (*b, v <= fl) and above bits
 * (*a, v >= ce) */
static inline void
test_u8(__m128i v, const quad_k *k, unsigned *b, unsigned *a)
{
	*b = (unsigned)_mm_movemask_epi8(_mm_cmpeq_epi8(_mm_min_epu8(v,
	    k->f8), v));
	*a = (unsigned)_mm_movemask_epi8(_mm_cmpeq_epi8(_mm_max_epu8(v,
	    k->c8), v));
}

/* chunk_*: the below bits (*b) and above bits (*a) of a chunk of W samples
 * at row p, in runs of run bytes at byte offsets ro */
static inline void
chunk_u8(const char *p, const int64_t *ro, int run, const quad_k *k,
    unsigned *b, unsigned *a)
{
	test_u8(load16(p, ro, run), k, b, a);
}

/* test_s16: the same for v0, v1 (16 signed samples): not above fl, not
 * below ce */
static inline void
test_s16(__m128i v0, __m128i v1, const quad_k *k, unsigned *b,
    unsigned *a)
{
	*b = (unsigned)_mm_movemask_epi8(_mm_packs_epi16(_mm_cmpgt_epi16(v0,
	    k->f16), _mm_cmpgt_epi16(v1, k->f16))) ^ 0xffffu;
	*a = (unsigned)_mm_movemask_epi8(_mm_packs_epi16(_mm_cmpgt_epi16(k->c16,
	    v0), _mm_cmpgt_epi16(k->c16, v1))) ^ 0xffffu;
}

/* test_s16_8: the same for 8 samples v */
static inline void
test_s16_8(__m128i v, const quad_k *k, unsigned *b, unsigned *a)
{
	unsigned m = (unsigned)_mm_movemask_epi8(_mm_packs_epi16(
	    _mm_cmpgt_epi16(v, k->f16), _mm_cmpgt_epi16(k->c16, v))) ^ 0xffffu;

	*b = m & 255u;
	*a = m >> 8;
}

/* load16s: load16 made signed: u16 (flip) with its top bit flipped, so
 * that signed compares order it as unsigned; i16 as it is */
static inline __m128i
load16s(const char *p, const int64_t *ro, int run, int flip)
{
	__m128i v = load16(p, ro, run);

	return flip ? _mm_xor_si128(v, _mm_set1_epi16(-0x8000)) : v;
}

static inline void
chunk_u16(const char *p, const int64_t *ro, int run, const quad_k *k,
    unsigned *b, unsigned *a)
{
	test_s16(load16s(p, ro, run, 1), load16s(p, ro + 16 / run, run, 1), k,
	    b, a);
}

static inline void
chunk_i16(const char *p, const int64_t *ro, int run, const quad_k *k,
    unsigned *b, unsigned *a)
{
	test_s16(load16s(p, ro, run, 0), load16s(p, ro + 16 / run, run, 0), k,
	    b, a);
}

/* tail_*: as chunk_* with runs of 16 bytes at ro[0], ro[1], only n samples
 * wanted: 16 bytes when they hold those */
static inline void
tail_u8(const char *p, const int64_t *ro, int n, const quad_k *k,
    unsigned *b, unsigned *a)
{
	(void)n;
	chunk_u8(p, ro, 16, k, b, a);
}

static inline void
tail_16(const char *p, const int64_t *ro, int n, const quad_k *k,
    unsigned *b, unsigned *a, int flip)
{
	if (n > 8)
		test_s16(load16s(p, ro, 16, flip), load16s(p, ro + 1, 16, flip),
		    k, b, a);
	else
		test_s16_8(load16s(p, ro, 16, flip), k, b, a);
}

static inline void
tail_u16(const char *p, const int64_t *ro, int n, const quad_k *k,
    unsigned *b, unsigned *a)
{
	tail_16(p, ro, n, k, b, a, 1);
}

static inline void
tail_i16(const char *p, const int64_t *ro, int n, const quad_k *k,
    unsigned *b, unsigned *a)
{
	tail_16(p, ro, n, k, b, a, 0);
}

static inline void
chunk_f32(const char *p, const int64_t *ro, int run, const quad_k *k,
    unsigned *b, unsigned *a)
{
	__m128 v0 = _mm_castsi128_ps(load16(p, ro, run));
	__m128 v1 = _mm_castsi128_ps(load16(p, ro + 16 / run, run));
	__m128 f0 = _mm_cmple_ps(_mm_and_ps(v0, k->abs), k->fmax);
	__m128 f1 = _mm_cmple_ps(_mm_and_ps(v1, k->abs), k->fmax);
	__m128i b01 = _mm_packs_epi32(
	    _mm_castps_si128(_mm_and_ps(_mm_cmple_ps(v0, k->val), f0)),
	    _mm_castps_si128(_mm_and_ps(_mm_cmple_ps(v1, k->val), f1)));
	__m128i a01 = _mm_packs_epi32(
	    _mm_castps_si128(_mm_and_ps(_mm_cmpge_ps(v0, k->val), f0)),
	    _mm_castps_si128(_mm_and_ps(_mm_cmpge_ps(v1, k->val), f1)));
	unsigned m = (unsigned)_mm_movemask_epi8(_mm_packs_epi16(b01, a01));

	*b = m & 255u;
	*a = m >> 8;
}

/* chunk_plan: whether a block's rows can be read in chunks of w samples of
 * sz bytes, the row's ns samples at x offsets o: the longest runs among
 * runs (a set of 16, 8 and 4 bytes, each at least one sample) that every
 * chunk's samples come in (runs of r bytes are runs of r / 2 too), and
 * their byte offsets from the row's start into ro; 0 when there is no
 * chunk or one has no such runs */
static int
chunk_plan(const int64_t *o, int64_t ns, int w, int sz, int runs,
    int64_t *ro)
{
	int n = (int)(ns / w), c, r, best = 16, i;

	for (c = 0; c < n; c++) {
		const int64_t *q = o + (int64_t)c * w;

		for (r = best; r >= 4 && r >= sz; r /= 2) {
			int step = r / sz;

			if (!(runs & r))
				continue;
			for (i = 0; i < w; i++)
				if (q[i] != q[i - i % step] + i % step)
					break;
			if (i == w)
				break;
		}
		if (r < 4 || r < sz)
			return 0;
		best = r;
	}
	if (n == 0)
		return 0;
	for (i = 0; i < n * w * sz / best; i++)
		ro[i] = o[i * best / sz] * sz;
	return best;
}

static inline void
quad_int(__m128i v, const quad_k *k, unsigned *b, unsigned *a)
{
	*b = ~(unsigned)_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(v,
	    k->fl))) & 15u;
	*a = (unsigned)_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(v,
	    k->cm1)));
}

static inline void
quad_u8(const uint8_t *p, const quad_k *k, unsigned *b, unsigned *a)
{
	uint32_t w;
	__m128i z = _mm_setzero_si128(), v;

	memcpy(&w, p, sizeof w);
	v = _mm_cvtsi32_si128((int)w);
	v = _mm_unpacklo_epi16(_mm_unpacklo_epi8(v, z), z);
	quad_int(v, k, b, a);
}

static inline void
quad_u16(const uint16_t *p, const quad_k *k, unsigned *b, unsigned *a)
{
	__m128i v = _mm_loadl_epi64((const __m128i *)(const void *)p);

	quad_int(_mm_unpacklo_epi16(v, _mm_setzero_si128()), k, b, a);
}

static inline void
quad_i16(const int16_t *p, const quad_k *k, unsigned *b, unsigned *a)
{
	__m128i v = _mm_loadl_epi64((const __m128i *)(const void *)p);

	quad_int(_mm_srai_epi32(_mm_unpacklo_epi16(v, v), 16), k, b, a);
}

static inline void
quad_f32(const float *p, const quad_k *k, unsigned *b, unsigned *a)
{
	__m128 v = _mm_loadu_ps(p);
	__m128 fin = _mm_cmple_ps(_mm_and_ps(v, k->abs), k->fmax);

	*b = (unsigned)_mm_movemask_ps(_mm_and_ps(_mm_cmple_ps(v, k->val), fin));
	*a = (unsigned)_mm_movemask_ps(_mm_and_ps(_mm_cmpge_ps(v, k->val), fin));
}

static inline void
tail_f32(const char *p, const int64_t *ro, int n, const quad_k *k,
    unsigned *b, unsigned *a)
{
	if (n > 4)
		chunk_f32(p, ro, 16, k, b, a);
	else
		quad_f32((const float *)(const void *)(p + ro[0]), k, b, a);
}

#define QUAD_RUN(T, QUAD)                                                \
	if (x + 4 <= ns[0] && o[x + 1] == o[x] + 1 &&                    \
	    o[x + 2] == o[x] + 2 && o[x + 3] == o[x] + 3) {              \
		unsigned b4, a4;                                         \
		QUAD((const T *)row + o[x], &qk, &b4, &a4);              \
		bb |= (uint64_t)b4 << x;                                 \
		aa |= (uint64_t)a4 << x;                                 \
		x += 4;                                                  \
		continue;                                                \
	}

/* a block's plan for reading its planes' rows in chunks, for one value */
typedef struct chunk_rows {
	const quad_k *k;
	int64_t fl, ce;           /* integer thresholds (the last samples) */
	float val;
	const char *base;         /* the samples */
	const int64_t *oz;        /* the planes' offsets, in samples */
	const int64_t *oy;        /* the rows' offsets, in samples */
	int64_t nz, ny;           /* planes, rows */
	int64_t ntile;            /* rows 0 to ntile - 1 read as tiles */
	const int64_t *ro;        /* the chunks' runs' byte offsets in a row */
	int nch;                  /* chunks in a row, >= 1 */
	int nt;                   /* samples after them, at byte offsets ot */
	const int64_t *ot;
	int tv;                   /* 1: those samples are one chunk's first,
	                             at ot[0], ot[1] in runs of 16 bytes
	                             (the rest read, in bounds, not used) */
	uint64_t *pb, *pa, *ub, *ua;   /* rows' bits: as MASK_ROWS */
	uint64_t *out;            /* the block's bits */
	int64_t step, pstep;      /* leaf rows', planes' bits apart */
	int nx;                   /* leaves in a row */
} chunk_rows;

/* CHUNK_PLANE: NAME(r, pl, y0, y1, pb, pa, ub, ua, nch) reads rows y0 to
 * y1 - 1 of the plane at pl as r plans, nch chunks of W samples of type T
 * in runs of R bytes, into below and above bits: a row's bits OR-ed with
 * the previous plane's row (pb, pa: in) into ub, ua, and its own into pb,
 * pa */
#define CHUNK_PLANE(NAME, T, CHUNK, TAIL, W, R, BELOW, ABOVE)            \
static inline __attribute__((always_inline)) void                        \
NAME(const chunk_rows *r, const char *pl, int64_t y0, int64_t y1,        \
    uint64_t *restrict pb, uint64_t *restrict pa, uint64_t *restrict ub, \
    uint64_t *restrict ua, const int nch)                                \
{                                                                        \
	const quad_k k = *r->k;                                          \
	const int64_t fl = r->fl, ce = r->ce;                            \
	const int64_t *oy = r->oy, *ro = r->ro, *ot = r->ot;             \
	const float val = r->val;                                        \
	const int nt = r->nt, tv = r->tv;                                \
	const int stride = (W) * (int)sizeof(T) / (R);                   \
	int64_t y;                                                       \
	int ch, t;                                                       \
									 \
	(void)fl;                                                        \
	(void)ce;                                                        \
	(void)val;                                                       \
	for (y = y0; y < y1; y++) {                                      \
		const char *row = pl + oy[y] * (int64_t)sizeof(T);       \
		uint64_t bb, aa;                                         \
		unsigned bw, aw;                                         \
									 \
		CHUNK(row, ro, R, &k, &bw, &aw);                         \
		bb = bw;                                                 \
		aa = aw;                                                 \
		for (ch = 1; ch < nch; ch++) {                           \
			CHUNK(row, ro + ch * stride, R, &k, &bw, &aw);   \
			bb |= (uint64_t)bw << (ch * (W));                \
			aa |= (uint64_t)aw << (ch * (W));                \
		}                                                        \
		if (tv) {                                                \
			TAIL(row, ot, nt, &k, &bw, &aw);                 \
			bb |= (uint64_t)bw << (nch * (W));               \
			aa |= (uint64_t)aw << (nch * (W));               \
		} else                                                   \
			for (t = 0; t < nt; t++) {                       \
				T v;                                     \
									 \
				memcpy(&v, row + ot[t], sizeof v);       \
				bb |= (uint64_t)(BELOW) << (nch * (W) + t); \
				aa |= (uint64_t)(ABOVE) << (nch * (W) + t); \
			}                                                \
		row_planes(ub, ua, pb, pa, y, bb, aa);                   \
	}                                                                \
}

CHUNK_PLANE(chunk_u8_16, uint8_t, chunk_u8, tail_u8, 16, 16, v <= fl,
    v >= ce)
CHUNK_PLANE(chunk_u8_4, uint8_t, chunk_u8, tail_u8, 16, 4, v <= fl, v >= ce)
CHUNK_PLANE(chunk_u16_16, uint16_t, chunk_u16, tail_u16, 16, 16, v <= fl,
    v >= ce)
CHUNK_PLANE(chunk_u16_8, uint16_t, chunk_u16, tail_u16, 16, 8, v <= fl,
    v >= ce)
CHUNK_PLANE(chunk_i16_16, int16_t, chunk_i16, tail_i16, 16, 16, v <= fl,
    v >= ce)
CHUNK_PLANE(chunk_i16_8, int16_t, chunk_i16, tail_i16, 16, 8, v <= fl,
    v >= ce)
CHUNK_PLANE(chunk_f32_16, float, chunk_f32, tail_f32, 8, 16,
    fabsf(v) <= FLT_MAX && v <= val, fabsf(v) <= FLT_MAX && v >= val)

/* load4: 16 bytes at each of row + q[0..3] */
static inline __attribute__((always_inline)) void
load4(const char *row, const int64_t *q, __m128i *v0, __m128i *v1,
    __m128i *v2, __m128i *v3)
{
	*v0 = _mm_loadu_si128((const __m128i *)(const void *)(row + q[0]));
	*v1 = _mm_loadu_si128((const __m128i *)(const void *)(row + q[1]));
	*v2 = _mm_loadu_si128((const __m128i *)(const void *)(row + q[2]));
	*v3 = _mm_loadu_si128((const __m128i *)(const void *)(row + q[3]));
}

/* tile_u8: as chunk_u8_4, rows y0 to y1 - 1 (y1 - y0 a multiple of 4) of
 * u8 samples in runs of 4 bytes, where each four rows from y0 on lie 4
 * bytes apart (a bricked layout's bricks 4 samples wide), so that 16 bytes
 * hold a run of each of the four: read as such tiles, turned into rows,
 * the last samples too (r->tv; nt <= 4; the bits past them, garbage, go
 * past the row's end, where no leaf reads them).  tile_rows: its body,
 * nch the chunks per row (a constant for one chunk, the usual) */
static inline __attribute__((always_inline)) void
tile_rows(const chunk_rows *r, const char *pl, int64_t y0, int64_t y1,
    uint64_t *restrict pb, uint64_t *restrict pa, uint64_t *restrict ub,
    uint64_t *restrict ua, const int nch)
{
	const quad_k k = *r->k;
	const int64_t *oy = r->oy, *ro = r->ro;
	const int sh = nch * 16, nt = r->nt;
	const int64_t t0 = r->ot[0];
	int64_t y;
	int ch, i;

	for (y = y0; y < y1; y += 4) {
		const char *row = pl + oy[y];
		uint64_t bb[4] = { 0, 0, 0, 0 }, aa[4] = { 0, 0, 0, 0 };
		unsigned bw, aw;

		for (ch = 0; ch < nch; ch++) {
			const int64_t *q = ro + ch * 4;
			__m128i v0, v1, v2, v3;

			load4(row, q, &v0, &v1, &v2, &v3);
			__m128i l01 = _mm_unpacklo_epi32(v0, v1);
			__m128i l23 = _mm_unpacklo_epi32(v2, v3);
			__m128i h01 = _mm_unpackhi_epi32(v0, v1);
			__m128i h23 = _mm_unpackhi_epi32(v2, v3);
			__m128i rw[4];

			rw[0] = _mm_unpacklo_epi64(l01, l23);
			rw[1] = _mm_unpackhi_epi64(l01, l23);
			rw[2] = _mm_unpacklo_epi64(h01, h23);
			rw[3] = _mm_unpackhi_epi64(h01, h23);
			for (i = 0; i < 4; i++) {
				test_u8(rw[i], &k, &bw, &aw);
				bb[i] |= (uint64_t)bw << (ch * 16);
				aa[i] |= (uint64_t)aw << (ch * 16);
			}
		}
		if (nt != 0) {
			test_u8(_mm_loadu_si128((const __m128i *)(const void *)
			    (row + t0)), &k, &bw, &aw);
			for (i = 0; i < 4; i++) {
				bb[i] |= (uint64_t)(bw >> 4 * i) << sh;
				aa[i] |= (uint64_t)(aw >> 4 * i) << sh;
			}
		}
		for (i = 0; i < 4; i++) {
			ub[y + i] = pb[y + i] | bb[i];
			ua[y + i] = pa[y + i] | aa[i];
			pb[y + i] = bb[i];
			pa[y + i] = aa[i];
		}
	}
}

/* tile_16: as tile_u8 for 16-bit samples (flip: u16) in runs of 8 bytes,
 * each two rows from y0 on 8 bytes apart (bricks 4 samples wide), so that
 * 16 bytes hold a run of each of the two; the last samples too (r->tv;
 * nt <= 4).  tile16_rows: its body */
static inline __attribute__((always_inline)) void
tile16_rows(const chunk_rows *r, const char *pl, int64_t y0, int64_t y1,
    uint64_t *restrict pb, uint64_t *restrict pa, uint64_t *restrict ub,
    uint64_t *restrict ua, const int nch, const int flip)
{
	const quad_k k = *r->k;
	const int64_t *oy = r->oy, *ro = r->ro;
	const int sh = nch * 16, nt = r->nt;
	const int64_t t0 = r->ot[0];
	const __m128i top = _mm_set1_epi16(flip ? -0x8000 : 0);
	int64_t y;
	int ch;

	for (y = y0; y < y1; y += 2) {
		const char *row = pl + oy[y] * 2;
		uint64_t b0 = 0, b1 = 0, a0 = 0, a1 = 0;
		unsigned bw, aw;

		for (ch = 0; ch < nch; ch++) {
			const int64_t *q = ro + ch * 4;
			__m128i v0, v1, v2, v3;

			load4(row, q, &v0, &v1, &v2, &v3);

			if (flip) {
				v0 = _mm_xor_si128(v0, top);
				v1 = _mm_xor_si128(v1, top);
				v2 = _mm_xor_si128(v2, top);
				v3 = _mm_xor_si128(v3, top);
			}
			test_s16(_mm_unpacklo_epi64(v0, v1),
			    _mm_unpacklo_epi64(v2, v3), &k, &bw, &aw);
			b0 |= (uint64_t)bw << (ch * 16);
			a0 |= (uint64_t)aw << (ch * 16);
			test_s16(_mm_unpackhi_epi64(v0, v1),
			    _mm_unpackhi_epi64(v2, v3), &k, &bw, &aw);
			b1 |= (uint64_t)bw << (ch * 16);
			a1 |= (uint64_t)aw << (ch * 16);
		}
		if (nt != 0) {
			__m128i v = _mm_loadu_si128((const __m128i *)(const
			    void *)(row + t0));

			test_s16_8(flip ? _mm_xor_si128(v, top) : v, &k, &bw,
			    &aw);
			b0 |= (uint64_t)bw << sh;
			a0 |= (uint64_t)aw << sh;
			b1 |= (uint64_t)(bw >> 4) << sh;
			a1 |= (uint64_t)(aw >> 4) << sh;
		}
		ub[y] = pb[y] | b0;
		ua[y] = pa[y] | a0;
		pb[y] = b0;
		pa[y] = a0;
		ub[y + 1] = pb[y + 1] | b1;
		ua[y + 1] = pa[y + 1] | a1;
		pb[y + 1] = b1;
		pa[y + 1] = a1;
	}
}

static inline __attribute__((always_inline)) void
tile_u16(const chunk_rows *r, const char *pl, int64_t y0, int64_t y1,
    uint64_t *restrict pb, uint64_t *restrict pa, uint64_t *restrict ub,
    uint64_t *restrict ua, const int nch)
{
	tile16_rows(r, pl, y0, y1, pb, pa, ub, ua, nch, 1);
}

static inline __attribute__((always_inline)) void
tile_i16(const chunk_rows *r, const char *pl, int64_t y0, int64_t y1,
    uint64_t *restrict pb, uint64_t *restrict pa, uint64_t *restrict ub,
    uint64_t *restrict ua, const int nch)
{
	tile16_rows(r, pl, y0, y1, pb, pa, ub, ua, nch, 0);
}

static inline __attribute__((always_inline)) void
tile_none(const chunk_rows *r, const char *pl, int64_t y0, int64_t y1,
    uint64_t *restrict pb, uint64_t *restrict pa, uint64_t *restrict ub,
    uint64_t *restrict ua, const int nch)
{
	(void)r, (void)pl, (void)y0, (void)y1, (void)pb, (void)pa, (void)ub;
	(void)ua, (void)nch;
}

/* BLOCK_FN: NAME(r) makes a block's bits for one value as r plans: each
 * plane's rows 0 to r->ntile - 1 read by TILE, the others by ROWS, then
 * its leaf rows (with the plane before); NAME_body with nch chunks a row,
 * a constant where it is 1 (the usual) */
#define BLOCK_FN(NAME, T, TILE, ROWS)                                    \
static inline __attribute__((always_inline)) void                        \
NAME##_body(const chunk_rows *r, const int nch)                          \
{                                                                        \
	const int64_t ny = r->ny, nty = r->ntile;                        \
	uint64_t *pb = r->pb, *pa = r->pa, *ub = r->ub, *ua = r->ua;     \
	int64_t z;                                                       \
									 \
	for (z = 0; z < r->nz; z++) {                                    \
		const char *pl = r->base + r->oz[z] * (int64_t)sizeof(T); \
									 \
		TILE(r, pl, 0, nty, pb, pa, ub, ua, nch);                \
		ROWS(r, pl, nty, ny, pb, pa, ub, ua, nch);               \
		if (z > 0)                                               \
			leaf_rows(r->out, ub, ua, ny - 1, r->pstep *     \
			    (z - 1), r->step, r->nx);                    \
	}                                                                \
}                                                                        \
									 \
static void                                                              \
NAME(const chunk_rows *r)                                                \
{                                                                        \
	if (r->nch == 1)                                                 \
		NAME##_body(r, 1);                                       \
	else                                                             \
		NAME##_body(r, r->nch);                                  \
}

/* the layouts that pay: linear and any bricks 16 bytes wide or more (runs
 * of 16), u8 bricks 4 wide (tiles, or rows where the block's rows do not
 * fall on the bricks' edges), u16 and i16 bricks 4 wide (the same): every
 * type's default bricks; others test samples four at a time (MASK_ROWS) */
BLOCK_FN(block_u8_16, uint8_t, tile_none, chunk_u8_16)
BLOCK_FN(block_u8_4, uint8_t, tile_rows, chunk_u8_4)
BLOCK_FN(block_u16_16, uint16_t, tile_none, chunk_u16_16)
BLOCK_FN(block_u16_8, uint16_t, tile_u16, chunk_u16_8)
BLOCK_FN(block_i16_16, int16_t, tile_none, chunk_i16_16)
BLOCK_FN(block_i16_8, int16_t, tile_i16, chunk_i16_8)
BLOCK_FN(block_f32_16, float, tile_none, chunk_f32_16)

typedef void block_fn(const chunk_rows *);

/* block_for: the block reader for type t and runs of run bytes; NULL:
 * none */
static block_fn *
block_for(vx_type t, int run)
{
	switch (t) {
	case VX_U8:
		return run == 16 ? block_u8_16 : run == 4 ? block_u8_4 : NULL;
	case VX_U16:
		return run == 16 ? block_u16_16 : run == 8 ? block_u16_8 : NULL;
	case VX_I16:
		return run == 16 ? block_i16_16 : run == 8 ? block_i16_8 : NULL;
	case VX_F32:
		return run == 16 ? block_f32_16 : NULL;
	default:
		return NULL;
	}
}
#else
#define QUAD_RUN(T, QUAD)
#endif

/* MASK_ROWS: plane z's rows' below and above bits, four samples at once
 * where they are adjacent, each row's OR-ed with the previous plane's row
 * (pb, pa: in) into ub, ua, and its own into pb, pa */
#define MASK_ROWS(T, QUAD, BELOW, ABOVE)                                 \
	do {                                                             \
		const T *dd = (const T *)g->data;                        \
		for (y = 0; y < ns[1]; y++) {                            \
			const T *row = dd + g->lay.off[1][lo[1] + y] +   \
			    g->lay.off[2][lo[2] + z];                    \
			const int64_t *o = ox + lo[0];                   \
			uint64_t bb = 0, aa = 0;                         \
			for (x = 0; x < ns[0];) {                        \
				QUAD_RUN(T, QUAD)                        \
				T v = row[o[x]];                         \
				bb |= (uint64_t)(BELOW) << x;            \
				aa |= (uint64_t)(ABOVE) << x;            \
				x++;                                     \
			}                                                \
			row_planes(ub, ua, pb, pa, y, bb, aa);           \
		}                                                        \
	} while (0)

/* mask_block: the bits of level-1 macrocell c (linear index) into out
 * (zeroed) */
static void
mask_block(const vx_macro *m, const vx_grid *g, int64_t c,
    const float *vals, int nvals, uint64_t *out)
{
	/* a plane's rows' bits, and those OR-ed with the previous plane's */
	uint64_t pb[VX_MACRO_MAXSIZE + 1], pa[VX_MACRO_MAXSIZE + 1];
	uint64_t ub[VX_MACRO_MAXSIZE + 1], ua[VX_MACRO_MAXSIZE + 1];
	const int64_t *ox = g->lay.off[0];
	const int64_t *w = m->width[1];
	int64_t b[3], lo[3], nl[3], ns[3], x, y, z;
	int a, j;
#ifdef MASK_SIMD
	/* the chunks' runs' byte offsets in a row (at most
	 * VX_CELLMASK_MAXROW + 1 samples in runs of 4 bytes or more), the
	 * last samples' */
	int64_t ro[VX_CELLMASK_MAXROW + 1], ot[16];
	block_fn *block = NULL;
	chunk_rows cr;
#endif

	b[0] = c % m->dims[1][0];
	b[1] = c / m->dims[1][0] % m->dims[1][1];
	b[2] = c / m->dims[1][0] / m->dims[1][1];
	for (a = 0; a < 3; a++) {
		lo[a] = b[a] * w[a];
		nl[a] = m->dims[0][a] - lo[a] < w[a] ? m->dims[0][a] - lo[a] :
		    w[a];
		ns[a] = nl[a] + 1;
	}
#ifdef MASK_SIMD
	if (ns[0] <= VX_CELLMASK_MAXROW + 1 && g->type >= VX_U8 &&
	    g->type <= VX_F32) {
		int cw = g->type == VX_F32 ? 8 : 16;
		int sz = (int)vx_type_size(g->type);
		/* the runs block_for has readers for */
		int run = chunk_plan(ox + lo[0], ns[0], cw, sz,
		    g->type == VX_U8 ? 16 | 4 : g->type == VX_F32 ? 16 :
		    16 | 8, ro);

		if (run != 0) {
			const int64_t *oy = g->lay.off[1] + lo[1];
			const int64_t *oz = g->lay.off[2] + lo[2];
			const int64_t *o = ox + lo[0];
			int64_t xt, top = 0, yt = 0, zt = 0;

			cr.base = (const char *)g->data;
			cr.oz = oz;
			cr.oy = oy;
			cr.nz = ns[2];
			cr.ny = ns[1];
			cr.ntile = 0;
			cr.ro = ro;
			cr.nch = (int)(ns[0] / cw);
			cr.nt = (int)(ns[0] % cw);
			cr.ot = ot;
			xt = (int64_t)cr.nch * cw;
			/* the last samples as a chunk: adjacent, and the
			 * chunk's bytes (32 for f32) within the samples from
			 * every row of the block */
			for (y = 0; y < ns[1]; y++)
				yt = oy[y] > yt ? oy[y] : yt;
			for (z = 0; z < ns[2]; z++)
				zt = oz[z] > zt ? oz[z] : zt;
			for (a = 1; a < cr.nt && o[xt + a] == o[xt] + a; a++)
				;
			if (cr.nt > 0)
				top = (yt + zt + o[xt]) * sz +
				    (cr.nt * sz > 16 ? 32 : 16);
			cr.tv = cr.nt > 0 && a == cr.nt && top > 0 &&
			    (uint64_t)top <= (uint64_t)g->nsample *
			    (uint64_t)sz;
			if (cr.tv) {
				ot[0] = o[xt] * sz;
				ot[1] = ot[0] + 16;
			} else
				for (a = 0; a < cr.nt; a++)
					ot[a] = o[xt + a] * sz;
			/* u8 in runs of 4 bytes, 16-bit in runs of 8: tiles of
			 * four (two) rows that many bytes apart (the last
			 * samples as a tile too) */
			if ((g->type == VX_U8 && run == 4) ||
			    ((g->type == VX_U16 || g->type == VX_I16) &&
			    run == 8)) {
				int gr = 16 / run, d = run / sz;

				if (cr.nt == 0 || (cr.tv && cr.nt <= d)) {
					for (y = 0; y + gr <= ns[1]; y += gr) {
						for (a = 1; a < gr && oy[y + a] ==
						    oy[y] + a * d; a++)
							;
						if (a < gr)
							break;
					}
					cr.ntile = y;
				}
			}
			block = block_for(g->type, run);
			cr.pb = pb;
			cr.pa = pa;
			cr.ub = ub;
			cr.ua = ua;
			cr.out = out;
			cr.step = w[0];
			cr.pstep = w[0] * w[1];
			cr.nx = (int)nl[0];
		}
	}
#endif
	for (j = 0; j < nvals; j++) {
		float val = vals[j];
		double cv;
		int64_t fl, ce;

		if (val != val)
			continue;    /* NaN brackets nothing */
		/* integers: v <= val is v <= floor(val), v >= val is
		 * v >= ceil(val) (val clamped far outside the 16-bit range) */
		cv = val < -0x1p40f ? -0x1p40 : val > 0x1p40f ? 0x1p40 :
		    (double)val;
		fl = (int64_t)floor(cv);
		ce = (int64_t)ceil(cv);
		/* no sample below, or none above: no leaf brackets */
		if ((g->type == VX_U8 && (fl < 0 || ce > 255)) ||
		    (g->type == VX_U16 && (fl < 0 || ce > 65535)) ||
		    (g->type == VX_I16 && (fl < -32768 || ce > 32767)))
			continue;
		for (y = 0; y < ns[1]; y++)
			pb[y] = pa[y] = 0;
#ifdef MASK_SIMD
		quad_k qk;

		quad_keys(&qk, g->type, fl, ce, val);
		cr.k = &qk;
		cr.fl = fl;
		cr.ce = ce;
		cr.val = val;
		if (block != NULL) {
			block(&cr);
			continue;
		}
#endif
		for (z = 0; z < ns[2]; z++) {
			switch (g->type) {
			case VX_U8:
				MASK_ROWS(uint8_t, quad_u8, v <= fl, v >= ce);
				break;
			case VX_U16:
				MASK_ROWS(uint16_t, quad_u16, v <= fl,
				    v >= ce);
				break;
			case VX_I16:
				MASK_ROWS(int16_t, quad_i16, v <= fl, v >= ce);
				break;
			case VX_F32:
				MASK_ROWS(float, quad_f32,
				    fabsf(v) <= FLT_MAX && v <= val,
				    fabsf(v) <= FLT_MAX && v >= val);
				break;
			default: return;
			}
			if (z == 0)
				continue;
			leaf_rows(out, ub, ua, nl[1], w[0] * w[1] * (z - 1),
			    w[0], (int)nl[0]);
		}
	}
}

/* vx_cellmask_block_bits: mask_get's answer where b's bits are not known
 * built: build them now if no one has (out of line: once per block) */
const uint64_t *
vx_cellmask_block_bits(vx_cellmask *k, const vx_macro *m, const vx_grid *g,
    int64_t b)
{
	unsigned char st, want = 0;

	st = atomic_load_explicit(&k->state[b], memory_order_acquire);
	if (st == 2)
		return k->bits + k->slot[b];
	if (st == 1 || !atomic_compare_exchange_strong_explicit(&k->state[b],
	    &want, 1, memory_order_acquire, memory_order_acquire))
		return want == 2 ? k->bits + k->slot[b] : NULL;
	mask_block(m, g, b, k->vals, k->nvals, k->bits + k->slot[b]);
	atomic_store_explicit(&k->state[b], 2, memory_order_release);
	atomic_fetch_add_explicit(&k->built, 1, memory_order_relaxed);
	return k->bits + k->slot[b];
}

int
vx_cellmask_matches(const vx_cellmask *k, const vx_macro *m,
    const float *vals, int nvals)
{
	return mask_matches(k, m, vals, nvals);
}

/* ---- cell masks: building ---- */

void
vx_cellmask_init(vx_cellmask *k)
{
	memset(k, 0, sizeof *k);
}

void
vx_cellmask_free(vx_cellmask *k)
{
	if (k == NULL)
		return;
	free(k->slot);
	free((void *)k->state);
	free(k->bits);
	free(k->set);
	vx_cellmask_init(k);
}

size_t
vx_cellmask_bytes(const vx_cellmask *k)
{
	if (k == NULL || !k->ready)
		return 0;
	return (size_t)k->nblock * (sizeof *k->slot + 1) +
	    (size_t)k->nset * sizeof *k->set +
	    (size_t)(k->nset * k->words) * sizeof *k->bits;
}

int64_t
vx_cellmask_built(const vx_cellmask *k)
{
	if (k == NULL || !k->ready)
		return 0;
	return atomic_load_explicit(&k->built, memory_order_relaxed);
}

int
vx_cellmask_block_built(const vx_cellmask *k, int64_t b)
{
	if (k == NULL || !k->ready || b < 0 || b >= k->nblock)
		return 0;
	return atomic_load_explicit(&k->state[b], memory_order_acquire) == 2;
}

int
vx_cellmask_build(vx_cellmask *k, const vx_macro *m, const vx_grid *g,
    const float *vals, int nvals, int lazy, int nthreads, vx_err *e)
{
	int64_t nb, i, nset = 0, words;
	size_t bytes;

	vx_cellmask_init(k);
	if (m == NULL || g == NULL || m->nlev < 1 || m->explicit_leaves ||
	    nvals < 1 || nvals > VX_CELLMASK_MAXV || !fits(m, g) ||
	    g->data == NULL || m->width[1][0] > VX_CELLMASK_MAXROW ||
	    m->width[1][1] > VX_MACRO_MAXSIZE)
		return 0;
	nb = (int64_t)ncells(m, 1);
	words = (m->width[1][0] * m->width[1][1] * m->width[1][2] + 63) / 64;
	k->slot = malloc((size_t)(nb > 0 ? nb : 1) * sizeof *k->slot);
	k->state = calloc((size_t)(nb > 0 ? nb : 1), 1);
	if (k->slot == NULL || k->state == NULL) {
		vx_cellmask_free(k);
		return vx_err_set(e, VX_ENOMEM, "cell mask: out of memory");
	}
	for (i = 0; i < nb; i++)
		k->slot[i] = brackets(m->mm[1][2 * i], m->mm[1][2 * i + 1],
		    vals, nvals) ? nset++ * words : -1;
	if ((k->set = malloc((size_t)(nset > 0 ? nset : 1) *
	    sizeof *k->set)) == NULL) {
		vx_cellmask_free(k);
		return vx_err_set(e, VX_ENOMEM, "cell mask: out of memory");
	}
	for (nset = 0, i = 0; i < nb; i++)
		if (k->slot[i] >= 0)
			k->set[nset++] = i;
	/* calloc: pages of blocks never entered are never touched */
	if (vx_mul_size(&bytes, (size_t)(nset > 0 ? nset : 1) *
	    (size_t)words, sizeof *k->bits) != 0 ||
	    (k->bits = calloc(1, bytes)) == NULL) {
		vx_cellmask_free(k);
		return vx_err_set(e, VX_ENOMEM, "cell mask: out of memory "
		    "(%lld macrocells)", (long long)nset);
	}
	k->m = m;
	k->g = g;
	memcpy(k->vals, vals, (size_t)nvals * sizeof *vals);
	k->nvals = nvals;
	k->nblock = nb;
	k->nset = nset;
	k->words = words;
	k->ready = 1;
	if (!lazy) {
		int nt = vx_par_threads(nthreads);

		(void)nt;
#ifdef _OPENMP
#pragma omp parallel for num_threads(nt) schedule(dynamic, 16)
#endif
		for (i = 0; i < nb; i++)
			if (k->slot[i] >= 0)
				(void)mask_get(k, m, g, i);
	}
	return 0;
}
