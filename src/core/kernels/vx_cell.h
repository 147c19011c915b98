/* vx_cell.h: ray vs trilinear cell: the cubic along a ray, its first root,
 * its exact maximum, crack-free face values, analytic gradient and normals.
 *
 * Conventions (shared by every function here):
 * - A cell's corners c[8] are floats; c[i] is the value at local corner
 *   (i&1, (i>>1)&1, (i>>2)&1) of the unit cube, as vx_grid_cell returns them.
 *   The field inside is the trilinear interpolation of the corners.
 * - Points are in cell-local index units: corner 0 at (0,0,0), corner 7 at
 *   (1,1,1).  A ray is p(t) = o + t d; o is relative to corner 0, d need not
 *   be normalized, t is the caller's ray parameter (shared across cells).
 * - All arithmetic is in double.  Every function is pure (no state, no
 *   allocation, thread-safe); callers count calls for --stats.
 * - Sign convention: f >= 0 is "inside" (sign(0) = +).  The isosurface is
 *   the boundary of the closed set {value >= iso}; a hit is a change of that
 *   sign along the ray (or a touch of zero, see vx_cell_first_root).
 *
 * Typical use by a renderer, per cell whose [min, max] brackets iso, with
 * the ray entering at t0 and leaving at t1:
 *     if (!vx_cell_finite(c)) skip the cell;
 *     f0 = vx_cell_face_value(c, entry axis, side, u, v) - iso;  (f1 alike)
 *     oc = ray origin + t0 d - cell corner 0;    (the entry point, local)
 *     vx_cell_poly(c, oc, d, iso, k);            (k in s = t - t0)
 *     if (vx_cell_first_root(k, 0, t1 - t0, f0, f1, VX_CELL_EXACT, &s, NULL))
 *         hit at t = t0 + s; vx_cell_normal(c, oc + s d, d, n);
 * Measuring t from the entry point matters: the coefficients are exact up
 * to rounding in the basis of t, so with o far from the cell (an eye 1000
 * cells away) the cubic is ill-conditioned on [t0, t1] and the root loses
 * about log10(|t|^3) digits (2e-7 of a cell at 1000 cells; a closed-form
 * solver loses as much).  The face values f0, f1 do not depend on t. */
#ifndef VX_CELL_H
#define VX_CELL_H

#include <math.h>
#include <stdint.h>

#include "vx_enum.h"

/* The inline kernels below are inlined in every caller (GCC, Clang). */
#if defined(__GNUC__)
#define VX_CELL_INLINE static inline __attribute__((always_inline))
#else
#define VX_CELL_INLINE static inline
#endif

/* Root solvers: the accuracy knob of vx_cell_first_root.  All three isolate
 * the first root identically (same hit or miss decision, same bracket);
 * they differ only in how the bracket is refined.  0 is EXACT, the default. */
typedef enum vx_cell_solver {
	VX_CELL_EXACT = 0,     /* safeguarded Halley/bisection to full precision */
	VX_CELL_NEUBAUER = 1,  /* Marmitt et al. 2004: repeated linear
	                          interpolation, VX_CELL_NEUBAUER_ITERS steps */
	VX_CELL_LINEAR = 2,    /* one linear interpolation (secant) step */
	VX_CELL_SOLVER_LAST
} vx_cell_solver;

/* Regula falsi steps of VX_CELL_NEUBAUER before its final interpolation. */
#define VX_CELL_NEUBAUER_ITERS 3
/* Iteration cap of VX_CELL_EXACT (bisection alone needs at most ~60). */
#define VX_CELL_MAXITER 100
/* Return values of vx_cell_first_root. */
enum {
	VX_CELL_MISS = 0,
	VX_CELL_CROSS = 1,  /* f changes sign at *t */
	VX_CELL_TOUCH = 2   /* f touches zero at a critical point *t */
};

/* Paths taken by vx_cell_normal. */
enum {
	VX_NORMAL_NONE = 0,      /* d was zero or not finite: n = (0,0,0) */
	VX_NORMAL_GRADIENT = 1,  /* the analytic gradient at p */
	VX_NORMAL_CENTER = 2,    /* gradient vanished: central differences of
	                            the face averages (the gradient at the cell
	                            centre) */
	VX_NORMAL_RAY = 3        /* both vanished: -d normalized */
};

