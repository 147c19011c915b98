/* tf_paraview.c: ParaView's colour-map presets (the JSON array "Save
 * presets" writes; formats/transfer.md, Imports): the first preset's
 * RGBPoints (x r g b ...) interpolated in its ColorSpace and Points
 * (x opacity midpoint sharpness ...). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "import_priv.h"
#include "tf_priv.h"
#include "vx_enum.h"

/* ---- VTK's colour spaces (vtkColorTransferFunction, vtkMath) ----
 * The colour between two nodes is interpolated linearly in the preset's
 * space and converted back to RGB; here each segment becomes a
 * piecewise-linear RGB curve within VX_TFI_SHARP_TOL of that. */

enum { CS_RGB = 1, CS_HSV, CS_LAB, CS_DIVERGING };

static void
rgb_hsv(const double c[3], double hsv[3])
{
	double mx = fmax(c[0], fmax(c[1], c[2]));
	double mn = fmin(c[0], fmin(c[1], c[2])), d = mx - mn, h = 0;

	hsv[2] = mx;
	hsv[1] = mx > 0 ? d / mx : 0;
	if (hsv[1] > 0) {
		if (c[0] == mx)
			h = (c[1] - c[2]) / d / 6;
		else if (c[1] == mx)
			h = 1.0 / 3 + (c[2] - c[0]) / d / 6;
		else
			h = 2.0 / 3 + (c[0] - c[1]) / d / 6;
		if (h < 0)
			h += 1;
	}
	hsv[0] = h;
}

static void
hsv_rgb(const double hsv[3], double c[3])
{
	double h = hsv[0], r, g, b;

	/* the hue's sector: one channel full, one rising or falling */
	if (h > 1.0 / 6 && h <= 1.0 / 3) {
		r = (1.0 / 3 - h) * 6; g = 1; b = 0;
	} else if (h > 1.0 / 3 && h <= 0.5) {
		r = 0; g = 1; b = (h - 1.0 / 3) * 6;
	} else if (h > 0.5 && h <= 2.0 / 3) {
		r = 0; g = (2.0 / 3 - h) * 6; b = 1;
	} else if (h > 2.0 / 3 && h <= 5.0 / 6) {
		r = (h - 2.0 / 3) * 6; g = 0; b = 1;
	} else if (h > 5.0 / 6 && h <= 1) {
		r = 1; g = 0; b = (1 - h) * 6;
	} else {
		r = 1; g = h * 6; b = 0;
	}
	c[0] = (hsv[1] * r + 1 - hsv[1]) * hsv[2];
	c[1] = (hsv[1] * g + 1 - hsv[1]) * hsv[2];
	c[2] = (hsv[1] * b + 1 - hsv[1]) * hsv[2];
}

/* sRGB (D65) to CIE L*a*b* and back, with VTK's constants */
static const double white[3] = { 0.9505, 1.000, 1.089 };

static double
lab_f(double t)
{
	return t > 0.008856 ? cbrt(t) : 7.787 * t + 16.0 / 116;
}

static void
rgb_lab(const double c[3], double lab[3])
{
	double l[3], xyz[3], f[3];

	for (int k = 0; k < 3; k++)
		l[k] = c[k] > 0.04045 ? pow((c[k] + 0.055) / 1.055, 2.4) :
		    c[k] / 12.92;
	xyz[0] = l[0] * 0.4124 + l[1] * 0.3576 + l[2] * 0.1805;
	xyz[1] = l[0] * 0.2126 + l[1] * 0.7152 + l[2] * 0.0722;
	xyz[2] = l[0] * 0.0193 + l[1] * 0.1192 + l[2] * 0.9505;
	for (int k = 0; k < 3; k++)
		f[k] = lab_f(xyz[k] / white[k]);
	lab[0] = 116 * f[1] - 16;
	lab[1] = 500 * (f[0] - f[1]);
	lab[2] = 200 * (f[1] - f[2]);
}

