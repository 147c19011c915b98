/* test_image.c: float images, the IMAG chunk, PFM and PNG files.
 * (Tone mapping and comparison: test_tonemap.c.) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include <png.h>
#include <zlib.h>

#include "vx_image.h"
#include "vx_imageio.h"

/* ---- helpers ---- */

/* file_bytes: rewind f and read all of it (test files are small). */
static unsigned char *
file_bytes(FILE *f, size_t *n)
{
	unsigned char *buf;
	vx_err e = { 0, "" };

	rewind(f);
	assert_int_equal(vx_file_read_all(f, (size_t)1 << 26, &buf, n, &e), 0);
	return buf;
}

static int
same_bits(float a, float b)
{
	return memcmp(&a, &b, sizeof a) == 0;
}

static void
put_f32(unsigned char *p, float v, int little)
{
	uint32_t u;

	memcpy(&u, &v, 4);
	for (int i = 0; i < 4; i++)
		p[little ? i : 3 - i] = (unsigned char)(u >> (8 * i));
}

/* ---- allocation limits ---- */

static void
alloc_limits(void **state)
{
	/* oracle: the limits as documented in vx_image.h */
	static const struct { int w, h, nc, rc; } t[] = {
		{ 1, 1, 1, 0 },
		{ 7, 3, 4, 0 },
		{ 65536, 1, 1, 0 },
		{ 0, 1, 1, VX_EDATA },
		{ 1, -1, 1, VX_EDATA },
		{ 65537, 1, 1, VX_EDATA },
		{ 65536, 65536, 1, VX_EDATA },   /* 2^32 pixels > 2^28 */
		{ 16384, 16385, 1, VX_EDATA },
		{ 2, 2, 0, VX_EDATA },
		{ 2, 2, 5, VX_EDATA },
	};
	size_t i;

	(void)state;
	for (i = 0; i < 2 * sizeof t / sizeof t[0]; i++) {
		/* the second pass: vx_image_alloc_uninit, the same limits
		 * (its pixels are not read: they are not set) */
		size_t k = i % (sizeof t / sizeof t[0]);
		int zero = i < sizeof t / sizeof t[0];
		vx_image img;
		vx_err e = { 0, "" };

		assert_int_equal((zero ? vx_image_alloc : vx_image_alloc_uninit)(
		    &img, t[k].w, t[k].h, t[k].nc, &e), t[k].rc);
		if (t[k].rc == 0) {
			assert_non_null(img.px);
			assert_int_equal(vx_image_nvalue(&img),
			    (size_t)t[k].w * (size_t)t[k].h * (size_t)t[k].nc);
			if (zero)
				assert_true(img.px[vx_image_nvalue(&img) - 1] ==
				    0);
			assert_string_equal(img.name, "image");
		} else {
			assert_null(img.px);
			assert_true(e.msg[0] != 0);
		}
		vx_image_free(&img);
		vx_image_free(&img);   /* freeing twice is fine */
	}
	vx_image_free(NULL);
}

static void
get_set_layout(void **state)
{
	/* oracle: the layout formula px[(y*w + x)*nc + c] */
	vx_image img;
	vx_err e = { 0, "" };

	(void)state;
	assert_int_equal(vx_image_alloc(&img, 5, 3, 4, &e), 0);
	vx_image_set(&img, 4, 2, 3, 7.5f);
	vx_image_set(&img, 1, 0, 2, -1.0f);
	assert_true(img.px[(2 * 5 + 4) * 4 + 3] == 7.5f);
	assert_true(img.px[(0 * 5 + 1) * 4 + 2] == -1.0f);
	assert_true(vx_image_get(&img, 4, 2, 3) == 7.5f);
	assert_int_equal(vx_image_has_alpha(&img), 1);
	assert_int_equal(vx_image_ncolor(&img), 3);
	vx_image_free(&img);
}

/* ---- IMAG chunk ---- */

static void
fill_pattern(vx_image *img)
{
	size_t i, n = vx_image_nvalue(img);

	for (i = 0; i < n; i++)
		img->px[i] = (float)i * 0.25f - 3.0f;
	img->px[0] = NAN;
	img->px[n - 1] = INFINITY;
	if (n > 2)
		img->px[1] = -INFINITY;
}

