/* tf_miter.c: teem miter's transfer functions (formats/transfer.md,
 * Imports): a NRRD of dimension 2 or 3 whose axis 0 holds the range
 * (its label spells it, one character per value, from "ARGBEadsp") and
 * whose other axes are the domain, labelled with gage items
 * ("gage(v)", "gage(scalar:gm)", ...) and spanning [axis min, axis max].
 * The header's fields are read here; the samples are decoded by the NRRD
 * reader from a header rebuilt with only the fields it needs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "import_priv.h"
#include "tf_priv.h"
#include "vx_import.h"
#include "vx_scan.h"

#define HDR_MAX ((size_t)65536)

enum { VAR_VALUE = 1, VAR_GMAG };
enum {
	K_DIMENSION, K_SIZES, K_TYPE, K_LABELS, K_MINS, K_MAXS, K_CENTERS,
	K_OLDMIN, K_OLDMAX, K_ENCODING, K_ENDIAN, K_LINESKIP, K_BYTESKIP,
	K_DATAFILE, K_LAST
};
/* the fields read (the others are ignored); those marked pass go into the
 * rebuilt header */
static const struct { const char *name[2]; int pass; } keys[K_LAST] = {
	{ { "dimension", NULL }, 0 }, { { "sizes", NULL }, 0 },
	{ { "type", NULL }, 1 }, { { "labels", NULL }, 0 },
	{ { "axis mins", "axismins" }, 0 }, { { "axis maxs", "axismaxs" }, 0 },
	{ { "centers", "centerings" }, 0 }, { { "old min", "oldmin" }, 0 },
	{ { "old max", "oldmax" }, 0 }, { { "encoding", NULL }, 1 },
	{ { "endian", NULL }, 1 }, { { "line skip", "lineskip" }, 1 },
	{ { "byte skip", "byteskip" }, 1 }, { { "data file", "datafile" }, 1 },
};

typedef struct txf {
	const char *val[K_LAST];
	size_t vlen[K_LAST];
	int line[K_LAST];
	size_t hdr_len;           /* bytes up to and including the empty line */
	int dim;
	int64_t sizes[3];
	char label[3][64];
	double mins[3], maxs[3];
	int node[3];              /* node-centred axis */
} txf;

/* header: the fields of the header at buf. */
static int
header(txf *t, const unsigned char *buf, size_t n, vx_err *e)
{
	const char *line;
	size_t len;
	vx_scan s;
	int lineno = 1, ended = 0;

	vx_scan_init(&s, buf, n < HDR_MAX ? n : HDR_MAX);
	if (!vx_scan_line(&s, n <= HDR_MAX, &line, &len) || len != 8 ||
	    memcmp(line, "NRRD000", 7) != 0 || line[7] < '1' || line[7] > '6')
		return vx_err_set(e, VX_EDATA, "line 1: not a NRRD magic "
		    "(NRRD0001 to NRRD0006)");
	while (vx_scan_line(&s, n <= HDR_MAX, &line, &len)) {
		const char *colon = NULL;
		int k;

		lineno++;
		if (len == 0) {
			ended = 1;
			break;
		}
		if (memchr(line, '\0', len) != NULL)
			return vx_err_set(e, VX_EDATA, "line %d: NUL byte", lineno);
		if (line[0] == '#')
			continue;
		for (size_t i = 0; i + 1 < len; i++)
			if (line[i] == ':' && (line[i + 1] == ' ' ||
			    line[i + 1] == '=')) {
				colon = line + i;
				break;
			}
		if (colon == NULL)
			return vx_err_set(e, VX_EDATA, "line %d: expected 'field: "
			    "value' or 'key:=value'", lineno);
		if (colon[1] == '=')
			continue;                       /* key:=value */
		for (k = 0; k < K_LAST; k++)
			if (vx_word_eq(line, (size_t)(colon - line),
			    keys[k].name[0], 1) || (keys[k].name[1] &&
			    vx_word_eq(line, (size_t)(colon - line),
			    keys[k].name[1], 1)))
				break;
		if (k == K_LAST)
			continue;                       /* not needed here */
		if (t->val[k] != NULL)
			return vx_err_set(e, VX_EDATA, "line %d: field '%s' given "
			    "twice", lineno, keys[k].name[0]);
		t->val[k] = colon + 2;
		t->vlen[k] = len - (size_t)(colon + 2 - line);
		t->line[k] = lineno;
		if (k == K_DATAFILE && t->vlen[k] >= 4 &&
		    memcmp(t->val[k], "LIST", 4) == 0)
			return vx_err_set(e, VX_EDATA, "line %d: a data file LIST "
			    "is not read for a transfer function", lineno);
	}
	if (!ended && t->val[K_DATAFILE] == NULL)
		return vx_err_set(e, VX_EDATA, "the header does not end (no empty "
		    "line within %zu bytes)", HDR_MAX);
	t->hdr_len = (size_t)(s.p - s.base);
	return 0;
}