/* The solvers' names (vx_enum.h): "exact", "neubauer", "linear"; -1 and
 * "unknown" for the others. */
extern const vx_enum vx_cell_solver_enum;

/* vx_cell_finite: 1 if all eight corners are finite, else 0.  A cell with a
 * NaN or infinite corner has no surface: callers skip it (the functions
 * below also never report a hit or a maximum from such a cell). */
int vx_cell_finite(const float c[8]);

/* vx_cell_trilinear: the trilinear value at p (any p; outside the unit cube
 * it extrapolates).  Nested linear interpolation along x, then y, then z. */
double vx_cell_trilinear(const float c[8], const double p[3]);

/* vx_cell_poly: coefficients of f(t) = trilinear(o + t d) - iso
 * = k[0] + k[1] t + k[2] t^2 + k[3] t^3.  Exact up to rounding; linear in
 * (c, iso), so scaling both by 2^k scales k exactly.  k[3] is 0 when any
 * component of d is 0 (axis-parallel rays: k[2] too when two are 0).
 * Non-finite corners give non-finite k (vx_cell_first_root then misses). */
void vx_cell_poly(const float c[8], const double o[3], const double d[3],
    double iso, double k[4]);

/* vx_cell_poly_eval: f(t) by Horner's rule. */
static inline double
vx_cell_poly_eval(const double k[4], double t)
{
	return ((k[3] * t + k[2]) * t + k[1]) * t + k[0];
}

/* vx_cell_poly_inline: vx_cell_poly itself (the same operations in the
 * same order, so the same bits), inlined where the caller wants it (MIP's
 * cell walks).
 *
 * The cubic along the ray.  Derived here again (Parker et al. 1999,
 * Appendix A, is garbled in our copy: its fractions lost their bars, so
 * "x_1 - x_a x_1 - x_0" is (x_1 - x_a)/(x_1 - x_0), and the signs of b_0 and
 * b_1 are swapped: u_0 = (x_1 - x)/(x_1 - x_0) decreases along the ray, so
 * b_0 = -x_b/(x_1 - x_0) and b_1 = +x_b/(x_1 - x_0)).  Its sum over
 * (u_i^a + t u_i^b)(v_j^a + t v_j^b)(w_k^a + t w_k^b) rho_ijk is the same
 * polynomial as the nested interpolation used here, which is cheaper and
 * better conditioned for o near the cell:
 *   x(t) = o_x + t d_x, and likewise y(t), z(t);
 *   edge along x at (y,z) = (j&1, j>>1):  e_j(t) = c[2j] + (c[2j+1] - c[2j]) x(t)
 *     = A_j + B_j t,  A_j = c[2j] + D_j o_x,  B_j = D_j d_x,  D_j = c[2j+1] - c[2j];
 *   face z = s:  P_s(t) = e_{2s} + (e_{2s+1} - e_{2s}) y(t)
 *     = (A_{2s} + dA o_y) + (B_{2s} + dA d_y + dB o_y) t + dB d_y t^2
 *     with dA = A_{2s+1} - A_{2s}, dB = B_{2s+1} - B_{2s};
 *   cell:  f(t) = P_0 + (P_1 - P_0) z(t) - iso, with Q = P_1 - P_0:
 *     k0 = P_0[0] + Q[0] o_z - iso
 *     k1 = P_0[1] + Q[0] d_z + Q[1] o_z
 *     k2 = P_0[2] + Q[1] d_z + Q[2] o_z
 *     k3 = Q[2] d_z.
 * Expanded, k3 = (c7 - c6 - c5 + c4 - c3 + c2 + c1 - c0) d_x d_y d_z: Parker's
 * A.  Every step is linear in (c, iso), so 2^k scaling is exact. */
VX_CELL_INLINE void
vx_cell_poly_inline(const float c[8], const double o[3], const double d[3],
    double iso, double k[4])
{
	double A[4], B[4], P[2][3], Q[3];
	int j, s;

	for (j = 0; j < 4; j++) {
		double D = (double)c[2 * j + 1] - (double)c[2 * j];

		A[j] = c[2 * j] + D * o[0];
		B[j] = D * d[0];
	}
	for (s = 0; s < 2; s++) {
		double dA = A[2 * s + 1] - A[2 * s], dB = B[2 * s + 1] - B[2 * s];

		P[s][0] = A[2 * s] + dA * o[1];
		P[s][1] = B[2 * s] + dA * d[1] + dB * o[1];
		P[s][2] = dB * d[1];
	}
	for (j = 0; j < 3; j++)
		Q[j] = P[1][j] - P[0][j];
	k[0] = (P[0][0] + Q[0] * o[2]) - iso;
	k[1] = P[0][1] + Q[0] * d[2] + Q[1] * o[2];
	k[2] = P[0][2] + Q[1] * d[2] + Q[2] * o[2];
	k[3] = Q[2] * d[2];
}

