/* tfimport.c: transfer-function files (vx_tfimport.h): reading the file
 * with its bound, telling the format, and the helpers the readers share
 * (tf_priv.h): growing point lists and VTK's midpoint/sharpness segments
 * made piecewise linear. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tf_priv.h"
#include "vx_file.h"
#include "vx_tfimport.h"


/* ---- point lists ---- */

void
vx_tfi_pts_init(vx_tfi_pts *p, int dim)
{
	memset(p, 0, sizeof *p);
	p->dim = dim;
}

void
vx_tfi_pts_free(vx_tfi_pts *p)
{
	free(p->x);
	free(p->y);
	vx_tfi_pts_init(p, p->dim);
}

int
vx_tfi_pts_add(vx_tfi_pts *p, double x, const double *y, vx_err *e)
{
	if (p->n >= VX_TF_MAX_POINTS)
		return vx_err_set(e, VX_EDATA, "more than %d control points",
		    VX_TF_MAX_POINTS);
	if (p->n == p->cap) {
		int cap = p->cap ? 2 * p->cap : 16;
		double *nx, *ny;

		if (cap > VX_TF_MAX_POINTS)
			cap = VX_TF_MAX_POINTS;
		if ((nx = realloc(p->x, (size_t)cap * sizeof *nx)) == NULL)
			return vx_err_set(e, VX_ENOMEM, "out of memory");
		p->x = nx;
		if ((ny = realloc(p->y, (size_t)cap * (size_t)p->dim *
		    sizeof *ny)) == NULL)
			return vx_err_set(e, VX_ENOMEM, "out of memory");
		p->y = ny;
		p->cap = cap;
	}
	p->x[p->n] = x;
	memcpy(p->y + (size_t)p->n * (size_t)p->dim, y, (size_t)p->dim *
	    sizeof *y);
	p->n++;
	return 0;
}

int
vx_tfi_set(vx_tf_list *l, const vx_tfi_pts *p, vx_err *e)
{
	return vx_tf_list_set(l, p->n, p->dim, p->x, p->y, e);
}

int
vx_tfi_at(vx_err *e, const vx_json_node *at, const char *fmt, ...)
{
	char msg[VX_ERR_MSG];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	return vx_err_set(e, VX_EDATA, "line %d: %s", at ? at->line : 0, msg);
}

int
vx_tfi_unit(double v, const char *what, vx_err *e)
{
	if (!(v >= 0 && v <= 1))        /* NaN too */
		return vx_err_set(e, VX_EDATA, "%s: %.17g is outside [0, 1]",
		    what, v);
	return 0;
}

/* ---- VTK's segments ---- */

/* VTK keeps the midpoint off the segment's ends by this much */
#define MID_EPS 1e-5

double
vx_tfi_vtk_eval(double y0, double y1, double mid, double sharp, double s)
{
	double h1, h2, h3, h4, ss, sss, t, v, lo, hi;

	if (mid < MID_EPS)
		mid = MID_EPS;
	if (mid > 1 - MID_EPS)
		mid = 1 - MID_EPS;
	/* the midpoint: where the value is halfway */
	s = s < mid ? 0.5 * s / mid : 0.5 + 0.5 * (s - mid) / (1 - mid);
	if (sharp < 0.01)
		return y0 + s * (y1 - y0);
	if (sharp > 0.99)
		return s < 0.5 ? y0 : y1;
	/* sharper: s pushed towards the ends, then a Hermite curve whose end
	 * slopes shrink with the sharpness */
	if (s < 0.5)
		s = 0.5 * pow(2 * s, 1 + 10 * sharp);
	else if (s > 0.5)
		s = 1 - 0.5 * pow(2 * (1 - s), 1 + 10 * sharp);
	ss = s * s;
	sss = ss * s;
	h1 = 2 * sss - 3 * ss + 1;
	h2 = -2 * sss + 3 * ss;
	h3 = sss - 2 * ss + s;
	h4 = sss - ss;
	t = (1 - sharp) * (y1 - y0);
	v = h1 * y0 + h2 * y1 + h3 * t + h4 * t;
	lo = y0 < y1 ? y0 : y1;
	hi = y0 < y1 ? y1 : y0;
	return v < lo ? lo : v > hi ? hi : v;
}

typedef struct seg {
	double mid, sharp;
	const double *y0, *y1;
	int dim;
} seg;

static void
seg_eval(const void *ctx, double s, double *out)
{
	const seg *g = ctx;

	for (int c = 0; c < g->dim; c++)
		out[c] = vx_tfi_vtk_eval(g->y0[c], g->y1[c], g->mid, g->sharp, s);
}

/* refine: points strictly inside (a, b), in order, until the chord from a
 * to b is within the tolerance at its quarter points (depth bounded). */
