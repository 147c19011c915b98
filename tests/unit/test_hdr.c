/* test_hdr.c: the HDR image readers: Radiance RGBE (flat, new and old
 * run-length scanlines, the 8 orientations, EXPOSURE and COLORCORR, the
 * malformed cases), the RGBE writer, OpenEXR through the library (files
 * built here byte by byte from the OpenEXR file layout), and reading any
 * of PFM, HDR and EXR by their first bytes. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "vx_image.h"
#include "vx_imageio.h"

/* ---- a byte buffer ---- */

typedef struct bytes {
	unsigned char b[1 << 16];
	size_t n;
} bytes;

static void
put(bytes *s, const void *p, size_t n)
{
	assert_true(s->n + n <= sizeof s->b);
	memcpy(s->b + s->n, p, n);
	s->n += n;
}

static void
puts_(bytes *s, const char *t)
{
	put(s, t, strlen(t));
}

static void
put4(bytes *s, int a, int b, int c, int d)
{
	unsigned char q[4] = { (unsigned char)a, (unsigned char)b,
	    (unsigned char)c, (unsigned char)d };

	put(s, q, 4);
}

static void
put_u32(bytes *s, uint32_t v)
{
	put4(s, (int)(v & 0xff), (int)(v >> 8 & 0xff), (int)(v >> 16 & 0xff),
	    (int)(v >> 24));
}

static void
put_u64(bytes *s, uint64_t v)
{
	put_u32(s, (uint32_t)v);
	put_u32(s, (uint32_t)(v >> 32));
}

static void
put_f32(bytes *s, float v)
{
	uint32_t u;

	memcpy(&u, &v, 4);
	put_u32(s, u);
}

/* rgbe_value: the oracle of the decoding rule, m * 2^(e - 136). */
static double
rgbe_value(int m, int e)
{
	return e == 0 ? 0 : ldexp(m, e - 136);
}

static const char HEAD[] = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n";

/* ---- Radiance: known bytes ---- */

static void
hdr_decode_flat(void **state)
{
	/* six flat pixels, each with its value by the rule above */
	static const int px[6][4] = {
		{ 128, 64, 32, 129 },   /* 1, 0.5, 0.25 */
		{ 255, 0, 1, 136 },     /* 255, 0, 1 */
		{ 1, 2, 3, 0 },         /* exponent 0: black */
		{ 0, 0, 0, 0 },
		{ 128, 128, 128, 1 },   /* 2^-128, subnormal as a float */
		{ 10, 20, 30, 140 },    /* 160, 320, 480 */
	};
	bytes s = { .n = 0 };
	vx_hdr_info in;
	vx_image img;
	vx_err e = { 0, "" };

	(void)state;
	puts_(&s, HEAD);
	puts_(&s, "-Y 2 +X 3\n");
	for (int k = 0; k < 6; k++)
		put4(&s, px[k][0], px[k][1], px[k][2], px[k][3]);
	assert_int_equal(vx_hdr_read_mem(&img, s.b, s.n, &in, &e), 0);
	assert_int_equal(img.w, 3);
	assert_int_equal(img.h, 2);
	assert_int_equal(img.nc, 3);
	assert_int_equal(in.nflat, 2);
	assert_int_equal(in.nrle, 0);
	assert_string_equal(in.orient, "-Y+X");
	assert_true(in.trailing == 0);
	for (int k = 0; k < 6; k++)
		for (int c = 0; c < 3; c++)
			assert_true(img.px[3 * k + c] ==
			    (float)rgbe_value(px[k][c], px[k][3]));
	assert_true(img.px[0] == 1.0f && img.px[12] == ldexpf(1, -128));
	vx_image_free(&img);
}