static void
lab_rgb(const double lab[3], double c[3])
{
	double f[3], xyz[3], mx;

	f[1] = (lab[0] + 16) / 116;
	f[0] = lab[1] / 500 + f[1];
	f[2] = f[1] - lab[2] / 200;
	for (int k = 0; k < 3; k++) {
		double t3 = f[k] * f[k] * f[k];

		xyz[k] = white[k] * (t3 > 0.008856 ? t3 : (f[k] - 16.0 / 116) /
		    7.787);
	}
	c[0] = xyz[0] * 3.2406 + xyz[1] * -1.5372 + xyz[2] * -0.4986;
	c[1] = xyz[0] * -0.9689 + xyz[1] * 1.8758 + xyz[2] * 0.0415;
	c[2] = xyz[0] * 0.0557 + xyz[1] * -0.2040 + xyz[2] * 1.0570;
	for (int k = 0; k < 3; k++)
		c[k] = c[k] > 0.0031308 ? 1.055 * pow(c[k], 1 / 2.4) - 0.055 :
		    12.92 * c[k];
	/* out of gamut: scaled into it, then clipped at 0, as VTK does */
	mx = fmax(c[0], fmax(c[1], c[2]));
	for (int k = 0; k < 3; k++) {
		if (mx > 1)
			c[k] /= mx;
		if (!(c[k] > 0))
			c[k] = 0;
	}
}

/* Moreland's diverging maps (2009): Lab in polar form, Msh */
static void
lab_msh(const double lab[3], double msh[3])
{
	msh[0] = sqrt(lab[0] * lab[0] + lab[1] * lab[1] + lab[2] * lab[2]);
	msh[1] = msh[0] > 0.001 ? acos(fmax(-1, fmin(1, lab[0] / msh[0]))) :
	    0;
	msh[2] = msh[1] > 0.001 ? atan2(lab[2], lab[1]) : 0;
}

static void
msh_lab(const double msh[3], double lab[3])
{
	lab[0] = msh[0] * cos(msh[1]);
	lab[1] = msh[0] * sin(msh[1]) * cos(msh[2]);
	lab[2] = msh[0] * sin(msh[1]) * sin(msh[2]);
}

static double
angle_diff(double a, double b)
{
	double d = fabs(a - b);

	d = fmod(d, 2 * M_PI);
	return d > M_PI ? 2 * M_PI - d : d;
}

/* adjust_hue: a hue for an unsaturated end (magnitude m) that spins away
 * from the saturated end's as Moreland's maps do */
static double
adjust_hue(const double msh[3], double m)
{
	double spin;

	if (msh[0] >= m - 0.1)
		return msh[2];
	spin = msh[1] * sqrt(m * m - msh[0] * msh[0]) / (msh[0] * sin(msh[1]));
	return msh[2] > -M_PI / 3 ? msh[2] + spin : msh[2] - spin;
}

typedef struct cseg {
	int space;
	const double *c0, *c1;
} cseg;

static void
cseg_eval(const void *ctx, double s, double *out)
{
	const cseg *g = ctx;
	double a[3], b[3], t[3];

	if (g->space == CS_HSV) {
		rgb_hsv(g->c0, a);
		rgb_hsv(g->c1, b);
		if (fabs(a[0] - b[0]) > 0.5) {     /* the short way round */
			if (a[0] > b[0])
				a[0] -= 1;
			else
				b[0] -= 1;
		}
		for (int k = 0; k < 3; k++)
			t[k] = a[k] + s * (b[k] - a[k]);
		if (t[0] < 0)
			t[0] += 1;
		hsv_rgb(t, out);
		return;
	}
	rgb_lab(g->c0, a);
	rgb_lab(g->c1, b);
	if (g->space == CS_DIVERGING) {
		double ma[3], mb[3];

		lab_msh(a, ma);
		lab_msh(b, mb);
		/* two saturated, distinct ends: white in between */
		if (ma[1] > 0.05 && mb[1] > 0.05 &&
		    angle_diff(ma[2], mb[2]) > 0.33 * M_PI) {
			double mid = fmax(fmax(ma[0], mb[0]), 88.0);

			if (s < 0.5) {
				mb[0] = mid;
				mb[1] = mb[2] = 0;
				s *= 2;
			} else {
				ma[0] = mid;
				ma[1] = ma[2] = 0;
				s = 2 * s - 1;
			}
		}
		if (ma[1] < 0.05 && mb[1] > 0.05)
			ma[2] = adjust_hue(mb, ma[0]);
		else if (mb[1] < 0.05 && ma[1] > 0.05)
			mb[2] = adjust_hue(ma, mb[0]);
		for (int k = 0; k < 3; k++)
			t[k] = ma[k] + s * (mb[k] - ma[k]);
		msh_lab(t, a);
		lab_rgb(a, out);
		return;
	}
	for (int k = 0; k < 3; k++)
		t[k] = a[k] + s * (b[k] - a[k]);
	lab_rgb(t, out);
}

