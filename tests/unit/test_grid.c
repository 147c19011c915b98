/* test_grid.c: layouts (linear and bricked offset tables), sample access,
 * ranges, and the VOLM chunk round trip. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "vx_grid.h"

/* Every (x,y,z) maps to a distinct index below nsample: the layout is a
 * bijection onto its range, for awkward dims that do not divide the bricks. */
static void
layouts_injective(void **state)
{
	static const struct { int64_t d[3]; const char *spec; } t[] = {
		{ { 1, 1, 1 }, "linear" },
		{ { 7, 5, 3 }, "linear" },
		{ { 7, 5, 3 }, "bricked 4x4x4" },
		{ { 17, 9, 33 }, "bricked 4x4x4 4x4x4" },
		{ { 16, 16, 16 }, "bricked 4x4x2 8x8x8" },
		{ { 5, 40, 3 }, "bricked 1x1x1 2x2x2 2x2x2" },
		{ { 3, 3, 3 }, "bricked 16x16x16" },
	};
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_layout lay;
		vx_err e = { 0, "" };
		size_t n;
		unsigned char *seen;
		int64_t x, y, z;

		assert_int_equal(vx_layout_parse(&lay, t[i].d, t[i].spec, &e), 0);
		n = vx_layout_nsample(&lay);
		seen = calloc(n, 1);
		for (z = 0; z < t[i].d[2]; z++)
			for (y = 0; y < t[i].d[1]; y++)
				for (x = 0; x < t[i].d[0]; x++) {
					int64_t k = lay.off[0][x] + lay.off[1][y] +
					    lay.off[2][z];
					assert_true(k >= 0 && (size_t)k < n);
					assert_int_equal(seen[k], 0);
					seen[k] = 1;
				}
		/* the guard entry repeats the edge */
		for (int a = 0; a < 3; a++)
			assert_int_equal(lay.off[a][t[i].d[a]],
			    lay.off[a][t[i].d[a] - 1]);
		char s[128];
		vx_layout_string(&lay, s, sizeof s);
		assert_string_equal(s, t[i].spec);
		free(seen);
		vx_layout_free(&lay);
	}
}

static void
bricked_inner_contiguous(void **state)
{
	/* Within one 4x4x4 brick of a u8 volume the 64 samples are contiguous
	 * (one cache line), x fastest. */
	int64_t d[3] = { 32, 32, 32 };
	vx_layout lay;
	vx_err e = { 0, "" };

	(void)state;
	assert_int_equal(vx_layout_parse(&lay, d, "bricked 4x4x4 4x4x4", &e), 0);
	int64_t base = lay.off[0][4] + lay.off[1][8] + lay.off[2][12];
	for (int z = 0; z < 4; z++)
		for (int y = 0; y < 4; y++)
			for (int x = 0; x < 4; x++)
				assert_int_equal(lay.off[0][4 + x] + lay.off[1][8 + y] +
				    lay.off[2][12 + z], base + x + 4 * y + 16 * z);
	vx_layout_free(&lay);
}

/* The worked examples of formats/stream.md, section 9.4; oracle: the
 * offset formula evaluated by hand there. */
static void
layout_worked_examples(void **state)
{
	static const int64_t fx[8] = { 0, 1, 8, 9, 32, 33, 40, 41 };
	static const int64_t fy[4] = { 0, 2, 64, 66 };
	static const int64_t fz[4] = { 0, 4, 16, 20 };
	int64_t d1[3] = { 5, 3, 2 }, d2[3] = { 8, 4, 4 };
	vx_layout lay;
	vx_err e = { 0, "" };
	int i;

	(void)state;
	assert_int_equal(vx_layout_parse(&lay, d1, "bricked 2x2x2", &e), 0);
	assert_true(lay.pdims[0] == 6 && lay.pdims[1] == 4 && lay.pdims[2] == 2);
	assert_int_equal(vx_layout_nsample(&lay), 48);
	assert_int_equal(lay.off[0][3] + lay.off[1][1] + lay.off[2][1], 15);
	assert_int_equal(lay.off[0][4] + lay.off[1][2] + lay.off[2][1], 44);
	vx_layout_free(&lay);
	assert_int_equal(vx_layout_parse(&lay, d2, "bricked 2x2x2 2x1x2", &e), 0);
	assert_true(lay.pdims[0] == 8 && lay.pdims[1] == 4 && lay.pdims[2] == 4);
	for (i = 0; i < 8; i++)
		assert_int_equal(lay.off[0][i], fx[i]);
	for (i = 0; i < 4; i++) {
		assert_int_equal(lay.off[1][i], fy[i]);
		assert_int_equal(lay.off[2][i], fz[i]);
	}
	vx_layout_free(&lay);
}

