/* test_import.c: the importers, table-driven.  Each case builds its input
 * in C (headers written field by field, samples from a formula, gzip by
 * zlib), writes it into a temporary directory when files are involved,
 * imports it and checks dims, type, spacing, origin and every sample
 * against the formula (the oracle), or the error code and message. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <unistd.h>
#include <sys/stat.h>
#include <zlib.h>
#include <cmocka.h>

#include "helper_tmp.h"

#include "vx_import.h"

/* ---- building inputs ---- */

typedef struct buf { unsigned char *p; size_t n; } buf;

static void
put(buf *b, const void *q, size_t n)
{
	b->p = realloc(b->p, b->n + n + 1);
	assert_non_null(b->p);
	memcpy(b->p + b->n, q, n);
	b->n += n;
}

static void __attribute__((format(printf, 2, 3)))
putf(buf *b, const char *fmt, ...)
{
	char s[4096];
	va_list ap;
	int n;

	va_start(ap, fmt);
	n = vsnprintf(s, sizeof s, fmt, ap);
	va_end(ap);
	assert_true(n >= 0 && (size_t)n < sizeof s);
	put(b, s, (size_t)n);
}

/* gz: gzip of p[0..n) (one member, zlib's gzip wrapper). */
static buf
gz(const void *p, size_t n)
{
	buf b = { NULL, 0 };
	z_stream zs;

	memset(&zs, 0, sizeof zs);
	assert_int_equal(deflateInit2(&zs, 6, Z_DEFLATED, 31, 8,
	    Z_DEFAULT_STRATEGY), Z_OK);
	b.p = malloc(deflateBound(&zs, n) + 1);
	zs.next_in = (unsigned char *)p;
	zs.avail_in = (uInt)n;
	zs.next_out = b.p;
	zs.avail_out = (uInt)deflateBound(&zs, n);
	assert_int_equal(deflate(&zs, Z_FINISH), Z_STREAM_END);
	b.n = zs.total_out;
	deflateEnd(&zs);
	return b;
}


static char *
tpath(const char *name)
{
	static char s[4][256];
	static int k;

	k = (k + 1) % 4;
	snprintf(s[k], sizeof s[k], "%s/%s", helper_tmpdir, name);
	return s[k];
}

static void
write_file(const char *name, const void *p, size_t n)
{
	FILE *f = fopen(tpath(name), "wb");

	assert_non_null(f);
	assert_int_equal(fwrite(p, 1, n, f), n);
	assert_int_equal(fclose(f), 0);
}

/* ---- the oracle: source sample i of each type ---- */

static double
src_val(vx_scalar st, uint64_t i)
{
	switch (st) {
	case VX_S_U8: return (double)(i * 37 % 256);
	case VX_S_I8: return (double)(i * 37 % 256) - 128;
	case VX_S_U16: return (double)(i * 2999 % 65536);
	case VX_S_I16: return (double)(i * 2999 % 65536) - 32768;
	/* wide integers stay within 2^24, where f32 is exact */
	case VX_S_U32: return (double)(i * 40503 % 16777216);
	case VX_S_I32: return (double)(i * 40503 % 16777216) - 8388608;
	case VX_S_U64: return (double)(i * 4099 % 16777216);
	case VX_S_I64: return (double)(i * 4099 % 16777216) - 8000000;
	case VX_S_F32: return (double)i * 0.25 - 7.5;
	case VX_S_F64: return (double)i * 0.125 - 3;
	default: return NAN;
	}
}

/* put_sample: v as source type st in the given byte order. */
static void
put_sample(buf *b, vx_scalar st, double v, int big)
{
	unsigned char q[8];
	size_t n = vx_scalar_size(st), i;
	union { uint8_t u8; int8_t i8; uint16_t u16; int16_t i16;
		uint32_t u32; int32_t i32; uint64_t u64; int64_t i64;
		float f32; double f64; } u;
	uint64_t bits = 0;

	switch (st) {
	case VX_S_U8: u.u8 = (uint8_t)v; bits = u.u8; break;
	case VX_S_I8: u.i8 = (int8_t)v; bits = (uint8_t)u.i8; break;
	case VX_S_U16: u.u16 = (uint16_t)v; bits = u.u16; break;
	case VX_S_I16: u.i16 = (int16_t)v; bits = (uint16_t)u.i16; break;
	case VX_S_U32: u.u32 = (uint32_t)v; bits = u.u32; break;
	case VX_S_I32: u.i32 = (int32_t)v; bits = (uint32_t)u.i32; break;
	case VX_S_U64: u.u64 = (uint64_t)v; bits = u.u64; break;
	case VX_S_I64: u.i64 = (int64_t)v; bits = (uint64_t)u.i64; break;
	case VX_S_F32: { uint32_t w; u.f32 = (float)v; memcpy(&w, &u.f32, 4);
		bits = w; break; }
	case VX_S_F64: u.f64 = v; memcpy(&bits, &u.f64, 8); break;
	default: fail();
	}
	for (i = 0; i < n; i++)
		q[big ? n - 1 - i : i] = (unsigned char)(bits >> (8 * i));
	put(b, q, n);
}

/* put_samples: samples first .. first+count-1, binary, ascii (1) or hex
 * (2). */
static void
put_samples(buf *b, vx_scalar st, uint64_t first, uint64_t count, int big,
    int text)
{
	uint64_t i;

	for (i = first; i < first + count; i++) {
		if (text == 1) {
			putf(b, "%.17g%s", src_val(st, i), i % 7 == 6 ? "\n" :
			    " ");
		} else if (text == 2) {
			buf t = { NULL, 0 };

			put_sample(&t, st, src_val(st, i), big);
			for (size_t k = 0; k < t.n; k++)
				putf(b, "%02x%s", t.p[k], k + 1 == t.n &&
				    i % 5 == 4 ? "\n" : "");
			free(t.p);
		} else
			put_sample(b, st, src_val(st, i), big);
	}
	if (text)
		putf(b, "\n");
}

/* check_grid: dims, type, spacing, origin and every sample against the
 * formula; flipx: the file's x axis runs the other way; scale: slope and
 * intercept applied (NULL: none). */
static void
check_grid(const char *what, const vx_grid *g, const int64_t dims[3],
    vx_type type, vx_scalar st, const double sp[3], const double org[3],
    int flipx, const double *scale)
{
	int64_t x, y, z;
	int a;

	for (a = 0; a < 3; a++)
		if (g->dims[a] != dims[a])
			fail_msg("%s: dims[%d] %lld, want %lld", what, a,
			    (long long)g->dims[a], (long long)dims[a]);
	if (g->type != type)
		fail_msg("%s: type %s, want %s", what,
		    vx_enum_str(&vx_type_enum, g->type),
		    vx_enum_str(&vx_type_enum, type));
	for (a = 0; a < 3; a++)
		if (fabs(g->spacing[a] - sp[a]) > 1e-9 ||
		    fabs(g->origin[a] - org[a]) > 1e-9)
			fail_msg("%s: axis %d spacing %g origin %g, want %g %g",
			    what, a, g->spacing[a], g->origin[a], sp[a], org[a]);
	for (z = 0; z < dims[2]; z++)
		for (y = 0; y < dims[1]; y++)
			for (x = 0; x < dims[0]; x++) {
				int64_t fx = flipx ? dims[0] - 1 - x : x;
				uint64_t i = (uint64_t)(fx + dims[0] * (y +
				    dims[1] * z));
				double want = src_val(st, i), got;

				if (scale != NULL)
					want = (double)(float)(want * scale[0] +
					    scale[1]);
				else if (type == VX_F32)
					want = (double)(float)want;
				got = vx_grid_get(g, x, y, z);
				if (got != want)
					fail_msg("%s: sample (%lld,%lld,%lld) = %.17g, "
					    "want %.17g", what, (long long)x,
					    (long long)y, (long long)z, got, want);
			}
	assert_true(g->has_range);
}

static const int64_t D3[3] = { 5, 4, 3 };    /* 60 samples, x fastest */

/* ---- NRRD ---- */

enum { E_RAW, E_GZIP, E_ASCII, E_HEX };
enum { FR_NONE, FR_SPACINGS, FR_DIRS, FR_DIRS_FLIP, FR_MINMAX };
enum { DF_ATTACHED, DF_SINGLE, DF_LIST, DF_PATTERN };

typedef struct nrrd_case {
	const char *name;
	const char *type;        /* as the header says it */
	vx_scalar st;
	int enc, big, frame, df, wholegz, dim2, upper;
	int lskip, bskip;        /* line skip, byte skip (-1: at the end) */
} nrrd_case;