/* spaced: the colour list of np nodes (x, y) interpolated in space */
static int
spaced(vx_tfi_pts *p, int space, int np, const double *x, const double *y,
    vx_err *e)
{
	double c[3];

	for (int i = 0; i < np; i++) {
		cseg g = { space, y + 3 * (size_t)i, y + 3 * (size_t)(i + 1) };

		if (i + 1 == np) {      /* the last node, as its segment ends */
			if (i > 0) {
				g.c0 = y + 3 * (size_t)(i - 1);
				g.c1 = y + 3 * (size_t)i;
				cseg_eval(&g, 1, c);
			} else
				memcpy(c, y, sizeof c);
			return vx_tfi_pts_add(p, x[i], c, e);
		}
		cseg_eval(&g, 0, c);
		if (vx_tfi_pts_add(p, x[i], c, e) != 0)
			return e->code;
		if (x[i + 1] > x[i] && vx_tfi_curve(p, x[i], x[i + 1], cseg_eval,
		    &g, e) != 0)
			return e->code;
	}
	return 0;
}

/* numbers: key's value in obj as an array of numbers whose count is a
 * positive multiple of stride, at most VX_TF_MAX_POINTS groups; *v
 * malloc'ed (count numbers), *np the groups.  *node gets the array. */
static int
numbers(const vx_json *j, const vx_json_node *obj, const char *key,
    int stride, double **v, int *np, const vx_json_node **node, vx_err *e)
{
	const vx_json_node *a, *c;
	int dup, i;

	*v = NULL;
	*np = 0;
	*node = a = vx_json_get(j, obj, key, &dup);
	if (dup)
		return vx_tfi_at(e, a, "key \"%s\" given twice", key);
	if (a->type != VX_JSON_ARRAY)
		return vx_tfi_at(e, a, "key \"%s\": a %s, not an array of "
		    "numbers", key, vx_json_type_name(a->type));
	if (a->n == 0 || a->n % stride != 0)
		return vx_tfi_at(e, a, "key \"%s\": %d numbers, not a positive "
		    "multiple of %d", key, a->n, stride);
	if (a->n / stride > VX_TF_MAX_POINTS)
		return vx_tfi_at(e, a, "key \"%s\": %d points (at most %d)", key,
		    a->n / stride, VX_TF_MAX_POINTS);
	if ((*v = vx_malloc((size_t)a->n * sizeof **v, e)) == NULL)
		return VX_ENOMEM;
	for (i = 0, c = vx_json_at(j, a->first); c != NULL; i++,
	    c = vx_json_at(j, c->next)) {
		if (c->type != VX_JSON_NUMBER) {
			free(*v);
			*v = NULL;
			return vx_tfi_at(e, c, "key \"%s\" element %d: a %s, not "
			    "a number", key, i, vx_json_type_name(c->type));
		}
		(*v)[i] = c->num;
	}
	*np = a->n / stride;
	return 0;
}

/* check: the groups of v (stride numbers each): x non-decreasing, the
 * others in [0,1]. */
static int
check(const double *v, int np, int stride, const char *key,
    const vx_json_node *a, vx_err *e)
{
	for (int i = 0; i < np; i++) {
		const double *g = v + (size_t)i * (size_t)stride;

		if (i > 0 && g[0] < g[-stride])
			return vx_tfi_at(e, a, "key \"%s\" element %d: x %.17g is "
			    "less than the one before it (%.17g)", key,
			    i * stride, g[0], g[-stride]);
		for (int c = 1; c < stride; c++)
			if (!(g[c] >= 0 && g[c] <= 1))
				return vx_tfi_at(e, a, "key \"%s\" element %d: "
				    "%.17g is outside [0, 1]", key, i * stride + c,
				    g[c]);
	}
	return 0;
}

/* split: the groups of v into x (n), y (n * dim: numbers 1..dim of each
 * group), and when stride > dim + 1, mid and sharp (the next two). */
static int
split(const double *v, int np, int stride, int dim, double **x, double **y,
    double **mid, double **sharp, vx_err *e)
{
	size_t n = (size_t)np;

	*x = vx_malloc(n * sizeof **x, e);
	*y = *x ? vx_malloc(n * (size_t)dim * sizeof **y, e) : NULL;
	*mid = *y ? vx_malloc(n * sizeof **mid, e) : NULL;
	*sharp = *mid ? vx_malloc(n * sizeof **sharp, e) : NULL;
	if (*sharp == NULL)
		return VX_ENOMEM;
	for (size_t i = 0; i < n; i++) {
		const double *g = v + i * (size_t)stride;

		(*x)[i] = g[0];
		memcpy(*y + i * (size_t)dim, g + 1, (size_t)dim * sizeof *g);
		(*mid)[i] = stride > dim + 1 ? g[dim + 1] : 0.5;
		(*sharp)[i] = stride > dim + 2 ? g[dim + 2] : 0;
	}
	return 0;
}

