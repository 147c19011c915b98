/* vx_sh.h: real spherical harmonics (SH): evaluation, projection, the
 * clamped-cosine convolution (irradiance), and rotation.
 *
 * Convention (Wyman et al. 2006, eq. 12, which follows Green 2003):
 *
 *   Y_l^m = sqrt(2) N_l^m P_l^m(cos theta) cos(m phi)       m > 0
 *           N_l^0 P_l^0(cos theta)                          m = 0
 *           sqrt(2) N_l^|m| P_l^|m|(cos theta) sin(|m| phi) m < 0
 *   N_l^m = sqrt((2l + 1) / (4 pi) (l - m)! / (l + m)!)
 *
 * with the direction w = (sin theta cos phi, sin theta sin phi, cos theta):
 * theta from +z, phi from +x towards +y.  P_l^m INCLUDES the Condon-Shortley
 * phase (-1)^m (P_1^1(x) = -sqrt(1 - x^2)), as Green's code does, so
 *   Y_1^-1 = -sqrt(3/(4 pi)) y,  Y_1^0 = sqrt(3/(4 pi)) z,
 *   Y_1^1  = -sqrt(3/(4 pi)) x.
 * Ramamoorthi and Hanrahan 2001 (and Ivanic and Ruedenberg) use the basis
 * without the phase, whose functions are (-1)^m times these (Y_1^1 =
 * +0.488603 x there): vx_sh_flip_phase converts coefficients either way.
 *
 * Coefficients of an order-n expansion (bands l = 0 .. n-1) are n*n doubles
 * per channel, (l, m) at vx_sh_index(l, m) = l*l + l + m.  Several channels
 * (r, g, b) are stored one after the other: channel k's coefficients at
 * c + k * n * n.  The basis is orthonormal over the sphere (integral of
 * Y_i Y_j over solid angle = delta_ij), so the coefficient of a function f is
 * the integral of f Y_i, and the integral of a product of two functions is
 * the dot product of their coefficients (eq. 15).
 *
 * Every function here is infallible and allocates nothing; orders are
 * preconditions: 1 <= order <= VX_SH_MAX_ORDER (tools check their options
 * against it). */
#ifndef VX_SH_H
#define VX_SH_H

#include <stddef.h>
#include <stdint.h>

/* Bands 0 .. 31.  Evaluation is by the fully normalized Legendre recurrence,
 * whose terms stay of the size of the result (no factorials, no overflow,
 * no cancellation that grows with the band): stable through band 31
 * (test_sh checks orthonormality and the addition theorem there). */
#define VX_SH_MAX_ORDER 32
#define VX_SH_MAX_COEF (VX_SH_MAX_ORDER * VX_SH_MAX_ORDER)

static inline int
vx_sh_index(int l, int m)
{
	return l * l + l + m;
}

/* ---- the basis ---- */

/* vx_sh_eval: y[vx_sh_index(l, m)] = Y_l^m(w) for l < order (order*order
 * values).  w must be a unit vector (the functions are polynomials in its
 * components; no trigonometry is used).  Thread-safe: the first call fills
 * a table of recurrence coefficients once (pthread_once). */
void vx_sh_eval(int order, const double w[3], double *y);

/* vx_sh_eval_sum: the expansion with coefficients c (one channel) at the unit
 * direction w: sum over i of c[i] Y_i(w). */
double vx_sh_eval_sum(int order, const double *c, const double w[3]);

/* vx_sh_flip_phase: multiply coefficient (l, m) by (-1)^m, in place, for
 * nchan channels: converts between this basis and the basis without the
 * Condon-Shortley phase (Ramamoorthi and Hanrahan's).  Its own inverse. */
void vx_sh_flip_phase(int order, int nchan, double *c);

/* ---- projection ---- */

/* vx_sh_fn: a function on the sphere: val[0 .. nchan-1] at unit direction w
 * (user is passed through). */
typedef void (*vx_sh_fn)(const double w[3], void *user, double *val);

