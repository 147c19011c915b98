/* compare.c: image error metrics and false-color difference images. */
#include "vx_compare.h"

#include <math.h>
#include <string.h>

static const vx_enum_name diff_map_names[] = {
	{ "abs", VX_DIFF_ABS }, { "signed", VX_DIFF_SIGNED },
	{ NULL, VX_DIFF_UNKNOWN }
};
const vx_enum vx_diff_map_enum = { "map", diff_map_names, "unknown", 0 };

static int
check_same(const vx_image *a, const vx_image *b, vx_err *e)
{
	if (a->w != b->w || a->h != b->h || a->nc != b->nc)
		return vx_err_set(e, VX_EDATA, "compare: image is %dx%d with %d "
		    "channels, reference %dx%d with %d", a->w, a->h, a->nc, b->w,
		    b->h, b->nc);
	return 0;
}

/* pair: classify one value pair; returns 1 when it enters the metrics
 * (with *d = a - b), 0 when skipped (and counted in r). */
static int
pair(double a, double b, double *d, vx_compare *r)
{
	int na = isnan(a), nb = isnan(b);

	if (na || nb) {
		r->nan_a += (size_t)na;
		r->nan_b += (size_t)nb;
		return 0;
	}
	if (a == b) {
		*d = 0;
		return 1;
	}
	if (isinf(a) || isinf(b)) {
		r->inf_mismatch++;
		return 0;
	}
	*d = a - b;
	return 1;
}

int
vx_image_compare(vx_compare *r, const vx_image *a, const vx_image *b,
    double peak, vx_err *e)
{
	double se = 0, rel = 0;
	size_t i, n;
	int rc;

	memset(r, 0, sizeof *r);
	if (!(peak > 0) || !isfinite(peak))
		return vx_err_set(e, VX_EUSAGE, "compare: peak must be positive");
	if ((rc = check_same(a, b, e)) != 0)
		return rc;
	n = vx_image_nvalue(a);
	r->peak = peak;
	for (i = 0; i < n; i++) {
		double d, bv = b->px[i];

		if (!pair(a->px[i], bv, &d, r))
			continue;
		r->n++;
		se += d * d;
		if (d != 0)
			rel += d * d / (bv * bv + VX_RELMSE_EPS);
		if (fabs(d) > r->max_abs) {
			size_t p = i / (size_t)a->nc;

			r->max_abs = fabs(d);
			r->max_c = (int)(i % (size_t)a->nc);
			r->max_x = (int)(p % (size_t)a->w);
			r->max_y = (int)(p / (size_t)a->w);
		}
	}
	if (r->n == 0)
		return vx_err_set(e, VX_EDATA, "compare: no pair of values left "
		    "to compare (%zu NaN in the image, %zu in the reference, %zu "
		    "unequal infinities)", r->nan_a, r->nan_b, r->inf_mismatch);
	r->mse = se / (double)r->n;
	r->rmse = sqrt(r->mse);
	r->relmse = rel / (double)r->n;
	r->psnr = r->mse > 0 ? 10 * log10(peak * peak / r->mse) : INFINITY;
	return 0;
}

/* viridis (matplotlib, van der Walt and Smith 2015, CC0) sampled at 9
 * evenly spaced points: #440154 #472d7b #3b528b #2c728e #21918c #28ae80
 * #5ec962 #addc30 #fde725; interpolated linearly between them in sRGB. */
static const unsigned char viridis9[9][3] = {
	{ 0x44, 0x01, 0x54 }, { 0x47, 0x2d, 0x7b }, { 0x3b, 0x52, 0x8b },
	{ 0x2c, 0x72, 0x8e }, { 0x21, 0x91, 0x8c }, { 0x28, 0xae, 0x80 },
	{ 0x5e, 0xc9, 0x62 }, { 0xad, 0xdc, 0x30 }, { 0xfd, 0xe7, 0x25 },
};

/* The ends of Moreland's cool-warm map (2009), with white in the middle. */
static const unsigned char cool[3] = { 0x3b, 0x4c, 0xc0 };
static const unsigned char warm[3] = { 0xb4, 0x04, 0x26 };

static void
colormap(int map, double t, float *rgb)
{
	int c;

	if (map == VX_DIFF_ABS) {
		double u = (t < 0 ? 0 : t > 1 ? 1 : t) * 8;
		int k = u >= 8 ? 7 : (int)u;
		double f = u - k;

		for (c = 0; c < 3; c++)
			rgb[c] = (float)((viridis9[k][c] * (1 - f) +
			    viridis9[k + 1][c] * f) / 255.0);
	} else {
		double f = t < -1 ? 1 : t > 1 ? 1 : fabs(t);
		const unsigned char *end = t < 0 ? cool : warm;

		for (c = 0; c < 3; c++)
			rgb[c] = (float)((255.0 * (1 - f) + end[c] * f) / 255.0);
	}
}

int
vx_image_diff(vx_image *dst, const vx_image *a, const vx_image *b, int map,
    double *scale, vx_err *e)
{
	size_t p, np = (size_t)a->w * (size_t)a->h;
	double top = 0;
	vx_compare dummy;   /* counts nobody reads */
	int rc, c;

	memset(&dummy, 0, sizeof dummy);
	vx_image_init(dst);
	if (map <= VX_DIFF_UNKNOWN || map >= VX_DIFF_LAST ||
	    !(*scale >= 0) || isinf(*scale))
		return vx_err_set(e, VX_EUSAGE, "diff: bad map or scale");
	if ((rc = check_same(a, b, e)) != 0)
		return rc;
	/* first pass: per-pixel means into dst channel 0, NaN when skipped */
	if ((rc = vx_image_alloc(dst, a->w, a->h, 3, e)) != 0)
		return rc;
	for (p = 0; p < np; p++) {
		double sum = 0, d;
		int bad = 0;

		for (c = 0; c < a->nc; c++) {
			size_t i = p * (size_t)a->nc + (size_t)c;

			if (pair(a->px[i], b->px[i], &d, &dummy))
				sum += map == VX_DIFF_ABS ? fabs(d) : d;
			else
				bad = 1;
		}
		sum /= a->nc;
		dst->px[3 * p] = bad ? NAN : (float)sum;
		if (!bad && fabs(sum) > top)
			top = fabs(sum);
	}
	if (*scale > 0)
		top = *scale;
	else if (top == 0)
		top = 1;
	*scale = top;
	for (p = 0; p < np; p++) {
		float *rgb = dst->px + 3 * p;

		if (isnan(rgb[0])) {
			rgb[0] = 1;
			rgb[1] = 0;
			rgb[2] = 1;
		} else
			colormap(map, rgb[0] / top, rgb);
	}
	return 0;
}
