/* import_nrrd.c: NRRD files (teem.sourceforge.net/nrrd/format.html):
 * attached and detached headers, raw/gzip/ascii/hex encodings. */
#include "import_priv.h"
#include "vx_scan.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define NRRD_HDR_MAX ((size_t)1 << 20)   /* header text, LIST included */
#define NRRD_MAX_FILES ((uint64_t)1 << 20)

/* The fields of the format.  Each is either used, or known and ignored
 * (it does not change how the samples are read or placed); any other
 * "field: value" line is an error, "key:=value" lines are ignored. */
enum {
	F_DIMENSION, F_TYPE, F_ENCODING, F_ENDIAN, F_SIZES, F_SPACINGS,
	F_AXIS_MINS, F_AXIS_MAXS, F_CENTERS, F_KINDS, F_SPACE, F_SPACE_DIM,
	F_SPACE_ORIGIN, F_SPACE_DIRS, F_DATA_FILE, F_LINE_SKIP, F_BYTE_SKIP,
	F_BLOCK_SIZE, F_USED_LAST,
	/* known, ignored */
	F_CONTENT = F_USED_LAST, F_MIN, F_MAX, F_OLD_MIN, F_OLD_MAX,
	F_NUMBER, F_SAMPLE_UNITS, F_THICKNESSES, F_LABELS, F_UNITS,
	F_SPACE_UNITS, F_MEASUREMENT_FRAME,
	F_LAST
};

static const vx_enum_name field_names[] = {
	{ "dimension", F_DIMENSION }, { "type", F_TYPE },
	{ "encoding", F_ENCODING }, { "endian", F_ENDIAN },
	{ "sizes", F_SIZES }, { "spacings", F_SPACINGS },
	{ "axis mins", F_AXIS_MINS }, { "axismins", F_AXIS_MINS },
	{ "axis maxs", F_AXIS_MAXS }, { "axismaxs", F_AXIS_MAXS },
	{ "centers", F_CENTERS }, { "centerings", F_CENTERS },
	{ "kinds", F_KINDS }, { "space", F_SPACE },
	{ "space dimension", F_SPACE_DIM }, { "spacedimension", F_SPACE_DIM },
	{ "space origin", F_SPACE_ORIGIN }, { "spaceorigin", F_SPACE_ORIGIN },
	{ "space directions", F_SPACE_DIRS },
	{ "spacedirections", F_SPACE_DIRS },
	{ "data file", F_DATA_FILE }, { "datafile", F_DATA_FILE },
	{ "line skip", F_LINE_SKIP }, { "lineskip", F_LINE_SKIP },
	{ "byte skip", F_BYTE_SKIP }, { "byteskip", F_BYTE_SKIP },
	{ "block size", F_BLOCK_SIZE }, { "blocksize", F_BLOCK_SIZE },
	{ "content", F_CONTENT }, { "min", F_MIN }, { "max", F_MAX },
	{ "old min", F_OLD_MIN }, { "oldmin", F_OLD_MIN },
	{ "old max", F_OLD_MAX }, { "oldmax", F_OLD_MAX },
	{ "number", F_NUMBER }, { "sample units", F_SAMPLE_UNITS },
	{ "sampleunits", F_SAMPLE_UNITS }, { "thicknesses", F_THICKNESSES },
	{ "labels", F_LABELS }, { "units", F_UNITS },
	{ "space units", F_SPACE_UNITS }, { "spaceunits", F_SPACE_UNITS },
	{ "measurement frame", F_MEASUREMENT_FRAME },
	{ "measurementframe", F_MEASUREMENT_FRAME }, { NULL, -1 }
};
static const vx_enum fields = { "field", field_names, "?", 1 };

static const char *
field_name(int f)
{
	return vx_enum_str(&fields, f);
}

enum { ENC_RAW = 1, ENC_GZIP, ENC_ASCII, ENC_HEX, ENC_UNSUPPORTED };

typedef struct nrrd {
	char *text;                 /* copy of the header; values point in */
	const char *val[F_LAST];    /* value of each field seen, or NULL */
	size_t vlen[F_LAST];
	int line[F_LAST];           /* its line number, for messages */
	size_t hdr_len;             /* bytes up to and including the empty
	                               line (or all, for a detached header) */
	int ended;                  /* an empty line ended the header */
	/* the list of data files after "data file: LIST" */
	const char **list;
	size_t *list_len, nlist;
	/* parsed */
	int dim, enc, big, space_dim;
	int64_t sizes[3];
	vx_scalar type;
	int64_t line_skip, byte_skip;
} nrrd;

static void
nrrd_free(nrrd *h)
{
	free(h->text);
	free(h->list);
	free(h->list_len);
	memset(h, 0, sizeof *h);
}

/* norm: lower-case p[0..n) with runs of blanks made one space, into buf. */
static const char *
norm(const char *p, size_t n, char *buf, size_t cap)
{
	size_t i, k = 0;

	vx_imp_trim(&p, &n);
	for (i = 0; i < n && k + 1 < cap; i++) {
		if (p[i] == ' ' || p[i] == '\t') {
			if (k > 0 && buf[k - 1] == ' ')
				continue;
			buf[k++] = ' ';
		} else
			buf[k++] = (char)tolower((unsigned char)p[i]);
	}
	buf[k] = '\0';
	return buf;
}

static int
list_add(nrrd *h, const char *p, size_t n, vx_err *e)
{
	if ((h->nlist & (h->nlist - 1)) == 0) {   /* 0, 1, 2, 4, ...: grow */
		size_t cap = h->nlist ? 2 * h->nlist : 16;
		const char **l = realloc(h->list, cap * sizeof *l);
		size_t *ll;

		if (l == NULL)
			return vx_err_set(e, VX_ENOMEM, "nrrd: out of memory");
		h->list = l;
		if ((ll = realloc(h->list_len, cap * sizeof *ll)) == NULL)
			return vx_err_set(e, VX_ENOMEM, "nrrd: out of memory");
		h->list_len = ll;
	}
	h->list[h->nlist] = p;
	h->list_len[h->nlist++] = n;
	return 0;
}

