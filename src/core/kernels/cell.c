/* cell.c: ray vs trilinear cell: cubic coefficients, robust first root,
 * exact maximum, crack-free face values, gradient and normals. */
#include "vx_cell.h"

#include <math.h>
#include <string.h>

static const vx_enum_name solver_names[] = {
	{ "exact", VX_CELL_EXACT }, { "neubauer", VX_CELL_NEUBAUER },
	{ "linear", VX_CELL_LINEAR }, { NULL, -1 }
};
const vx_enum vx_cell_solver_enum = { "solver", solver_names, "unknown", 0 };

const char *
vx_cell_solver_name(int solver)
{
	return vx_enum_str(&vx_cell_solver_enum, solver);
}

int
vx_cell_solver_parse(const char *s)
{
	return vx_enum_val(&vx_cell_solver_enum, s);
}

int
vx_cell_finite(const float c[8])
{
	int i;

	for (i = 0; i < 8; i++)
		if (!isfinite(c[i]))
			return 0;
	return 1;
}

static inline double
lerp(double a, double b, double s)
{
	return a + (b - a) * s;
}

double
vx_cell_trilinear(const float c[8], const double p[3])
{
	double e0 = lerp(c[0], c[1], p[0]), e1 = lerp(c[2], c[3], p[0]);
	double e2 = lerp(c[4], c[5], p[0]), e3 = lerp(c[6], c[7], p[0]);

	return lerp(lerp(e0, e1, p[1]), lerp(e2, e3, p[1]), p[2]);
}

/* The cubic along the ray.  Derived here again (Parker et al. 1999,
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
void
vx_cell_poly(const float c[8], const double o[3], const double d[3],
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

double
vx_cell_poly_eval(const double k[4], double t)
{
	return ((k[3] * t + k[2]) * t + k[1]) * t + k[0];
}

/* f' and f'' at t */
static inline double
deriv1(const double k[4], double t)
{
	return (3 * k[3] * t + 2 * k[2]) * t + k[1];
}

static inline double
deriv2(const double k[4], double t)
{
	return 6 * k[3] * t + 2 * k[2];
}

/* f, f' and f'' together. */
static inline double
eval3(const double k[4], double t, double *df, double *d2f)
{
	*d2f = deriv2(k, t);
	*df = deriv1(k, t);
	return ((k[3] * t + k[2]) * t + k[1]) * t + k[0];
}

/* Sum of the terms' magnitudes at t: the scale of f's rounding error. */
static inline double
terms(const double k[4], double t)
{
	double a = fabs(t);

	return fabs(k[0]) + a * (fabs(k[1]) + a * (fabs(k[2]) + a * fabs(k[3])));
}

double
vx_cell_face_value(const float c[8], int axis, int side, double u, double v)
{
	/* in-face axes: the other two, in increasing order */
	static const int ua[3] = { 1, 0, 0 }, va[3] = { 2, 2, 1 };
	int base;

	if (axis < 0 || axis > 2)
		return NAN;
	base = (side ? 1 : 0) << axis;
	/* Inf - Inf is NaN too */
	if (!isfinite((double)c[base] + c[base | 1 << ua[axis]] +
	    c[base | 1 << va[axis]] + c[base | 1 << ua[axis] | 1 << va[axis]]))
		return NAN;
	return vx_cell_face_value_fin(c, axis, side ? 1 : 0, u, v);
}

/* Critical points of the cubic strictly inside (t0, t1), ascending: the
 * zeros of f' = a t^2 + b t + c (a = 3 k3, b = 2 k2, c = k1) by the stable
 * quadratic formula, the discriminant by Kahan's fma difference of products
 * (accurate when the two critical points nearly coincide).  a == 0 (or tiny)
 * needs no special case beyond a == 0 exactly: the large root then leaves
 * the interval and the small one is c/q.  ext[i] is 1 for an extremum (f'
 * changes sign), 0 for the inflection of a double zero of f' (discriminant
 * exactly 0: f is monotone through it, so it is no touch).  Returns their
 * number (0..2). */
