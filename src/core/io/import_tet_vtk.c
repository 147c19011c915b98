/* import_tet_vtk.c: VTK legacy DATASET UNSTRUCTURED_GRID files (ASCII or
 * BINARY big-endian; legacy CELLS lists or the 5.1 OFFSETS/CONNECTIVITY
 * form) as tet meshes with one point scalar. */
#include "vx_tetimport.h"
#include "import_priv.h"
#include "vx_scan.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define TOK 256              /* a keyword's or a name's bytes, with the NUL */

typedef struct vtkr {
	vx_scan s;
	int binary;
	int v51;                 /* CELLS as OFFSETS + CONNECTIVITY */
	vx_err *e;
} vtkr;

static int
fail(vtkr *r, const char *fmt, const char *a, const char *b)
{
	char msg[400];
	snprintf(msg, sizeof msg, fmt, a ? a : "", b ? b : "");
	return vx_err_set(r->e, VX_EDATA, "vtk: line %zu: %s",
	    vx_scan_lineno(&r->s), msg);
}

/* is: token t is keyword kw (VTK keywords are read in any case). */
static int
is(const char *t, const char *kw)
{
	return strcasecmp(t, kw) == 0;
}

/* next_i64: the next word as an integer of the file (VX_IMP_INT_MAX). */
static int
next_i64(vx_scan *s, int64_t *v)
{
	return vx_scan_i64(s, -VX_IMP_INT_MAX, VX_IMP_INT_MAX, v) == 0;
}

static int
parse_type(vtkr *r, const char *t, int *out)
{
	if ((*out = vx_enum_val(&vx_imp_vtk_types, t)) != VX_SCALAR_UNKNOWN)
		return 0;
	return fail(r, "data type '%.40s' is not supported", t, NULL);
}

/* Move past the end of the current header line: binary data starts on
 * the next byte. */
static void
end_line(vtkr *r)
{
	vx_scan_next_line(&r->s);
}

static uint64_t
be(const unsigned char *p, size_t n)
{
	uint64_t v = 0;
	for (size_t i = 0; i < n; i++)
		v = v << 8 | p[i];
	return v;
}

/* One binary value as double and as int64 (exact for the integer types). */
static void
decode(int t, const unsigned char *p, double *f, int64_t *i)
{
	uint64_t u = be(p, vx_scalar_size((vx_scalar)t));
	float f32;
	double f64;

	switch (t) {
	case VX_S_U8: case VX_S_U16: case VX_S_U32:
		*i = (int64_t)u;
		*f = (double)u;
		return;
	case VX_S_I8:
		*i = (int8_t)u;
		break;
	case VX_S_I16:
		*i = (int16_t)u;
		break;
	case VX_S_I32:
		*i = (int32_t)(uint32_t)u;
		break;
	case VX_S_U64:
		*i = u > INT64_MAX ? -1 : (int64_t)u;
		*f = (double)u;
		return;
	case VX_S_I64:
		*i = (int64_t)u;
		break;
	case VX_S_F32: {
		uint32_t w = (uint32_t)u;
		memcpy(&f32, &w, 4);
		*f = f32;
		*i = 0;
		return;
	}
	default:
		memcpy(&f64, &u, 8);
		*f = f64;
		*i = 0;
		return;
	}
	*f = (double)*i;
}

/* 1 if count values of size sz (binary) or of at least two characters
 * (ASCII: a digit and a separator) could still be in the input. */
static int
fits(vtkr *r, uint64_t count, size_t sz)
{
	size_t left = vx_scan_left(&r->s);
	return r->binary ? count <= left / sz : count <= left / 2 + 1;
}

/* read: count values of type t into fo (doubles) or io (integers; a
 * floating-point value there is an error), or skip them when both are
 * NULL.  The count is bounded by the bytes left before anything else. */
