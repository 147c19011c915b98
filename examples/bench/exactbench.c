/* exactbench.c: what vx_cell_first_root's exact signs cost (cell.c: a
 * filter in double, big numbers where it cannot decide).  Three sets of
 * cubics with exact coefficients, A (t - r)^2 (t - q) + eps on [0, 1]
 * (r inside, q = 2 beyond; A = 2^-20 .. 2^20, r from a grid of 64):
 *   far:   eps = +-A / 64: the extremum clearly off zero, every sign
 *          decided by the filter (the common case of a cell whose cubic
 *          has a critical point inside its segment);
 *   near:  eps = +-2^-45 A: beyond the filter's reach (the old touch
 *          tolerance 2^-40 took these for touches), decided exactly;
 *   touch: eps = 0, a double root: exactly.
 * Prints ns per vx_cell_first_root_x call (median of runs) and the exact
 * evaluations per call.  Build and run from the repository root (after
 * `make`):
 *     cc -O2 $(make -s print-core-inc) -o build/exactbench \
 *         examples/bench/exactbench.c build/libvoxlux.a -lm && build/exactbench
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "vx_cell.h"

#define N 4096

static double
now(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int
cmp(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return x < y ? -1 : x > y;
}

int
main(void)
{
	static double k[N][4], f0[N], f1[N];
	static const char *names[3] = { "far", "near", "touch" };
	volatile double sink = 0;

	for (int set = 0; set < 3; set++) {
		double rt[11], t;
		unsigned ex = 0;

		for (int i = 0; i < N; i++) {
			double A = ldexp(1, (i % 41) - 20), r = (1 + i % 63) / 64.0;
			double q = 2, s = i & 64 ? 1 : -1;
			double eps = set == 0 ? s * A / 64 : set == 1 ?
			    s * ldexp(A, -45) : 0;

			k[i][3] = A;
			k[i][2] = -A * (2 * r + q);
			k[i][1] = A * (r * r + 2 * r * q);
			k[i][0] = -A * r * r * q + eps;
			f0[i] = vx_cell_poly_eval(k[i], 0);
			f1[i] = vx_cell_poly_eval(k[i], 1);
		}
		for (int i = 0; i < N; i++)
			vx_cell_first_root_x(k[i], 0, 1, f0[i], f1[i],
			    VX_CELL_EXACT, &t, NULL, &ex);
		for (int r = 0; r < 11; r++) {
			double t0 = now(), t1;
			long calls = 0;

			do {
				for (int i = 0; i < N; i++) {
					vx_cell_first_root_x(k[i], 0, 1, f0[i], f1[i],
					    VX_CELL_EXACT, &t, NULL, NULL);
					sink += t;
				}
				calls += N;
			} while ((t1 = now()) - t0 < 0.05);
			rt[r] = (t1 - t0) / (double)calls * 1e9;
		}
		qsort(rt, 11, sizeof rt[0], cmp);
		printf("%-6s %8.1f ns/call  %5.2f exact evaluations/call\n",
		    names[set], rt[5], (double)ex / N);
	}
	(void)sink;
	return 0;
}
