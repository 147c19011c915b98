/* test_par.c: the parallel loop over blocks (vx_par.h): every cell of the
 * domain in exactly one block, states merged to the same sums at any
 * thread count, the lowest failing block's code whatever the timing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "vx_par.h"

/* a thread's state: counters, padded as renderers' are */
typedef struct local {
	_Alignas(64) uint64_t blocks, cells, sum;
	int id;
} local;

typedef struct cover {
	int64_t n[3];
	unsigned char *hits;     /* per cell: blocks that covered it */
	int64_t fail_a, fail_b;  /* blocks that fail (-1: none) */
} cover;

static int
cover_block(void *ctx, void *lp, const vx_par_block *b)
{
	cover *c = ctx;
	local *L = lp;

	L->blocks++;
	for (int64_t z = b->lo[2]; z < b->hi[2]; z++)
		for (int64_t y = b->lo[1]; y < b->hi[1]; y++)
			for (int64_t x = b->lo[0]; x < b->hi[0]; x++) {
				/* each cell is one block's: no race */
				c->hits[x + c->n[0] * (y + c->n[1] * z)]++;
				L->cells++;
				L->sum += (uint64_t)(x + 3 * y + 7 * z);
			}
	if (b->index == c->fail_a)
		return 65;
	if (b->index == c->fail_b)
		return 74;
	return 0;
}

static int
merge(void *ctx, void *lp, int t)
{
	local *all = ctx, *L = lp;

	all->blocks += L->blocks;
	all->cells += L->cells;
	all->sum += L->sum;
	return 0;
}

/* tiles_cover: domains whose edges are and are not multiples of the block,
 * empty ones, 1 to 7 threads.  Oracle: every cell covered once, the
 * number of blocks the product of ceil(n / b), the merged sums the serial
 * loop's. */
static void
tiles_cover(void **state)
{
	static const struct { int64_t n[3], b[3]; int chunk; } t[] = {
		{ { 37, 23, 1 }, { 16, 16, 1 }, 1 },
		{ { 32, 32, 1 }, { 16, 16, 1 }, 1 },
		{ { 9, 10, 11 }, { 4, 4, 4 }, 1 },
		{ { 100, 1, 1 }, { 1, 1, 1 }, 16 },
		{ { 5, 5, 5 }, { 0, -2, 9 }, 0 },      /* edges < 1 count as 1 */
		{ { 0, 8, 8 }, { 4, 4, 4 }, 1 },       /* empty */
	};
	static const int nthr[] = { 1, 2, 3, 7 };

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		int64_t ncell = t[i].n[0] * t[i].n[1] * t[i].n[2], nblock = 1;
		uint64_t want_sum = 0;

		for (int a = 0; a < 3; a++) {
			int64_t b = t[i].b[a] > 0 ? t[i].b[a] : 1;

			nblock *= (t[i].n[a] + b - 1) / b;
		}
		for (int64_t z = 0; z < t[i].n[2]; z++)
			for (int64_t y = 0; y < t[i].n[1]; y++)
				for (int64_t x = 0; x < t[i].n[0]; x++)
					want_sum += (uint64_t)(x + 3 * y + 7 * z);
		for (size_t k = 0; k < sizeof nthr / sizeof nthr[0]; k++) {
			vx_par_loop lp;
			vx_par team;
			vx_par_time tm;
			local all;
			cover c;
			vx_err e = { 0, "" };

			memcpy(lp.n, t[i].n, sizeof lp.n);
			memcpy(lp.block, t[i].b, sizeof lp.block);
			lp.chunk = t[i].chunk;
			memcpy(c.n, t[i].n, sizeof c.n);
			c.hits = calloc((size_t)(ncell > 0 ? ncell : 1), 1);
			c.fail_a = c.fail_b = -1;
			assert_non_null(c.hits);
			assert_int_equal(vx_par_init(&team, nthr[k],
			    sizeof(local), &e), 0);
			assert_int_equal(team.nthreads, nthr[k]);
			/* the states are zeroed and on lines of their own */
			for (int th = 0; th < team.nthreads; th++) {
				local *L = vx_par_local(&team, th);

				assert_int_equal((uintptr_t)L % 64, 0);
				assert_int_equal(L->blocks + L->cells, 0);
			}
			assert_int_equal(vx_par_run(&team, &lp, cover_block, &c,
			    &tm), 0);
			memset(&all, 0, sizeof all);
			assert_int_equal(vx_par_each(&team, merge, &all), 0);
			assert_int_equal(all.blocks, nblock);
			assert_int_equal(all.cells, ncell);
			assert_true(all.sum == want_sum);
			for (int64_t j = 0; j < ncell; j++)
				assert_int_equal(c.hits[j], 1);
			assert_int_equal(tm.threads, nthr[k]);
			assert_true(tm.seconds >= 0 && tm.thread_seconds >= 0);
			vx_par_free(&team);
			free(c.hits);
		}
	}
}

