/* vx_compare.h: error metrics between an image and a reference, and
 * false-color difference images, for the accuracy studies.
 *
 * Metrics run over every value (pixel and channel) of two images of equal
 * size and channel count.  A pair where either value is NaN is skipped and
 * counted; a pair of equal values (equal infinities included) has error 0;
 * a pair where one value is infinite and the other differs is skipped and
 * counted.  Nothing non-finite reaches the sums.  Sums are in double, in
 * raster order, so results do not depend on threads. */
#ifndef VX_COMPARE_H
#define VX_COMPARE_H

#include <stddef.h>

#include "vx_enum.h"
#include "vx_err.h"
#include "vx_image.h"

/* The epsilon of the relative MSE: (a - b)^2 / (b^2 + VX_RELMSE_EPS). */
#define VX_RELMSE_EPS 1e-2

typedef struct vx_compare {
	size_t n;              /* value pairs that entered the metrics */
	double mse;            /* mean of (a - b)^2 */
	double rmse;           /* sqrt(mse) */
	double relmse;         /* mean of (a - b)^2 / (b^2 + VX_RELMSE_EPS) */
	double peak;           /* the peak PSNR was computed with */
	double psnr;           /* 10 log10(peak^2 / mse) in dB; +inf if mse 0 */
	double max_abs;        /* largest |a - b| */
	int max_x, max_y, max_c; /* where it first occurs (raster order) */
	size_t nan_a, nan_b;   /* NaN values in a, in b (pairs skipped) */
	size_t inf_mismatch;   /* pairs skipped for an unequal infinity */
} vx_compare;

/* vx_image_compare: metrics of a against the reference b.  peak > 0 is the
 * PSNR peak (1 for display values in [0,1]).  Errors: VX_EDATA when sizes or
 * channel counts differ or no pair is left to compare, VX_EUSAGE for a bad
 * peak. */
int vx_image_compare(vx_compare *r, const vx_image *a, const vx_image *b,
    double peak, vx_err *e);

enum {
	VX_DIFF_UNKNOWN = 0,
	VX_DIFF_ABS,      /* mean |a - b| over channels, viridis, 0 .. scale */
	VX_DIFF_SIGNED,   /* mean (a - b) over channels, blue-white-red,
	                     -scale .. scale (blue: a below b) */
	VX_DIFF_LAST
};

/* The maps' names (vx_enum.h): "abs", "signed". */
extern const vx_enum vx_diff_map_enum;

/* vx_image_diff: a false-color RGB picture of a - b into dst (initialized
 * by this call), already display-encoded (sRGB) for vx_image_png_write.
 * *scale > 0 sets the value mapped to the top of the colormap; otherwise
 * the largest per-pixel magnitude is used (1 if all are 0) and *scale gets
 * it.  Pixels with a skipped pair (see above) are magenta (1, 0, 1).
 * Errors as vx_image_compare. */
int vx_image_diff(vx_image *dst, const vx_image *a, const vx_image *b,
    int map, double *scale, vx_err *e);

#endif