static void
hdr_decode_rle(void **state)
{
	/* row 0: new run-length (runs and literals in each plane); row 1:
	 * flat (its first bytes are no run-length start), as Radiance allows */
	static const int lit[8] = { 0, 1, 2, 3, 4, 5, 6, 7 };
	bytes s = { .n = 0 };
	vx_hdr_info in;
	vx_image img;
	vx_err e = { 0, "" };

	(void)state;
	puts_(&s, HEAD);
	puts_(&s, "-Y 2 +X 8\n");
	put4(&s, 2, 2, 0, 8);
	put4(&s, 128 + 8, 100, 8, 0);      /* R: a run of 8 of 100; G: 8 literals */
	for (int k = 1; k < 8; k++) {
		unsigned char q = (unsigned char)lit[k];

		put(&s, &q, 1);
	}
	put4(&s, 128 + 4, 5, 4, 1);        /* B: a run of 4 of 5, 4 literals */
	put4(&s, 2, 3, 4, 128 + 8);        /* E: a run of 8 of 130 */
	{
		unsigned char q = 130;

		put(&s, &q, 1);
	}
	for (int k = 0; k < 8; k++)        /* row 1 flat */
		put4(&s, 3 + k, 0, 0, 136);
	put4(&s, 9, 9, 9, 9);              /* 4 bytes after the image */
	assert_int_equal(vx_hdr_read_mem(&img, s.b, s.n, &in, &e), 0);
	assert_int_equal(in.nrle, 1);
	assert_int_equal(in.nflat, 1);
	assert_true(in.trailing == 4);
	for (int k = 0; k < 8; k++) {
		const float *p = vx_image_pixel(&img, k, 0), *q;

		assert_true(p[0] == (float)rgbe_value(100, 130));
		assert_true(p[1] == (float)rgbe_value(k, 130));
		assert_true(p[2] == (float)rgbe_value(k < 4 ? 5 : k - 3, 130));
		q = vx_image_pixel(&img, k, 1);
		assert_true(q[0] == 3 + k && q[1] == 0 && q[2] == 0);
	}
	vx_image_free(&img);
}

static void
hdr_decode_old_rle(void **state)
{
	/* width 4 (< 8: never the new encoding): A, run 3 -> A A A A;
	 * width 259: A, run 2, run 1 << 8 (two codes in a row) = 259 */
	bytes s = { .n = 0 };
	vx_hdr_info in;
	vx_image img;
	vx_err e = { 0, "" };

	(void)state;
	puts_(&s, HEAD);
	puts_(&s, "-Y 2 +X 4\n");
	put4(&s, 7, 8, 9, 136);
	put4(&s, 1, 1, 1, 3);
	put4(&s, 1, 2, 3, 136);            /* row 1: flat */
	put4(&s, 4, 5, 6, 136);
	put4(&s, 1, 1, 1, 1);              /* a run of 1: 4 5 6 again */
	put4(&s, 7, 7, 7, 136);
	assert_int_equal(vx_hdr_read_mem(&img, s.b, s.n, &in, &e), 0);
	assert_int_equal(in.nflat, 2);
	for (int k = 0; k < 4; k++)
		assert_true(vx_image_get(&img, k, 0, 0) == 7 &&
		    vx_image_get(&img, k, 0, 2) == 9);
	assert_true(vx_image_get(&img, 0, 1, 0) == 1 &&
	    vx_image_get(&img, 1, 1, 0) == 4 && vx_image_get(&img, 2, 1, 1) == 5 &&
	    vx_image_get(&img, 3, 1, 2) == 7);
	vx_image_free(&img);

	s.n = 0;
	puts_(&s, HEAD);
	puts_(&s, "-Y 1 +X 259\n");
	put4(&s, 3, 2, 1, 137);            /* not 2 2: the old encoding */
	put4(&s, 1, 1, 1, 2);
	put4(&s, 1, 1, 1, 1);
	assert_int_equal(vx_hdr_read_mem(&img, s.b, s.n, &in, &e), 0);
	assert_int_equal(img.w, 259);
	for (int k = 0; k < 259; k++)
		assert_true(vx_image_get(&img, k, 0, 0) == 6 &&
		    vx_image_get(&img, k, 0, 2) == 2);
	vx_image_free(&img);
}

static void
hdr_orientations(void **state)
{
	/* the image  1 2 3 / 4 5 6  (top row first), and the order in which
	 * each resolution line stores it (Radiance: +Y is up, +X right; the
	 * first axis is the scanlines') */
	static const struct { const char *res; int order[6]; } t[] = {
		{ "-Y 2 +X 3", { 1, 2, 3, 4, 5, 6 } },
		{ "-Y 2 -X 3", { 3, 2, 1, 6, 5, 4 } },
		{ "+Y 2 +X 3", { 4, 5, 6, 1, 2, 3 } },
		{ "+Y 2 -X 3", { 6, 5, 4, 3, 2, 1 } },
		{ "+X 3 -Y 2", { 1, 4, 2, 5, 3, 6 } },
		{ "+X 3 +Y 2", { 4, 1, 5, 2, 6, 3 } },
		{ "-X 3 -Y 2", { 3, 6, 2, 5, 1, 4 } },
		{ "-X 3 +Y 2", { 6, 3, 5, 2, 4, 1 } },
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		bytes s = { .n = 0 };
		vx_image img;
		vx_err e = { 0, "" };

		puts_(&s, HEAD);
		puts_(&s, t[i].res);
		puts_(&s, "\n");
		for (int k = 0; k < 6; k++)
			put4(&s, t[i].order[k], 0, 0, 136);
		assert_int_equal(vx_hdr_read_mem(&img, s.b, s.n, NULL, &e), 0);
		assert_int_equal(img.w, 3);
		assert_int_equal(img.h, 2);
		for (int k = 0; k < 6; k++)
			assert_true(img.px[3 * k] == k + 1);
		vx_image_free(&img);
	}
}