/* vx_cell_crit_points: the critical points of the cubic k strictly inside
 * (t0, t1), ascending, into r: the zeros of f' = a t^2 + b t + c (a = 3 k3,
 * b = 2 k2, c = k1) by the stable quadratic formula, the discriminant by
 * Kahan's fma difference of products (accurate when the two critical points
 * nearly coincide).  a == 0 (or tiny) needs no special case beyond a == 0
 * exactly: the large root then leaves the interval and the small one is
 * c/q.  ext[i] is 1 for an extremum (f' changes sign), 0 for the
 * inflection of a double zero of f' (discriminant exactly 0: f is monotone
 * through it, so it is no touch; ext may be NULL).  Returns their number
 * (0..2). */
VX_CELL_INLINE int
vx_cell_crit_points(const double k[4], double t0, double t1, double r[2],
    int ext[2])
{
	double a = 3 * k[3], b = 2 * k[2], c = k[1];
	double x[2];
	int n = 0, m = 0, i, e2 = 1;

	if (a == 0) {
		if (b != 0)
			x[n++] = -c / b;
	} else {
		double w = 4 * a * c, bb = b * b;
		double disc = bb - w;

		/* Kahan's fma difference of products where it cancels (the
		 * critical points nearly coincide); fma is a library call */
		if (fabs(disc) < 0x1p-20 * bb)
			disc = fma(b, b, -w) + fma(-4 * a, c, w);
		/* disc < 0 or NaN: none */
		if (disc == 0) {
			x[n++] = -b / (2 * a);
			e2 = 0;
		} else if (disc > 0) {
			double q = -0.5 * (b + copysign(sqrt(disc), b));

			x[n++] = q / a;
			x[n++] = c / q;
		}
	}
	for (i = 0; i < 2; i++)    /* a fixed count: unrolled where inlined */
		if (i < n && x[i] > t0 && x[i] < t1) {   /* false for NaN */
			if (ext)
				ext[m] = e2;
			r[m++] = x[i];
		}
	if (m == 2 && r[0] > r[1]) {
		double s = r[0];
		r[0] = r[1];
		r[1] = s;
	}
	if (m == 2 && r[0] == r[1])
		m = 1;
	return m;
}

/* vx_cell_argmax: where the cubic k is largest among t0, its critical
 * points strictly inside (t0, t1) and t1, by Horner's values, the smallest
 * t among equal values: vx_cell_max's *tmax for a k it need not rescale.
 * For finite k, t0, t1 with t0 <= t1. */
VX_CELL_INLINE double
vx_cell_argmax(const double k[4], double t0, double t1)
{
	double r[2], bt = t0, bf = vx_cell_poly_eval(k, t0), f;
	int m = vx_cell_crit_points(k, t0, t1, r, NULL), i;

	for (i = 0; i < m; i++) {
		f = vx_cell_poly_eval(k, r[i]);
		if (f > bf) {
			bf = f;
			bt = r[i];
		}
	}
	f = vx_cell_poly_eval(k, t1);
	return f > bf ? t1 : bt;
}

/* vx_cell_face_value: the bilinear value on face (axis, side) (axis 0..2,
 * side 0 or 1: the face where coordinate `axis` is `side`) at in-face
 * coordinates (u, v), u along the lower and v along the higher of the other
 * two axes.  Crack-free contract: the result depends only on the 4 corners
 * of that face, taken in an order fixed by their in-face position, and on
 * (u, v); so two cells sharing a face give bit-identical values for the same
 * (u, v).  u and v are clamped into [0, 1] and the result into [min, max]
 * of the 4 corners.  A NaN or infinite corner on the face gives NaN, and
 * so does NaN u or v (vx_cell_first_root then misses). */
double vx_cell_face_value(const float c[8], int axis, int side, double u,
    double v);

