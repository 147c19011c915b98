/* irrvol.c: the irradiance volume: lattice, sparse bricks, exact
 * accumulators, interpolation, merging, and the IRRV chunk
 * (formats/irradiance.md). */
#include "vx_irrvol.h"
#include "vx_bspline.h"
#include "vx_half.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const vx_enum_name store_names[] = {
	{ "accum", VX_IRR_ACCUM }, { "f32", VX_IRR_F32 }, { "f16", VX_IRR_F16 },
	{ NULL, -1 }
};
const vx_enum vx_irr_store_enum = { "store", store_names, "?", 0 };


void
vx_irr_init(vx_irrvol *v)
{
	memset(v, 0, sizeof *v);
	v->fixed = VX_IRR_FIXED;
	v->ncomp = 3;
	v->channels = 3;
	v->scale = 1;
	v->offset = 0.5;
	v->seed = 1;
}

void
vx_irr_free(vx_irrvol *v)
{
	free(v->slot);
	free(v->acc);
	free(v->mean);
	free(v->flags);
	vx_irr_init(v);
}

int
vx_irr_lattice(const int64_t vdims[3], double s, int64_t dims[3], vx_err *e)
{
	double total = 1;

	if (!(s > 0) || !isfinite(s))
		return vx_err_set(e, VX_EUSAGE, "lattice scale %g: must be > 0",
		    s);
	for (int a = 0; a < 3; a++) {
		double n;

		if (vdims[a] < 1)
			return vx_err_set(e, VX_EDATA, "volume dims %lld",
			    (long long)vdims[a]);
		if (vdims[a] == 1) {
			dims[a] = 1;
			continue;
		}
		n = floor((double)(vdims[a] - 1) * s + 0.5) + 1;
		if (n < 2)
			n = 2;
		if (n > (double)VX_GRID_MAX_DIM)
			return vx_err_set(e, VX_EUSAGE, "lattice scale %g: %g "
			    "texels on an axis (at most %lld)", s, n,
			    (long long)VX_GRID_MAX_DIM);
		dims[a] = (int64_t)n;
		total *= n;
	}
	if (total > (double)VX_IRR_MAX_TEXELS)
		return vx_err_set(e, VX_EUSAGE, "lattice scale %g: %.0f texels "
		    "(at most %llu)", s, total,
		    (unsigned long long)VX_IRR_MAX_TEXELS);
	return 0;
}

static int
set_lattice(vx_irrvol *v, vx_err *e)
{
	size_t nb = 1;

	for (int a = 0; a < 3; a++) {
		v->step[a] = v->dims[a] > 1 ?
		    (double)(v->vdims[a] - 1) / (double)(v->dims[a] - 1) : 1;
		v->bdims[a] = (v->dims[a] + VX_IRR_BRICK - 1) / VX_IRR_BRICK;
		if (vx_mul_size(&nb, nb, (size_t)v->bdims[a]) != 0)
			return vx_err_set(e, VX_EDATA, "too many bricks");
	}
	free(v->slot);
	v->slot = vx_calloc(nb, sizeof *v->slot, e);
	return v->slot == NULL ? VX_ENOMEM : 0;
}

static size_t
nbricks(const vx_irrvol *v)
{
	return (size_t)v->bdims[0] * (size_t)v->bdims[1] * (size_t)v->bdims[2];
}

int
vx_irr_setup(vx_irrvol *v, const vx_grid *g, uint32_t vcrc, double s,
    vx_irr_store store, vx_err *e)
{
	return vx_irr_setup_sh(v, g, vcrc, s, store, 0, 3, e);
}

int
vx_irr_setup_sh(vx_irrvol *v, const vx_grid *g, uint32_t vcrc, double s,
    vx_irr_store store, int order, int channels, vx_err *e)
{
	int rc;

	vx_irr_free(v);
	if (order < 0 || order > 16 || (channels != 1 && channels != 3) ||
	    (order == 0 && channels != 3))
		return vx_err_set(e, VX_EUSAGE, "SH order %d with %d channels",
		    order, channels);
	v->sh_order = order;
	v->channels = channels;
	v->ncomp = order ? channels * order * order : 3;
	snprintf(v->volume, sizeof v->volume, "%s", g->name);
	memcpy(v->vdims, g->dims, sizeof v->vdims);
	v->vcrc = vcrc;
	v->scale = s;
	v->store = store;
	if ((rc = vx_irr_lattice(g->dims, s, v->dims, e)) != 0)
		return rc;
	return set_lattice(v, e);
}

int
vx_irr_reserve(vx_irrvol *v, size_t n, vx_err *e)
{
	size_t texels, b;
	void *p;

	if (n <= v->cap)
		return 0;
	if (vx_mul_size(&texels, n, VX_IRR_BRICK3) != 0)
		return vx_err_set(e, VX_ENOMEM, "irradiance volume too large");
	if (v->store == VX_IRR_ACCUM) {
		if (vx_mul_size(&b, texels, vx_irr_acc_bytes(v->ncomp)) != 0 ||
		    (p = realloc(v->acc, b)) == NULL)
			return vx_err_set(e, VX_ENOMEM, "out of memory for "
			    "%zu texels", texels);
		v->acc = p;
	}
	if (vx_mul_size(&b, texels, (size_t)v->ncomp * sizeof *v->mean) != 0 ||
	    (p = realloc(v->mean, b)) == NULL)
		return vx_err_set(e, VX_ENOMEM, "out of memory for %zu texels",
		    texels);
	v->mean = p;
	if ((p = realloc(v->flags, texels * sizeof *v->flags)) == NULL)
		return vx_err_set(e, VX_ENOMEM, "out of memory for %zu texels",
		    texels);
	v->flags = p;
	v->cap = n;
	return 0;
}

