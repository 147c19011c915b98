/* par.c: the parallel loop over blocks of a domain (vx_par.h). */
#include "vx_par.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifdef _OPENMP
#include <omp.h>
#endif

/* a state's alignment, and the stride's unit: a cache line */
#define LINE 64

double
vx_par_seconds(void)
{
	struct timespec t;

	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int
vx_par_threads(int nthreads)
{
#ifdef _OPENMP
	return nthreads > 0 ? nthreads : omp_get_max_threads();
#else
	(void)nthreads;
	return 1;
#endif
}

int
vx_par_init(vx_par *p, int nthreads, size_t local_size, vx_err *e)
{
	size_t stride = (local_size + LINE - 1) / LINE * LINE, bytes;

	memset(p, 0, sizeof *p);
	p->nthreads = vx_par_threads(nthreads);
	p->stride = stride > 0 ? stride : LINE;
	if (vx_mul_size(&bytes, p->stride, (size_t)p->nthreads) != 0 ||
	    (p->locals = aligned_alloc(LINE, bytes)) == NULL)
		return vx_err_set(e, VX_ENOMEM, "threads' state: out of memory "
		    "(%d threads)", p->nthreads);
	memset(p->locals, 0, bytes);
	return 0;
}

void
vx_par_free(vx_par *p)
{
	if (p == NULL)
		return;
	free(p->locals);
	memset(p, 0, sizeof *p);
}

void *
vx_par_local(const vx_par *p, int t)
{
	return (char *)p->locals + (size_t)t * p->stride;
}

int
vx_par_each(const vx_par *p, vx_par_each_fn fn, void *ctx)
{
	int rc;

	for (int t = 0; t < p->nthreads; t++)
		if ((rc = fn(ctx, vx_par_local(p, t), t)) != 0)
			return rc;
	return 0;
}

/* block k of a domain of nb blocks of edge bs over n cells */
static void
block_of(const int64_t n[3], const int64_t bs[3], const int64_t nb[3],
    int64_t k, vx_par_block *b)
{
	int64_t c[3] = { k % nb[0], k / nb[0] % nb[1], k / nb[0] / nb[1] };

	b->index = k;
	for (int a = 0; a < 3; a++) {
		b->lo[a] = c[a] * bs[a];
		b->hi[a] = b->lo[a] + bs[a] < n[a] ? b->lo[a] + bs[a] : n[a];
	}
}

int
vx_par_run(vx_par *p, const vx_par_loop *lp, vx_par_fn fn, void *ctx,
    vx_par_time *tm)
{
	int64_t n[3], bs[3], nb[3], total = 1;
	int chunk = lp->chunk > 0 ? lp->chunk : 1, nt = p->nthreads;
	int fail_rc = 0;
	double t0 = vx_par_seconds(), busy = 0;
	/* the lowest-numbered block that failed so far: blocks after it are
	 * skipped, those before it still run, so the lowest failing block of
	 * all is found whatever the timing */
	_Atomic int64_t first_fail = INT64_MAX;

	for (int a = 0; a < 3; a++) {
		n[a] = lp->n[a] > 0 ? lp->n[a] : 0;
		bs[a] = lp->block[a] > 0 ? lp->block[a] : 1;
		nb[a] = (n[a] + bs[a] - 1) / bs[a];
		total *= nb[a];
	}
	(void)chunk;
#ifdef _OPENMP
#pragma omp parallel num_threads(nt) reduction(+:busy)
#endif
	{
#ifdef _OPENMP
		int t = omp_get_thread_num();
#else
		int t = 0;
#endif
		void *local = vx_par_local(p, t);
		double s0 = vx_par_seconds();
		int64_t my_at = INT64_MAX;   /* this thread's first failure */
		int my_rc = 0;

#ifdef _OPENMP
#pragma omp for schedule(dynamic, chunk) nowait
#endif
		for (int64_t k = 0; k < total; k++) {
			vx_par_block b;
			int64_t f;
			int rc;

			if (k > atomic_load_explicit(&first_fail,
			    memory_order_relaxed))
				continue;
			block_of(n, bs, nb, k, &b);
			if ((rc = fn(ctx, local, &b)) == 0)
				continue;
			if (k < my_at) {
				my_at = k;
				my_rc = rc;
			}
			f = atomic_load_explicit(&first_fail,
			    memory_order_relaxed);
			while (k < f && !atomic_compare_exchange_weak_explicit(
			    &first_fail, &f, k, memory_order_relaxed,
			    memory_order_relaxed))
				;
		}
		busy += vx_par_seconds() - s0;
		/* the lowest failing block is final once every thread is
		 * done; the one thread that ran it says its code */
#ifdef _OPENMP
#pragma omp barrier
#endif
		if (my_at < INT64_MAX && my_at == atomic_load_explicit(
		    &first_fail, memory_order_relaxed))
			fail_rc = my_rc;
	}
	if (tm != NULL) {
		tm->threads = nt;
		tm->seconds = vx_par_seconds() - t0;
		tm->thread_seconds = busy;
	}
	return fail_rc;
}