/* vx_cell_face_value_fin: vx_cell_face_value inlined for renderers' inner
 * loops, for axis 0..2, side 0 or 1 and a face whose four corners are
 * finite (e.g. vx_cell_finite(c)); vx_cell_face_value is this after its
 * checks, so the two give the same bits. */
static inline double
vx_cell_face_value_fin(const float c[8], int axis, int side, double u,
    double v)
{
	int base = side << axis, bu = axis == 0 ? 2 : 1, bv = axis == 2 ? 2 : 4;
	double c00 = c[base], c10 = c[base | bu], c01 = c[base | bv];
	double c11 = c[base | bu | bv], e0, e1, r, lo, hi;

	/* clamps written so that NaN passes through */
	u = u < 0 ? 0 : u > 1 ? 1 : u;
	v = v < 0 ? 0 : v > 1 ? 1 : v;
	e0 = c00 + (c10 - c00) * u;
	e1 = c01 + (c11 - c01) * u;
	r = e0 + (e1 - e0) * v;
	lo = c00 < c10 ? c00 : c10;
	hi = c00 < c10 ? c10 : c00;
	lo = c01 < lo ? c01 : lo;
	hi = c01 > hi ? c01 : hi;
	lo = c11 < lo ? c11 : lo;
	hi = c11 > hi ? c11 : hi;
	return r < lo ? lo : r > hi ? hi : r;   /* NaN u or v stays NaN */
}

/* vx_cell_first_root: the first t in [t0, t1] where f (coefficients k)
 * changes sign or touches zero.  f0 and f1 are the caller's values at t0 and
 * t1 (face values minus iso, so neighbouring cells agree on the sign at
 * their shared face; f(t0) and f(t1) from k are never used).
 * Method: the sign sequence f0, f(c_1), ..., f(c_m), f1 over the critical
 * points c_i of f strictly inside (t0, t1) (zeros of f', stable quadratic
 * formula; none where f' provably keeps one sign on [t0, t1], its three
 * Bernstein coefficients beyond a margin rounding cannot close, so that
 * most hits skip the square root and divisions) decides: the first
 * segment whose ends differ in sign holds the
 * first crossing (f is monotone there, so exactly one).  The critical
 * points' number, order and the sign of f at each are exact for the
 * cubic k as given (its coefficients and t0, t1 taken as exact numbers):
 * signs of small polynomials in them (the discriminants of f and f', f'(t0),
 * f'(t1), f at the inflection), each evaluated in double with a proven
 * error bound and, where the bound cannot decide, exactly in binary big
 * numbers (cell.c; vx_cell_first_root_x counts those).  So an extremum
 * where f is exactly zero ending a segment at or before that one is a
 * touch, reported at the extremum (approximated to rounding: the stable
 * quadratic formula), and one where f misses zero by any amount is none:
 * no exact touch is missed and no near-miss is a hit; where f crosses
 * zero beside an extremum by any amount, the two crossings are found.
 * Touches exactly at t0 or t1 (on a cell face) are the caller's: see
 * vx_iso.h.  An inflection where f' has a double zero (e.g. a triple
 * root) is no touch.  A leading
 * coefficient that is zero or tiny needs no special case.  The bracket is
 * then refined by `solver`:
 *   VX_CELL_EXACT: Halley steps (cubically convergent, from the secant
 *     point) kept inside the bracket, bisection when they leave it,
 *     converge slowly or fall below a quarter of Newton's step, until the
 *     bracket is 4 ulp of max(|t0|,|t1|) wide, f(t) == 0, or the step (or
 *     Halley's error estimate for the next iterate, |f''^2 / (4 f'^2) -
 *     f''' / (6 f')| step^3) is at most half of that: the root of the
 *     computed cubic to full precision (error about rounding(f) / |f'(t)|
 *     beyond that; test_cell checks 4 ulp plus 8 u terms(t) / |f'(t)|
 *     against a long double oracle).  2.3-3.2 evaluations a crossing
 *     (Newton steps took 4.6-7.1).
 *   VX_CELL_NEUBAUER: VX_CELL_NEUBAUER_ITERS steps of regula falsi, then a
 *     final linear interpolation; guaranteed only to lie in the last
 *     bracket.  Plain regula falsi stalls when one end of the bracket is an
 *     extremum (f flat there), so the tail is long: measured error in units
 *     of the segment t1 - t0 (examples/bench/cellbench.c), median / 99% /
 *     max: 2e-6 / 0.02 / 0.065 on a smooth field, 6e-5 / 0.05 / 0.26 on
 *     rough random u8 cells.
 *   VX_CELL_LINEAR: one linear interpolation between the bracket's ends;
 *     within the bracket, error second order in its width; measured 0.02 /
 *     0.21 / 0.26 (smooth), 0.06 / 0.25 / 0.40 (rough).
 * Every result is clamped into the isolated bracket, so within [t0, t1].
 * Touch hits are the critical point itself for every solver, and a bracket
 * end where the sequence is exactly 0 is returned as is (a surface through
 * a shared face is hit exactly there, and only once along the ray).
 * Returns VX_CELL_MISS (0, *t untouched), VX_CELL_CROSS or VX_CELL_TOUCH.
 * No hit when t0 > t1, or when any input is not finite.  k all zero (all
 * corners equal the isovalue, or a ray in a face at the isovalue): f is 0,
 * i.e. inside, along the whole segment: no hit, unless f0 and f1 differ in
 * sign (then the hit is the sign change, as for any cubic).  Rationale: the
 * surface is the boundary of {f >= 0}; the cell lies inside that set, and
 * where the set ends, the neighbouring cell sees f go from negative to 0 at
 * the shared face and reports the hit there (once).
 * With t0 == t1 the answer is t0 if f0 and f1 differ in sign.
 * iters (may be NULL) gets the number of polynomial evaluations spent in
 * refinement (0 for a touch or a miss). */
