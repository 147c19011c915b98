/* import_vtk.c: VTK legacy files, DATASET STRUCTURED_POINTS with one
 * scalar point array, ASCII or BINARY (big-endian). */
#include "import_priv.h"

#include <string.h>

#define VTK_HDR_MAX ((size_t)1 << 16)

/* a cursor over the header window; tokens are blank-separated, lines end
 * in "\n" */
typedef struct cur {
	const unsigned char *p;
	size_t n, i;
	int at_end;                 /* the window holds the rest of the input */
} cur;

static int
space(unsigned char c)
{
	return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' ||
	    c == '\v';
}

/* tok: the next token, or 0 when the window ends. */
static int
tok(cur *c, const char **t, size_t *tl)
{
	while (c->i < c->n && space(c->p[c->i]))
		c->i++;
	if (c->i == c->n)
		return 0;
	*t = (const char *)c->p + c->i;
	while (c->i < c->n && !space(c->p[c->i]))
		c->i++;
	*tl = (size_t)((const char *)c->p + c->i - *t);
	return 1;
}

static int
tok_num(cur *c, double *v)
{
	const char *t;
	size_t tl;

	return tok(c, &t, &tl) && vx_imp_parse_f64(t, tl, v) == 0;
}

static int
tok_int(cur *c, int64_t *v)
{
	const char *t;
	size_t tl;

	return tok(c, &t, &tl) && vx_imp_parse_i64(t, tl, v) == 0;
}

/* line: the next line (for the fixed first lines). */
static int
line(cur *c, const char **l, size_t *ll)
{
	size_t pos = c->i;

	if (!vx_imp_next_line(c->p, c->n, &pos, c->at_end, l, ll))
		return 0;
	c->i = pos;
	return 1;
}

static const vx_enum_name vtk_type_names[] = {
	{ "unsigned_char", VX_S_U8 }, { "char", VX_S_I8 },
	{ "signed_char", VX_S_I8 },
	{ "unsigned_short", VX_S_U16 }, { "short", VX_S_I16 },
	{ "unsigned_int", VX_S_U32 }, { "int", VX_S_I32 },
	/* LP64: VTK writes long as 8 bytes on 64-bit Unix */
	{ "unsigned_long", VX_S_U64 }, { "long", VX_S_I64 },
	{ "unsigned_long_long", VX_S_U64 }, { "long_long", VX_S_I64 },
	/* the legacy writer writes vtkIdType arrays as int */
	{ "vtkIdType", VX_S_I32 },
	{ "vtktypeint8", VX_S_I8 }, { "vtktypeuint8", VX_S_U8 },
	{ "vtktypeint16", VX_S_I16 }, { "vtktypeuint16", VX_S_U16 },
	{ "vtktypeint32", VX_S_I32 }, { "vtktypeuint32", VX_S_U32 },
	{ "vtktypeint64", VX_S_I64 }, { "vtktypeuint64", VX_S_U64 },
	{ "float", VX_S_F32 }, { "double", VX_S_F64 },
	{ "vtktypefloat32", VX_S_F32 }, { "vtktypefloat64", VX_S_F64 },
	{ NULL, VX_SCALAR_UNKNOWN }
};
const vx_enum vx_imp_vtk_types = { "VTK data type", vtk_type_names, "?", 1 };

