/* cellbench.c: speed and accuracy of the ray vs trilinear cell root solvers
 * (VX_CELL_EXACT, VX_CELL_NEUBAUER, VX_CELL_LINEAR) on random cells, with a
 * closed-form cubic (Schwarze-style Cardano, as Parker et al. used) for
 * comparison.  Prints ns per call (median of runs) and the error of each
 * solver's t against EXACT.
 *
 * Build and run from the repository root (after `make`):
 *     cc -O2 -Isrc/core -o build/cellbench examples/bench/cellbench.c \
 *         build/libvoxlux.a -lm && build/cellbench [ncases] [runs]
 * Cells are random (hash-based, reproducible); each ray joins random points
 * on two faces of the cell and t runs over [0, 1], so errors are in units
 * of the segment's length.  "all" times vx_cell_poly + vx_cell_first_root
 * over every case (hits and misses); "hits" times vx_cell_first_root alone
 * over the cases that hit. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vx_cell.h"

typedef struct bcase {
	float c[8];
	double o[3], d[3], iso, f0, f1, k[4];
} bcase;

static uint64_t
mix(uint64_t x)
{
	x += 0x9e3779b97f4a7c15ULL;
	x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
	x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
	return x ^ (x >> 31);
}

static double
uni(uint64_t i, uint64_t j)
{
	return (double)(mix(mix(i) ^ j) >> 11) * 0x1p-53;
}

static int family;   /* 0: rough u8-like corners, 1: smooth field */

static void
gen(uint64_t i, bcase *b)
{
	static const int ua[3] = { 1, 0, 0 }, va[3] = { 2, 2, 1 };
	double lo = INFINITY, hi = -INFINITY, P[3], Q[3];
	int ap = (int)(uni(i, 11) * 3), sp = uni(i, 12) < 0.5;
	int aq = (int)(uni(i, 13) * 3), sq = uni(i, 14) < 0.5;
	double up = uni(i, 16), vp = uni(i, 17), uq = uni(i, 18), vq = uni(i, 19);

	for (int j = 0; j < 8; j++) {
		if (family == 0) {
			b->c[j] = (float)floor(256 * uni(i, (uint64_t)j));  /* u8-like */
		} else {
			/* a smooth field: three plane waves, wavelength 8 cells,
			 * sampled around a random cell position */
			double v = 0;
			for (int w = 0; w < 3; w++) {
				double ph = 0;
				for (int a = 0; a < 3; a++) {
					double x = 50 * uni(i, (uint64_t)(40 + a)) +
					    ((j >> a) & 1);
					ph += (2 * uni(77, (uint64_t)(3 * w + a)) - 1) * x;
				}
				v += sin(2 * 3.14159265358979 * ph / 8 + w);
			}
			b->c[j] = (float)(100 * v);
		}
		lo = fmin(lo, b->c[j]);
		hi = fmax(hi, b->c[j]);
	}
	if (aq == ap && sq == sp)
		sq = !sp;
	P[ap] = sp; P[ua[ap]] = up; P[va[ap]] = vp;
	Q[aq] = sq; Q[ua[aq]] = uq; Q[va[aq]] = vq;
	for (int a = 0; a < 3; a++) {
		b->o[a] = P[a];
		b->d[a] = Q[a] - P[a];
	}
	b->iso = lo + (hi - lo) * uni(i, 8);
	if (family == 0)
		b->iso = floor(b->iso) + 0.5;
	b->f0 = vx_cell_face_value(b->c, ap, sp, up, vp) - b->iso;
	b->f1 = vx_cell_face_value(b->c, aq, sq, uq, vq) - b->iso;
	vx_cell_poly(b->c, b->o, b->d, b->iso, b->k);
}

/* Closed-form cubic after Schwarze (Graphics Gems, 1990), with Parker's
 * changes (quadratic/linear fallbacks, EQN_EPS 1e-30): smallest root in
 * [t0, t1], or 0. */