static const nrrd_case nrrd_cases[] = {
	/* every type, raw little-endian, spacings */
	{ "uchar", "uchar", VX_S_U8, E_RAW, 0, FR_SPACINGS, 0, 0, 0, 0, 0, 0 },
	{ "signed char", "signed char", VX_S_I8, E_RAW, 0, FR_SPACINGS, 0, 0,
	  0, 0, 0, 0 },
	{ "short", "short", VX_S_I16, E_RAW, 0, FR_SPACINGS, 0, 0, 0, 0, 0, 0 },
	{ "ushort", "ushort", VX_S_U16, E_RAW, 0, FR_SPACINGS, 0, 0, 0, 0, 0, 0 },
	{ "int", "int", VX_S_I32, E_RAW, 0, FR_SPACINGS, 0, 0, 0, 0, 0, 0 },
	{ "uint", "unsigned int", VX_S_U32, E_RAW, 0, FR_SPACINGS, 0, 0, 0,
	  0, 0, 0 },
	{ "int64", "long long int", VX_S_I64, E_RAW, 0, FR_SPACINGS, 0, 0, 0,
	  0, 0, 0 },
	{ "uint64", "uint64_t", VX_S_U64, E_RAW, 0, FR_SPACINGS, 0, 0, 0, 0, 0, 0 },
	{ "float", "float", VX_S_F32, E_RAW, 0, FR_SPACINGS, 0, 0, 0, 0, 0, 0 },
	{ "double", "double", VX_S_F64, E_RAW, 0, FR_SPACINGS, 0, 0, 0, 0, 0, 0 },
	/* byte orders */
	{ "short big", "int16", VX_S_I16, E_RAW, 1, FR_SPACINGS, 0, 0, 0, 0, 0, 0 },
	{ "float big", "float", VX_S_F32, E_RAW, 1, FR_NONE, 0, 0, 0, 0, 0, 0 },
	{ "double big", "double", VX_S_F64, E_RAW, 1, FR_DIRS, 0, 0, 0, 0, 0, 0 },
	/* encodings */
	{ "gzip short", "short", VX_S_I16, E_GZIP, 0, FR_DIRS, 0, 0, 0, 0, 0, 0 },
	{ "gzip ushort big", "unsigned short", VX_S_U16, E_GZIP, 1, FR_SPACINGS,
	  0, 0, 0, 0, 0, 0 },
	{ "ascii uchar", "unsigned char", VX_S_U8, E_ASCII, 0, FR_SPACINGS, 0,
	  0, 0, 0, 0, 0 },
	{ "ascii float", "float", VX_S_F32, E_ASCII, 0, FR_DIRS, 0, 0, 0, 0, 0, 0 },
	{ "ascii int", "int32_t", VX_S_I32, E_ASCII, 0, FR_NONE, 0, 0, 0, 0, 0, 0 },
	{ "hex short big", "short", VX_S_I16, E_HEX, 1, FR_SPACINGS, 0, 0, 0,
	  0, 0, 0 },
	/* frames */
	{ "space directions mirrored x", "float", VX_S_F32, E_RAW, 0,
	  FR_DIRS_FLIP, 0, 0, 0, 0, 0, 0 },
	{ "axis mins and maxs", "uchar", VX_S_U8, E_RAW, 0, FR_MINMAX, 0, 0, 0,
	  0, 0, 0 },
	/* detached data */
	{ "detached raw", "short", VX_S_I16, E_RAW, 0, FR_SPACINGS, DF_SINGLE,
	  0, 0, 0, 0, 0 },
	{ "detached gzip", "float", VX_S_F32, E_GZIP, 1, FR_DIRS, DF_SINGLE, 0,
	  0, 0, 0, 0 },
	{ "detached LIST", "ushort", VX_S_U16, E_RAW, 0, FR_SPACINGS, DF_LIST,
	  0, 0, 0, 0, 0 },
	{ "detached pattern", "uchar", VX_S_U8, E_GZIP, 0, FR_SPACINGS,
	  DF_PATTERN, 0, 0, 0, 0, 0 },
	{ "detached ascii", "double", VX_S_F64, E_ASCII, 0, FR_SPACINGS,
	  DF_SINGLE, 0, 0, 0, 0, 0 },
	/* whole file gzipped, dimension 2, upper-case field names */
	{ "whole file gzip", "short", VX_S_I16, E_RAW, 0, FR_DIRS, 0, 1, 0, 0, 0, 0 },
	{ "dimension 2", "uchar", VX_S_U8, E_RAW, 0, FR_SPACINGS, 0, 0, 1, 0, 0, 0 },
	{ "field case and blanks", "Unsigned  Short", VX_S_U16, E_RAW, 1,
	  FR_DIRS, 0, 0, 0, 1, 0, 0 },
	/* skips: lines before the data (before gunzip), bytes after it */
	{ "byte skip", "short", VX_S_I16, E_RAW, 0, FR_SPACINGS, 0, 0, 0, 0,
	  0, 7 },
	{ "byte skip -1", "float", VX_S_F32, E_RAW, 1, FR_SPACINGS, DF_SINGLE,
	  0, 0, 0, 0, -1 },
	{ "line skip", "uchar", VX_S_U8, E_RAW, 0, FR_SPACINGS, DF_SINGLE, 0, 0,
	  0, 3, 0 },
	{ "line and byte skip gzip", "int", VX_S_I32, E_GZIP, 0, FR_SPACINGS,
	  0, 0, 0, 0, 2, 5 },
	{ "byte skip ascii", "short", VX_S_I16, E_ASCII, 0, FR_SPACINGS,
	  DF_SINGLE, 0, 0, 0, 1, 4 },
};

static void
nrrd_build(const nrrd_case *c, buf *hdr, const int64_t dims[3], double sp[3],
    double org[3], int *flipx)
{
	static const char *encname[] = { "raw", "gzip", "ascii", "hex" };
	int dim = c->dim2 ? 2 : 3, a;
	uint64_t total = (uint64_t)(dims[0] * dims[1] * dims[2]);

	sp[0] = 0.5; sp[1] = 0.75; sp[2] = 2;
	org[0] = org[1] = org[2] = 0;
	*flipx = 0;
	putf(hdr, "NRRD0005\n# a comment\n");
	putf(hdr, c->upper ? "TYPE: %s\n" : "type: %s\n", c->type);
	putf(hdr, "dimension: %d\n", dim);
	if (dim == 2)
		putf(hdr, "sizes: %lld %lld\n", (long long)dims[0],
		    (long long)dims[1]);
	else
		putf(hdr, "sizes:  %lld\t%lld %lld \n", (long long)dims[0],
		    (long long)dims[1], (long long)dims[2]);
	putf(hdr, "encoding: %s\n", encname[c->enc]);
	if (vx_scalar_size(c->st) > 1 || c->big)
		putf(hdr, c->upper ? "Endian: %s\n" : "endian: %s\n",
		    c->big ? "BIG" : "little");
	putf(hdr, "creator:=the test\nkinds: domain domain%s\n",
	    dim == 3 ? " space" : "");
	switch (c->frame) {
	case FR_NONE:
		sp[0] = sp[1] = sp[2] = 1;
		break;
	case FR_SPACINGS:
		if (dim == 2) {
			putf(hdr, "spacings: 0.5 0.75\n");
			sp[2] = 1;
		} else
			putf(hdr, "spacings: 0.5 0.75 2\n");
		break;
	case FR_DIRS:
	case FR_DIRS_FLIP:
		putf(hdr, "space: left-posterior-superior\n");
		putf(hdr, c->upper ? "SPACE DIRECTIONS: (%g,0,0) ( 0 , 0.75, "
		    "0)\t(0,0,2)\n" : "space directions: (%g,0,0) (0,0.75,0) "
		    "(0,0,2)\n", c->frame == FR_DIRS_FLIP ? -0.5 : 0.5);
		putf(hdr, "space origin: (10,-20,30.5)\n");
		org[0] = 10; org[1] = -20; org[2] = 30.5;
		if (c->frame == FR_DIRS_FLIP) {
			*flipx = 1;
			org[0] = 10 - 0.5 * (double)(dims[0] - 1);
		}
		break;
	case FR_MINMAX:
		/* node-centred x: 5 samples on [0,2]; cell-centred y: 4 cells
		 * on [0,2]; z default (cell): 3 cells on [-3,3] */
		putf(hdr, "centers: node cell ???\naxis mins: 0 0 -3\n"
		    "axis maxs: 2 2 3\n");
		sp[0] = 0.5; sp[1] = 0.5; sp[2] = 2;
		org[0] = 0; org[1] = 0.25; org[2] = -2;
		break;
	}
	if (c->lskip)
		putf(hdr, "line skip: %d\n", c->lskip);
	if (c->bskip)
		putf(hdr, "byte skip: %d\n", c->bskip);
	(void)a;
	(void)total;
}

