/* tonemap.c: exposure, tone operators, transfer functions, dither. */
#include "vx_tonemap.h"

#include <math.h>
#include <string.h>

/* Rec. 709 / sRGB luminance weights of linear RGB. */
#define LUM_R 0.2126
#define LUM_G 0.7152
#define LUM_B 0.0722

static const vx_enum_name op_names[] = {
	{ "clamp", VX_TM_CLAMP }, { "reinhard", VX_TM_REINHARD },
	{ "aces", VX_TM_ACES }, { NULL, VX_TM_UNKNOWN }
};
const vx_enum vx_tonemap_op_enum = { "operator", op_names, "unknown", 0 };

void
vx_tonemap_defaults(vx_tonemap_opts *o)
{
	memset(o, 0, sizeof *o);
	o->op = VX_TM_CLAMP;
	o->transfer = VX_TF_SRGB;
	o->gamma = 2.2;
}

double
vx_srgb_oetf(double x)
{
	if (!(x > 0))
		return 0;
	if (x >= 1)
		return 1;
	if (x <= 0.0031308)
		return 12.92 * x;
	return 1.055 * pow(x, 1 / 2.4) - 0.055;
}

double
vx_srgb_eotf(double v)
{
	if (!(v > 0))
		return 0;
	if (v >= 1)
		return 1;
	if (v <= 0.04045)
		return v / 12.92;
	return pow((v + 0.055) / 1.055, 2.4);
}

/*
 * The operators, on x >= 0 (+inf allowed):
 *
 * clamp:    min(x, 1).
 *
 * reinhard: E. Reinhard, M. Stark, P. Shirley, J. Ferwerda, "Photographic
 *           tone reproduction for digital images", SIGGRAPH 2002, eq. 3
 *           L_d = L / (1 + L), and with a white point L_white eq. 4
 *           L_d = L (1 + L / L_white^2) / (1 + L), which maps L_white to 1.
 *           The paper's key-value scaling (its eq. 2) is left to --exposure.
 *           Written for L >= 1 as (1 + L / Lw^2) / (1 + 1 / L) so that huge L
 *           does not overflow.
 *
 * aces:     K. Narkowicz, "ACES Filmic Tone Mapping Curve" (2016,
 *           knarkowicz.wordpress.com), a rational fit of the ACES reference
 *           rendering and output transforms:
 *           f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clamped to
 *           [0, 1].  Applied per channel, without the 0.6 pre-exposure some
 *           versions fold in.  For x >= 1 written as
 *           (2.51 + 0.03 / x) / (2.43 + 0.59 / x + 0.14 / x^2) (same value,
 *           no overflow; +inf gives 2.51 / 2.43, clamped to 1).
 */
double
vx_tonemap_curve(int op, double x, double white)
{
	if (!(x > 0))
		return 0;
	switch (op) {
	case VX_TM_REINHARD: {
		double w2 = white > 0 && isfinite(white) ? white * white : INFINITY;

		if (x < 1)
			return x * (1 + x / w2) / (1 + x);
		return (1 + x / w2) / (1 + 1 / x);
	}
	case VX_TM_ACES: {
		double y = x < 1 ? x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) +
		    0.14) : (2.51 + 0.03 / x) / (2.43 + 0.59 / x + 0.14 / (x * x));

		return y < 1 ? y : 1;
	}
	default:
		return x < 1 ? x : 1;
	}
}

static double
encode(const vx_tonemap_opts *o, double d)
{
	if (!(d > 0))
		return 0;
	if (d >= 1)
		return 1;
	switch (o->transfer) {
	case VX_TF_SRGB:
		return vx_srgb_oetf(d);
	case VX_TF_GAMMA:
		return pow(d, 1 / o->gamma);
	default:
		return d;
	}
}

int
vx_tonemap_nc_out(const vx_tonemap_opts *o, int nc)
{
	if (o->flatten && (nc == 2 || nc == 4))
		return nc - 1;
	return nc;
}

/* clean: a color or alpha value after exposure, with the repairs counted. */
static double
clean(double v, vx_tonemap_stats *st)
{
	if (isnan(v)) {
		st->nan++;
		return 0;
	}
	if (v < 0) {
		st->neg++;
		return 0;
	}
	if (isinf(v))
		st->posinf++;
	return v;
}