int
vx_irr_want_brick(vx_irrvol *v, size_t b, vx_err *e)
{
	size_t base;
	int rc;

	if (b >= nbricks(v))
		return vx_err_set(e, VX_EINTERNAL, "brick %zu of %zu", b,
		    nbricks(v));
	if (v->slot[b] != 0)
		return 0;
	if (v->nslot >= UINT32_MAX - 1)
		return vx_err_set(e, VX_ENOMEM, "too many bricks");
	if (v->nslot == v->cap &&
	    (rc = vx_irr_reserve(v, v->cap < 16 ? 16 : v->cap * 2, e)) != 0)
		return rc;
	base = v->nslot * VX_IRR_BRICK3;
	if (v->store == VX_IRR_ACCUM)
		memset(v->acc + base * vx_irr_acc_bytes(v->ncomp), 0,
		    VX_IRR_BRICK3 * vx_irr_acc_bytes(v->ncomp));
	memset(v->mean + (size_t)v->ncomp * base, 0,
	    (size_t)v->ncomp * VX_IRR_BRICK3 * sizeof *v->mean);
	memset(v->flags + base, 0, VX_IRR_BRICK3 * sizeof *v->flags);
	v->slot[b] = (uint32_t)++v->nslot;
	return 0;
}

int64_t
vx_irr_want_texel(vx_irrvol *v, int64_t i, int64_t j, int64_t k, vx_err *e)
{
	int64_t s;

	if (i < 0 || j < 0 || k < 0 || i >= v->dims[0] || j >= v->dims[1] ||
	    k >= v->dims[2]) {
		vx_err_set(e, VX_EINTERNAL, "texel %lld %lld %lld outside the "
		    "lattice", (long long)i, (long long)j, (long long)k);
		return -1;
	}
	if (vx_irr_want_brick(v, (size_t)(i / VX_IRR_BRICK + v->bdims[0] *
	    (j / VX_IRR_BRICK + v->bdims[1] * (k / VX_IRR_BRICK))), e) != 0)
		return -1;
	s = vx_irr_texel(v, i, j, k);
	v->flags[s] |= VX_TEXEL_WANTED;
	return s;
}

void
vx_irr_texel_point(const vx_irrvol *v, int64_t i, int64_t j, int64_t k,
    double p[3])
{
	p[0] = (double)i * v->step[0];
	p[1] = (double)j * v->step[1];
	p[2] = (double)k * v->step[2];
}

/* ---- accumulators ---- */

static const double LUM[3] = { 0.2126, 0.7152, 0.0722 };

/* 64 x 64 -> 128-bit product, portable */
static void
mul64(uint64_t a, uint64_t b, uint64_t *lo, uint64_t *hi)
{
	uint64_t a0 = a & 0xffffffffu, a1 = a >> 32;
	uint64_t b0 = b & 0xffffffffu, b1 = b >> 32;
	uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
	uint64_t mid = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);

	*lo = (mid << 32) | (p00 & 0xffffffffu);
	*hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
}

/* q: v in units of 1/scale (scale = 2^fixed: the product is exact),
 * rounded to nearest; *sat set when v is too large for 2^62 units */
static inline uint64_t
quant(double v, double scale, int *sat)
{
	double s;

	if (!(v > 0))                  /* 0, negative, NaN */
		return 0;
	s = v * scale;
	if (!(s < 4611686018427387904.0)) {   /* 2^62, and +Inf */
		*sat = 1;
		return (uint64_t)1 << 62;
	}
	return (uint64_t)llrint(s);
}

/* qs: the signed quant (NaN is 0) */
static inline int64_t
qs(double v, double scale, int *sat)
{
	return v < 0 ? -(int64_t)quant(-v, scale, sat) :
	    (int64_t)quant(v, scale, sat);
}

/* add: *a += q, saturating at +-INT64_MAX */
static inline void
add_sat(int64_t *a, int64_t q, int *sat)
{
	if (q > 0 && *a > INT64_MAX - q) {
		*a = INT64_MAX;
		*sat = 1;
	} else if (q < 0 && *a < -INT64_MAX - q) {
		*a = -INT64_MAX;
		*sat = 1;
	} else {
		*a += q;
	}
}

/* the luminance of a sample or a mean (see vx_irr_acc_add) */
static double
lum(const vx_irrvol *v, const double *val)
{
	size_t cs = v->sh_order ? (size_t)v->sh_order * (size_t)v->sh_order : 1;
	double y = 0;

	if (v->channels == 1)
		return val[0] > 0 ? val[0] : 0;
	for (int c = 0; c < 3; c++)
		if (val[c * cs] > 0 && isfinite(val[c * cs]))
			y += LUM[c] * val[c * cs];
	return y;
}

void
vx_irr_acc_add(const vx_irrvol *v, vx_irr_acc *a, const double *val)
{
	double scale = ldexp(1, v->fixed);
	int sat = 0;
	uint64_t qy, lo, hi;

	if (v->sh_order)
		for (int c = 0; c < v->ncomp; c++)
			add_sat(&a->sum[c], qs(val[c], scale, &sat), &sat);
	else
		for (int c = 0; c < v->ncomp; c++)
			add_sat(&a->sum[c], (int64_t)quant(val[c], scale, &sat),
			    &sat);
	qy = quant(lum(v, val), scale, &sat);
	mul64(qy, qy, &lo, &hi);
	a->sq[0] += lo;
	hi += a->sq[0] < lo;
	if (a->sq[1] > UINT64_MAX - hi) {
		a->sq[0] = a->sq[1] = UINT64_MAX;
		sat = 1;
	} else {
		a->sq[1] += hi;
	}
	if (a->count < UINT32_MAX)
		a->count++;
	if (sat)
		a->flags |= VX_TEXEL_OVERFLOW;
}

void
vx_irr_acc_merge(const vx_irrvol *v, vx_irr_acc *a, const vx_irr_acc *b)
{
	uint64_t lo;
	int sat = 0;

	for (int c = 0; c < v->ncomp; c++)
		add_sat(&a->sum[c], b->sum[c], &sat);
	if (sat)
		a->flags |= VX_TEXEL_OVERFLOW;
	lo = a->sq[0] + b->sq[0];
	{
		uint64_t carry = lo < a->sq[0], hi = b->sq[1] + carry;

		if (hi < carry || a->sq[1] > UINT64_MAX - hi) {
			a->sq[0] = a->sq[1] = UINT64_MAX;
			a->flags |= VX_TEXEL_OVERFLOW;
		} else {
			a->sq[0] = lo;
			a->sq[1] += hi;
		}
	}
	a->count = a->count > UINT32_MAX - b->count ? UINT32_MAX :
	    a->count + b->count;
	a->flags |= b->flags;
}