static void
hdr_exposure(void **state)
{
	/* the values are divided by the product of the EXPOSURE lines and of
	 * the COLORCORR lines (oracle: Radiance's header conventions) */
	bytes s = { .n = 0 };
	vx_hdr_info in;
	vx_image img;
	vx_err e = { 0, "" };

	(void)state;
	puts_(&s, "#?RGBE\r\n# a comment\nEXPOSURE= 2\nSOFTWARE=x y\n"
	    "EXPOSURE=4e0\r\nCOLORCORR=1 2 0.5\nFORMAT= 32-bit_rle_rgbe \n\n"
	    "-Y 1 +X 1\n");
	put4(&s, 64, 64, 64, 137);        /* 128 each */
	assert_int_equal(vx_hdr_read_mem(&img, s.b, s.n, &in, &e), 0);
	assert_true(in.exposure == 8);
	assert_true(in.colorcorr[1] == 2);
	assert_true(img.px[0] == 16 && img.px[1] == 8 && img.px[2] == 32);
	vx_image_free(&img);
}

static void
hdr_malformed(void **state)
{
	/* each input is refused with VX_EDATA and a message naming what is
	 * wrong (the phrase), and leaves the image empty */
	struct { const char *name, *head, *res; const char *data; size_t nd;
	    const char *phrase; } t[] = {
		{ "no magic", "RADIANCE\n\n", "-Y 1 +X 1\n", "\1\1\1\1", 4,
		    "not a Radiance file" },
		{ "header without its end", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe",
		    "", "", 0, "without the empty line" },
		{ "xyze", "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n", "-Y 1 +X 1\n",
		    "\1\1\1\1", 4, "XYZE" },
		{ "format word", "#?RADIANCE\nFORMAT=rgb\n\n", "-Y 1 +X 1\n",
		    "\1\1\1\1", 4, "FORMAT" },
		{ "exposure 0", "#?RADIANCE\nEXPOSURE=0\n\n", "-Y 1 +X 1\n",
		    "\1\1\1\1", 4, "EXPOSURE" },
		{ "exposure nan", "#?RADIANCE\nEXPOSURE=nan\n\n", "-Y 1 +X 1\n",
		    "\1\1\1\1", 4, "EXPOSURE" },
		{ "exposure overflow", "#?RADIANCE\nEXPOSURE=1e300\n"
		    "EXPOSURE=1e300\n\n", "-Y 1 +X 1\n", "\1\1\1\1", 4,
		    "infinite" },
		{ "colorcorr two", "#?RADIANCE\nCOLORCORR=1 2\n\n", "-Y 1 +X 1\n",
		    "\1\1\1\1", 4, "COLORCORR" },
		{ "same axis twice", HEAD, "-Y 1 +Y 1\n", "\1\1\1\1", 4,
		    "resolution line" },
		{ "resolution word", HEAD, "-Y one +X 1\n", "\1\1\1\1", 4,
		    "resolution line" },
		{ "no resolution newline", HEAD, "-Y 1 +X 1", "", 0,
		    "resolution line" },
		{ "width 0", HEAD, "-Y 1 +X 0\n", "", 0, "size" },
		{ "huge width", HEAD, "-Y 1 +X 70000\n", "\1\1\1\1", 4,
		    "beyond the limits" },
		{ "ten digits", HEAD, "-Y 1 +X 1000000000\n", "", 0,
		    "beyond the limits" },
		{ "beyond int32", HEAD, "-Y 1 +X 99999999999\n", "", 0,
		    "resolution line" },
		{ "hex count", HEAD, "-Y 1 +X 0x10\n", "", 0,
		    "resolution line" },
		{ "exposure hex", "#?RADIANCE\nEXPOSURE=0x1p1\n\n", "-Y 1 +X 1\n",
		    "\1\1\1\1", 4, "EXPOSURE" },
		{ "too many pixels", HEAD, "-Y 65536 +X 65536\n", "\1\1\1\1", 4,
		    "size" },
		{ "flat truncated", HEAD, "-Y 2 +X 2\n", "\5\5\5\5\6\6\6\6\7", 9,
		    "truncated" },
		{ "rle truncated", HEAD, "-Y 1 +X 8\n", "\x02\x02\x00\x08\x88\x01"
		    "\x88\x01\x88", 9, "truncated" },
		{ "rle start cut", HEAD, "-Y 1 +X 8\n", "\x02\x02", 2,
		    "truncated" },
		{ "rle run past the end", HEAD, "-Y 1 +X 8\n",
		    "\x02\x02\x00\x08\x89\x01", 6, "passes the scanline's end" },
		{ "rle literal past the end", HEAD, "-Y 1 +X 8\n",
		    "\x02\x02\x00\x08\x09\x01", 6, "passes the scanline's end" },
		{ "rle count 0", HEAD, "-Y 1 +X 8\n", "\x02\x02\x00\x08\x00", 5,
		    "count of 0" },
		{ "rle width lie", HEAD, "-Y 1 +X 8\n", "\x02\x02\x00\x09\x88\x01",
		    6, "gives 9 pixels" },
		{ "old run first", HEAD, "-Y 1 +X 4\n", "\1\1\1\3", 4,
		    "no pixel before" },
		{ "old run first (8 wide)", HEAD, "-Y 1 +X 8\n", "\1\1\1\7", 4,
		    "no pixel before" },
		{ "old run past the end", HEAD, "-Y 1 +X 4\n", "\5\5\5\5\1\1\1\4",
		    8, "passes the scanline's end" },
		{ "four old runs in a row", HEAD, "-Y 1 +X 4\n",
		    "\5\5\5\5\1\1\1\0\1\1\1\0\1\1\1\0\1\1\1\1", 20,
		    "three old run-length codes" },
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		bytes s = { .n = 0 };
		vx_image img;
		vx_err e = { 0, "" };
		int rc;

		puts_(&s, t[i].head);
		puts_(&s, t[i].res);
		put(&s, t[i].data, t[i].nd);
		rc = vx_hdr_read_mem(&img, s.b, s.n, NULL, &e);
		if (rc != VX_EDATA || strstr(e.msg, t[i].phrase) == NULL)
			fail_msg("%s: rc %d, message '%s' (want '%s')", t[i].name,
			    rc, e.msg, t[i].phrase);
		assert_null(img.px);
	}
}

