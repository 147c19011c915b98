/* png.c: PNG output and input of float images through libpng.
 *
 * libpng reports errors by longjmp.  Each use keeps all its state in a
 * struct png_io that lives in the caller's frame; the only function that calls
 * setjmp (write_guarded, read_guarded) changes no local variable after it, so
 * nothing is indeterminate after the jump, and the caller frees whatever the
 * struct holds whichever way the work ended.  Warnings are dropped (the core
 * never prints); errors come back as vx_err. */
#include "vx_imageio.h"

#include <errno.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <png.h>

#define ZLIB_MAX_RATIO 1032

struct png_io {
	png_structp png;
	png_infop info;
	char msg[256];          /* libpng's error message */
	int werr;               /* errno of a failed write, 0 if none */
	/* writing */
	FILE *f;
	const vx_image *img;
	int bits;
	double gamma;           /* < 0: no color-space chunk */
	png_textp text;
	size_t ntext;
	unsigned char *row;
	/* reading */
	const unsigned char *buf;
	size_t n, pos;
	unsigned char *data;    /* decoded rows */
	png_bytep *rows;
	vx_image *out;
	int outbits;
	int rc;                 /* a vx error code set before png_error */
};

static void
on_error(png_structp png, png_const_charp msg)
{
	struct png_io *io = png_get_error_ptr(png);

	if (io->msg[0] == '\0')
		snprintf(io->msg, sizeof io->msg, "%s", msg);
	png_longjmp(png, 1);
}

static void
on_warning(png_structp png, png_const_charp msg)
{
	(void)png;
	(void)msg;
}

/* ---- writing ---- */

static void
write_fn(png_structp png, png_bytep data, size_t n)
{
	struct png_io *io = png_get_io_ptr(png);

	if (fwrite(data, 1, n, io->f) != n) {
		io->werr = errno ? errno : EIO;
		png_error(png, "write failed");
	}
}

static void
flush_fn(png_structp png)
{
	struct png_io *io = png_get_io_ptr(png);

	if (fflush(io->f) != 0) {
		io->werr = errno ? errno : EIO;
		png_error(png, "write failed");
	}
}

/* write_body: everything after the structs exist; may longjmp. */
static void
write_body(struct png_io *io)
{
	static const int ctype[5] = { 0, PNG_COLOR_TYPE_GRAY,
	    PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
	    PNG_COLOR_TYPE_RGB_ALPHA };
	const vx_image *img = io->img;
	unsigned maxv = io->bits == 16 ? 65535u : 255u;
	size_t rowlen = (size_t)img->w * (size_t)img->nc;
	int y;

	png_set_write_fn(io->png, io, write_fn, flush_fn);
	png_set_IHDR(io->png, io->info, (png_uint_32)img->w,
	    (png_uint_32)img->h, io->bits, ctype[img->nc], PNG_INTERLACE_NONE,
	    PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
	if (io->gamma == 0)
		png_set_sRGB_gAMA_and_cHRM(io->png, io->info,
		    PNG_sRGB_INTENT_PERCEPTUAL);
	else if (io->gamma > 0)
		png_set_gAMA(io->png, io->info, 1.0 / io->gamma);
	if (io->ntext > 0)
		png_set_text(io->png, io->info, io->text, (int)io->ntext);
	png_write_info(io->png, io->info);
	for (y = 0; y < img->h; y++) {
		const float *p = vx_image_pixel(img, 0, y);
		size_t i;

		if (io->bits == 8)
			for (i = 0; i < rowlen; i++)
				io->row[i] = (unsigned char)vx_quantize(p[i], maxv);
		else
			for (i = 0; i < rowlen; i++) {
				unsigned v = vx_quantize(p[i], maxv);

				io->row[2 * i] = (unsigned char)(v >> 8);
				io->row[2 * i + 1] = (unsigned char)(v & 0xff);
			}
		png_write_row(io->png, io->row);
	}
	png_write_end(io->png, io->info);
}

static int
write_guarded(struct png_io *io)
{
	if (setjmp(png_jmpbuf(io->png)))
		return -1;
	write_body(io);
	return 0;
}

/* text_key_ok: a tEXt keyword: 1..79 Latin-1 printable characters, no
 * leading, trailing or doubled spaces (PNG spec 11.3.4.3). */
static int
text_key_ok(const char *k)
{
	size_t i, n = strlen(k);

	if (n < 1 || n > 79 || k[0] == ' ' || k[n - 1] == ' ')
		return 0;
	for (i = 0; i < n; i++) {
		unsigned char c = (unsigned char)k[i];

		if (!((c >= 32 && c <= 126) || c >= 161))
			return 0;
		if (c == ' ' && k[i + 1] == ' ')
			return 0;
	}
	return 1;
}

int
vx_image_png_write_gamma(const vx_image *img, FILE *f, int bits,
    double gamma, const vx_text *text, size_t ntext, vx_err *e)
{
	struct png_io io;
	size_t i;
	int rc = 0;

	if (bits != 8 && bits != 16)
		return vx_err_set(e, VX_EUSAGE, "png: bit depth %d (8 or 16)",
		    bits);
	if (img->px == NULL || img->nc < 1 || img->nc > 4)
		return vx_err_set(e, VX_EUSAGE, "png: empty image or %d channels",
		    img->nc);
	for (i = 0; i < ntext; i++)
		if (!text_key_ok(text[i].key))
			return vx_err_set(e, VX_EUSAGE, "png: bad text key '%.80s'",
			    text[i].key);
	memset(&io, 0, sizeof io);
	io.f = f;
	io.img = img;
	io.bits = bits;
	io.gamma = gamma;
	io.ntext = ntext;
	io.row = vx_malloc((size_t)img->w * (size_t)img->nc * (size_t)(bits /
	    8), e);
	if (io.row == NULL)
		return VX_ENOMEM;
	if (ntext > 0 && (io.text = vx_calloc(ntext, sizeof *io.text,
	    e)) == NULL) {
		free(io.row);
		return VX_ENOMEM;
	}
	for (i = 0; i < ntext; i++) {
		/* libpng copies the strings; its struct wants them non-const */
		io.text[i].compression = PNG_TEXT_COMPRESSION_NONE;
		io.text[i].key = (png_charp)(uintptr_t)text[i].key;
		io.text[i].text = (png_charp)(uintptr_t)(text[i].value ?
		    text[i].value : "");
		io.text[i].text_length = strlen(io.text[i].text);
	}
	io.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &io, on_error,
	    on_warning);
	if (io.png == NULL || (io.info = png_create_info_struct(io.png)) ==
	    NULL)
		rc = vx_err_set(e, VX_ENOMEM, "png: out of memory");
	else if (write_guarded(&io) != 0) {
		if (io.werr != 0)
			rc = vx_err_set(e, VX_EIO, "png: write: %s",
			    strerror(io.werr));
		else
			rc = vx_err_set(e, VX_EDATA, "png: %s", io.msg);
	} else if (fflush(f) != 0 || ferror(f))
		rc = vx_err_set(e, VX_EIO, "png: write: %s", strerror(errno));
	png_destroy_write_struct(io.png ? &io.png : NULL, &io.info);
	free(io.text);
	free(io.row);
	return rc;
}