static void
chunk_roundtrip(void **state)
{
	(void)state;
	for (int nc = 1; nc <= 4; nc++)
		for (int z = 0; z <= 6; z += 6) {
			vx_image a, b;
			vx_chunk c;
			vx_hdr h;
			const unsigned char *body;
			size_t bl, i;
			vx_err e = { 0, "" };

			assert_int_equal(vx_image_alloc(&a, 7, 3, nc, &e), 0);
			fill_pattern(&a);
			snprintf(a.name, sizeof a.name, "depth %d", nc);
			memset(&c, 0, sizeof c);
			assert_int_equal(vx_image_to_chunk(&a, z, &c, &e), 0);
			assert_string_equal(c.type, "IMAG");
			/* the header says what formats/image.md says */
			vx_hdr_init(&h);
			assert_int_equal(vx_payload_parse(&c, &h, &body, &bl, &e), 0);
			assert_string_equal(vx_hdr_get(&h, "width"), "7");
			assert_string_equal(vx_hdr_get(&h, "height"), "3");
			assert_string_equal(vx_hdr_get(&h, "colorspace"), "linear");
			assert_string_equal(vx_hdr_get(&h, "encoding"),
			    z ? "zlib" : "raw");
			if (nc == 2 || nc == 4)
				assert_string_equal(vx_hdr_get(&h, "alpha"),
				    "premultiplied");
			else
				assert_null(vx_hdr_get(&h, "alpha"));
			if (z == 0) {
				/* body: f32 LE, top row first */
				assert_int_equal(bl, 7 * 3 * nc * 4);
				unsigned char want[4];
				put_f32(want, a.px[5], 1);
				assert_memory_equal(body + 5 * 4, want, 4);
			}
			vx_hdr_free(&h);
			assert_int_equal(vx_image_from_chunk(&b, &c, &e), 0);
			assert_int_equal(b.w, 7);
			assert_int_equal(b.h, 3);
			assert_int_equal(b.nc, nc);
			assert_string_equal(b.name, a.name);
			for (i = 0; i < vx_image_nvalue(&a); i++)
				assert_true(same_bits(a.px[i], b.px[i]));
			vx_chunk_free(&c);
			vx_image_free(&a);
			vx_image_free(&b);
		}
}

/* make_chunk: an IMAG chunk from a header text and a body. */
static void
make_chunk(vx_chunk *c, const char *hdr, const void *body, size_t n)
{
	size_t hl = strlen(hdr);

	memset(c, 0, sizeof *c);
	memcpy(c->type, "IMAG", 5);
	c->len = hl + n;
	c->data = malloc(c->len + 1);
	memcpy(c->data, hdr, hl);
	if (n > 0)
		memcpy(c->data + hl, body, n);
}

static void
chunk_malformed(void **state)
{
	/* oracle: each header breaks one documented rule */
	static const char *bad[] = {
		"width: 2\nheight: 1\n\n",                      /* no channels */
		"width: 0\nheight: 1\nchannels: 1\n\n",
		"width: 2\nheight: 1\nchannels: 5\n\n",
		"width: 70000\nheight: 1\nchannels: 1\n\n",
		"width: 2\nheight: 1\nchannels: 1\ncolorspace: srgb\n\n",
		"width: 2\nheight: 1\nchannels: 2\nalpha: straight\n\n",
		"width: 2\nheight: 1\nchannels: 1\nencoding: lzma\n\n",
		"width: 3\nheight: 1\nchannels: 1\n\n",         /* body short */
		"width: 1\nheight: 1\nchannels: 1\n\n",         /* body long */
		/* 2^28 pixels claimed by 8 bytes: refused before allocating */
		"width: 16384\nheight: 16384\nchannels: 4\n\n",
		"width: 16384\nheight: 16384\nchannels: 4\nencoding: zlib\n\n",
	};
	float body[2] = { 1, 2 };
	size_t i;

	(void)state;
	for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		vx_chunk c;
		vx_image img;
		vx_err e = { 0, "" };

		make_chunk(&c, bad[i], body, sizeof body);
		assert_int_equal(vx_image_from_chunk(&img, &c, &e), VX_EDATA);
		assert_null(img.px);
		assert_true(strncmp(e.msg, "image", 5) == 0);
		vx_chunk_free(&c);
	}
	/* a good one for contrast, without the optional keys */
	{
		vx_chunk c;
		vx_image img;
		vx_err e = { 0, "" };
		unsigned char le[8];

		put_f32(le, 1.5f, 1);
		put_f32(le + 4, -2.0f, 1);
		make_chunk(&c, "width: 1\nheight: 2\nchannels: 1\n\n", le, 8);
		assert_int_equal(vx_image_from_chunk(&img, &c, &e), 0);
		assert_true(vx_image_get(&img, 0, 0, 0) == 1.5f);
		assert_true(vx_image_get(&img, 0, 1, 0) == -2.0f);
		assert_string_equal(img.name, "image");
		vx_image_free(&img);
		vx_chunk_free(&c);
	}
}