/* words: the dim blank-separated words of field k. */
static int
words(const txf *t, int k, const char *w[3], size_t wl[3], vx_err *e)
{
	const char *more;
	vx_scan s;
	int a;

	if (t->val[k] == NULL)
		return vx_err_set(e, VX_EDATA, "no field '%s'", keys[k].name[0]);
	vx_scan_init(&s, t->val[k], t->vlen[k]);
	for (a = 0; a < t->dim; a++)
		if ((wl[a] = vx_scan_word(&s, &w[a])) == 0)
			break;
	if (a < t->dim || vx_scan_word(&s, &more) != 0)
		return vx_err_set(e, VX_EDATA, "line %d: field '%s': expected %d "
		    "values", t->line[k], keys[k].name[0], t->dim);
	return 0;
}

/* labels: the dim quoted strings of "labels". */
static int
labels(txf *t, vx_err *e)
{
	const char *p = t->val[K_LABELS], *end;
	int a;

	if (p == NULL)
		return vx_err_set(e, VX_EDATA, "no field 'labels': a txf names "
		    "its range and domain there");
	end = p + t->vlen[K_LABELS];
	for (a = 0; a < t->dim; a++) {
		size_t k = 0;

		while (p < end && (*p == ' ' || *p == '\t'))
			p++;
		if (p == end || *p != '"')
			goto bad;
		for (p++; p < end && *p != '"'; p++) {
			if (*p == '\\' && p + 1 < end)
				p++;
			if (k + 1 >= sizeof t->label[a])
				goto bad;
			t->label[a][k++] = *p;
		}
		if (p == end)
			goto bad;
		p++;
		t->label[a][k] = '\0';
	}
	while (p < end && (*p == ' ' || *p == '\t' || *p == '\r'))
		p++;
	if (p == end)
		return 0;
bad:
	return vx_err_set(e, VX_EDATA, "line %d: field 'labels': expected %d "
	    "quoted labels (each under 64 bytes)", t->line[K_LABELS], t->dim);
}

/* show: a label as printable text for messages */
static const char *
show(const char *label)
{
	return vx_imp_show(label, strlen(label));
}

/* variable: the domain variable a gage label names, or 0. */
static int
variable(const char *l)
{
	static const struct { const char *name; int var; } vars[] = {
		{ "v", VAR_VALUE }, { "val", VAR_VALUE },
		{ "value", VAR_VALUE }, { "gm", VAR_GMAG },
		{ "gmag", VAR_GMAG }, { "gradient magnitude", VAR_GMAG },
		{ "grad mag", VAR_GMAG }, { "g mag", VAR_GMAG },
	};
	size_t n = strlen(l);

	if (n < 7 || memcmp(l, "gage(", 5) != 0 || l[n - 1] != ')')
		return 0;
	l += 5;
	n -= 6;
	if (n > 7 && memcmp(l, "scalar:", 7) == 0) {
		l += 7;
		n -= 7;
	}
	for (size_t i = 0; i < sizeof vars / sizeof vars[0]; i++)
		if (vx_word_eq(l, n, vars[i].name, 1))
			return vars[i].var;
	return 0;
}

static int
f64(const txf *t, int k, double *v, vx_err *e)
{
	vx_scan s;
	const char *w, *more;
	size_t wl;

	vx_scan_init(&s, t->val[k], t->vlen[k]);
	if ((wl = vx_scan_word(&s, &w)) == 0 || vx_num_f64(w, wl, 0, v) != 0 ||
	    vx_scan_word(&s, &more) != 0)
		return vx_err_set(e, VX_EDATA, "line %d: field '%s': not a "
		    "finite number", t->line[k], keys[k].name[0]);
	return 0;
}