static void
bad_layouts(void **state)
{
	static const struct { int64_t d[3]; const char *spec; } t[] = {
		{ { 0, 5, 5 }, "linear" },
		{ { -3, 5, 5 }, "linear" },
		{ { 5, 5, 5 }, "bricked 3x4x4" },
		{ { 5, 5, 5 }, "bricked" },
		{ { 5, 5, 5 }, "bricked 4x4" },
		{ { 5, 5, 5 }, "tiled" },
		{ { (int64_t)1 << 20, (int64_t)1 << 20, 1 << 10 }, "linear" },
		{ { (int64_t)1 << 40, 1, 1 }, "linear" },
		{ { 5, 5, 5 }, "bricked 1x1x1 1x1x1 1x1x1 1x1x1 1x1x1" },
		/* the grammar is exact: one space before each level, digits */
		{ { 5, 5, 5 }, "bricked 4x4x4 " },
		{ { 5, 5, 5 }, "bricked  4x4x4" },
		{ { 5, 5, 5 }, "bricked 4x 4x4" },
		{ { 5, 5, 5 }, "bricked +4x4x4" },
		{ { 5, 5, 5 }, "bricked 4x4x4x4" },
		{ { 5, 5, 5 }, "bricked 4X4X4" },
		{ { 5, 5, 5 }, "bricked 10244x4x4" },
		{ { 5, 5, 5 }, "bricked 2048x4x4" },
		{ { 5, 5, 5 }, "bricked\t4x4x4" },
		{ { 5, 5, 5 }, "linear " },
	};
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_layout lay;
		vx_err e = { 0, "" };

		if (vx_layout_parse(&lay, t[i].d, t[i].spec, &e) != VX_EDATA)
			fail_msg("case %zu (%s) accepted", i, t[i].spec);
	}
}

static void
chunk_roundtrip(void **state)
{
	static const vx_type types[] = { VX_U8, VX_U16, VX_I16, VX_F32 };
	static const char *specs[] = { "linear", "bricked 2x2x2 2x2x2" };
	int64_t d[3] = { 5, 6, 7 };

	(void)state;
	for (size_t ti = 0; ti < 4; ti++)
		for (size_t si = 0; si < 2; si++)
			for (int z = 0; z <= 6; z += 6) {
				vx_grid g, h;
				vx_chunk c;
				vx_err e = { 0, "" };
				int64_t x, y, k;

				assert_int_equal(vx_grid_alloc(&g, d, types[ti],
				    specs[si], &e), 0);
				for (k = 0; k < 7; k++)
					for (y = 0; y < 6; y++)
						for (x = 0; x < 5; x++)
							vx_grid_set(&g, x, y, k,
							    (double)(x + 3 * y + 11 * k));
				g.spacing[2] = 2.5;
				vx_grid_range(&g);
				assert_true(g.vmin == 0 && g.vmax == 4 + 15 + 66);
				assert_int_equal(vx_grid_to_chunk(&g, z, &c, &e), 0);
				assert_int_equal(vx_grid_from_chunk(&h, &c, &e), 0);
				assert_int_equal(h.type, g.type);
				assert_true(h.spacing[2] == 2.5);
				for (k = 0; k < 7; k++)
					for (y = 0; y < 6; y++)
						for (x = 0; x < 5; x++)
							assert_true(vx_grid_get(&h, x, y, k) ==
							    (double)(x + 3 * y + 11 * k));
				float cell[8];
				vx_grid_cell(&h, 1, 2, 3, cell);
				for (int i = 0; i < 8; i++)
					assert_true(cell[i] == (float)((1 + (i & 1)) +
					    3 * (2 + ((i >> 1) & 1)) + 11 * (3 + (i >> 2))));
				vx_chunk_free(&c);
				vx_grid_free(&g);
				vx_grid_free(&h);
			}
}

/* make_volm: a VOLM payload from header text and a raw body. */
static void
make_volm(vx_chunk *c, const char *hdr, const void *body, size_t n)
{
	size_t hl = strlen(hdr);

	memset(c, 0, sizeof *c);
	memcpy(c->type, "VOLM", 5);
	c->len = hl + n;
	c->data = malloc(c->len + 1);
	memcpy(c->data, hdr, hl);
	if (n > 0)
		memcpy(c->data + hl, body, n);
}