static void
stream_by_name(void **state)
{
	/* a renderer's stream: color, depth, normal under their names */
	static const struct { const char *name; int nc; } im[] = {
		{ "color", 4 }, { "depth", 1 }, { "normal", 3 },
	};
	vx_stream s;
	vx_image img;
	vx_err e = { 0, "" };
	long idx = -1;
	size_t i;

	(void)state;
	vx_stream_init(&s);
	assert_int_equal(vx_stream_history_add(&s, "raycast 0.1.0", &e), 0);
	for (i = 0; i < 3; i++) {
		vx_chunk c;

		assert_int_equal(vx_image_alloc(&img, 4, 2, im[i].nc, &e), 0);
		snprintf(img.name, sizeof img.name, "%s", im[i].name);
		img.px[0] = (float)i;
		assert_int_equal(vx_image_to_chunk(&img, 1, &c, &e), 0);
		assert_int_equal(vx_stream_append(&s, &c, &e), 0);
		vx_image_free(&img);
	}
	assert_int_equal(vx_image_from_stream(&img, &s, "depth", &idx, &e), 0);
	assert_int_equal(idx, 2);   /* the history chunk is first */
	assert_int_equal(img.nc, 1);
	assert_true(img.px[0] == 1.0f);
	vx_image_free(&img);
	assert_int_equal(vx_image_from_stream(&img, &s, NULL, &idx, &e), 0);
	assert_string_equal(img.name, "color");
	assert_int_equal(img.nc, 4);
	vx_image_free(&img);
	assert_int_equal(vx_image_from_stream(&img, &s, "albedo", NULL, &e),
	    VX_EDATA);
	assert_non_null(strstr(e.msg, "albedo"));
	vx_stream_free(&s);
	vx_stream_init(&s);
	assert_int_equal(vx_image_from_stream(&img, &s, NULL, NULL, &e),
	    VX_EDATA);
	vx_stream_free(&s);
}

/* ---- PFM ---- */

static void
pfm_decode_known(void **state)
{
	/* hand-made files; oracle: the PFM rules (sign of the scale gives the
	 * byte order, rows bottom first) applied by hand */
	unsigned char buf[64];
	vx_image img;
	vx_err e = { 0, "" };
	size_t k;

	(void)state;
	/* gray 2x2, little-endian: stored rows (1 2) then (3 4) */
	k = (size_t)sprintf((char *)buf, "Pf\n2 2\n-1.0\n");
	for (int i = 0; i < 4; i++)
		put_f32(buf + k + 4 * i, (float)(i + 1), 1);
	assert_int_equal(vx_pfm_read_mem(&img, buf, k + 16, &e), 0);
	assert_int_equal(img.w, 2);
	assert_int_equal(img.h, 2);
	assert_int_equal(img.nc, 1);
	assert_true(vx_image_get(&img, 0, 0, 0) == 3.0f);  /* top row */
	assert_true(vx_image_get(&img, 1, 0, 0) == 4.0f);
	assert_true(vx_image_get(&img, 0, 1, 0) == 1.0f);  /* bottom row */
	assert_true(vx_image_get(&img, 1, 1, 0) == 2.0f);
	vx_image_free(&img);

	/* RGB 1x1, big-endian (positive scale 4.0, not applied), raw bytes
	 * 3f000000 = 0.5, 3f800000 = 1.0, c0000000 = -2.0 */
	k = (size_t)sprintf((char *)buf, "PF 1 1 4.0\n");
	memcpy(buf + k, "\x3f\x00\x00\x00\x3f\x80\x00\x00\xc0\x00\x00\x00", 12);
	assert_int_equal(vx_pfm_read_mem(&img, buf, k + 12, &e), 0);
	assert_int_equal(img.nc, 3);
	assert_true(img.px[0] == 0.5f);
	assert_true(img.px[1] == 1.0f);
	assert_true(img.px[2] == -2.0f);
	vx_image_free(&img);

	/* same values little-endian: 00 00 00 3f ... */
	k = (size_t)sprintf((char *)buf, "PF\n1 1\n-0.5\n");
	memcpy(buf + k, "\x00\x00\x00\x3f\x00\x00\x80\x3f\x00\x00\x00\xc0", 12);
	assert_int_equal(vx_pfm_read_mem(&img, buf, k + 12, &e), 0);
	assert_true(img.px[0] == 0.5f && img.px[1] == 1.0f &&
	    img.px[2] == -2.0f);
	vx_image_free(&img);
}

