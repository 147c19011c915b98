/* tetisect.c: watertight ray / tetrahedron isosurface intersection (Parker
 * et al. 1999, Appendix B, with entry and exit faces found as in Woop,
 * Benthin and Wald 2013).
 *
 * Why it is crack-free.  The ray is sheared into ray space, where it is the
 * +z axis through the origin O; each vertex gets its own 2D image (x, y)
 * and depth z, computed the same way in every tet.  For each edge (i, j),
 * i < j by vertex index, the edge function E = x_i y_j - y_i x_j is the
 * orientation of (O, v_i, v_j).  Its sign is exact: rounding is monotonic,
 * so the rounded difference never has the wrong sign, and when it rounds to
 * zero the exact sign is the sign of the two products' rounding errors
 * (fma).  An exact zero is resolved by moving O by an infinitesimal
 * (eps, eps^2): the sign becomes that of -e_y, or of e_x when e_y = 0, for
 * the edge vector e = v_j - v_i.  A face is crossed when the signs of its
 * three edges, taken around it, agree.  With exact, consistently perturbed
 * signs, the perturbed ray is a generic line: it crosses 0 or 2 faces of
 * every tet (the projected boundary of a tet covers every point of the
 * plane with total signed multiplicity 0, and at most twice), and a face
 * shared by two tets gets the same answer in both.  Its depth t and value f
 * are interpolated from the same three vertices in the same (index) order,
 * so they are bit-identical too: along the ray, the crossed tets form
 * chains whose consecutive faces carry one sequence of values, and every
 * sign change of f - iso in it lies in exactly one tet. */
#include "vx_tetleaf.h"

#include <math.h>
#include <string.h>

#ifdef __clang__
#pragma STDC FP_CONTRACT OFF   /* gcc: off already under -std=c11 */
#endif

void
vx_tetray_init(vx_tetray *r, const double o[3], const double d[3])
{
	int a, kz = 0;

	for (a = 0; a < 3; a++) {
		r->o[a] = o[a];
		r->d[a] = d[a];
	}
	if (fabs(d[1]) > fabs(d[kz]))
		kz = 1;
	if (fabs(d[2]) > fabs(d[kz]))
		kz = 2;
	r->kz = kz;
	r->kx = (kz + 1) % 3;
	r->ky = (kz + 2) % 3;
	if (d[kz] < 0) {
		/* keep the handedness of ray space */
		int t = r->kx;
		r->kx = r->ky;
		r->ky = t;
	}
	r->sx = d[r->kx] / d[kz];
	r->sy = d[r->ky] / d[kz];
	r->sz = 1.0 / d[kz];
}

/* Ray-space image of point p. */
static void
to_ray(const vx_tetray *r, const double *p, double *x, double *y, double *z)
{
	double ax = p[r->kx] - r->o[r->kx];
	double ay = p[r->ky] - r->o[r->ky];
	double az = p[r->kz] - r->o[r->kz];

	*x = ax - r->sx * az;
	*y = ay - r->sy * az;
	*z = az * r->sz;
}

/* Exact sign of edge (i -> j) at the perturbed origin; e gets the rounded
 * edge function. */
static int
edge_sign(double xi, double yi, double xj, double yj, double *e)
{
	double p = xi * yj, q = yi * xj, d = p - q;

	*e = d;
	if (d > 0)
		return 1;
	if (d < 0)
		return -1;
	/* p == q as doubles: the exact difference is the difference of the
	 * products' rounding errors, each exact by fma */
	d = fma(xi, yj, -p) - fma(yi, xj, -q);
	if (d > 0)
		return 1;
	if (d < 0)
		return -1;
	/* exactly on the line: symbolic perturbation of O by (eps, eps^2) */
	double ex = xj - xi, ey = yj - yi;
	if (ey < 0)
		return 1;
	if (ey > 0)
		return -1;
	if (ex > 0)
		return 1;
	if (ex < 0)
		return -1;
	return 0;  /* both ends project to one point: faces through it have
	              no area and are never crossed */
}