/* VOLM headers a reader must refuse, each with its message; the first case
 * is the valid baseline.  Oracle: formats/stream.md, "VOLM". */
static void
volm_errors(void **state)
{
	static const struct { const char *hdr; size_t n; const char *msg; } t[] = {
		{ "dims: 2 2 2\ntype: u8\n\n", 8, NULL },
		{ "dims: 2 2 2\ntype: u8\nname: \n\n", 8, "name must" },
		{ "dims: 2 2 2\ntype: u8\nname: "
		  "0123456789012345678901234567890123456789012345678901234567890123"
		  "\n\n", 8, "name must" },
		{ "dims: 2 2 2\ntype: u8\nrange: 5 1\n\n", 8, "range must" },
		{ "dims: 2 2 2\ntype: u8\nrange: nan 1\n\n", 8, "range" },
		{ "dims: 2 2 2\ntype: u8\nspacing: 0x1p0 1 1\n\n", 8, "spacing" },
		{ "dims: 2 2 2\ntype: u8\nspacing: 1 0 1\n\n", 8, "spacing" },
		{ "dims: 2 2 2\ntype: u8\n\n", 7, "body has 7 bytes" },
		{ "dims: 2 2 2\ntype: u8\n\n", 9, "body has 9 bytes" },
		{ "dims: 2 2 2\ntype: f64\n\n", 8, "unknown type" },
		{ "dims: 2 2\ntype: u8\n\n", 8, "dims" },
		{ "dims: 2 2 2\ntype: u8\nlayout: bricked 4x4x4\n\n", 8,
		  "body has 8 bytes, header implies 64" },
		{ "dims: 1024 1024 1024\ntype: f32\nencoding: zlib\n\n", 8,
		  "cannot hold" },
		{ "dims: 2 2 2\ntype: u8\nencoding: lz4\n\n", 8,
		  "unknown encoding" },
	};
	static const unsigned char body[16] = { 1, 2, 3, 4, 5, 6, 7, 8 };
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_chunk c;
		vx_grid g;
		vx_err e = { 0, "" };
		int rc;

		make_volm(&c, t[i].hdr, body, t[i].n);
		rc = vx_grid_from_chunk(&g, &c, &e);
		if (t[i].msg == NULL) {
			if (rc != 0)
				fail_msg("case %zu: %s", i, e.msg);
			assert_true(g.vmin == 1 && g.vmax == 8);
			assert_string_equal(g.name, "density");
		} else if (rc != VX_EDATA || strstr(e.msg, t[i].msg) == NULL ||
		    strncmp(e.msg, "volume: ", 8) != 0)
			fail_msg("case %zu: got %d '%s', want '%s'", i, rc, e.msg,
			    t[i].msg);
		vx_grid_free(&g);
		vx_chunk_free(&c);
	}
}

/* The example stream of formats/stream.md, section 1, byte for byte; oracle:
 * the hex dump there (CRCs from python3's zlib.crc32). */
static void
spec_example_bytes(void **state)
{
	/* 107 bytes of keys and the empty line, then the writer's pad line
	 * ("pad:" and 15 spaces, 21 bytes) puts the body at 128 = 8 x 16 */
	static const char hdr[] = "name: density\ndims: 2 2 1\ntype: u8\n"
	    "spacing: 1 1 2.5\norigin: 0 0 0\nlayout: linear\nrange: 1 4\n"
	    "encoding: raw\npad:                \n\n";
	unsigned char want[210], *w = want;
	int64_t d[3] = { 2, 2, 1 };
	vx_grid g;
	vx_stream s;
	vx_chunk c;
	vx_err e = { 0, "" };
	char *out = NULL;
	size_t outn = 0;
	FILE *f;

	(void)state;
	memcpy(w, "\x89VXL\r\n\x1a\nhist\x16\0\0\0\0\0\0\0", 20);
	w += 20;
	memcpy(w, "vread 0.1.0 --synth x\n\x10\xc2\xe1\xf1", 26);
	w += 26;
	memcpy(w, "VOLM\x84\0\0\0\0\0\0\0", 12);
	w += 12;
	assert_int_equal(strlen(hdr), 128);
	memcpy(w, hdr, 128);
	w += 128;
	memcpy(w, "\x01\x02\x03\x04\x9c\x28\x4f\x2d", 8);
	w += 8;
	memcpy(w, "VEND\0\0\0\0\0\0\0\0\x4b\x27\x38\xa6", 16);
	w += 16;
	assert_int_equal(w - want, 210);

	assert_int_equal(vx_grid_alloc(&g, d, VX_U8, NULL, &e), 0);
	vx_grid_set(&g, 0, 0, 0, 1);
	vx_grid_set(&g, 1, 0, 0, 2);
	vx_grid_set(&g, 0, 1, 0, 3);
	vx_grid_set(&g, 1, 1, 0, 4);
	g.spacing[2] = 2.5;
	vx_grid_range(&g);
	vx_stream_init(&s);
	assert_int_equal(vx_grid_to_chunk(&g, 0, &c, &e), 0);
	assert_int_equal(vx_stream_append(&s, &c, &e), 0);
	assert_int_equal(vx_stream_history_add(&s, "vread 0.1.0 --synth x", &e), 0);
	f = open_memstream(&out, &outn);
	assert_int_equal(vx_stream_write(&s, f, &e), 0);
	fclose(f);
	assert_int_equal(outn, sizeof want);
	assert_memory_equal(out, want, sizeof want);
	free(out);
	vx_stream_free(&s);
	vx_grid_free(&g);
}