static void
pfm_malformed(void **state)
{
	/* oracle: each breaks one rule of the header or the size */
	static const struct { const char *hdr; size_t data; } t[] = {
		{ "PF", 0 },                   /* nothing after the magic */
		{ "PF\n2", 0 },
		{ "PF\n2 2\n", 48 },           /* no scale */
		{ "PX\n1 1\n-1\n", 12 },
		{ "PF1 1\n-1\n", 12 },         /* no space after magic */
		{ "PF\n1 1\n0\n", 12 },        /* zero scale */
		{ "PF\n1 1\nnan\n", 12 },
		{ "PF\n1 1\ninf\n", 12 },
		{ "PF\n1 1\n-1x\n", 12 },
		{ "PF\n1 1\n-1", 0 },          /* header not ended */
		{ "PF\n0 1\n-1\n", 0 },
		{ "PF\n-1 1\n-1\n", 12 },
		{ "PF\n65537 1\n-1\n", 12 },
		{ "PF\n1234567890 1\n-1\n", 12 },
		{ "Pf\n65536 65536\n-1\n", 4 }, /* huge claim, 4 bytes */
		{ "PF\n2 1\n-1\n", 23 },       /* one byte short */
		{ "PF\n2 1\n-1\n", 25 },       /* one byte long */
		{ "Pf\n2 1\n-1\n", 4 },
	};
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		size_t hl = strlen(t[i].hdr);
		unsigned char *buf = calloc(1, hl + t[i].data + 1);
		vx_image img;
		vx_err e = { 0, "" };

		memcpy(buf, t[i].hdr, hl);
		assert_int_equal(vx_pfm_read_mem(&img, buf, hl + t[i].data, &e),
		    VX_EDATA);
		assert_null(img.px);
		assert_true(strncmp(e.msg, "pfm: ", 5) == 0);
		free(buf);
	}
}

static void
pfm_roundtrip(void **state)
{
	(void)state;
	for (int nc = 1; nc <= 3; nc += 2) {
		vx_image a, b;
		vx_err e = { 0, "" };
		FILE *f = tmpfile();
		unsigned char *buf;
		size_t n, i;
		char hdr[32];
		int hl;

		assert_int_equal(vx_image_alloc(&a, 3, 2, nc, &e), 0);
		fill_pattern(&a);
		assert_int_equal(vx_pfm_write(&a, f, &e), 0);
		buf = file_bytes(f, &n);
		/* the writer's header and byte order: little-endian, scale -1,
		 * the first stored row is the bottom one */
		hl = sprintf(hdr, "P%c\n3 2\n-1.0\n", nc == 3 ? 'F' : 'f');
		assert_int_equal(n, (size_t)hl + 3 * 2 * nc * 4);
		assert_memory_equal(buf, hdr, (size_t)hl);
		unsigned char want[4];
		put_f32(want, vx_image_get(&a, 0, 1, 0), 1);
		assert_memory_equal(buf + hl, want, 4);
		assert_int_equal(vx_pfm_read_mem(&b, buf, n, &e), 0);
		assert_int_equal(b.nc, nc);
		for (i = 0; i < vx_image_nvalue(&a); i++)
			assert_true(same_bits(a.px[i], b.px[i]));
		vx_image_free(&b);
		/* and the big-endian form of the same data reads the same */
		buf[hl - 5] = ' ';   /* "-1.0" -> " 1.0" */
		for (i = (size_t)hl; i < n; i += 4) {
			unsigned char t0 = buf[i], t1 = buf[i + 1];
			buf[i] = buf[i + 3];
			buf[i + 1] = buf[i + 2];
			buf[i + 2] = t1;
			buf[i + 3] = t0;
		}
		assert_int_equal(vx_pfm_read_mem(&b, buf, n, &e), 0);
		for (i = 0; i < vx_image_nvalue(&a); i++)
			assert_true(same_bits(a.px[i], b.px[i]));
		vx_image_free(&b);
		free(buf);
		fclose(f);
		vx_image_free(&a);
	}
	/* 2 or 4 channels do not fit a PFM */
	{
		vx_image a;
		vx_err e = { 0, "" };

		assert_int_equal(vx_image_alloc(&a, 1, 1, 4, &e), 0);
		assert_int_equal(vx_pfm_write(&a, stdout, &e), VX_EUSAGE);
		vx_image_free(&a);
	}
}

/* ---- PNG ---- */

/* What libpng itself reads back (an oracle independent of png.c's reader):
 * raw rows, bit depth, color type, text chunks, color-space chunks. */
struct ref_png {
	png_uint_32 w, h;
	int depth, ctype, has_srgb, has_gama;
	double gama;
	unsigned char *data;
	size_t rowbytes;
	char software[128], history[512];
};

struct membuf {
	const unsigned char *p;
	size_t n, pos;
};

static void
mem_read(png_structp png, png_bytep out, size_t n)
{
	struct membuf *m = png_get_io_ptr(png);

	if (n > m->n - m->pos)
		png_error(png, "eof");
	memcpy(out, m->p + m->pos, n);
	m->pos += n;
}

