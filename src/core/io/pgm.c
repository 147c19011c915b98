/* pgm.c: the binary portable graymap (Netpbm PGM, "P5"), read from memory
 * (vx_imageio.h). */
#include "pnm_priv.h"
#include "vx_imageio.h"

#include <stdint.h>
#include <string.h>

static int
is_space(unsigned char c)
{
	return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' ||
	    c == '\f';
}

/* skip: whitespace and comments ('#' to the end of the line); at least
 * one whitespace byte or comment. */
static int
skip(const unsigned char *p, size_t n, size_t *pos)
{
	size_t s = *pos;

	while (*pos < n) {
		if (is_space(p[*pos]))
			(*pos)++;
		else if (p[*pos] == '#') {
			while (*pos < n && p[*pos] != '\n' && p[*pos] != '\r')
				(*pos)++;
		} else
			break;
	}
	return *pos > s ? 0 : -1;
}

int
vx_pgm_read_mem(vx_image *img, const void *buf, size_t n, int *maxval,
    vx_err *e)
{
	const unsigned char *p = buf;
	size_t pos = 2, need, np;
	long w, h, mv;
	int bpp, rc;

	vx_image_init(img);
	if (n < 2 || p[0] != 'P' || p[1] != '5')
		return vx_err_set(e, VX_EDATA, "pgm: not a binary PGM file (no "
		    "P5 magic)");
	if (skip(p, n, &pos) || vx_pnm_decimal(p, n, &pos, &w) ||
	    skip(p, n, &pos) || vx_pnm_decimal(p, n, &pos, &h))
		return vx_err_set(e, VX_EDATA, "pgm: bad or missing size in "
		    "header");
	if (skip(p, n, &pos) || vx_pnm_decimal(p, n, &pos, &mv))
		return vx_err_set(e, VX_EDATA, "pgm: bad or missing maxval in "
		    "header");
	if (pos >= n || !is_space(p[pos]))
		return vx_err_set(e, VX_EDATA, "pgm: header not ended by one "
		    "whitespace byte");
	pos++;
	if (mv < 1 || mv > 65535)
		return vx_err_set(e, VX_EDATA, "pgm: maxval %ld: must be in "
		    "1..65535", mv);
	if (w < 1 || h < 1 || w > VX_IMAGE_MAX_DIM || h > VX_IMAGE_MAX_DIM)
		return vx_err_set(e, VX_EDATA, "pgm: size %ld x %ld: each side "
		    "must be in 1..%d", w, h, VX_IMAGE_MAX_DIM);
	bpp = mv > 255 ? 2 : 1;
	/* bounded: w, h <= 2^16, so need <= 2^33 */
	np = (size_t)w * (size_t)h;
	need = np * (size_t)bpp;
	if (need != n - pos)
		return vx_err_set(e, VX_EDATA, "pgm: %ld x %ld of %d-byte samples "
		    "needs %zu data bytes, the file has %zu", w, h, bpp, need,
		    n - pos);
	if ((rc = vx_image_alloc_uninit(img, (int)w, (int)h, 1, e)) != 0)
		return vx_err_push(e, "pgm");
	for (size_t i = 0; i < np; i++) {
		const unsigned char *b = p + pos + i * (size_t)bpp;
		long v = bpp == 2 ? (long)b[0] << 8 | b[1] : b[0];

		if (v > mv) {
			vx_image_free(img);
			return vx_err_set(e, VX_EDATA, "pgm: pixel (%zu, %zu): %ld "
			    "exceeds maxval %ld", i % (size_t)w, i / (size_t)w, v,
			    mv);
		}
		img->px[i] = (float)((double)v / (double)mv);
	}
	if (maxval != NULL)
		*maxval = (int)mv;
	return 0;
}
