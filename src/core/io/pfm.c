/* pfm.c: the portable float map (PFM), read from memory and written to a
 * FILE.  "PF" is RGB, "Pf" gray; the scale's sign gives the byte order
 * (negative: little-endian); rows are stored bottom row first. */
#include "pnm_priv.h"
#include "vx_imageio.h"
#include "vx_scan.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static int
is_space(unsigned char c)
{
	return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

/* skip_space: at least one whitespace byte, then any more. */
static int
skip_space(const unsigned char *p, size_t n, size_t *pos)
{
	if (*pos >= n || !is_space(p[*pos]))
		return -1;
	while (*pos < n && is_space(p[*pos]))
		(*pos)++;
	return 0;
}

int
vx_pnm_decimal(const unsigned char *p, size_t n, size_t *pos, long *out)
{
	long v = 0;
	int k = 0;

	while (*pos < n && p[*pos] >= '0' && p[*pos] <= '9' && k < 10) {
		v = v * 10 + (p[*pos] - '0');
		(*pos)++;
		k++;
	}
	if (k == 0 || k > 9)
		return -1;
	*out = v;
	return 0;
}

/* read_scale: a real (vx_scan.h's grammar), not 0. */
static int
read_scale(const unsigned char *p, size_t n, size_t *pos, double *out)
{
	size_t s = *pos;

	while (*pos < n && !is_space(p[*pos]))
		(*pos)++;
	if (vx_num_f64((const char *)p + s, *pos - s, 0, out) != 0 || *out == 0)
		return -1;
	return 0;
}

int
vx_pfm_read_mem(vx_image *img, const void *buf, size_t n, vx_err *e)
{
	const unsigned char *p = buf, *src;
	size_t pos = 2, need, row, y, i;
	long w, h;
	double scale;
	int nc, rc, little;

	vx_image_init(img);
	if (n < 3 || p[0] != 'P' || (p[1] != 'F' && p[1] != 'f'))
		return vx_err_set(e, VX_EDATA, "pfm: not a PFM file (no PF or Pf "
		    "magic)");
	nc = p[1] == 'F' ? 3 : 1;
	if (skip_space(p, n, &pos) || vx_pnm_decimal(p, n, &pos, &w) ||
	    skip_space(p, n, &pos) || vx_pnm_decimal(p, n, &pos, &h))
		return vx_err_set(e, VX_EDATA, "pfm: bad or missing size in "
		    "header");
	if (skip_space(p, n, &pos) || read_scale(p, n, &pos, &scale))
		return vx_err_set(e, VX_EDATA, "pfm: bad or missing scale "
		    "(a nonzero finite number)");
	if (pos >= n || !is_space(p[pos]))
		return vx_err_set(e, VX_EDATA, "pfm: header not ended by "
		    "whitespace");
	pos++;
	if (w < 1 || h < 1 || w > VX_IMAGE_MAX_DIM || h > VX_IMAGE_MAX_DIM)
		return vx_err_set(e, VX_EDATA, "pfm: size %ld x %ld: each side "
		    "must be in 1..%d", w, h, VX_IMAGE_MAX_DIM);
	/* bounded: w, h <= 2^16, so need < 2^36 */
	need = (size_t)w * (size_t)h * (size_t)nc * 4;
	if (need != n - pos)
		return vx_err_set(e, VX_EDATA, "pfm: %ld x %ld %s needs %zu data "
		    "bytes, the file has %zu", w, h, nc == 3 ? "RGB" : "gray",
		    need, n - pos);
	if ((rc = vx_image_alloc(img, (int)w, (int)h, nc, e)) != 0)
		return vx_err_push(e, "pfm");
	little = scale < 0;
	row = (size_t)w * (size_t)nc;
	for (y = 0; y < (size_t)h; y++) {
		/* stored row y is image row h - 1 - y */
		float *dst = vx_image_pixel(img, 0, (int)((size_t)h - 1 - y));

		src = p + pos + y * row * 4;
		for (i = 0; i < row; i++) {
			const unsigned char *b = src + 4 * i;
			uint32_t u = little ?
			    (uint32_t)b[0] | (uint32_t)b[1] << 8 |
			    (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24 :
			    (uint32_t)b[3] | (uint32_t)b[2] << 8 |
			    (uint32_t)b[1] << 16 | (uint32_t)b[0] << 24;

			memcpy(&dst[i], &u, 4);
		}
	}
	return 0;
}

int
vx_pfm_write(const vx_image *img, FILE *f, vx_err *e)
{
	unsigned char *buf;
	size_t row, y, i;
	int rc = 0;

	if (img->px == NULL || (img->nc != 1 && img->nc != 3))
		return vx_err_set(e, VX_EUSAGE, "pfm: %d channels (PFM holds 1 "
		    "or 3)", img->nc);
	row = (size_t)img->w * (size_t)img->nc;
	if ((buf = vx_malloc(row * 4, e)) == NULL)
		return VX_ENOMEM;
	if (fprintf(f, "P%c\n%d %d\n-1.0\n", img->nc == 3 ? 'F' : 'f', img->w,
	    img->h) < 0)
		rc = VX_EIO;
	for (y = (size_t)img->h; rc == 0 && y-- > 0;) {
		const float *src = vx_image_pixel(img, 0, (int)y);

		for (i = 0; i < row; i++) {
			uint32_t u;

			memcpy(&u, &src[i], 4);
			buf[4 * i] = (unsigned char)u;
			buf[4 * i + 1] = (unsigned char)(u >> 8);
			buf[4 * i + 2] = (unsigned char)(u >> 16);
			buf[4 * i + 3] = (unsigned char)(u >> 24);
		}
		if (fwrite(buf, 1, row * 4, f) != row * 4)
			rc = VX_EIO;
	}
	free(buf);
	if (rc == 0 && (fflush(f) != 0 || ferror(f)))
		rc = VX_EIO;
	if (rc != 0)
		return vx_err_set(e, VX_EIO, "pfm: write: %s", strerror(errno));
	return 0;
}