static void
ref_png_read(struct ref_png *r, const unsigned char *buf, size_t n)
{
	struct membuf m = { buf, n, 0 };
	png_structp png;
	png_infop info;
	png_bytepp rows;
	png_textp text;
	int nt, i;

	memset(r, 0, sizeof *r);
	png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
	info = png_create_info_struct(png);
	if (setjmp(png_jmpbuf(png)))
		fail_msg("libpng could not read our PNG");
	png_set_read_fn(png, &m, mem_read);
	png_read_png(png, info, PNG_TRANSFORM_IDENTITY, NULL);
	r->w = png_get_image_width(png, info);
	r->h = png_get_image_height(png, info);
	r->depth = png_get_bit_depth(png, info);
	r->ctype = png_get_color_type(png, info);
	r->rowbytes = png_get_rowbytes(png, info);
	r->has_srgb = png_get_valid(png, info, PNG_INFO_sRGB) != 0;
	r->has_gama = png_get_gAMA(png, info, &r->gama) != 0;
	rows = png_get_rows(png, info);
	r->data = malloc(r->rowbytes * r->h);
	for (png_uint_32 y = 0; y < r->h; y++)
		memcpy(r->data + y * r->rowbytes, rows[y], r->rowbytes);
	nt = png_get_text(png, info, &text, NULL);
	for (i = 0; i < nt; i++) {
		assert_int_equal(text[i].compression, PNG_TEXT_COMPRESSION_NONE);
		if (strcmp(text[i].key, "Software") == 0)
			snprintf(r->software, sizeof r->software, "%s", text[i].text);
		if (strcmp(text[i].key, "voxlux-history") == 0)
			snprintf(r->history, sizeof r->history, "%s", text[i].text);
	}
	png_destroy_read_struct(&png, &info, NULL);
}

static unsigned
ref_code(const struct ref_png *r, size_t i)
{
	if (r->depth == 8)
		return r->data[i];
	return (unsigned)r->data[2 * i] << 8 | r->data[2 * i + 1];
}

static void
png_write_read(void **state)
{
	static const int ctype[5] = { 0, PNG_COLOR_TYPE_GRAY,
	    PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
	    PNG_COLOR_TYPE_RGB_ALPHA };
	const vx_text text[2] = {
		{ "Software", "voxlux 0.1.0" },
		{ "voxlux-history", "vread 0.1.0 --synth sphere\ntonemap 0.1.0" },
	};

	(void)state;
	for (int bits = 8; bits <= 16; bits += 8)
		for (int nc = 1; nc <= 4; nc++) {
			unsigned maxv = bits == 8 ? 255 : 65535;
			vx_image a, b;
			vx_err e = { 0, "" };
			struct ref_png r;
			FILE *f = tmpfile();
			unsigned char *buf;
			size_t n, i, nv;
			unsigned *want;
			int rbits;

			assert_int_equal(vx_image_alloc(&a, 5, 3, nc, &e), 0);
			nv = vx_image_nvalue(&a);
			want = calloc(nv, sizeof *want);
			/* oracle: exact codes k/maxv give k; +-0.49 of a step
			 * rounds to the nearest code; out-of-range values clamp;
			 * NaN gives 0 */
			for (i = 0; i < nv; i++) {
				unsigned k = (unsigned)((i * 2654435761u) % maxv);
				double off = i % 3 == 0 ? 0 : i % 3 == 1 ? 0.49 : -0.49;

				if (k == 0 && off < 0)
					off = 0;
				a.px[i] = (float)((k + off) / maxv);
				want[i] = k;
			}
			a.px[0] = -0.5f, want[0] = 0;
			a.px[1] = 2.0f, want[1] = maxv;
			a.px[2] = NAN, want[2] = 0;
			a.px[3] = INFINITY, want[3] = maxv;
			a.px[4] = 1.0f, want[4] = maxv;
			assert_int_equal(vx_image_png_write(&a, f, bits, text, 2, &e),
			    0);
			buf = file_bytes(f, &n);
			ref_png_read(&r, buf, n);
			assert_int_equal(r.w, 5);
			assert_int_equal(r.h, 3);
			assert_int_equal(r.depth, bits);
			assert_int_equal(r.ctype, ctype[nc]);
			assert_int_equal(r.has_srgb, 0);
			assert_int_equal(r.has_gama, 0);
			for (i = 0; i < nv; i++)
				assert_int_equal(ref_code(&r, i), want[i]);
			assert_string_equal(r.software, "voxlux 0.1.0");
			assert_string_equal(r.history,
			    "vread 0.1.0 --synth sphere\ntonemap 0.1.0");
			/* our reader gives code / maxv */
			assert_int_equal(vx_image_png_read_mem(&b, buf, n, &rbits,
			    &e), 0);
			assert_int_equal(rbits, bits);
			assert_int_equal(b.nc, nc);
			for (i = 0; i < nv; i++)
				assert_true(b.px[i] == (float)(want[i] / (double)maxv));
			/* vx_image_quantize agrees with what the file holds */
			vx_image_quantize(&a, bits);
			for (i = 0; i < nv; i++)
				assert_true(a.px[i] == b.px[i]);
			vx_image_free(&b);
			free(r.data);
			free(buf);
			free(want);
			fclose(f);
			vx_image_free(&a);
		}
}