static void
nrrd_one(const nrrd_case *c, int k)
{
	const int64_t dims2[3] = { 5, 4, 1 };
	const int64_t *dims = c->dim2 ? dims2 : D3;
	uint64_t total = (uint64_t)(dims[0] * dims[1] * dims[2]);
	int text = c->enc == E_ASCII ? 1 : c->enc == E_HEX ? 2 : 0;
	double sp[3], org[3];
	buf hdr = { NULL, 0 }, data = { NULL, 0 };
	char name[64];
	int flipx, rc;
	vx_grid g;
	vx_err e = { 0, "" };
	vx_import_opts o;

	nrrd_build(c, &hdr, dims, sp, org, &flipx);
	if (c->df == DF_ATTACHED || c->df == DF_SINGLE) {
		/* bytes skipped after decompression, lines before it */
		for (int j = 0; j < (c->bskip < 0 ? 13 : c->bskip); j++)
			put(&data, "#", 1);
		put_samples(&data, c->st, 0, total, c->big, text);
		if (c->enc == E_GZIP) {
			buf z = gz(data.p, data.n);

			free(data.p);
			data = z;
		}
		if (c->lskip) {
			buf l = { NULL, 0 };

			for (int j = 0; j < c->lskip; j++)
				putf(&l, "skipped line %d\n", j);
			put(&l, data.p, data.n);
			free(data.p);
			data = l;
		}
	}
	switch (c->df) {
	case DF_ATTACHED:
		putf(&hdr, "\n");
		put(&hdr, data.p, data.n);
		break;
	case DF_SINGLE:
		snprintf(name, sizeof name, "data%d.bin", k);
		write_file(name, data.p, data.n);
		putf(&hdr, "data file: %s\n", name);
		break;
	case DF_LIST:
	case DF_PATTERN:
		/* one file per z slice */
		if (c->df == DF_LIST)
			putf(&hdr, "data file: LIST\n");
		else
			putf(&hdr, "data file: slice%d_%%03d.bin 2 %d 1\n", k,
			    (int)dims[2] + 1);
		for (int64_t z = 0; z < dims[2]; z++) {
			buf s = { NULL, 0 };
			uint64_t per = (uint64_t)(dims[0] * dims[1]);

			put_samples(&s, c->st, (uint64_t)z * per, per, c->big,
			    text);
			if (c->enc == E_GZIP) {
				buf z2 = gz(s.p, s.n);

				free(s.p);
				s = z2;
			}
			snprintf(name, sizeof name, c->df == DF_LIST ?
			    "list%d_%lld.bin" : "slice%d_%03lld.bin", k,
			    (long long)(c->df == DF_LIST ? z : z + 2));
			write_file(name, s.p, s.n);
			if (c->df == DF_LIST)
				putf(&hdr, "%s\n", name);
			free(s.p);
		}
		break;
	}
	if (c->wholegz) {
		buf z = gz(hdr.p, hdr.n);

		free(hdr.p);
		hdr = z;
	}
	/* through the file wrapper (detached names are relative to it) */
	snprintf(name, sizeof name, "case%d.nhdr", k);
	write_file(name, hdr.p, hdr.n);
	vx_import_opts_init(&o);
	rc = vx_import_file(&g, tpath(name), &o, &e);
	if (rc != 0)
		fail_msg("nrrd %s: %d %s", c->name, rc, e.msg);
	check_grid(c->name, &g, dims, vx_scalar_target(c->st), c->st, sp, org,
	    flipx, NULL);
	vx_grid_free(&g);
	/* and straight from memory when attached */
	if (c->df == DF_ATTACHED) {
		rc = vx_import_nrrd_mem(&g, hdr.p, hdr.n, NULL, &e);
		if (rc != 0)
			fail_msg("nrrd mem %s: %d %s", c->name, rc, e.msg);
		check_grid(c->name, &g, dims, vx_scalar_target(c->st), c->st,
		    sp, org, flipx, NULL);
		vx_grid_free(&g);
	}
	free(hdr.p);
	free(data.p);
}

static void
nrrd_variants(void **state)
{
	size_t i;

	(void)state;
	for (i = 0; i < sizeof nrrd_cases / sizeof nrrd_cases[0]; i++)
		nrrd_one(&nrrd_cases[i], (int)i);
}

/* ---- NIfTI-1 ---- */

enum { N_SFORM, N_PIXDIM, N_QFORM, N_SFORM_FLIP, N_QFORM_FLIP };

typedef struct nii_case {
	const char *name;
	int datatype, bitpix;
	vx_scalar st;
	int big, gzip, pair;
	float slope, inter;
	int frame;      /* N_SFORM, N_PIXDIM, N_QFORM, N_SFORM_FLIP,
	                   N_QFORM_FLIP (180 deg about y plus qfac -1) */
	int vox_offset;
	int dim0;
} nii_case;

/* unset fields: vox_offset 352 (0 for pairs), dim[0] 3, sform frame */
#define NII(n, dt, bp, t) .name = n, .datatype = dt, .bitpix = bp, .st = t
static const nii_case nii_cases[] = {
	{ NII("uint8", 2, 8, VX_S_U8) },
	{ NII("int16", 4, 16, VX_S_I16) },
	{ NII("int32", 8, 32, VX_S_I32) },
	{ NII("float32", 16, 32, VX_S_F32) },
	{ NII("float64", 64, 64, VX_S_F64) },
	{ NII("int8", 256, 8, VX_S_I8) },
	{ NII("uint16", 512, 16, VX_S_U16) },
	{ NII("uint32", 768, 32, VX_S_U32) },
	{ NII("int64", 1024, 64, VX_S_I64) },
	{ NII("uint64", 1280, 64, VX_S_U64), .big = 1 },
	{ NII("swapped int16", 4, 16, VX_S_I16), .big = 1 },
	{ NII("swapped float64 gz qform", 64, 64, VX_S_F64), .big = 1,
	  .gzip = 1, .frame = N_QFORM },
	{ NII("gz uint8 pixdim only, dim0 4", 2, 8, VX_S_U8), .gzip = 1,
	  .frame = N_PIXDIM, .dim0 = 4 },
	{ NII("slope 1 inter 0", 4, 16, VX_S_I16), .slope = 1 },
	{ NII("slope 2 inter -5", 4, 16, VX_S_I16), .slope = 2, .inter = -5 },
	{ NII("slope 0.5 uint8 swapped", 2, 8, VX_S_U8), .big = 1,
	  .slope = 0.5f, .inter = 1 },
	{ NII("slope 0 inter 7 (unscaled)", 512, 16, VX_S_U16), .inter = 7 },
	{ NII("vox_offset 1000", 512, 16, VX_S_U16), .vox_offset = 1000 },
	{ NII("vox_offset 348", 2, 8, VX_S_U8), .vox_offset = 348 },
	{ NII("sform mirrored x", 16, 32, VX_S_F32), .frame = N_SFORM_FLIP },
	{ NII("qform mirrored x", 16, 32, VX_S_F32), .big = 1, .frame = N_QFORM_FLIP },
	{ NII("pair", 4, 16, VX_S_I16), .pair = 1 },
	{ NII("pair swapped gz", 4, 16, VX_S_I16), .pair = 1, .big = 1,
	  .gzip = 1, .frame = N_QFORM, .vox_offset = 16 },
};

static void
put_i16(unsigned char *h, size_t off, int v, int big)
{
	uint16_t u = (uint16_t)v;

	h[off + (big ? 1 : 0)] = (unsigned char)u;
	h[off + (big ? 0 : 1)] = (unsigned char)(u >> 8);
}

static void
put_i32(unsigned char *h, size_t off, uint32_t u, int big)
{
	for (int i = 0; i < 4; i++)
		h[off + (big ? 3 - i : i)] = (unsigned char)(u >> (8 * i));
}

static void
put_f32(unsigned char *h, size_t off, float f, int big)
{
	uint32_t u;

	memcpy(&u, &f, 4);
	put_i32(h, off, u, big);
}

/* nii_header: a 348-byte NIfTI-1 header for dims D3. */
static int
nii_offset(const nii_case *c)
{
	return c->vox_offset ? c->vox_offset : c->pair ? 0 : 352;
}