static void
range_ignores_nonfinite(void **state)
{
	int64_t d[3] = { 2, 2, 2 };
	vx_grid g;
	vx_err e = { 0, "" };

	(void)state;
	assert_int_equal(vx_grid_alloc(&g, d, VX_F32, NULL, &e), 0);
	vx_grid_set(&g, 0, 0, 0, NAN);
	vx_grid_set(&g, 1, 0, 0, INFINITY);
	vx_grid_set(&g, 0, 1, 0, -3);
	vx_grid_set(&g, 1, 1, 1, 7);
	vx_grid_range(&g);
	assert_true(g.has_range && g.vmin == -3 && g.vmax == 7);
	vx_grid_free(&g);
}

static void
relayout_identical(void **state)
{
	int64_t d[3] = { 9, 10, 11 };
	vx_grid g, b;
	vx_err e = { 0, "" };

	(void)state;
	assert_int_equal(vx_grid_alloc(&g, d, VX_I16, NULL, &e), 0);
	for (int64_t z = 0; z < 11; z++)
		for (int64_t y = 0; y < 10; y++)
			for (int64_t x = 0; x < 9; x++)
				vx_grid_set(&g, x, y, z, (double)((x * 31 + y * 17 + z * 5) % 200 - 100));
	assert_int_equal(vx_grid_relayout(&b, &g, "bricked 4x4x2 2x2x4", &e), 0);
	for (int64_t z = 0; z + 1 < 11; z++)
		for (int64_t y = 0; y + 1 < 10; y++)
			for (int64_t x = 0; x + 1 < 9; x++) {
				float c1[8], c2[8];
				vx_grid_cell(&g, x, y, z, c1);
				vx_grid_cell(&b, x, y, z, c2);
				assert_memory_equal(c1, c2, sizeof c1);
			}
	vx_grid_free(&g);
	vx_grid_free(&b);
}

/* Default bricks: the inner brick is one 64-byte cache line of samples, the
 * outer one a 4 KiB page (Parker §3.1), for every sample type. */
static void
default_bricks(void **state)
{
	static const vx_type t[] = { VX_U8, VX_U16, VX_I16, VX_F32 };
	int b[2][3];

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		size_t ts = vx_type_size(t[i]);

		assert_int_equal(vx_layout_default_bricks(t[i], b), 2);
		assert_int_equal((size_t)(b[0][0] * b[0][1] * b[0][2]) * ts, 64);
		assert_int_equal((size_t)(b[0][0] * b[0][1] * b[0][2] * b[1][0] *
		    b[1][1] * b[1][2]) * ts, 4096);
	}
	assert_int_equal(vx_layout_default_bricks(VX_TYPE_UNKNOWN, b), 0);
}

/* vx_grid_to_chunk_extra: keys of extra that the writer does not write
 * itself are added with their values verbatim; extra's known keys (a stale
 * layout, range or encoding) never override the grid's.  Oracle: the
 * header as text, compared line by line. */