int vx_cell_first_root(const double k[4], double t0, double t1, double f0,
    double f1, int solver, double *t, int *iters);

/* vx_cell_first_root_x: vx_cell_first_root, adding to *exact (when not
 * NULL) the number of signs its filter could not decide and that were
 * evaluated exactly (the slow path; --stats and the benchmarks count it). */
int vx_cell_first_root_x(const double k[4], double t0, double t1, double f0,
    double f1, int solver, double *t, int *iters, unsigned *exact);

/* vx_cell_end_sign: the sign of f (coefficients k) just before t1, on
 * (t1 - e, t1) for every small e > 0, where f0 is the caller's value at
 * t0 (its sign only) and no root of f lies in (t0, t1) but at critical
 * points: the last nonzero one of f0's sign and the exact signs of f at
 * the critical points strictly inside (t0, t1) (f is monotone between
 * them).  For a caller whose segment ends at a zero of f (a face value
 * exactly 0) and that found no hit on it: +1 when f came down to that
 * zero from above, -1 from below, 0 when f is zero all along (or input is
 * not finite, or t0 >= t1). */
int vx_cell_end_sign(const double k[4], double t0, double t1, double f0);

/* vx_cell_sign_bound: a cheap, exact early-out for vx_cell_first_root on
 * [0, len] (t measured from the entry point, as in the typical use above).
 * Returns +1 when the cubic k provably stays positive on [0, len] by a
 * margin that rounding cannot close, -1 when it provably stays negative, 0
 * when it cannot tell (then call vx_cell_first_root).  Guarantee, for every
 * solver: if it returns +1 and f0 >= 0 and f1 >= 0, or -1 and f0 < 0 and
 * f1 < 0, then vx_cell_first_root(k, 0, len, f0, f1, solver, ...) returns
 * VX_CELL_MISS.  (Only the signs of f0 and f1 are needed, so a caller can
 * often skip computing them.)  Method: the Bernstein coefficients of f on
 * [0, len] all of one sign with margin 2^-38 times the sum of the terms'
 * magnitudes; the proof is in cell.c.  0 for non-finite input, len < 0 or
 * > 2^100, or coefficients outside [2^-400, 2^400). */
int vx_cell_sign_bound(const double k[4], double len);

/* vx_cell_sign_bound_b3: vx_cell_sign_bound inlined for renderers' inner
 * loops (the same answer), with *b3 its computed last Bernstein
 * coefficient, k's value at len within 8 u S (cell.c's proof) when the
 * answer is nonzero (else unset). */