void
vx_irr_acc_mean(const vx_irrvol *v, const vx_irr_acc *a, double *out)
{
	for (int c = 0; c < v->ncomp; c++)
		out[c] = a->count ? ldexp((double)a->sum[c], -v->fixed) /
		    (double)a->count : 0;
}

double
vx_irr_acc_relerr(const vx_irrvol *v, const vx_irr_acc *a)
{
	double m[VX_IRR_MAX_COMP], my, sq, var, n = a->count;

	if (a->count < 2)
		return 0;
	vx_irr_acc_mean(v, a, m);
	my = lum(v, m);
	if (!(my > 0))
		return 0;
	sq = ldexp(ldexp((double)a->sq[1], 64) + (double)a->sq[0],
	    -2 * v->fixed);
	var = (sq / n - my * my) * n / (n - 1);
	if (var < 0)
		var = 0;
	return sqrt(var / n) / my;
}

void
vx_irr_finish(vx_irrvol *v)
{
	size_t n = v->nslot * VX_IRR_BRICK3;

	if (v->store != VX_IRR_ACCUM)
		return;
	for (size_t s = 0; s < n; s++) {
		const vx_irr_acc *a = vx_irr_accp(v, (int64_t)s);
		double m[VX_IRR_MAX_COMP];

		vx_irr_acc_mean(v, a, m);
		for (int c = 0; c < v->ncomp; c++)
			v->mean[(size_t)v->ncomp * s + (size_t)c] = (float)m[c];
		v->flags[s] = a->flags | (a->count > 0 ? VX_TEXEL_SAMPLED : 0);
	}
}

/* ---- lookup ---- */

/* lattice coordinates of p: base texel (floor, clamped so base+1 is inside
 * where the axis has two texels) and fraction */
static void
lattice_coord(const vx_irrvol *v, const double p[3], int64_t b[3],
    double f[3])
{
	for (int a = 0; a < 3; a++) {
		double u = p[a] / v->step[a], hi = (double)(v->dims[a] - 1);

		if (!(u > 0))
			u = 0;
		if (u > hi)
			u = hi;
		b[a] = (int64_t)floor(u);
		if (b[a] > v->dims[a] - 2)
			b[a] = v->dims[a] - 2;
		if (b[a] < 0)
			b[a] = 0;
		f[a] = u - (double)b[a];
		if (f[a] > 1)
			f[a] = 1;
	}
}

/* weights: the texels and raw weights of a lookup; *ws gets their sum
 * (n = 0 when it is not positive) */
static int
weights(const vx_irrvol *v, const double p[3], vx_interp m,
    const vx_grid *g, double iso, int64_t idx[64], double w[64], double *ws)
{
	int64_t b[3];
	double f[3], wsum = 0;
	int n = 0;

	*ws = 1;

	lattice_coord(v, p, b, f);
	if (m == VX_INTERP_NEAREST) {
		int64_t s = vx_irr_texel(v, b[0] + (f[0] >= 0.5),
		    b[1] + (f[1] >= 0.5), b[2] + (f[2] >= 0.5));

		if (s >= 0 && vx_irr_usable(v, s)) {
			idx[0] = s;
			w[0] = 1;
			return 1;
		}
		m = VX_INTERP_TRILINEAR;  /* unusable nearest: its neighbours */
	}
	if (m == VX_INTERP_NEAREST_ISO) {
		double best = INFINITY;
		int64_t bs = -1;

		for (int k = 0; k < 8; k++) {
			int64_t i = b[0] + (k & 1), j = b[1] + ((k >> 1) & 1),
			    l = b[2] + ((k >> 2) & 1), s = vx_irr_texel(v, i, j, l);
			double q[3], d;

			if (s < 0 || !vx_irr_usable(v, s))
				continue;
			vx_irr_texel_point(v, i, j, l, q);
			d = fabs(vx_grid_trilinear(g, q) - iso);
			if (d < best) {
				best = d;
				bs = s;
			}
		}
		if (bs < 0)
			return 0;
		idx[0] = bs;
		w[0] = 1;
		return 1;
	}
	if (m == VX_INTERP_TRICUBIC) {
		double wt3[3][4];

		for (int a = 0; a < 3; a++)
			vx_bspline_weights(f[a], wt3[a], 0);
		for (int z = 0; z < 4; z++)
			for (int y = 0; y < 4; y++)
				for (int x = 0; x < 4; x++) {
					int64_t s = vx_irr_texel(v, b[0] - 1 + x,
					    b[1] - 1 + y, b[2] - 1 + z);
					double wt = wt3[0][x] * wt3[1][y] *
					    wt3[2][z];

					if (s < 0 || !vx_irr_usable(v, s))
						continue;
					wsum += wt;
					idx[n] = s;
					w[n++] = wt;
				}
	} else {
		for (int k = 0; k < 8; k++) {
			int64_t s = vx_irr_texel(v, b[0] + (k & 1),
			    b[1] + ((k >> 1) & 1), b[2] + ((k >> 2) & 1));
			double wt = ((k & 1) ? f[0] : 1 - f[0]) *
			    (((k >> 1) & 1) ? f[1] : 1 - f[1]) *
			    (((k >> 2) & 1) ? f[2] : 1 - f[2]);

			if (s < 0 || !vx_irr_usable(v, s))
				continue;
			wsum += wt;
			idx[n] = s;
			w[n++] = wt;
		}
	}
	*ws = wsum;
	return wsum > 0 ? n : 0;
}

int
vx_irr_weights(const vx_irrvol *v, const double p[3], vx_interp m,
    const vx_grid *g, double iso, int64_t idx[64], double w[64])
{
	double ws;
	int n = weights(v, p, m, g, iso, idx, w, &ws);

	for (int k = 0; k < n; k++)
		w[k] /= ws;
	return n;
}