static int
read_values(vtkr *r, int t, size_t count, double *fo, int64_t *io,
    const char *what)
{
	size_t i, left = vx_scan_left(&r->s);

	if (r->binary) {
		size_t sz = vx_scalar_size((vx_scalar)t);
		if (count > left / sz)
			return fail(r, "truncated: %s needs more bytes than the "
			    "file has", what, NULL);
		const unsigned char *p = r->s.p;
		if (fo != NULL || io != NULL)
			for (i = 0; i < count; i++, p += sz) {
				double f;
				int64_t v;
				decode(t, p, &f, &v);
				if (fo != NULL)
					fo[i] = f;
				else if (t == VX_S_F32 || t == VX_S_F64) {
					if (!(f == floor(f) && fabs(f) < 9e15))
						return fail(r, "%s: a non-integer "
						    "value", what, NULL);
					io[i] = (int64_t)f;
				} else
					io[i] = v;
			}
		r->s.p += count * sz;
		return 0;
	}
	/* ASCII: every value takes at least one digit and one separator */
	if (count > left / 2 + 1)
		return fail(r, "truncated: %s needs more values than the file "
		    "has", what, NULL);
	for (i = 0; i < count; i++) {
		const char *w;
		size_t n = vx_scan_word(&r->s, &w);
		double f;
		if (n == 0)
			return fail(r, "truncated: %s ends early", what, NULL);
		if (vx_num_f64(w, n, VX_NUM_NONFINITE, &f) != 0)
			return fail(r, "%s: '%.40s' is not a number", what,
			    vx_imp_show(w, n));
		if (fo != NULL)
			fo[i] = f;
		else if (io != NULL) {
			int64_t v;
			if (vx_num_i64(w, n, -VX_IMP_INT_MAX, VX_IMP_INT_MAX,
			    &v) != 0)
				return fail(r, "%s: '%.40s' is not an integer",
				    what, vx_imp_show(w, n));
			io[i] = v;
		}
	}
	return 0;
}

/* Decode %hh escapes of VTK array names in place. */
static void
unescape(char *t)
{
	char *o = t;
	for (; *t; t++) {
		unsigned h;
		if (t[0] == '%' && sscanf(t + 1, "%2x", &h) == 1 &&
		    t[1] && t[2]) {
			*o++ = (char)h;
			t += 2;
		} else
			*o++ = *t;
	}
	*o = '\0';
}

/* the import state */
typedef struct vtkimp {
	vtkr r;
	const vx_tetimport_opt *opt;
	vx_tetimport_info *info;
	int64_t npoint;          /* -1 until POINTS */
	double *pts;
	int64_t ncell, nconn;    /* -1 until CELLS */
	int64_t *conn;           /* legacy: the CELLS lists; 5.1: connectivity */
	int64_t *offs;           /* 5.1: ncell + 1 offsets */
	int64_t ntype;
	int64_t *ctype;
	double *val;             /* the chosen point scalar */
	char valname[VX_TETMESH_NAME];
} vtkimp;

/* An array of n tuples x ncomp in attribute data (mode 'p' point data,
 * 'c' cell data): read it into val when it is the chosen point scalar,
 * else skip it. */
static int
attr_array(vtkimp *v, int mode, const char *name, int t, int64_t n,
    int64_t ncomp, const char *what)
{
	vtkr *r = &v->r;
	int want = 0;
	size_t count;

	if (ncomp < 1 || ncomp > 1 << 20 || n < 0 || n > (int64_t)1 << 40)
		return fail(r, "%s: bad component or tuple count", what, NULL);
	count = (size_t)(n * ncomp);
	if (!fits(r, count, vx_scalar_size((vx_scalar)t)))
		return fail(r, "truncated: %s needs more data than the file has",
		    what, NULL);
	if (mode == 'p' && ncomp == 1 && v->info)
		v->info->narray++;
	if (mode == 'p' && v->val == NULL) {
		const char *sel = v->opt ? v->opt->scalar : NULL;
		if (sel == NULL ? ncomp == 1 : strcmp(sel, name) == 0) {
			if (ncomp != 1)
				return fail(r, "array '%.60s' has several "
				    "components (need one)", name, NULL);
			want = 1;
		}
	}
	if (!want)
		return read_values(r, t, count, NULL, NULL, what);
	if ((v->val = vx_malloc(count * sizeof *v->val, r->e)) == NULL)
		return VX_ENOMEM;
	snprintf(v->valname, sizeof v->valname, "%.*s",
	    (int)sizeof v->valname - 1, name);
	return read_values(r, t, count, v->val, NULL, what);
}