/* The four vertices of a tet in canonical order, in ray space.  The order
 * is by position (x, then y, then z), then by index: faces shared by two
 * tets are evaluated identically, and so are geometrically identical faces
 * over duplicated points (unmerged seams), whatever their indices. */
typedef struct tetv {
	uint32_t id[4];
	double x[4], y[4], z[4], f[4];
} tetv;

static int
before(const vx_tetmesh *m, uint32_t a, uint32_t b)
{
	const double *p = m->pts + 3 * (size_t)a, *q = m->pts + 3 * (size_t)b;

	for (int k = 0; k < 3; k++)
		if (p[k] != q[k])
			return p[k] < q[k];
	return a < b;
}

static void
load_sorted(const vx_tetmesh *m, size_t t, const vx_tetray *r, tetv *v)
{
	const uint32_t *q = m->tet + 4 * t;
	uint32_t a[4] = { q[0], q[1], q[2], q[3] }, s;
	int i, j;

	/* insertion sort of four */
	for (i = 1; i < 4; i++)
		for (j = i; j > 0 && before(m, a[j], a[j - 1]); j--) {
			s = a[j];
			a[j] = a[j - 1];
			a[j - 1] = s;
		}
	for (i = 0; i < 4; i++) {
		v->id[i] = a[i];
		to_ray(r, m->pts + 3 * (size_t)a[i], &v->x[i], &v->y[i],
		    &v->z[i]);
		v->f[i] = m->val[a[i]];
	}
}

/* Depth and value where the ray meets edge (p, q), p before q in canonical
 * order: the point of the edge's 2D image nearest the origin. */
static void
edge_point(const tetv *v, int p, int q, double *t, double *f)
{
	double ex = v->x[q] - v->x[p], ey = v->y[q] - v->y[p];
	double l2 = ex * ex + ey * ey, s = 0.5;

	if (l2 > 0) {
		s = -(v->x[p] * ex + v->y[p] * ey) / l2;
		s = s < 0 ? 0 : s > 1 ? 1 : s;
	}
	*t = v->z[p] + s * (v->z[q] - v->z[p]);
	*f = v->f[p] + s * (v->f[q] - v->f[p]);
}