/* trilinear: the trilinear lookup of the lattice cell at b with fractions
 * f (0 <= b[a] <= dims[a] - 2): each texel's storage index from its
 * brick's slot and its place in the brick, per axis computed once for the
 * cell's two layers; RGB summed in registers.  The same operations in the
 * same order as weights and the general sums below (texels k = x + 2y +
 * 4z, the usable ones, each weight the same product), so the same bits. */
static inline int
trilinear(const vx_irrvol *v, const int64_t b[3], const double f[3],
    double *out)
{
	int64_t bk[3][2], lc[3][2];
	double wsum = 0, o[VX_IRR_MAX_COMP], wa[3][2];
	int nc = v->ncomp;

	for (int a = 0; a < 3; a++) {
		for (int h = 0; h < 2; h++) {
			bk[a][h] = (b[a] + h) / VX_IRR_BRICK;
			lc[a][h] = (b[a] + h) % VX_IRR_BRICK;
		}
		wa[a][0] = 1 - f[a];
		wa[a][1] = f[a];
	}
	for (int c = 0; c < nc; c++)
		o[c] = 0;
	for (int k = 0; k < 8; k++) {
		int x = k & 1, y = (k >> 1) & 1, z = (k >> 2) & 1;
		uint32_t slot = v->slot[bk[0][x] + v->bdims[0] * (bk[1][y] +
		    v->bdims[1] * bk[2][z])];
		double wt = wa[0][x] * wa[1][y] * wa[2][z];
		int64_t s;
		const float *t;

		if (slot == 0)
			continue;
		s = (int64_t)(slot - 1) * VX_IRR_BRICK3 + lc[0][x] +
		    VX_IRR_BRICK * (lc[1][y] + VX_IRR_BRICK * lc[2][z]);
		if (!vx_irr_usable(v, s))
			continue;
		t = v->mean + (size_t)nc * (size_t)s;
		wsum += wt;
		if (nc == 3) {
			o[0] += wt * t[0];
			o[1] += wt * t[1];
			o[2] += wt * t[2];
		} else {
			for (int c = 0; c < nc; c++)
				o[c] += wt * t[c];
		}
	}
	if (!(wsum > 0)) {
		for (int c = 0; c < nc; c++)
			out[c] = 0;
		return 0;
	}
	for (int c = 0; c < nc; c++)
		out[c] = wsum != 1 ? o[c] / wsum : o[c];
	return 1;
}

int
vx_irr_lookup(const vx_irrvol *v, const double p[3], vx_interp m,
    const vx_grid *g, double iso, double *out)
{
	int64_t idx[64];
	double w[64], ws;
	int n, nc = v->ncomp;

	if ((m == VX_INTERP_TRILINEAR || m == VX_INTERP_UNKNOWN) &&
	    v->dims[0] >= 2 && v->dims[1] >= 2 &&
	    v->dims[2] >= 2) {
		int64_t b[3];
		double f[3];

		lattice_coord(v, p, b, f);
		return trilinear(v, b, f, out);
	}
	n = weights(v, p, m, g, iso, idx, w, &ws);

	for (int c = 0; c < nc; c++)
		out[c] = 0;
	for (int k = 0; k < n; k++) {
		const float *t = v->mean + (size_t)nc * (size_t)idx[k];

		for (int c = 0; c < nc; c++)
			out[c] += w[k] * t[c];
	}
	if (n == 0)
		return 0;
	if (ws != 1)      /* nearest modes give one weight of 1 exactly */
		for (int c = 0; c < nc; c++)
			out[c] /= ws;
	return 1;
}

void
vx_irr_reach(const vx_irrvol *v, const double p[3], vx_interp m,
    vx_irr_need_fn fn, void *ctx)
{
	int64_t b[3];
	double f[3];
	int lo = 0, hi = 1;

	lattice_coord(v, p, b, f);
	if (m == VX_INTERP_TRICUBIC) {
		lo = -1;
		hi = 2;
	}
	for (int z = lo; z <= hi; z++)
		for (int y = lo; y <= hi; y++)
			for (int x = lo; x <= hi; x++) {
				int64_t i = b[0] + x, j = b[1] + y, k = b[2] + z;

				if (i < 0 || j < 0 || k < 0 || i >= v->dims[0] ||
				    j >= v->dims[1] || k >= v->dims[2])
					continue;
				fn(ctx, i, j, k);
			}
}

/* ---- merging and finalizing ---- */

static int
same_lattice(const vx_irrvol *a, const vx_irrvol *b, vx_err *e)
{
	if (strcmp(a->volume, b->volume) != 0)
		return vx_err_set(e, VX_EDATA, "volumes differ ('%s', '%s')",
		    a->volume, b->volume);
	for (int k = 0; k < 3; k++)
		if (a->vdims[k] != b->vdims[k] || a->dims[k] != b->dims[k])
			return vx_err_set(e, VX_EDATA, "lattices differ");
	if (a->vcrc != b->vcrc)
		return vx_err_set(e, VX_EDATA, "baked from different samples "
		    "(volume-crc32 %08x, %08x)", (unsigned)a->vcrc,
		    (unsigned)b->vcrc);
	if (strcmp(a->key, b->key) != 0)
		return vx_err_set(e, VX_EDATA, "baked with different settings "
		    "(key %s, %s)", a->key, b->key);
	if (a->store != VX_IRR_ACCUM || b->store != VX_IRR_ACCUM)
		return vx_err_set(e, VX_EDATA, "a final (%s) bake cannot be "
		    "merged or resumed",
		    vx_enum_str(&vx_irr_store_enum, a->store != VX_IRR_ACCUM ?
		    a->store : b->store));
	if (a->fixed != b->fixed)
		return vx_err_set(e, VX_EDATA, "fixed-point bits differ");
	if (a->sh_order != b->sh_order || a->channels != b->channels)
		return vx_err_set(e, VX_EDATA, "texel contents differ");
	return 0;
}