void
vx_tonemap_pixel(const vx_tonemap_opts *o, const float *in, int nc,
    float *out, vx_tonemap_stats *st)
{
	int ncol = nc <= 2 ? 1 : 3, has_alpha = nc == 2 || nc == 4, c;
	double scale = exp2(o->exposure), col[3], d[3], a = 1;
	vx_tonemap_stats dummy;

	if (st == NULL)
		st = &dummy;
	if (has_alpha) {
		a = clean(in[ncol], st);
		if (a > 1)
			a = 1;
	}
	for (c = 0; c < ncol; c++) {
		col[c] = clean(in[c] * scale, st);
		/* straight color from premultiplied; inf / a stays inf */
		if (has_alpha)
			col[c] = a > 0 ? col[c] / a : 0;
	}
	if (o->op == VX_TM_REINHARD) {
		double L = ncol == 1 ? col[0] :
		    LUM_R * col[0] + LUM_G * col[1] + LUM_B * col[2];

		if (isinf(L))
			/* the limit of c * L_d(L) / L as the infinite channels
			 * grow: finite channels go to 0, infinite ones to
			 * 1 / weight, which clamps to 1 */
			for (c = 0; c < ncol; c++)
				d[c] = isinf(col[c]) ? 1 : 0;
		else if (L > 0) {
			double s = vx_tonemap_curve(VX_TM_REINHARD, L, o->white) / L;

			for (c = 0; c < ncol; c++)
				d[c] = col[c] * s;
		} else
			for (c = 0; c < ncol; c++)
				d[c] = 0;
	} else
		for (c = 0; c < ncol; c++)
			d[c] = vx_tonemap_curve(o->op, col[c], o->white);
	for (c = 0; c < ncol; c++) {
		if (d[c] > 1)
			d[c] = 1;
		if (has_alpha && o->flatten) {
			double bg = ncol == 1 ? LUM_R * o->background[0] + LUM_G *
			    o->background[1] + LUM_B * o->background[2] :
			    o->background[c];

			d[c] = d[c] * a + bg * (1 - a);
		}
		out[c] = (float)encode(o, d[c]);
	}
	if (has_alpha && !o->flatten)
		out[ncol] = (float)a;
}

/* hash32: a 32-bit integer mix (Wellons' "lowbias32", an avalanche-tested
 * xorshift-multiply) used to draw the dither threshold per value. */
static uint32_t
hash32(uint32_t x)
{
	x ^= x >> 16;
	x *= 0x7feb352dU;
	x ^= x >> 15;
	x *= 0x846ca68bU;
	x ^= x >> 16;
	return x;
}

int
vx_tonemap_image(vx_image *dst, const vx_image *src,
    const vx_tonemap_opts *o, vx_tonemap_stats *st, vx_err *e)
{
	size_t nan = 0, neg = 0, posinf = 0;
	int nco, rc, y;

	vx_image_init(dst);
	if (o->op <= VX_TM_UNKNOWN || o->op >= VX_TM_LAST ||
	    o->transfer <= VX_TF_UNKNOWN || o->transfer >= VX_TF_LAST ||
	    (o->transfer == VX_TF_GAMMA && !(o->gamma > 0 &&
	    isfinite(o->gamma))) || !isfinite(o->exposure) ||
	    (o->dither_bits != 0 && o->dither_bits != 8 &&
	    o->dither_bits != 16))
		return vx_err_set(e, VX_EUSAGE, "tonemap: bad options");
	nco = vx_tonemap_nc_out(o, src->nc);
	if ((rc = vx_image_alloc(dst, src->w, src->h, nco, e)) != 0)
		return rc;
	memcpy(dst->name, src->name, sizeof dst->name);
#pragma omp parallel for schedule(dynamic, 8) reduction(+:nan, neg, posinf)
	for (y = 0; y < src->h; y++) {
		vx_tonemap_stats s = { 0, 0, 0 };
		double step = o->dither_bits ? 1.0 / ((1u << o->dither_bits) -
		    1) : 0;

		for (int x = 0; x < src->w; x++) {
			float *out = vx_image_pixel(dst, x, y);

			vx_tonemap_pixel(o, vx_image_pixel(src, x, y), src->nc,
			    out, &s);
			if (step == 0)
				continue;
			for (int c = 0; c < nco; c++) {
				uint32_t h = hash32(o->seed ^ hash32((uint32_t)x ^
				    hash32((uint32_t)y ^ hash32((uint32_t)c))));
				double u = (h >> 8) * (1.0 / 16777216.0);

				out[c] = (float)(out[c] + (u - 0.5) * step);
			}
		}
		nan += s.nan;
		neg += s.neg;
		posinf += s.posinf;
	}
	if (st != NULL) {
		st->nan = nan;
		st->neg = neg;
		st->posinf = posinf;
	}
	return 0;
}
