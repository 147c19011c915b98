/* vx_image.h: float images, their stream chunk (IMAG), and PNG / PFM files.
 *
 * An image is w x h pixels of nc float channels, row-major, top row first,
 * channels interleaved:  px[(y * w + x) * nc + c].
 *
 *   nc 1  gray            nc 3  RGB
 *   nc 2  gray + alpha    nc 4  RGBA
 *
 * Convention for images in a stream (formats/image.md): color values are
 * linear (scene-referred radiance, "colorspace: linear"), and when there is an
 * alpha channel (coverage) the color is premultiplied by it ("associated"
 * alpha): a pixel half covered by a surface of radiance 0.8 stores color 0.4,
 * alpha 0.5.  That is what a renderer's pixel filter sums naturally and what
 * averages correctly.  Auxiliary images travel in the same stream under other
 * names: "depth" (nc 1, +inf where nothing was hit), "normal" (nc 3).
 *
 * PNG and PFM files are read and written by vx_imageio.h (io); tone mapping
 * (linear to display values) lives in vx_tonemap.h. */
#ifndef VX_IMAGE_H
#define VX_IMAGE_H

#include <stddef.h>
#include <stdio.h>

#include "vx_err.h"
#include "vx_stream.h"

/* Size limits: each side at most VX_IMAGE_MAX_DIM pixels, at most
 * VX_IMAGE_MAX_PIXELS pixels in all (a 16384 x 16384 image; 4 GiB as RGBA
 * floats).  Checked before anything is allocated. */
#define VX_IMAGE_MAX_DIM    65536
#define VX_IMAGE_MAX_PIXELS ((size_t)1 << 28)

typedef struct vx_image {
	int w, h, nc;          /* width, height, channels (1..4) */
	float *px;             /* w * h * nc values, owned; NULL when empty */
	char name[64];         /* "image" unless told otherwise */
} vx_image;

/* A key/value pair for PNG text chunks (tEXt). */
typedef struct vx_text {
	const char *key;       /* 1..79 printable Latin-1 characters */
	const char *value;
} vx_text;

/* vx_image_init: an empty image (no pixels, name "image"). */
void vx_image_init(vx_image *img);

/* vx_image_alloc: (re)initialize img as w x h x nc zeroed pixels, name
 * "image".  Errors: VX_EDATA for sizes out of the limits above or nc outside
 * 1..4, VX_ENOMEM.  On error img is empty.  Free with vx_image_free. */
int vx_image_alloc(vx_image *img, int w, int h, int nc, vx_err *e);
/* vx_image_alloc_uninit: vx_image_alloc without zeroing the pixels, for a
 * writer that writes every one of them (a renderer's tiles: the clear
 * would be serial work before the threads start). */
int vx_image_alloc_uninit(vx_image *img, int w, int h, int nc, vx_err *e);

/* vx_image_free: release the pixels; img becomes empty.  Accepts an empty or
 * NULL image. */
void vx_image_free(vx_image *img);

/* vx_image_copy: dst (initialized by this call) gets a deep copy of src. */
int vx_image_copy(vx_image *dst, const vx_image *src, vx_err *e);

/* vx_image_nvalue: w * h * nc (fits size_t by the limits). */
size_t vx_image_nvalue(const vx_image *img);

/* vx_image_pixel: pointer to pixel (x, y)'s nc values (no bounds check). */
static inline float *
vx_image_pixel(const vx_image *img, int x, int y)
{
	return img->px + ((size_t)y * (size_t)img->w + (size_t)x) *
	    (size_t)img->nc;
}

/* vx_image_get / vx_image_set: one value (no bounds check). */
static inline float
vx_image_get(const vx_image *img, int x, int y, int c)
{
	return vx_image_pixel(img, x, y)[c];
}

static inline void
vx_image_set(vx_image *img, int x, int y, int c, float v)
{
	vx_image_pixel(img, x, y)[c] = v;
}

/* vx_image_has_alpha: 1 for nc 2 and 4.  vx_image_ncolor: 1 or 3. */
static inline int
vx_image_has_alpha(const vx_image *img)
{
	return img->nc == 2 || img->nc == 4;
}

static inline int
vx_image_ncolor(const vx_image *img)
{
	return img->nc <= 2 ? 1 : 3;
}

/* vx_quantize: the nearest code in 0..maxv for a display value v in [0,1]:
 * values below 0 and NaN give 0, values above 1 give maxv, ties round up
 * (floor(v * maxv + 0.5)).  The one rounding rule of PNG output. */
static inline unsigned
vx_quantize(double v, unsigned maxv)
{
	if (!(v > 0))
		return 0;
	if (v >= 1)
		return maxv;
	return (unsigned)(v * maxv + 0.5);
}

/* vx_image_quantize: replace every value by vx_quantize(v, 2^bits - 1) /
 * (2^bits - 1), bits 1..16: what a PNG of that depth would hold. */
void vx_image_quantize(vx_image *img, int bits);

/* vx_image_flatten: dst (initialized by this call) gets src's color times
 * `scale`, composited over the linear background bg: premultiplied color +
 * (1 - alpha) * bg, without the alpha channel (gray images use bg's Rec. 709
 * luminance).  nc 1 or 3 images are only scaled.  Values are not repaired:
 * NaN, inf and negative values pass through. */
int vx_image_flatten(vx_image *dst, const vx_image *src, double scale,
    const double bg[3], vx_err *e);

/* ---- stream form: the IMAG chunk (formats/image.md) ----
 * Header keys: name, width, height, channels, colorspace (linear), alpha
 * (premultiplied; only with nc 2 or 4), encoding.  Body: w*h*nc f32 LE,
 * top row first.  zlevel 0 writes the body raw, 1..9 zlib-compressed. */
int vx_image_to_chunk(const vx_image *img, int zlevel, vx_chunk *c,
    vx_err *e);
/* vx_image_from_chunk: decode c into img (initialized by this call).  The
 * allocation is bounded by the limits above and by the body actually present
 * (raw: exact size; zlib: at most 1032 times the compressed size, deflate's
 * largest ratio).  Unknown colorspace or alpha values are errors. */
int vx_image_from_chunk(vx_image *img, const vx_chunk *c, vx_err *e);
/* vx_image_from_stream: the first IMAG chunk whose name is `name` (any name
 * when NULL); *index (if not NULL) gets its chunk index.  Only the chosen
 * chunk's body is decoded.  VX_EDATA when there is none. */
int vx_image_from_stream(vx_image *img, const vx_stream *s, const char *name,
    long *index, vx_err *e);

#endif
