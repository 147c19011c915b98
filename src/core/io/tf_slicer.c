/* tf_slicer.c: 3D Slicer's volume property (formats/transfer.md,
 * Imports): the .vp text (vtkMRMLVolumePropertyStorageNode: nine lines,
 * the last three "N x y ..." or "N x r g b ..." with N the count of
 * numbers) and the .vp.json (vtkMRMLVolumePropertyJsonStorageNode: the
 * first component of the first of "volumeProperties"). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "import_priv.h"
#include "tf_priv.h"
#include "vx_scan.h"

/* ---- .vp ---- */

static const char *line_names[9] = {
	"interpolation type", "shade", "diffuse", "ambient", "specular",
	"specular power", "scalar opacity", "gradient opacity",
	"color transfer function"
};

/* vp_list: "N v1 ... vN" on one line (N a multiple of stride, the point
 * count at most VX_TF_MAX_POINTS) into l; an empty line leaves l absent. */
static int
vp_list(const char *line, size_t len, int lineno, int stride, vx_tf_list *l,
    vx_err *e)
{
	const char *name = line_names[lineno - 1], *w;
	double *v = NULL, *x = NULL, *y = NULL;
	int64_t count;
	size_t wl;
	vx_scan s;
	int np, dim = stride - 1, rc = 0;

	vx_scan_init(&s, line, len);
	if ((wl = vx_scan_word(&s, &w)) == 0)
		return 0;                       /* absent */
	if (vx_num_i64(w, wl, 0, INT64_MAX, &count) != 0)
		return vx_err_set(e, VX_EDATA, "line %d (%s): the count '%s' "
		    "is not a non-negative integer", lineno, name,
		    vx_imp_show(w, wl));
	if (count % stride != 0)
		return vx_err_set(e, VX_EDATA, "line %d (%s): the count %lld is "
		    "not a multiple of %d", lineno, name, (long long)count,
		    stride);
	if (count / stride > VX_TF_MAX_POINTS)
		return vx_err_set(e, VX_EDATA, "line %d (%s): %lld points (at "
		    "most %d)", lineno, name, (long long)(count / stride),
		    VX_TF_MAX_POINTS);
	if (count == 0)
		return 0;
	/* each number takes two bytes at least: a count the line cannot
	 * hold is refused before anything is allocated */
	if ((uint64_t)count > len / 2)
		return vx_err_set(e, VX_EDATA, "line %d (%s): the count %lld is "
		    "more than the line holds", lineno, name, (long long)count);
	np = (int)(count / stride);
	v = vx_malloc((size_t)count * sizeof *v, e);
	x = v ? vx_malloc((size_t)np * sizeof *x, e) : NULL;
	y = x ? vx_malloc((size_t)np * (size_t)dim * sizeof *y, e) : NULL;
	if (y == NULL) {
		rc = VX_ENOMEM;
		goto out;
	}
	for (int64_t i = 0; i < count; i++) {
		if ((wl = vx_scan_word(&s, &w)) == 0) {
			rc = vx_err_set(e, VX_EDATA, "line %d (%s): the count is "
			    "%lld but %lld numbers follow it", lineno, name,
			    (long long)count, (long long)i);
			goto out;
		}
		if (vx_num_f64(w, wl, 0, &v[i]) != 0) {
			rc = vx_err_set(e, VX_EDATA, "line %d (%s): number %lld "
			    "'%s' is not a finite number", lineno, name,
			    (long long)i + 1, vx_imp_show(w, wl));
			goto out;
		}
	}
	if (vx_scan_word(&s, &w) != 0) {
		rc = vx_err_set(e, VX_EDATA, "line %d (%s): more numbers than "
		    "the count %lld", lineno, name, (long long)count);
		goto out;
	}
	for (int i = 0; i < np; i++) {
		const double *g = v + (size_t)i * (size_t)stride;

		if (i > 0 && g[0] < g[-stride]) {
			rc = vx_err_set(e, VX_EDATA, "line %d (%s): number %d: x "
			    "%.17g is less than the one before it (%.17g)",
			    lineno, name, i * stride + 1, g[0], g[-stride]);
			goto out;
		}
		for (int c = 1; c < stride; c++)
			if (!(g[c] >= 0 && g[c] <= 1)) {
				rc = vx_err_set(e, VX_EDATA, "line %d (%s): number "
				    "%d: %.17g is outside [0, 1]", lineno, name,
				    i * stride + c + 1, g[c]);
				goto out;
			}
		x[i] = g[0];
		memcpy(y + (size_t)i * (size_t)dim, g + 1, (size_t)dim *
		    sizeof *g);
	}
	if ((rc = vx_tf_list_set(l, np, dim, x, y, e)) != 0)
		vx_err_push(e, "line %d (%s)", lineno, name);
out:
	free(v);
	free(x);
	free(y);
	return rc;
}