static void
nii_header(unsigned char h[348], const nii_case *c, double sp[3],
    double org[3], int *flipx)
{
	int b = c->big, a;

	memset(h, 0, 348);
	put_i32(h, 0, 348, b);
	put_i16(h, 40, c->dim0 ? c->dim0 : 3, b);
	for (a = 0; a < 3; a++)
		put_i16(h, 42 + 2 * a, (int)D3[a], b);
	put_i16(h, 48, 1, b);
	put_i16(h, 70, c->datatype, b);
	put_i16(h, 72, c->bitpix, b);
	sp[0] = 1.5; sp[1] = 2; sp[2] = 0.5;
	put_f32(h, 76, c->frame == N_QFORM_FLIP ? -1.0f : 1.0f, b); /* qfac */
	for (a = 0; a < 3; a++)
		put_f32(h, 80 + 4 * a, (float)sp[a], b);
	put_f32(h, 108, (float)nii_offset(c), b);
	put_f32(h, 112, c->slope, b);
	put_f32(h, 116, c->inter, b);
	org[0] = org[1] = org[2] = 0;
	*flipx = 0;
	if (c->frame == N_SFORM || c->frame == N_SFORM_FLIP) {
		put_i16(h, 254, 4, b);
		/* srow: x = -s0*i + ... when mirrored */
		put_f32(h, 280, c->frame == N_SFORM_FLIP ? -1.5f : 1.5f, b);
		put_f32(h, 292, 90, b);
		put_f32(h, 300, 2, b);
		put_f32(h, 308, -126, b);
		put_f32(h, 320, 0.5f, b);
		put_f32(h, 324, -72, b);
		org[0] = 90; org[1] = -126; org[2] = -72;
		/* a qform that disagrees: the sform wins */
		put_i16(h, 252, 1, b);
		put_f32(h, 268, 1000, b);
	} else if (c->frame == N_QFORM || c->frame == N_QFORM_FLIP) {
		put_i16(h, 252, 1, b);
		if (c->frame == N_QFORM_FLIP) {
			/* b,c,d = (0,1,0): 180 degrees about y, so x and z
			 * flip; qfac -1 flips z back */
			put_f32(h, 260, 1, b);
		}
		put_f32(h, 268, 7, b);
		put_f32(h, 272, -8, b);
		put_f32(h, 276, 9.5f, b);
		org[0] = 7; org[1] = -8; org[2] = 9.5;
	}
	if (c->frame == N_SFORM_FLIP || c->frame == N_QFORM_FLIP) {
		*flipx = 1;
		org[0] -= 1.5 * (double)(D3[0] - 1);
	}
	memcpy(h + 344, c->pair ? "ni1" : "n+1", 4);
}

static void
nii_variants(void **state)
{
	size_t i;

	(void)state;
	for (i = 0; i < sizeof nii_cases / sizeof nii_cases[0]; i++) {
		const nii_case *c = &nii_cases[i];
		unsigned char h[348];
		buf f = { NULL, 0 }, img = { NULL, 0 };
		double sp[3], org[3], scale[2] = { c->slope, c->inter };
		int flipx, rc, scaled = c->slope != 0 && !(c->slope == 1 &&
		    c->inter == 0);   /* the NIfTI rule, restated */
		char name[64];
		vx_grid g;
		vx_err e = { 0, "" };
		vx_import_opts o;

		nii_header(h, c, sp, org, &flipx);
		put(&f, h, 348);
		if (!c->pair) {
			/* extension flag, then padding up to vox_offset */
			while (f.n < (size_t)nii_offset(c))
				put(&f, "\0", 1);
			put_samples(&f, c->st, 0, 60, c->big, 0);
		} else {
			while (img.n < (size_t)nii_offset(c))
				put(&img, "\0", 1);
			put_samples(&img, c->st, 0, 60, c->big, 0);
		}
		if (c->gzip) {
			buf z = gz(f.p, f.n);

			free(f.p);
			f = z;
			if (c->pair) {
				z = gz(img.p, img.n);
				free(img.p);
				img = z;
			}
		}
		if (c->pair) {
			snprintf(name, sizeof name, "pair%zu.img%s", i,
			    c->gzip ? ".gz" : "");
			write_file(name, img.p, img.n);
			snprintf(name, sizeof name, "pair%zu.hdr%s", i,
			    c->gzip ? ".gz" : "");
		} else
			snprintf(name, sizeof name, "vol%zu.nii%s", i,
			    c->gzip ? ".gz" : "");
		write_file(name, f.p, f.n);
		vx_import_opts_init(&o);
		rc = vx_import_file(&g, tpath(name), &o, &e);
		if (rc != 0)
			fail_msg("nifti %s: %d %s", c->name, rc, e.msg);
		check_grid(c->name, &g, D3, scaled ? VX_F32 :
		    vx_scalar_target(c->st), c->st, sp, org, flipx,
		    scaled ? scale : NULL);
		vx_grid_free(&g);
		if (!c->pair) {
			rc = vx_import_nifti_mem(&g, f.p, f.n, &e);
			if (rc != 0)
				fail_msg("nifti mem %s: %d %s", c->name, rc, e.msg);
			vx_grid_free(&g);
		}
		free(f.p);
		free(img.p);
	}
}

/* ---- VTK ---- */

typedef struct vtk_case {
	const char *name;
	const char *type;
	vx_scalar st;
	int binary, gzip, ncomp, aspect, blank_lines;
} vtk_case;

static const vtk_case vtk_cases[] = {
	{ "ascii uchar", "unsigned_char", VX_S_U8, 0, 0, 0, 0, 0 },
	{ "ascii char", "char", VX_S_I8, 0, 0, 1, 0, 0 },
	{ "ascii short", "short", VX_S_I16, 0, 0, 0, 1, 0 },
	{ "ascii float", "float", VX_S_F32, 0, 0, 1, 0, 0 },
	{ "ascii double gz", "double", VX_S_F64, 0, 1, 0, 0, 0 },
	{ "binary uchar", "unsigned_char", VX_S_U8, 1, 0, 0, 0, 1 },
	{ "binary char", "char", VX_S_I8, 1, 0, 0, 0, 0 },
	{ "binary short", "short", VX_S_I16, 1, 0, 1, 0, 0 },
	{ "binary ushort", "unsigned_short", VX_S_U16, 1, 0, 0, 1, 0 },
	{ "binary int", "int", VX_S_I32, 1, 0, 0, 0, 0 },
	{ "binary float gz", "float", VX_S_F32, 1, 1, 0, 0, 0 },
	{ "binary double", "double", VX_S_F64, 1, 0, 1, 0, 0 },
	/* the names VTK's own writers use (the table tet meshes share) */
	{ "binary long", "long", VX_S_I64, 1, 0, 0, 0, 0 },
	{ "binary vtkIdType", "vtkIdType", VX_S_I32, 1, 0, 0, 0, 0 },
	{ "ascii vtktypeuint16", "vtktypeuint16", VX_S_U16, 0, 0, 0, 0, 0 },
	{ "binary vtktypefloat64", "VTKTYPEFLOAT64", VX_S_F64, 1, 0, 0, 0, 0 },
};

static void
vtk_variants(void **state)
{
	size_t i;

	(void)state;
	for (i = 0; i < sizeof vtk_cases / sizeof vtk_cases[0]; i++) {
		const vtk_case *c = &vtk_cases[i];
		double sp[3] = { 0.5, 1, 4 }, org[3] = { -1, 2.5, 0 };
		buf f = { NULL, 0 };
		vx_grid g;
		vx_err e = { 0, "" };
		int rc;

		putf(&f, "# vtk DataFile Version %s\nmade by test_import\n%s%s\n"
		    "DATASET STRUCTURED_POINTS\n", c->blank_lines ? "1.0" : "3.0",
		    c->blank_lines ? "\n" : "", c->binary ? "BINARY" : "ASCII");
		putf(&f, "ORIGIN -1 2.5 0\n%s 0.5 1 4\nDIMENSIONS 5 4 3\n",
		    c->aspect ? "ASPECT_RATIO" : "SPACING");
		putf(&f, "POINT_DATA 60\nSCALARS density %s%s\n"
		    "LOOKUP_TABLE default\n", c->type, c->ncomp ? " 1" : "");
		put_samples(&f, c->st, 0, 60, 1, c->binary ? 0 : 1);
		putf(&f, "\nCELL_DATA 24\n");   /* ignored */
		if (c->gzip) {
			buf z = gz(f.p, f.n);

			free(f.p);
			f = z;
		}
		rc = vx_import_vtk_mem(&g, f.p, f.n, &e);
		if (rc != 0)
			fail_msg("vtk %s: %d %s", c->name, rc, e.msg);
		check_grid(c->name, &g, D3, vx_scalar_target(c->st), c->st, sp,
		    org, 0, NULL);
		vx_grid_free(&g);
		free(f.p);
	}
}

/* ---- raw ---- */

static void
raw_variants(void **state)
{
	static const struct {
		const char *name;
		vx_scalar st;
		int big, gzip;
		uint64_t skip;
	} t[] = {
		{ "u8", VX_S_U8, 0, 0, 0 },
		{ "i8", VX_S_I8, 0, 0, 3 },
		{ "u16 little skip", VX_S_U16, 0, 0, 17 },
		{ "u16 big skip", VX_S_U16, 1, 0, 17 },
		{ "i16 big gz", VX_S_I16, 1, 1, 0 },
		{ "i32 little", VX_S_I32, 0, 0, 4 },
		{ "u32 big", VX_S_U32, 1, 0, 0 },
		{ "f32 big gz skip", VX_S_F32, 1, 1, 100 },
		{ "f64 little", VX_S_F64, 0, 0, 0 },
	};
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		double sp[3] = { 1, 2, 3 }, org[3] = { -4, 5, 6 };
		buf f = { NULL, 0 };
		vx_raw_info r;
		vx_grid g;
		vx_err e = { 0, "" };
		int rc;

		for (uint64_t k = 0; k < t[i].skip; k++)
			put(&f, "H", 1);
		put_samples(&f, t[i].st, 0, 60, t[i].big, 0);
		if (t[i].gzip) {
			buf z = gz(f.p, f.n);

			free(f.p);
			f = z;
		}
		vx_raw_info_init(&r);
		memcpy(r.dims, D3, sizeof r.dims);
		r.type = t[i].st;
		r.big_endian = t[i].big;
		r.skip = t[i].skip;
		memcpy(r.spacing, sp, sizeof sp);
		memcpy(r.origin, org, sizeof org);
		rc = vx_import_raw_mem(&g, f.p, f.n, &r, &e);
		if (rc != 0)
			fail_msg("raw %s: %d %s", t[i].name, rc, e.msg);
		check_grid(t[i].name, &g, D3, vx_scalar_target(t[i].st), t[i].st,
		    sp, org, 0, NULL);
		vx_grid_free(&g);
		free(f.p);
	}
}

