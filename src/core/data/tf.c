/* tf.c: transfer-function containers (vx_tf.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vx_tf.h"

static const vx_enum_name tf_format_names[] = {
	{ "auto", VX_TF_FORMAT_AUTO },
	{ "paraview", VX_TF_FORMAT_PARAVIEW },
	{ "slicer", VX_TF_FORMAT_SLICER },
	{ "miter", VX_TF_FORMAT_MITER },
	{ NULL, VX_TF_FORMAT_UNKNOWN }
};
const vx_enum vx_tf_format_enum = { "transfer-function format",
    tf_format_names, "unknown", 0 };

void
vx_tf_init(vx_tf *tf)
{
	memset(tf, 0, sizeof *tf);
}

void
vx_tf_list_free(vx_tf_list *l)
{
	free(l->x);
	free(l->y);
	memset(l, 0, sizeof *l);
}

void
vx_tf_free(vx_tf *tf)
{
	vx_tf_list_free(&tf->color);
	vx_tf_list_free(&tf->opacity);
	vx_tf_list_free(&tf->transport);
	vx_tf_list_free(&tf->surface);
	vx_tf_list_free(&tf->gradient);
	free(tf->rgba);
	vx_tf_init(tf);
}

static int
unit(double y)
{
	return y >= 0.0 && y <= 1.0;       /* false for NaN */
}

int
vx_tf_list_set(vx_tf_list *l, int n, int dim, const double *x,
    const double *y, vx_err *e)
{
	double *nx, *ny;

	if (n < 1 || n > VX_TF_MAX_POINTS)
		return vx_err_set(e, VX_EDATA, "%d control points (1 to %d)",
		    n, VX_TF_MAX_POINTS);
	if (dim != 1 && dim != 3)
		return vx_err_set(e, VX_EDATA, "%d values per point (1 or 3)",
		    dim);
	for (int i = 0; i < n; i++) {
		if (!isfinite(x[i]))
			return vx_err_set(e, VX_EDATA, "point %d: abscissa is "
			    "not finite", i + 1);
		if (i > 0 && x[i] < x[i - 1])
			return vx_err_set(e, VX_EDATA, "point %d: abscissa %.17g "
			    "is less than the one before it (%.17g)", i + 1,
			    x[i], x[i - 1]);
		for (int c = 0; c < dim; c++)
			if (!unit(y[dim * i + c]))
				return vx_err_set(e, VX_EDATA, "point %d: value "
				    "%.17g is outside [0, 1]", i + 1,
				    y[dim * i + c]);
	}
	nx = vx_malloc((size_t)n * sizeof *nx, e);
	ny = nx ? vx_malloc((size_t)n * (size_t)dim * sizeof *ny, e) : NULL;
	if (ny == NULL) {
		free(nx);
		return VX_ENOMEM;
	}
	memcpy(nx, x, (size_t)n * sizeof *nx);
	memcpy(ny, y, (size_t)n * (size_t)dim * sizeof *ny);
	vx_tf_list_free(l);
	l->n = n;
	l->dim = dim;
	l->x = nx;
	l->y = ny;
	return 0;
}

void
vx_tf_list_eval(const vx_tf_list *l, double t, double *out)
{
	int lo = 0, hi = l->n;     /* find the last i with x[i] <= t */
	const double *a, *b;
	double f;

	if (!(t >= l->x[0])) {     /* below, or NaN */
		memcpy(out, l->y, (size_t)l->dim * sizeof *out);
		return;
	}
	while (hi - lo > 1) {
		int mid = lo + (hi - lo) / 2;

		if (l->x[mid] <= t)
			lo = mid;
		else
			hi = mid;
	}
	a = l->y + (size_t)l->dim * (size_t)lo;
	if (lo == l->n - 1) {
		memcpy(out, a, (size_t)l->dim * sizeof *out);
		return;
	}
	b = a + l->dim;            /* x[lo] <= t < x[lo + 1] */
	f = (t - l->x[lo]) / (l->x[lo + 1] - l->x[lo]);
	for (int c = 0; c < l->dim; c++)
		out[c] = a[c] + f * (b[c] - a[c]);
}