/* FIELD name narrays: each "name ncomp ntuples type" then the values. */
static int
field(vtkimp *v, int mode, int64_t ntuple)
{
	vtkr *r = &v->r;
	char tok[TOK], name[TOK];
	int64_t narr, nc, nt;
	int t, rc;

	if (vx_scan_token(&r->s, tok, TOK) <= 0 || !next_i64(&r->s, &narr) ||
	    narr < 0 || narr > 1 << 20)
		return fail(r, "FIELD: expected a name and an array count", NULL,
		    NULL);
	end_line(r);
	for (int64_t a = 0; a < narr; a++) {
		if (vx_scan_token(&r->s, name, TOK) <= 0)
			return fail(r, "FIELD: truncated", NULL, NULL);
		if (is(name, "METADATA")) {
			/* belongs to the previous array: skip to a blank line */
			end_line(r);
			while (r->s.p < r->s.end && !vx_scan_eol(&r->s))
				end_line(r);
			end_line(r);
			a--;
			continue;
		}
		if (!next_i64(&r->s, &nc) || !next_i64(&r->s, &nt) ||
		    vx_scan_token(&r->s, tok, TOK) <= 0)
			return fail(r, "FIELD array '%.60s': expected components, "
			    "tuples and type", name, NULL);
		if ((rc = parse_type(r, tok, &t)) != 0)
			return rc;
		end_line(r);
		unescape(name);
		if ((rc = attr_array(v, mode == 'p' && nt == ntuple ? 'p' : 'x',
		    name, t, nt, nc, "FIELD array")) != 0)
			return rc;
	}
	return 0;
}

/* index_array: "KW type", then n integers into *out (allocated here); a
 * 5.1 file's OFFSETS and CONNECTIVITY, which follow after. */
static int
index_array(vtkr *r, const char *kw, const char *after, int64_t n,
    int64_t **out)
{
	char tok[TOK];
	int t, rc;

	if (vx_scan_token(&r->s, tok, TOK) <= 0 || !is(tok, kw) ||
	    vx_scan_token(&r->s, tok, TOK) <= 0)
		return fail(r, "expected %s after %s", kw, after);
	if ((rc = parse_type(r, tok, &t)) != 0)
		return rc;
	end_line(r);
	if (!fits(r, (uint64_t)n, vx_scalar_size((vx_scalar)t)))
		return fail(r, "truncated: %s", kw, NULL);
	if ((*out = vx_malloc((size_t)n * sizeof **out, r->e)) == NULL)
		return VX_ENOMEM;
	return read_values(r, t, (size_t)n, NULL, *out, kw);
}

static int
cells(vtkimp *v, int64_t a, int64_t b)
{
	vtkr *r = &v->r;
	int rc;

	if (v->ncell >= 0)
		return fail(r, "CELLS given twice", NULL, NULL);
	if (a < 0 || b < 0 || a > (int64_t)1 << 40 || b > (int64_t)1 << 40)
		return fail(r, "CELLS: bad counts", NULL, NULL);
	if (!r->v51) {
		v->ncell = a;
		v->nconn = b;
		end_line(r);
		if (!fits(r, (uint64_t)b, 4))
			return fail(r, "truncated: CELLS needs more data than the "
			    "file has", NULL, NULL);
		if ((v->conn = vx_malloc((size_t)b * sizeof *v->conn, r->e)) ==
		    NULL)
			return VX_ENOMEM;
		return read_values(r, VX_S_I32, (size_t)b, NULL, v->conn, "CELLS");
	}
	/* 5.1: CELLS noffsets nconnectivity, then OFFSETS and CONNECTIVITY */
	if (a < 1)
		return fail(r, "CELLS: need at least one offset", NULL, NULL);
	v->ncell = a - 1;
	v->nconn = b;
	end_line(r);
	if ((rc = index_array(r, "OFFSETS", "CELLS", a, &v->offs)) != 0)
		return rc;
	return index_array(r, "CONNECTIVITY", "OFFSETS", b, &v->conn);
}