/* gzip members are read in turn (as gzip -d does); bytes after the last
 * member are ignored */
static void
gzip_members(void **state)
{
	buf a = { NULL, 0 }, b = { NULL, 0 }, f = { NULL, 0 }, z;
	double sp[3] = { 1, 1, 1 }, org[3] = { 0, 0, 0 };
	vx_raw_info r;
	vx_grid g;
	vx_err e = { 0, "" };

	(void)state;
	put_samples(&a, VX_S_I16, 0, 25, 0, 0);
	put_samples(&b, VX_S_I16, 25, 35, 0, 0);
	z = gz(a.p, a.n);
	put(&f, z.p, z.n);
	free(z.p);
	z = gz(b.p, b.n);
	put(&f, z.p, z.n);
	free(z.p);
	put(&f, "\0\0\0\0", 4);      /* padding, as tape tools leave */
	vx_raw_info_init(&r);
	memcpy(r.dims, D3, sizeof r.dims);
	r.type = VX_S_I16;
	assert_int_equal(vx_import_raw_mem(&g, f.p, f.n, &r, &e), 0);
	check_grid("two members", &g, D3, VX_I16, VX_S_I16, sp, org, 0, NULL);
	vx_grid_free(&g);
	free(a.p);
	free(b.p);
	free(f.p);
}

/* ---- synthetic fields ---- */

static void
synth_fields(void **state)
{
	/* oracle: the formulas of vx_import.h evaluated here independently */
	static const int64_t dims[][3] = { { 9, 9, 9 }, { 41, 41, 41 },
	    { 2, 7, 1 } };
	int k;
	size_t d;

	(void)state;
	for (k = VX_SYNTH_UNKNOWN + 1; k < VX_SYNTH_LAST; k++)
		for (d = 0; d < sizeof dims / sizeof dims[0]; d++) {
			vx_grid g;
			vx_err e = { 0, "" };

			assert_int_equal(vx_synth_make(&g, (vx_synth_kind)k,
			    dims[d], &e), 0);
			assert_int_equal(g.type, VX_F32);
			for (int a = 0; a < 3; a++) {
				double n = (double)dims[d][a];

				assert_true(fabs(g.origin[a] - (n > 1 ? -1 : 0)) <
				    1e-15);
				assert_true(fabs(g.spacing[a] - (n > 1 ? 2 /
				    (n - 1) : 1)) < 1e-15);
			}
			for (int64_t z = 0; z < dims[d][2]; z++)
				for (int64_t y = 0; y < dims[d][1]; y++)
					for (int64_t x = 0; x < dims[d][0]; x++) {
						double px = dims[d][0] > 1 ? -1 + 2.0 *
						    (double)x / (double)(dims[d][0] - 1) : 0;
						double py = dims[d][1] > 1 ? -1 + 2.0 *
						    (double)y / (double)(dims[d][1] - 1) : 0;
						double pz = dims[d][2] > 1 ? -1 + 2.0 *
						    (double)z / (double)(dims[d][2] - 1) : 0;
						double want = 0, got;

						switch (k) {
						case VX_SYNTH_SPHERE:
							want = sqrt(px * px + py * py +
							    pz * pz);
							break;
						case VX_SYNTH_TORUS:
							want = hypot(hypot(px, py) - 0.5,
							    pz);
							break;
						case VX_SYNTH_LINEAR:
							want = px + 2 * py + 3 * pz + 0.5;
							break;
						case VX_SYNTH_ML: {
							double r = hypot(px, py);

							want = (1 - sin(M_PI * pz / 2) +
							    0.25 * (1 + cos(12 * M_PI *
							    cos(M_PI * r / 2)))) / 2.5;
							break;
						}
						case VX_SYNTH_SADDLE:
							want = px * py * pz + (px * py +
							    py * pz + pz * px) / 2;
							break;
						}
						got = vx_grid_get(&g, x, y, z);
						if (fabs(got - want) > 1e-6)
							fail_msg("field %d (%lld,%lld,"
							    "%lld): %g, want %g", k,
							    (long long)x, (long long)y,
							    (long long)z, got, want);
						/* exactness: the stored value is the
						 * float of the documented evaluation */
						assert_true(got == (double)(float)
						    vx_synth_eval((vx_synth_kind)k,
						    vx_synth_coord(x, dims[d][0]),
						    vx_synth_coord(y, dims[d][1]),
						    vx_synth_coord(z, dims[d][2])));
					}
			vx_grid_free(&g);
		}
	/* known values: ML at the centre column top (0,0,1): rho_r(0) =
	 * cos(12 pi) = 1, so f = (1 - 1 + 0.25 * 2) / 2.5 = 0.2 */
	assert_true(fabs(vx_synth_eval(VX_SYNTH_ML, 0, 0, 1) - 0.2) < 1e-15);
	assert_true(vx_synth_eval(VX_SYNTH_SADDLE, 0, 0, 0) == 0);
	assert_true(vx_synth_eval(VX_SYNTH_SADDLE, -1, -1, -1) == 0.5);
}

/* ---- malformed input ---- */

typedef struct bad_case {
	const char *name;
	int code;
	const char *msg;
	void (*make)(buf *b);
	int format;   /* vx_format to read as */
} bad_case;

static void
nrrd_head(buf *b, const char *type, const char *sizes, const char *enc)
{
	putf(b, "NRRD0004\ntype: %s\ndimension: 3\nsizes: %s\nencoding: %s\n"
	    "endian: little\n", type, sizes, enc);
}

static void mk_nrrd_truncated(buf *b)
{
	nrrd_head(b, "short", "5 4 3", "raw");
	putf(b, "\n");
	put_samples(b, VX_S_I16, 0, 59, 0, 0);
}
static void mk_nrrd_zero(buf *b) { nrrd_head(b, "uchar", "5 0 3", "raw");
	putf(b, "\nxxxx"); }
static void mk_nrrd_negative(buf *b) { nrrd_head(b, "uchar", "5 -4 3", "raw");
	putf(b, "\nxxxx"); }
static void mk_nrrd_two_sizes(buf *b) { nrrd_head(b, "uchar", "5 4", "raw");
	putf(b, "\nxxxx"); }
static void mk_nrrd_overflow(buf *b)
{
	nrrd_head(b, "uchar", "4294967296 4294967296 4294967296", "raw");
	putf(b, "\nxxxx");
}
static void mk_nrrd_huge(buf *b)
{
	/* each size within limits, the product beyond 2^36 */
	nrrd_head(b, "float", "1048576 1048576 2", "raw");
	putf(b, "\nxxxx");
}
static void mk_nrrd_claims_more(buf *b)
{
	/* a plausible size the data cannot back: refused before allocating */
	nrrd_head(b, "float", "1000 1000 1000", "raw");
	putf(b, "\nxxxx");
}
static void mk_nrrd_badtype(buf *b) { nrrd_head(b, "quaternion", "5 4 3",
	"raw"); putf(b, "\n"); }
static void mk_nrrd_block(buf *b) { nrrd_head(b, "block", "5 4 3", "raw");
	putf(b, "\n"); }
static void mk_nrrd_bzip2(buf *b) { nrrd_head(b, "uchar", "5 4 3", "bzip2");
	putf(b, "\n"); }
static void mk_nrrd_unknown_field(buf *b)
{
	nrrd_head(b, "uchar", "5 4 3", "raw");
	putf(b, "wobble: 3\n\n");
	put_samples(b, VX_S_U8, 0, 60, 0, 0);
}
static void mk_nrrd_dup(buf *b)
{
	nrrd_head(b, "uchar", "5 4 3", "raw");
	putf(b, "sizes: 5 4 3\n\n");
}
static void mk_nrrd_noendian(buf *b)
{
	putf(b, "NRRD0004\ntype: short\ndimension: 3\nsizes: 5 4 3\n"
	    "encoding: raw\n\n");
	put_samples(b, VX_S_I16, 0, 60, 0, 0);
}
/* header numbers: vx_scan.h's grammar (no hexadecimal, no overflow to
 * infinity) */
