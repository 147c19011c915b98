/* vx_tonemap.h: from linear radiance to display values in [0,1].
 *
 * The pipeline, per pixel (every step in double precision):
 *
 *   1. exposure: color *= 2^exposure (alpha untouched)
 *   2. clean up: NaN -> 0 (counted), negative and -inf -> 0; alpha clamped
 *      to [0,1]; premultiplied color divided by alpha where alpha > 0
 *      (color 0 where alpha is 0)
 *   3. operator (clamp, reinhard, aces), giving linear display values in
 *      [0,1]; +inf maps to 1
 *   4. optional flattening over a background: d = d * alpha + bg * (1 -
 *      alpha), in linear display values; the alpha channel is dropped
 *   5. transfer function: sRGB OETF (exact piecewise), 1/gamma power, or none
 *   6. optional dither offset of up to half a code step (see dither_bits)
 *
 * Without flattening the alpha channel stays, straight (unassociated), as
 * PNG wants it.  Quantizing to codes is vx_quantize (round to nearest), done
 * by the PNG writer. */
#ifndef VX_TONEMAP_H
#define VX_TONEMAP_H

#include <stddef.h>
#include <stdint.h>

#include "vx_enum.h"
#include "vx_err.h"
#include "vx_image.h"

enum {
	VX_TM_UNKNOWN = 0,
	VX_TM_CLAMP,      /* min(x, 1) per channel */
	VX_TM_REINHARD,   /* Reinhard et al. 2002 eq. 3/4 on luminance */
	VX_TM_ACES,       /* Narkowicz 2015 fit of the ACES RRT+ODT, per channel */
	VX_TM_LAST
};

enum {
	VX_TF_UNKNOWN = 0,
	VX_TF_SRGB,       /* IEC 61966-2-1 piecewise OETF */
	VX_TF_GAMMA,      /* x^(1/gamma) */
	VX_TF_LINEAR,     /* no encoding */
	VX_TF_LAST
};

typedef struct vx_tonemap_opts {
	double exposure;       /* stops; color is scaled by 2^exposure */
	int op;                /* VX_TM_* */
	double white;          /* reinhard: the smallest luminance (after
	                          exposure) mapped to 1; <= 0 or inf: none */
	int transfer;          /* VX_TF_* */
	double gamma;          /* for VX_TF_GAMMA, > 0 */
	int flatten;           /* composite over background, drop alpha */
	double background[3];  /* linear display values in [0,1] */
	int dither_bits;       /* 0: none; 8 or 16: add (u - 0.5) / (2^bits-1)
	                          to each value, u in [0,1) hashed from (seed,
	                          x, y, channel): quantizing then rounds up
	                          with probability equal to the fraction */
	uint32_t seed;
} vx_tonemap_opts;

/* Counts of the values step 2 had to repair (over all channels). */
typedef struct vx_tonemap_stats {
	size_t nan;            /* NaN, mapped to 0 */
	size_t neg;            /* negative or -inf, mapped to 0 */
	size_t posinf;         /* +inf, mapped to 1 by the operator */
} vx_tonemap_stats;

/* vx_tonemap_defaults: exposure 0, clamp, no white point, sRGB, gamma 2.2
 * (unused), no flattening, black background, no dither. */
void vx_tonemap_defaults(vx_tonemap_opts *o);

/* The operators' names (vx_enum.h): "clamp", "reinhard", "aces";
 * VX_TM_UNKNOWN and "unknown" for the others. */
extern const vx_enum vx_tonemap_op_enum;

/* vx_tonemap_curve: the operator on one clean value x >= 0 (or +inf) used
 * as luminance (reinhard) or per channel (clamp, aces).  For reinhard this
 * is L_d before the final clamp (it exceeds 1 above the white point). */
double vx_tonemap_curve(int op, double x, double white);

/* vx_srgb_oetf / vx_srgb_eotf: the exact sRGB transfer functions on [0,1]
 * (12.92 x below 0.0031308, 1.055 x^(1/2.4) - 0.055 above; and inverse). */
double vx_srgb_oetf(double x);
double vx_srgb_eotf(double v);

/* vx_tonemap_pixel: steps 1-5 for one pixel of nc channels (1..4, as in
 * vx_image).  out gets nc values, or vx_tonemap_nc_out(o, nc) when
 * flattening.  st (may be NULL) accumulates the repair counts. */
void vx_tonemap_pixel(const vx_tonemap_opts *o, const float *in, int nc,
    float *out, vx_tonemap_stats *st);

/* vx_tonemap_nc_out: channels of the output for nc input channels. */
int vx_tonemap_nc_out(const vx_tonemap_opts *o, int nc);

/* vx_tonemap_image: the whole pipeline over src into dst (initialized by
 * this call, same size, vx_tonemap_nc_out channels, src's name).  Output
 * values are display values in [0,1] (slightly outside with dither, which
 * quantizing clamps).  Deterministic whatever the thread count.  st (may be
 * NULL) gets the repair counts.  Errors: VX_EUSAGE for bad options,
 * VX_ENOMEM. */
int vx_tonemap_image(vx_image *dst, const vx_image *src,
    const vx_tonemap_opts *o, vx_tonemap_stats *st, vx_err *e);

#endif