int
vx_tf_table_set(vx_tf *tf, const int size[2], const double vrange[2],
    const double grange[2], const float *rgba, vx_err *e)
{
	size_t n;
	float *t;

	for (int a = 0; a < 2; a++)
		if (size[a] < 1 || size[a] > VX_TF_MAX_TABLE)
			return vx_err_set(e, VX_EDATA, "table axis %d has %d "
			    "cells (1 to %d)", a, size[a], VX_TF_MAX_TABLE);
	if (!isfinite(vrange[0]) || !isfinite(vrange[1]) ||
	    !(vrange[0] < vrange[1]))
		return vx_err_set(e, VX_EDATA, "table value range [%g, %g] is "
		    "empty or not finite", vrange[0], vrange[1]);
	if (!isfinite(grange[0]) || !isfinite(grange[1]) ||
	    !(grange[0] < grange[1]))
		return vx_err_set(e, VX_EDATA, "table gradient range [%g, %g] "
		    "is empty or not finite", grange[0], grange[1]);
	n = 4 * (size_t)size[0] * (size_t)size[1];
	for (size_t i = 0; i < n; i++)
		if (!unit(rgba[i]))
			return vx_err_set(e, VX_EDATA, "table cell %zu: value "
			    "%g is outside [0, 1]", i / 4, (double)rgba[i]);
	if ((t = vx_malloc(n * sizeof *t, e)) == NULL)
		return VX_ENOMEM;
	memcpy(t, rgba, n * sizeof *t);
	free(tf->rgba);
	tf->rgba = t;
	tf->has_table = 1;
	for (int a = 0; a < 2; a++) {
		tf->size[a] = size[a];
		tf->vrange[a] = vrange[a];
		tf->grange[a] = grange[a];
	}
	return 0;
}

static int
dim_ok(const vx_tf_list *l, int dim, const char *name, vx_err *e)
{
	if (l->n > 0 && l->dim != dim)
		return vx_err_set(e, VX_EDATA, "the %s list has %d values per "
		    "point, not %d", name, l->dim, dim);
	return 0;
}

int
vx_tf_check(const vx_tf *tf, vx_err *e)
{
	int rc;

	if ((rc = dim_ok(&tf->color, 3, "color", e)) != 0 ||
	    (rc = dim_ok(&tf->opacity, 1, "opacity", e)) != 0 ||
	    (rc = dim_ok(&tf->transport, 3, "transport", e)) != 0 ||
	    (rc = dim_ok(&tf->surface, 1, "surface", e)) != 0 ||
	    (rc = dim_ok(&tf->gradient, 1, "gradient", e)) != 0)
		return rc;
	if (tf->has_table && (tf->color.n > 0 || tf->opacity.n > 0))
		return vx_err_set(e, VX_EDATA, "a 2D table and a color or "
		    "opacity list: give one or the other");
	if (!tf->has_table && tf->opacity.n == 0)
		return vx_err_set(e, VX_EDATA, "no opacity: the transfer "
		    "function needs an opacity list or a 2D table");
	if (tf->has_surface_ramp && !(tf->surface_ramp[0] >= 0 &&
	    isfinite(tf->surface_ramp[1]) &&
	    tf->surface_ramp[1] > tf->surface_ramp[0]))
		return vx_err_set(e, VX_EDATA, "surface gradient ramp %g %g: "
		    "need 0 <= G0 < G1, finite", tf->surface_ramp[0],
		    tf->surface_ramp[1]);
	if (!isfinite(tf->ref_step) || tf->ref_step < 0)
		return vx_err_set(e, VX_EDATA, "reference step %g is negative "
		    "or not finite", tf->ref_step);
	return 0;
}

/* ---- classification ---- */