/* the same samples of a texel in both bakes (bakes of overlapping texel
 * ranges): kept once */
static int
same_samples(const vx_irrvol *a, const vx_irr_acc *x, const vx_irrvol *b,
    const vx_irr_acc *y)
{
	return a->first == b->first && x->count == y->count &&
	    memcmp(x->sum, y->sum, (size_t)a->ncomp * sizeof *x->sum) == 0 &&
	    memcmp(x->sq, y->sq, sizeof x->sq) == 0;
}

int
vx_irr_merge(vx_irrvol *a, const vx_irrvol *b, vx_err *e)
{
	size_t nb = nbricks(a);
	int rc;

	if ((rc = same_lattice(a, b, e)) != 0)
		return rc;
	/* check every texel first, so a refused merge leaves a unchanged */
	for (size_t br = 0; br < nb; br++) {
		int64_t ob, oa;

		if (b->slot[br] == 0 || a->slot[br] == 0)
			continue;
		ob = (int64_t)(b->slot[br] - 1) * VX_IRR_BRICK3;
		oa = (int64_t)(a->slot[br] - 1) * VX_IRR_BRICK3;
		for (int t = 0; t < VX_IRR_BRICK3; t++) {
			const vx_irr_acc *pa = vx_irr_accp(a, oa + t);
			const vx_irr_acc *pb = vx_irr_accp(b, ob + t);

			if (pa->count > 0 && pb->count > 0 &&
			    !same_samples(a, pa, b, pb) &&
			    (uint64_t)a->first + pa->count != b->first)
				return vx_err_set(e, VX_EDATA, "sample ranges do "
				    "not join: a texel has samples [%u, %llu), "
				    "the other bake starts at %u", a->first,
				    (unsigned long long)a->first + pa->count,
				    b->first);
		}
	}
	for (size_t br = 0; br < nb; br++) {
		int64_t ob, oa;

		if (b->slot[br] == 0)
			continue;
		if ((rc = vx_irr_want_brick(a, br, e)) != 0)
			return rc;
		ob = (int64_t)(b->slot[br] - 1) * VX_IRR_BRICK3;
		oa = (int64_t)(a->slot[br] - 1) * VX_IRR_BRICK3;
		for (int t = 0; t < VX_IRR_BRICK3; t++) {
			vx_irr_acc *pa = vx_irr_accp(a, oa + t);
			const vx_irr_acc *pb = vx_irr_accp(b, ob + t);

			if (pb->count == 0 || same_samples(a, pa, b, pb)) {
				pa->flags |= pb->flags;
				continue;
			}
			if (pa->count == 0) {
				uint32_t fl = pa->flags;

				memcpy(pa, pb, vx_irr_acc_bytes(a->ncomp));
				pa->flags |= fl;
				continue;
			}
			vx_irr_acc_merge(a, pa, pb);
		}
	}
	if ((uint64_t)a->first + a->samples == b->first)
		a->samples += b->samples;
	else if (b->samples > a->samples)
		a->samples = b->samples;
	vx_irr_finish(a);
	return 0;
}

/* half_round: x rounded through binary16; a finite x beyond its range
 * saturates at the largest finite half (65504), *sat set, so every mean a
 * final f16 store keeps reads back (readers refuse infinities) */
static float
half_round(float x, int *sat)
{
	float h = vx_half_to_float(vx_half_from_float(x));

	if (isinf(h) && isfinite(x)) {
		*sat = 1;
		return copysignf(65504.0f, x);
	}
	return h;
}

void
vx_irr_settle(vx_irrvol *v, int64_t s, const vx_irr_acc *a)
{
	double m[VX_IRR_MAX_COMP];
	float *out = v->mean + (size_t)v->ncomp * (size_t)s;
	int sat = 0;

	vx_irr_acc_mean(v, a, m);
	for (int c = 0; c < v->ncomp; c++) {
		out[c] = (float)m[c];
		if (v->store == VX_IRR_F16)
			out[c] = half_round(out[c], &sat);
	}
	v->flags[s] = a->flags & ~(uint32_t)(VX_TEXEL_SAMPLED |
	    (a->count == 0 ? VX_TEXEL_WANTED : 0));
	if (sat)
		v->flags[s] |= VX_TEXEL_OVERFLOW;
}

int
vx_irr_finalize(vx_irrvol *v, vx_irr_store store, vx_err *e)
{
	if (store == VX_IRR_ACCUM || v->store != VX_IRR_ACCUM) {
		if (store == v->store)
			return 0;
		return vx_err_set(e, VX_EUSAGE, "cannot turn a %s bake into %s",
		    vx_enum_str(&vx_irr_store_enum, v->store),
		    vx_enum_str(&vx_irr_store_enum, store));
	}
	/* each texel as a final bake settles it (a texel without samples
	 * keeps no count in a final store, so its wanted bit goes) */
	v->store = store;
	for (size_t t = 0; t < v->nslot * VX_IRR_BRICK3; t++)
		vx_irr_settle(v, (int64_t)t, vx_irr_accp(v, (int64_t)t));
	free(v->acc);
	v->acc = NULL;
	return 0;
}

size_t
vx_irr_texel_bytes(vx_irr_store s, int ncomp)
{
	switch (s) {
	case VX_IRR_ACCUM:
		return vx_irr_acc_bytes(ncomp);
	case VX_IRR_F32:
		return 4 + 4 * (size_t)ncomp;
	case VX_IRR_F16:
		return 2 + 2 * (size_t)ncomp;
	default:
		return 0;
	}
}

size_t
vx_irr_texel_memory(vx_irr_store s, int ncomp)
{
	size_t t = 4 + 4 * (size_t)ncomp;       /* flags, mean */

	return s == VX_IRR_ACCUM ? t + vx_irr_acc_bytes(ncomp) : t;
}

size_t
vx_irr_bytes(const vx_irrvol *v)
{
	return v->nslot * VX_IRR_BRICK3 * vx_irr_texel_memory(v->store,
	    v->ncomp) + nbricks(v) * sizeof *v->slot;
}