/* VTK cell types: dimension (0..3) or -1 unknown; names of volume cells
 * for messages. */
static int
cell_dim(int64_t t, const char **name)
{
	static const struct { int t; const char *n; } vol[] = {
		{ 10, "tetra" }, { 11, "voxel" }, { 12, "hexahedron" },
		{ 13, "wedge" }, { 14, "pyramid" }, { 15, "pentagonal prism" },
		{ 16, "hexagonal prism" }, { 24, "quadratic tetra" },
		{ 25, "quadratic hexahedron" }, { 26, "quadratic wedge" },
		{ 27, "quadratic pyramid" }, { 29, "triquadratic hexahedron" },
		{ 31, "quadratic linear wedge" },
		{ 32, "biquadratic quadratic wedge" },
		{ 33, "biquadratic quadratic hexahedron" },
		{ 37, "triquadratic pyramid" }, { 42, "polyhedron" },
		{ 71, "Lagrange tetrahedron" }, { 72, "Lagrange hexahedron" },
		{ 73, "Lagrange wedge" }, { 74, "Lagrange pyramid" },
		{ 78, "Bezier tetrahedron" }, { 79, "Bezier hexahedron" },
		{ 80, "Bezier wedge" }, { 81, "Bezier pyramid" },
	};
	static const int lower[] = {
		0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 21, 22, 23, 28, 30, 34, 35, 36,
		68, 69, 70, 75, 76, 77,
	};
	size_t i;

	*name = NULL;
	for (i = 0; i < sizeof vol / sizeof vol[0]; i++)
		if (vol[i].t == t) {
			*name = vol[i].n;
			return 3;
		}
	for (i = 0; i < sizeof lower / sizeof lower[0]; i++)
		if (lower[i] == t)
			return 1;
	return -1;
}

/* Turn cells into the mesh: count tets, check, fill. */
static int
build(vtkimp *v, vx_tetmesh *m)
{
	vtkr *r = &v->r;
	vx_err *e = r->e;
	int64_t c, pos = 0, ntet = 0;
	int pass;

	if (v->ntype != v->ncell)
		return vx_err_set(e, VX_EDATA, "vtk: CELL_TYPES has %lld cells, "
		    "CELLS %lld", (long long)v->ntype, (long long)v->ncell);
	if (v->offs != NULL) {
		if (v->offs[0] != 0 || v->offs[v->ncell] != v->nconn)
			return vx_err_set(e, VX_EDATA, "vtk: OFFSETS must run "
			    "from 0 to the connectivity size %lld",
			    (long long)v->nconn);
		for (c = 0; c < v->ncell; c++)
			if (v->offs[c + 1] < v->offs[c])
				return vx_err_set(e, VX_EDATA, "vtk: OFFSETS "
				    "decrease at cell %lld", (long long)c);
	}
	for (pass = 0; pass < 2; pass++) {
		size_t t = 0;
		pos = 0;
		for (c = 0; c < v->ncell; c++) {
			int64_t k, *q;
			const char *name;
			if (v->offs != NULL) {
				k = v->offs[c + 1] - v->offs[c];
				q = v->conn + v->offs[c];
			} else {
				if (pos >= v->nconn || v->conn[pos] < 0 ||
				    v->conn[pos] > v->nconn - pos - 1)
					return vx_err_set(e, VX_EDATA, "vtk: "
					    "CELLS: cell %lld runs past the "
					    "list's %lld entries", (long long)c,
					    (long long)v->nconn);
				k = v->conn[pos];
				q = v->conn + pos + 1;
				pos += 1 + k;
			}
			int dim = cell_dim(v->ctype[c], &name);
			if (dim < 0)
				return vx_err_set(e, VX_EDATA, "vtk: cell %lld "
				    "has unknown cell type %lld", (long long)c,
				    (long long)v->ctype[c]);
			if (dim < 3) {
				if (pass == 0 && v->info)
					v->info->nskip_lower++;
				continue;
			}
			if (v->ctype[c] != 10) {
				if (v->opt && v->opt->skip_volume_cells) {
					if (pass == 0 && v->info)
						v->info->nskip_volume++;
					continue;
				}
				return vx_err_set(e, VX_EDATA, "vtk: cell %lld "
				    "is a %s (type %lld): only tetrahedra "
				    "(type 10) are supported", (long long)c,
				    name, (long long)v->ctype[c]);
			}
			if (k != 4)
				return vx_err_set(e, VX_EDATA, "vtk: cell %lld: "
				    "a tetra with %lld points", (long long)c,
				    (long long)k);
			if (pass == 0) {
				for (int i = 0; i < 4; i++)
					if (q[i] < 0 || q[i] >= v->npoint)
						return vx_err_set(e, VX_EDATA,
						    "vtk: cell %lld refers to "
						    "point %lld of %lld",
						    (long long)c, (long long)q[i],
						    (long long)v->npoint);
				ntet++;
			} else {
				for (int i = 0; i < 4; i++)
					m->tet[4 * t + (size_t)i] = (uint32_t)q[i];
				t++;
			}
		}
		if (v->offs == NULL && pos != v->nconn)
			return vx_err_set(e, VX_EDATA, "vtk: CELLS claims %lld "
			    "entries, the cells use %lld", (long long)v->nconn,
			    (long long)pos);
		if (pass == 0) {
			if ((uint64_t)ntet > VX_TETMESH_MAX_TETS)
				return vx_err_set(e, VX_EDATA, "vtk: %lld tets "
				    "(limit %llu)", (long long)ntet,
				    (unsigned long long)VX_TETMESH_MAX_TETS);
			m->tet = vx_malloc((size_t)ntet * 4 * sizeof *m->tet, e);
			if (m->tet == NULL && ntet > 0)
				return VX_ENOMEM;
			m->ntet = (size_t)ntet;
		}
	}
	return 0;
}