/* fields: dimension, sizes, labels, mins and maxs, checked. */
static int
fields(txf *t, vx_err *e)
{
	const char *w[3];
	size_t wl[3];
	int64_t v;

	if (t->val[K_DIMENSION] == NULL || vx_num_i64(t->val[K_DIMENSION],
	    t->vlen[K_DIMENSION], 1, 16, &v) != 0 || v < 2 || v > 3)
		return vx_err_set(e, VX_EDATA, "line %d: field 'dimension': a "
		    "txf has 2 (one domain variable) or 3 (two)",
		    t->line[K_DIMENSION]);
	t->dim = (int)v;
	if (words(t, K_SIZES, w, wl, e) != 0)
		return e->code;
	for (int a = 0; a < t->dim; a++)
		if (vx_num_i64(w[a], wl[a], 1, a == 0 ? 9 : t->dim == 2 ?
		    VX_TF_MAX_POINTS : VX_TF_MAX_TABLE, &t->sizes[a]) != 0 ||
		    (a > 0 && t->sizes[a] < 2))
			return vx_err_set(e, VX_EDATA, "line %d: field 'sizes': "
			    "axis %d: '%s' is not in [%d, %d]", t->line[K_SIZES],
			    a, vx_imp_show(w[a], wl[a]), a ? 2 : 1,
			    a == 0 ? 9 : t->dim == 2 ? VX_TF_MAX_POINTS :
			    VX_TF_MAX_TABLE);
	if (labels(t, e) != 0)
		return e->code;
	if (strlen(t->label[0]) != (size_t)t->sizes[0] ||
	    strspn(t->label[0], "ARGBEadsp") != strlen(t->label[0]))
		return vx_err_set(e, VX_EDATA, "axis 0: label \"%s\" with size "
		    "%lld: the range axis is labelled with one of "
		    "\"ARGBEadsp\" per value", show(t->label[0]),
		    (long long)t->sizes[0]);
	if (words(t, K_MINS, w, wl, e) != 0)
		return e->code;
	for (int a = 0; a < t->dim; a++)
		if (vx_num_f64(w[a], wl[a], VX_NUM_NONFINITE, &t->mins[a]) != 0)
			return vx_err_set(e, VX_EDATA, "line %d: field 'axis "
			    "mins': axis %d is not a number", t->line[K_MINS], a);
	if (words(t, K_MAXS, w, wl, e) != 0)
		return e->code;
	for (int a = 0; a < t->dim; a++)
		if (vx_num_f64(w[a], wl[a], VX_NUM_NONFINITE, &t->maxs[a]) != 0)
			return vx_err_set(e, VX_EDATA, "line %d: field 'axis "
			    "maxs': axis %d is not a number", t->line[K_MAXS], a);
	for (int a = 1; a < t->dim; a++)
		if (!isfinite(t->mins[a]) || !isfinite(t->maxs[a]) ||
		    !(t->mins[a] < t->maxs[a]))
			return vx_err_set(e, VX_EDATA, "axis %d: [axis min, axis "
			    "max] = [%g, %g] is not a finite, non-empty range", a,
			    t->mins[a], t->maxs[a]);
	if (t->val[K_CENTERS] != NULL) {
		if (words(t, K_CENTERS, w, wl, e) != 0)
			return e->code;
		for (int a = 0; a < t->dim; a++)
			t->node[a] = vx_word_eq(w[a], wl[a], "node", 1);
	}
	return 0;
}

/* samples: the data decoded by the NRRD reader from a rebuilt header;
 * g initialized by the call. */
