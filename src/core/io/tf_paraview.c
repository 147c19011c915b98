/* tf_paraview.c: ParaView's colour-map presets (the JSON array "Save
 * presets" writes; formats/transfer.md, Imports): the first preset's
 * RGBPoints (x r g b ...) and Points (x opacity midpoint sharpness ...). */
#include <stdlib.h>
#include <string.h>

#include "tf_priv.h"

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
    int stride, int dim, vx_tf_list *l, double range[2], vx_err *e)
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
	    ((rc = vx_tfi_vtk(&p, np, dim, x, y, mid, sharp, e)) != 0 ||
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
	double crange[2] = { 0, 1 }, orange[2];
	int dup, rc;

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
		if (strcmp(cs->str, "RGB") != 0)
			return vx_tfi_at(e, cs, "key \"ColorSpace\": \"%.40s\" is "
			    "not supported (only \"RGB\": interpolation in "
			    "other spaces is not piecewise linear in RGB)",
			    cs->str);
	}
	if (vx_json_get(j, pre, "RGBPoints", NULL) == NULL &&
	    vx_json_get(j, pre, "Points", NULL) == NULL)
		return vx_tfi_at(e, pre, vx_json_get(j, pre, "IndexedColors",
		    NULL) ? "a categorical preset (IndexedColors): not a "
		    "transfer function" : "the preset has neither \"RGBPoints\" "
		    "nor \"Points\"");
	if (vx_json_get(j, pre, "RGBPoints", NULL) != NULL &&
	    (rc = list(j, pre, "RGBPoints", 4, 3, &tf->color, crange, e)) != 0)
		return rc;
	if (vx_json_get(j, pre, "Points", NULL) != NULL)
		return list(j, pre, "Points", 4, 1, &tf->opacity, orange, e);
	/* no opacity: ParaView's default, a ramp over the colours' range */
	{
		static const double ramp[] = { 0, 1 }, one[] = { 1 };

		if (crange[0] < crange[1])
			return vx_tf_list_set(&tf->opacity, 2, 1, crange, ramp,
			    e);
		return vx_tf_list_set(&tf->opacity, 1, 1, crange, one, e);
	}
}
