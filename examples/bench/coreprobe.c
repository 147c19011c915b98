/* coreprobe: two loops that touch no memory, to tell whether two vCPUs share
 * a physical core (SMT siblings) at the time they run.
 *
 *   coreprobe alu N   N iterations of 6 integer additions in 3 independent
 *                     chains (more than the core's integer units do in a
 *                     cycle: it keeps them busy)
 *   coreprobe div N   N dependent double divisions (one result every 13 or
 *                     so cycles: it waits on latency, and leaves the units
 *                     free)
 *
 * Prints the seconds the loop took.  Run two copies side by side and alone:
 * if the pair's alu loops are slower than alone while the div loops are
 * not, the two vCPUs are sharing one core's execution units (neither loop
 * reads memory, so caches and memory bandwidth play no part).  voxlux's
 * frame is like the alu loop (a dense stream of instructions); see
 * corepair.sh and RESULTS.md, "Two threads". */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double
now(void)
{
	struct timespec t;

	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int
main(int argc, char **argv)
{
	long n;
	double t0;

	if (argc != 3 || (strcmp(argv[1], "alu") != 0 &&
	    strcmp(argv[1], "div") != 0) || (n = atol(argv[2])) <= 0) {
		fprintf(stderr, "usage: coreprobe alu|div ITERATIONS\n");
		return 2;
	}
	t0 = now();
	if (argv[1][0] == 'a') {
		unsigned long a = 1, b = 2, c = 3, d = 4, e = 5, f = 6;

		/* six additions an iteration, three chains of two: more
		 * than the core's integer units do in one cycle (the empty
		 * asm keeps the compiler from folding the loop) */
		for (unsigned long i = 0; i < (unsigned long)n; i++) {
			a += i;
			b += i;
			c += i;
			d += a;
			e += b;
			f += c;
			__asm__ volatile("" : "+r"(a), "+r"(b), "+r"(c),
			    "+r"(d), "+r"(e), "+r"(f));
		}
		if (a + b + c + d + e + f == 42)
			puts("");
	} else {
		volatile double x = 1.0000001;
		double y = 1.5;

		for (long i = 0; i < n; i++)
			y = y / x + 1e-9;
		if (y == 42)
			puts("");
	}
	printf("%.4f\n", now() - t0);
	return 0;
}