/* nrrd_lines: split the header into fields.  Returns 0 or an error. */
static int
nrrd_lines(nrrd *h, const unsigned char *p, size_t n, int at_end, vx_err *e)
{
	const char *line;
	size_t len;
	int lineno = 1, in_list = 0, f;
	vx_scan s;

	vx_scan_init(&s, p, n);
	if (!vx_scan_line(&s, at_end, &line, &len))
		return vx_err_set(e, VX_EDATA, "nrrd: no magic line");
	if (len < 4 || memcmp(line, "NRRD", 4) != 0)
		return vx_err_set(e, VX_EDATA, "nrrd: not a NRRD file (magic "
		    "'%s')", vx_imp_show(line, len));
	if (!((len == 8 && memcmp(line, "NRRD000", 7) == 0 && line[7] >= '1' &&
	    line[7] <= '6') || (len == 9 && memcmp(line, "NRRD00.01", 9) == 0)))
		return vx_err_set(e, VX_EDATA, "nrrd: unsupported version '%s' "
		    "(NRRD0001..NRRD0006 are read)", vx_imp_show(line, len));
	while (vx_scan_line(&s, at_end, &line, &len)) {
		const char *colon;
		size_t k;

		lineno++;
		if (len == 0) {
			h->ended = 1;
			break;
		}
		if (memchr(line, '\0', len) != NULL)
			return vx_err_set(e, VX_EDATA, "nrrd: line %d: NUL byte",
			    lineno);
		if (in_list) {
			if (list_add(h, line, len, e) != 0)
				return e->code;
			continue;
		}
		if (line[0] == '#')
			continue;
		/* "field: desc" when the text before the first ": " is a
		 * field; otherwise "key:=value" */
		colon = NULL;
		for (k = 0; k + 1 < len; k++)
			if (line[k] == ':' && (line[k + 1] == ' ' ||
			    line[k + 1] == '\t')) {
				colon = line + k;
				break;
			}
		if (colon == NULL && len > 0 && line[len - 1] == ':')
			colon = line + len - 1;       /* "field:" empty desc */
		f = colon ? vx_enum_val_n(&fields, line, (size_t)(colon -
		    line)) : -1;
		if (f < 0) {
			for (k = 0; k + 1 < len; k++)
				if (line[k] == ':' && line[k + 1] == '=')
					break;
			if (k + 1 < len)
				continue;             /* key:=value */
			if (colon != NULL)
				return vx_err_set(e, VX_EDATA, "nrrd: line %d: "
				    "unknown field '%s'", lineno, vx_imp_show(line,
				    (size_t)(colon - line)));
			return vx_err_set(e, VX_EDATA, "nrrd: line %d: expected "
			    "'field: value' or 'key:=value', got '%s'", lineno,
			    vx_imp_show(line, len));
		}
		if (h->val[f] != NULL)
			return vx_err_set(e, VX_EDATA, "nrrd: line %d: field '%s' "
			    "given twice", lineno, field_name(f));
		h->val[f] = colon + 1;
		h->vlen[f] = len - (size_t)(colon + 1 - line);
		vx_imp_trim(&h->val[f], &h->vlen[f]);
		h->line[f] = lineno;
		if (f == F_DATA_FILE && h->vlen[f] >= 4 &&
		    memcmp(h->val[f], "LIST", 4) == 0 &&
		    (h->vlen[f] == 4 || h->val[f][4] == ' ' ||
		    h->val[f][4] == '\t'))
			in_list = 1;    /* the rest of the header lists files */
	}
	h->hdr_len = (size_t)(s.p - s.base);
	return 0;
}

static int
parse_type(nrrd *h, vx_err *e)
{
	static const vx_enum_name type_names[] = {
		{ "signed char", VX_S_I8 }, { "int8", VX_S_I8 },
		{ "int8_t", VX_S_I8 },
		{ "uchar", VX_S_U8 }, { "unsigned char", VX_S_U8 },
		{ "uint8", VX_S_U8 }, { "uint8_t", VX_S_U8 },
		{ "short", VX_S_I16 }, { "short int", VX_S_I16 },
		{ "signed short", VX_S_I16 }, { "signed short int", VX_S_I16 },
		{ "int16", VX_S_I16 }, { "int16_t", VX_S_I16 },
		{ "ushort", VX_S_U16 }, { "unsigned short", VX_S_U16 },
		{ "unsigned short int", VX_S_U16 }, { "uint16", VX_S_U16 },
		{ "uint16_t", VX_S_U16 },
		{ "int", VX_S_I32 }, { "signed int", VX_S_I32 },
		{ "int32", VX_S_I32 }, { "int32_t", VX_S_I32 },
		{ "uint", VX_S_U32 }, { "unsigned int", VX_S_U32 },
		{ "uint32", VX_S_U32 }, { "uint32_t", VX_S_U32 },
		{ "longlong", VX_S_I64 }, { "long long", VX_S_I64 },
		{ "long long int", VX_S_I64 }, { "signed long long", VX_S_I64 },
		{ "signed long long int", VX_S_I64 }, { "int64", VX_S_I64 },
		{ "int64_t", VX_S_I64 },
		{ "ulonglong", VX_S_U64 }, { "unsigned long long", VX_S_U64 },
		{ "unsigned long long int", VX_S_U64 }, { "uint64", VX_S_U64 },
		{ "uint64_t", VX_S_U64 },
		{ "float", VX_S_F32 }, { "double", VX_S_F64 },
		{ NULL, VX_SCALAR_UNKNOWN }
	};
	static const vx_enum types = { "type", type_names, "?", 0 };
	char buf[64];
	const char *t;

	if (h->val[F_TYPE] == NULL)
		return vx_err_set(e, VX_EDATA, "nrrd: type: missing");
	t = norm(h->val[F_TYPE], h->vlen[F_TYPE], buf, sizeof buf);
	if ((h->type = (vx_scalar)vx_enum_val(&types, t)) != VX_SCALAR_UNKNOWN)
		return 0;
	if (strcmp(t, "block") == 0)
		return vx_err_set(e, VX_EDATA, "nrrd: type: block is not "
		    "supported (scalar volumes only)");
	return vx_err_set(e, VX_EDATA, "nrrd: type: unknown type '%s'",
	    vx_imp_show(h->val[F_TYPE], h->vlen[F_TYPE]));
}