static void
png_gamma_chunks(void **state)
{
	/* oracle: libpng sees the chunk we asked for */
	static const struct { double g; int srgb, gama; double want; } t[] = {
		{ 0, 1, 1, 0.45455 }, { 2.2, 0, 1, 1 / 2.2 }, { 1, 0, 1, 1.0 },
	};

	(void)state;
	for (size_t k = 0; k < sizeof t / sizeof t[0]; k++) {
		vx_image a;
		vx_err e = { 0, "" };
		struct ref_png r;
		FILE *f = tmpfile();
		unsigned char *buf;
		size_t n;

		assert_int_equal(vx_image_alloc(&a, 2, 2, 3, &e), 0);
		assert_int_equal(vx_image_png_write_gamma(&a, f, 8, t[k].g, NULL, 0,
		    &e), 0);
		buf = file_bytes(f, &n);
		ref_png_read(&r, buf, n);
		assert_int_equal(r.has_srgb, t[k].srgb);
		assert_int_equal(r.has_gama, t[k].gama);
		assert_true(fabs(r.gama - t[k].want) < 1e-5);
		free(r.data);
		free(buf);
		fclose(f);
		vx_image_free(&a);
	}
}

static void
png_write_errors(void **state)
{
	vx_image a;
	vx_err e = { 0, "" };
	FILE *f = tmpfile();
	static const char *badkey[] = { "", " lead", "trail ", "two  spaces",
	    "key-of-eighty-characters-key-of-eighty-characters-key-of-eighty-characters-abcde",
	    "tab\there" };

	(void)state;
	assert_int_equal(vx_image_alloc(&a, 2, 2, 1, &e), 0);
	assert_int_equal(vx_image_png_write(&a, f, 12, NULL, 0, &e), VX_EUSAGE);
	for (size_t i = 0; i < sizeof badkey / sizeof badkey[0]; i++) {
		vx_text t = { badkey[i], "x" };

		assert_int_equal(vx_image_png_write(&a, f, 8, &t, 1, &e),
		    VX_EUSAGE);
	}
	fclose(f);
	/* a write error (read-only stream) comes back as VX_EIO */
	f = fopen("/dev/null", "r");
	assert_non_null(f);
	assert_int_equal(vx_image_png_write(&a, f, 8, NULL, 0, &e), VX_EIO);
	fclose(f);
	f = fopen("/dev/full", "w");
	if (f != NULL) {
		assert_int_equal(vx_image_png_write(&a, f, 8, NULL, 0, &e), VX_EIO);
		fclose(f);
	}
	vx_image_free(&a);
}

/* write_ref_png: a PNG made by libpng directly, for reader tests. */
static unsigned char *
write_ref_png(int w, int h, int depth, int ctype, const unsigned char *rows,
    const png_color *pal, int npal, const png_byte *trns, int ntrns,
    int interlace, size_t *n)
{
	FILE *f = tmpfile();
	png_structp png;
	png_infop info;
	unsigned char *buf;
	size_t rb;

	png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
	info = png_create_info_struct(png);
	if (setjmp(png_jmpbuf(png)))
		fail_msg("libpng write failed");
	png_init_io(png, f);
	png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, ctype,
	    interlace, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
	if (pal != NULL)
		png_set_PLTE(png, info, pal, npal);
	if (trns != NULL)
		png_set_tRNS(png, info, trns, ntrns, NULL);
	png_write_info(png, info);
	rb = png_get_rowbytes(png, info);
	{
		int passes = png_set_interlace_handling(png);

		for (int p = 0; p < passes; p++)
			for (int y = 0; y < h; y++)
				png_write_row(png, (png_const_bytep)rows + (size_t)y * rb);
	}
	png_write_end(png, info);
	png_destroy_write_struct(&png, &info);
	buf = file_bytes(f, n);
	fclose(f);
	return buf;
}

