/* vx_imageio.h: image files: PNG (libpng) and PFM, read from memory and
 * written to a FILE, and format sniffing.  The images themselves are
 * vx_image (vx_image.h). */
#ifndef VX_IMAGEIO_H
#define VX_IMAGEIO_H

#include <stdio.h>

#include "vx_err.h"
#include "vx_file.h"
#include "vx_image.h"
#include "vx_stream.h"

/* ---- whole files in memory ---- */

enum {
	VX_IMGFMT_UNKNOWN = 0,
	VX_IMGFMT_STREAM,      /* voxlux stream signature */
	VX_IMGFMT_PFM,         /* "PF" or "Pf" then whitespace */
	VX_IMGFMT_PNG,         /* PNG signature */
	VX_IMGFMT_LAST
};

/* vx_image_sniff: which format the first bytes announce. */
int vx_image_sniff(const void *buf, size_t n);

/* ---- PNG (libpng) ---- */

/* vx_image_png_write: write img as an 8- or 16-bit PNG (gray, gray+alpha,
 * RGB, RGBA for nc 1..4) with ntext tEXt chunks.  The values are display
 * values in [0,1], already encoded (see vx_tonemap.h): each is clamped to
 * [0,1] (NaN gives 0) and rounded to the nearest code, round(v * (2^bits-1)).
 * No color-space chunk is written (viewers then assume sRGB).  Does not close
 * f; flushes it and checks for write errors.  Errors: VX_EUSAGE for a bad bit
 * depth or text key, VX_EIO for write errors, VX_EDATA from libpng. */
int vx_image_png_write(const vx_image *img, FILE *f, int bits,
    const vx_text *text, size_t ntext, vx_err *e);

/* vx_image_png_write_gamma: as vx_image_png_write, and say how the values are
 * encoded: gamma 0 writes an sRGB chunk (with the gAMA and cHRM values the
 * PNG spec recommends alongside), gamma G > 0 a gAMA chunk of 1/G (1 for
 * linear values). */
int vx_image_png_write_gamma(const vx_image *img, FILE *f, int bits,
    double gamma, const vx_text *text, size_t ntext, vx_err *e);

/* vx_image_png_read_mem: decode a PNG of any color type and bit depth into
 * img (initialized by this call): palette images become RGB (RGBA with
 * tRNS), gray below 8 bits is expanded, tRNS becomes an alpha channel.
 * Values are the stored codes divided by 2^depth - 1, in [0,1]: they are not
 * decoded from sRGB or gamma (the PNG's encoding is left as it is).
 * *bits (if not NULL) gets the bit depth after expansion, 8 or 16.  The
 * allocation is bounded by the size limits and by n (deflate's largest ratio
 * is 1032:1).  Errors: VX_EDATA for bad or truncated data. */
int vx_image_png_read_mem(vx_image *img, const void *buf, size_t n,
    int *bits, vx_err *e);

/* ---- PFM (portable float map) ----
 * "PF" (RGB) or "Pf" (gray), whitespace, width, whitespace, height,
 * whitespace, scale, one whitespace byte, then w*h*nc f32 values.  A
 * negative scale means little-endian, positive big-endian; |scale| is not
 * applied.  Rows are stored bottom row first. */

/* vx_pfm_read_mem: decode a PFM into img (initialized by this call), rows
 * flipped to top first.  Dimensions are checked against the limits and the
 * bytes present before allocating; the data must fill the rest of the
 * buffer exactly.  Errors: VX_EDATA. */
int vx_pfm_read_mem(vx_image *img, const void *buf, size_t n, vx_err *e);

/* vx_pfm_write: write img (nc 1 or 3) as "Pf" / "PF", little-endian (scale
 * -1), bottom row first.  Other channel counts are VX_EUSAGE: flatten first.
 * Flushes f and checks for write errors (VX_EIO). */
int vx_pfm_write(const vx_image *img, FILE *f, vx_err *e);

#endif
