/* test_export.c: the NRRD writer, read back by hand: header lines, the body
 * byte for byte (x fastest, little-endian, whatever the layout), gzip bodies
 * inflated with zlib, comments made harmless, write errors. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>
#include <zlib.h>

#include "vx_export.h"

#define NX 5
#define NY 4
#define NZ 3

/* value: the sample at (x, y, z) of the test volumes, in every type's range */
static double
value(vx_type t, int x, int y, int z)
{
	double v = x * 17 + y * 5 - z * 40;   /* -80 .. 83 */

	switch (t) {
	case VX_U8: return v + 100;
	case VX_U16: return (v + 100) * 300;
	case VX_I16: return v * 300;
	default: return v / 8;             /* exact in f32 */
	}
}

/* expected_body: the oracle, the samples written out one by one in x-fastest
 * order, little-endian, by shifting (not by memcpy of host words). */
static size_t
expected_body(vx_type t, unsigned char *out)
{
	size_t k = 0;

	for (int z = 0; z < NZ; z++)
		for (int y = 0; y < NY; y++)
			for (int x = 0; x < NX; x++) {
				double v = value(t, x, y, z);
				uint32_t u;
				float f;

				switch (t) {
				case VX_U8:
					out[k++] = (unsigned char)v;
					break;
				case VX_U16:
				case VX_I16:
					u = (uint16_t)(int32_t)v;
					out[k++] = (unsigned char)(u & 0xff);
					out[k++] = (unsigned char)(u >> 8);
					break;
				default:
					f = (float)v;
					memcpy(&u, &f, 4);
					for (int b = 0; b < 4; b++)
						out[k++] = (unsigned char)(u >> (8 * b));
				}
			}
	return k;
}

static void
make_grid(vx_grid *g, vx_type t, const char *layout)
{
	int64_t d[3] = { NX, NY, NZ };
	vx_err e = { 0, "" };

	assert_int_equal(vx_grid_alloc(g, d, t, layout, &e), 0);
	for (int z = 0; z < NZ; z++)
		for (int y = 0; y < NY; y++)
			for (int x = 0; x < NX; x++)
				vx_grid_set(g, x, y, z, value(t, x, y, z));
	g->spacing[0] = 0.5;
	g->spacing[1] = 1;
	g->spacing[2] = 0.1;
	g->origin[0] = -90;
	g->origin[1] = 1e-3;
	g->origin[2] = 2.25;
}

/* inflate_gzip: the body as a gzip member, inflated by zlib; returns the
 * decoded size (or (size_t)-1 on error). */
static size_t
inflate_gzip(const unsigned char *in, size_t n, unsigned char *out, size_t cap)
{
	z_stream zs;
	int zr;

	memset(&zs, 0, sizeof zs);
	if (inflateInit2(&zs, 15 + 16) != Z_OK)
		return (size_t)-1;
	zs.next_in = (Bytef *)(uintptr_t)in;
	zs.avail_in = (uInt)n;
	zs.next_out = out;
	zs.avail_out = (uInt)cap;
	zr = inflate(&zs, Z_FINISH);
	inflateEnd(&zs);
	if (zr != Z_STREAM_END || zs.avail_in != 0)
		return (size_t)-1;
	return cap - zs.avail_out;
}

/* Every type, linear and bricked, raw and gzip.  Oracle for the header: the
 * NRRD0004 field list written out here; for the body: expected_body. */
static void
header_and_body(void **state)
{
	static const vx_type types[] = { VX_U8, VX_U16, VX_I16, VX_F32 };
	static const char *tnames[] = { "uint8", "uint16", "int16", "float" };
	static const char *layouts[] = { "linear", "bricked 2x2x2",
	    "bricked 4x1x2 2x4x2" };

	(void)state;
	for (size_t ti = 0; ti < 4; ti++)
		for (size_t li = 0; li < 3; li++)
			for (int gz = 0; gz <= 1; gz++) {
				unsigned char want[NX * NY * NZ * 4];
				unsigned char got[NX * NY * NZ * 4 + 16];
				size_t wn = expected_body(types[ti], want), gn;
				char hdr[2048], *out = NULL, *body;
				size_t outn = 0;
				vx_err e = { 0, "" };
				vx_grid g;
				FILE *f;

				make_grid(&g, types[ti], layouts[li]);
				f = open_memstream(&out, &outn);
				assert_int_equal(vx_export_nrrd(&g, f, gz, &e), 0);
				fclose(f);
				snprintf(hdr, sizeof hdr,
				    "NRRD0004\n"
				    "# Complete NRRD file format specification at:\n"
				    "# http://teem.sourceforge.net/nrrd/format.html\n"
				    "content: density\n"
				    "type: %s\n"
				    "dimension: 3\n"
				    "space: 3D-right-handed\n"
				    "sizes: 5 4 3\n"
				    "space directions: (0.5,0,0) (0,1,0) "
				    "(0,0,0.10000000000000001)\n"
				    "kinds: domain domain domain\n"
				    "centerings: node node node\n"
				    "endian: little\n"
				    "encoding: %s\n"
				    "space origin: (-90,0.001,2.25)\n\n",
				    tnames[ti], gz ? "gzip" : "raw");
				assert_true(outn > strlen(hdr));
				if (memcmp(out, hdr, strlen(hdr)) != 0)
					fail_msg("header differs:\n%.*s", (int)strlen(hdr),
					    out);
				body = out + strlen(hdr);
				if (!gz) {
					assert_int_equal(outn - strlen(hdr), wn);
					assert_memory_equal(body, want, wn);
				} else {
					assert_true((unsigned char)body[0] == 0x1f &&
					    (unsigned char)body[1] == 0x8b);
					gn = inflate_gzip((unsigned char *)body,
					    outn - strlen(hdr), got, sizeof got);
					assert_int_equal(gn, wn);
					assert_memory_equal(got, want, wn);
				}
				free(out);
				vx_grid_free(&g);
			}
}