static int
parse(vtkimp *v, vx_tetmesh *m)
{
	vtkr *r = &v->r;
	vx_scan *s = &r->s;
	char tok[TOK], name[TOK];
	int mode = 0, rc, t;
	int64_t ntuple = 0, a, b;
	static const char magic[] = "# vtk DataFile Version";

	/* line 1: magic and version; line 2: title; line 3: ASCII|BINARY */
	if (vx_scan_left(s) < sizeof magic - 1 ||
	    strncasecmp((const char *)s->p, magic, sizeof magic - 1) != 0)
		return vx_err_set(r->e, VX_EDATA, "vtk: not a VTK legacy file "
		    "(no '# vtk DataFile Version' line)");
	s->p += sizeof magic - 1;
	double ver = 0;
	const char *w;
	size_t wn = vx_scan_word_line(s, &w);
	if (wn > 0 && vx_num_f64(w, wn, 0, &ver) != 0)
		ver = 0;
	r->v51 = ver >= 5.05;
	end_line(r);
	end_line(r);
	if (vx_scan_token(s, tok, TOK) <= 0)
		return fail(r, "truncated header", NULL, NULL);
	if (is(tok, "BINARY"))
		r->binary = 1;
	else if (!is(tok, "ASCII"))
		return fail(r, "expected ASCII or BINARY, not '%.40s'", tok, NULL);
	if (vx_scan_token(s, tok, TOK) <= 0 || !is(tok, "DATASET") ||
	    vx_scan_token(s, name, TOK) <= 0)
		return fail(r, "expected DATASET", NULL, NULL);
	if (!is(name, "UNSTRUCTURED_GRID"))
		return fail(r, "dataset %.40s is not supported (need "
		    "UNSTRUCTURED_GRID)", name, NULL);
	end_line(r);
	v->info->format = r->binary ? VX_TETFMT_VTK_BINARY : VX_TETFMT_VTK_ASCII;

	while ((rc = vx_scan_token(s, tok, TOK)) != 0) {
		if (rc < 0)
			return fail(r, "unexpected long token", NULL, NULL);
		if (is(tok, "POINTS")) {
			if (v->npoint >= 0)
				return fail(r, "POINTS given twice", NULL, NULL);
			if (!next_i64(s, &a) || a < 0 ||
			    (uint64_t)a > VX_TETMESH_MAX_POINTS ||
			    vx_scan_token(s, tok, TOK) <= 0)
				return fail(r, "POINTS: expected a count (0 .. "
				    "2^32-2) and a type", NULL, NULL);
			if ((rc = parse_type(r, tok, &t)) != 0)
				return rc;
			end_line(r);
			if (!fits(r, 3 * (uint64_t)a, vx_scalar_size((vx_scalar)t)))
				return fail(r, "truncated: POINTS needs more data "
				    "than the file has", NULL, NULL);
			v->npoint = a;
			if ((v->pts = vx_malloc(3 * (size_t)a * sizeof *v->pts,
			    r->e)) == NULL)
				return VX_ENOMEM;
			if ((rc = read_values(r, t, 3 * (size_t)a, v->pts, NULL,
			    "POINTS")) != 0)
				return rc;
		} else if (is(tok, "CELLS")) {
			if (!next_i64(s, &a) || !next_i64(s, &b))
				return fail(r, "CELLS: expected two counts", NULL,
				    NULL);
			if ((rc = cells(v, a, b)) != 0)
				return rc;
		} else if (is(tok, "CELL_TYPES")) {
			if (v->ntype >= 0)
				return fail(r, "CELL_TYPES given twice", NULL,
				    NULL);
			if (!next_i64(s, &a) || a < 0 || a > (int64_t)1 << 40)
				return fail(r, "CELL_TYPES: expected a count",
				    NULL, NULL);
			end_line(r);
			if (!fits(r, (uint64_t)a, 4))
				return fail(r, "truncated: CELL_TYPES needs more "
				    "data than the file has", NULL, NULL);
			v->ntype = a;
			if ((v->ctype = vx_malloc((size_t)a * sizeof *v->ctype,
			    r->e)) == NULL && a > 0)
				return VX_ENOMEM;
			if ((rc = read_values(r, VX_S_I32, (size_t)a, NULL,
			    v->ctype, "CELL_TYPES")) != 0)
				return rc;
		} else if (is(tok, "POINT_DATA") ||
		    is(tok, "CELL_DATA")) {
			mode = is(tok, "POINT_DATA") ? 'p' : 'c';
			if (!next_i64(s, &ntuple) || ntuple < 0)
				return fail(r, "%s: expected a count", tok, NULL);
			if (mode == 'p' && ntuple != v->npoint)
				return fail(r, "POINT_DATA has a count other "
				    "than POINTS'", NULL, NULL);
			end_line(r);
		} else if (is(tok, "FIELD")) {
			if ((rc = field(v, mode, ntuple)) != 0)
				return rc;
		} else if (is(tok, "METADATA")) {
			end_line(r);
			while (s->p < s->end && !vx_scan_eol(s))
				end_line(r);
			end_line(r);
		} else if (mode == 0) {
			return fail(r, "unknown keyword '%.40s'", tok, NULL);
		} else if (is(tok, "SCALARS")) {
			int64_t nc = 1;
			if (vx_scan_token(s, name, TOK) <= 0 ||
			    vx_scan_token(s, tok, TOK) <= 0)
				return fail(r, "SCALARS: expected a name and a type",
				    NULL, NULL);
			if ((rc = parse_type(r, tok, &t)) != 0)
				return rc;
			if ((wn = vx_scan_word_line(s, &w)) > 0 &&
			    vx_num_i64(w, wn, 1, 4, &nc) != 0)
				return fail(r, "SCALARS: bad component count "
				    "'%.40s'", vx_imp_show(w, wn), NULL);
			end_line(r);
			/* an optional LOOKUP_TABLE line */
			const unsigned char *save = s->p;
			if (vx_scan_token(s, tok, TOK) > 0 &&
			    is(tok, "LOOKUP_TABLE"))
				end_line(r);
			else
				s->p = save;
			unescape(name);
			if ((rc = attr_array(v, mode, name, t, ntuple, nc,
			    "SCALARS")) != 0)
				return rc;
		} else if (is(tok, "LOOKUP_TABLE") ||
		    is(tok, "COLOR_SCALARS")) {
			int lut = is(tok, "LOOKUP_TABLE");
			if (vx_scan_token(s, name, TOK) <= 0 ||
			    !next_i64(s, &a) ||
			    a < 0 || a > 1 << 24)
				return fail(r, "%s: expected a name and a size",
				    tok, NULL);
			end_line(r);
			if ((rc = attr_array(v, 'x', name, r->binary ? VX_S_U8 :
			    VX_S_F32, lut ? a : ntuple, lut ? 4 : a, tok)) != 0)
				return rc;
		} else if (is(tok, "VECTORS") || is(tok, "NORMALS") ||
		    is(tok, "TENSORS") || is(tok, "TENSORS6") ||
		    is(tok, "GLOBAL_IDS") || is(tok, "PEDIGREE_IDS") ||
		    is(tok, "TEXTURE_COORDINATES")) {
			int64_t nc = is(tok, "VECTORS") ||
			    is(tok, "NORMALS") ? 3 : is(tok, "TENSORS") ?
			    9 : is(tok, "TENSORS6") ? 6 : 1;
			char kw[TOK];
			memcpy(kw, tok, sizeof kw);
			if (vx_scan_token(s, name, TOK) <= 0)
				return fail(r, "%s: expected a name", kw, NULL);
			if (is(kw, "TEXTURE_COORDINATES") &&
			    (!next_i64(s, &nc) || nc < 1 || nc > 3))
				return fail(r, "TEXTURE_COORDINATES: bad "
				    "dimension", NULL, NULL);
			if (vx_scan_token(s, tok, TOK) <= 0)
				return fail(r, "%s: expected a type", kw, NULL);
			if ((rc = parse_type(r, tok, &t)) != 0)
				return rc;
			end_line(r);
			if ((rc = attr_array(v, 'x', name, t, ntuple, nc, kw)) != 0)
				return rc;
		} else
			return fail(r, "unknown keyword '%.40s'", tok, NULL);
	}
	if (v->npoint < 0)
		return vx_err_set(r->e, VX_EDATA, "vtk: no POINTS");
	if (v->ncell < 0 || v->ntype < 0)
		return vx_err_set(r->e, VX_EDATA, "vtk: no CELLS or CELL_TYPES");
	if (v->val == NULL) {
		if (v->opt && v->opt->scalar)
			return vx_err_set(r->e, VX_EDATA, "vtk: no point array "
			    "named '%.60s'", v->opt->scalar);
		return vx_err_set(r->e, VX_EDATA, "vtk: no point scalars "
		    "(POINT_DATA with a one-component SCALARS or FIELD array)");
	}
	v->info->ncell = (size_t)v->ncell;
	return build(v, m);
}