static void
chunk_extra_keys(void **state)
{
	static const char *const in[][2] = {
		{ "layout", "linear" }, { "units", "HU" }, { "range", "7 8" },
		{ "encoding", "zlib" }, { "x-note", " a\tb " }, { "name", "old" },
		{ "pad", "          " },
	};
	/* the input's pad line is not copied: the writer makes its own,
	 * which starts the body at a multiple of 16 */
	static const char want[] =
	    "name: density\ndims: 2 1 1\ntype: u8\nspacing: 1 1 1\n"
	    "origin: 0 0 0\nlayout: bricked 2x2x2\nrange: 0 5\nunits: HU\n"
	    "x-note:  a\tb \nencoding: raw\npad:   \n\n";
	int64_t d[3] = { 2, 1, 1 };
	vx_err e = { 0, "" };
	vx_grid g;
	vx_chunk c;
	vx_hdr h;
	size_t i;

	(void)state;
	vx_hdr_init(&h);
	for (i = 0; i < sizeof in / sizeof in[0]; i++)
		assert_int_equal(vx_hdr_set_str(&h, in[i][0], in[i][1], &e), 0);
	assert_int_equal(vx_grid_alloc(&g, d, VX_U8, "bricked 2x2x2", &e), 0);
	vx_grid_set(&g, 1, 0, 0, 5);
	vx_grid_range(&g);
	assert_int_equal(vx_grid_to_chunk_extra(&g, 0, &h, &c, &e), 0);
	assert_true(c.len == strlen(want) + 8);
	assert_int_equal(strlen(want) % VX_BODY_ALIGN, 0);
	assert_memory_equal(c.data, want, strlen(want));
	vx_chunk_free(&c);
	/* NULL: the same as vx_grid_to_chunk */
	assert_int_equal(vx_grid_to_chunk_extra(&g, 0, NULL, &c, &e), 0);
	assert_true(memmem(c.data, c.len, "units", 5) == NULL);
	vx_chunk_free(&c);
	vx_grid_free(&g);
	vx_hdr_free(&h);
}

/* vx_grid_view_chunk: a raw body the writer made is used in place (its
 * offset is a multiple of VX_BODY_ALIGN), for every type and layout, and
 * gives the samples vx_grid_from_chunk copies; a zlib body and a raw body
 * the hand-made header leaves misaligned for its type are copied, with the
 * same samples.  Oracle: vx_grid_from_chunk's grid, sample by sample. */
static void
view_in_place(void **state)
{
	static const vx_type types[] = { VX_U8, VX_U16, VX_I16, VX_F32 };
	static const char *const lays[] = { "linear", "bricked 2x2x2" };
	int64_t d[3] = { 5, 3, 4 };
	vx_err e = { 0, "" };

	(void)state;
	for (size_t ti = 0; ti < 4; ti++)
		for (size_t li = 0; li < 2; li++)
			for (int z = 0; z < 2; z++) {
				vx_grid g, gc, gv;
				vx_chunk c;
				const unsigned char *p;

				assert_int_equal(vx_grid_alloc(&g, d, types[ti],
				    lays[li], &e), 0);
				for (int k = 0; k < 4; k++)
					for (int j = 0; j < 3; j++)
						for (int i = 0; i < 5; i++)
							vx_grid_set(&g, i, j, k,
							    (i * 7 + j * 3 + k * 11) % 23);
				vx_grid_range(&g);
				assert_int_equal(vx_grid_to_chunk(&g, z ? 6 : 0,
				    &c, &e), 0);
				assert_int_equal(vx_grid_from_chunk(&gc, &c, &e), 0);
				assert_int_equal(vx_grid_view_chunk(&gv, &c, &e), 0);
				p = gv.data;
				if (z == 0) {
					assert_int_equal(gv.borrowed, 1);
					assert_true(p > c.data && p < c.data + c.len);
					assert_int_equal((p - c.data) % VX_BODY_ALIGN,
					    0);
				} else
					assert_int_equal(gv.borrowed, 0);
				assert_int_equal(gc.borrowed, 0);
				assert_int_equal(gv.nsample, gc.nsample);
				assert_memory_equal(gv.data, gc.data, gv.nsample *
				    vx_type_size(gv.type));
				assert_true(gv.vmin == gc.vmin && gv.vmax == gc.vmax);
				vx_grid_free(&gv);   /* leaves c's payload alone */
				{
					/* from a stream: a copy always, a view
					 * of a raw body */
					vx_stream st;
					vx_grid gs;
					vx_chunk cc = c;
					long ix;

					cc.data = malloc(c.len);
					assert_non_null(cc.data);
					memcpy(cc.data, c.data, c.len);
					vx_stream_init(&st);
					assert_int_equal(vx_stream_append(&st, &cc,
					    &e), 0);
					assert_int_equal(vx_grid_from_stream(&gs, &st,
					    "density", &ix, &e), 0);
					assert_int_equal(gs.borrowed, 0);
					assert_memory_equal(gs.data, gc.data,
					    gs.nsample * vx_type_size(gs.type));
					vx_grid_free(&gs);
					assert_int_equal(vx_grid_view_stream(&gs, &st,
					    NULL, &ix, &e), 0);
					assert_int_equal(gs.borrowed, z == 0);
					assert_memory_equal(gs.data, gc.data,
					    gs.nsample * vx_type_size(gs.type));
					vx_grid_free(&gs);
					vx_stream_free(&st);
				}
				assert_int_equal(vx_grid_view_chunk(&gv, &c, &e), 0);
				assert_memory_equal(gv.data, gc.data, gv.nsample *
				    vx_type_size(gv.type));
				vx_grid_free(&gv);
				vx_grid_free(&gc);
				vx_grid_free(&g);
				vx_chunk_free(&c);
			}
	/* a header of odd length (no pad line: not the reference writer's)
	 * puts the i16 body at an odd address: copied */
	{
		static const char hdr[] = "name: v\ndims: 2 1 1\ntype: i16\n"
		    "range: -3 5\nencoding: raw\n\n";
		size_t hl = strlen(hdr);
		vx_chunk c;
		vx_grid gv;

		assert_int_equal(hl % 2, 1);
		memset(&c, 0, sizeof c);
		memcpy(c.type, "VOLM", 5);
		c.len = hl + 4;
		c.data = malloc(c.len);
		assert_non_null(c.data);
		memcpy(c.data, hdr, hl);
		memcpy(c.data + hl, "\xfd\xff\x05\x00", 4);
		assert_int_equal(vx_grid_view_chunk(&gv, &c, &e), 0);
		assert_int_equal(gv.borrowed, 0);
		assert_true(vx_grid_get(&gv, 0, 0, 0) == -3);
		assert_true(vx_grid_get(&gv, 1, 0, 0) == 5);
		vx_grid_free(&gv);
		vx_chunk_free(&c);
	}
}