static int
samples(const txf *t, const unsigned char *buf, size_t n, const char *dir,
    vx_grid *g, vx_err *e)
{
	char head[2048];
	size_t k, total;
	unsigned char *copy;
	int rc;

	k = (size_t)snprintf(head, sizeof head, "NRRD0004\ndimension: %d\n"
	    "sizes: %lld %lld", t->dim, (long long)t->sizes[0],
	    (long long)t->sizes[1]);
	if (t->dim == 3)
		k += (size_t)snprintf(head + k, sizeof head - k, " %lld",
		    (long long)t->sizes[2]);
	k += (size_t)snprintf(head + k, sizeof head - k, "\n");
	for (int f = 0; f < K_LAST; f++) {
		if (!keys[f].pass || t->val[f] == NULL)
			continue;
		if (t->vlen[f] > 512)
			return vx_err_set(e, VX_EDATA, "line %d: field '%s' is "
			    "longer than 512 bytes", t->line[f], keys[f].name[0]);
		k += (size_t)snprintf(head + k, sizeof head - k, "%s: %.*s\n",
		    keys[f].name[0], (int)t->vlen[f], t->val[f]);
	}
	k += (size_t)snprintf(head + k, sizeof head - k, "\n");
	if (k >= sizeof head)
		return vx_err_set(e, VX_EINTERNAL, "rebuilt header too long");
	total = k + (n - t->hdr_len);
	if ((copy = vx_malloc(total, e)) == NULL)
		return VX_ENOMEM;
	memcpy(copy, head, k);
	memcpy(copy + k, buf + t->hdr_len, n - t->hdr_len);
	rc = vx_import_nrrd_mem(g, copy, total, dir, e);
	free(copy);
	return rc;
}

/* unquantize: miter's reading of a sample: uchar v as the centre of its
 * 256th of [old min, old max] (default [0,1]), float and double as is. */
static int
unquantizer(const txf *t, int *uchar, double *lo, double *hi, vx_err *e)
{
	const char *p = t->val[K_TYPE];
	size_t n = t->vlen[K_TYPE];

	*uchar = 0;
	*lo = 0;
	*hi = 1;
	if (p == NULL)
		return vx_err_set(e, VX_EDATA, "no field 'type'");
	if (vx_word_eq(p, n, "float", 1) || vx_word_eq(p, n, "double", 1))
		return 0;
	if (!(vx_word_eq(p, n, "uchar", 1) || vx_word_eq(p, n, "unsigned char",
	    1) || vx_word_eq(p, n, "uint8", 1) || vx_word_eq(p, n, "uint8_t", 1)))
		return vx_err_set(e, VX_EDATA, "line %d: type '%s': a txf is "
		    "float, double or uchar", t->line[K_TYPE], vx_imp_show(p, n));
	*uchar = 1;
	if ((t->val[K_OLDMIN] && f64(t, K_OLDMIN, lo, e) != 0) ||
	    (t->val[K_OLDMAX] && f64(t, K_OLDMAX, hi, e) != 0))
		return e->code;
	return 0;
}