static void
nrrd_spacings(buf *b, const char *sp)
{
	nrrd_head(b, "uchar", "5 4 3", "raw");
	putf(b, "spacings: %s\n\n", sp);
	put_samples(b, VX_S_U8, 0, 60, 0, 0);
}
static void mk_nrrd_hex_spacing(buf *b) { nrrd_spacings(b, "1 0x1p-1 1"); }
static void mk_nrrd_inf_spacing(buf *b) { nrrd_spacings(b, "1 1 1e999"); }
static void mk_nrrd_version(buf *b) { putf(b, "NRRD0009\ntype: uchar\n\n"); }
static void mk_nrrd_dim4(buf *b)
{
	putf(b, "NRRD0004\ntype: uchar\ndimension: 4\nsizes: 5 4 3 2\n"
	    "encoding: raw\n\n");
}
static void mk_nrrd_vector_kind(buf *b)
{
	nrrd_head(b, "uchar", "3 4 5", "raw");
	putf(b, "kinds: RGB-color space space\n\n");
	put_samples(b, VX_S_U8, 0, 60, 0, 0);
}
static void mk_nrrd_rotated(buf *b)
{
	nrrd_head(b, "uchar", "5 4 3", "raw");
	putf(b, "space: RAS\nspace directions: (0.7,0.7,0) (-0.7,0.7,0) "
	    "(0,0,1)\n\n");
	put_samples(b, VX_S_U8, 0, 60, 0, 0);
}
static void mk_nrrd_spacings_and_dirs(buf *b)
{
	nrrd_head(b, "uchar", "5 4 3", "raw");
	putf(b, "space: RAS\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n"
	    "spacings: 1 1 1\n\n");
	put_samples(b, VX_S_U8, 0, 60, 0, 0);
}
static void mk_nrrd_detached_mem(buf *b)
{
	nrrd_head(b, "uchar", "5 4 3", "raw");
	putf(b, "data file: x.raw\n");
}
static void mk_nrrd_no_blank(buf *b) { nrrd_head(b, "uchar", "5 4 3",
	"raw"); }
static void mk_nrrd_ascii_bad(buf *b)
{
	nrrd_head(b, "uchar", "5 4 3", "ascii");
	putf(b, "\n1 2 3 300");
	for (int i = 0; i < 56; i++)
		putf(b, " 1");
}
static void mk_nrrd_ascii_short(buf *b)
{
	nrrd_head(b, "float", "5 4 3", "ascii");
	putf(b, "\n");
	for (int i = 0; i < 59; i++)
		putf(b, "%d.5 ", i);
}
static void
gz_data(buf *b, uint64_t count, size_t cut, int extra)
{
	buf d = { NULL, 0 }, z;

	nrrd_head(b, "short", "5 4 3", "gzip");
	putf(b, "\n");
	put_samples(&d, VX_S_I16, 0, count, 0, 0);
	if (extra)
		put(&d, "\0\0", 2);
	z = gz(d.p, d.n);
	put(b, z.p, z.n - cut);
	free(d.p);
	free(z.p);
}
static void mk_nrrd_gz_short(buf *b) { gz_data(b, 59, 0, 0); }
static void mk_nrrd_gz_long(buf *b) { gz_data(b, 60, 0, 1); }
static void mk_nrrd_gz_cut(buf *b) { gz_data(b, 60, 10, 0); }
static void mk_nrrd_gz_corrupt(buf *b)
{
	gz_data(b, 60, 0, 0);
	b->p[b->n - 30] ^= 0x55;
}
static void mk_nrrd_gz_crc(buf *b)
{
	gz_data(b, 60, 0, 0);
	b->p[b->n - 6] ^= 1;     /* the CRC-32 in the trailer */
}
static void mk_nrrd_long_raw(buf *b)
{
	nrrd_head(b, "uchar", "5 4 3", "raw");
	putf(b, "\n");
	for (int i = 0; i < 5000; i++)
		put(b, "x", 1);
}

static void
nii_bad(buf *b, void (*edit)(unsigned char *h), int ndata)
{
	static const nii_case c = { NII("", 4, 16, VX_S_I16) };
	unsigned char h[348];
	double sp[3], org[3];
	int flipx;

	nii_header(h, &c, sp, org, &flipx);
	if (edit)
		edit(h);
	put(b, h, 348);
	put(b, "\0\0\0\0", 4);
	put_samples(b, VX_S_I16, 0, (uint64_t)ndata, 0, 0);
}
static void ed_dim0(unsigned char *h) { put_i16(h, 40, 0, 0); }
static void ed_dim_neg(unsigned char *h) { put_i16(h, 44, -4, 0); }
static void ed_dim4(unsigned char *h) { put_i16(h, 40, 4, 0);
	put_i16(h, 48, 2, 0); }
static void ed_dtype(unsigned char *h) { put_i16(h, 70, 128, 0);
	put_i16(h, 72, 24, 0); }
static void ed_bitpix(unsigned char *h) { put_i16(h, 72, 8, 0); }
static void ed_voxoff(unsigned char *h) { put_f32(h, 108, 100, 0); }
static void ed_voxoff_frac(unsigned char *h) { put_f32(h, 108, 352.5f, 0); }
static void ed_magic(unsigned char *h) { memcpy(h + 344, "xyz", 4); }
static void ed_ni1(unsigned char *h) { memcpy(h + 344, "ni1", 4); }
static void ed_nifti2(unsigned char *h) { put_i32(h, 0, 540, 0); }
static void ed_sizeof(unsigned char *h) { put_i32(h, 0, 349, 0); }
static void ed_oblique(unsigned char *h)
{
	put_i16(h, 254, 1, 0);
	put_f32(h, 280, 1, 0);
	put_f32(h, 284, 0.3f, 0);
	put_f32(h, 300, 1, 0);
	put_f32(h, 320, 1, 0);
}
static void mk_nii_truncated(buf *b) { nii_bad(b, NULL, 59); }
static void mk_nii_long(buf *b)
{
	nii_bad(b, NULL, 60);
	for (int i = 0; i < 5000; i++)
		put(b, "x", 1);
}
static void mk_nii_dim0(buf *b) { nii_bad(b, ed_dim0, 60); }
static void mk_nii_dim_neg(buf *b) { nii_bad(b, ed_dim_neg, 60); }
static void mk_nii_dim4(buf *b) { nii_bad(b, ed_dim4, 120); }
static void mk_nii_dtype(buf *b) { nii_bad(b, ed_dtype, 60); }
static void mk_nii_bitpix(buf *b) { nii_bad(b, ed_bitpix, 60); }
static void mk_nii_voxoff(buf *b) { nii_bad(b, ed_voxoff, 60); }
static void mk_nii_voxoff_frac(buf *b) { nii_bad(b, ed_voxoff_frac, 60); }
static void mk_nii_magic(buf *b) { nii_bad(b, ed_magic, 60); }
static void mk_nii_ni1(buf *b) { nii_bad(b, ed_ni1, 60); }
static void mk_nii_nifti2(buf *b) { nii_bad(b, ed_nifti2, 60); }
static void mk_nii_sizeof(buf *b) { nii_bad(b, ed_sizeof, 60); }
static void mk_nii_oblique(buf *b) { nii_bad(b, ed_oblique, 60); }
static void mk_nii_short_hdr(buf *b) { nii_bad(b, NULL, 0); b->n = 200; }
static void mk_nii_gz_short(buf *b)
{
	buf t = { NULL, 0 }, z;

	nii_bad(&t, NULL, 59);
	z = gz(t.p, t.n);
	put(b, z.p, z.n);
	free(t.p);
	free(z.p);
}
static void mk_nii_gz_long(buf *b)
{
	buf t = { NULL, 0 }, z;

	nii_bad(&t, NULL, 60);
	for (int i = 0; i < 5000; i++)
		put(&t, "x", 1);
	z = gz(t.p, t.n);
	put(b, z.p, z.n);
	free(t.p);
	free(z.p);
}

static void
vtk_head(buf *b, const char *mode, const char *dims, const char *npts,
    const char *type)
{
	putf(b, "# vtk DataFile Version 3.0\nt\n%s\nDATASET STRUCTURED_POINTS\n"
	    "DIMENSIONS %s\nSPACING 1 1 1\nORIGIN 0 0 0\nPOINT_DATA %s\n"
	    "SCALARS s %s\nLOOKUP_TABLE default\n", mode, dims, npts, type);
}
static void mk_vtk_truncated(buf *b)
{
	vtk_head(b, "BINARY", "5 4 3", "60", "short");
	put_samples(b, VX_S_I16, 0, 59, 1, 0);
}
static void mk_vtk_npts(buf *b)
{
	vtk_head(b, "BINARY", "5 4 3", "61", "unsigned_char");
	put_samples(b, VX_S_U8, 0, 61, 1, 0);
}
static void mk_vtk_zero(buf *b) { vtk_head(b, "ASCII", "5 0 3", "0",
	"float"); }