static int
parse_encoding(nrrd *h, vx_err *e)
{
	static const vx_enum_name enc_names[] = {
		{ "raw", ENC_RAW }, { "gzip", ENC_GZIP }, { "gz", ENC_GZIP },
		{ "ascii", ENC_ASCII }, { "text", ENC_ASCII },
		{ "txt", ENC_ASCII }, { "hex", ENC_HEX },
		{ "bzip2", ENC_UNSUPPORTED }, { "bz2", ENC_UNSUPPORTED },
		{ "zrl", ENC_UNSUPPORTED }, { NULL, 0 }
	};
	static const vx_enum encs = { "encoding", enc_names, "?", 0 };
	char buf[32];
	const char *s;

	if (h->val[F_ENCODING] == NULL)
		return vx_err_set(e, VX_EDATA, "nrrd: encoding: missing");
	s = norm(h->val[F_ENCODING], h->vlen[F_ENCODING], buf, sizeof buf);
	h->enc = vx_enum_val(&encs, s);
	if (h->enc == ENC_UNSUPPORTED)
		return vx_err_set(e, VX_EDATA, "nrrd: encoding: %s is not "
		    "supported (raw, gzip, ascii, hex are)", s);
	if (h->enc == 0)
		return vx_err_set(e, VX_EDATA, "nrrd: encoding: unknown "
		    "encoding '%s'", vx_imp_show(h->val[F_ENCODING],
		    h->vlen[F_ENCODING]));
	return 0;
}

/* words: split a per-axis field into exactly h->dim blank-separated
 * words; w[i], wl[i]. */
static int
words(const nrrd *h, int f, const char *w[3], size_t wl[3], vx_err *e)
{
	const char *p = h->val[f];
	size_t n = h->vlen[f], i = 0;
	int k = 0;

	while (1) {
		while (i < n && (p[i] == ' ' || p[i] == '\t'))
			i++;
		if (i == n)
			break;
		if (k == h->dim)
			goto bad;
		w[k] = p + i;
		while (i < n && p[i] != ' ' && p[i] != '\t')
			i++;
		wl[k] = (size_t)(p + i - w[k]);
		k++;
	}
	if (k == h->dim)
		return 0;
bad:
	return vx_err_set(e, VX_EDATA, "nrrd: %s: expected %d values, got '%s'",
	    field_name(f), h->dim, vx_imp_show(p, n));
}

/* per_axis_f64: a per-axis field of numbers (NaN allowed). */
static int
per_axis_f64(const nrrd *h, int f, double v[3], vx_err *e)
{
	const char *w[3];
	size_t wl[3];
	int a;

	if (words(h, f, w, wl, e) != 0)
		return e->code;
	for (a = 0; a < h->dim; a++)
		if (vx_num_f64(w[a], wl[a], VX_NUM_NONFINITE, &v[a]) != 0)
			return vx_err_set(e, VX_EDATA, "nrrd: %s: '%s' is not a "
			    "number", field_name(f), vx_imp_show(w[a], wl[a]));
	return 0;
}

static int
parse_sizes(nrrd *h, vx_err *e)
{
	const char *w[3];
	size_t wl[3];
	int64_t v;
	int a;

	if (h->val[F_DIMENSION] == NULL)
		return vx_err_set(e, VX_EDATA, "nrrd: dimension: missing");
	if (vx_num_i64(h->val[F_DIMENSION], h->vlen[F_DIMENSION], 1,
	    INT64_MAX, &v) != 0)
		return vx_err_set(e, VX_EDATA, "nrrd: dimension: '%s' is not a "
		    "positive integer", vx_imp_show(h->val[F_DIMENSION],
		    h->vlen[F_DIMENSION]));
	if (v > 3)
		return vx_err_set(e, VX_EDATA, "nrrd: dimension: %lld: only 1 to "
		    "3 are supported (scalar volumes)", (long long)v);
	h->dim = (int)v;
	if (h->val[F_SIZES] == NULL)
		return vx_err_set(e, VX_EDATA, "nrrd: sizes: missing");
	if (words(h, F_SIZES, w, wl, e) != 0)
		goto bad;
	for (a = 0; a < 3; a++) {
		if (a >= h->dim) {
			h->sizes[a] = 1;
			continue;
		}
		if (vx_num_i64(w[a], wl[a], 1, INT64_MAX, &h->sizes[a]) != 0)
			goto bad;
	}
	return 0;
bad:
	return vx_err_set(e, VX_EDATA, "nrrd: sizes: expected %d positive "
	    "integers, got '%s'", h->dim, vx_imp_show(h->val[F_SIZES],
	    h->vlen[F_SIZES]));
}

static int
parse_kinds(const nrrd *h, vx_err *e)
{
	static const char *ok[] = { "domain", "space", "time", "none", "???",
	    "-" };
	const char *w[3];
	size_t wl[3], i;
	int a;

	if (h->val[F_KINDS] == NULL)
		return 0;
	if (words(h, F_KINDS, w, wl, e) != 0)
		return e->code;
	for (a = 0; a < h->dim; a++) {
		for (i = 0; i < sizeof ok / sizeof ok[0]; i++)
			if (vx_word_eq(w[a], wl[a], ok[i], 1))
				break;
		if (i == sizeof ok / sizeof ok[0])
			return vx_err_set(e, VX_EDATA, "nrrd: kinds: axis %d is "
			    "'%s': only scalar volumes are supported", a,
			    vx_imp_show(w[a], wl[a]));
	}
	return 0;
}