/* ---- the IRRV chunk ---- */

int
vx_irr_to_chunk(const vx_irrvol *v, int zlevel, vx_chunk *c, vx_err *e)
{
	size_t nb = nbricks(v), mapn = (nb + 7) / 8, rec, n;
	unsigned char *body = NULL, *q;
	vx_hdr h;
	int rc;

	rec = vx_irr_texel_bytes(v->store, v->ncomp);
	if (vx_mul_size(&n, v->nslot * VX_IRR_BRICK3, rec) != 0 ||
	    vx_add_size(&n, n, mapn) != 0)
		return vx_err_set(e, VX_ENOMEM, "irradiance volume too large");
	vx_hdr_init(&h);
	if ((rc = vx_hdr_set(&h, "volume", e, "%s", v->volume)) ||
	    (rc = vx_hdr_set(&h, "volume-dims", e, "%lld %lld %lld",
	    (long long)v->vdims[0], (long long)v->vdims[1],
	    (long long)v->vdims[2])) ||
	    (rc = vx_hdr_set(&h, "volume-crc32", e, "%08x",
	    (unsigned)v->vcrc)) ||
	    (rc = vx_hdr_set(&h, "lattice-dims", e, "%lld %lld %lld",
	    (long long)v->dims[0], (long long)v->dims[1],
	    (long long)v->dims[2])) ||
	    (rc = vx_hdr_set(&h, "scale", e, "%.17g", v->scale)) ||
	    (v->sh_order > 0 &&
	    ((rc = vx_hdr_set(&h, "order", e, "%d", v->sh_order)) ||
	    (rc = vx_hdr_set(&h, "channels", e, "%d", v->channels)))) ||
	    (rc = vx_hdr_set(&h, "brick", e, "%d", VX_IRR_BRICK)) ||
	    (rc = vx_hdr_set(&h, "bricks", e, "%zu", v->nslot)) ||
	    (rc = vx_hdr_set(&h, "store", e, "%s",
	    vx_enum_str(&vx_irr_store_enum, v->store))) ||
	    (v->store == VX_IRR_ACCUM &&
	    (rc = vx_hdr_set(&h, "fixed", e, "%d", v->fixed))) ||
	    (rc = vx_hdr_set(&h, "first-sample", e, "%u", v->first)) ||
	    (rc = vx_hdr_set(&h, "samples", e, "%u", v->samples)) ||
	    (rc = vx_hdr_set(&h, "offset", e, "%.17g", v->offset)) ||
	    (rc = vx_hdr_set(&h, "seed", e, "%llu",
	    (unsigned long long)v->seed)) ||
	    (rc = vx_hdr_set(&h, "side", e, "%s", v->high ? "high" : "low")) ||
	    (rc = vx_hdr_set(&h, "key", e, "%s", v->key[0] ? v->key :
	    "0000000000000000")) ||
	    (v->settings[0] &&
	    (rc = vx_hdr_set_str(&h, "settings", v->settings, e))))
		goto out;
	if ((body = vx_calloc(n ? n : 1, 1, e)) == NULL) {
		rc = VX_ENOMEM;
		goto out;
	}
	for (size_t b = 0; b < nb; b++)
		if (v->slot[b] != 0)
			body[b / 8] |= (unsigned char)(1u << (b % 8));
	q = body + mapn;
	for (size_t b = 0; b < nb; b++) {
		size_t base;

		if (v->slot[b] == 0)
			continue;
		base = (size_t)(v->slot[b] - 1) * VX_IRR_BRICK3;
		for (size_t t = base; t < base + VX_IRR_BRICK3; t++) {
			int nc = v->ncomp;

			if (v->store == VX_IRR_ACCUM) {
				const vx_irr_acc *a = vx_irr_accp(v, (int64_t)t);

				vx_put_le32(q, a->count);
				vx_put_le32(q + 4, a->flags);
				for (int ch = 0; ch < nc; ch++)
					vx_put_le64(q + 8 + 8 * ch,
					    (uint64_t)a->sum[ch]);
				vx_put_le64(q + 8 + 8 * nc, a->sq[0]);
				vx_put_le64(q + 16 + 8 * nc, a->sq[1]);
			} else if (v->store == VX_IRR_F32) {
				vx_put_le32(q, v->flags[t] &
				    ~(uint32_t)VX_TEXEL_SAMPLED);
				for (int ch = 0; ch < nc; ch++) {
					uint32_t u;

					memcpy(&u, &v->mean[(size_t)nc * t +
					    (size_t)ch], 4);
					vx_put_le32(q + 4 + 4 * ch, u);
				}
			} else {
				uint16_t f = (uint16_t)v->flags[t];

				q[0] = (unsigned char)(f & 0xff);
				q[1] = (unsigned char)(f >> 8);
				for (int ch = 0; ch < nc; ch++) {
					uint16_t hv = vx_half_from_float(
					    v->mean[(size_t)nc * t + (size_t)ch]);

					q[2 + 2 * ch] = (unsigned char)(hv & 0xff);
					q[3 + 2 * ch] = (unsigned char)(hv >> 8);
				}
			}
			q += rec;
		}
	}
	rc = vx_payload_make(c, v->sh_order ? VX_CHUNK_SHXFER : VX_CHUNK_IRRAD,
	    &h, body, n, zlevel, e);
out:
	free(body);
	vx_hdr_free(&h);
	if (rc != 0)
		vx_err_push(e, v->sh_order ? "SH transfer volume" :
		    "irradiance volume");
	return rc;
}

static int
parse_u32(const vx_hdr *h, const char *key, uint32_t *out, vx_err *e)
{
	int64_t x;
	int rc;

	if ((rc = vx_hdr_get_i64(h, key, &x, 1, e)) != 0)
		return rc;
	if (x < 0 || x > (int64_t)UINT32_MAX)
		return vx_err_set(e, VX_EDATA, "%s %lld: out of range", key,
		    (long long)x);
	*out = (uint32_t)x;
	return 0;
}