int
vx_tfi_slicer_vp(const char *buf, size_t n, vx_tf *tf, vx_err *e)
{
	const char *line;
	size_t len;
	vx_scan s;
	int lineno = 0, rc;

	vx_scan_init(&s, buf, n);
	while (vx_scan_line(&s, 1, &line, &len)) {
		const char *w;
		size_t wl;
		vx_scan ls;
		double v;

		lineno++;
		if (memchr(line, '\0', len) != NULL)
			return vx_err_set(e, VX_EDATA, "line %d: NUL byte",
			    lineno);
		if (lineno > 9) {
			vx_scan_init(&ls, line, len);
			if (vx_scan_word(&ls, &w) != 0)
				return vx_err_set(e, VX_EDATA, "line %d: text "
				    "after the nine lines of a volume property",
				    lineno);
			continue;
		}
		if (lineno >= 7) {
			vx_tf_list *l = lineno == 7 ? &tf->opacity :
			    lineno == 8 ? &tf->gradient : &tf->color;

			if ((rc = vp_list(line, len, lineno, lineno == 9 ? 4 : 2,
			    l, e)) != 0)
				return rc;
			continue;
		}
		/* interpolation, shade, lighting: checked, not used */
		vx_scan_init(&ls, line, len);
		if ((wl = vx_scan_word(&ls, &w)) == 0)
			continue;                 /* Slicer skips it too */
		if ((lineno <= 2 ? vx_num_i64(w, wl, 0, 2, &(int64_t){ 0 }) :
		    vx_num_f64(w, wl, 0, &v)) != 0 || vx_scan_word(&ls, &w) != 0)
			return vx_err_set(e, VX_EDATA, "line %d (%s): expected %s",
			    lineno, line_names[lineno - 1], lineno == 1 ?
			    "0, 1 or 2" : lineno == 2 ? "0 or 1" : "one number");
	}
	if (lineno < 7 || tf->opacity.n == 0)
		return vx_err_set(e, VX_EDATA, "no scalar opacity (line 7 of a "
		    "volume property)");
	return 0;
}

/* ---- .vp.json ---- */

/* member: key of obj, of type t (NULL when absent and optional). */
static int
member(const vx_json *j, const vx_json_node *obj, const char *key,
    vx_json_type t, int need, const vx_json_node **out, vx_err *e)
{
	const vx_json_node *m;
	int dup;

	*out = NULL;
	m = vx_json_get(j, obj, key, &dup);
	if (m == NULL)
		return need ? vx_tfi_at(e, obj, "no key \"%s\"", key) : 0;
	if (dup)
		return vx_tfi_at(e, m, "key \"%s\" given twice", key);
	if (m->type != t && !(t == VX_JSON_TRUE && m->type == VX_JSON_FALSE))
		return vx_tfi_at(e, m, "key \"%s\": a %s, not a%s %s", key,
		    vx_json_type_name(m->type), t == VX_JSON_ARRAY ||
		    t == VX_JSON_OBJECT ? "n" : "", t == VX_JSON_TRUE ?
		    "boolean" : vx_json_type_name(t));
	*out = m;
	return 0;
}