/* parse_space: the space dimension, from "space" or "space dimension". */
static int
parse_space(nrrd *h, vx_err *e)
{
	static const struct { const char *name; int dim; } spaces[] = {
		{ "right-anterior-superior", 3 }, { "ras", 3 },
		{ "left-anterior-superior", 3 }, { "las", 3 },
		{ "left-posterior-superior", 3 }, { "lps", 3 },
		{ "scanner-xyz", 3 }, { "3d-right-handed", 3 },
		{ "3d-left-handed", 3 }, { "right-up", 2 }, { "ru", 2 },
		{ "right-down", 2 }, { "rd", 2 },
		{ "right-anterior-superior-time", 4 }, { "rast", 4 },
		{ "left-anterior-superior-time", 4 }, { "last", 4 },
		{ "left-posterior-superior-time", 4 }, { "lpst", 4 },
		{ "scanner-xyz-time", 4 }, { "3d-right-handed-time", 4 },
		{ "3d-left-handed-time", 4 },
	};
	char buf[64];
	const char *s;
	size_t i;
	int64_t v;

	if (h->val[F_SPACE] != NULL && h->val[F_SPACE_DIM] != NULL)
		return vx_err_set(e, VX_EDATA, "nrrd: space and space dimension: "
		    "only one may be given");
	if (h->val[F_SPACE] != NULL) {
		s = norm(h->val[F_SPACE], h->vlen[F_SPACE], buf, sizeof buf);
		for (i = 0; i < sizeof spaces / sizeof spaces[0]; i++)
			if (strcmp(s, spaces[i].name) == 0)
				break;
		if (i == sizeof spaces / sizeof spaces[0])
			return vx_err_set(e, VX_EDATA, "nrrd: space: unknown space "
			    "'%s'", vx_imp_show(h->val[F_SPACE], h->vlen[F_SPACE]));
		h->space_dim = spaces[i].dim;
	} else if (h->val[F_SPACE_DIM] != NULL) {
		if (vx_num_i64(h->val[F_SPACE_DIM], h->vlen[F_SPACE_DIM], 1,
		    INT64_MAX, &v) != 0)
			return vx_err_set(e, VX_EDATA, "nrrd: space dimension: "
			    "'%s' is not a positive integer",
			    vx_imp_show(h->val[F_SPACE_DIM], h->vlen[F_SPACE_DIM]));
		h->space_dim = v > 4 ? 5 : (int)v;
	} else
		return 0;
	if (h->space_dim < 2 || h->space_dim > 3)
		return vx_err_set(e, VX_EDATA, "nrrd: space: %d-dimensional world "
		    "space is not supported (2 or 3)", h->space_dim);
	return 0;
}

/* vector: "(a,b,c)" with space_dim numbers at *p; advances *p.  Returns
 * 1 for "none", 0 for a vector, -1 on error. */
static int
vector(const nrrd *h, const char **p, const char *end, double v[3])
{
	const char *q = *p, *close;
	int count;

	while (q < end && (*q == ' ' || *q == '\t'))
		q++;
	if (end - q >= 4 && vx_word_eq(q, 4, "none", 1) &&
	    (end - q == 4 || q[4] == ' ' || q[4] == '\t')) {
		*p = q + 4;
		return 1;
	}
	if (q == end || *q != '(')
		return -1;
	if ((close = memchr(q, ')', (size_t)(end - q))) == NULL)
		return -1;
	v[0] = v[1] = v[2] = 0;
	if (vx_imp_numbers(q + 1, (size_t)(close - q - 1), v, 3, &count) != 0 ||
	    count != h->space_dim)
		return -1;
	*p = close + 1;
	return 0;
}

