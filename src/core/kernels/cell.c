/* cell.c: ray vs trilinear cell: cubic coefficients, robust first root,
 * exact maximum, crack-free face values, gradient and normals. */
#include "vx_cell.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

static const vx_enum_name solver_names[] = {
	{ "exact", VX_CELL_EXACT }, { "neubauer", VX_CELL_NEUBAUER },
	{ "linear", VX_CELL_LINEAR }, { NULL, -1 }
};
const vx_enum vx_cell_solver_enum = { "solver", solver_names, "unknown", 0 };

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

void
vx_cell_poly(const float c[8], const double o[3], const double d[3],
    double iso, double k[4])
{
	vx_cell_poly_inline(c, o, d, iso, k);
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

/* ---- exact signs of polynomials in doubles ----
 * The touch and crossing decisions of vx_cell_first_root are signs of
 * small polynomials in the cubic's coefficients and the segment's ends,
 * all doubles.  Each is first evaluated in double with an error bound (the
 * filter); only where the bound cannot decide is it evaluated exactly, in
 * a binary big number (xnum), as robust geometric predicates do.
 *
 * The filter's bound.  A quantity q = sum of m terms c * x1 * ... * xp (c
 * a small integer, p <= 4, m <= 5) evaluated term by term and summed in
 * order has |fl(q) - q| <= gamma_n S with S the sum of the terms'
 * magnitudes and n the roundings on the longest path: at most 4 for a term
 * (3 products, and the constant's when it is not a power of 2) plus m - 1
 * for the sum, n <= 8, gamma_8 < 2^-49.9; the computed S is at least
 * (1 - gamma_8) S.  Gradual underflow adds at most 2^-1074 an operation,
 * under 40 operations: 2^-1060 covers it.  So |fl(q)| > 2^-48 fl(S) +
 * 2^-1060 proves sign(fl(q)) = sign(q); overflow (fl(S) not finite) never
 * decides.
 *
 * The exact evaluation.  A term's factors are doubles: a product of four
 * has its lowest bit at 2^-4296 or above and its highest below 2^4102, so
 * a sum of five such spans under 8400 bits: XN_LIMBS limbs of 32 bits hold
 * any of them. */

#define XN_LIMBS 272

typedef struct xnum {
	int neg;                 /* the sign (0 for zero) */
	int e;                   /* the exponent of limb 0's lowest bit */
	int n;                   /* limbs used; 0 for zero */
	uint32_t m[XN_LIMBS];    /* magnitude, least significant limb first */
} xnum;

/* xn_trim: drop zero limbs at the top, and at the bottom (raising e) */
static void
xn_trim(xnum *x)
{
	int lo = 0, i;

	while (x->n > 0 && x->m[x->n - 1] == 0)
		x->n--;
	if (x->n == 0) {
		x->neg = 0;
		x->e = 0;
		return;
	}
	while (lo < x->n && x->m[lo] == 0)
		lo++;
	if (lo > 0) {
		for (i = lo; i < x->n; i++)
			x->m[i - lo] = x->m[i];
		x->n -= lo;
		x->e += 32 * lo;
	}
}

/* xn_set: the exact value of a finite double */
static void
xn_set(xnum *x, double v)
{
	uint64_t bits, mant;
	int ex;

	memcpy(&bits, &v, sizeof bits);
	x->neg = (int)(bits >> 63);
	ex = (int)(bits >> 52 & 0x7ff);
	mant = bits & (((uint64_t)1 << 52) - 1);
	if (ex == 0)
		ex = 1;                       /* subnormal */
	else
		mant |= (uint64_t)1 << 52;
	x->e = ex - 1075;
	x->m[0] = (uint32_t)mant;
	x->m[1] = (uint32_t)(mant >> 32);
	x->n = 2;
	xn_trim(x);
}

/* xn_mul: r = x * v, v a finite double (r may be x) */
static void
xn_mul(xnum *r, const xnum *x, double v)
{
	uint32_t out[XN_LIMBS];
	xnum y;
	int i, j, n;

	xn_set(&y, v);
	if (x->n == 0 || y.n == 0) {
		r->n = 0;
		r->neg = 0;
		r->e = 0;
		return;
	}
	n = x->n + y.n;
	for (i = 0; i < n; i++)
		out[i] = 0;
	for (j = 0; j < y.n; j++) {
		uint64_t carry = 0;

		for (i = 0; i < x->n; i++) {
			uint64_t t = (uint64_t)x->m[i] * y.m[j] + out[i + j] +
			    carry;

			out[i + j] = (uint32_t)t;
			carry = t >> 32;
		}
		out[x->n + j] = (uint32_t)carry;
	}
	r->neg = x->neg ^ y.neg;
	r->e = x->e + y.e;
	r->n = n;
	memcpy(r->m, out, (size_t)n * sizeof *out);
	xn_trim(r);
}

/* xn_shifted: x's magnitude with its exponent lowered to e (<= x->e):
 * out[0..*n); 0, or -1 beyond XN_LIMBS (never for sign_sum's terms: the
 * bound above) */
static int
xn_shifted(const xnum *x, int e, uint32_t *out, int *n)
{
	int sh = x->e - e, q = sh / 32, r = sh % 32, i;

	if (q + x->n + 2 > XN_LIMBS)
		return -1;
	for (i = 0; i < q; i++)
		out[i] = 0;
	out[q + x->n] = 0;
	for (i = 0; i < x->n; i++)
		out[q + i] = x->m[i] << r;
	if (r > 0)
		for (i = 0; i < x->n; i++)
			out[q + i + 1] |= x->m[i] >> (32 - r);
	*n = q + x->n + 1;
	return 0;
}

/* xn_add: r += x (signed); 0, or -1 beyond XN_LIMBS */
static int
xn_add(xnum *r, const xnum *x)
{
	uint32_t a[XN_LIMBS], b[XN_LIMBS];
	int na, nb, n, i, e, c;

	if (x->n == 0)
		return 0;
	if (r->n == 0) {
		*r = *x;
		return 0;
	}
	e = r->e < x->e ? r->e : x->e;
	if (xn_shifted(r, e, a, &na) != 0 || xn_shifted(x, e, b, &nb) != 0)
		return -1;
	n = na > nb ? na : nb;
	for (i = na; i < n; i++)
		a[i] = 0;
	for (i = nb; i < n; i++)
		b[i] = 0;
	if (r->neg == x->neg) {
		uint64_t carry = 0;

		for (i = 0; i < n; i++) {
			uint64_t t = (uint64_t)a[i] + b[i] + carry;

			r->m[i] = (uint32_t)t;
			carry = t >> 32;
		}
		r->m[n] = (uint32_t)carry;   /* n < XN_LIMBS: see above */
		r->n = n + 1;
	} else {
		/* the larger magnitude minus the smaller, its sign */
		for (c = 0, i = n - 1; i >= 0 && c == 0; i--)
			c = a[i] > b[i] ? 1 : a[i] < b[i] ? -1 : 0;
		if (c == 0) {
			r->n = 0;
			r->neg = 0;
			r->e = 0;
			return 0;
		}
		uint32_t *big = c > 0 ? a : b, *small = c > 0 ? b : a;
		int64_t borrow = 0;

		for (i = 0; i < n; i++) {
			int64_t t = (int64_t)big[i] - small[i] - borrow;

			borrow = t < 0;
			r->m[i] = (uint32_t)(t + (borrow ? (int64_t)1 << 32 : 0));
		}
		r->neg = c > 0 ? r->neg : x->neg;
		r->n = n;
	}
	r->e = e;
	xn_trim(r);
	return 0;
}

/* A term of a polynomial: c * x[0] * ... * x[np - 1]. */
typedef struct term {
	double c;
	double x[4];
	int np;
} term;

/* sign_sum: the exact sign (-1, 0, +1) of the sum of t[0..m), by the
 * filter, else exactly; *exact counts the exact evaluations */
static int
sign_sum(const term *t, int m, unsigned *exact)
{
	double q = 0, S = 0;
	int i, j;

	for (i = 0; i < m; i++) {
		double p = t[i].c;

		for (j = 0; j < t[i].np; j++)
			p *= t[i].x[j];
		q += p;
		S += fabs(p);
	}
	if (S <= 0x1p1000 && fabs(q) > 0x1p-48 * S + 0x1p-1060)
		return q > 0 ? 1 : -1;
	if (exact)
		(*exact)++;
	{
		xnum acc, p;

		acc.n = 0;
		acc.neg = 0;
		acc.e = 0;
		for (i = 0; i < m; i++) {
			xn_set(&p, t[i].c);
			for (j = 0; j < t[i].np; j++)
				xn_mul(&p, &p, t[i].x[j]);
			if (xn_add(&acc, &p) != 0)   /* cannot happen */
				return q > 0 ? 1 : q < 0 ? -1 : 0;
		}
		return acc.n == 0 ? 0 : acc.neg ? -1 : 1;
	}
}

#define T1(c, a) { (c), { (a), 0, 0, 0 }, 1 }
#define T2(c, a, b) { (c), { (a), (b), 0, 0 }, 2 }
#define T3(c, a, b, d) { (c), { (a), (b), (d), 0 }, 3 }
#define T4(c, a, b, d, e) { (c), { (a), (b), (d), (e) }, 4 }

/* Exact critical points of the cubic f = a t^3 + b t^2 + c t + d (a = k3,
 * b = k2, c = k1, d = k0) strictly inside (t0, t1), in order, with the
 * exact sign of f at each.  With D1 = b^2 - 3 a c (f' = 3 a t^2 + 2 b t + c
 * has discriminant 4 D1), E = 27 a^2 d - 9 a b c + 2 b^3 (27 a^2 f at the
 * inflection -b / (3a)) and Delta = 18 abcd - 4 b^3 d + b^2 c^2 - 4 a c^3 -
 * 27 a^2 d^2 (f's discriminant):
 *   - a = 0: f' is linear; its zero -c / (2b) (b != 0) is inside when
 *     -c - 2 b t0 and -c - 2 b t1 have the signs that say so, and f there
 *     is (4 b d - c^2) / (4 b);
 *   - D1 < 0: no critical point; D1 = 0: one, the inflection -b / (3a),
 *     where f' has a double zero (no extremum), f there of E's sign;
 *   - D1 > 0: two, r1 < r2.  Where a point x lies among them follows from
 *     the signs of a f'(x) (positive outside [r1, r2]) and of a (3 a x +
 *     b) (x against the inflection, their midpoint).  f(r1) f(r2) =
 *     -Delta / (27 a^2), and the local maximum is the larger: Delta > 0
 *     gives f(r1) of a's sign and f(r2) of the other; Delta < 0 gives both
 *     E's sign (the inflection lies between them); Delta = 0 gives a
 *     double root, at r1 when E a < 0 (it lies before the inflection by
 *     E / (6 a D1)) and the other then of -a's sign, else at r2 and r1 of
 *     a's sign (f = a (t - t_d)^2 (t - t_s), the other critical point
 *     between t_d and t_s).
 * r[] gets approximate positions (the stable quadratic formula, clamped
 * into [t0, t1]) for the caller's brackets; sg[] the exact signs; ext[] 1
 * for an extremum, 0 for the inflection.  Returns how many (0..2). */
static int
crit_exact(const double k[4], double t0, double t1, double r[2], int sg[2],
    int ext[2], unsigned *exact)
{
	double a = k[3], b = k[2], c = k[1], d = k[0];
	double x[2];
	int m = 0, sa, i;

	if (a == 0) {
		if (b == 0)
			return 0;
		const term lo[2] = { T1(-1, c), T2(-2, b, t0) };
		const term hi[2] = { T1(-1, c), T2(-2, b, t1) };
		int sb = b > 0 ? 1 : -1;

		if (sign_sum(lo, 2, exact) * sb <= 0 ||
		    sign_sum(hi, 2, exact) * sb >= 0)
			return 0;
		const term v[2] = { T2(4, b, d), T2(-1, c, c) };

		x[0] = -c / (2 * b);
		r[0] = x[0] > t0 ? (x[0] < t1 ? x[0] : t1) : t0;
		sg[0] = sign_sum(v, 2, exact) * sb;
		ext[0] = 1;
		return 1;
	}
	sa = a > 0 ? 1 : -1;
	const term D1[2] = { T2(1, b, b), T2(-3, a, c) };
	int s1 = sign_sum(D1, 2, exact);

	if (s1 < 0)
		return 0;
	const term E[3] = { T3(27, a, a, d), T3(-9, a, b, c), T3(2, b, b, b) };
	if (s1 == 0) {
		const term lo[2] = { T1(-1, b), T2(-3, a, t0) };
		const term hi[2] = { T1(-1, b), T2(-3, a, t1) };

		if (sign_sum(lo, 2, exact) * sa <= 0 ||
		    sign_sum(hi, 2, exact) * sa >= 0)
			return 0;
		x[0] = -b / (3 * a);
		r[0] = x[0] > t0 ? (x[0] < t1 ? x[0] : t1) : t0;
		sg[0] = sign_sum(E, 3, exact);
		ext[0] = 0;
		return 1;
	}
	/* where t0 and t1 lie: 0 before r1, 1 at r1, 2 between, 3 at r2,
	 * 4 beyond r2 */
	int pos[2];
	for (i = 0; i < 2; i++) {
		double t = i ? t1 : t0;
		const term fp[3] = { T3(3, a, t, t), T2(2, b, t), T1(1, c) };
		const term lin[2] = { T2(3, a, t), T1(1, b) };
		int s = sign_sum(fp, 3, exact) * sa;
		int w = sign_sum(lin, 2, exact) * sa;

		pos[i] = s < 0 ? 2 : s > 0 ? (w < 0 ? 0 : 4) : (w < 0 ? 1 : 3);
	}
	int in1 = pos[0] == 0 && pos[1] >= 2, in2 = pos[0] <= 2 && pos[1] == 4;

	if (!in1 && !in2)
		return 0;
	/* f at them */
	const term Dl[5] = { T4(18, a, b, c, d), T4(-4, b, b, b, d),
	    T4(1, b, b, c, c), T4(-4, a, c, c, c), T4(-27, a, a, d, d) };
	int sD = sign_sum(Dl, 5, exact), v1, v2;

	if (sD > 0) {
		v1 = sa;
		v2 = -sa;
	} else if (sD < 0) {
		v1 = v2 = sign_sum(E, 3, exact);
	} else if (sign_sum(E, 3, exact) * sa < 0) {
		v1 = 0;
		v2 = -sa;
	} else {
		v1 = sa;
		v2 = 0;
	}
	/* positions: the stable quadratic formula on f' (both roots, or the
	 * inflection twice where rounding makes the discriminant negative) */
	{
		double A = 3 * a, B = 2 * b, w = 4 * A * c, disc = B * B - w;

		if (fabs(disc) < 0x1p-20 * B * B)
			disc = fma(B, B, -w) + fma(-4 * A, c, w);
		if (disc > 0) {
			double q = -0.5 * (B + copysign(sqrt(disc), B));

			x[0] = q / A;
			x[1] = c / q;
		} else
			x[0] = x[1] = -B / (2 * A);
		if (!(x[0] <= x[1])) {
			double t = x[0];
			x[0] = x[1];
			x[1] = t;
		}
		for (i = 0; i < 2; i++)
			x[i] = x[i] > t0 ? (x[i] < t1 ? x[i] : t1) : t0;
	}
	if (in1) {
		r[m] = x[0];
		sg[m] = v1;
		ext[m++] = 1;
	}
	if (in2) {
		r[m] = x[1];
		sg[m] = v2;
		ext[m++] = 1;
	}
	return m;
}

/* monotone: 1 when f' provably keeps one sign on [t0, t1] (t0 < t1,
 * finite, T = max(|t0|, |t1|); k normalized, |k_i| < 2^400), so that f
 * has no critical point there and vx_cell_crit_points need not be called (its
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
	return vx_cell_first_root_x(k, t0, t1, f0, f1, solver, t, iters, NULL);
}

int
vx_cell_first_root_x(const double k[4], double t0, double t1, double f0,
    double f1, int solver, double *t, int *iters, unsigned *exact)
{
	double kk[4], r[2], p[4], v[4], tol, T;
	int ext[2], sg[2], m, i, n = 0;

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
	/* a segment where f is provably monotone has no critical point;
	 * elsewhere their number, order and signs are exact (crit_exact) */
	m = monotone(kk, t0, t1, T) ? 0 : crit_exact(kk, t0, t1, r, sg, ext,
	    exact);
	p[0] = t0;
	v[0] = f0;
	for (i = 0; i < m; i++) {
		double f = vx_cell_poly_eval(kk, r[i]);

		/* the value for the brackets' secant starts, of the exact
		 * sign (a zero only where f is exactly zero) */
		p[i + 1] = r[i];
		v[i + 1] = sg[i] == 0 ? 0 : (f > 0) == (sg[i] > 0) && f != 0 ?
		    f : sg[i] * 0x1p-1074;
	}
	p[m + 1] = t1;
	v[m + 1] = f1;
	for (i = 0; i <= m; i++) {
		/* a touch first: an extremum where f is exactly zero (a
		 * double root) ends this segment */
		if (i + 1 <= m && ext[i] && sg[i] == 0) {
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

int
vx_cell_end_sign(const double k[4], double t0, double t1, double f0)
{
	double kk[4], r[2], g0 = 0, g1 = 0;
	int sg[2], ext[2], m, i, last;

	if (!(isfinite(k[0]) && isfinite(k[1]) && isfinite(k[2]) &&
	    isfinite(k[3]) && isfinite(t0) && isfinite(t1) && isfinite(f0)) ||
	    !(t0 < t1))
		return 0;
	memcpy(kk, k, sizeof kk);
	normalize(kk, &g0, &g1);
	last = f0 > 0 ? 1 : f0 < 0 ? -1 : 0;
	m = crit_exact(kk, t0, t1, r, sg, ext, NULL);
	for (i = 0; i < m; i++)
		if (sg[i] != 0)
			last = sg[i];
	return last;
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
 * 3. vx_cell_first_root's sign sequence takes, at each critical point r
 *    strictly inside (0, L), the exact sign of the cubic k there
 *    (crit_exact: exact for k as given, whatever scaling normalize
 *    applies, as every sign it takes is of a homogeneous polynomial in
 *    k): by step 2 that is f's sign on [0, L], never 0.  So no critical
 *    point is a touch, every value in the sign sequence f0, f(c_1), ...,
 *    f1 has the same sign when f0 and f1 have it, and the result is a
 *    miss, whatever the solver (the solvers differ only after a bracket
 *    is found).  With L = 0 the result is a miss by the sign of f0 and f1
 *    alone.
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
	double kk[4], bt, g0 = 0, g1 = 0;

	*tmax = 0;
	*fmax = -INFINITY;
	if (!(isfinite(k[0]) && isfinite(k[1]) && isfinite(k[2]) &&
	    isfinite(k[3]) && isfinite(t0) && isfinite(t1)) || t0 > t1)
		return 0;
	memcpy(kk, k, sizeof kk);
	normalize(kk, &g0, &g1);
	bt = vx_cell_argmax(kk, t0, t1);
	/* back to the caller's scale (the identity unless normalized),
	 * rounded down: never above the exact maximum */
	*tmax = bt;
	*fmax = vx_cell_poly_low(k, bt);
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