/* ---- Radiance: the writer ---- */

/* write_mem: vx_hdr_write into memory. */
static unsigned char *
write_mem(const vx_image *img, int rle, size_t *n)
{
	char *p = NULL;
	FILE *f = open_memstream(&p, n);
	vx_err e = { 0, "" };

	assert_non_null(f);
	assert_int_equal(vx_hdr_write(img, f, rle, &e), 0);
	fclose(f);
	return (unsigned char *)p;
}

static void
hdr_write_values(void **state)
{
	/* oracle: the nearest RGBE value, worked out by hand */
	static const struct { float in[3]; float out[3]; } t[] = {
		{ { 1, 0.5f, 0.25f }, { 1, 0.5f, 0.25f } },       /* exact */
		{ { 255, 0, 1 }, { 255, 0, 1 } },
		{ { 255.6f, 0, 0 }, { 256, 0, 0 } },     /* carries: 128 * 2 */
		{ { 257, 0, 0 }, { 258, 0, 0 } },        /* 128.5 * 2: ties up */
		{ { 1, 1.0f / 256, 0 }, { 1, 1.0f / 128, 0 } },   /* 0.5 up */
		{ { 1, 1.0f / 512, 0 }, { 1, 0, 0 } },
		{ { -3, 2, -0.0f }, { 0, 2, 0 } },       /* negatives are 0 */
		{ { 3.0e38f, 0, 0 }, { 255 * 0x1p119f, 0, 0 } },  /* the largest */
		{ { 0x1p-128f, 0, 0 }, { 0x1p-128f, 0, 0 } },     /* e byte 1 */
		{ { 0x1p-140f, 0, 0 }, { 0, 0, 0 } },    /* below 2^-136 / 2 */
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_image img, back;
		vx_err e = { 0, "" };
		unsigned char *p;
		size_t n;

		assert_int_equal(vx_image_alloc(&img, 1, 1, 3, &e), 0);
		memcpy(img.px, t[i].in, sizeof t[i].in);
		p = write_mem(&img, 1, &n);
		assert_int_equal(vx_hdr_read_mem(&back, p, n, NULL, &e), 0);
		for (int c = 0; c < 3; c++)
			if (back.px[c] != t[i].out[c])
				fail_msg("case %zu channel %d: %g, want %g", i, c,
				    back.px[c], t[i].out[c]);
		free(p);
		vx_image_free(&img);
		vx_image_free(&back);
	}
}