/* list: l from key's groups (stride numbers: x, dim values, and maybe
 * midpoint and sharpness). */
static int
list(const vx_json *j, const vx_json_node *obj, const char *key,
    int stride, int dim, int space, vx_tf_list *l, double range[2],
    vx_err *e)
{
	const vx_json_node *a;
	double *v, *x = NULL, *y = NULL, *mid = NULL, *sharp = NULL;
	vx_tfi_pts p;
	int np, rc;

	if ((rc = numbers(j, obj, key, stride, &v, &np, &a, e)) != 0)
		return rc;
	vx_tfi_pts_init(&p, dim);
	if ((rc = check(v, np, stride, key, a, e)) == 0 &&
	    (rc = split(v, np, stride, dim, &x, &y, &mid, &sharp, e)) == 0 &&
	    ((rc = space > CS_RGB ? spaced(&p, space, np, x, y, e) :
	    vx_tfi_vtk(&p, np, dim, x, y, mid, sharp, e)) != 0 ||
	    (rc = vx_tfi_set(l, &p, e)) != 0) && rc == VX_EDATA) {
		vx_err_push(e, "key \"%s\"", key);
		vx_err_push(e, "line %d", a->line);
	}
	if (rc == 0) {
		range[0] = v[0];
		range[1] = v[(size_t)(np - 1) * (size_t)stride];
	}
	vx_tfi_pts_free(&p);
	free(v);
	free(x);
	free(y);
	free(mid);
	free(sharp);
	return rc;
}

int
vx_tfi_paraview(const vx_json *j, vx_tf *tf, vx_err *e)
{
	const vx_json_node *top = vx_json_at(j, 0), *pre, *cs;
	static const vx_enum_name space_names[] = {
		{ "RGB", CS_RGB }, { "HSV", CS_HSV }, { "Lab", CS_LAB },
		{ "Diverging", CS_DIVERGING }, { NULL, 0 }
	};
	static const vx_enum spaces = { "colour space", space_names, "?", 0 };
	double crange[2] = { 0, 1 }, orange[2];
	int dup, rc, space = CS_RGB;

	if (top->type == VX_JSON_ARRAY) {
		/* the presets file: the first preset is read */
		if ((pre = vx_json_at(j, top->first)) == NULL)
			return vx_tfi_at(e, top, "an empty array: no preset");
	} else
		pre = top;
	if (pre->type != VX_JSON_OBJECT)
		return vx_tfi_at(e, pre, "a %s, not a preset object",
		    vx_json_type_name(pre->type));
	if ((cs = vx_json_get(j, pre, "ColorSpace", &dup)) != NULL) {
		if (dup)
			return vx_tfi_at(e, cs, "key \"ColorSpace\" given twice");
		if (cs->type != VX_JSON_STRING)
			return vx_tfi_at(e, cs, "key \"ColorSpace\": a %s, not a "
			    "string", vx_json_type_name(cs->type));
		if ((space = vx_enum_val(&spaces, cs->str)) == 0)
			return vx_tfi_at(e, cs, "key \"ColorSpace\": \"%s\" is "
			    "not supported (RGB, HSV, Lab or Diverging)",
			    vx_imp_show(cs->str, cs->len));
	}
	if (vx_json_get(j, pre, "RGBPoints", NULL) == NULL &&
	    vx_json_get(j, pre, "Points", NULL) == NULL)
		return vx_tfi_at(e, pre, vx_json_get(j, pre, "IndexedColors",
		    NULL) ? "a categorical preset (IndexedColors): not a "
		    "transfer function" : "the preset has neither \"RGBPoints\" "
		    "nor \"Points\"");
	if (vx_json_get(j, pre, "RGBPoints", NULL) != NULL &&
	    (rc = list(j, pre, "RGBPoints", 4, 3, space, &tf->color, crange,
	    e)) != 0)
		return rc;
	if (vx_json_get(j, pre, "Points", NULL) != NULL)
		return list(j, pre, "Points", 4, 1, CS_RGB, &tf->opacity, orange,
		    e);
	/* no opacity: ParaView's default, a ramp over the colours' range */
	{
		static const double ramp[] = { 0, 1 }, one[] = { 1 };

		if (crange[0] < crange[1])
			return vx_tf_list_set(&tf->opacity, 2, 1, crange, ramp,
			    e);
		return vx_tf_list_set(&tf->opacity, 1, 1, crange, one, e);
	}
}
