/* vx_par.h: the core's parallel loop, the one place for OpenMP scheduling
 * and timing of the renderers (and of the bakers to come): a domain of
 * cells (an image's pixels, a lattice's texels) cut into blocks (tiles,
 * texel blocks), the blocks taken by a team of threads with dynamic
 * scheduling, each thread with a state of its own (workspaces, counters),
 * the states merged in thread order after the loops.
 *
 * Determinism.  Which thread runs which block depends on timing; nothing
 * else may.  A loop body must write only its block's outputs and its own
 * thread's state, and a block's outputs must depend only on the block (a
 * state carried from one block to the next, such as a bound kept from the
 * previous ray, is reset at each block's start).  Counters merged by
 * addition are then the same at any thread count, and so is every output,
 * bit for bit.  A body draws no random numbers from a shared generator;
 * random numbers are pure functions of (seed, stream, sample, dimension).
 *
 * Use:
 *
 *     vx_par team;
 *     if ((rc = vx_par_init(&team, nthreads, sizeof(my_local), e)) != 0)
 *             return rc;
 *     vx_par_each(&team, my_init, &ctx);       (per-thread workspaces)
 *     vx_par_loop lp = VX_PAR_TILES(w, h, 16); (or a 3D block of texels)
 *     rc = vx_par_run(&team, &lp, my_block, &ctx, &time);
 *     vx_par_each(&team, my_merge, &stats);    (thread order)
 *     vx_par_free(&team);
 *
 * A team serves any number of loops (a sparse pass and the main pass of a
 * frame share the threads' states). */
#ifndef VX_PAR_H
#define VX_PAR_H

#include <stddef.h>
#include <stdint.h>

#include "vx_err.h"

/* A team: nthreads states of local_size bytes, each on cache lines of its
 * own (a thread writes its counters per cell; neighbours sharing a line
 * would slow each other), zeroed by vx_par_init. */
typedef struct vx_par {
	int nthreads;            /* threads every loop of the team runs on */
	size_t stride;           /* bytes from one state to the next */
	void *locals;            /* the states */
} vx_par;

/* A loop's domain: n[0] x n[1] x n[2] cells cut into blocks of block[0] x
 * block[1] x block[2] (the last ones along an axis shorter), numbered x
 * fastest; a thread takes chunk blocks at a time.  n[a] >= 0; a block or
 * chunk edge below 1 counts as 1. */
typedef struct vx_par_loop {
	int64_t n[3];
	int64_t block[3];
	int chunk;
} vx_par_loop;

/* VX_PAR_TILES: an image of w x h pixels in tiles of t x t, one a grab.
 * VX_PAR_ITEMS: n items, chunk c at a time.  VX_PAR_BLOCKS3: a lattice of
 * nx x ny x nz texels in blocks of b^3, one a grab. */
#define VX_PAR_TILES(w, h, t) \
	((vx_par_loop){ { (w), (h), 1 }, { (t), (t), 1 }, 1 })
#define VX_PAR_ITEMS(n, c) \
	((vx_par_loop){ { (n), 1, 1 }, { 1, 1, 1 }, (c) })
#define VX_PAR_BLOCKS3(nx, ny, nz, b) \
	((vx_par_loop){ { (nx), (ny), (nz) }, { (b), (b), (b) }, 1 })

/* One block of a loop: its number and its cells [lo, hi) per axis. */
typedef struct vx_par_block {
	int64_t index;
	int64_t lo[3], hi[3];
} vx_par_block;

/* vx_par_fn: the loop body, called once per block with the state of the
 * thread that runs it; 0 to go on, nonzero (a sysexits code) to stop: no
 * block numbered above it is started after that, blocks below it still
 * run. */
typedef int (*vx_par_fn)(void *ctx, void *local, const vx_par_block *b);

/* vx_par_each_fn: called on each thread's state in turn (thread t's state
 * and t); 0 to go on. */
typedef int (*vx_par_each_fn)(void *ctx, void *local, int t);

/* What a loop took: its threads, its wall time, and the threads' time in
 * it summed (each thread's from its first block to its last block's end:
 * at 1 thread the wall time; at N the same work spread over N plus what
 * running side by side costs each thread, so thread_seconds / (threads
 * seconds) is the loop's balance). */
typedef struct vx_par_time {
	int threads;
	double seconds;
	double thread_seconds;
} vx_par_time;

/* vx_par_threads: the thread count for nthreads (<= 0: OpenMP's default,
 * one per processor unless OMP_NUM_THREADS or omp_set_num_threads, as
 * the tools' -j does, says otherwise; 1 without OpenMP). */
int vx_par_threads(int nthreads);

/* vx_par_init: a team of vx_par_threads(nthreads) threads with zeroed
 * states of local_size bytes (aligned to 64 bytes: a state's type may
 * ask for that alignment, no more).  Errors: VX_ENOMEM. */
int vx_par_init(vx_par *p, int nthreads, size_t local_size, vx_err *e);

/* vx_par_free: the states' memory (accepts a zeroed or freed team). */
void vx_par_free(vx_par *p);

/* vx_par_local: thread t's state (0 <= t < p->nthreads). */
void *vx_par_local(const vx_par *p, int t);

/* vx_par_each: fn on each state in thread order (set-up, merging of
 * statistics, clean-up), serially; returns the first nonzero value of fn
 * (the rest are not called), else 0. */
int vx_par_each(const vx_par *p, vx_par_each_fn fn, void *ctx);

/* vx_par_run: fn on every block of lp, in parallel on p's threads, blocks
 * handed out dynamically (lp->chunk at a time, in block order).  tm (may be
 * NULL) gets the loop's times.  Returns 0, or fn's nonzero value for the
 * lowest-numbered block where it returned one: the same block whatever
 * the threads and their timing (blocks after it may not have run). */
int vx_par_run(vx_par *p, const vx_par_loop *lp, vx_par_fn fn, void *ctx,
    vx_par_time *tm);

/* vx_par_seconds: a monotonic clock, in seconds (for a caller's own
 * phases: the same clock the loops are timed with). */
double vx_par_seconds(void);

#endif