static int
parse_hex(const char *s, int digits, uint64_t *out)
{
	uint64_t x = 0;

	if (s == NULL || (int)strlen(s) != digits)
		return -1;
	for (int i = 0; i < digits; i++) {
		int c = s[i], d;

		if (c >= '0' && c <= '9')
			d = c - '0';
		else if (c >= 'a' && c <= 'f')
			d = c - 'a' + 10;
		else
			return -1;
		x = x << 4 | (uint64_t)d;
	}
	*out = x;
	return 0;
}

static int
from_chunk(vx_irrvol *v, const vx_chunk *c, vx_err *e)
{
	const unsigned char *body, *q;
	unsigned char *raw = NULL;
	size_t bodylen, nb, mapn, rec, expect, nset = 0;
	const char *s;
	vx_hdr h;
	int64_t d[3];
	uint64_t x;
	uint32_t nstored = 0, brick = 0;
	int rc, st = -1;

	vx_hdr_init(&h);
	if ((rc = vx_payload_parse(c, &h, &body, &bodylen, e)) != 0)
		goto out;
	if (memcmp(c->type, VX_CHUNK_SHXFER, 4) == 0) {
		int64_t o[1], ch[1];

		if ((rc = vx_hdr_get_i64(&h, "order", o, 1, e)) != 0 ||
		    (rc = vx_hdr_get_i64(&h, "channels", ch, 1, e)) != 0)
			goto out;
		if (o[0] < 1 || o[0] > 16 || (ch[0] != 1 && ch[0] != 3)) {
			rc = vx_err_set(e, VX_EDATA, "order %lld, channels "
			    "%lld: order 1 to 16, channels 1 or 3",
			    (long long)o[0], (long long)ch[0]);
			goto out;
		}
		v->sh_order = (int)o[0];
		v->channels = (int)ch[0];
		v->ncomp = v->channels * v->sh_order * v->sh_order;
	}
	if ((s = vx_hdr_get(&h, "volume")) == NULL || !*s ||
	    strlen(s) >= sizeof v->volume) {
		rc = vx_err_set(e, VX_EDATA, "volume: missing or too long");
		goto out;
	}
	snprintf(v->volume, sizeof v->volume, "%s", s);
	if ((rc = vx_hdr_get_i64(&h, "volume-dims", v->vdims, 3, e)) != 0 ||
	    (rc = vx_hdr_get_i64(&h, "lattice-dims", d, 3, e)) != 0 ||
	    (rc = vx_hdr_get_f64(&h, "scale", &v->scale, 1, e)) != 0 ||
	    (rc = parse_u32(&h, "brick", &brick, e)) != 0 ||
	    (rc = parse_u32(&h, "bricks", &nstored, e)) != 0 ||
	    (rc = parse_u32(&h, "first-sample", &v->first, e)) != 0)
		goto out;
	if (parse_hex(vx_hdr_get(&h, "volume-crc32"), 8, &x) != 0) {
		rc = vx_err_set(e, VX_EDATA, "volume-crc32: not 8 hex digits");
		goto out;
	}
	v->vcrc = (uint32_t)x;
	if (parse_hex(vx_hdr_get(&h, "key"), 16, &x) != 0) {
		rc = vx_err_set(e, VX_EDATA, "key: not 16 hex digits");
		goto out;
	}
	snprintf(v->key, sizeof v->key, "%s", vx_hdr_get(&h, "key"));
	if ((s = vx_hdr_get(&h, "settings")) != NULL)
		snprintf(v->settings, sizeof v->settings, "%s", s);
	{
		int found = 0;
		double x2;

		if ((rc = vx_hdr_get_f64_opt(&h, "offset", &v->offset, 1, &found,
		    e)) != 0)
			goto out;
		if ((rc = vx_hdr_get_f64_opt(&h, "seed", &x2, 1, &found, e)) != 0)
			goto out;
		if (found) {
			if (!(x2 >= 0 && x2 <= 9007199254740992.0)) {
				rc = vx_err_set(e, VX_EDATA, "seed: out of range");
				goto out;
			}
			v->seed = (uint64_t)x2;
		}
		if ((rc = vx_hdr_get_f64_opt(&h, "samples", &x2, 1, &found,
		    e)) != 0)
			goto out;
		if (found) {
			if (!(x2 >= 0 && x2 <= 4294967295.0)) {
				rc = vx_err_set(e, VX_EDATA, "samples: out of range");
				goto out;
			}
			v->samples = (uint32_t)x2;
		}
		s = vx_hdr_get(&h, "side");
		v->high = s != NULL && strcmp(s, "high") == 0;
	}
	if (brick != VX_IRR_BRICK) {
		rc = vx_err_set(e, VX_EDATA, "brick %u: only %d is supported",
		    brick, VX_IRR_BRICK);
		goto out;
	}
	s = vx_hdr_get(&h, "store");
	if (s == NULL || (st = vx_enum_val(&vx_irr_store_enum, s)) < 0) {
		rc = vx_err_set(e, VX_EDATA, "store '%s': not accum, f32 or f16",
		    s ? s : "");
		goto out;
	}
	v->store = (vx_irr_store)st;
	if (v->store == VX_IRR_ACCUM) {
		uint32_t fx = 0;

		if ((rc = parse_u32(&h, "fixed", &fx, e)) != 0)
			goto out;
		if (fx > 40) {
			rc = vx_err_set(e, VX_EDATA, "fixed %u: at most 40", fx);
			goto out;
		}
		v->fixed = (int)fx;
	}
	if (!(v->scale > 0) || !isfinite(v->scale)) {
		rc = vx_err_set(e, VX_EDATA, "scale: must be > 0");
		goto out;
	}
	{
		double total = 1;

		for (int a = 0; a < 3; a++) {
			if (v->vdims[a] < 1 || v->vdims[a] > VX_GRID_MAX_DIM ||
			    d[a] < 1 || d[a] > VX_GRID_MAX_DIM ||
			    (v->vdims[a] == 1) != (d[a] == 1)) {
				rc = vx_err_set(e, VX_EDATA, "lattice-dims %lld "
				    "%lld %lld do not fit volume-dims",
				    (long long)d[0], (long long)d[1],
				    (long long)d[2]);
				goto out;
			}
			total *= (double)d[a];
		}
		if (total > (double)VX_IRR_MAX_TEXELS) {
			rc = vx_err_set(e, VX_EDATA, "too many texels");
			goto out;
		}
	}
	memcpy(v->dims, d, sizeof d);
	nb = (size_t)((d[0] + 7) / 8) * (size_t)((d[1] + 7) / 8) *
	    (size_t)((d[2] + 7) / 8);
	if (nstored > nb) {
		rc = vx_err_set(e, VX_EDATA, "bricks %u: the lattice has %zu",
		    nstored, nb);
		goto out;
	}
	mapn = (nb + 7) / 8;
	rec = vx_irr_texel_bytes(v->store, v->ncomp);
	expect = mapn + (size_t)nstored * VX_IRR_BRICK3 * rec;
	if ((rc = vx_body_fits(&h, bodylen, expect, e)) != 0)
		goto out;
	if ((raw = vx_malloc(expect ? expect : 1, e)) == NULL) {
		rc = VX_ENOMEM;
		goto out;
	}
	if ((rc = vx_body_decode(&h, body, bodylen, raw, expect, e)) != 0)
		goto out;
	for (size_t b = 0; b < nb; b++)
		nset += (raw[b / 8] >> (b % 8)) & 1;
	for (size_t b = nb; b < 8 * mapn; b++)
		if ((raw[b / 8] >> (b % 8)) & 1) {
			rc = vx_err_set(e, VX_EDATA, "brick map: bits past the "
			    "last brick");
			goto out;
		}
	if (nset != nstored) {
		rc = vx_err_set(e, VX_EDATA, "brick map has %zu bricks, the "
		    "header says %u", nset, nstored);
		goto out;
	}
	if ((rc = set_lattice(v, e)) != 0 ||
	    (rc = vx_irr_reserve(v, nstored, e)) != 0)
		goto out;
	q = raw + mapn;
	for (size_t b = 0; b < nb; b++) {
		size_t base;

		if (!((raw[b / 8] >> (b % 8)) & 1))
			continue;
		if ((rc = vx_irr_want_brick(v, b, e)) != 0)
			goto out;
		base = (size_t)(v->slot[b] - 1) * VX_IRR_BRICK3;
		for (size_t t = base; t < base + VX_IRR_BRICK3; t++, q += rec) {
			int nc = v->ncomp;

			if (v->store == VX_IRR_ACCUM) {
				vx_irr_acc *a = vx_irr_accp(v, (int64_t)t);

				a->count = vx_le32(q);
				/* SAMPLED is derived from count, never stored */
				a->flags = vx_le32(q + 4) &
				    ~(uint32_t)VX_TEXEL_SAMPLED;
				for (int k = 0; k < nc; k++) {
					a->sum[k] = (int64_t)vx_le64(q + 8 + 8 * k);
					if (a->sum[k] < (v->sh_order ?
					    -INT64_MAX : 0)) {
						rc = vx_err_set(e, VX_EDATA,
						    "a negative irradiance sum");
						goto out;
					}
				}
				a->sq[0] = vx_le64(q + 8 + 8 * nc);
				a->sq[1] = vx_le64(q + 16 + 8 * nc);
				v->flags[t] = a->flags;
			} else {
				for (int k = 0; k < nc; k++) {
					float fv;

					if (v->store == VX_IRR_F32) {
						uint32_t u = vx_le32(q + 4 + 4 * k);

						memcpy(&fv, &u, 4);
					} else {
						fv = vx_half_to_float((uint16_t)(
						    q[2 + 2 * k] |
						    (unsigned)q[3 + 2 * k] << 8));
					}
					if (!isfinite(fv) || (v->sh_order == 0 &&
					    !(fv >= 0))) {
						rc = vx_err_set(e, VX_EDATA,
						    v->sh_order ? "coefficient %g: "
						    "must be finite" : "irradiance "
						    "%g: must be finite and >= 0",
						    fv);
						goto out;
					}
					v->mean[(size_t)nc * t + (size_t)k] = fv;
				}
				v->flags[t] = v->store == VX_IRR_F32 ?
				    vx_le32(q) : (uint32_t)(q[0] | q[1] << 8);
				v->flags[t] &= ~(uint32_t)VX_TEXEL_SAMPLED;
			}
		}
	}
	vx_irr_finish(v);
out:
	free(raw);
	vx_hdr_free(&h);
	return rc;
}