static void
hdr_roundtrip(void **state)
{
	/* any value comes back within half a mantissa step of its pixel's
	 * largest channel (2^-9 of 2^ceil(log2 max)); what came back is
	 * written again bit for bit (RGBE values are fixed points), and the
	 * flat and run-length files decode to the same pixels */
	static const int widths[] = { 1, 7, 8, 9, 130, 300 };

	(void)state;
	for (size_t k = 0; k < sizeof widths / sizeof widths[0]; k++) {
		int w = widths[k], h = 3;
		vx_image img, a, b, c;
		vx_err e = { 0, "" };
		unsigned char *pr, *pf, *p2;
		size_t nr, nf, n2;
		uint32_t x = 12345u + (uint32_t)w;

		assert_int_equal(vx_image_alloc(&img, w, h, 3, &e), 0);
		for (size_t i = 0; i < vx_image_nvalue(&img); i++) {
			x = x * 1664525u + 1013904223u;
			/* runs of equal values where (i / 3) % 17 < 9 */
			img.px[i] = (i / 3) % 17 < 9 ? 2.5f :
			    ldexpf((float)(x >> 8) / (1 << 24), (int)(x % 40) - 20);
		}
		pr = write_mem(&img, 1, &nr);
		pf = write_mem(&img, 0, &nf);
		assert_int_equal(vx_hdr_read_mem(&a, pr, nr, NULL, &e), 0);
		assert_int_equal(vx_hdr_read_mem(&b, pf, nf, NULL, &e), 0);
		assert_memory_equal(a.px, b.px, vx_image_nvalue(&a) * 4);
		for (int y = 0; y < h; y++)
			for (int xx = 0; xx < w; xx++) {
				const float *p = vx_image_pixel(&img, xx, y);
				const float *q = vx_image_pixel(&a, xx, y);
				double m = fmax(p[0], fmax(p[1], p[2]));
				int ex;

				(void)frexp(m, &ex);
				for (int ch = 0; ch < 3; ch++)
					assert_true(fabs(p[ch] - q[ch]) <=
					    ldexp(1, ex - 9) * (1 + 1e-12));
			}
		p2 = write_mem(&a, 1, &n2);
		assert_true(n2 == nr);
		assert_memory_equal(p2, pr, nr);
		assert_int_equal(vx_hdr_read_mem(&c, p2, n2, NULL, &e), 0);
		assert_memory_equal(c.px, a.px, vx_image_nvalue(&a) * 4);
		free(pr);
		free(pf);
		free(p2);
		vx_image_free(&img);
		vx_image_free(&a);
		vx_image_free(&b);
		vx_image_free(&c);
	}
}

static void
hdr_write_errors(void **state)
{
	vx_image img;
	vx_err e = { 0, "" };
	FILE *f = tmpfile();

	(void)state;
	assert_non_null(f);
	assert_int_equal(vx_image_alloc(&img, 2, 1, 3, &e), 0);
	img.px[4] = NAN;
	assert_int_equal(vx_hdr_write(&img, f, 1, &e), VX_EDATA);
	assert_non_null(strstr(e.msg, "pixel (1, 0) is NaN"));
	img.px[4] = INFINITY;
	assert_int_equal(vx_hdr_write(&img, f, 1, &e), VX_EDATA);
	assert_non_null(strstr(e.msg, "infinite"));
	vx_image_free(&img);
	assert_int_equal(vx_image_alloc(&img, 2, 1, 4, &e), 0);
	assert_int_equal(vx_hdr_write(&img, f, 1, &e), VX_EUSAGE);
	vx_image_free(&img);
	fclose(f);
}

/* ---- OpenEXR: files built from the layout of the OpenEXR spec ---- */

enum { EXR_UINT = 0, EXR_HALF = 1, EXR_FLOAT = 2 };