int
vx_tfi_miter(const unsigned char *buf, size_t n, const char *dir,
    vx_tf *tf, vx_err *e)
{
	int var[3] = { 0, 0, 0 }, ch[4] = { -1, -1, -1, -1 }, uchar, rc;
	double qlo, qhi;
	const char *rgba = "RGBA";
	float *table = NULL;
	vx_grid g;
	txf t;

	memset(&t, 0, sizeof t);
	if ((rc = header(&t, buf, n, e)) != 0 || (rc = fields(&t, e)) != 0 ||
	    (rc = unquantizer(&t, &uchar, &qlo, &qhi, e)) != 0)
		return rc;
	for (int a = 1; a < t.dim; a++)
		if ((var[a] = variable(t.label[a])) == 0)
			return vx_err_set(e, VX_EDATA, "axis %d: label \"%s\": "
			    "only the value (gage(v)) and the gradient magnitude "
			    "(gage(gm)) are read", a, show(t.label[a]));
	if (t.dim == 2 && var[1] != VAR_VALUE)
		return vx_err_set(e, VX_EDATA, "axis 1: a 1-D txf over \"%s\": "
		    "only one over the value (gage(v)) is read", show(t.label[1]));
	if (t.dim == 3 && var[1] == var[2])
		return vx_err_set(e, VX_EDATA, "axes 1 and 2 are both \"%s\": a "
		    "2-D txf is over the value and the gradient magnitude",
		    show(t.label[1]));
	for (int c = 0; c < 4; c++) {
		const char *q = strchr(t.label[0], rgba[c]);

		if (q && strchr(q + 1, rgba[c]))
			return vx_err_set(e, VX_EDATA, "axis 0: label \"%s\" "
			    "names %c twice", t.label[0], rgba[c]);
		ch[c] = q ? (int)(q - t.label[0]) : -1;
	}
	if (ch[3] < 0)
		return vx_err_set(e, VX_EDATA, "axis 0: label \"%s\" has no A: "
		    "the txf gives no opacity", show(t.label[0]));
	if ((ch[0] < 0) != (ch[1] < 0) || (ch[1] < 0) != (ch[2] < 0))
		return vx_err_set(e, VX_EDATA, "axis 0: label \"%s\" has some of "
		    "R, G and B but not all", show(t.label[0]));
	if ((rc = samples(&t, buf, n, dir, &g, e)) != 0)
		return rc;
	{
		int64_t nv = t.sizes[1], ng = t.dim == 3 ? t.sizes[2] : 1;
		int vax = 1, size[2];
		double vr[2], gr[2];
		vx_tfi_pts cp, op;

		if (t.dim == 3 && var[1] == VAR_GMAG) {
			vax = 2;                /* the value along axis 2 */
			nv = t.sizes[2];
			ng = t.sizes[1];
		}
		vx_tfi_pts_init(&cp, 3);
		vx_tfi_pts_init(&op, 1);
		if (t.dim == 3 && (table = vx_malloc(4 * (size_t)nv * (size_t)ng *
		    sizeof *table, e)) == NULL) {
			rc = VX_ENOMEM;
			goto done;
		}
		for (int64_t j = 0; j < ng && rc == 0; j++)
			for (int64_t i = 0; i < nv && rc == 0; i++) {
				int64_t y = vax == 1 ? i : j, z = vax == 1 ? j : i;
				double px[4] = { 1, 1, 1, 0 }, xi;

				for (int c = 0; c < 4; c++) {
					double v;

					if (ch[c] < 0)
						continue;
					v = vx_grid_get(&g, ch[c], y, z);
					if (uchar)
						v = qlo + (v + 0.5) / 256 * (qhi - qlo);
					if (!(v >= 0 && v <= 1)) {
						rc = vx_err_set(e, VX_EDATA, "sample "
						    "(%d, %lld, %lld): %c = %.9g is "
						    "outside [0, 1]", ch[c], (long long)y,
						    (long long)z, rgba[c], v);
						break;
					}
					px[c] = v;
				}
				if (rc != 0)
					break;
				if (t.dim == 3) {
					for (int c = 0; c < 4; c++)
						table[4 * (i + nv * j) + c] =
						    (float)px[c];
					continue;
				}
				xi = t.node[1] ? t.mins[1] + (double)i *
				    (t.maxs[1] - t.mins[1]) / (double)(nv - 1) :
				    t.mins[1] + ((double)i + 0.5) * (t.maxs[1] -
				    t.mins[1]) / (double)nv;
				if ((ch[0] >= 0 && (rc = vx_tfi_pts_add(&cp, xi, px,
				    e)) != 0) || (rc = vx_tfi_pts_add(&op, xi,
				    px + 3, e)) != 0)
					break;
			}
		if (rc != 0)
			goto done;
		if (t.dim == 2) {
			if ((cp.n > 0 && (rc = vx_tfi_set(&tf->color, &cp, e)) !=
			    0) || (rc = vx_tfi_set(&tf->opacity, &op, e)) != 0)
				goto done;
		} else {
			int va = vax, ga = vax == 1 ? 2 : 1;

			/* node-centred axes: the cells' range is half a step
			 * wider on each side */
			vr[0] = t.mins[va];
			vr[1] = t.maxs[va];
			gr[0] = t.mins[ga];
			gr[1] = t.maxs[ga];
			if (t.node[va]) {
				double h = (vr[1] - vr[0]) / (double)(nv - 1);

				vr[0] -= h / 2;
				vr[1] += h / 2;
			}
			if (t.node[ga]) {
				double h = (gr[1] - gr[0]) / (double)(ng - 1);

				gr[0] -= h / 2;
				gr[1] += h / 2;
			}
			size[0] = (int)nv;
			size[1] = (int)ng;
			rc = vx_tf_table_set(tf, size, vr, gr, table, e);
		}
done:
		vx_tfi_pts_free(&cp);
		vx_tfi_pts_free(&op);
	}
	free(table);
	vx_grid_free(&g);
	return rc;
}
