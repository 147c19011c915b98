/* import_vtk.c: VTK legacy files, DATASET STRUCTURED_POINTS with one
 * scalar point array, ASCII or BINARY (big-endian). */
#include "import_priv.h"
#include "vx_scan.h"

#include <string.h>

#define VTK_HDR_MAX ((size_t)1 << 16)

/* is: word t (tl bytes) is keyword kw, in any case. */
static int
is(const char *t, size_t tl, const char *kw)
{
	return vx_word_eq(t, tl, kw, 1);
}

/* the geometry keywords before POINT_DATA */
enum { G_DIMENSIONS = 1, G_SPACING, G_ORIGIN, G_POINT_DATA, G_UNSUPPORTED };

static const vx_enum_name geometry_names[] = {
	{ "dimensions", G_DIMENSIONS }, { "spacing", G_SPACING },
	{ "aspect_ratio", G_SPACING }, { "origin", G_ORIGIN },
	{ "point_data", G_POINT_DATA }, { "cell_data", G_UNSUPPORTED },
	{ "field", G_UNSUPPORTED }, { NULL, 0 }
};
static const vx_enum geometry = { "keyword", geometry_names, "?", 1 };

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
	int binary, have_dims = 0, rc, a, kw;
	uint64_t total, bytes;
	const unsigned char *hdr;
	const char *l, *t;
	size_t n, ll, tl;
	vx_scalar st = VX_SCALAR_UNKNOWN;
	vx_imp_frame f;
	vx_imp_conv c;
	vx_scan k;

	if ((rc = vx_imp_peek(s, VTK_HDR_MAX, &hdr, &n, e)) != 0)
		return rc;
	vx_scan_init(&k, hdr, n);
	if (!vx_scan_line(&k, n < VTK_HDR_MAX, &l, &ll) || ll < 14 ||
	    memcmp(l, "# vtk DataFile", 14))
		return vx_err_set(e, VX_EDATA, "vtk: not a VTK legacy file (no "
		    "'# vtk DataFile' line)");
	if (!vx_scan_line(&k, n < VTK_HDR_MAX, &l, &ll))
		return vx_err_set(e, VX_EDATA, "vtk: header truncated after the "
		    "first line");
	/* after the title line, words (VTK's own reader skips blank lines
	 * here, and files such as VTKData's ironProt.vtk have them) */
	if ((tl = vx_scan_word(&k, &t)) == 0)
		return vx_err_set(e, VX_EDATA, "vtk: header truncated before "
		    "ASCII or BINARY");
	if (is(t, tl, "ascii"))
		binary = 0;
	else if (is(t, tl, "binary"))
		binary = 1;
	else
		return vx_err_set(e, VX_EDATA, "vtk: expected ASCII or BINARY "
		    "after the title, got '%s'", vx_imp_show(t, tl));
	tl = vx_scan_word(&k, &t);
	if (!is(t, tl, "dataset"))
		return vx_err_set(e, VX_EDATA, "vtk: expected DATASET");
	if ((tl = vx_scan_word(&k, &t)) == 0)
		return vx_err_set(e, VX_EDATA, "vtk: DATASET: missing type");
	if (!is(t, tl, "structured_points"))
		return vx_err_set(e, VX_EDATA, "vtk: DATASET %s: only "
		    "STRUCTURED_POINTS volumes are read", vx_imp_show(t, tl));
	/* geometry keywords in any order, then POINT_DATA */
	do {
		if ((tl = vx_scan_word(&k, &t)) == 0)
			return vx_err_set(e, VX_EDATA, "vtk: header ends before "
			    "POINT_DATA");
		switch ((kw = vx_enum_val_n(&geometry, t, tl))) {
		case G_DIMENSIONS:
			for (a = 0; a < 3; a++)
				if (vx_scan_i64(&k, 1, INT64_MAX, &dims[a]))
					return vx_err_set(e, VX_EDATA, "vtk: "
					    "DIMENSIONS: expected 3 positive "
					    "integers");
			have_dims = 1;
			break;
		case G_SPACING:
		case G_ORIGIN:
			for (a = 0; a < 3; a++)
				if (vx_scan_f64(&k, VX_NUM_NONFINITE,
				    kw == G_SPACING ? &sp[a] : &org[a]))
					return vx_err_set(e, VX_EDATA, "vtk: "
					    "%s: expected 3 numbers",
					    kw == G_SPACING ? "SPACING" :
					    "ORIGIN");
			break;
		case G_POINT_DATA:
			if (vx_scan_i64(&k, 1, INT64_MAX, &npts) != 0)
				return vx_err_set(e, VX_EDATA, "vtk: POINT_DATA: "
				    "expected a positive count");
			break;
		case G_UNSUPPORTED:
			return vx_err_set(e, VX_EDATA, "vtk: %s before "
			    "POINT_DATA is not supported", vx_imp_show(t, tl));
		default:
			return vx_err_set(e, VX_EDATA, "vtk: unknown keyword "
			    "'%s'", vx_imp_show(t, tl));
		}
	} while (kw != G_POINT_DATA);
	if (!have_dims)
		return vx_err_set(e, VX_EDATA, "vtk: DIMENSIONS: missing");
	if ((rc = vx_imp_total(dims, 1, &total, &bytes, "vtk: DIMENSIONS",
	    e)) != 0)
		return rc;
	if ((uint64_t)npts != total)
		return vx_err_set(e, VX_EDATA, "vtk: POINT_DATA %lld does not "
		    "match DIMENSIONS %lld x %lld x %lld", (long long)npts,
		    (long long)dims[0], (long long)dims[1], (long long)dims[2]);
	if ((tl = vx_scan_word(&k, &t)) == 0)
		return vx_err_set(e, VX_EDATA, "vtk: POINT_DATA: no array");
	if (!is(t, tl, "scalars"))
		return vx_err_set(e, VX_EDATA, "vtk: POINT_DATA: expected "
		    "SCALARS, got %s (only scalar fields are read)",
		    vx_imp_show(t, tl));
	if (vx_scan_word(&k, &t) == 0)
		return vx_err_set(e, VX_EDATA, "vtk: SCALARS: missing name");
	if ((tl = vx_scan_word(&k, &t)) == 0)
		return vx_err_set(e, VX_EDATA, "vtk: SCALARS: missing type");
	st = (vx_scalar)vx_enum_val_n(&vx_imp_vtk_types, t, tl);
	if (st == VX_SCALAR_UNKNOWN)
		return vx_err_set(e, VX_EDATA, "vtk: SCALARS: type '%s' is not "
		    "supported", vx_imp_show(t, tl));
	/* optional component count, then LOOKUP_TABLE name */
	if ((tl = vx_scan_word(&k, &t)) == 0)
		return vx_err_set(e, VX_EDATA, "vtk: SCALARS: expected "
		    "LOOKUP_TABLE");
	if (!is(t, tl, "lookup_table")) {
		if (vx_num_i64(t, tl, INT64_MIN, INT64_MAX, &ncomp) != 0)
			return vx_err_set(e, VX_EDATA, "vtk: SCALARS: expected a "
			    "component count or LOOKUP_TABLE, got '%s'",
			    vx_imp_show(t, tl));
		if (ncomp != 1)
			return vx_err_set(e, VX_EDATA, "vtk: SCALARS: %lld "
			    "components: only 1 is supported", (long long)ncomp);
		tl = vx_scan_word(&k, &t);
		if (!is(t, tl, "lookup_table"))
			return vx_err_set(e, VX_EDATA, "vtk: SCALARS: expected "
			    "LOOKUP_TABLE");
	}
	if (vx_scan_word(&k, &t) == 0)
		return vx_err_set(e, VX_EDATA, "vtk: LOOKUP_TABLE: missing name");
	/* binary samples start after the end of this line */
	if (binary && !vx_scan_next_line(&k))
		return vx_err_set(e, VX_EDATA, "vtk: header ends before the "
		    "binary data");
	if ((rc = vx_imp_frame_plain(&f, sp, org, dims, "vtk: SPACING", e)) != 0)
		return rc;
	bytes = total * vx_scalar_size(st);
	if ((rc = vx_imp_skip(s, (size_t)(k.p - k.base), e)) != 0)
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