typedef struct exrspec {
	const char *chans;       /* channel names, one letter each, sorted */
	int type;                /* EXR_HALF or EXR_FLOAT for all */
	int dw[4], dp[4];        /* data, display window: xmin ymin xmax ymax */
	int cut;                 /* drop this many bytes from the end */
	int xsamp;               /* x sampling of every channel (1) */
} exrspec;

/* exr_attr: name, type, size, value. */
static void
exr_attr(bytes *s, const char *name, const char *type, const void *v,
    size_t n)
{
	put(s, name, strlen(name) + 1);
	put(s, type, strlen(type) + 1);
	put_u32(s, (uint32_t)n);
	put(s, v, n);
}

/* half_of: the half-float bits of v (exact for the values used here). */
static uint16_t
half_of(float v)
{
	uint32_t u;
	int ex;

	memcpy(&u, &v, 4);
	if (v == 0)
		return 0;
	ex = (int)(u >> 23 & 0xff) - 127 + 15;
	return (uint16_t)((u >> 16 & 0x8000) | (uint32_t)ex << 10 |
	    (u >> 13 & 0x3ff));
}

/* exr_build: an uncompressed scanline file; pixel (x, y) of the channel
 * named ch holds value(ch, x, y). */
static void
exr_build(bytes *s, const exrspec *sp, float (*value)(char, int, int))
{
	int nc = (int)strlen(sp->chans), w = sp->dw[2] - sp->dw[0] + 1;
	int h = sp->dw[3] - sp->dw[1] + 1, sz = sp->type == EXR_HALF ? 2 : 4;
	bytes cl = { .n = 0 };
	size_t table, first;
	unsigned char z = 0;

	s->n = 0;
	put4(s, 0x76, 0x2f, 0x31, 0x01);
	put_u32(s, 2);
	for (int c = 0; c < nc; c++) {
		char name[2] = { sp->chans[c], 0 };

		put(&cl, name, 2);
		put_u32(&cl, (uint32_t)sp->type);
		put4(&cl, 0, 0, 0, 0);          /* pLinear, reserved */
		put_u32(&cl, (uint32_t)(sp->xsamp ? sp->xsamp : 1));
		put_u32(&cl, 1);
	}
	put(&cl, &z, 1);
	exr_attr(s, "channels", "chlist", cl.b, cl.n);
	exr_attr(s, "compression", "compression", &z, 1);
	{
		bytes b = { .n = 0 };

		for (int k = 0; k < 4; k++)
			put_u32(&b, (uint32_t)sp->dw[k]);
		exr_attr(s, "dataWindow", "box2i", b.b, 16);
		b.n = 0;
		for (int k = 0; k < 4; k++)
			put_u32(&b, (uint32_t)sp->dp[k]);
		exr_attr(s, "displayWindow", "box2i", b.b, 16);
		exr_attr(s, "lineOrder", "lineOrder", &z, 1);
		b.n = 0;
		put_f32(&b, 1);
		exr_attr(s, "pixelAspectRatio", "float", b.b, 4);
		b.n = 0;
		put_f32(&b, 0);
		put_f32(&b, 0);
		exr_attr(s, "screenWindowCenter", "v2f", b.b, 8);
		b.n = 0;
		put_f32(&b, 1);
		exr_attr(s, "screenWindowWidth", "float", b.b, 4);
	}
	put(s, &z, 1);
	table = s->n;
	first = table + 8 * (size_t)h;
	for (int y = 0; y < h; y++)
		put_u64(s, first + (size_t)y * (8 + (size_t)(nc * w * sz)));
	for (int y = 0; y < h; y++) {
		put_u32(s, (uint32_t)(sp->dw[1] + y));
		put_u32(s, (uint32_t)(nc * w * sz));
		for (int c = 0; c < nc; c++)
			for (int x = 0; x < w; x++) {
				float v = value(sp->chans[c], sp->dw[0] + x,
				    sp->dw[1] + y);

				if (sz == 4) {
					put_f32(s, v);
				} else {
					uint16_t hb = half_of(v);

					put(s, &hb, 2);
				}
			}
	}
	s->n -= (size_t)sp->cut;
}

/* exr_value: R = 100 + x + 0.5 y, G = 10 + y, B = 0.5 x, A = 7: exact
 * in half floats and in RGBE for the small x, y used */
static float
exr_value(char ch, int x, int y)
{
	return ch == 'R' ? 100.0f + (float)x + 0.5f * (float)y :
	    ch == 'G' ? 10.0f + (float)y : ch == 'B' ? 0.5f * (float)x : 7;
}

static float
exr_nan(char ch, int x, int y)
{
	return ch == 'R' && x == 1 && y == 0 ? NAN : exr_value(ch, x, y);
}