static int
refine(vx_tfi_pts *p, double x0, double x1, int dim, vx_tfi_fn fn,
    const void *ctx, double a, double b, int depth, vx_err *e)
{
	double ya[3], yb[3], yq[3], m = 0.5 * (a + b);
	int ok = 1;

	fn(ctx, a, ya);
	fn(ctx, b, yb);
	for (int q = 1; q <= 3 && ok; q++) {
		fn(ctx, a + (b - a) * q / 4, yq);
		for (int c = 0; c < dim; c++)
			if (fabs(yq[c] - (ya[c] + (yb[c] - ya[c]) * q / 4)) >
			    VX_TFI_SHARP_TOL)
				ok = 0;
	}
	if (ok || depth >= 16)
		return 0;
	if (refine(p, x0, x1, dim, fn, ctx, a, m, depth + 1, e) != 0)
		return e->code;
	fn(ctx, m, yq);
	if (vx_tfi_pts_add(p, x0 + m * (x1 - x0), yq, e) != 0)
		return e->code;
	return refine(p, x0, x1, dim, fn, ctx, m, b, depth + 1, e);
}

int
vx_tfi_curve(vx_tfi_pts *p, double x0, double x1, vx_tfi_fn fn,
    const void *ctx, vx_err *e)
{
	return refine(p, x0, x1, p->dim, fn, ctx, 0, 1, 0, e);
}

int
vx_tfi_vtk(vx_tfi_pts *p, int n, int dim, const double *x,
    const double *y, const double *mid, const double *sharp, vx_err *e)
{
	for (int i = 0; i < n; i++) {
		const double *yi = y + (size_t)i * (size_t)dim;
		seg g;
		double x0, x1;

		if (vx_tfi_pts_add(p, x[i], yi, e) != 0)
			return e->code;
		if (i + 1 == n || x[i + 1] == x[i])
			continue;
		x0 = x[i];
		x1 = x[i + 1];
		g.mid = mid ? mid[i] : 0.5;
		g.sharp = sharp ? sharp[i] : 0;
		g.y0 = yi;
		g.y1 = yi + dim;
		g.dim = dim;
		if (g.mid < MID_EPS)
			g.mid = MID_EPS;
		if (g.mid > 1 - MID_EPS)
			g.mid = 1 - MID_EPS;
		if (g.sharp < 0.01) {
			double ym[3], xm = x0 + g.mid * (x1 - x0);

			if (g.mid == 0.5)
				continue;       /* the plain line */
			for (int c = 0; c < dim; c++)
				ym[c] = 0.5 * (g.y0[c] + g.y1[c]);
			if (vx_tfi_pts_add(p, xm, ym, e) != 0)
				return e->code;
		} else if (g.sharp > 0.99) {
			double xm = x0 + g.mid * (x1 - x0);

			if (vx_tfi_pts_add(p, xm, g.y0, e) != 0 ||
			    vx_tfi_pts_add(p, xm, g.y1, e) != 0)
				return e->code;
		} else if (vx_tfi_curve(p, x0, x1, seg_eval, &g, e) != 0)
			return e->code;
	}
	return 0;
}

/* ---- files ---- */

/* load: the file's bytes, at most VX_TF_FILE_MAX. */
static int
load(const char *path, unsigned char **buf, size_t *n, vx_err *e)
{
	struct stat st;
	FILE *f;
	int fd, rc;

	if (strcmp(path, "-") == 0)
		fd = dup(STDIN_FILENO);
	else
		fd = open(path, O_RDONLY);
	if (fd < 0)
		return vx_err_set(e, VX_ENOINPUT, "%s", strerror(errno));
	if (fstat(fd, &st) != 0) {
		rc = vx_err_set(e, VX_EIO, "%s", strerror(errno));
		close(fd);
		return rc;
	}
	if (S_ISDIR(st.st_mode)) {
		close(fd);
		return vx_err_set(e, VX_ENOINPUT, "is a directory");
	}
	if (S_ISREG(st.st_mode) && (uint64_t)st.st_size > VX_TF_FILE_MAX) {
		close(fd);
		return vx_err_set(e, VX_EDATA, "larger than %zu bytes",
		    VX_TF_FILE_MAX);
	}
	if ((f = fdopen(fd, "rb")) == NULL) {
		rc = vx_err_set(e, VX_EIO, "%s", strerror(errno));
		close(fd);
		return rc;
	}
	rc = vx_file_read_all(f, VX_TF_FILE_MAX, buf, n, e);
	fclose(f);
	if (rc == 0 && *n == 0) {
		free(*buf);
		*buf = NULL;
		return vx_err_set(e, VX_ENOINPUT, "empty file");
	}
	return rc;
}

/* first_byte: the first byte that is not a blank (or a UTF-8 byte-order
 * mark), or -1. */
static int
first_byte(const unsigned char *p, size_t n)
{
	size_t i = 0;

	if (n >= 3 && memcmp(p, "\xef\xbb\xbf", 3) == 0)
		i = 3;
	for (; i < n; i++)
		if (p[i] != ' ' && p[i] != '\t' && p[i] != '\r' && p[i] != '\n')
			return p[i];
	return -1;
}