int
vx_tet_segment(const vx_tetmesh *m, size_t t, const vx_tetray *r,
    double *t0, double *f0, double *t1, double *f1)
{
	/* faces in canonical vertex order: the face opposite vertex k */
	static const int face[4][3] = {
		{ 1, 2, 3 }, { 0, 2, 3 }, { 0, 1, 3 }, { 0, 1, 2 },
	};
	double E[4][4], ht[2], hf[2];
	int S[4][4], i, j, k, nhit = 0, side[2];
	tetv v;

	load_sorted(m, t, r, &v);
	for (i = 0; i < 4; i++)
		for (j = i + 1; j < 4; j++) {
			S[i][j] = edge_sign(v.x[i], v.y[i], v.x[j], v.y[j],
			    &E[i][j]);
		}
	for (k = 0; k < 4; k++) {
		int a = face[k][0], b = face[k][1], c = face[k][2];
		/* around the face a -> b -> c -> a */
		int sab = S[a][b], sbc = S[b][c], sca = -S[a][c];
		if (sab == 0 || sab != sbc || sab != sca)
			continue;
		if (nhit == 2)
			return 0;  /* cannot happen with exact signs */
		/* sab > 0: the face (a, b, c) turns counterclockwise around
		 * the ray, i.e. its normal (b - a) x (c - a) has a positive
		 * component along d */
		side[nhit] = sab * ((k & 1) ? 1 : -1);
		/* barycentric weights: the edge opposite each vertex */
		double U = E[b][c], V = -E[a][c], W = E[a][b];
		int nz = (U != 0) + (V != 0) + (W != 0);
		if (nz == 3) {
			double det = U + V + W;
			ht[nhit] = (U * v.z[a] + V * v.z[b] + W * v.z[c]) / det;
			hf[nhit] = (U * v.f[a] + V * v.f[b] + W * v.f[c]) / det;
		} else if (nz == 2) {
			/* the ray meets an edge: evaluate on the edge alone, so
			 * every face around it gives the same value */
			int p = W == 0 ? a : V == 0 ? a : b;
			int q = W == 0 ? b : c;
			edge_point(&v, p, q, &ht[nhit], &hf[nhit]);
		} else if (nz == 1) {
			/* the ray meets a vertex: its own depth and value */
			int p = U != 0 ? a : V != 0 ? b : c;
			ht[nhit] = v.z[p];
			hf[nhit] = v.f[p];
		} else {
			/* a face of no visible area that the perturbed ray
			 * still crosses: its centroid stands for the point */
			ht[nhit] = (v.z[a] + v.z[b] + v.z[c]) / 3;
			hf[nhit] = (v.f[a] + v.f[b] + v.f[c]) / 3;
		}
		/* keep the value within its vertices' (rounding may step out),
		 * so leaf ranges of vertex values never cull a crossing */
		double lo = fmin(v.f[a], fmin(v.f[b], v.f[c]));
		double hi = fmax(v.f[a], fmax(v.f[b], v.f[c]));
		hf[nhit] = hf[nhit] < lo ? lo : hf[nhit] > hi ? hi : hf[nhit];
		nhit++;
	}
	if (nhit != 2)
		return 0;
	/* The normal of the face opposite vertex k, with its vertices in
	 * order, points to vertex k (inwards) when o * (-1)^(k+1) > 0, o the
	 * orientation det(v1 - v0, v2 - v0, v3 - v0) of the ordered tet (the
	 * parity of the permutation (a, b, c, k)); the ray enters through the
	 * face whose inward normal has a positive component along d, i.e.
	 * where side * o > 0, side = sab * (-1)^(k+1). */
	int o = vx_orient3d(m->pts + 3 * (size_t)v.id[0],
	    m->pts + 3 * (size_t)v.id[1], m->pts + 3 * (size_t)v.id[2],
	    m->pts + 3 * (size_t)v.id[3]);
	if (o != 0)
		i = side[0] * o < 0;  /* index of the entry face */
	else
		i = ht[1] < ht[0];
	*t0 = ht[i];
	*f0 = hf[i];
	*t1 = ht[!i];
	*f1 = hf[!i];
	return 1;
}

int
vx_tet_normal(const vx_tetmesh *m, size_t t, const vx_tetray *r, int sgn,
    double n[3])
{
	const uint32_t *q = m->tet + 4 * t;
	uint32_t a[4] = { q[0], q[1], q[2], q[3] }, s;
	double e[3][3], c[3][3], df[3], g[3], det, mx, len;
	int i, j, k;

	for (i = 1; i < 4; i++)
		for (j = i; j > 0 && a[j - 1] > a[j]; j--) {
			s = a[j];
			a[j] = a[j - 1];
			a[j - 1] = s;
		}
	const double *p0 = m->pts + 3 * (size_t)a[0];
	for (i = 0; i < 3; i++) {
		const double *p = m->pts + 3 * (size_t)a[i + 1];
		for (k = 0; k < 3; k++)
			e[i][k] = p[k] - p0[k];
		df[i] = (double)m->val[a[i + 1]] - (double)m->val[a[0]];
	}
	/* c[i] = e[i+1] x e[i+2]: grad = sum df[i] c[i] / det */
	for (i = 0; i < 3; i++) {
		const double *u = e[(i + 1) % 3], *w = e[(i + 2) % 3];
		c[i][0] = u[1] * w[2] - u[2] * w[1];
		c[i][1] = u[2] * w[0] - u[0] * w[2];
		c[i][2] = u[0] * w[1] - u[1] * w[0];
	}
	det = e[0][0] * c[0][0] + e[0][1] * c[0][1] + e[0][2] * c[0][2];
	mx = 0;
	for (k = 0; k < 3; k++) {
		g[k] = df[0] * c[0][k] + df[1] * c[1][k] + df[2] * c[2][k];
		if (det < 0)
			g[k] = -g[k];
		if (fabs(g[k]) > mx)
			mx = fabs(g[k]);
	}
	if (det != 0 && mx > 0 && isfinite(mx)) {
		for (k = 0; k < 3; k++)
			g[k] /= mx;
		len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
		for (k = 0; k < 3; k++)
			n[k] = g[k] / len;
		return 1;
	}
	mx = fmax(fabs(r->d[0]), fmax(fabs(r->d[1]), fabs(r->d[2])));
	for (k = 0; k < 3; k++)
		g[k] = r->d[k] / mx;
	len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
	for (k = 0; k < 3; k++)
		n[k] = (sgn < 0 ? -g[k] : g[k]) / len;
	return 0;
}