static void
exr_decode(void **state)
{
	/* float and half RGB, Y alone, a data window inside and overlapping
	 * the display window */
	static const exrspec t[] = {
		{ "BGR", EXR_FLOAT, { 0, 0, 3, 2 }, { 0, 0, 3, 2 }, 0, 0 },
		{ "BGR", EXR_HALF, { 0, 0, 3, 2 }, { 0, 0, 3, 2 }, 0, 0 },
		{ "ABGR", EXR_FLOAT, { 0, 0, 2, 1 }, { 0, 0, 2, 1 }, 0, 0 },
		{ "BGR", EXR_FLOAT, { 1, 1, 2, 1 }, { 0, 0, 3, 2 }, 0, 0 },
		{ "BGR", EXR_FLOAT, { -1, 1, 4, 3 }, { 0, 0, 2, 2 }, 0, 0 },
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		static bytes s;
		const exrspec *sp = &t[i];
		vx_image img;
		vx_err e = { 0, "" };

		exr_build(&s, sp, exr_value);
		if (vx_exr_read_mem(&img, s.b, s.n, &e) != 0)
			fail_msg("case %zu: %s", i, e.msg);
		assert_int_equal(img.w, sp->dp[2] - sp->dp[0] + 1);
		assert_int_equal(img.h, sp->dp[3] - sp->dp[1] + 1);
		for (int y = 0; y < img.h; y++)
			for (int x = 0; x < img.w; x++) {
				int fx = x + sp->dp[0], fy = y + sp->dp[1];
				int in = fx >= sp->dw[0] && fx <= sp->dw[2] &&
				    fy >= sp->dw[1] && fy <= sp->dw[3];
				const float *p = vx_image_pixel(&img, x, y);

				for (int c = 0; c < 3; c++) {
					float want = in ? exr_value("RGB"[c], fx,
					    fy) : 0;

					if (p[c] != want)
						fail_msg("case %zu (%d, %d) channel "
						    "%d: %g, want %g", i, x, y, c,
						    p[c], want);
				}
			}
		vx_image_free(&img);
	}
}

static float
exr_gray(char ch, int x, int y)
{
	(void)ch;
	return 1.5f + (float)(x + 4 * y);
}

static void
exr_luminance(void **state)
{
	static bytes s;
	exrspec sp = { "Y", EXR_FLOAT, { 0, 0, 3, 1 }, { 0, 0, 3, 1 }, 0, 0 };
	vx_image img;
	vx_err e = { 0, "" };

	(void)state;
	exr_build(&s, &sp, exr_gray);
	assert_int_equal(vx_exr_read_mem(&img, s.b, s.n, &e), 0);
	for (int y = 0; y < 2; y++)
		for (int x = 0; x < 4; x++)
			for (int c = 0; c < 3; c++)
				assert_true(vx_image_get(&img, x, y, c) ==
				    exr_gray('Y', x, y));
	vx_image_free(&img);
}

static void
exr_malformed(void **state)
{
	static const struct { exrspec sp; const char *phrase; } t[] = {
		{ { "BGR", EXR_FLOAT, { 0, 0, 3, 2 }, { 0, 0, 3, 2 }, 7, 0 },
		    "" },                               /* truncated data */
		{ { "BGR", EXR_FLOAT, { 0, 0, 3, 2 }, { 0, 0, 3, 2 }, 150, 0 },
		    "" },                               /* cut in the pixels */
		{ { "A", EXR_FLOAT, { 0, 0, 1, 1 }, { 0, 0, 1, 1 }, 0, 0 },
		    "no channel R" },
		{ { "BG", EXR_FLOAT, { 0, 0, 1, 1 }, { 0, 0, 1, 1 }, 0, 0 },
		    "no channel R" },
		{ { "BGR", EXR_FLOAT, { 0, 0, 1, 1 }, { 0, 0, 1, 1 }, 0, 2 },
		    "" },                               /* subsampled */
		{ { "BGR", EXR_FLOAT, { 0, 0, 0, 0 }, { 0, 0, 69999, 0 }, 0, 0 },
		    "beyond the limits" },                        /* a huge width */
		{ { "BGR", EXR_FLOAT, { 0, 0, 0, 0 }, { 0, 0, 65535, 65535 }, 0,
		    0 }, "beyond the limits" },                   /* too many pixels */
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		static bytes s;
		vx_image img;
		vx_err e = { 0, "" };
		int rc;

		exr_build(&s, &t[i].sp, exr_value);
		rc = vx_exr_read_mem(&img, s.b, s.n, &e);
		if (rc != VX_EDATA || strncmp(e.msg, "exr: ", 5) != 0 ||
		    strstr(e.msg, t[i].phrase) == NULL ||
		    strchr(e.msg, '\n') != NULL)
			fail_msg("case %zu: rc %d, '%s'", i, rc, e.msg);
		assert_null(img.px);
	}
	{   /* garbage after the magic; the magic alone */
		vx_image img;
		vx_err e = { 0, "" };

		assert_int_equal(vx_exr_read_mem(&img, "\x76\x2f\x31\x01\x02\0\0"
		    "\0garbage", 15, &e), VX_EDATA);
		assert_int_equal(vx_exr_read_mem(&img, "\x76\x2f\x31\x01", 4, &e),
		    VX_EDATA);
	}
}