static void
png_read_expand(void **state)
{
	/* oracle: the PNG spec's expansion rules, values worked by hand */
	vx_image img;
	vx_err e = { 0, "" };
	unsigned char *buf;
	size_t n;
	int bits;

	(void)state;
	/* 2-bit palette, 4 pixels in one byte: indices 0 1 2 3 = 0x1b;
	 * entry 1 is transparent by tRNS -> RGBA 8-bit */
	{
		png_color pal[4] = { { 0, 0, 0 }, { 255, 0, 0 }, { 0, 51, 0 },
		    { 0, 0, 255 } };
		png_byte trns[2] = { 255, 0 };
		unsigned char row[1] = { 0x1b };

		buf = write_ref_png(4, 1, 2, PNG_COLOR_TYPE_PALETTE, row, pal, 4,
		    trns, 2, PNG_INTERLACE_NONE, &n);
		assert_int_equal(vx_image_png_read_mem(&img, buf, n, &bits, &e), 0);
		assert_int_equal(img.nc, 4);
		assert_int_equal(bits, 8);
		assert_true(vx_image_get(&img, 0, 0, 3) == 1.0f);
		assert_true(vx_image_get(&img, 1, 0, 0) == 1.0f);
		assert_true(vx_image_get(&img, 1, 0, 3) == 0.0f);
		assert_true(vx_image_get(&img, 2, 0, 1) == (float)(51 / 255.0));
		assert_true(vx_image_get(&img, 3, 0, 2) == 1.0f);
		assert_true(vx_image_get(&img, 3, 0, 3) == 1.0f);
		vx_image_free(&img);
		free(buf);
	}
	/* 1-bit gray, 8 pixels 10110000 -> 1 0 1 1 0 0 0 0 */
	{
		unsigned char row[1] = { 0xb0 };

		buf = write_ref_png(8, 1, 1, PNG_COLOR_TYPE_GRAY, row, NULL, 0,
		    NULL, 0, PNG_INTERLACE_NONE, &n);
		assert_int_equal(vx_image_png_read_mem(&img, buf, n, &bits, &e), 0);
		assert_int_equal(img.nc, 1);
		static const float want[8] = { 1, 0, 1, 1, 0, 0, 0, 0 };
		for (int x = 0; x < 8; x++)
			assert_true(img.px[x] == want[x]);
		vx_image_free(&img);
		free(buf);
	}
	/* 16-bit RGB, Adam7 interlaced, 3x3: value of channel c at (x, y) is
	 * 1000 * (3y + x) + c */
	{
		unsigned char rows[3 * 3 * 3 * 2];

		for (int i = 0; i < 27; i++) {
			unsigned v = 1000u * (unsigned)(i / 3) + (unsigned)(i % 3);

			rows[2 * i] = (unsigned char)(v >> 8);
			rows[2 * i + 1] = (unsigned char)v;
		}
		buf = write_ref_png(3, 3, 16, PNG_COLOR_TYPE_RGB, rows, NULL, 0,
		    NULL, 0, PNG_INTERLACE_ADAM7, &n);
		assert_int_equal(vx_image_png_read_mem(&img, buf, n, &bits, &e), 0);
		assert_int_equal(bits, 16);
		assert_int_equal(img.nc, 3);
		for (int i = 0; i < 27; i++)
			assert_true(img.px[i] == (float)((1000.0 * (i / 3) + i % 3) /
			    65535.0));
		vx_image_free(&img);
		/* every truncation of a valid file is an error, never a crash */
		for (size_t k = 0; k < n; k++) {
			assert_int_equal(vx_image_png_read_mem(&img, buf, k, &bits,
			    &e), VX_EDATA);
			assert_null(img.px);
		}
		/* a flipped byte in the pixel data fails its CRC */
		buf[n - 20] ^= 0x40;
		assert_int_equal(vx_image_png_read_mem(&img, buf, n, &bits, &e),
		    VX_EDATA);
		free(buf);
	}
}

/* put_chunk: a PNG chunk with its CRC (zlib's crc32 is the PNG CRC). */
static size_t
put_chunk(unsigned char *p, const char *type, const unsigned char *d,
    uint32_t n)
{
	uint32_t crc;

	p[0] = (unsigned char)(n >> 24), p[1] = (unsigned char)(n >> 16);
	p[2] = (unsigned char)(n >> 8), p[3] = (unsigned char)n;
	memcpy(p + 4, type, 4);
	if (n > 0)
		memcpy(p + 8, d, n);
	crc = (uint32_t)crc32(crc32(0, p + 4, 4), d, n);
	p[8 + n] = (unsigned char)(crc >> 24), p[9 + n] = (unsigned char)(crc >> 16);
	p[10 + n] = (unsigned char)(crc >> 8), p[11 + n] = (unsigned char)crc;
	return 12 + n;
}