static void mk_vtk_type(buf *b) { vtk_head(b, "ASCII", "5 4 3", "60",
	"bit"); }
static void mk_vtk_grid(buf *b)
{
	putf(b, "# vtk DataFile Version 3.0\nt\nASCII\n"
	    "DATASET UNSTRUCTURED_GRID\nPOINTS 0 float\n");
}
static void mk_vtk_vectors(buf *b)
{
	putf(b, "# vtk DataFile Version 3.0\nt\nASCII\nDATASET "
	    "STRUCTURED_POINTS\nDIMENSIONS 1 1 1\nPOINT_DATA 1\n"
	    "VECTORS v float\n1 2 3\n");
}
static void mk_vtk_ncomp(buf *b)
{
	putf(b, "# vtk DataFile Version 3.0\nt\nASCII\nDATASET "
	    "STRUCTURED_POINTS\nDIMENSIONS 1 1 1\nPOINT_DATA 1\n"
	    "SCALARS v float 3\nLOOKUP_TABLE default\n1 2 3\n");
}
static void mk_vtk_ascii_word(buf *b)
{
	vtk_head(b, "ASCII", "2 1 1", "2", "float");
	putf(b, "1.5 abc\n");
}
static void mk_vtk_mode(buf *b) { vtk_head(b, "EBCDIC", "2 1 1", "2",
	"float"); }
static void mk_vtk_inf_origin(buf *b)
{
	putf(b, "# vtk DataFile Version 3.0\nt\nASCII\nDATASET "
	    "STRUCTURED_POINTS\nDIMENSIONS 1 1 1\nORIGIN 0 -1e999 0\n"
	    "POINT_DATA 1\nSCALARS v float\nLOOKUP_TABLE default\n1\n");
}

static void
raw_case(buf *b, size_t n)
{
	put_samples(b, VX_S_U16, 0, n, 0, 0);
}
static void mk_raw_short(buf *b) { raw_case(b, 59); }
static void mk_raw_long(buf *b) { raw_case(b, 61); }
static void mk_raw_gz_long(buf *b)
{
	buf t = { NULL, 0 }, z;

	raw_case(&t, 61);
	z = gz(t.p, t.n);
	put(b, z.p, z.n);
	free(t.p);
	free(z.p);
}
static void mk_raw_gz_short(buf *b)
{
	buf t = { NULL, 0 }, z;

	raw_case(&t, 59);
	z = gz(t.p, t.n);
	put(b, z.p, z.n);
	free(t.p);
	free(z.p);
}
static void mk_raw_gz_bomb(buf *b)
{
	/* 1 MiB of zeros compresses to ~1 KiB: fine; but claim far more */
	static unsigned char zero[1 << 20];
	buf z = gz(zero, sizeof zero);

	put(b, z.p, z.n);
	free(z.p);
}

enum { R_NRRD = 1, R_NII, R_VTK, R_RAW, R_RAW_HUGE };

static const bad_case bad[] = {
	{ "nrrd truncated data", 65, "truncated", mk_nrrd_truncated, R_NRRD },
	{ "nrrd zero size", 65, "sizes: expected 3 positive integers",
	  mk_nrrd_zero, R_NRRD },
	{ "nrrd negative size", 65, "sizes: expected 3 positive integers",
	  mk_nrrd_negative, R_NRRD },
	{ "nrrd too few sizes", 65, "sizes: expected 3 positive integers",
	  mk_nrrd_two_sizes, R_NRRD },
	{ "nrrd size overflow", 65, "size 4294967296 of axis 0 out of range",
	  mk_nrrd_overflow, R_NRRD },
	{ "nrrd product over limit", 65, "exceed the limit", mk_nrrd_huge,
	  R_NRRD },
	{ "nrrd claims more than present", 65, "cannot hold",
	  mk_nrrd_claims_more, R_NRRD },
	{ "nrrd bad type", 65, "type: unknown type 'quaternion'",
	  mk_nrrd_badtype, R_NRRD },
	{ "nrrd block type", 65, "block is not supported", mk_nrrd_block,
	  R_NRRD },
	{ "nrrd bzip2", 65, "bzip2 is not supported", mk_nrrd_bzip2, R_NRRD },
	{ "nrrd unknown field", 65, "unknown field 'wobble'",
	  mk_nrrd_unknown_field, R_NRRD },
	{ "nrrd duplicate field", 65, "field 'sizes' given twice", mk_nrrd_dup,
	  R_NRRD },
	{ "nrrd missing endian", 65, "endian: missing", mk_nrrd_noendian,
	  R_NRRD },
	{ "nrrd version", 65, "unsupported version 'NRRD0009'",
	  mk_nrrd_version, R_NRRD },
	{ "nrrd dimension 4", 65, "dimension: 4", mk_nrrd_dim4, R_NRRD },
	{ "nrrd colour axis", 65, "kinds: axis 0 is 'RGB-color'",
	  mk_nrrd_vector_kind, R_NRRD },
	{ "nrrd rotated", 65, "not aligned", mk_nrrd_rotated, R_NRRD },
	{ "nrrd spacings and directions", 65, "not allowed together",
	  mk_nrrd_spacings_and_dirs, R_NRRD },
	{ "nrrd detached from memory", 65, "detached data is not read from "
	  "memory", mk_nrrd_detached_mem, R_NRRD },
	{ "nrrd no empty line", 65, "names no data file", mk_nrrd_no_blank,
	  R_NRRD },
	{ "nrrd ascii out of range", 65, "value 3 '300' is not a u8",
	  mk_nrrd_ascii_bad, R_NRRD },
	{ "nrrd ascii too few", 65, "truncated: 59 of 60 values",
	  mk_nrrd_ascii_short,
	  R_NRRD },
	{ "nrrd gzip decompresses short", 65, "truncated", mk_nrrd_gz_short,
	  R_NRRD },
	{ "nrrd gzip decompresses long", 65, "gzip data longer",
	  mk_nrrd_gz_long, R_NRRD },
	{ "nrrd gzip cut", 65, "compressed data ends early", mk_nrrd_gz_cut,
	  R_NRRD },
	{ "nrrd gzip corrupt", 65, "gzip: corrupt data", mk_nrrd_gz_corrupt,
	  R_NRRD },
	{ "nrrd gzip crc", 65, "gzip: corrupt data", mk_nrrd_gz_crc, R_NRRD },
	{ "nrrd raw data too long", 65, "data longer than sizes",
	  mk_nrrd_long_raw, R_NRRD },
	{ "nifti truncated", 65, "truncated", mk_nii_truncated, R_NII },
	{ "nifti too long", 65, "more than 4096 bytes follow", mk_nii_long,
	  R_NII },
	{ "nifti dim[0] 0", 65, "dim[0] = 0", mk_nii_dim0, R_NII },
	{ "nifti negative dim", 65, "dim[2] = -4: must be positive",
	  mk_nii_dim_neg, R_NII },
	{ "nifti 4D", 65, "dim[4] = 2", mk_nii_dim4, R_NII },
	{ "nifti RGB", 65, "datatype 128 (RGB24) is not supported", mk_nii_dtype,
	  R_NII },
	{ "nifti bitpix", 65, "bitpix 8 does not match", mk_nii_bitpix, R_NII },
	{ "nifti vox_offset small", 65, "vox_offset 100", mk_nii_voxoff, R_NII },
	{ "nifti vox_offset fraction", 65, "vox_offset 352.5",
	  mk_nii_voxoff_frac, R_NII },
	{ "nifti magic", 65, "Analyze 7.5", mk_nii_magic, R_NII },
	{ "nifti ni1 in memory", 65, ".hdr/.img pair", mk_nii_ni1, R_NII },
	{ "nifti-2", 65, "NIfTI-2 is not supported", mk_nii_nifti2, R_NII },
	{ "nifti sizeof_hdr", 65, "sizeof_hdr is 349", mk_nii_sizeof, R_NII },
	{ "nifti oblique sform", 65, "sform: axis 1 is not aligned",
	  mk_nii_oblique, R_NII },
	{ "nifti short header", 65, "header truncated", mk_nii_short_hdr,
	  R_NII },
	{ "nifti gzip decompresses short", 65, "truncated", mk_nii_gz_short,
	  R_NII },
	{ "nifti gzip decompresses long", 65, "more than 4096 bytes follow",
	  mk_nii_gz_long, R_NII },
	{ "vtk truncated", 65, "truncated", mk_vtk_truncated, R_VTK },
	{ "vtk point count", 65, "POINT_DATA 61 does not match", mk_vtk_npts,
	  R_VTK },
	{ "vtk zero dims", 65, "DIMENSIONS: expected 3 positive integers",
	  mk_vtk_zero, R_VTK },
	{ "vtk bad type", 65, "type 'bit' is not supported", mk_vtk_type,
	  R_VTK },
	{ "vtk dataset", 65, "only STRUCTURED_POINTS", mk_vtk_grid, R_VTK },
	{ "vtk vectors", 65, "expected SCALARS, got VECTORS", mk_vtk_vectors,
	  R_VTK },
	{ "vtk components", 65, "3 components", mk_vtk_ncomp, R_VTK },
	{ "vtk ascii word", 65, "'abc' is not a number", mk_vtk_ascii_word,
	  R_VTK },
	{ "vtk mode", 65, "expected ASCII or BINARY", mk_vtk_mode, R_VTK },
	{ "vtk overflowing origin", 65, "ORIGIN: expected 3 numbers",
	  mk_vtk_inf_origin, R_VTK },
	{ "nrrd hexadecimal spacing", 65, "spacings: '0x1p-1' is not a number",
	  mk_nrrd_hex_spacing, R_NRRD },
	{ "nrrd overflowing spacing", 65, "spacings: '1e999' is not a number",
	  mk_nrrd_inf_spacing, R_NRRD },
	{ "raw short", 65, "truncated", mk_raw_short, R_RAW },
	{ "raw long", 65, "input is longer", mk_raw_long, R_RAW },
	{ "raw gzip decompresses long", 65, "input is longer", mk_raw_gz_long,
	  R_RAW },
	{ "raw gzip decompresses short", 65, "truncated", mk_raw_gz_short,
	  R_RAW },
	{ "raw gzip bomb claim", 65, "can hold at most", mk_raw_gz_bomb,
	  R_RAW_HUGE },
};