static int
crit_points(const double k[4], double t0, double t1, double r[2], int ext[2])
{
	double a = 3 * k[3], b = 2 * k[2], c = k[1];
	double x[2];
	int n = 0, m = 0, i, e2 = 1;

	if (a == 0) {
		if (b == 0)
			return 0;
		x[n++] = -c / b;
	} else {
		double w = 4 * a * c, bb = b * b;
		double disc = bb - w;

		/* Kahan's fma difference of products where it cancels (the
		 * critical points nearly coincide); fma is a library call */
		if (fabs(disc) < 0x1p-20 * bb)
			disc = fma(b, b, -w) + fma(-4 * a, c, w);

		if (disc < 0)
			return 0;
		if (disc == 0) {
			x[n++] = -b / (2 * a);
			e2 = 0;
		} else {
			double q = -0.5 * (b + copysign(sqrt(disc), b));

			x[n++] = q / a;
			x[n++] = c / q;
		}
	}
	for (i = 0; i < n; i++)
		if (x[i] > t0 && x[i] < t1) {   /* false for NaN */
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

/* monotone: 1 when f' provably keeps one sign on [t0, t1] (t0 < t1,
 * finite, T = max(|t0|, |t1|); k normalized, |k_i| < 2^400), so that f
 * has no critical point there and crit_points need not be called (its
 * square root and divisions are the longest wait of a hit's path).
 * Method: f' = k1 + 2 k2 t + 3 k3 t^2 is a quadratic; on [t0, t1] its
 * Bernstein coefficients are f'(t0), f'(t0) + (L/2) f''(t0) and f'(t1)
 * (L = t1 - t0), and f' lies in their hull.  Each is computed with under
 * 12 roundings of quantities bounded by S = |k1| + 2 |k2| T + 3 |k3| T^2
 * times at most 3 (L <= 2 T, so (L/2) |f''(t0)| <= 2 |k2| T + 6 |k3| T^2 <= 2 S): their
 * errors are under 40 u S < 2^-47 S, far below the margin 2^-40 S asked
 * of all three (S computed is within 6 u of S).  Gradual underflow adds
 * at most 2^-1074 a step; the margin is at least 2^-40 S, and a tiny S
 * (below 2^-900) or an overflowing one (inf, NaN) answers 0: the caller
 * then computes the critical points, as always before. */
static inline int
monotone(const double k[4], double t0, double t1, double T)
{
	double S = fabs(k[1]) + T * (2 * fabs(k[2]) + T * 3 * fabs(k[3]));
	double d0 = deriv1(k, t0), d2 = deriv1(k, t1);
	double d1 = d0 + 0.5 * (t1 - t0) * deriv2(k, t0);
	double mg = 0x1p-40 * S;

	if (!(S >= 0x1p-900 && S <= 0x1p900))
		return 0;
	return (d0 > mg && d1 > mg && d2 > mg) ||
	    (d0 < -mg && d1 < -mg && d2 < -mg);
}

/* Normalize k (and f0, f1) by a power of two when their magnitude could
 * overflow or underflow the squares taken below.  Exact, so it changes no
 * result that was computable without it.  k is finite (both callers check):
 * then "no |k_i| >= 2^400 and not all <= 2^-400" is the fast path below. */
static inline void
normalize(double k[4], double *f0, double *f1)
{
	double m0 = fabs(k[0]), m1 = fabs(k[1]), m2 = fabs(k[2]), m3 = fabs(k[3]);
	double m = m0 > m1 ? m0 : m1;
	int e, i;

	m = m2 > m ? m2 : m;
	m = m3 > m ? m3 : m;
	if ((m < 0x1p400 && m > 0x1p-400) || m == 0)
		return;
	e = ilogb(m);
	for (i = 0; i < 4; i++)
		k[i] = ldexp(k[i], -e);
	*f0 = ldexp(*f0, -e);
	*f1 = ldexp(*f1, -e);
}

/* Refinement inside a bracket [a, b] where pos(fa) != pos(fb) (pos(x) is
 * x >= 0) and f is monotone strictly inside.  *n counts evaluations.
 * Halley's iteration x - f f' / (f'^2 - f f'' / 2): one evaluation of f,
 * f' and f'' a step, as one of f and f' is for Newton's, and the error
 * cubed rather than squared each step, so about one dependent evaluation
 * and division less per root (the chain a hit waits on). */
static double
refine_exact(const double k[4], double a, double b, double fa, double fb,
    double tol, int *n)
{
	int sa = fa >= 0;
	double x, f, df, d2f, step, dx, dxold;

	/* start at the secant point: |fa - fb| >= max(|fa|, |fb|) > 0 */
	x = a + (b - a) * (fa / (fa - fb));
	if (!(x > a && x < b))
		x = a + 0.5 * (b - a);
	dx = dxold = b - a;
	while (*n < VX_CELL_MAXITER) {
		f = eval3(k, x, &df, &d2f);
		(*n)++;
		if (f == 0)
			return x;
		if ((f >= 0) == sa)
			a = x;
		else
			b = x;
		if (b - a <= tol)
			break;
		/* Halley if it stays strictly inside, at least halves the
		 * step before last (as Numerical Recipes' rtsafe does for
		 * Newton) and is at least a quarter of Newton's step f / f'
		 * (near a zero of f' Halley's step shrinks towards f's
		 * extremum, not its root, and would pass for converged);
		 * else bisect.  A zero or NaN denominator, or f' = 0, fails
		 * these tests: bisection. */
		dxold = dx;
		step = f * df / (df * df - 0.5 * f * d2f);
		double xn = x - step;
		if (!(xn > a && xn < b) || fabs(2 * step) > fabs(dxold) ||
		    !(fabs(f) <= 4 * fabs(step * df))) {
			dx = 0.5 * (b - a);
			xn = a + dx;
		} else {
			dx = step;
			/* converged: x's error is about step, and Halley's
			 * error after the step about |K| step^3, K = f''^2 /
			 * (4 f'^2) - f''' / (6 f') (Taylor; f''' = 6 k3): at
			 * most tol / 2 returns xn, without the evaluation
			 * that would find its step that small.  Multiplied
			 * out by f'^2: no division; an overflow (inf) or NaN
			 * only goes on iterating. */
			if (fabs(step) <= tol ||
			    fabs(0.25 * d2f * d2f - k[3] * df) * fabs(step) *
			    step * step <= 0.5 * tol * df * df)
				return xn;
		}
		if (xn == x)
			break;
		x = xn;
	}
	return x < a ? a : x > b ? b : x;
}

/* Regula falsi, `steps` times, then one last interpolation. */
static double
refine_linear(const double k[4], double a, double b, double fa, double fb,
    int steps, int *n)
{
	int sa = fa >= 0, i;
	double x;

	for (i = 0; i < steps; i++) {
		double f;

		x = a + (b - a) * (fa / (fa - fb));
		if (!(x > a && x < b))
			break;
		f = vx_cell_poly_eval(k, x);
		(*n)++;
		if (f == 0)
			return x;
		if ((f >= 0) == sa) {
			a = x;
			fa = f;
		} else {
			b = x;
			fb = f;
		}
	}
	x = a + (b - a) * (fa / (fa - fb));
	return x < a ? a : x > b ? b : x;
}

int
vx_cell_first_root(const double k[4], double t0, double t1, double f0,
    double f1, int solver, double *t, int *iters)
{
	double kk[4], r[2], p[4], v[4], tol, T;
	int ext[2], m, i, n = 0;

	if (iters)
		*iters = 0;
	if (!(isfinite(k[0]) && isfinite(k[1]) && isfinite(k[2]) &&
	    isfinite(k[3]) && isfinite(t0) && isfinite(t1) && isfinite(f0) &&
	    isfinite(f1)) || t0 > t1)
		return VX_CELL_MISS;
	if (t0 == t1) {
		if ((f0 >= 0) == (f1 >= 0))
			return VX_CELL_MISS;
		*t = t0;
		return VX_CELL_CROSS;
	}
	memcpy(kk, k, sizeof kk);
	normalize(kk, &f0, &f1);
	/* t0, t1 finite: a plain max, no fmax call */
	T = fabs(t0) > fabs(t1) ? fabs(t0) : fabs(t1);
	/* a segment where f is provably monotone has no critical point */
	m = monotone(kk, t0, t1, T) ? 0 : crit_points(kk, t0, t1, r, ext);
	p[0] = t0;
	v[0] = f0;
	for (i = 0; i < m; i++) {
		p[i + 1] = r[i];
		v[i + 1] = vx_cell_poly_eval(kk, r[i]);
	}
	p[m + 1] = t1;
	v[m + 1] = f1;
	for (i = 0; i <= m; i++) {
		/* a touch first: an extremum within tolerance of zero ends this
		 * segment; if f also changes sign on the way, the crossing is
		 * within the same rounding ambiguity of it (|t - t_c| about
		 * sqrt(2 |f(t_c)| / |f''(t_c)|)), and the extremum is the
		 * better answer for a true double root */
		if (i + 1 <= m && ext[i] &&
		    fabs(v[i + 1]) <= VX_CELL_TOUCH_TOL * terms(kk, p[i + 1])) {
			*t = p[i + 1];
			return VX_CELL_TOUCH;
		}
		if ((v[i] >= 0) != (v[i + 1] >= 0)) {
			double a = p[i], b = p[i + 1];

			/* a zero at either end is the root itself (f(a) = 0 is
			 * "+", so f leaves zero at a; f(b) = 0: f reaches it) */
			if (v[i] == 0 || v[i + 1] == 0) {
				*t = v[i] == 0 ? a : b;
				return VX_CELL_CROSS;
			}
			switch (solver) {
			case VX_CELL_LINEAR:
				*t = refine_linear(kk, a, b, v[i], v[i + 1], 0, &n);
				break;
			case VX_CELL_NEUBAUER:
				*t = refine_linear(kk, a, b, v[i], v[i + 1],
				    VX_CELL_NEUBAUER_ITERS, &n);
				break;
			default:
				tol = 4 * 0x1p-52 * T;
				*t = refine_exact(kk, a, b, v[i], v[i + 1], tol, &n);
				break;
			}
			if (iters)
				*iters = n;
			return VX_CELL_CROSS;
		}
	}
	return VX_CELL_MISS;
}

/* Proof of the vx_cell_sign_bound guarantee (u = 2^-53, gamma_n = n u /
 * (1 - n u); L = len; S = |k0| + |k1| L + |k2| L^2 + |k3| L^3 exactly).
 * 1. The Bernstein coefficients of f(t) on [0, L] (s = t / L, a_i = k_i L^i)
 *    are b0 = a0, b1 = a0 + a1/3, b2 = a0 + (2 a1 + a2)/3, b3 = a0 + a1 +
 *    a2 + a3, and f(t) = sum b_i B_i(s) with B_i >= 0, sum B_i = 1 on
 *    [0, 1]: f(t) >= min b_i and <= max b_i for t in [0, L].  Each b_i is
 *    computed here with at most 7 roundings of quantities bounded by S (the
 *    thirds are products with 1/3 rounded, that rounding counted: b2's
 *    longest chain is a2's two, the sum's, the constant's, the product's
 *    and the last sum's: 6), so |b_i computed - b_i| <= 8 u S; S computed
 *    >= (1 - gamma_7) S.
 * 2. The test asks min |b_i computed| > 2^-38 S computed, all b_i of one
 *    sign; so the exact b_i, hence f on [0, L], have that sign with
 *    |f(t)| >= (2^-38 (1 - gamma_7) - 8 u) S > (2^-40 + 2^-48) S.
 * 3. vx_cell_first_root leaves k unscaled here (normalize acts only when
 *    some |k_i| >= 2^400 or all <= 2^-400, both excluded), evaluates f by
 *    Horner only at critical points r strictly inside (0, L), and there
 *    |fl(f(r)) - f(r)| <= gamma_6 terms(r) <= gamma_6 S < |f(r)|: the
 *    computed value has f's sign (and is not 0), and its magnitude exceeds
 *    (2^-40 + 2^-48 - gamma_6) S > VX_CELL_TOUCH_TOL (1 + gamma_6) S, which
 *    bounds the touch threshold VX_CELL_TOUCH_TOL * terms(r) as computed
 *    (terms(r) <= S as r < L).  So no critical point is a touch, every
 *    value in the sign sequence f0, f(c_1), ..., f1 has the same sign when
 *    f0 and f1 have it, and the result is a miss, whatever the solver (the
 *    solvers differ only after a bracket is found).  With L = 0 the result
 *    is a miss by the sign of f0 and f1 alone.
 * 4. Gradual underflow adds at most 2^-1074 per operation, times at most
 *    L^3 <= 2^300: below 2^-760, while the margin left in step 2 is at least
 *    2^-41 S >= 2^-641 (S computed >= 2^-600 is required).  Overflow cannot
 *    happen: |k_i| < 2^400 and L <= 2^100 bound every quantity by 2^702.
 * NaN fails every comparison below, so it gives 0. */
int
vx_cell_sign_bound(const double k[4], double len)
{
	double b3;

	return vx_cell_sign_bound_b3(k, len, &b3);
}

int
vx_cell_max(const double k[4], double t0, double t1, double *tmax,
    double *fmax)
{
	double kk[4], r[2], bt, bf, f, g0 = 0, g1 = 0;
	int ext[2], m, i;

	*tmax = 0;
	*fmax = -INFINITY;
	if (!(isfinite(k[0]) && isfinite(k[1]) && isfinite(k[2]) &&
	    isfinite(k[3]) && isfinite(t0) && isfinite(t1)) || t0 > t1)
		return 0;
	memcpy(kk, k, sizeof kk);
	normalize(kk, &g0, &g1);
	bt = t0;
	bf = vx_cell_poly_eval(kk, t0);
	m = crit_points(kk, t0, t1, r, ext);
	for (i = 0; i < m; i++) {
		f = vx_cell_poly_eval(kk, r[i]);
		if (f > bf) {
			bf = f;
			bt = r[i];
		}
	}
	f = vx_cell_poly_eval(kk, t1);
	if (f > bf) {
		bf = f;
		bt = t1;
	}
	/* back to the caller's scale (the identity unless normalized) */
	*tmax = bt;
	*fmax = vx_cell_poly_eval(k, bt);
	if (!isfinite(*fmax)) {
		*tmax = 0;
		*fmax = -INFINITY;
		return 0;
	}
	return 1;
}

void
vx_cell_gradient(const float c[8], const double p[3], double g[3])
{
	double dx[4], dy[4], dz[4];
	int j;

	/* edge differences along each axis, indexed by the other two axes'
	 * bits in increasing order */
	for (j = 0; j < 4; j++) {
		int ix = 2 * j;                          /* x = 0, (y,z) = j */
		int iy = (j & 1) | ((j >> 1) << 2);      /* y = 0, (x,z) = j */
		int iz = j;                              /* z = 0, (x,y) = j */

		dx[j] = (double)c[ix + 1] - c[ix];
		dy[j] = (double)c[iy + 2] - c[iy];
		dz[j] = (double)c[iz + 4] - c[iz];
	}
	g[0] = lerp(lerp(dx[0], dx[1], p[1]), lerp(dx[2], dx[3], p[1]), p[2]);
	g[1] = lerp(lerp(dy[0], dy[1], p[0]), lerp(dy[2], dy[3], p[0]), p[2]);
	g[2] = lerp(lerp(dz[0], dz[1], p[0]), lerp(dz[2], dz[3], p[0]), p[1]);
}

/* n = s * g / |g| if that is finite and |g| > thresh; returns 1 if so. */
static int
unit(const double g[3], double s, double thresh, double n[3])
{
	double m = fmax(fmax(fabs(g[0]), fabs(g[1])), fabs(g[2]));
	double x, y, z, len;

	if (!(isfinite(g[0]) && isfinite(g[1]) && isfinite(g[2])) ||
	    !(m > thresh) || m == 0)
		return 0;
	/* divide by the largest component first: no overflow in the squares */
	x = g[0] / m;
	y = g[1] / m;
	z = g[2] / m;
	len = sqrt(x * x + y * y + z * z);
	n[0] = s * x / len;
	n[1] = s * y / len;
	n[2] = s * z / len;
	return 1;
}

double
vx_cell_normal_thresh(const float c[8])
{
	double lo[4], hi[4];
	int i;

	/* fmin/fmax without the calls, a NaN skipped unless all are, as a
	 * tree of depth 3 rather than a chain of 7: the least and the
	 * greatest of the values that are not NaN (NaN when all are), in any
	 * order (where zeros of both signs tie, hi - lo is a zero either
	 * way) */
	for (i = 0; i < 4; i++) {
		double x = c[2 * i], y = c[2 * i + 1];

		lo[i] = y < x || x != x ? y : x;
		hi[i] = y > x || x != x ? y : x;
	}
	for (i = 0; i < 2; i++) {
		lo[i] = lo[i + 2] < lo[i] || lo[i] != lo[i] ? lo[i + 2] : lo[i];
		hi[i] = hi[i + 2] > hi[i] || hi[i] != hi[i] ? hi[i + 2] : hi[i];
	}
	lo[0] = lo[1] < lo[0] || lo[0] != lo[0] ? lo[1] : lo[0];
	hi[0] = hi[1] > hi[0] || hi[0] != hi[0] ? hi[1] : hi[0];
	return 0x1p-40 * (hi[0] - lo[0]);
}

int
vx_cell_normal(const float c[8], const double p[3], const double d[3],
    double n[3])
{
	static const double centre[3] = { 0.5, 0.5, 0.5 };
	double g[3], thresh = vx_cell_normal_thresh(c);   /* unit() checks */
	int i;

	if (isfinite(thresh)) {
		vx_cell_gradient(c, p, g);
		if (unit(g, 1, thresh, g)) {
			if (g[0] * d[0] + g[1] * d[1] + g[2] * d[2] > 0)
				for (i = 0; i < 3; i++)
					g[i] = -g[i];
			memcpy(n, g, sizeof g);
			return VX_NORMAL_GRADIENT;
		}
		vx_cell_gradient(c, centre, g);
		if (unit(g, 1, thresh, g)) {
			if (g[0] * d[0] + g[1] * d[1] + g[2] * d[2] > 0)
				for (i = 0; i < 3; i++)
					g[i] = -g[i];
			memcpy(n, g, sizeof g);
			return VX_NORMAL_CENTER;
		}
	}
	if (unit(d, -1, 0, n))
		return VX_NORMAL_RAY;
	n[0] = n[1] = n[2] = 0;
	return VX_NORMAL_NONE;
}