static int
num(const vx_json *j, const vx_json_node *obj, const char *key, int need,
    double def, double *v, vx_err *e)
{
	const vx_json_node *m;
	int rc;

	*v = def;
	if ((rc = member(j, obj, key, VX_JSON_NUMBER, need, &m, e)) != 0)
		return rc;
	if (m != NULL)
		*v = m->num;
	return 0;
}

/* json_fn: the function under key of comp ({"points": [{...}, ...]}),
 * dim 1 ("y") or 3 ("color"), into l through vx_tfi_vtk. */
static int
json_fn(const vx_json *j, const vx_json_node *comp, const char *key,
    int dim, vx_tf_list *l, vx_err *e)
{
	const vx_json_node *fn, *pts, *pt;
	double *x = NULL, *y = NULL, *mid = NULL, *sharp = NULL;
	vx_tfi_pts p;
	int rc, np, i;

	if ((rc = member(j, comp, key, VX_JSON_OBJECT, 0, &fn, e)) != 0 ||
	    fn == NULL)
		return rc;
	if ((rc = member(j, fn, "points", VX_JSON_ARRAY, 1, &pts, e)) != 0)
		return rc;
	if ((np = pts->n) == 0)
		return 0;                       /* no points: absent */
	if (np > VX_TF_MAX_POINTS)
		return vx_tfi_at(e, pts, "key \"%s\": %d points (at most %d)",
		    key, np, VX_TF_MAX_POINTS);
	vx_tfi_pts_init(&p, dim);
	x = vx_malloc((size_t)np * sizeof *x, e);
	y = x ? vx_malloc((size_t)np * (size_t)dim * sizeof *y, e) : NULL;
	mid = y ? vx_malloc((size_t)np * sizeof *mid, e) : NULL;
	sharp = mid ? vx_malloc((size_t)np * sizeof *sharp, e) : NULL;
	if (sharp == NULL) {
		rc = VX_ENOMEM;
		goto out;
	}
	for (i = 0, pt = vx_json_at(j, pts->first); pt != NULL; i++,
	    pt = vx_json_at(j, pt->next)) {
		const vx_json_node *col, *c;
		double *yi = y + (size_t)i * (size_t)dim;
		int k;

		if (pt->type != VX_JSON_OBJECT) {
			rc = vx_tfi_at(e, pt, "key \"%s\" point %d: a %s, not an "
			    "object", key, i, vx_json_type_name(pt->type));
			goto out;
		}
		if ((rc = num(j, pt, "x", 1, 0, &x[i], e)) != 0 ||
		    (rc = num(j, pt, "midpoint", 0, 0.5, &mid[i], e)) != 0 ||
		    (rc = num(j, pt, "sharpness", 0, 0, &sharp[i], e)) != 0)
			goto push;
		if (dim == 1) {
			if ((rc = num(j, pt, "y", 1, 0, yi, e)) != 0)
				goto push;
		} else {
			if ((rc = member(j, pt, "color", VX_JSON_ARRAY, 1, &col,
			    e)) != 0)
				goto push;
			if (col->n != 3) {
				rc = vx_tfi_at(e, col, "key \"%s\" point %d: "
				    "\"color\" has %d numbers, not 3", key, i,
				    col->n);
				goto out;
			}
			for (k = 0, c = vx_json_at(j, col->first); c != NULL;
			    k++, c = vx_json_at(j, c->next)) {
				if (c->type != VX_JSON_NUMBER) {
					rc = vx_tfi_at(e, c, "key \"%s\" point %d: "
					    "\"color\" element %d is a %s", key, i,
					    k, vx_json_type_name(c->type));
					goto out;
				}
				yi[k] = c->num;
			}
		}
		if (i > 0 && x[i] < x[i - 1]) {
			rc = vx_tfi_at(e, pt, "key \"%s\" point %d: x %.17g is "
			    "less than the one before it (%.17g)", key, i, x[i],
			    x[i - 1]);
			goto out;
		}
		for (k = 0; k < dim; k++)
			if (!(yi[k] >= 0 && yi[k] <= 1)) {
				rc = vx_tfi_at(e, pt, "key \"%s\" point %d: %s "
				    "%.17g is outside [0, 1]", key, i, dim == 1 ?
				    "y" : "color", yi[k]);
				goto out;
			}
		if (!(mid[i] >= 0 && mid[i] <= 1) ||
		    !(sharp[i] >= 0 && sharp[i] <= 1)) {
			rc = vx_tfi_at(e, pt, "key \"%s\" point %d: midpoint "
			    "%.17g or sharpness %.17g is outside [0, 1]", key, i,
			    mid[i], sharp[i]);
			goto out;
		}
		continue;
push:
		if (rc == VX_EDATA)
			vx_err_push(e, "key \"%s\" point %d", key, i);
		goto out;
	}
	if ((rc = vx_tfi_vtk(&p, np, dim, x, y, mid, sharp, e)) != 0 ||
	    (rc = vx_tfi_set(l, &p, e)) != 0) {
		vx_err_push(e, "key \"%s\"", key);
		vx_err_push(e, "line %d", pts->line);
	}
out:
	vx_tfi_pts_free(&p);
	free(x);
	free(y);
	free(mid);
	free(sharp);
	return rc;
}