static void
malformed(void **state)
{
	size_t i;

	(void)state;
	for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		buf b = { NULL, 0 };
		vx_grid g;
		vx_err e = { 0, "" };
		vx_raw_info r;
		int rc = -1;

		bad[i].make(&b);
		vx_raw_info_init(&r);
		r.dims[0] = 5;
		r.dims[1] = 4;
		r.dims[2] = 3;
		r.type = VX_S_U16;
		switch (bad[i].format) {
		case R_NRRD:
			rc = vx_import_nrrd_mem(&g, b.p, b.n, NULL, &e);
			break;
		case R_NII:
			rc = vx_import_nifti_mem(&g, b.p, b.n, &e);
			break;
		case R_VTK:
			rc = vx_import_vtk_mem(&g, b.p, b.n, &e);
			break;
		case R_RAW_HUGE:
			r.dims[0] = r.dims[1] = 1024;
			r.dims[2] = 1024;
			r.type = VX_S_F32;
			/* fall through */
		case R_RAW:
			rc = vx_import_raw_mem(&g, b.p, b.n, &r, &e);
			break;
		}
		if (rc != bad[i].code || strstr(e.msg, bad[i].msg) == NULL)
			fail_msg("%s: got %d '%s', want %d '%s'", bad[i].name, rc,
			    e.msg, bad[i].code, bad[i].msg);
		/* a failed import leaves an empty grid */
		assert_null(g.data);
		free(b.p);
	}
}

/* detached data that is missing, short, or in the wrong count */
static void
detached_errors(void **state)
{
	static const struct {
		const char *name, *hdr;
		int code;
		const char *msg;
	} t[] = {
		{ "missing file", "data file: nosuch.raw\n", 66,
		  "nosuch.raw: No such file or directory" },
		{ "short file", "data file: short.raw\n", 65, "cannot hold" },
		{ "LIST count", "data file: LIST\nshort.raw\nshort.raw\n", 65,
		  "expected 3 files" },
		{ "pattern two conversions", "data file: a%d%d.raw 1 3 1\n", 65,
		  "only one %d" },
		{ "pattern bad step", "data file: a%d.raw 1 3 -1\n", 65,
		  "does not go from 1 to 3" },
	};
	size_t i;

	(void)state;
	write_file("short.raw", "abcdefghij", 10);
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		buf b = { NULL, 0 };
		vx_grid g;
		vx_err e = { 0, "" };
		vx_import_opts o;
		int rc;

		nrrd_head(&b, "uchar", "5 4 3", "raw");
		putf(&b, "%s", t[i].hdr);
		write_file("det.nhdr", b.p, b.n);
		vx_import_opts_init(&o);
		rc = vx_import_file(&g, tpath("det.nhdr"), &o, &e);
		if (rc != t[i].code || strstr(e.msg, t[i].msg) == NULL)
			fail_msg("%s: got %d '%s', want %d '%s'", t[i].name, rc,
			    e.msg, t[i].code, t[i].msg);
		free(b.p);
	}
}

/* ---- detection and the file wrapper ---- */

static void
detection(void **state)
{
	buf n = { NULL, 0 }, z;
	unsigned char h[348];
	double sp[3], org[3];
	int flipx;
	static const nii_case c = { NII("", 2, 8, VX_S_U8), .big = 1 };

	(void)state;
	assert_int_equal(vx_import_detect("NRRD0004\n", 9, NULL),
	    VX_FORMAT_NRRD);
	assert_int_equal(vx_import_detect("# vtk DataFile Version 2.0\n", 27,
	    "x.nrrd"), VX_FORMAT_VTK);
	nii_header(h, &c, sp, org, &flipx);   /* big-endian header */
	assert_int_equal(vx_import_detect(h, 348, NULL), VX_FORMAT_NIFTI);
	putf(&n, "NRRD0001\n");
	z = gz(n.p, n.n);
	assert_int_equal(vx_import_detect(z.p, z.n, NULL), VX_FORMAT_NRRD);
	assert_int_equal(vx_import_detect("xxxx", 4, "a/b.NII.GZ"),
	    VX_FORMAT_NIFTI);
	assert_int_equal(vx_import_detect("xxxx", 4, "a.raw"), VX_FORMAT_RAW);
	assert_int_equal(vx_import_detect("xxxx", 4, "a.txt"),
	    VX_FORMAT_UNKNOWN);
	assert_int_equal(vx_import_detect("xxxx", 4, NULL), VX_FORMAT_UNKNOWN);
	free(n.p);
	free(z.p);
	{
		vx_grid g;
		vx_err e = { 0, "" };
		vx_import_opts o;

		vx_import_opts_init(&o);
		assert_int_equal(vx_import_file(&g, tpath("nonexistent.nrrd"),
		    &o, &e), VX_ENOINPUT);
		assert_non_null(strstr(e.msg, "nonexistent.nrrd"));
		write_file("stream.vx", "\x89VXL\r\n\x1a\n", 8);
		assert_int_equal(vx_import_file(&g, tpath("stream.vx"), &o,
		    &e), VX_EDATA);
		assert_non_null(strstr(e.msg, "voxlux stream already"));
		write_file("mystery.dat", "hello", 5);
		assert_int_equal(vx_import_file(&g, tpath("mystery.dat"), &o,
		    &e), VX_EDATA);
		assert_non_null(strstr(e.msg, "unknown format"));
		write_file("empty.nrrd", "", 0);
		assert_int_equal(vx_import_file(&g, tpath("empty.nrrd"), &o,
		    &e), VX_ENOINPUT);
	}
	assert_int_equal(vx_scalar_target(VX_S_I8), VX_I16);
}

/* ---- the real template from mricron-data, when installed ---- */

static void
ch2_template(void **state)
{
	const char *path = "/usr/share/mricron/templates/ch2.nii.gz";
	vx_grid g;
	vx_err e = { 0, "" };
	vx_import_opts o;

	(void)state;
	if (access(path, R_OK) != 0) {
		skip();
		return;
	}
	vx_import_opts_init(&o);
	/* oracle: the data README (header fields read with nibabel-free
	 * tools: sform rows (1,0,0,-90) (0,1,0,-125) (0,0,1,-71)) */
	assert_int_equal(vx_import_file(&g, path, &o, &e), 0);
	assert_int_equal(g.dims[0], 181);
	assert_int_equal(g.dims[1], 217);
	assert_int_equal(g.dims[2], 181);
	assert_int_equal(g.type, VX_U8);
	assert_true(g.has_range && g.vmin == 0 && g.vmax == 254);
	for (int a = 0; a < 3; a++)
		assert_true(g.spacing[a] == 1);
	assert_true(g.origin[0] == -90 && g.origin[1] == -125 &&
	    g.origin[2] == -71);
	vx_grid_free(&g);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(nrrd_variants),
		cmocka_unit_test(nii_variants),
		cmocka_unit_test(vtk_variants),
		cmocka_unit_test(raw_variants),
		cmocka_unit_test(gzip_members),
		cmocka_unit_test(synth_fields),
		cmocka_unit_test(malformed),
		cmocka_unit_test(detached_errors),
		cmocka_unit_test(detection),
		cmocka_unit_test(ch2_template),
	};

	return cmocka_run_group_tests(tests, helper_tmp_setup,
	    helper_tmp_teardown);
}
