/* benchutil.h: what the C benchmarks and probes share.  A program defines
 * BENCH_NAME (its name, for messages) before including it, after the
 * system and voxlux headers (vx_scene.h, vx_stream.h). */
#ifndef BENCHUTIL_H
#define BENCHUTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

/* die: "NAME: what[: e's message]" on standard error, then exit with e's
 * code (1 without one). */
static inline void
die(const char *what, const vx_err *e)
{
	fprintf(stderr, BENCH_NAME ": %s%s%s\n", what, e ? ": " : "",
	    e ? e->msg : "");
	exit(e && e->code ? e->code : 1);
}

/* now: seconds on clock id. */
static inline double
now(clockid_t id)
{
	struct timespec ts;

	clock_gettime(id, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static inline int
cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return x < y ? -1 : x > y;
}

/* median of v[0..n) (sorts v) */
static inline double
median(double *v, int n)
{
	qsort(v, (size_t)n, sizeof *v, cmp_double);
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* quantile q of v[0..n) (sorts v): linear between order statistics */
static inline double
quantile(double *v, int n, double q)
{
	double x = q * (n - 1);
	int i = (int)x;

	qsort(v, (size_t)n, sizeof *v, cmp_double);
	if (i + 1 >= n)
		return v[n - 1];
	return v[i] + (x - i) * (v[i + 1] - v[i]);
}

/* load_scene, load_stream: the scene file or stream at path into s
 * (initialized here), or die. */
static inline void
load_scene(vx_scene *s, const char *path)
{
	vx_err e = { 0, "" };
	FILE *f;

	vx_scene_init(s);
	if ((f = fopen(path, "r")) == NULL)
		die(path, NULL);
	if (vx_scene_read(s, f, &e) != 0)
		die(path, &e);
	fclose(f);
}

static inline void
load_stream(vx_stream *st, const char *path)
{
	vx_err e = { 0, "" };
	FILE *f;

	vx_stream_init(st);
	if ((f = fopen(path, "rb")) == NULL)
		die(path, NULL);
	if (vx_stream_read(st, f, &e) != 0)
		die(path, &e);
	fclose(f);
}

#endif