/* dir_of: path's directory (malloc'ed), "." when it has none. */
static char *
dir_of(const char *path, vx_err *e)
{
	const char *slash = strrchr(path, '/');
	size_t k = slash ? (size_t)(slash - path) : 1;
	char *d;

	if (slash == path)
		k = 1;
	if ((d = vx_malloc(k + 1, e)) == NULL)
		return NULL;
	memcpy(d, slash ? path : ".", k);
	d[k] = '\0';
	return d;
}

static int
read_json(const unsigned char *buf, size_t n, vx_tf_format fmt, vx_tf *tf,
    vx_err *e)
{
	const vx_json_node *top;
	vx_json j;
	int rc;

	if ((rc = vx_json_parse(&j, buf, n, VX_TFI_JSON_DEPTH,
	    VX_TFI_JSON_NODES, e)) != 0)
		return rc;
	top = vx_json_at(&j, 0);
	if (fmt == VX_TF_FORMAT_AUTO)   /* Slicer's has volumeProperties */
		fmt = vx_json_get(&j, top, "volumeProperties", NULL) ?
		    VX_TF_FORMAT_SLICER : VX_TF_FORMAT_PARAVIEW;
	if (fmt == VX_TF_FORMAT_SLICER)
		rc = vx_tfi_slicer_json(&j, tf, e);
	else
		rc = vx_tfi_paraview(&j, tf, e);
	vx_json_free(&j);
	return rc;
}

int
vx_tf_import_mem(const void *buf_, size_t n, vx_tf_format fmt,
    const char *dir, vx_tf *tf, vx_err *e)
{
	const unsigned char *buf = buf_;
	vx_err local;
	int rc = 0, c;

	if (e == NULL)                  /* the readers need somewhere to say */
		e = &local;
	vx_tf_init(tf);
	if (fmt <= VX_TF_FORMAT_UNKNOWN || fmt >= VX_TF_FORMAT_LAST)
		return vx_err_set(e, VX_EUSAGE, "unknown transfer-function "
		    "format %d", (int)fmt);
	if (n > VX_TF_FILE_MAX)
		return vx_err_set(e, VX_EDATA, "larger than %zu bytes",
		    VX_TF_FILE_MAX);
	if (n == 0)
		return vx_err_set(e, VX_ENOINPUT, "empty file");
	c = first_byte(buf, n);
	if (fmt == VX_TF_FORMAT_AUTO) {
		if (n >= 4 && memcmp(buf, "NRRD", 4) == 0)
			fmt = VX_TF_FORMAT_MITER;
		else if (c == '[' || c == '{')
			fmt = VX_TF_FORMAT_PARAVIEW;   /* or Slicer's: read_json */
		else if (c >= '0' && c <= '9')
			fmt = VX_TF_FORMAT_SLICER;
		else
			return vx_err_set(e, VX_EDATA, "not a transfer function "
			    "(a ParaView JSON, a Slicer .vp or .vp.json, or a "
			    "miter txf NRRD)");
		if (fmt == VX_TF_FORMAT_PARAVIEW)
			fmt = VX_TF_FORMAT_AUTO;
	}
	switch (fmt) {
	case VX_TF_FORMAT_AUTO:
	case VX_TF_FORMAT_PARAVIEW:
		rc = read_json(buf, n, fmt, tf, e);
		break;
	case VX_TF_FORMAT_SLICER:
		if (c == '{')
			rc = read_json(buf, n, fmt, tf, e);
		else
			rc = vx_tfi_slicer_vp((const char *)buf, n, tf, e);
		break;
	case VX_TF_FORMAT_MITER:
		rc = vx_tfi_miter(buf, n, dir, tf, e);
		break;
	default:
		rc = vx_err_set(e, VX_EINTERNAL, "format %d", (int)fmt);
		break;
	}
	if (rc == 0)
		rc = vx_tf_check(tf, e);
	if (rc != 0)
		vx_tf_free(tf);
	return rc;
}

int
vx_tf_import(const char *path, vx_tf_format fmt, vx_tf *tf, vx_err *e)
{
	unsigned char *buf = NULL;
	char *dir = NULL;
	size_t n = 0;
	int rc;
	vx_err local;

	if (e == NULL)
		e = &local;
	vx_tf_init(tf);
	if (fmt <= VX_TF_FORMAT_UNKNOWN || fmt >= VX_TF_FORMAT_LAST)
		return vx_err_set(e, VX_EUSAGE, "unknown transfer-function "
		    "format %d", (int)fmt);
	if ((rc = load(path, &buf, &n, e)) == 0) {
		if ((dir = dir_of(strcmp(path, "-") == 0 ? "." : path, e)) ==
		    NULL)
			rc = VX_ENOMEM;
		else
			rc = vx_tf_import_mem(buf, n, fmt, dir, tf, e);
	}
	free(buf);
	free(dir);
	if (rc != 0)
		vx_err_push(e, "%s", path);
	return rc;
}