/* nrrd_text: the NRRD file vx_export_nrrd_opts writes for g (the caller
 * frees it) */
static char *
nrrd_text(const vx_grid *g, const vx_nrrd_opts *o)
{
	vx_err e = { 0, "" };
	char *out = NULL;
	size_t outn = 0;
	FILE *f = open_memstream(&out, &outn);

	assert_non_null(f);
	assert_int_equal(vx_export_nrrd_opts(g, f, o, &e), 0);
	fclose(f);
	return out;
}

/* Comments and the content line cannot break the header: control
 * characters become '?'. */
static void
comments(void **state)
{
	static const char *lines[] = { "vread 0.1.0 a\rb", "x\ty\x1b[31m" };
	vx_nrrd_opts o;
	vx_grid g;
	char *out;

	(void)state;
	make_grid(&g, VX_U8, NULL);
	snprintf(g.name, sizeof g.name, "a\tb");
	memset(&o, 0, sizeof o);
	o.comments = lines;
	o.ncomments = 2;
	out = nrrd_text(&g, &o);
	assert_non_null(strstr(out, "\n# vread 0.1.0 a?b\n# x?y?[31m\n"
	    "content: a?b\ntype: uint8\n"));
	free(out);
	vx_grid_free(&g);
}

/* Key/value pairs: after the fields, before the empty line, in order,
 * backslash and newline escaped as NRRD does, other control characters
 * '?'.  Oracle: the header text. */
static void
key_values(void **state)
{
	vx_nrrd_opts o;
	vx_err e = { 0, "" };
	vx_hdr h;
	vx_grid g;
	char *out;

	(void)state;
	make_grid(&g, VX_U8, NULL);
	vx_hdr_init(&h);
	assert_int_equal(vx_hdr_set_str(&h, "units", "HU", &e), 0);
	assert_int_equal(vx_hdr_set_str(&h, "x-note", "a\\b\tc := d", &e), 0);
	memset(&o, 0, sizeof o);
	o.keys = &h;
	out = nrrd_text(&g, &o);
	assert_non_null(strstr(out, ")\nunits:=HU\nx-note:=a\\\\b?c := d\n\n"));
	free(out);
	vx_hdr_free(&h);
	vx_grid_free(&g);
}

/* A full disk is an I/O error, not success. */
static void
write_error(void **state)
{
	vx_err e = { 0, "" };
	vx_grid g;
	FILE *f = fopen("/dev/full", "wb");

	(void)state;
	if (f == NULL)
		skip();
	make_grid(&g, VX_F32, NULL);
	assert_int_equal(vx_export_nrrd(&g, f, 0, &e), VX_EIO);
	assert_non_null(strstr(e.msg, "write"));
	fclose(f);
	vx_grid_free(&g);
}

/* A gzip body larger than the writer's buffers still inflates exactly. */
static void
gzip_large(void **state)
{
	int64_t d[3] = { 300, 200, 7 };
	size_t n = 300 * 200 * 7 * 4, hl, gn;
	unsigned char *got = malloc(n + 1);
	vx_err e = { 0, "" };
	char *out = NULL, *body;
	size_t outn = 0;
	uint32_t s = 1;
	vx_grid g;
	FILE *f;

	(void)state;
	assert_int_equal(vx_grid_alloc(&g, d, VX_F32, "bricked 8x8x8", &e), 0);
	for (int z = 0; z < 7; z++)
		for (int y = 0; y < 200; y++)
			for (int x = 0; x < 300; x++) {
				s = s * 1664525u + 1013904223u;   /* noise */
				vx_grid_set(&g, x, y, z, (double)(s >> 8));
			}
	f = open_memstream(&out, &outn);
	assert_int_equal(vx_export_nrrd(&g, f, 1, &e), 0);
	fclose(f);
	body = strstr(out, "\n\n") + 2;
	hl = (size_t)(body - out);
	gn = inflate_gzip((unsigned char *)body, outn - hl, got, n + 1);
	assert_int_equal(gn, n);
	s = 1;
	for (size_t i = 0; i < n / 4; i++) {
		uint32_t u = (uint32_t)got[4 * i] | (uint32_t)got[4 * i + 1] << 8 |
		    (uint32_t)got[4 * i + 2] << 16 | (uint32_t)got[4 * i + 3] << 24;
		float v;

		s = s * 1664525u + 1013904223u;
		memcpy(&v, &u, 4);
		if (v != (float)(s >> 8))
			fail_msg("sample %zu: %g", i, (double)v);
	}
	free(got);
	free(out);
	vx_grid_free(&g);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(header_and_body),
		cmocka_unit_test(comments),
		cmocka_unit_test(key_values),
		cmocka_unit_test(write_error),
		cmocka_unit_test(gzip_large),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