/* table_at: bilinear RGBA at (v, g) between cell centres, clamped. */
static void
table_at(const vx_tf *tf, double v, double g, double out[4])
{
	double f[2], w[2];
	int i0[2], i1[2];
	double t[2] = { v, g };
	const double *r[2] = { tf->vrange, tf->grange };

	for (int a = 0; a < 2; a++) {
		double x = (t[a] - r[a][0]) / (r[a][1] - r[a][0]) *
		    tf->size[a] - 0.5;

		if (!(x > 0))              /* below the first centre, or NaN */
			x = 0;
		if (x > tf->size[a] - 1)
			x = tf->size[a] - 1;
		i0[a] = (int)x;
		i1[a] = i0[a] + 1 < tf->size[a] ? i0[a] + 1 : i0[a];
		f[a] = x - i0[a];
		w[a] = 1 - f[a];
	}
	for (int c = 0; c < 4; c++) {
		const float *p = tf->rgba + c;
		size_t n0 = (size_t)tf->size[0];
		double a00 = p[4 * (i0[0] + n0 * i0[1])];
		double a10 = p[4 * (i1[0] + n0 * i0[1])];
		double a01 = p[4 * (i0[0] + n0 * i1[1])];
		double a11 = p[4 * (i1[0] + n0 * i1[1])];

		out[c] = w[1] * (w[0] * a00 + f[0] * a10) +
		    f[1] * (w[0] * a01 + f[0] * a11);
	}
}

void
vx_tf_classify(const vx_tf *tf, double v, double g, vx_tf_sample *o)
{
	double x[4];

	if (isnan(v)) {
		memset(o, 0, sizeof *o);
		o->transport[0] = o->transport[1] = o->transport[2] = 1;
		return;
	}
	if (tf->has_table) {
		table_at(tf, v, g, x);
		o->color[0] = x[0];
		o->color[1] = x[1];
		o->color[2] = x[2];
		o->alpha = x[3];
	} else {
		if (tf->color.n > 0)
			vx_tf_list_eval(&tf->color, v, o->color);
		else
			o->color[0] = o->color[1] = o->color[2] = 1;
		vx_tf_list_eval(&tf->opacity, v, &o->alpha);
	}
	if (tf->gradient.n > 0) {
		vx_tf_list_eval(&tf->gradient, g, x);
		o->alpha *= x[0];
	}
	if (tf->transport.n > 0)
		vx_tf_list_eval(&tf->transport, v, o->transport);
	else
		o->transport[0] = o->transport[1] = o->transport[2] =
		    1 - o->alpha;
	if (tf->surface.n > 0)
		vx_tf_list_eval(&tf->surface, v, &o->surface);
	else
		o->surface = tf->has_surface_ramp ? 1 : 0;
	if (tf->has_surface_ramp)
		o->surface *= vx_tf_surface_ramp(tf, g);
}

double
vx_tf_surface_ramp(const vx_tf *tf, double g)
{
	double g0 = tf->surface_ramp[0], g1 = tf->surface_ramp[1];

	if (!tf->has_surface_ramp)
		return 1;
	if (!(g > g0))
		return 0;          /* NaN too */
	if (g >= g1)
		return 1;
	return (g - g0) / (g1 - g0);
}

int
vx_tf_has_surface(const vx_tf *tf)
{
	return tf->surface.n > 0 || tf->has_surface_ramp;
}

int
vx_tf_class_gradient(const vx_tf *tf)
{
	return tf->has_table || tf->gradient.n > 0 || tf->has_surface_ramp;
}

int
vx_tf_needs_gradient(const vx_tf *tf)
{
	return vx_tf_class_gradient(tf) || vx_tf_has_surface(tf);
}

/* list_extreme: the largest (want_max) or smallest value of channel c of
 * l over [lo, hi]: at the ends or at a control point inside. */
static double
list_extreme(const vx_tf_list *l, int c, double lo, double hi, int want_max)
{
	double y[3], m;

	vx_tf_list_eval(l, lo, y);
	m = y[c];
	vx_tf_list_eval(l, hi, y);
	m = want_max ? fmax(m, y[c]) : fmin(m, y[c]);
	for (int i = 0; i < l->n; i++)
		if (l->x[i] >= lo && l->x[i] <= hi) {
			double t = l->y[(size_t)l->dim * (size_t)i + (size_t)c];

			m = want_max ? fmax(m, t) : fmin(m, t);
		}
	return m;
}