/* nrrd_frame: spacing, origin and mirroring of the grid. */
static int
nrrd_frame(const nrrd *h, vx_imp_frame *f, vx_err *e)
{
	double col[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
	double org[3] = { 0, 0, 0 }, sp[3] = { 1, 1, 1 };
	int a, rc, center[3] = { 0, 0, 0 };

	if (h->val[F_SPACE_ORIGIN] != NULL) {
		const char *p = h->val[F_SPACE_ORIGIN];
		const char *end = p + h->vlen[F_SPACE_ORIGIN];

		if (h->space_dim == 0)
			return vx_err_set(e, VX_EDATA, "nrrd: space origin: needs "
			    "space or space dimension");
		if (vector(h, &p, end, org) != 0)
			goto bad_origin;
		while (p < end && (*p == ' ' || *p == '\t'))
			p++;
		if (p != end)
			goto bad_origin;
	}
	if (h->val[F_SPACE_DIRS] != NULL) {
		const char *p = h->val[F_SPACE_DIRS];
		const char *end = p + h->vlen[F_SPACE_DIRS];

		if (h->space_dim == 0)
			return vx_err_set(e, VX_EDATA, "nrrd: space directions: "
			    "needs space or space dimension");
		if (h->val[F_SPACINGS] != NULL)
			return vx_err_set(e, VX_EDATA, "nrrd: spacings: not "
			    "allowed together with space directions");
		for (a = 0; a < h->dim; a++) {
			rc = vector(h, &p, end, col[a]);
			if (rc < 0)
				return vx_err_set(e, VX_EDATA, "nrrd: space "
				    "directions: expected %d vectors of %d "
				    "numbers like (1,0,0), got '%s'", h->dim,
				    h->space_dim, vx_imp_show(h->val[F_SPACE_DIRS],
				    h->vlen[F_SPACE_DIRS]));
			if (rc == 1)
				return vx_err_set(e, VX_EDATA, "nrrd: space "
				    "directions: axis %d is 'none': only spatial "
				    "axes are supported", a);
		}
		while (p < end && (*p == ' ' || *p == '\t'))
			p++;
		if (p != end)
			return vx_err_set(e, VX_EDATA, "nrrd: space directions: "
			    "more than %d vectors", h->dim);
		return vx_imp_frame_axes(f, (const double (*)[3])col, org, h->sizes,
		    "nrrd: space directions", e);
	}
	if (h->val[F_CENTERS] != NULL) {
		const char *w[3];
		size_t wl[3];

		if (words(h, F_CENTERS, w, wl, e) != 0)
			return e->code;
		for (a = 0; a < h->dim; a++)
			center[a] = vx_word_eq(w[a], wl[a], "node", 1) ? 2 :
			    vx_word_eq(w[a], wl[a], "cell", 1) ? 1 : 0;
	}
	if (h->val[F_SPACINGS] != NULL) {
		if ((rc = per_axis_f64(h, F_SPACINGS, sp, e)) != 0)
			return rc;
		for (a = 0; a < h->dim; a++) {
			if (isnan(sp[a]))
				sp[a] = 1;      /* unknown */
			if (!isfinite(sp[a]) || sp[a] == 0)
				return vx_err_set(e, VX_EDATA, "nrrd: spacings: "
				    "axis %d: %g is not a usable spacing", a,
				    sp[a]);
		}
	} else if (h->val[F_AXIS_MINS] != NULL && h->val[F_AXIS_MAXS] != NULL) {
		double lo[3], hi[3];

		if ((rc = per_axis_f64(h, F_AXIS_MINS, lo, e)) != 0 ||
		    (rc = per_axis_f64(h, F_AXIS_MAXS, hi, e)) != 0)
			return rc;
		for (a = 0; a < h->dim; a++) {
			/* nrrd's default centering is cell */
			int node = center[a] == 2;
			double cells = (double)(node ? h->sizes[a] - 1 :
			    h->sizes[a]);

			if (!isfinite(lo[a]) || !isfinite(hi[a]))
				continue;
			if (cells > 0 && hi[a] != lo[a])
				sp[a] = (hi[a] - lo[a]) / cells;
			if (h->val[F_SPACE_ORIGIN] == NULL)
				org[a] = node ? lo[a] : lo[a] + sp[a] / 2;
		}
	}
	return vx_imp_frame_plain(f, sp, org, h->sizes, "nrrd: spacings", e);
bad_origin:
	return vx_err_set(e, VX_EDATA, "nrrd: space origin: expected a vector "
	    "of %d numbers like (0,0,0), got '%s'", h->space_dim,
	    vx_imp_show(h->val[F_SPACE_ORIGIN], h->vlen[F_SPACE_ORIGIN]));
}

static int
parse_skips(nrrd *h, vx_err *e)
{
	if (h->val[F_LINE_SKIP] != NULL &&
	    vx_num_i64(h->val[F_LINE_SKIP], h->vlen[F_LINE_SKIP], 0,
	    INT64_MAX, &h->line_skip) != 0)
		return vx_err_set(e, VX_EDATA, "nrrd: line skip: '%s' is not a "
		    "non-negative integer", vx_imp_show(h->val[F_LINE_SKIP],
		    h->vlen[F_LINE_SKIP]));
	if (h->val[F_BYTE_SKIP] != NULL &&
	    vx_num_i64(h->val[F_BYTE_SKIP], h->vlen[F_BYTE_SKIP], -1,
	    INT64_MAX, &h->byte_skip) != 0)
		return vx_err_set(e, VX_EDATA, "nrrd: byte skip: '%s' is not an "
		    "integer >= -1", vx_imp_show(h->val[F_BYTE_SKIP],
		    h->vlen[F_BYTE_SKIP]));
	if (h->byte_skip == -1 && h->enc != ENC_RAW)
		return vx_err_set(e, VX_EDATA, "nrrd: byte skip: -1 needs raw "
		    "encoding");
	return 0;
}

/* ---- reading the samples ---- */

static int
skip_lines(vx_imp_src *s, int64_t n, vx_err *e)
{
	while (n > 0) {
		const unsigned char *p, *nl;
		size_t avail;
		int rc;

		if ((rc = vx_imp_peek(s, (size_t)1 << 16, &p, &avail, e)) != 0)
			return rc;
		if (avail == 0)
			return vx_err_set(e, VX_EDATA, "line skip: input ends "
			    "before %lld more lines", (long long)n);
		if ((nl = memchr(p, '\n', avail)) == NULL) {
			if ((rc = vx_imp_skip(s, avail, e)) != 0)
				return rc;
			continue;
		}
		if ((rc = vx_imp_skip(s, (size_t)(nl - p) + 1, e)) != 0)
			return rc;
		n--;
	}
	return 0;
}

static int
hexval(unsigned char ch)
{
	if (ch >= '0' && ch <= '9')
		return ch - '0';
	if (ch >= 'a' && ch <= 'f')
		return ch - 'a' + 10;
	if (ch >= 'A' && ch <= 'F')
		return ch - 'A' + 10;
	return -1;
}

/* read_hex: two hex digits per byte, white space anywhere between. */
static int
read_hex(vx_imp_conv *c, vx_imp_src *s, vx_err *e)
{
	size_t nb = 0, batch = c->ss * IMP_STAGE;
	uint64_t want = (c->stop - c->next) * c->ss;
	int hi = -1, rc;

	if ((rc = vx_imp_need(s, 2 * want, "hex data", e)) != 0)
		return rc;
	while (c->next < c->stop) {
		const unsigned char *p;
		size_t avail, i;

		if ((rc = vx_imp_peek(s, (size_t)1 << 16, &p, &avail, e)) != 0)
			return rc;
		if (avail == 0)
			return vx_err_set(e, VX_EDATA, "hex data: truncated");
		for (i = 0; i < avail && c->next < c->stop; i++) {
			int v = hexval(p[i]);

			if (v < 0) {
				if (isspace(p[i]))
					continue;
				return vx_err_set(e, VX_EDATA, "hex data: '%c' is "
				    "not a hex digit", isprint(p[i]) ? p[i] : '?');
			}
			if (hi < 0) {
				hi = v;
				continue;
			}
			c->tmp[nb++] = (unsigned char)(hi << 4 | v);
			hi = -1;
			if (nb == batch || (c->next * c->ss + nb) ==
			    c->stop * c->ss) {
				if ((rc = vx_imp_conv_bytes(c, c->tmp, nb / c->ss,
				    e)) != 0)
					return rc;
				nb = 0;
			}
		}
		if ((rc = vx_imp_skip(s, i, e)) != 0)
			return rc;
	}
	return 0;
}

/* read_piece: the samples next .. stop from one data file's bytes (or the
 * attached data at src's position). */
static int
read_piece(const nrrd *h, vx_imp_conv *c, vx_imp_src *file, vx_err *e)
{
	uint64_t bytes = (c->stop - c->next) * c->ss;
	vx_imp_src gz, *s = file;
	int rc, more;
	size_t slack = IMP_SLACK;

	if ((rc = skip_lines(file, h->line_skip, e)) != 0)
		return rc;
	if (h->enc == ENC_GZIP) {
		if ((rc = vx_imp_src_gzip(&gz, file, e)) != 0)
			return rc;
		s = &gz;
		slack = 0;       /* the gzip stream holds just the samples */
	}
	if (h->byte_skip == -1) {
		/* raw data at the very end of the file */
		uint64_t left = vx_imp_left_max(s);

		if (s->gz)
			return vx_err_set(e, VX_EDATA, "byte skip: -1 needs an "
			    "uncompressed data file");
		if (left < bytes) {
			rc = vx_err_set(e, VX_EDATA, "truncated: %llu bytes, "
			    "%llu needed", (unsigned long long)left,
			    (unsigned long long)bytes);
			goto out;
		}
		rc = vx_imp_skip(s, left - bytes, e);
	} else if ((rc = vx_imp_need(s, (uint64_t)h->byte_skip, "byte skip",
	    e)) == 0)
		rc = vx_imp_skip(s, (uint64_t)h->byte_skip, e);
	if (rc != 0) {
		vx_err_push(e, "byte skip %lld", (long long)h->byte_skip);
		goto out;
	}
	switch (h->enc) {
	case ENC_RAW:
	case ENC_GZIP:
		if ((rc = vx_imp_need(s, bytes, "data", e)) == 0)
			rc = vx_imp_conv_binary(c, s, e);
		break;
	case ENC_ASCII:
		rc = vx_imp_conv_ascii(c, s, e);
		break;
	case ENC_HEX:
		rc = read_hex(c, s, e);
		break;
	}
	if (rc != 0)
		goto out;
	if ((rc = vx_imp_trailing(s, slack, &more, e)) != 0)
		goto out;
	if (more)
		rc = vx_err_set(e, VX_EDATA, "%s data longer than sizes and type "
		    "imply (%llu bytes%s)", h->enc == ENC_GZIP ? "gzip" :
		    "the", (unsigned long long)bytes, slack ? " plus slack" : "");
out:
	if (s == &gz)
		vx_imp_src_close(&gz);
	return rc;
}

/* pattern: "name%03d.raw min max step [subdim]": expand one name. */
typedef struct pattern {
	const char *fmt;
	size_t fmtlen, conv, convlen;   /* the "%0Nd" inside fmt */
	int width, zero;
	int64_t min, max, step, count;
	int subdim;
} pattern;

static int
parse_pattern(const nrrd *h, pattern *pt, vx_err *e)
{
	const char *v = h->val[F_DATA_FILE];
	size_t n = h->vlen[F_DATA_FILE], i, sp;
	double nums[4];
	int count, found = 0;

	memset(pt, 0, sizeof *pt);
	for (sp = 0; sp < n && v[sp] != ' ' && v[sp] != '\t'; sp++)
		;
	pt->fmt = v;
	pt->fmtlen = sp;
	for (i = 0; i < sp; i++) {
		size_t j;

		if (v[i] != '%')
			continue;
		if (i + 1 < sp && v[i + 1] == '%') {
			i++;
			continue;
		}
		j = i + 1;
		if (j < sp && v[j] == '0')
			pt->zero = 1;
		while (j < sp && isdigit((unsigned char)v[j]))
			pt->width = pt->width * 10 + (v[j++] - '0');
		if (j >= sp || v[j] != 'd' || found || pt->width > 20)
			return vx_err_set(e, VX_EDATA, "data file: pattern '%s': "
			    "only one %%d (or %%0Nd) conversion is allowed",
			    vx_imp_show(v, sp));
		found = 1;
		pt->conv = i;
		pt->convlen = j + 1 - i;
		i = j;
	}
	if (vx_imp_numbers(v + sp, n - sp, nums, 4, &count) != 0 || count < 3)
		return vx_err_set(e, VX_EDATA, "data file: pattern needs "
		    "<min> <max> <step> [<subdim>] after the name");
	for (i = 0; i < (size_t)count; i++)
		if (nums[i] != floor(nums[i]) || fabs(nums[i]) > 1e9)
			return vx_err_set(e, VX_EDATA, "data file: pattern: "
			    "'%g' is not an integer", nums[i]);
	pt->min = (int64_t)nums[0];
	pt->max = (int64_t)nums[1];
	pt->step = (int64_t)nums[2];
	pt->subdim = count == 4 ? (int)nums[3] : h->dim - 1;
	if (pt->step == 0 || (pt->max - pt->min) * pt->step < 0)
		return vx_err_set(e, VX_EDATA, "data file: pattern: step %lld "
		    "does not go from %lld to %lld", (long long)pt->step,
		    (long long)pt->min, (long long)pt->max);
	pt->count = (pt->max - pt->min) / pt->step + 1;
	return 0;
}

static char *
pattern_name(const pattern *pt, int64_t k, const char *dir)
{
	char num[32], name[4200];
	size_t i, o = 0;
	int len;

	len = snprintf(num, sizeof num, pt->zero ? "%0*lld" : "%*lld",
	    pt->width, (long long)(pt->min + k * pt->step));
	for (i = 0; i < pt->fmtlen && o + 32 < sizeof name; i++) {
		if (i == pt->conv) {
			memcpy(name + o, num, (size_t)len);
			o += (size_t)len;
			i += pt->convlen - 1;
		} else if (pt->fmt[i] == '%' && i + 1 < pt->fmtlen &&
		    pt->fmt[i + 1] == '%') {
			name[o++] = '%';
			i++;
		} else
			name[o++] = pt->fmt[i];
	}
	return vx_imp_join(dir, name, o);
}

/* pieces: how many equal pieces the samples come in, checked against
 * the sizes as the format defines it (subdim: dimension of each piece). */
static int
check_pieces(const nrrd *h, uint64_t nfiles, int subdim, vx_err *e)
{
	uint64_t expect = 1;
	int a;

	if (nfiles < 1 || nfiles > NRRD_MAX_FILES)
		return vx_err_set(e, VX_EDATA, "data file: %llu files",
		    (unsigned long long)nfiles);
	if (subdim < 1 || subdim > h->dim)
		return vx_err_set(e, VX_EDATA, "data file: piece dimension %d "
		    "outside 1..%d", subdim, h->dim);
	if (subdim == h->dim) {
		if ((uint64_t)h->sizes[h->dim - 1] % nfiles != 0)
			return vx_err_set(e, VX_EDATA, "data file: %llu files do "
			    "not divide the %lld slices of axis %d",
			    (unsigned long long)nfiles,
			    (long long)h->sizes[h->dim - 1], h->dim - 1);
		return 0;
	}
	for (a = subdim; a < h->dim; a++)
		expect *= (uint64_t)h->sizes[a];
	if (expect != nfiles)
		return vx_err_set(e, VX_EDATA, "data file: expected %llu files "
		    "(of %d-D pieces), got %llu", (unsigned long long)expect,
		    subdim, (unsigned long long)nfiles);
	return 0;
}

/* The data files of a detached header: one name, a LIST, or a pattern. */
typedef struct files {
	int mode;                 /* 0: single, 1: LIST, 2: pattern */
	uint64_t n;
	int subdim;
	pattern pt;
} files;

static int
files_plan(const nrrd *h, files *fl, vx_err *e)
{
	const char *v = h->val[F_DATA_FILE];
	size_t n = h->vlen[F_DATA_FILE], i;
	int rc, pct = 0;

	memset(fl, 0, sizeof *fl);
	if (n >= 4 && memcmp(v, "LIST", 4) == 0) {
		const char *d = v + 4;
		size_t dn = n - 4;
		int64_t sd = h->dim - 1;

		vx_imp_trim(&d, &dn);
		if (dn > 0 && vx_num_i64(d, dn, INT64_MIN, INT64_MAX, &sd) != 0)
			return vx_err_set(e, VX_EDATA, "data file: LIST: '%s' is "
			    "not a piece dimension", vx_imp_show(v + 4, n - 4));
		fl->mode = 1;
		fl->n = h->nlist;
		fl->subdim = sd < 1 || sd > 3 ? (h->dim == 1 && n == 4 ? 1 : 0) :
		    (int)sd;
		return check_pieces(h, fl->n, fl->subdim, e);
	}
	for (i = 0; i + 1 < n; i++) {
		if (v[i] == '%' && v[i + 1] == '%')
			i++;
		else if (v[i] == '%') {
			pct = 1;
			break;
		}
	}
	if (!pct) {
		fl->n = 1;
		fl->subdim = h->dim;
		return 0;
	}
	if ((rc = parse_pattern(h, &fl->pt, e)) != 0)
		return rc;
	fl->mode = 2;
	fl->n = (uint64_t)fl->pt.count;
	fl->subdim = fl->pt.subdim == 0 && h->dim == 1 ? 1 : fl->pt.subdim;
	return check_pieces(h, fl->n, fl->subdim, e);
}

static char *
files_path(const nrrd *h, const files *fl, uint64_t k, const char *dir)
{
	if (fl->mode == 0)
		return vx_imp_join(dir, h->val[F_DATA_FILE], h->vlen[F_DATA_FILE]);
	if (fl->mode == 1)
		return vx_imp_join(dir, h->list[k], h->list_len[k]);
	return pattern_name(&fl->pt, (int64_t)k, dir);
}

/* enc_holds: how many sample bytes `in` input bytes can hold at most in
 * the header's encoding. */
static uint64_t
enc_holds(const nrrd *h, uint64_t in)
{
	switch (h->enc) {
	case ENC_GZIP:
		return in > (UINT64_MAX >> 12) ? UINT64_MAX :
		    in * IMP_GZ_RATIO + ((uint64_t)1 << 16);
	case ENC_ASCII:   /* a digit and a separator per value */
		return (in / 2 + 1) * vx_scalar_size(h->type);
	case ENC_HEX:
		return in / 2;
	default:
		return in;
	}
}

/* files_size: the total size of the data files (stat only), so the
 * samples can be bounded before they are allocated. */
static int
files_size(const nrrd *h, const files *fl, const char *dir, uint64_t *sum,
    vx_err *e)
{
	uint64_t k;

	*sum = 0;
	for (k = 0; k < fl->n; k++) {
		char *path = files_path(h, fl, k, dir);
		struct stat st;

		if (path == NULL)
			return vx_err_set(e, VX_EDATA, "data file: name too long "
			    "or invalid");
		if (stat(path, &st) != 0) {
			int err = errno;

			vx_err_set(e, VX_ENOINPUT, "data file %s: %s", path,
			    strerror(err));
			free(path);
			return VX_ENOINPUT;
		}
		free(path);
		if (S_ISREG(st.st_mode) && st.st_size > 0)
			*sum += (uint64_t)st.st_size;
		else
			*sum = UINT64_MAX / 2;   /* pipes: bounded when read */
	}
	return 0;
}

/* read_detached: the samples from the header's data files. */
static int
read_detached(const nrrd *h, const files *fl, vx_imp_conv *c, const char *dir,
    vx_err *e)
{
	uint64_t per = c->total / fl->n, k;
	int rc;

	for (k = 0; k < fl->n; k++) {
		char *path = files_path(h, fl, k, dir);
		vx_imp_file f;
		vx_imp_src s;

		if (path == NULL)
			return vx_err_set(e, VX_EDATA, "data file: name too long "
			    "or invalid");
		if ((rc = vx_imp_file_load(&f, path, e)) != 0) {
			vx_err_push(e, "data file");
			free(path);
			return rc;
		}
		vx_imp_src_mem(&s, f.p, f.n);
		c->stop = c->next + per;
		rc = read_piece(h, c, &s, e);
		vx_imp_src_close(&s);
		vx_imp_file_free(&f);
		if (rc != 0) {
			vx_err_push(e, "data file %s", path);
			free(path);
			return rc;
		}
		free(path);
	}
	return 0;
}

/* nrrd_header: read and check the header from s; leaves s at the data. */
static int
nrrd_header(nrrd *h, vx_imp_src *s, vx_imp_frame *f, vx_err *e)
{
	const unsigned char *p;
	size_t avail;
	int rc;

	if ((rc = vx_imp_peek(s, NRRD_HDR_MAX, &p, &avail, e)) != 0)
		return rc;
	/* header lines point into a copy: the window moves later */
	if ((h->text = vx_malloc(avail + 1, e)) == NULL)
		return VX_ENOMEM;
	memcpy(h->text, p, avail);
	h->text[avail] = '\0';
	if ((rc = nrrd_lines(h, (const unsigned char *)h->text, avail,
	    avail < NRRD_HDR_MAX, e)) != 0)
		return rc;
	if (!h->ended && avail == NRRD_HDR_MAX)
		return vx_err_set(e, VX_EDATA, "nrrd: header longer than %zu "
		    "bytes (or no empty line ends it)", NRRD_HDR_MAX);
	if (!h->ended && h->val[F_DATA_FILE] == NULL)
		return vx_err_set(e, VX_EDATA, "nrrd: header ends without an "
		    "empty line, and names no data file");
	if ((rc = parse_sizes(h, e)) != 0 || (rc = parse_type(h, e)) != 0 ||
	    (rc = parse_encoding(h, e)) != 0 || (rc = parse_kinds(h, e)) != 0 ||
	    (rc = parse_space(h, e)) != 0 || (rc = parse_skips(h, e)) != 0)
		return rc;
	if (h->val[F_ENDIAN] != NULL) {
		h->big = vx_enum_val_n(&vx_endian_enum, h->val[F_ENDIAN],
		    h->vlen[F_ENDIAN]);
		if (h->big < 0)
			return vx_err_set(e, VX_EDATA, "nrrd: endian: '%s' is not "
			    "little or big", vx_imp_show(h->val[F_ENDIAN],
			    h->vlen[F_ENDIAN]));
	} else if (vx_scalar_size(h->type) > 1 && (h->enc == ENC_RAW ||
	    h->enc == ENC_GZIP || h->enc == ENC_HEX))
		return vx_err_set(e, VX_EDATA, "nrrd: endian: missing (needed "
		    "for type %s with %s encoding)",
		    vx_enum_str(&vx_scalar_enum, h->type), h->enc == ENC_HEX ?
		    "hex" : h->enc == ENC_GZIP ? "gzip" : "raw");
	if ((rc = nrrd_frame(h, f, e)) != 0)
		return rc;
	if (h->val[F_DATA_FILE] == NULL)
		return vx_imp_skip(s, h->hdr_len, e);
	return 0;
}

/* nrrd_read: the whole file from s. */
static int
nrrd_read(vx_grid *g, vx_imp_src *s, const char *dir, vx_err *e)
{
	uint64_t total, bytes, in;
	vx_imp_frame f;
	vx_imp_conv c;
	files fl;
	nrrd h;
	int rc;

	memset(&h, 0, sizeof h);
	if ((rc = nrrd_header(&h, s, &f, e)) != 0)
		goto out;
	if ((rc = vx_imp_total(h.sizes, vx_scalar_size(h.type), &total, &bytes,
	    "nrrd: sizes", e)) != 0)
		goto out;
	/* bound the samples by the input before allocating them */
	if (h.val[F_DATA_FILE] == NULL) {
		if (h.enc == ENC_GZIP && s->gz) {
			rc = vx_err_set(e, VX_EDATA, "nrrd: gzip encoding inside "
			    "a gzip-compressed file is not supported");
			goto out;
		}
		in = vx_imp_left_max(s);
	} else {
		if (dir == NULL) {
			rc = vx_err_set(e, VX_EDATA, "nrrd: data file: detached "
			    "data is not read from memory (no directory given)");
			goto out;
		}
		if ((rc = files_plan(&h, &fl, e)) != 0 ||
		    (rc = files_size(&h, &fl, dir, &in, e)) != 0) {
			vx_err_push(e, "nrrd");
			goto out;
		}
	}
	if (enc_holds(&h, in) < bytes) {
		rc = vx_err_set(e, VX_EDATA, "nrrd: data: truncated: %llu bytes "
		    "of %s data cannot hold the %llu bytes that sizes and type "
		    "imply", (unsigned long long)in, h.enc == ENC_GZIP ? "gzip" :
		    h.enc == ENC_ASCII ? "ascii" : h.enc == ENC_HEX ? "hex" :
		    "raw", (unsigned long long)bytes);
		goto out;
	}
	if ((rc = vx_imp_conv_begin(&c, g, h.sizes, h.type, h.big, &f, NULL,
	    e)) != 0)
		goto out;
	if (h.val[F_DATA_FILE] == NULL) {
		rc = read_piece(&h, &c, s, e);
		if (rc != 0)
			vx_err_push(e, "nrrd: data");
	} else {
		rc = read_detached(&h, &fl, &c, dir, e);
		if (rc != 0)
			vx_err_push(e, "nrrd");
	}
	if (rc == 0)
		rc = vx_imp_conv_end(&c, e);
	vx_imp_conv_abort(&c);
out:
	nrrd_free(&h);
	return rc;
}

int
vx_import_nrrd_mem(vx_grid *g, const void *buf, size_t n, const char *dir,
    vx_err *e)
{
	vx_imp_src s;
	int rc;

	vx_grid_init(g);
	if ((rc = vx_imp_src_auto(&s, buf, n, e)) != 0)
		return rc;
	rc = nrrd_read(g, &s, dir, e);
	vx_imp_src_close(&s);
	if (rc != 0)
		vx_grid_free(g);
	return rc;
}
