/* shbench.c: the time of spherical-harmonic projection and rotation at
 * orders 3, 5, 10 and 16 (light/vx_sh.h).
 *
 *   projection  an RGB lat-long environment of W x H pixels projected by
 *               exact quadrature: one vx_sh_accumulate per pixel, weight
 *               the pixel's solid angle (what projecting a real
 *               environment costs; the pixels' directions and values are
 *               made beforehand and not timed)
 *   IR matrix   vx_sh_rot_from_matrix: the Ivanic-Ruedenberg recurrence
 *   ZYZ matrix  vx_sh_rot_from_zyz: the independent check's product
 *   apply RGB   vx_sh_rot_apply on 3 channels
 *   rotate      IR matrix + apply RGB: what turning the lighting costs
 * Each figure is the median over RUNS runs; a run repeats the operation
 * until it has taken at least 20 ms and reports the time per operation.
 * The last columns check the work: |IR - ZYZ| (largest element), and the
 * red constant term of the projection against the exact integral of the
 * radiance (relative; the pixel quadrature's own error, O(1/h^2)).
 *
 * Build and run from the repository root (after `make`), or with
 * `make -C examples/bench bench-sh`:
 *     cc -O2 $(make -s print-core-inc) -o build/shbench \
 *         examples/bench/shbench.c build/libvoxlux.a -lm -lpthread
 *     build/shbench [runs] [width]      (defaults 11, 512: 512 x 256) */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vx_sh.h"

#define PI 3.14159265358979323846

static double
now(void)
{
	struct timespec t;

	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int
cmp(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return x < y ? -1 : x > y;
}

/* the environment: directions, solid angles, RGB */
static int npix;
static double *dirs, *omega, *rgb;
static double coef[3 * VX_SH_MAX_COEF];
static double rot[VX_SH_MAX_ORDER * (4 * VX_SH_MAX_ORDER * VX_SH_MAX_ORDER - 1)
    / 3];
static double rot2[sizeof rot / sizeof rot[0]];
static double sink;

enum { PROJECT, IR, ZYZ, APPLY, ROTATE, NOP };

static void
op(int which, int order)
{
	double r[3][3];

	switch (which) {
	case PROJECT:
		memset(coef, 0, sizeof coef);
		for (int p = 0; p < npix; p++)
			vx_sh_accumulate(order, dirs + 3 * p, omega[p],
			    rgb + 3 * p, 3, coef);
		break;
	case IR:
		vx_rot3_zyz(0.3, 1.1, -0.7, r);
		vx_sh_rot_from_matrix(order, r, rot);
		break;
	case ZYZ:
		vx_sh_rot_from_zyz(order, 0.3, 1.1, -0.7, rot2);
		break;
	case APPLY:
		vx_sh_rot_apply(order, rot, 3, coef, coef);
		break;
	case ROTATE:
		vx_rot3_zyz(0.3, 1.1, -0.7, r);
		vx_sh_rot_from_matrix(order, r, rot);
		vx_sh_rot_apply(order, rot, 3, coef, coef);
		break;
	}
	sink += coef[0] + rot[vx_sh_rot_size(order) - 1] +
	    rot2[vx_sh_rot_size(order) - 1];
}

/* per_op: median over runs of the seconds per operation */
static double
per_op(int which, int order, int runs)
{
	double t[101];
	long reps = 1;

	/* calibrate: enough repetitions for 20 ms */
	for (;;) {
		double t0 = now();

		for (long k = 0; k < reps; k++)
			op(which, order);
		if (now() - t0 >= 0.02 || reps > (1L << 30))
			break;
		reps *= 2;
	}
	for (int i = 0; i < runs; i++) {
		double t0 = now();

		for (long k = 0; k < reps; k++)
			op(which, order);
		t[i] = (now() - t0) / (double)reps;
	}
	qsort(t, (size_t)runs, sizeof t[0], cmp);
	return t[runs / 2];
}

int
main(int argc, char **argv)
{
	static const int orders[] = { 3, 5, 10, 16 };
	int runs = argc > 1 ? atoi(argv[1]) : 11;
	int w = argc > 2 ? atoi(argv[2]) : 512, h = w / 2;
	double exact = (4 * PI + 2 * PI * (1 - exp(-8.0)) / 4) / sqrt(4 * PI);

	if (runs < 1 || runs > 101 || w < 2 || w > 8192) {
		fprintf(stderr, "usage: shbench [runs 1-101] [width 2-8192]\n");
		return 64;
	}
	npix = w * h;
	dirs = malloc(sizeof *dirs * 3 * (size_t)npix);
	omega = malloc(sizeof *omega * (size_t)npix);
	rgb = malloc(sizeof *rgb * 3 * (size_t)npix);
	if (!dirs || !omega || !rgb) {
		fprintf(stderr, "shbench: out of memory\n");
		return 71;
	}
	/* lat-long: row j spans theta in [j, j+1] pi / h, the pixel's solid
	 * angle (cos theta0 - cos theta1) 2 pi / w; radiance 1 + (c + 1)
	 * exp(4 (z - 1)), whose integral over the sphere is
	 * 4 pi + (c + 1) 2 pi (1 - e^-8) / 4 */
	for (int j = 0; j < h; j++)
		for (int i = 0; i < w; i++) {
			int p = j * w + i;
			double t0 = PI * j / h, t1 = PI * (j + 1) / h;
			double th = 0.5 * (t0 + t1);
			double ph = 2 * PI * (i + 0.5) / w;
			double *d = dirs + 3 * p;

			d[0] = sin(th) * cos(ph);
			d[1] = sin(th) * sin(ph);
			d[2] = cos(th);
			omega[p] = (cos(t0) - cos(t1)) * 2 * PI / w;
			for (int c = 0; c < 3; c++)
				rgb[3 * p + c] = 1 + (c + 1) *
				    exp(4 * (d[2] - 1));
		}
	printf("# shbench: %d x %d lat-long RGB environment, median of %d "
	    "runs\n", w, h, runs);
	printf("| order | projection ms | ns/pixel | IR matrix us "
	    "| ZYZ matrix us | apply RGB us | rotate us | IR-ZYZ "
	    "| c00 rel. error |\n");
	printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
	for (size_t k = 0; k < sizeof orders / sizeof orders[0]; k++) {
		int n = orders[k];
		double t[NOP], d = 0;

		for (int which = 0; which < NOP; which++)
			t[which] = per_op(which, n, runs);
		op(PROJECT, n);
		double c00 = coef[0];

		op(IR, n);
		op(ZYZ, n);
		for (size_t i = 0; i < vx_sh_rot_size(n); i++)
			d = fmax(d, fabs(rot[i] - rot2[i]));
		printf("| %d | %.2f | %.1f | %.2f | %.1f | %.2f | %.2f | %.1e "
		    "| %.1e |\n", n, t[PROJECT] * 1e3, t[PROJECT] * 1e9 / npix,
		    t[IR] * 1e6, t[ZYZ] * 1e6, t[APPLY] * 1e6, t[ROTATE] * 1e6,
		    d, fabs(c00 / exact - 1));
	}
	fprintf(stderr, "(checksum %g)\n", sink);
	free(dirs);
	free(omega);
	free(rgb);
	return 0;
}