int
vx_tf_range_clear(const vx_tf *tf, double lo, double hi)
{
	if (isnan(lo) || isnan(hi))
		return 0;
	if (lo > hi)
		return 1;
	if (tf->has_table) {
		double r = tf->vrange[1] - tf->vrange[0];
		double x0 = (lo - tf->vrange[0]) / r * tf->size[0] - 0.5;
		double x1 = (hi - tf->vrange[0]) / r * tf->size[0] - 0.5;
		int n = tf->size[0];
		int c0 = x0 < 0 ? 0 : x0 > n - 1 ? n - 1 : (int)floor(x0);
		int c1 = x1 < 0 ? 0 : x1 > n - 1 ? n - 1 : (int)floor(x1) + 1;

		if (c1 > n - 1)
			c1 = n - 1;
		for (int j = 0; j < tf->size[1]; j++)
			for (int i = c0; i <= c1; i++)
				if (tf->rgba[4 * ((size_t)i + (size_t)n *
				    (size_t)j) + 3] != 0)
					return 0;
	} else if (list_extreme(&tf->opacity, 0, lo, hi, 1) != 0)
		return 0;
	if (tf->transport.n > 0)
		for (int c = 0; c < 3; c++)
			if (list_extreme(&tf->transport, c, lo, hi, 0) != 1)
				return 0;
	return 1;
}

double
vx_tf_correct(double alpha, double r)
{
	if (alpha <= 0)
		return 0;
	if (alpha >= 1)
		return 1;
	return 1 - pow(1 - alpha, r);
}

void
vx_tf_optic_of(const vx_tf_sample *c, vx_tf_optic *o)
{
	o->sigma = c->alpha <= 0 ? 0 : c->alpha >= 1 ? VX_TF_SIGMA_MAX :
	    fmin(-log1p(-c->alpha), VX_TF_SIGMA_MAX);
	for (int k = 0; k < 3; k++) {
		double t = c->transport[k];

		o->color[k] = c->color[k];
		o->ltr[k] = t >= 1 ? 0 : t <= 0 ? -VX_TF_SIGMA_MAX :
		    fmax(log(t), -VX_TF_SIGMA_MAX);
	}
	o->surface = c->surface;
}

int
vx_tf_lut_build(vx_tf_lut *t, const vx_tf *tf, double lo, double hi, int n,
    vx_err *e)
{
	memset(t, 0, sizeof *t);
	if (vx_tf_class_gradient(tf))
		return vx_err_set(e, VX_EDATA, "transfer table: the function "
		    "depends on the gradient magnitude");
	if (!isfinite(lo) || !isfinite(hi) || lo > hi || n < 1 ||
	    n > VX_TF_MAX_LUT)
		return vx_err_set(e, VX_EDATA, "transfer table: %d intervals "
		    "over [%g, %g]", n, lo, hi);
	if ((t->node = vx_malloc(((size_t)n + 1) * 8 * sizeof *t->node, e)) ==
	    NULL)
		return VX_ENOMEM;
	t->n = n;
	t->lo = lo;
	t->scale = hi > lo ? n / (hi - lo) : 0;
	for (int i = 0; i <= n; i++) {
		vx_tf_sample c;
		vx_tf_optic o;
		float *p = t->node + 8 * (size_t)i;

		/* the nodes' values exactly as eval finds them: lo + i / scale
		 * is i's x; the last node at hi itself */
		vx_tf_classify(tf, i == n ? hi : hi > lo ? lo + i / t->scale :
		    lo, 0, &c);
		vx_tf_optic_of(&c, &o);
		p[0] = (float)o.sigma;
		for (int k = 0; k < 3; k++) {
			p[1 + k] = (float)o.color[k];
			p[4 + k] = (float)o.ltr[k];
		}
		p[7] = (float)o.surface;
	}
	return 0;
}

void
vx_tf_lut_free(vx_tf_lut *t)
{
	free(t->node);
	memset(t, 0, sizeof *t);
}