/* vx_sh_accumulate: c[k n^2 + i] += weight val[k] Y_i(w) for each channel
 * k < nchan.  A quadrature is a loop of these: over an environment's pixels
 * with weight = the pixel's solid angle (exact projection of the
 * piecewise-constant map), or over Monte Carlo samples with
 * weight = 1 / (N pdf). */
void vx_sh_accumulate(int order, const double w[3], double weight,
    const double *val, int nchan, double *c);

/* vx_sh_project_samples: the Monte Carlo estimate from n samples:
 * c = (1/n) sum over s of val_s Y(w_s) / pdf_s, written over c (nchan
 * channels).  w holds 3 n doubles, pdf n (in solid angle, > 0), val
 * nchan n (sample s's channels at val + s nchan).  n = 0 gives zeros. */
void vx_sh_project_samples(int order, size_t n, const double *w,
    const double *pdf, const double *val, int nchan, double *c);

/* vx_sh_project_mc: the Monte Carlo projection of f with nsample directions
 * uniform over the sphere (pdf 1/(4 pi)), the points of vx_rng_ld2(seed,
 * stream, i, dim) warped by vx_warp_uniform_sphere: deterministic, and for a
 * smooth f and nsample a power of two the error falls about as
 * nsample^-3/2 (scrambled Sobol points), not nsample^-1/2.  Written over c
 * (nchan <= VX_SH_MAX_CHAN channels). */
#define VX_SH_MAX_CHAN 16
void vx_sh_project_mc(int order, vx_sh_fn f, void *user, int nchan,
    uint64_t nsample, uint64_t seed, uint64_t stream, uint32_t dim,
    double *c);

/* vx_sh_project_gauss: the projection by a product rule: nz Gauss-Legendre
 * nodes in z = cos theta times 2 nz equally spaced phi.  Exact (to
 * rounding) when f is a polynomial on the sphere of degree d (a sum of SH of
 * bands <= d) with d + order - 1 <= 2 nz - 1.  1 <= nz <= VX_SH_GAUSS_MAX.
 * nchan <= VX_SH_MAX_CHAN.  Written over c. */
#define VX_SH_GAUSS_MAX 256
void vx_sh_project_gauss(int order, int nz, vx_sh_fn f, void *user,
    int nchan, double *c);

/* vx_sh_gauss_legendre: the n-point Gauss-Legendre rule on [-1, 1]:
 * nodes x (ascending) and weights wt, by Newton's iteration on P_n; exact for
 * polynomials of degree <= 2n - 1.  1 <= n <= VX_SH_GAUSS_MAX. */
void vx_sh_gauss_legendre(int n, double *x, double *wt);

/* ---- convolution with the clamped cosine: irradiance ---- */

/* vx_sh_cosine_band: A_l, the factor by which convolution with the clamped
 * cosine max(cos theta, 0) scales band l (Ramamoorthi and Hanrahan 2001's
 * A-hat, which includes the Funk-Hecke factor sqrt(4 pi / (2l + 1))):
 * A_0 = pi, A_1 = 2 pi / 3, A_l = 0 for odd l > 1, and for even l
 *   A_l = 2 pi (-1)^(l/2 - 1) / ((l + 2)(l - 1)) * l! / (2^l ((l/2)!)^2)
 * (A_2 = pi/4, A_4 = -pi/24, A_6 = pi/64).  Any l >= 0. */
double vx_sh_cosine_band(int l);

/* vx_sh_convolve_cosine: out = A_l in, band by band, for nchan channels
 * (out may alias in): radiance coefficients in, irradiance coefficients
 * out, so that E(n) = vx_sh_eval_sum(order, out, n). */
void vx_sh_convolve_cosine(int order, int nchan, const double *in,
    double *out);

/* vx_sh_irradiance: the irradiance at a surface with unit normal n under
 * distant lighting whose radiance has coefficients c (nchan channels):
 * e[k] = sum over (l, m) of A_l c_lm Y_lm(n), the integral of L(w)
 * max(n.w, 0) over the sphere for the band-limited L.  A constant radiance
 * L gives pi L at every n. */
void vx_sh_irradiance(int order, int nchan, const double *c,
    const double n[3], double *e);

/* ---- rotations of the sphere (3x3) ---- */

