/* vx_imageio.h: image files: PNG (libpng), PFM, Radiance RGBE (.hdr) and
 * OpenEXR (the OpenEXR library), read from memory and (but for OpenEXR)
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
	VX_IMGFMT_HDR,         /* Radiance RGBE: "#?" */
	VX_IMGFMT_EXR,         /* OpenEXR magic 76 2f 31 01 */
	VX_IMGFMT_PGM,         /* binary PGM: "P5" then whitespace or '#' */
	VX_IMGFMT_LAST
};

/* vx_image_sniff: which format the first bytes announce. */
int vx_image_sniff(const void *buf, size_t n);
/* vx_image_format_name: "PFM", "Radiance HDR", ... ("unknown"). */
const char *vx_image_format_name(int fmt);

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

/* ---- PGM (Netpbm's binary portable graymap) ----
 * "P5", whitespace, width, whitespace, height, whitespace, maxval (1 ..
 * 65535), one whitespace byte, then w*h samples, top row first, of one
 * byte (maxval < 256) or two, most significant first; '#' starts a
 * comment to the end of the line anywhere before the maxval's end. */

/* vx_pgm_read_mem: decode a binary PGM into img (initialized by this
 * call), nc 1, each value its sample over maxval, in [0,1]; *maxval (if
 * not NULL) gets the maxval.  Dimensions are checked against the limits
 * and the data must fill the rest of the buffer exactly (one image)
 * before anything is allocated.  A sample over maxval, and the plain
 * (ASCII, "P2") form, are VX_EDATA. */
int vx_pgm_read_mem(vx_image *img, const void *buf, size_t n, int *maxval,
    vx_err *e);

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

/* ---- Radiance RGBE (.hdr) ----
 * A text header ("#?" first line, then VAR=value lines up to an empty line),
 * a resolution line, then scanlines of 4-byte pixels (r, g, b mantissas and
 * a shared exponent byte).  A pixel decodes to m * 2^(exponent - 136) per
 * channel, and to 0 when the exponent byte is 0; as pbrt-v4, Mitsuba,
 * OpenImageIO and stb_image do (Radiance's own readers add half a mantissa
 * step, m + 0.5).  The result is divided by the product of the EXPOSURE
 * lines and, per channel, of the COLORCORR lines (the header's statement of
 * how the values were scaled), so it is the radiance as written.  FORMAT must
 * be 32-bit_rle_rgbe (or absent); 32-bit_rle_xyze and others are refused.
 * PRIMARIES and the other variables are ignored: the values are taken as
 * linear RGB.  Each scanline is in the new run-length encoding (2, 2, width
 * as 2 bytes, then four planes of runs), or flat, or in the old run-length
 * encoding ((1, 1, 1, n) repeats the pixel before n << shift times, the shift
 * growing by 8 for each run code in a row); a reader tells them apart per
 * scanline by its first 4 bytes, as Radiance does.  The resolution line may
 * give any of the 8 orientations ("-Y H +X W" is rows from the top, pixels
 * from the left; "+Y" starts at the bottom, "-X" at the right, an X axis
 * first makes the scanlines columns); the image comes back top row first. */

typedef struct vx_hdr_info {
	double exposure;       /* product of the EXPOSURE values (1 without) */
	double colorcorr[3];   /* products of the COLORCORR values */
	char orient[8];        /* the resolution line's axes: "-Y+X" */
	int nrle;              /* scanlines in the new run-length encoding */
	int nflat;             /* scanlines flat or in the old encoding */
	size_t trailing;       /* bytes after the last scanline (ignored) */
} vx_hdr_info;

/* vx_hdr_read_mem: decode a Radiance RGBE file into img (initialized by this
 * call), nc 3.  The dimensions are checked against the image limits, and the
 * scanlines are decoded once without output before the image is allocated,
 * so no allocation rests on a header's word alone.  Bytes after the last
 * scanline are ignored (info->trailing counts them).  info may be NULL.
 * Errors: VX_EDATA, naming the scanline and what is wrong. */
int vx_hdr_read_mem(vx_image *img, const void *buf, size_t n,
    vx_hdr_info *info, vx_err *e);

/* vx_hdr_write: write img (nc 1 or 3; gray is written as r = g = b) as a
 * Radiance file: "#?RADIANCE", FORMAT=32-bit_rle_rgbe, "-Y H +X W", and each
 * scanline in the new run-length encoding when rle is 1 and 8 <= W <= 32767,
 * else flat.  Each pixel is rounded to the nearest RGBE value (shared
 * exponent from the largest channel); negative values are written as 0,
 * values beyond the largest RGBE value (255 * 2^119) as that value.
 * VX_EDATA for NaN or infinite values, VX_EUSAGE for other channel counts,
 * VX_EIO for write errors (f is flushed, not closed). */
int vx_hdr_write(const vx_image *img, FILE *f, int rle, vx_err *e);

/* ---- OpenEXR (through the OpenEXR library) ----
 * vx_exr_read_mem: decode an OpenEXR file's first part into img
 * (initialized by this call), nc 3, as 32-bit floats whatever the channels'
 * type (half, float, uint).  Channels R, G and B are read; an image with Y
 * alone (luminance) gives r = g = b = Y; other channels are ignored, and an
 * image with neither, or with subsampled (RY, BY) channels, is refused.  The
 * image is the display window; pixels of the data window outside it are
 * dropped, display pixels outside the data window are 0.  Both windows are
 * checked against the image limits before the library reads any pixel.
 * Every compression the library knows is read (DWAA and DWAB included).
 * Errors: VX_EDATA with the library's message, VX_ENOMEM. */
int vx_exr_read_mem(vx_image *img, const void *buf, size_t n, vx_err *e);

/* ---- any linear (HDR) image file ---- */

/* vx_image_read_linear_mem: decode a PFM, Radiance or OpenEXR file (told by
 * its first bytes) into img (initialized by this call); *fmt (if not NULL)
 * gets the VX_IMGFMT_ it was.  Other formats are VX_EDATA. */
int vx_image_read_linear_mem(vx_image *img, const void *buf, size_t n,
    int *fmt, vx_err *e);

/* vx_image_read_linear_file: the same for the file at path, read whole (at
 * most VX_IMAGE_FILE_MAX bytes: uncompressed RGBA floats of the largest
 * image, and room for headers).  VX_ENOINPUT when it cannot be opened,
 * VX_EIO on read errors; the message starts with path. */
#define VX_IMAGE_FILE_MAX (VX_IMAGE_MAX_PIXELS * 16 + ((size_t)1 << 20))
int vx_image_read_linear_file(vx_image *img, const char *path, int *fmt,
    vx_err *e);

#endif