int
vx_image_png_write(const vx_image *img, FILE *f, int bits,
    const vx_text *text, size_t ntext, vx_err *e)
{
	return vx_image_png_write_gamma(img, f, bits, -1, text, ntext, e);
}

/* ---- reading ---- */

static void
read_fn(png_structp png, png_bytep data, size_t n)
{
	struct png_io *io = png_get_io_ptr(png);

	if (n > io->n - io->pos)
		png_error(png, "truncated PNG");
	memcpy(data, io->buf + io->pos, n);
	io->pos += n;
}

/* read_body: decode into io->out; may longjmp.  Buffers hang off io. */
static void
read_body(struct png_io *io)
{
	png_uint_32 w, h, y;
	size_t rowbytes, raw, bound, x, nv;
	int depth, ctype, interlace, nc;
	vx_err e = { 0, "" };

	png_set_read_fn(io->png, io, read_fn);
	png_set_user_limits(io->png, VX_IMAGE_MAX_DIM, VX_IMAGE_MAX_DIM);
	/* no chunk (text, profile, unknown) is buffered beyond 8 MB, libpng's
	 * own recommended ceiling, whatever its length word claims (Debian's
	 * build leaves it unlimited); at most 1000 ancillary chunks kept */
	png_set_chunk_malloc_max(io->png, (png_alloc_size_t)8 << 20);
	png_set_chunk_cache_max(io->png, 1000);
	png_read_info(io->png, io->info);
	png_get_IHDR(io->png, io->info, &w, &h, &depth, &ctype, &interlace,
	    NULL, NULL);
	if ((uint64_t)w * h > VX_IMAGE_MAX_PIXELS) {
		snprintf(io->msg, sizeof io->msg, "%lu x %lu pixels exceed the "
		    "limit of %zu", (unsigned long)w, (unsigned long)h,
		    VX_IMAGE_MAX_PIXELS);
		png_error(io->png, io->msg);
	}
	/* the filtered rows (one filter byte each) must fit in what the
	 * compressed data present could inflate to */
	raw = ((size_t)png_get_rowbytes(io->png, io->info) + 1) * h;
	bound = io->n > SIZE_MAX / ZLIB_MAX_RATIO ? SIZE_MAX :
	    io->n * ZLIB_MAX_RATIO;
	if (raw > bound) {
		snprintf(io->msg, sizeof io->msg, "%lu x %lu pixels cannot come "
		    "from %zu bytes", (unsigned long)w, (unsigned long)h, io->n);
		png_error(io->png, io->msg);
	}
	if (ctype == PNG_COLOR_TYPE_PALETTE)
		png_set_palette_to_rgb(io->png);
	if ((ctype & PNG_COLOR_MASK_COLOR) == 0 && depth < 8)
		png_set_expand_gray_1_2_4_to_8(io->png);
	if (png_get_valid(io->png, io->info, PNG_INFO_tRNS))
		png_set_tRNS_to_alpha(io->png);
	(void)png_set_interlace_handling(io->png);
	png_read_update_info(io->png, io->info);
	nc = png_get_channels(io->png, io->info);
	depth = png_get_bit_depth(io->png, io->info);
	rowbytes = png_get_rowbytes(io->png, io->info);
	if (nc < 1 || nc > 4 || (depth != 8 && depth != 16) ||
	    rowbytes != (size_t)w * (size_t)nc * (size_t)(depth / 8))
		png_error(io->png, "unexpected layout after expansion");
	if ((io->data = malloc(rowbytes * h)) == NULL ||
	    (io->rows = malloc(h * sizeof *io->rows)) == NULL) {
		io->rc = VX_ENOMEM;
		png_error(io->png, "out of memory");
	}
	for (y = 0; y < h; y++)
		io->rows[y] = io->data + (size_t)y * rowbytes;
	png_read_image(io->png, io->rows);
	png_read_end(io->png, NULL);
	if ((io->rc = vx_image_alloc(io->out, (int)w, (int)h, nc, &e)) != 0) {
		snprintf(io->msg, sizeof io->msg, "%.200s", e.msg);
		png_error(io->png, io->msg);
	}
	nv = (size_t)w * h * (size_t)nc;
	if (depth == 8)
		for (x = 0; x < nv; x++)
			io->out->px[x] = (float)(io->data[x] / 255.0);
	else
		for (x = 0; x < nv; x++)
			io->out->px[x] = (float)((io->data[2 * x] << 8 |
			    io->data[2 * x + 1]) / 65535.0);
	io->outbits = depth;
}