int
vx_irr_from_chunk(vx_irrvol *v, const vx_chunk *c, vx_err *e)
{
	int rc;

	vx_irr_init(v);
	if ((rc = from_chunk(v, c, e)) != 0) {
		vx_irr_free(v);
		vx_err_push(e, memcmp(c->type, VX_CHUNK_SHXFER, 4) == 0 ?
		    "SH transfer volume" : "irradiance volume");
	}
	return rc;
}

static int
find(vx_irrvol *v, const vx_stream *s, const char *tag, const char *volume,
    long *index, vx_err *e)
{
	long i = -1;
	int rc;

	vx_irr_init(v);
	if (index != NULL)
		*index = -1;
	while ((i = vx_stream_find(s, tag, (size_t)(i + 1))) >= 0) {
		if ((rc = vx_irr_from_chunk(v, &s->chunk[i], e)) != 0)
			return rc;
		if (volume == NULL || strcmp(v->volume, volume) == 0) {
			if (index != NULL)
				*index = i;
			return 0;
		}
		vx_irr_free(v);
	}
	return 0;
}

int
vx_irr_from_stream(vx_irrvol *v, const vx_stream *s, const char *volume,
    long *index, vx_err *e)
{
	return find(v, s, VX_CHUNK_IRRAD, volume, index, e);
}

int
vx_irr_sh_from_stream(vx_irrvol *v, const vx_stream *s, const char *volume,
    long *index, vx_err *e)
{
	return find(v, s, VX_CHUNK_SHXFER, volume, index, e);
}
