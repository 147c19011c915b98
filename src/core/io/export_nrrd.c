/* export_nrrd.c: NRRD0004 files (attached header, raw or gzip) from volumes.
 * Format: http://teem.sourceforge.net/nrrd/format.html.  Readers in mind:
 * Teem (unu), ITK (3D Slicer) and VTK's vtkNrrdReader (ParaView), which
 * splits "space directions" on spaces, so vectors carry none inside. */
#include "vx_export.h"

#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>


/* Output pieces handed to zlib and fwrite at a time (zlib counts in uInt). */
#define OUTBUF ((size_t)1 << 16)

const char *
vx_nrrd_type(vx_type t)
{
	switch (t) {
	case VX_U8: return "uint8";
	case VX_U16: return "uint16";
	case VX_I16: return "int16";
	case VX_F32: return "float";
	default: return NULL;
	}
}

/* ---- the body sink: raw bytes or a gzip member ---- */

typedef struct sink {
	FILE *f;
	int gzip;
	z_stream zs;
	unsigned char out[OUTBUF];
} sink;

static int
put(FILE *f, const void *p, size_t n, vx_err *e)
{
	if (n > 0 && fwrite(p, 1, n, f) != n)
		return vx_err_set(e, VX_EIO, "write: %s",
		    errno ? strerror(errno) : "short write");
	return 0;
}

static int
sink_open(sink *s, FILE *f, int gzip, int level, vx_err *e)
{
	memset(&s->zs, 0, sizeof s->zs);
	s->f = f;
	s->gzip = gzip;
	/* windowBits 15 + 16: a gzip wrapper (RFC 1952), mtime 0, no name */
	if (gzip && deflateInit2(&s->zs, level > 0 && level <= 9 ? level :
	    Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8,
	    Z_DEFAULT_STRATEGY) != Z_OK)
		return vx_err_set(e, VX_EINTERNAL, "zlib: deflateInit2 failed");
	return 0;
}

/* sink_deflate: run deflate over what is in zs with `flush`, writing every
 * full or final output buffer. */
static int
sink_deflate(sink *s, int flush, vx_err *e)
{
	int zr, rc;

	do {
		s->zs.next_out = s->out;
		s->zs.avail_out = (uInt)sizeof s->out;
		zr = deflate(&s->zs, flush);
		if (zr == Z_STREAM_ERROR)
			return vx_err_set(e, VX_EINTERNAL, "zlib: deflate failed");
		if ((rc = put(s->f, s->out, sizeof s->out - s->zs.avail_out,
		    e)) != 0)
			return rc;
	} while (s->zs.avail_out == 0 || (flush == Z_FINISH &&
	    zr != Z_STREAM_END));
	return 0;
}

static int
sink_write(sink *s, const unsigned char *p, size_t n, vx_err *e)
{
	if (!s->gzip)
		return put(s->f, p, n, e);
	while (n > 0) {
		size_t k = n > OUTBUF ? OUTBUF : n;
		int rc;

		s->zs.next_in = (Bytef *)(uintptr_t)p;
		s->zs.avail_in = (uInt)k;
		if ((rc = sink_deflate(s, Z_NO_FLUSH, e)) != 0)
			return rc;
		p += k;
		n -= k;
	}
	return 0;
}

static int
sink_close(sink *s, int ok, vx_err *e)
{
	int rc = 0;

	if (s->gzip) {
		if (ok) {
			s->zs.next_in = NULL;
			s->zs.avail_in = 0;
			rc = sink_deflate(s, Z_FINISH, e);
		}
		deflateEnd(&s->zs);
	}
	return rc;
}

/* ---- header ---- */

/* put_comment: "# line\n" with control characters replaced by '?', so a
 * history line cannot end the header or hide a field. */
static void
put_comment(FILE *f, const char *line)
{
	fputs("# ", f);
	for (; *line != '\0'; line++)
		fputc((unsigned char)*line < 0x20 || *line == 0x7f ? '?' : *line,
		    f);
	fputc('\n', f);
}

/* put_escaped: a key or value of a "key:=value" line, with NRRD's escapes
 * for backslash and newline (other control characters become '?') */
static void
put_escaped(FILE *f, const char *s)
{
	for (; *s != '\0'; s++) {
		unsigned char ch = (unsigned char)*s;

		if (ch == '\\')
			fputs("\\\\", f);
		else if (ch == '\n')
			fputs("\\n", f);
		else
			fputc(ch < 0x20 || ch == 0x7f ? '?' : ch, f);
	}
}

/* What a header describes: a scalar volume, or (rgb) a first axis of
 * ncomp components before the three space axes: 3 colour components
 * (kind RGB-color) or another count (an SH transfer's coefficients, kind
 * list). */
typedef struct nrrd_geom {
	const char *content;
	const char *type;
	int rgb;
	int ncomp;
	int64_t dims[3];
	double spacing[3];
	double origin[3];
} nrrd_geom;

