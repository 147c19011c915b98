/* image.c: float images, the IMAG chunk, reading whole files into memory. */
#include "vx_image.h"

#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* deflate's largest expansion: one 258-byte match per 2 bits, ~1032:1. */
#define ZLIB_MAX_RATIO 1032

void
vx_image_init(vx_image *img)
{
	memset(img, 0, sizeof *img);
	snprintf(img->name, sizeof img->name, "image");
}

void
vx_image_free(vx_image *img)
{
	if (img == NULL)
		return;
	free(img->px);
	vx_image_init(img);
}

size_t
vx_image_nvalue(const vx_image *img)
{
	return (size_t)img->w * (size_t)img->h * (size_t)img->nc;
}

/* check_size: the limits of vx_image.h, with the values named. */
static int
check_size(long long w, long long h, long long nc, vx_err *e)
{
	if (nc < 1 || nc > 4)
		return vx_err_set(e, VX_EDATA, "image: %lld channels (1..4)", nc);
	if (w < 1 || h < 1 || w > VX_IMAGE_MAX_DIM || h > VX_IMAGE_MAX_DIM)
		return vx_err_set(e, VX_EDATA, "image: size %lld x %lld: each "
		    "side must be in 1..%d", w, h, VX_IMAGE_MAX_DIM);
	/* both sides <= 2^16, so the product fits in 64 bits */
	if ((unsigned long long)w * (unsigned long long)h > VX_IMAGE_MAX_PIXELS)
		return vx_err_set(e, VX_EDATA, "image: %lld x %lld pixels exceed "
		    "the limit of %zu pixels", w, h, VX_IMAGE_MAX_PIXELS);
	return 0;
}

/* alloc: vx_image_alloc's work, the pixels zeroed or not */
static int
alloc(vx_image *img, int w, int h, int nc, int zero, vx_err *e)
{
	size_t n, bytes;
	int rc;

	vx_image_init(img);
	if ((rc = check_size(w, h, nc, e)) != 0)
		return rc;
	/* check_size bounds w h by VX_IMAGE_MAX_PIXELS: n fits; its bytes
	 * may not where size_t is 32 bits */
	n = (size_t)w * (size_t)h * (size_t)nc;
	if (vx_mul_size(&bytes, n, sizeof(float)) != 0)
		return vx_err_set(e, VX_ENOMEM, "image: %zu values: too many "
		    "bytes", n);
	img->px = zero ? vx_calloc(n, sizeof(float), e) : vx_malloc(bytes, e);
	if (img->px == NULL)
		return VX_ENOMEM;
	img->w = w;
	img->h = h;
	img->nc = nc;
	return 0;
}

int
vx_image_alloc(vx_image *img, int w, int h, int nc, vx_err *e)
{
	return alloc(img, w, h, nc, 1, e);
}

int
vx_image_alloc_uninit(vx_image *img, int w, int h, int nc, vx_err *e)
{
	return alloc(img, w, h, nc, 0, e);
}

int
vx_image_copy(vx_image *dst, const vx_image *src, vx_err *e)
{
	int rc;

	if ((rc = vx_image_alloc(dst, src->w, src->h, src->nc, e)) != 0)
		return rc;
	memcpy(dst->px, src->px, vx_image_nvalue(src) * sizeof(float));
	memcpy(dst->name, src->name, sizeof dst->name);
	return 0;
}

/* ---- the IMAG chunk ---- */

int
vx_image_to_chunk(const vx_image *img, int zlevel, vx_chunk *c, vx_err *e)
{
	size_t n = vx_image_nvalue(img), nbytes = n * sizeof(float);
	const void *body = img->px;
	void *tmp = NULL;
	vx_hdr h;
	int rc;

	if ((rc = check_size(img->w, img->h, img->nc, e)) != 0)
		return vx_err_push(e, "image '%s'", img->name);
	if (strchr(img->name, '\n') != NULL || img->name[0] == '\0')
		return vx_err_set(e, VX_EUSAGE, "image: name must be one "
		    "non-empty line");
	vx_hdr_init(&h);
	if ((rc = vx_hdr_set(&h, "name", e, "%s", img->name)) ||
	    (rc = vx_hdr_set(&h, "width", e, "%d", img->w)) ||
	    (rc = vx_hdr_set(&h, "height", e, "%d", img->h)) ||
	    (rc = vx_hdr_set(&h, "channels", e, "%d", img->nc)) ||
	    (rc = vx_hdr_set(&h, "colorspace", e, "linear")))
		goto out;
	if (vx_image_has_alpha(img) &&
	    (rc = vx_hdr_set(&h, "alpha", e, "premultiplied")))
		goto out;
	if (!vx_host_is_le()) {
		if ((tmp = vx_malloc(nbytes, e)) == NULL) {
			rc = VX_ENOMEM;
			goto out;
		}
		memcpy(tmp, img->px, nbytes);
		vx_swap_bytes(tmp, n, sizeof(float));
		body = tmp;
	}
	rc = vx_payload_make(c, VX_CHUNK_IMAGE, &h, body, nbytes, zlevel, e);
out:
	free(tmp);
	vx_hdr_free(&h);
	return rc;
}

/* parse_header: size, channels and name of an IMAG chunk, checking the keys
 * this reader must understand.  Leaves the pixels alone. */