static inline int
vx_cell_sign_bound_b3(const double k[4], double len, double *b3)
{
	double m0 = fabs(k[0]), m1 = fabs(k[1]), m2 = fabs(k[2]);
	double m3 = fabs(k[3]), mx, a1, a2, a3, b1, b2, s, lo;

	if (!(len >= 0 && len <= 0x1p100))
		return 0;
	if (!(m0 < 0x1p400 && m1 < 0x1p400 && m2 < 0x1p400 && m3 < 0x1p400))
		return 0;
	mx = m0 > m1 ? m0 : m1;
	mx = m2 > mx ? m2 : mx;
	mx = m3 > mx ? m3 : mx;
	if (!(mx > 0x1p-400))
		return 0;
	a1 = k[1] * len;
	a2 = k[2] * len * len;
	a3 = k[3] * len * len * len;
	s = m0 + fabs(a1) + fabs(a2) + fabs(a3);
	if (!(s >= 0x1p-600))
		return 0;
	lo = 0x1p-38 * s;
	/* thirds by a product, not a division (cell.c's proof counts the
	 * constant's rounding): two divisions less on every grazed cell's
	 * path to its answer */
	b1 = k[0] + a1 * (1.0 / 3);
	b2 = k[0] + (2 * a1 + a2) * (1.0 / 3);
	*b3 = k[0] + a1 + a2 + a3;
	if (k[0] > lo && b1 > lo && b2 > lo && *b3 > lo)
		return 1;
	if (k[0] < -lo && b1 < -lo && b2 < -lo && *b3 < -lo)
		return -1;
	return 0;
}

/* vx_cell_poly_low: a lower bound of the cubic k's exact value at t (k
 * and t taken as exact): k[0] itself at t == 0 (Horner is exact there),
 * else Horner's value less its error bound, 2^-50 times the terms'
 * magnitudes (over gamma_6 of them, Higham's bound for degree 3) plus
 * 2^-1067 (gradual underflow), and then the next double below (the
 * subtraction's own rounding): never above k's value at t, at most a few
 * units of Horner's rounding below it.  For finite k and t. */
static inline double
vx_cell_poly_low(const double k[4], double t)
{
	union { double d; uint64_t u; } v;
	double a = fabs(t);

	if (t == 0)
		return k[0];
	v.d = ((k[3] * t + k[2]) * t + k[1]) * t + k[0];
	v.d -= 0x1p-50 * (fabs(k[0]) + a * (fabs(k[1]) + a * (fabs(k[2]) +
	    a * fabs(k[3])))) + 0x1p-1067;
	if (v.d > 0)
		v.u--;
	else if (v.d < 0)
		v.u++;
	else
		v.d = -0x1p-1074;
	return v.d;
}

/* vx_cell_max: the exact maximum of the cubic k on [t0, t1]: the larger of
 * the ends and the critical points inside (stable quadratic formula), ties
 * broken by the smallest t.  Returns 1 and sets *tmax, *fmax; returns 0 (no
 * value: *tmax = 0, *fmax = -INFINITY) if any input is not finite or
 * t0 > t1.  For maximum-intensity projection pass iso = 0 to vx_cell_poly
 * and, as above, measure t from the cell's entry point.  The value is that
 * of the computed cubic (the ends are not replaced by face values) at
 * *tmax, rounded down (vx_cell_poly_low): never above the cubic's exact
 * maximum on [t0, t1], whatever rounding did to the choice of *tmax (a
 * maximum reached at an interior critical point is approximated from
 * below), and below it by at most the rounding of the candidates'
 * values (a few units of 2^-50 times the terms' magnitudes). */
int vx_cell_max(const double k[4], double t0, double t1, double *tmax,
    double *fmax);

/* vx_cell_gradient: the analytic gradient of the trilinear field at p, in
 * index units (value per cell edge): g[a] is the bilinear interpolation of
 * the four edge differences along axis a. */
void vx_cell_gradient(const float c[8], const double p[3], double g[3]);

/* vx_cell_normal_thresh: the size at or below which a gradient counts as
 * vanishing for vx_cell_normal: 2^-40 times the corners' range (NaN corners
 * skipped; not finite when the range is not). */
double vx_cell_normal_thresh(const float c[8]);

/* vx_cell_normal: unit normal at p with n . d <= 0 (facing the ray).
 * Uses the gradient at p; if it is not finite or |g| <= 2^-40 times the
 * corners' range, the gradient at the cell centre (central differences of
 * the face averages); if that vanishes too, -d normalized.  Returns the path
 * taken (VX_NORMAL_*); n is never NaN. */
int vx_cell_normal(const float c[8], const double p[3], const double d[3],
    double n[3]);

#endif