/* failure: blocks fail with different codes.  Oracle: the code of the
 * lowest-numbered failing block, at any thread count, and every block
 * before it ran. */
static void
failure_lowest(void **state)
{
	static const struct { int64_t a, b; int want; } t[] = {
		{ 5, -1, 65 },
		{ 30, 3, 74 },         /* the later-listed one is lower */
		{ 0, 99, 65 },
		{ -1, -1, 0 },
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++)
		for (int nt = 1; nt <= 4; nt++) {
			vx_par_loop lp = VX_PAR_ITEMS(100, 1);
			vx_par team;
			cover c;
			vx_err e = { 0, "" };
			int64_t low = t[i].a < 0 ? t[i].b : t[i].b < 0 ? t[i].a :
			    t[i].a < t[i].b ? t[i].a : t[i].b;

			memset(&c, 0, sizeof c);
			c.n[0] = 100;
			c.n[1] = c.n[2] = 1;
			c.hits = calloc(100, 1);
			c.fail_a = t[i].a;
			c.fail_b = t[i].b;
			assert_int_equal(vx_par_init(&team, nt, sizeof(local),
			    &e), 0);
			for (int rep = 0; rep < 20; rep++) {
				memset(c.hits, 0, 100);
				assert_int_equal(vx_par_run(&team, &lp,
				    cover_block, &c, NULL), t[i].want);
				for (int64_t j = 0; j < (low < 0 ? 100 : low); j++)
					assert_int_equal(c.hits[j], 1);
			}
			vx_par_free(&team);
			free(c.hits);
		}
}

static int
each_order(void *ctx, void *lp, int t)
{
	int *seen = ctx;
	local *L = lp;

	L->id = t;
	seen[t] = ++seen[16];
	return t == 2 ? 70 : 0;
}

/* each: states in thread order, stopping at the first nonzero.  Oracle:
 * thread t's state seen t + 1-th, none after the one that stopped. */
static void
each_in_order(void **state)
{
	vx_par team;
	vx_err e = { 0, "" };
	int seen[17];

	(void)state;
	memset(seen, 0, sizeof seen);
	assert_int_equal(vx_par_init(&team, 5, sizeof(local), &e), 0);
	assert_int_equal(vx_par_each(&team, each_order, seen), 70);
	assert_int_equal(seen[0], 1);
	assert_int_equal(seen[1], 2);
	assert_int_equal(seen[2], 3);
	assert_int_equal(seen[3], 0);
	assert_int_equal(((local *)vx_par_local(&team, 1))->id, 1);
	vx_par_free(&team);
	vx_par_free(&team);      /* a freed team frees nothing twice */
	assert_int_equal(vx_par_threads(3), 3);
	assert_true(vx_par_threads(0) >= 1);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(tiles_cover),
		cmocka_unit_test(failure_lowest),
		cmocka_unit_test(each_in_order),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