static int
read_guarded(struct png_io *io)
{
	if (setjmp(png_jmpbuf(io->png)))
		return -1;
	read_body(io);
	return 0;
}

/* chunks_fit: every chunk's length word fits in the bytes that follow it.
 * libpng allocates a chunk's buffer (tEXt, for one) from the length word
 * before reading the data, so a lying length is refused here first. */
static int
chunks_fit(const unsigned char *p, size_t n, vx_err *e)
{
	size_t pos = 8;

	while (pos < n) {
		uint32_t len;

		if (n - pos < 12)
			return vx_err_set(e, VX_EDATA, "png: truncated chunk at "
			    "offset %zu", pos);
		len = (uint32_t)p[pos] << 24 | (uint32_t)p[pos + 1] << 16 |
		    (uint32_t)p[pos + 2] << 8 | p[pos + 3];
		if (len > n - pos - 12)
			return vx_err_set(e, VX_EDATA, "png: chunk at offset %zu "
			    "claims %lu bytes, %zu remain", pos, (unsigned long)len,
			    n - pos - 12);
		if (memcmp(p + pos + 4, "IEND", 4) == 0)
			break;
		pos += 12 + (size_t)len;
	}
	return 0;
}

int
vx_image_png_read_mem(vx_image *img, const void *buf, size_t n, int *bits,
    vx_err *e)
{
	struct png_io io;
	int rc = 0;

	vx_image_init(img);
	if (n < 8 || png_sig_cmp(buf, 0, 8) != 0)
		return vx_err_set(e, VX_EDATA, "png: not a PNG file");
	if ((rc = chunks_fit(buf, n, e)) != 0)
		return rc;
	memset(&io, 0, sizeof io);
	io.buf = buf;
	io.n = n;
	io.out = img;
	io.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &io, on_error,
	    on_warning);
	if (io.png == NULL || (io.info = png_create_info_struct(io.png)) ==
	    NULL)
		rc = vx_err_set(e, VX_ENOMEM, "png: out of memory");
	else if (read_guarded(&io) != 0) {
		rc = vx_err_set(e, io.rc ? io.rc : VX_EDATA, "png: %s", io.msg);
		vx_image_free(img);
	} else if (bits != NULL)
		*bits = io.outbits;
	png_destroy_read_struct(io.png ? &io.png : NULL, &io.info, NULL);
	free(io.rows);
	free(io.data);
	return rc;
}