/* Rotation matrices are row-major double[3][3] acting on column vectors
 * (w' = r w), proper (det +1).  ZYZ Euler angles: r = Rz(alpha) Ry(beta)
 * Rz(gamma), each a right-handed (counterclockwise seen from the axis's tip)
 * turn in radians: the vector is turned by gamma about z, then by beta about
 * y, then by alpha about z. */
void vx_rot3_zyz(double alpha, double beta, double gamma, double r[3][3]);

/* vx_rot3_axis: the turn by angle (radians, right-handed) about axis
 * (Rodrigues' formula; axis normalized here, a zero axis gives identity). */
void vx_rot3_axis(const double axis[3], double angle, double r[3][3]);

/* vx_rot3_to_zyz: ZYZ angles of the rotation r: beta in [0, pi], alpha and
 * gamma in [-pi, pi].  At gimbal lock (sin beta = 0: beta = 0 or pi) alpha
 * = 0 and gamma carries the whole turn about z.  Near it alpha is
 * ill-determined, but gamma is computed from r and alpha, so the three
 * angles rebuild r to rounding always. */
void vx_rot3_to_zyz(const double r[3][3], double *alpha, double *beta,
    double *gamma);

/* ---- rotation of SH coefficients ---- */

/* A rotation of an order-n expansion is block diagonal (bands do not mix):
 * band l is a (2l+1) x (2l+1) matrix, row-major, rows and columns m = -l..l,
 * at offset vx_sh_rot_offset(l) of an array of vx_sh_rot_size(n) doubles.
 * The matrix of the rotation r maps the coefficients of f to those of the
 * rotated function g(w) = f(r^-1 w) (the lighting turned by r): element
 * (s, t) = integral of Y_s(r w) Y_t(w) (Wyman et al. eq. 16).  It is
 * orthogonal, and the map r -> matrix is a homomorphism:
 * matrix(a b) = matrix(a) matrix(b). */
static inline size_t
vx_sh_rot_offset(int l)
{
	return (size_t)l * (size_t)(4 * l * l - 1) / 3;
}

static inline size_t
vx_sh_rot_size(int order)
{
	return vx_sh_rot_offset(order);
}

/* vx_sh_rot_from_matrix: the SH rotation of r by Ivanic and Ruedenberg's
 * recurrence (1996, with their 1998 corrections): band 1 is r itself
 * reordered (y, z, x) in the basis without the phase, band l follows from
 * band l-1 and band 1; converted to this basis at the end.  O(order^3). */
void vx_sh_rot_from_matrix(int order, const double r[3][3], double *rot);

/* vx_sh_rot_from_axis: the same for the turn by angle about axis. */
void vx_sh_rot_from_axis(int order, const double axis[3], double angle,
    double *rot);

/* vx_sh_rot_from_zyz: the SH rotation of Rz(alpha) Ry(beta) Rz(gamma) built
 * independently of the recurrence, as the product
 *   Z(alpha) X(-90) Z(beta) X(+90) Z(gamma)
 * (Ry(beta) = Rx(-90 deg) Rz(beta) Rx(90 deg)): rotations about z in closed
 * form (cos, sin of m angle on each (m, -m) pair), X(+90) by exact
 * quadrature of eq. 16 (Gauss-Legendre x uniform phi), X(-90) its transpose.
 * A check on vx_sh_rot_from_matrix, much slower (the quadrature is
 * O(order^5)) and using about 100 KB of stack; for speed, turn Euler angles
 * into a matrix (vx_rot3_zyz) and use vx_sh_rot_from_matrix. */
void vx_sh_rot_from_zyz(int order, double alpha, double beta, double gamma,
    double *rot);

/* vx_sh_rot_apply: out = rot in, band by band, for nchan channels (out may
 * alias in). */
void vx_sh_rot_apply(int order, const double *rot, int nchan,
    const double *in, double *out);

/* vx_sh_rot_z: rotate coefficients about z by alpha directly (closed form,
 * O(order^2)), for nchan channels (out may alias in). */
void vx_sh_rot_z(int order, double alpha, int nchan, const double *in,
    double *out);

#endif