/* ---- any of them ---- */

static void
read_linear_any(void **state)
{
	/* one image as PFM, RGBE (values exact in RGBE) and OpenEXR: the
	 * same pixels from each; a PNG is refused */
	static bytes exr;
	exrspec sp = { "BGR", EXR_FLOAT, { 0, 0, 3, 2 }, { 0, 0, 3, 2 }, 0, 0 };
	vx_image img, a;
	vx_err e = { 0, "" };
	char *pp = NULL;
	size_t pn;
	FILE *f;
	unsigned char *hp;
	size_t hn;
	int fmt;

	(void)state;
	exr_build(&exr, &sp, exr_value);
	assert_int_equal(vx_image_alloc(&img, 4, 3, 3, &e), 0);
	for (int y = 0; y < 3; y++)
		for (int x = 0; x < 4; x++)
			for (int c = 0; c < 3; c++)
				vx_image_set(&img, x, y, c, exr_value("RGB"[c], x,
				    y));
	f = open_memstream(&pp, &pn);
	assert_int_equal(vx_pfm_write(&img, f, &e), 0);
	fclose(f);
	hp = write_mem(&img, 0, &hn);
	assert_int_equal(vx_image_read_linear_mem(&a, pp, pn, &fmt, &e), 0);
	assert_int_equal(fmt, VX_IMGFMT_PFM);
	assert_memory_equal(a.px, img.px, 4 * 3 * 3 * 4);
	vx_image_free(&a);
	assert_int_equal(vx_image_read_linear_mem(&a, hp, hn, &fmt, &e), 0);
	assert_int_equal(fmt, VX_IMGFMT_HDR);
	assert_memory_equal(a.px, img.px, 4 * 3 * 3 * 4);
	vx_image_free(&a);
	assert_int_equal(vx_image_read_linear_mem(&a, exr.b, exr.n, &fmt, &e), 0);
	assert_int_equal(fmt, VX_IMGFMT_EXR);
	assert_memory_equal(a.px, img.px, 4 * 3 * 3 * 4);
	vx_image_free(&a);
	assert_int_equal(vx_image_read_linear_mem(&a, "\x89PNG\r\n\x1a\n", 8,
	    &fmt, &e), VX_EDATA);
	assert_non_null(strstr(e.msg, "PNG"));
	assert_int_equal(vx_image_read_linear_file(&a, "/nonexistent/x.hdr",
	    &fmt, &e), VX_ENOINPUT);
	assert_non_null(strstr(e.msg, "/nonexistent/x.hdr"));
	free(pp);
	free(hp);
	vx_image_free(&img);
	/* a NaN in an EXR is read as it is (the environment refuses it) */
	exr_build(&exr, &sp, exr_nan);
	assert_int_equal(vx_exr_read_mem(&a, exr.b, exr.n, &e), 0);
	assert_true(isnan(vx_image_get(&a, 1, 0, 0)));
	vx_image_free(&a);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(hdr_decode_flat),
		cmocka_unit_test(hdr_decode_rle),
		cmocka_unit_test(hdr_decode_old_rle),
		cmocka_unit_test(hdr_orientations),
		cmocka_unit_test(hdr_exposure),
		cmocka_unit_test(hdr_malformed),
		cmocka_unit_test(hdr_write_values),
		cmocka_unit_test(hdr_roundtrip),
		cmocka_unit_test(hdr_write_errors),
		cmocka_unit_test(exr_decode),
		cmocka_unit_test(exr_luminance),
		cmocka_unit_test(exr_malformed),
		cmocka_unit_test(read_linear_any),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