int
vx_tetmesh_import_vtk(vx_tetmesh *m, const void *buf, size_t n,
    const vx_tetimport_opt *opt, vx_tetimport_info *info, vx_err *e)
{
	vx_tetimport_info dummy;
	vtkimp v;
	int rc;

	vx_tetmesh_init(m);
	if (info == NULL)
		info = &dummy;
	memset(info, 0, sizeof *info);
	memset(&v, 0, sizeof v);
	vx_scan_init(&v.r.s, buf, n);
	v.r.e = e;
	v.opt = opt;
	v.info = info;
	v.npoint = v.ncell = v.ntype = -1;
	rc = parse(&v, m);
	if (rc == 0) {
		size_t bad;

		m->npoint = (size_t)v.npoint;
		m->pts = v.pts;
		v.pts = NULL;
		if ((rc = vx_imp_mesh_values(m, v.val, &bad, e)) == VX_EDATA)
			vx_err_set(e, rc, "vtk: value %g of point %zu is "
			    "beyond the float range", v.val[bad], bad);
		vx_tetmesh_set_scalar(m, v.valname);
	}
	if (rc == 0)
		rc = vx_tetmesh_validate(m, e);
	free(v.pts);
	free(v.conn);
	free(v.offs);
	free(v.ctype);
	free(v.val);
	if (rc != 0)
		vx_tetmesh_free(m);
	return rc;
}