static int
cardano_first(const double k[4], double t0, double t1, double *t)
{
	double r[3], best = INFINITY;
	int n = 0;
	const double eps = 1e-30;

	if (fabs(k[3]) < eps) {
		if (fabs(k[2]) < eps) {
			if (fabs(k[1]) < eps)
				return 0;
			r[n++] = -k[0] / k[1];
		} else {
			double p = k[1] / (2 * k[2]), q = k[0] / k[2], D = p * p - q;
			if (D >= 0) {
				r[n++] = -p - sqrt(D);
				r[n++] = -p + sqrt(D);
			}
		}
	} else {
		double A = k[2] / k[3], B = k[1] / k[3], C = k[0] / k[3];
		double sq_A = A * A;
		double p = (-sq_A / 3 + B) / 3;
		double q = (2.0 / 27 * A * sq_A - A * B / 3 + C) / 2;
		double cb_p = p * p * p, D = q * q + cb_p;

		if (fabs(D) < eps) {
			if (fabs(q) < eps) {
				r[n++] = 0;
			} else {
				double u = cbrt(-q);
				r[n++] = 2 * u;
				r[n++] = -u;
			}
		} else if (D < 0) {
			double phi = acos(-q / sqrt(-cb_p)) / 3, s = 2 * sqrt(-p);
			r[n++] = s * cos(phi);
			r[n++] = -s * cos(phi + (3.14159265358979323846 / 3));
			r[n++] = -s * cos(phi - (3.14159265358979323846 / 3));
		} else {
			double sqD = sqrt(D);
			r[n++] = cbrt(sqD - q) - cbrt(sqD + q);
		}
		for (int i = 0; i < n; i++)
			r[i] -= A / 3;
	}
	for (int i = 0; i < n; i++)
		if (r[i] >= t0 && r[i] <= t1 && r[i] < best)
			best = r[i];
	if (best == INFINITY)
		return 0;
	*t = best;
	return 1;
}

/* The unit tests' hard cases, exact vs the closed form. */
static void
hard_cases(void)
{
	static const float dbl[8] = { 0, 0, 0, 0, 0, 0, 0, 27 };
	static const float cb[8] = { 1, -1, -1, 1, -1, 1, 1, -1 };
	static const float mix8[8] = { 0.5f, 3, -1, 2, 1.25f, -2, 4, 0 };
	static const struct {
		const char *name;
		const float *c;
		double o[3], d[3], iso;
	} h[] = {
		{ "double root, touch (iso 4, t 2/3)", dbl, { 0, 0, 1 }, { 1, 1, -1 }, 4 },
		{ "double root, cross (iso 1)", dbl, { 0, 0, 1 }, { 1, 1, -1 }, 1 },
		{ "triple root (iso 0, t 1/2)", cb, { 0, 0, 0 }, { 1, 1, 1 }, 0 },
		{ "near triple root (iso 1e-9)", cb, { 0, 0, 0 }, { 1, 1, 1 }, 1e-9 },
		{ "tiny k3 (d = 1, 1e-9, -1e-9)", mix8, { 0, 0.25, 0.5 }, { 1, 1e-9, -1e-9 }, NAN },
		{ "far origin (t in [1000,1001])", dbl, { -1000, -1000, 1001 }, { 1, 1, -1 }, 1 },
		{ "same, t from the entry point", dbl, { 0, 0, 1 }, { 1, 1, -1 }, 1 },
	};

	printf("%-34s %-22s %-22s\n", "hard case", "exact t", "cardano t");
	for (size_t i = 0; i < sizeof h / sizeof h[0]; i++) {
		double k[4], p0[3], p1[3], t0 = 0, t1 = 1, te = NAN, tc = NAN;
		double iso = h[i].iso, add = i == 6 ? 1000 : 0;
		char se[32], sc[32];

		if (h[i].o[0] == -1000) {
			t0 = 1000;
			t1 = 1001;
		}
		for (int a = 0; a < 3; a++) {
			p0[a] = h[i].o[a] + t0 * h[i].d[a];
			p1[a] = h[i].o[a] + t1 * h[i].d[a];
		}
		if (isnan(iso)) {   /* the field 37% of the way: a root exists */
			double q[3];
			for (int a = 0; a < 3; a++)
				q[a] = h[i].o[a] + 0.37 * h[i].d[a];
			iso = vx_cell_trilinear(h[i].c, q);
		}
		vx_cell_poly(h[i].c, h[i].o, h[i].d, iso, k);
		if (!vx_cell_first_root(k, t0, t1,
		    vx_cell_trilinear(h[i].c, p0) - iso,
		    vx_cell_trilinear(h[i].c, p1) - iso, VX_CELL_EXACT, &te,
		    NULL))
			te = NAN;
		if (!cardano_first(k, t0, t1, &tc))
			tc = NAN;
		te += add;
		tc += add;
		snprintf(se, sizeof se, isnan(te) ? "miss" : "%.17g", te);
		snprintf(sc, sizeof sc, isnan(tc) ? "miss" : "%.17g", tc);
		printf("%-34s %-22s %-22s\n", h[i].name, se, sc);
	}
}

static double
now(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);  /* CPU time: the machine is shared */
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static int
cmpd(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return x < y ? -1 : x > y;
}