int
vx_tfi_slicer_json(const vx_json *j, vx_tf *tf, vx_err *e)
{
	const vx_json_node *top = vx_json_at(j, 0), *vps, *vp, *comps, *comp,
	    *dis;
	double unit;
	int rc;

	if (top->type != VX_JSON_OBJECT)
		return vx_tfi_at(e, top, "a %s, not a volume property object",
		    vx_json_type_name(top->type));
	if ((rc = member(j, top, "volumeProperties", VX_JSON_ARRAY, 1, &vps,
	    e)) != 0)
		return rc;
	if ((vp = vx_json_at(j, vps->first)) == NULL)
		return vx_tfi_at(e, vps, "key \"volumeProperties\": empty");
	if (vp->type != VX_JSON_OBJECT)
		return vx_tfi_at(e, vp, "key \"volumeProperties\" element 0: a "
		    "%s, not an object", vx_json_type_name(vp->type));
	if ((rc = member(j, vp, "components", VX_JSON_ARRAY, 1, &comps, e)) !=
	    0)
		return rc;
	if ((comp = vx_json_at(j, comps->first)) == NULL)
		return vx_tfi_at(e, comps, "key \"components\": empty");
	if (comp->type != VX_JSON_OBJECT)
		return vx_tfi_at(e, comp, "key \"components\" element 0: a %s, "
		    "not an object", vx_json_type_name(comp->type));
	if ((rc = json_fn(j, comp, "scalarOpacity", 1, &tf->opacity, e)) != 0 ||
	    (rc = json_fn(j, comp, "rgbTransferFunction", 3, &tf->color,
	    e)) != 0)
		return rc;
	if ((rc = member(j, comp, "disableGradientOpacity", VX_JSON_TRUE, 0,
	    &dis, e)) != 0)
		return rc;
	if ((dis == NULL || dis->type == VX_JSON_FALSE) &&
	    (rc = json_fn(j, comp, "gradientOpacity", 1, &tf->gradient, e)) !=
	    0)
		return rc;
	if ((rc = num(j, comp, "scalarOpacityUnitDistance", 0, 0, &unit,
	    e)) != 0)
		return rc;
	if (!(unit >= 0) || !isfinite(unit))
		return vx_tfi_at(e, comp, "key \"scalarOpacityUnitDistance\": "
		    "%.17g is not a distance", unit);
	tf->ref_step = unit;
	if (tf->opacity.n == 0)
		return vx_tfi_at(e, comp, "no scalar opacity (key "
		    "\"scalarOpacity\" with points)");
	return 0;
}