static void
png_read_bounds(void **state)
{
	/* IHDRs that claim far more pixels than the file could hold are
	 * refused before any pixel buffer is allocated */
	static const struct { uint32_t w, h; } t[] = {
		{ 16384, 16384 },   /* within the limits, but not in 60 bytes */
		{ 65536, 65536 },   /* beyond VX_IMAGE_MAX_PIXELS */
		{ 70000, 1 },       /* beyond VX_IMAGE_MAX_DIM */
		{ 0, 1 },
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		unsigned char buf[128], ihdr[13], idat[16];
		uLongf zn = sizeof idat;
		unsigned char raw[2] = { 0, 0 };
		size_t k = 8;
		vx_image img;
		vx_err e = { 0, "" };

		memcpy(buf, "\x89PNG\r\n\x1a\n", 8);
		ihdr[0] = (unsigned char)(t[i].w >> 24), ihdr[1] = (unsigned char)(t[i].w >> 16);
		ihdr[2] = (unsigned char)(t[i].w >> 8), ihdr[3] = (unsigned char)t[i].w;
		ihdr[4] = (unsigned char)(t[i].h >> 24), ihdr[5] = (unsigned char)(t[i].h >> 16);
		ihdr[6] = (unsigned char)(t[i].h >> 8), ihdr[7] = (unsigned char)t[i].h;
		ihdr[8] = 8, ihdr[9] = 6, ihdr[10] = 0, ihdr[11] = 0, ihdr[12] = 0;
		k += put_chunk(buf + k, "IHDR", ihdr, 13);
		assert_int_equal(compress(idat, &zn, raw, 2), Z_OK);
		k += put_chunk(buf + k, "IDAT", idat, (uint32_t)zn);
		k += put_chunk(buf + k, "IEND", NULL, 0);
		assert_int_equal(vx_image_png_read_mem(&img, buf, k, NULL, &e),
		    VX_EDATA);
		assert_null(img.px);
	}
	/* a chunk whose length word exceeds the file (found by fuzzing: libpng
	 * 1.6.39 allocated a tEXt buffer of that size before reading) */
	{
		unsigned char buf[64], ihdr[13] = { 0, 0, 0, 3, 0, 0, 0, 2, 8, 2,
		    0, 0, 0 };
		size_t k = 8;
		vx_image img;
		vx_err e = { 0, "" };

		memcpy(buf, "\x89PNG\r\n\x1a\n", 8);
		k += put_chunk(buf + k, "IHDR", ihdr, 13);
		memcpy(buf + k, "\x72\x63\x89\x15tEXtSoftware", 16);
		k += 16;
		assert_int_equal(vx_image_png_read_mem(&img, buf, k, NULL, &e),
		    VX_EDATA);
		assert_non_null(strstr(e.msg, "claims"));
	}
	/* not a PNG at all */
	{
		vx_image img;
		vx_err e = { 0, "" };

		assert_int_equal(vx_image_png_read_mem(&img, "PF\n1 1\n", 7, NULL,
		    &e), VX_EDATA);
	}
}

static void
sniff_formats(void **state)
{
	static const struct { const char *s; size_t n; int want; } t[] = {
		{ "\x89VXL\r\n\x1a\n", 8, VX_IMGFMT_STREAM },
		{ "\x89PNG\r\n\x1a\n", 8, VX_IMGFMT_PNG },
		{ "PF\n1", 4, VX_IMGFMT_PFM },
		{ "Pf 1", 4, VX_IMGFMT_PFM },
		{ "P6\n1", 4, VX_IMGFMT_UNKNOWN },
		{ "PF", 2, VX_IMGFMT_UNKNOWN },
		{ "#?RADIANCE\n", 11, VX_IMGFMT_HDR },
		{ "#?", 2, VX_IMGFMT_HDR },
		{ "#!", 2, VX_IMGFMT_UNKNOWN },
		{ "\x76\x2f\x31\x01\x02", 5, VX_IMGFMT_EXR },
		{ "\x76\x2f\x31", 3, VX_IMGFMT_UNKNOWN },
		{ "", 0, VX_IMGFMT_UNKNOWN },
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++)
		assert_int_equal(vx_image_sniff(t[i].s, t[i].n), t[i].want);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(alloc_limits),
		cmocka_unit_test(get_set_layout),
		cmocka_unit_test(chunk_roundtrip),
		cmocka_unit_test(chunk_malformed),
		cmocka_unit_test(stream_by_name),
		cmocka_unit_test(pfm_decode_known),
		cmocka_unit_test(pfm_malformed),
		cmocka_unit_test(pfm_roundtrip),
		cmocka_unit_test(png_write_read),
		cmocka_unit_test(png_gamma_chunks),
		cmocka_unit_test(png_write_errors),
		cmocka_unit_test(png_read_expand),
		cmocka_unit_test(png_read_bounds),
		cmocka_unit_test(sniff_formats),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