static double
median(double *v, int n)
{
	qsort(v, (size_t)n, sizeof *v, cmpd);
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int
main(int argc, char **argv)
{
	int n = argc > 1 ? atoi(argv[1]) : 20000;
	int runs = argc > 2 ? atoi(argv[2]) : 11;
	bcase *b = malloc((size_t)n * sizeof *b);
	int *hit = malloc((size_t)n * sizeof *hit);
	int *hidx = malloc((size_t)n * sizeof *hidx);
	double *tex = malloc((size_t)n * sizeof *tex);
	double *err = malloc((size_t)n * sizeof *err);
	double *rt = malloc((size_t)runs * sizeof *rt);
	volatile double sink = 0;
	int nhit = 0;

	if (!b || !hit || !hidx || !tex || !err || !rt || n < 1 || runs < 1)
		return 1;
	for (family = 0; family < 2; family++) {
	nhit = 0;
	for (int i = 0; i < n; i++) {
		gen((uint64_t)i, &b[i]);
		hit[i] = vx_cell_first_root(b[i].k, 0, 1, b[i].f0, b[i].f1,
		    VX_CELL_EXACT, &tex[i], NULL);
		if (hit[i])
			hidx[nhit++] = i;
	}
	printf("%s: %d cases, %d hit; median of %d runs\n", family ?
	    "smooth field (3 plane waves, wavelength 8 cells)" :
	    "rough cells (u8-like random corners)", n, nhit, runs);
	printf("%-9s %9s %9s %9s %11s %11s %11s %6s\n", "solver", "ns/hits",
	    "ns/all", "evals", "err med", "err 99%", "err max", "diff");
	for (int s = 0; s <= VX_CELL_SOLVER_LAST; s++) {
		const char *name = s < VX_CELL_SOLVER_LAST ?
		    vx_enum_str(&vx_cell_solver_enum, s) : "cardano";
		double ns_hit, ns_all, t;
		long evals = 0;
		int ne = 0, diff = 0;

		/* hits only: root solve from precomputed k (each run repeats
		 * the set until it has taken 50 ms, to ride out scheduling) */
		for (int r = 0; r < runs; r++) {
			double t0 = now(), t1;
			long calls = 0;
			do {
				for (int j = 0; j < nhit; j++) {
					const bcase *c = &b[hidx[j]];
					if (s < VX_CELL_SOLVER_LAST)
						vx_cell_first_root(c->k, 0, 1, c->f0,
						    c->f1, s, &t, NULL);
					else
						cardano_first(c->k, 0, 1, &t);
					sink += t;
				}
				calls += nhit;
			} while ((t1 = now()) - t0 < 0.05);
			rt[r] = (t1 - t0) / calls * 1e9;
		}
		ns_hit = median(rt, runs);
		/* all cases: coefficients + solve, as a renderer pays */
		for (int r = 0; r < runs; r++) {
			double t0 = now(), t1, k[4];
			long calls = 0;
			do {
				for (int i = 0; i < n; i++) {
					vx_cell_poly(b[i].c, b[i].o, b[i].d, b[i].iso, k);
					t = 0;
					if (s < VX_CELL_SOLVER_LAST)
						vx_cell_first_root(k, 0, 1, b[i].f0,
						    b[i].f1, s, &t, NULL);
					else
						cardano_first(k, 0, 1, &t);
					sink += t;
				}
				calls += n;
			} while ((t1 = now()) - t0 < 0.05);
			rt[r] = (t1 - t0) / calls * 1e9;
		}
		ns_all = median(rt, runs);
		/* accuracy against EXACT, and hit/miss disagreements */
		for (int i = 0; i < n; i++) {
			int it = 0, h;
			if (s < VX_CELL_SOLVER_LAST)
				h = vx_cell_first_root(b[i].k, 0, 1, b[i].f0,
				    b[i].f1, s, &t, &it);
			else
				h = cardano_first(b[i].k, 0, 1, &t);
			evals += it;
			if ((h != 0) != (hit[i] != 0)) {
				diff++;
				continue;
			}
			if (h)
				err[ne++] = fabs(t - tex[i]);
		}
		qsort(err, (size_t)ne, sizeof *err, cmpd);
		printf("%-9s %9.1f %9.1f %9.2f %11.3g %11.3g %11.3g %6d\n", name,
		    ns_hit, ns_all, nhit ? (double)evals / nhit : 0,
		    ne ? err[ne / 2] : 0, ne ? err[(int)(0.99 * (ne - 1))] : 0,
		    ne ? err[ne - 1] : 0, diff);
	}
	}
	printf("(evals: refinement evaluations per hit; diff: cases whose hit or"
	    " miss differs from exact)\n\n");
	hard_cases();
	free(b);
	free(hit);
	free(hidx);
	free(tex);
	free(err);
	free(rt);
	return sink == 12345.678;
}