/* vx_grid_to_chunk_take: the chunk vx_grid_to_chunk_extra makes, byte for
 * byte (oracle), from the grid's own memory, for every type, both layouts,
 * raw and zlib, with extra keys; the grid is consumed. */
static void
to_chunk_take_same(void **state)
{
	static const vx_type types[] = { VX_U8, VX_U16, VX_I16, VX_F32 };
	static const char *const lays[] = { "linear", "bricked 2x2x2" };
	int64_t d[3] = { 7, 3, 2 };
	vx_err e = { 0, "" };
	vx_hdr x;

	(void)state;
	vx_hdr_init(&x);
	assert_int_equal(vx_hdr_set_str(&x, "units", "HU", &e), 0);
	assert_int_equal(vx_hdr_set_str(&x, "pad", "   ", &e), 0);
	for (size_t ti = 0; ti < 4; ti++)
		for (size_t li = 0; li < 2; li++)
			for (int z = 0; z < 2; z++)
				for (int k = 0; k < 2; k++) {
					vx_grid g;
					vx_chunk c1, c2;

					assert_int_equal(vx_grid_alloc(&g, d,
					    types[ti], lays[li], &e), 0);
					for (int i = 0; i < 7; i++)
						vx_grid_set(&g, i, i % 3, i % 2,
						    i * 5 - 3);
					vx_grid_range(&g);
					assert_int_equal(vx_grid_to_chunk_extra(&g,
					    z ? 6 : 0, k ? &x : NULL, &c1, &e), 0);
					assert_int_equal(vx_grid_to_chunk_take(&g,
					    z ? 6 : 0, k ? &x : NULL, &c2, &e), 0);
					assert_null(g.data);
					assert_int_equal(c2.len, c1.len);
					assert_memory_equal(c2.data, c1.data, c1.len);
					vx_chunk_free(&c1);
					vx_chunk_free(&c2);
				}
	vx_hdr_free(&x);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(layouts_injective),
		cmocka_unit_test(bricked_inner_contiguous),
		cmocka_unit_test(layout_worked_examples),
		cmocka_unit_test(bad_layouts),
		cmocka_unit_test(chunk_roundtrip),
		cmocka_unit_test(volm_errors),
		cmocka_unit_test(spec_example_bytes),
		cmocka_unit_test(range_ignores_nonfinite),
		cmocka_unit_test(relayout_identical),
		cmocka_unit_test(default_bricks),
		cmocka_unit_test(chunk_extra_keys),
		cmocka_unit_test(view_in_place),
		cmocka_unit_test(to_chunk_take_same),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