static void
put_header(const nrrd_geom *g, FILE *f, const vx_nrrd_opts *o)
{
	char line[256];
	size_t i;

	fputs("NRRD0004\n", f);
	fputs("# Complete NRRD file format specification at:\n", f);
	fputs("# http://teem.sourceforge.net/nrrd/format.html\n", f);
	for (i = 0; i < o->ncomments; i++)
		put_comment(f, o->comments[i]);
	fputs("content: ", f);
	for (i = 0; g->content[i] != '\0'; i++)   /* one line, whatever the name */
		fputc((unsigned char)g->content[i] < 0x20 ? '?' : g->content[i],
		    f);
	fprintf(f, "\ntype: %s\n", g->type);
	fprintf(f, "dimension: %d\n", g->rgb ? 4 : 3);
	fputs("space: 3D-right-handed\n", f);
	if (g->rgb)
		fprintf(f, "sizes: %d %lld %lld %lld\n", g->ncomp,
		    (long long)g->dims[0], (long long)g->dims[1],
		    (long long)g->dims[2]);
	else
		fprintf(f, "sizes: %lld %lld %lld\n", (long long)g->dims[0],
		    (long long)g->dims[1], (long long)g->dims[2]);
	/* reals with a '.' whatever LC_NUMERIC says */
	vx_snprintf_c(line, sizeof line, "space directions: %s(%.17g,0,0) "
	    "(0,%.17g,0) (0,0,%.17g)\n", g->rgb ? "none " : "", g->spacing[0],
	    g->spacing[1], g->spacing[2]);
	fputs(line, f);
	fprintf(f, "kinds: %sdomain domain domain\n", !g->rgb ? "" :
	    g->ncomp == 3 ? "RGB-color " : "list ");
	fprintf(f, "centerings: %snode node node\n", g->rgb ? "??? " : "");
	fputs("endian: little\n", f);
	fprintf(f, "encoding: %s\n", o->gzip ? "gzip" : "raw");
	vx_snprintf_c(line, sizeof line, "space origin: (%.17g,%.17g,%.17g)\n",
	    g->origin[0], g->origin[1], g->origin[2]);
	fputs(line, f);
	for (i = 0; o->keys != NULL && i < o->keys->n; i++) {
		put_escaped(f, o->keys->key[i]);
		fputs(":=", f);
		put_escaped(f, o->keys->val[i]);
		fputc('\n', f);
	}
	fputc('\n', f);
}

/* begin: the header, then the body's sink; on failure row is freed. */
static int
begin(const nrrd_geom *geom, FILE *f, const vx_nrrd_opts *o, sink *s,
    void *row, vx_err *e)
{
	int rc;

	errno = 0;
	put_header(geom, f, o);
	if (ferror(f))
		rc = vx_err_set(e, VX_EIO, "write: %s",
		    errno ? strerror(errno) : "stream error");
	else if ((rc = sink_open(s, f, o->gzip, o->level, e)) == 0)
		return 0;
	free(row);
	return rc;
}

/* finish: close the sink (rc: the body's writes so far), free row, and
 * check that everything reached f. */
static int
finish(sink *s, FILE *f, void *row, int rc, vx_err *e)
{
	if (sink_close(s, rc == 0, e) != 0 && rc == 0)
		rc = e ? e->code : VX_EIO;
	free(row);
	if (rc == 0 && (fflush(f) != 0 || ferror(f)))
		rc = vx_err_set(e, VX_EIO, "write: %s",
		    errno ? strerror(errno) : "stream error");
	return rc;
}

/* ---- body ---- */

/* row_le: samples (0..nx-1, y, z) of g as little-endian bytes into buf. */
static size_t
row_le(const vx_grid *g, int64_t y, int64_t z, unsigned char *buf)
{
	size_t base = (size_t)(g->lay.off[1][y] + g->lay.off[2][z]);
	size_t ts = vx_type_size(g->type), k = 0;
	int64_t x;

	for (x = 0; x < g->dims[0]; x++, k += ts) {
		const unsigned char *p = (const unsigned char *)g->data +
		    (base + (size_t)g->lay.off[0][x]) * ts;

		memcpy(buf + k, p, ts);
	}
	if (!vx_host_is_le())
		vx_swap_bytes(buf, (size_t)g->dims[0], ts);
	return k;
}

int
vx_export_nrrd_opts(const vx_grid *g, FILE *f, const vx_nrrd_opts *o,
    vx_err *e)
{
	static const vx_nrrd_opts none;
	unsigned char *row;
	nrrd_geom geom;
	int64_t y, z;
	sink s;
	int rc = 0;

	if (o == NULL)
		o = &none;
	if (vx_nrrd_type(g->type) == NULL || g->data == NULL)
		return vx_err_set(e, VX_EINTERNAL, "nrrd: not a volume");
	if ((row = vx_malloc((size_t)g->dims[0] * vx_type_size(g->type),
	    e)) == NULL)
		return VX_ENOMEM;
	geom.content = g->name;
	geom.type = vx_nrrd_type(g->type);
	geom.rgb = 0;
	for (int a = 0; a < 3; a++) {
		geom.dims[a] = g->dims[a];
		geom.spacing[a] = g->spacing[a];
		geom.origin[a] = g->origin[a];
	}
	if ((rc = begin(&geom, f, o, &s, row, e)) != 0)
		return rc;
	for (z = 0; z < g->dims[2] && rc == 0; z++)
		for (y = 0; y < g->dims[1] && rc == 0; y++)
			rc = sink_write(&s, row, row_le(g, y, z, row), e);
	return finish(&s, f, row, rc, e);
}