static int
parse_header(const vx_hdr *h, int64_t dim[3], char name[64], vx_err *e)
{
	const char *v;
	int rc;

	if ((rc = vx_hdr_get_i64(h, "width", &dim[0], 1, e)) != 0 ||
	    (rc = vx_hdr_get_i64(h, "height", &dim[1], 1, e)) != 0 ||
	    (rc = vx_hdr_get_i64(h, "channels", &dim[2], 1, e)) != 0)
		return rc;
	if ((rc = check_size(dim[0], dim[1], dim[2], e)) != 0)
		return rc;
	if ((v = vx_hdr_get(h, "colorspace")) != NULL && strcmp(v, "linear"))
		return vx_err_set(e, VX_EDATA, "unknown colorspace '%.40s' "
		    "(this reader knows linear)", v);
	if ((v = vx_hdr_get(h, "alpha")) != NULL &&
	    strcmp(v, "premultiplied") != 0)
		return vx_err_set(e, VX_EDATA, "unknown alpha '%.40s' (this "
		    "reader knows premultiplied)", v);
	v = vx_hdr_get(h, "name");
	snprintf(name, 64, "%s", v != NULL && v[0] != '\0' ? v : "image");
	return 0;
}

int
vx_image_from_chunk(vx_image *img, const vx_chunk *c, vx_err *e)
{
	const unsigned char *body;
	size_t bodylen, nbytes, bound;
	const char *enc;
	int64_t dim[3];
	char name[64];
	vx_hdr h;
	int rc;

	vx_image_init(img);
	vx_hdr_init(&h);
	if ((rc = vx_payload_parse(c, &h, &body, &bodylen, e)) != 0 ||
	    (rc = parse_header(&h, dim, name, e)) != 0)
		goto out;
	nbytes = (size_t)dim[0] * (size_t)dim[1] * (size_t)dim[2] *
	    sizeof(float);
	enc = vx_hdr_get(&h, "encoding");
	/* bound the allocation by the bytes present before making it */
	if (enc == NULL || strcmp(enc, "raw") == 0)
		bound = bodylen;
	else if (vx_mul_size(&bound, bodylen, ZLIB_MAX_RATIO) != 0)
		bound = SIZE_MAX;
	if (nbytes > bound) {
		rc = vx_err_set(e, VX_EDATA, "body of %zu bytes cannot hold "
		    "%lld x %lld x %lld floats", bodylen, (long long)dim[0],
		    (long long)dim[1], (long long)dim[2]);
		goto out;
	}
	if ((rc = vx_image_alloc(img, (int)dim[0], (int)dim[1], (int)dim[2],
	    e)) != 0)
		goto out;
	memcpy(img->name, name, sizeof img->name);
	if ((rc = vx_body_decode(&h, body, bodylen, img->px, nbytes, e)) != 0)
		goto out;
	if (!vx_host_is_le())
		vx_swap_bytes(img->px, vx_image_nvalue(img), sizeof(float));
out:
	vx_hdr_free(&h);
	if (rc != 0) {
		vx_image_free(img);
		vx_err_push(e, "image");
	}
	return rc;
}

int
vx_image_from_stream(vx_image *img, const vx_stream *s, const char *name,
    long *index, vx_err *e)
{
	long i = -1;
	int rc;

	vx_image_init(img);
	while ((i = vx_stream_find(s, VX_CHUNK_IMAGE, (size_t)(i + 1))) >= 0) {
		const unsigned char *body;
		size_t bodylen;
		int64_t dim[3];
		char cname[64];
		vx_hdr h;

		vx_hdr_init(&h);
		rc = vx_payload_parse(&s->chunk[i], &h, &body, &bodylen, e);
		if (rc == 0)
			rc = parse_header(&h, dim, cname, e);
		vx_hdr_free(&h);
		if (rc != 0)
			return vx_err_push(e, "image chunk %ld", i);
		if (name != NULL && strcmp(cname, name) != 0)
			continue;
		if ((rc = vx_image_from_chunk(img, &s->chunk[i], e)) != 0)
			return rc;
		if (index != NULL)
			*index = i;
		return 0;
	}
	if (name != NULL)
		return vx_err_set(e, VX_EDATA, "no image named '%s' in the stream",
		    name);
	return vx_err_set(e, VX_EDATA, "no image in the stream");
}

void
vx_image_quantize(vx_image *img, int bits)
{
	unsigned maxv = (1u << bits) - 1;
	size_t i, n = vx_image_nvalue(img);

	for (i = 0; i < n; i++)
		img->px[i] = (float)((double)vx_quantize(img->px[i], maxv) / maxv);
}

int
vx_image_flatten(vx_image *dst, const vx_image *src, double scale,
    const double bg[3], vx_err *e)
{
	int ncol = vx_image_ncolor(src), alpha = vx_image_has_alpha(src), rc;
	double gbg = 0.2126 * bg[0] + 0.7152 * bg[1] + 0.0722 * bg[2];
	size_t i, n = (size_t)src->w * (size_t)src->h;

	if ((rc = vx_image_alloc(dst, src->w, src->h, ncol, e)) != 0)
		return rc;
	memcpy(dst->name, src->name, sizeof dst->name);
	for (i = 0; i < n; i++) {
		const float *s = src->px + i * (size_t)src->nc;
		float *d = dst->px + i * (size_t)ncol;
		double a = alpha ? s[ncol] : 1;

		for (int c = 0; c < ncol; c++) {
			double b = ncol == 1 ? gbg : bg[c];

			d[c] = (float)(s[c] * scale + (alpha ? (1 - a) * b : 0));
		}
	}
	return 0;
}