/* The nearest crossing in tet t of any isovalue, in [tmin, tmax): 1 with
 * *th, *which (isovalue index) and *enter, or 0. */
static int
tet_cross(const vx_tetmesh *m, size_t t, const vx_tetray *r,
    const double *iso, int niso, double tmin, double tmax, double *th,
    int *which, int *enter)
{
	const uint32_t *q = m->tet + 4 * t;
	double t0, f0, t1, f1, best = 0;
	int k, found = 0;

	for (k = 0; k < 4; k++)
		if (!isfinite(m->val[q[k]]))
			return 0;
	if (!vx_tet_segment(m, t, r, &t0, &f0, &t1, &f1))
		return 0;
	if (t1 < tmin || t0 >= tmax)
		return 0;
	for (k = 0; k < niso; k++) {
		int s0 = f0 >= iso[k], s1 = f1 >= iso[k];
		if (s0 == s1)
			continue;
		double x = t0 + (t1 - t0) * ((iso[k] - f0) / (f1 - f0));
		if (!(x >= t0))
			x = t0;
		if (!(x <= t1))
			x = t1;
		if (x < tmin || x >= tmax)
			continue;
		if (!found || x < best) {
			best = x;
			*which = k;
			*enter = s1;
			found = 1;
		}
	}
	if (!found || vx_tetmesh_degenerate(m, t))
		return 0;
	*th = best;
	return 1;
}

int
vx_tet_intersect(const vx_tetmesh *m, uint32_t tet, const double o[3],
    const double d[3], double iso, double tmin, double tmax, double *t,
    double n[3])
{
	vx_tetray r;
	int which, enter;

	if (tet >= m->ntet)
		return 0;
	vx_tetray_init(&r, o, d);
	if (!tet_cross(m, tet, &r, &iso, 1, tmin, tmax, t, &which, &enter))
		return 0;
	if (n != NULL)
		vx_tet_normal(m, tet, &r, enter ? 1 : -1, n);
	return 1;
}

int
vx_tet_nearest(const vx_tetmesh *m, const uint32_t *list, size_t n,
    const vx_tetray *r, const double *iso, int niso, double tmin,
    double tmax, vx_tethit *hit)
{
	size_t i;
	int found = 0;

	for (i = 0; i < n; i++) {
		uint32_t t = list[i];
		double th;
		int which, enter;
		if (t >= m->ntet ||
		    !tet_cross(m, t, r, iso, niso, tmin, tmax, &th, &which,
		    &enter))
			continue;
		if (found && (th > hit->t || (th == hit->t && (t > hit->tet ||
		    (t == hit->tet && which >= hit->iso)))))
			continue;
		hit->t = th;
		hit->tet = t;
		hit->iso = which;
		hit->enter = enter;
		found = 1;
	}
	if (found)
		vx_tet_normal(m, hit->tet, r, hit->enter ? 1 : -1, hit->n);
	return found;
}