int
vx_export_nrrd(const vx_grid *g, FILE *f, int gzip, vx_err *e)
{
	vx_nrrd_opts o;

	memset(&o, 0, sizeof o);
	o.gzip = gzip;
	return vx_export_nrrd_opts(g, f, &o, e);
}

/* ---- irradiance volumes ---- */

/* irr_row_le: texels (0..n0-1, j, k) of v as little-endian bytes into buf:
 * the mean RGB as binary32 (0 where not usable) or the flags as `bytes`
 * (1 or 4) each (0 where absent). */
static size_t
irr_row_le(const vx_irrvol *v, int flags, int bytes, int64_t j, int64_t k,
    unsigned char *buf)
{
	size_t n = 0;

	for (int64_t i = 0; i < v->dims[0]; i++) {
		int64_t s = vx_irr_texel(v, i, j, k);

		if (flags) {
			uint32_t x = s >= 0 ? v->flags[s] &
			    ~(uint32_t)VX_TEXEL_SAMPLED : 0;

			for (int b = 0; b < bytes; b++)
				buf[n++] = (unsigned char)(x >> (8 * b));
			continue;
		}
		for (int c = 0; c < v->ncomp; c++) {
			float m = s >= 0 && vx_irr_usable(v, s) ?
			    v->mean[(size_t)v->ncomp * (size_t)s + (size_t)c] :
			    0.0f;
			uint32_t u;

			memcpy(&u, &m, 4);
			for (int b = 0; b < 4; b++)
				buf[n++] = (unsigned char)(u >> (8 * b));
		}
	}
	return n;
}

static int
irr_export(const vx_irrvol *v, const vx_grid *g, int flags, int bytes,
    FILE *f, const vx_nrrd_opts *o, vx_err *e)
{
	static const vx_nrrd_opts none;
	unsigned char *row;
	nrrd_geom geom;
	size_t per = flags ? (size_t)bytes : 4 * (size_t)v->ncomp;
	sink s;
	int rc = 0;

	if (o == NULL)
		o = &none;
	for (int a = 0; a < 3; a++)
		if (g->dims[a] != v->vdims[a])
			return vx_err_set(e, VX_EDATA, "the volume '%s' has dims "
			    "%lld %lld %lld, its irradiance volume was laid over "
			    "%lld %lld %lld", g->name, (long long)g->dims[0],
			    (long long)g->dims[1], (long long)g->dims[2],
			    (long long)v->vdims[0], (long long)v->vdims[1],
			    (long long)v->vdims[2]);
	if (flags) {
		uint32_t lim = bytes == 1 ? 0xffu : 0xffffffffu;
		size_t n = v->nslot * VX_IRR_BRICK3;

		for (size_t t = 0; t < n; t++) {
			uint32_t x = v->flags[t] & ~(uint32_t)VX_TEXEL_SAMPLED;

			if (x > lim)
				return vx_err_set(e, VX_EDATA, "flags 0x%x do not "
				    "fit in 8 bits", (unsigned)x);
		}
	}
	geom.content = v->volume;
	geom.type = !flags ? "float" : bytes == 1 ? "uint8" : "uint32";
	geom.rgb = !flags;
	geom.ncomp = v->sh_order ? v->ncomp : 3;
	for (int a = 0; a < 3; a++) {
		geom.dims[a] = v->dims[a];
		geom.spacing[a] = v->step[a] * g->spacing[a];
		geom.origin[a] = g->origin[a];
	}
	if ((row = vx_malloc((size_t)v->dims[0] * per, e)) == NULL)
		return VX_ENOMEM;
	if ((rc = begin(&geom, f, o, &s, row, e)) != 0)
		return rc;
	for (int64_t k = 0; k < v->dims[2] && rc == 0; k++)
		for (int64_t j = 0; j < v->dims[1] && rc == 0; j++)
			rc = sink_write(&s, row, irr_row_le(v, flags, bytes, j,
			    k, row), e);
	return finish(&s, f, row, rc, e);
}

int
vx_export_nrrd_irr(const vx_irrvol *v, const vx_grid *g, FILE *f,
    const vx_nrrd_opts *o, vx_err *e)
{
	return irr_export(v, g, 0, 0, f, o, e);
}

int
vx_export_nrrd_irr_flags(const vx_irrvol *v, const vx_grid *g, int bytes,
    FILE *f, const vx_nrrd_opts *o, vx_err *e)
{
	if (bytes != 1 && bytes != 4)
		return vx_err_set(e, VX_EUSAGE, "flags: 1 or 4 bytes a texel, "
		    "not %d", bytes);
	return irr_export(v, g, 1, bytes, f, o, e);
}