static int
vtk_read(vx_grid *g, vx_imp_src *s, vx_err *e)
{
	int64_t dims[3] = { 0, 0, 0 }, npts = -1, ncomp = 1;
	double sp[3] = { 1, 1, 1 }, org[3] = { 0, 0, 0 };
	int binary, have_dims = 0, rc, a;
	uint64_t total, bytes;
	const char *l, *t;
	size_t ll, tl;
	vx_scalar st = VX_SCALAR_UNKNOWN;
	vx_imp_frame f;
	vx_imp_conv c;
	cur k;

	if ((rc = vx_imp_peek(s, VTK_HDR_MAX, &k.p, &k.n, e)) != 0)
		return rc;
	k.i = 0;
	k.at_end = k.n < VTK_HDR_MAX;
	if (!line(&k, &l, &ll) || ll < 14 || memcmp(l, "# vtk DataFile", 14))
		return vx_err_set(e, VX_EDATA, "vtk: not a VTK legacy file (no "
		    "'# vtk DataFile' line)");
	if (!line(&k, &l, &ll))
		return vx_err_set(e, VX_EDATA, "vtk: header truncated after the "
		    "first line");
	/* after the title line, tokens (VTK's own reader skips blank lines
	 * here, and files such as VTKData's ironProt.vtk have them) */
	if (!tok(&k, &t, &tl))
		return vx_err_set(e, VX_EDATA, "vtk: header truncated before "
		    "ASCII or BINARY");
	if (vx_imp_word_eq(t, tl, "ascii"))
		binary = 0;
	else if (vx_imp_word_eq(t, tl, "binary"))
		binary = 1;
	else
		return vx_err_set(e, VX_EDATA, "vtk: expected ASCII or BINARY "
		    "after the title, got '%s'", vx_imp_show(t, tl));
	if (!tok(&k, &t, &tl) || !vx_imp_word_eq(t, tl, "dataset"))
		return vx_err_set(e, VX_EDATA, "vtk: expected DATASET");
	if (!tok(&k, &t, &tl))
		return vx_err_set(e, VX_EDATA, "vtk: DATASET: missing type");
	if (!vx_imp_word_eq(t, tl, "structured_points"))
		return vx_err_set(e, VX_EDATA, "vtk: DATASET %s: only "
		    "STRUCTURED_POINTS volumes are read", vx_imp_show(t, tl));
	/* geometry keywords in any order, then POINT_DATA */
	for (;;) {
		if (!tok(&k, &t, &tl))
			return vx_err_set(e, VX_EDATA, "vtk: header ends before "
			    "POINT_DATA");
		if (vx_imp_word_eq(t, tl, "dimensions")) {
			for (a = 0; a < 3; a++)
				if (!tok_int(&k, &dims[a]) || dims[a] < 1)
					return vx_err_set(e, VX_EDATA, "vtk: "
					    "DIMENSIONS: expected 3 positive "
					    "integers");
			have_dims = 1;
		} else if (vx_imp_word_eq(t, tl, "spacing") ||
		    vx_imp_word_eq(t, tl, "aspect_ratio")) {
			for (a = 0; a < 3; a++)
				if (!tok_num(&k, &sp[a]))
					return vx_err_set(e, VX_EDATA, "vtk: "
					    "SPACING: expected 3 numbers");
		} else if (vx_imp_word_eq(t, tl, "origin")) {
			for (a = 0; a < 3; a++)
				if (!tok_num(&k, &org[a]))
					return vx_err_set(e, VX_EDATA, "vtk: "
					    "ORIGIN: expected 3 numbers");
		} else if (vx_imp_word_eq(t, tl, "point_data")) {
			if (!tok_int(&k, &npts) || npts < 1)
				return vx_err_set(e, VX_EDATA, "vtk: POINT_DATA: "
				    "expected a positive count");
			break;
		} else if (vx_imp_word_eq(t, tl, "cell_data") ||
		    vx_imp_word_eq(t, tl, "field"))
			return vx_err_set(e, VX_EDATA, "vtk: %s before "
			    "POINT_DATA is not supported", vx_imp_show(t, tl));
		else
			return vx_err_set(e, VX_EDATA, "vtk: unknown keyword "
			    "'%s'", vx_imp_show(t, tl));
	}
	if (!have_dims)
		return vx_err_set(e, VX_EDATA, "vtk: DIMENSIONS: missing");
	if ((rc = vx_imp_total(dims, 1, &total, &bytes, "vtk: DIMENSIONS",
	    e)) != 0)
		return rc;
	if ((uint64_t)npts != total)
		return vx_err_set(e, VX_EDATA, "vtk: POINT_DATA %lld does not "
		    "match DIMENSIONS %lld x %lld x %lld", (long long)npts,
		    (long long)dims[0], (long long)dims[1], (long long)dims[2]);
	if (!tok(&k, &t, &tl))
		return vx_err_set(e, VX_EDATA, "vtk: POINT_DATA: no array");
	if (!vx_imp_word_eq(t, tl, "scalars"))
		return vx_err_set(e, VX_EDATA, "vtk: POINT_DATA: expected "
		    "SCALARS, got %s (only scalar fields are read)",
		    vx_imp_show(t, tl));
	if (!tok(&k, &t, &tl))
		return vx_err_set(e, VX_EDATA, "vtk: SCALARS: missing name");
	if (!tok(&k, &t, &tl))
		return vx_err_set(e, VX_EDATA, "vtk: SCALARS: missing type");
	st = (vx_scalar)vx_enum_val_n(&vx_imp_vtk_types, t, tl);
	if (st == VX_SCALAR_UNKNOWN)
		return vx_err_set(e, VX_EDATA, "vtk: SCALARS: type '%s' is not "
		    "supported", vx_imp_show(t, tl));
	/* optional component count, then LOOKUP_TABLE name */
	if (!tok(&k, &t, &tl))
		return vx_err_set(e, VX_EDATA, "vtk: SCALARS: expected "
		    "LOOKUP_TABLE");
	if (!vx_imp_word_eq(t, tl, "lookup_table")) {
		if (vx_imp_parse_i64(t, tl, &ncomp) != 0)
			return vx_err_set(e, VX_EDATA, "vtk: SCALARS: expected a "
			    "component count or LOOKUP_TABLE, got '%s'",
			    vx_imp_show(t, tl));
		if (ncomp != 1)
			return vx_err_set(e, VX_EDATA, "vtk: SCALARS: %lld "
			    "components: only 1 is supported", (long long)ncomp);
		if (!tok(&k, &t, &tl) || !vx_imp_word_eq(t, tl, "lookup_table"))
			return vx_err_set(e, VX_EDATA, "vtk: SCALARS: expected "
			    "LOOKUP_TABLE");
	}
	if (!tok(&k, &t, &tl))
		return vx_err_set(e, VX_EDATA, "vtk: LOOKUP_TABLE: missing name");
	if (binary) {
		/* the samples start after the end of this line */
		while (k.i < k.n && k.p[k.i] != '\n')
			k.i++;
		if (k.i == k.n)
			return vx_err_set(e, VX_EDATA, "vtk: header ends before "
			    "the binary data");
		k.i++;
	}
	if ((rc = vx_imp_frame_plain(&f, sp, org, dims, "vtk: SPACING", e)) != 0)
		return rc;
	bytes = total * vx_scalar_size(st);
	if ((rc = vx_imp_skip(s, k.i, e)) != 0)
		return rc;
	if ((rc = vx_imp_need(s, binary ? bytes : 2 * total - 1, "vtk: data",
	    e)) != 0)
		return rc;
	if ((rc = vx_imp_conv_begin(&c, g, dims, st, 1, &f, NULL, e)) != 0)
		return rc;
	rc = binary ? vx_imp_conv_binary(&c, s, e) : vx_imp_conv_ascii(&c, s, e);
	if (rc == 0)
		rc = vx_imp_conv_end(&c, e);
	vx_imp_conv_abort(&c);
	if (rc != 0)
		return vx_err_push(e, "vtk: data");
	/* later sections (more arrays, metadata) are ignored, and not
	 * decompressed beyond the slack */
	return 0;
}

int
vx_import_vtk_mem(vx_grid *g, const void *buf, size_t n, vx_err *e)
{
	vx_imp_src s;
	int rc;

	vx_grid_init(g);
	if ((rc = vx_imp_src_auto(&s, buf, n, e)) != 0)
		return rc;
	rc = vtk_read(g, &s, e);
	if (rc == 0) {
		int more;

		/* a gzip stream ending within the slack gets its CRC checked */
		rc = vx_imp_trailing(&s, IMP_SLACK, &more, e);
		if (rc != 0)
			vx_err_push(e, "vtk");
	}
	vx_imp_src_close(&s);
	if (rc != 0)
		vx_grid_free(g);
	return rc;
}
