/* export_nrrd.c: NRRD0004 files (attached header, raw or gzip) from volumes.
 * Format: http://teem.sourceforge.net/nrrd/format.html.  Readers in mind:
 * Teem (unu), ITK (3D Slicer) and VTK's vtkNrrdReader (ParaView), which
 * splits "space directions" on spaces, so vectors carry none inside. */
#include "vx_export.h"

#include <errno.h>
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

static void
put_header(const vx_grid *g, FILE *f, const vx_nrrd_opts *o)
{
	char line[256];
	size_t i;

	fputs("NRRD0004\n", f);
	fputs("# Complete NRRD file format specification at:\n", f);
	fputs("# http://teem.sourceforge.net/nrrd/format.html\n", f);
	for (i = 0; i < o->ncomments; i++)
		put_comment(f, o->comments[i]);
	fputs("content: ", f);
	for (i = 0; g->name[i] != '\0'; i++)   /* one line, whatever the name */
		fputc((unsigned char)g->name[i] < 0x20 ? '?' : g->name[i], f);
	fprintf(f, "\ntype: %s\n", vx_nrrd_type(g->type));
	fputs("dimension: 3\n", f);
	fputs("space: 3D-right-handed\n", f);
	fprintf(f, "sizes: %lld %lld %lld\n", (long long)g->dims[0],
	    (long long)g->dims[1], (long long)g->dims[2]);
	/* reals with a '.' whatever LC_NUMERIC says */
	vx_snprintf_c(line, sizeof line, "space directions: (%.17g,0,0) "
	    "(0,%.17g,0) (0,0,%.17g)\n", g->spacing[0], g->spacing[1],
	    g->spacing[2]);
	fputs(line, f);
	fputs("kinds: domain domain domain\n", f);
	fputs("centerings: node node node\n", f);
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
	errno = 0;
	put_header(g, f, o);
	if (ferror(f)) {
		free(row);
		return vx_err_set(e, VX_EIO, "write: %s",
		    errno ? strerror(errno) : "stream error");
	}
	if ((rc = sink_open(&s, f, o->gzip, o->level, e)) != 0) {
		free(row);
		return rc;
	}
	for (z = 0; z < g->dims[2] && rc == 0; z++)
		for (y = 0; y < g->dims[1] && rc == 0; y++)
			rc = sink_write(&s, row, row_le(g, y, z, row), e);
	if (sink_close(&s, rc == 0, e) != 0 && rc == 0)
		rc = e ? e->code : VX_EIO;
	free(row);
	if (rc == 0 && (fflush(f) != 0 || ferror(f)))
		rc = vx_err_set(e, VX_EIO, "write: %s",
		    errno ? strerror(errno) : "stream error");
	return rc;
}

int
vx_export_nrrd(const vx_grid *g, FILE *f, int gzip, vx_err *e)
{
	vx_nrrd_opts o;

	memset(&o, 0, sizeof o);
	o.gzip = gzip;
	return vx_export_nrrd_opts(g, f, &o, e);
}
