/* scene.c: the scene model: defaults, reading a file, command-line
 * overrides, equality, the SCNE chunk, and color maps.  The text form is in
 * scene_parse.c and scene_format.c; formats/scene.md is the spec. */
#include "vx_scene.h"
#include "vx_scan.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---- defaults ---- */

void
vx_light_init(vx_light *l, vx_light_type type)
{
	memset(l, 0, sizeof *l);
	l->type = type;
	l->color[0] = l->color[1] = l->color[2] = 1;
	l->intensity = 1;
	l->falloff = VX_FALLOFF_NONE;
	l->shadows = type == VX_LIGHT_POINT || type == VX_LIGHT_DIRECTIONAL;
	l->layout = VX_ENV_LATLONG;
}

void
vx_surface_init(vx_surface *sf, double iso)
{
	memset(sf, 0, sizeof *sf);
	sf->iso = iso;
	sf->m.color[0] = sf->m.color[1] = sf->m.color[2] = 0.8;
	sf->m.opacity = 1;
	sf->m.kd = 1;
	sf->m.ks = 0.2;
	sf->m.shininess = 32;
	sf->m.colormap = VX_COLORMAP_GRAY;
}

void
vx_scene_init(vx_scene *s)
{
	memset(s, 0, sizeof *s);
	vx_camera_init(&s->camera);
	s->ambient[0] = s->ambient[1] = s->ambient[2] = 1;
	s->ambient_intensity = 0.1;
	s->effects = VX_FX_DEFAULT;
	s->default_lights = 1;
	s->nlight = 1;
	vx_light_init(&s->light[0], VX_LIGHT_HEADLIGHT);
	s->bounces = 1;
	s->samples = 16;
	s->illumination = VX_ILLUM_LOCAL;
	s->pt_samples = 16;
	s->sh_order = 3;
	s->interp = VX_INTERP_TRILINEAR;
	s->phase = VX_PHASE_ISOTROPIC;
	s->albedo[0] = s->albedo[1] = s->albedo[2] = 1;
}

/* ---- reading and overriding ---- */

int
vx_scene_read(vx_scene *s, FILE *f, vx_err *e)
{
	size_t cap = 4096, n = 0, k;
	char *b = NULL, *nb;
	int rc;

	for (;;) {
		if (n == cap || b == NULL) {
			if (b != NULL)
				cap *= 2;
			if ((nb = realloc(b, cap)) == NULL) {
				free(b);
				vx_scene_init(s);
				return vx_err_set(e, VX_ENOMEM, "scene: out of "
				    "memory");
			}
			b = nb;
		}
		k = fread(b + n, 1, cap - n, f);
		n += k;
		if (n > VX_SCENE_TEXT_MAX) {
			free(b);
			vx_scene_init(s);
			return vx_err_set(e, VX_EDATA, "scene longer than %zu "
			    "bytes", VX_SCENE_TEXT_MAX);
		}
		if (k == 0)
			break;
	}
	if (ferror(f)) {
		free(b);
		vx_scene_init(s);
		return vx_err_set(e, VX_EIO, "read error: %s", strerror(errno));
	}
	rc = vx_scene_parse(s, b, n, e);
	free(b);
	return rc;
}

int
vx_scene_set_iso(vx_scene *s, const double *iso, int n, vx_err *e)
{
	vx_surface sf[VX_SCENE_MAX_SURFACES];
	int k, j;

	if (n < 1 || n > VX_SCENE_MAX_SURFACES)
		return vx_err_set(e, VX_EUSAGE, "between 1 and %d isovalues",
		    VX_SCENE_MAX_SURFACES);
	for (k = 0; k < n; k++) {
		if (!isfinite(iso[k]))
			return vx_err_set(e, VX_EUSAGE, "isovalue %g is not "
			    "finite", iso[k]);
		for (j = 0; j < k; j++)
			if (iso[j] == iso[k])
				return vx_err_set(e, VX_EUSAGE, "isovalue %g given "
				    "twice", iso[k]);
		if (k < s->nsurface)
			sf[k] = s->surface[k];
		else if (s->nsurface > 0)
			sf[k] = s->surface[s->nsurface - 1];
		else
			vx_surface_init(&sf[k], 0);
		sf[k].iso = iso[k];
	}
	memcpy(s->surface, sf, (size_t)n * sizeof sf[0]);
	s->nsurface = n;
	return 0;
}

int
vx_scene_set_view(vx_scene *s, vx_view v, double azimuth, double elevation,
    vx_err *e)
{
	vx_camera *c = &s->camera;

	if (v <= VX_VIEW_UNKNOWN || v >= VX_VIEW_LAST)
		return vx_err_set(e, VX_EUSAGE, "unknown view");
	if (v == VX_VIEW_ANGLES && (!isfinite(azimuth) ||
	    !(elevation >= -90 && elevation <= 90)))
		return vx_err_set(e, VX_EUSAGE, "azimuth must be finite and "
		    "elevation in [-90, 90]");
	if (!c->is_auto)
		c->has_up = 0;
	c->is_auto = 1;
	c->view = v;
	c->azimuth = v == VX_VIEW_ANGLES ? azimuth : 0;
	c->elevation = v == VX_VIEW_ANGLES ? elevation : 0;
	return 0;
}

/* numbers_list: up to max numbers separated by commas and/or spaces. */
static int
numbers_list(const char *v, double *out, int max, int *n)
{
	char b[1024], *p, *save = NULL;

	if (strlen(v) >= sizeof b)
		return -1;
	strcpy(b, v);
	*n = 0;
	for (p = strtok_r(b, ", \t", &save); p != NULL;
	    p = strtok_r(NULL, ", \t", &save)) {
		if (*n == max || vx_num_f64(p, strlen(p), 0, &out[*n]) != 0)
			return -1;
		(*n)++;
	}
	return 0;
}

int
vx_scene_option(vx_scene *s, const char *name, const char *value,
    vx_err *e)
{
	char line[VX_SCENE_LINE_MAX + 64];
	double v[VX_SCENE_MAX_SURFACES];
	int n, rc;

	if (strlen(value) > VX_SCENE_LINE_MAX)
		return vx_err_set(e, VX_EUSAGE, "--%s: value too long", name);
	if (strcmp(name, "set") == 0) {
		rc = vx_scene_apply(s, value, e);
	} else if (strcmp(name, "iso") == 0) {
		if (numbers_list(value, v, VX_SCENE_MAX_SURFACES, &n) != 0 ||
		    n == 0)
			rc = vx_err_set(e, VX_EUSAGE, "expected 1 to %d numbers, "
			    "got '%.60s'", VX_SCENE_MAX_SURFACES, value);
		else
			rc = vx_scene_set_iso(s, v, n, e);
	} else if (strcmp(name, "size") == 0) {
		const char *x = strchr(value, 'x');
		int64_t w, h;

		if (x == NULL || vx_num_i64(value, (size_t)(x - value), 1,
		    VX_CAMERA_MAX_PIXELS, &w) != 0 || vx_num_i64(x + 1,
		    strlen(x + 1), 1, VX_CAMERA_MAX_PIXELS, &h) != 0)
			rc = vx_err_set(e, VX_EUSAGE, "expected WxH with each "
			    "in 1..%d, got '%.60s'", VX_CAMERA_MAX_PIXELS,
			    value);
		else {
			s->camera.w = (int)w;
			s->camera.h = (int)h;
			rc = 0;
		}
	} else if (strcmp(name, "view") == 0) {
		vx_view vw = (vx_view)vx_enum_val(&vx_view_enum, value);

		if (vw != VX_VIEW_UNKNOWN && vw != VX_VIEW_ANGLES)
			rc = vx_scene_set_view(s, vw, 0, 0, e);
		else if (numbers_list(value, v, 2, &n) == 0 && n == 2)
			rc = vx_scene_set_view(s, VX_VIEW_ANGLES, v[0], v[1], e);
		else
			rc = vx_err_set(e, VX_EUSAGE, "expected front, back, "
			    "left, right, top, bottom or AZIMUTH,ELEVATION, got "
			    "'%.60s'", value);
	} else if (strcmp(name, "light") == 0) {
		snprintf(line, sizeof line, "light %s", value);
		rc = vx_scene_apply(s, line, e);
	} else if (strcmp(name, "lights") == 0) {
		if (strcmp(value, "none") != 0)
			rc = vx_err_set(e, VX_EUSAGE, "expected none");
		else
			rc = vx_scene_apply(s, "light none", e);
	} else if (strcmp(name, "effects") == 0) {
		snprintf(line, sizeof line, "effects %s", value);
		rc = vx_scene_apply(s, line, e);
	} else if (strcmp(name, "background") == 0) {
		if (numbers_list(value, v, 3, &n) != 0 || n != 3 ||
		    !(v[0] >= 0 && v[1] >= 0 && v[2] >= 0))
			rc = vx_err_set(e, VX_EUSAGE, "expected R,G,B >= 0, got "
			    "'%.60s'", value);
		else {
			memcpy(s->background, v, sizeof s->background);
			rc = 0;
		}
	} else if (strcmp(name, "fov") == 0) {
		snprintf(line, sizeof line, "camera fov %s", value);
		rc = vx_scene_apply(s, line, e);
	} else {
		return vx_err_set(e, VX_EINTERNAL, "scene option '%s' unknown",
		    name);
	}
	if (rc != 0 && rc != VX_ENOMEM)
		vx_err_push(e, "--%s", name);
	return rc;
}

/* ---- equality ---- */

static int
same(const double *a, const double *b, int n)
{
	return memcmp(a, b, (size_t)n * sizeof *a) == 0;
}

static int
camera_equal(const vx_camera *a, const vx_camera *b)
{
	if (a->projection != b->projection || a->is_auto != b->is_auto ||
	    a->w != b->w || a->h != b->h)
		return 0;
	if (a->projection == VX_PERSPECTIVE && !same(&a->fov, &b->fov, 1))
		return 0;
	if (a->is_auto) {
		if (a->view != b->view || !same(&a->distance, &b->distance, 1) ||
		    a->has_up != b->has_up)
			return 0;
		if (a->view == VX_VIEW_ANGLES &&
		    (!same(&a->azimuth, &b->azimuth, 1) ||
		    !same(&a->elevation, &b->elevation, 1)))
			return 0;
		return !a->has_up || same(a->up, b->up, 3);
	}
	if (!same(a->eye, b->eye, 3) || !same(a->look, b->look, 3) ||
	    !same(a->up, b->up, 3))
		return 0;
	return a->projection != VX_ORTHOGRAPHIC ||
	    same(&a->view_width, &b->view_width, 1);
}

static int
light_equal(const vx_light *a, const vx_light *b)
{
	if (a->type != b->type || !same(a->color, b->color, 3) ||
	    !same(&a->intensity, &b->intensity, 1) || a->shadows != b->shadows)
		return 0;
	switch (a->type) {
	case VX_LIGHT_POINT:
		return same(a->position, b->position, 3) &&
		    a->falloff == b->falloff;
	case VX_LIGHT_DIRECTIONAL:
		return same(a->direction, b->direction, 3);
	case VX_LIGHT_HEADLIGHT:
		return a->falloff == b->falloff;
	case VX_LIGHT_ENVIRONMENT:
		return strcmp(a->file, b->file) == 0 && a->layout == b->layout &&
		    same(a->rotation, b->rotation, 3) &&
		    a->has_hash == b->has_hash &&
		    (!a->has_hash || a->hash == b->hash);
	default:
		return 1;
	}
}

static int
surface_equal(const vx_surface *a, const vx_surface *b)
{
	const vx_material *p = &a->m, *q = &b->m;

	return same(&a->iso, &b->iso, 1) && same(p->color, q->color, 3) &&
	    same(&p->opacity, &q->opacity, 1) && same(&p->kd, &q->kd, 1) &&
	    same(&p->ks, &q->ks, 1) && same(&p->shininess, &q->shininess, 1) &&
	    strcmp(p->texture, q->texture) == 0 && p->colormap == q->colormap &&
	    p->has_window == q->has_window &&
	    (!p->has_window || same(p->window, q->window, 2));
}

int
vx_scene_equal(const vx_scene *a, const vx_scene *b)
{
	int i;

	if (!camera_equal(&a->camera, &b->camera) ||
	    strcmp(a->volume, b->volume) != 0 ||
	    !same(a->background, b->background, 3) ||
	    !same(a->ambient, b->ambient, 3) ||
	    !same(&a->ambient_intensity, &b->ambient_intensity, 1) ||
	    a->effects != b->effects || a->default_lights != b->default_lights ||
	    a->nlight != b->nlight || a->nsurface != b->nsurface ||
	    a->has_interreflection != b->has_interreflection ||
	    a->has_occlusion != b->has_occlusion ||
	    (a->has_occlusion && !same(&a->occlusion_distance,
	    &b->occlusion_distance, 1)) ||
	    a->has_illumination != b->has_illumination ||
	    a->ntf_opacity != b->ntf_opacity || a->ntf_color != b->ntf_color ||
	    a->ntf_transport != b->ntf_transport ||
	    a->ntf_surface != b->ntf_surface ||
	    a->ntf_gradient != b->ntf_gradient ||
	    a->has_tf_step != b->has_tf_step ||
	    a->has_tf_surface_ramp != b->has_tf_surface_ramp ||
	    strcmp(a->tf_file, b->tf_file) != 0 ||
	    a->has_medium != b->has_medium || a->next != b->next)
		return 0;
	for (i = 0; i < a->nlight && i < VX_SCENE_MAX_LIGHTS; i++)
		if (!light_equal(&a->light[i], &b->light[i]))
			return 0;
	for (i = 0; i < a->nsurface && i < VX_SCENE_MAX_SURFACES; i++)
		if (!surface_equal(&a->surface[i], &b->surface[i]))
			return 0;
	if (a->has_interreflection &&
	    (a->bounces != b->bounces || a->samples != b->samples))
		return 0;
	if (a->has_illumination) {
		if (a->illumination != b->illumination)
			return 0;
		if (a->illumination == VX_ILLUM_SH && a->sh_order != b->sh_order)
			return 0;
		if (a->illumination == VX_ILLUM_PATHTRACE &&
		    a->pt_samples != b->pt_samples)
			return 0;
		if (a->illumination != VX_ILLUM_LOCAL &&
		    a->illumination != VX_ILLUM_PATHTRACE && a->interp != b->interp)
			return 0;
	}
	for (i = 0; i < a->ntf_opacity && i < VX_SCENE_MAX_TF; i++)
		if (!same(a->tf_opacity[i], b->tf_opacity[i], 2))
			return 0;
	for (i = 0; i < a->ntf_color && i < VX_SCENE_MAX_TF; i++)
		if (!same(a->tf_color[i], b->tf_color[i], 4))
			return 0;
	for (i = 0; i < a->ntf_transport && i < VX_SCENE_MAX_TF; i++)
		if (!same(a->tf_transport[i], b->tf_transport[i], 4))
			return 0;
	for (i = 0; i < a->ntf_surface && i < VX_SCENE_MAX_TF; i++)
		if (!same(a->tf_surface[i], b->tf_surface[i], 2))
			return 0;
	for (i = 0; i < a->ntf_gradient && i < VX_SCENE_MAX_TF; i++)
		if (!same(a->tf_gradient[i], b->tf_gradient[i], 2))
			return 0;
	if (a->has_tf_step && !same(&a->tf_step, &b->tf_step, 1))
		return 0;
	if (a->has_tf_surface_ramp && !same(a->tf_surface_ramp,
	    b->tf_surface_ramp, 2))
		return 0;
	for (i = 0; i < VX_PERTURB_N; i++) {
		const vx_scene_perturb *p = &a->perturb[i], *q = &b->perturb[i];

		if (p->on != q->on)
			return 0;
		if (p->on && (!same(&p->scale, &q->scale, 1) ||
		    !same(&p->amplitude, &q->amplitude, 1) ||
		    p->octaves != q->octaves ||
		    !same(&p->lacunarity, &q->lacunarity, 1) ||
		    !same(&p->gain, &q->gain, 1) || p->seed != q->seed ||
		    p->turbulence != q->turbulence))
			return 0;
	}
	if (a->tf_file[0] != '\0' && a->tf_file_format != b->tf_file_format)
		return 0;
	if (a->has_medium && (a->phase != b->phase ||
	    !same(&a->phase_g, &b->phase_g, 1) || !same(a->albedo, b->albedo, 3)))
		return 0;
	for (i = 0; i < a->next && i < VX_SCENE_MAX_EXT; i++)
		if (strcmp(a->ext[i], b->ext[i]) != 0)
			return 0;
	return 1;
}

/* ---- the SCNE chunk ---- */

int
vx_scene_to_chunk(const vx_scene *s, int zlevel, vx_chunk *c, vx_err *e)
{
	char *text;
	size_t n;
	vx_hdr h;
	int rc;

	if ((rc = vx_scene_format(s, &text, &n, e)) != 0)
		return rc;
	vx_hdr_init(&h);
	if ((rc = vx_hdr_set(&h, "version", e, "%d", VX_SCENE_VERSION)) == 0 &&
	    (rc = vx_hdr_set(&h, "length", e, "%zu", n)) == 0)
		rc = vx_payload_make(c, VX_CHUNK_SCENE, &h, text, n, zlevel, e);
	vx_hdr_free(&h);
	free(text);
	return rc;
}

int
vx_scene_from_chunk(vx_scene *s, const vx_chunk *c, vx_err *e)
{
	const unsigned char *body;
	size_t bodylen;
	int64_t v[1];
	char *text = NULL;
	vx_hdr h;
	int rc;

	vx_hdr_init(&h);
	if ((rc = vx_payload_parse(c, &h, &body, &bodylen, e)) != 0)
		goto out;
	if (vx_hdr_get(&h, "version") != NULL) {
		if ((rc = vx_hdr_get_i64(&h, "version", v, 1, e)) != 0)
			goto out;
		if (v[0] < 1 || v[0] > VX_SCENE_VERSION) {
			rc = vx_err_set(e, VX_EDATA, "version %lld not supported "
			    "(this reader: %d)", (long long)v[0],
			    VX_SCENE_VERSION);
			goto out;
		}
	}
	if ((rc = vx_hdr_get_i64(&h, "length", v, 1, e)) != 0)
		goto out;
	if (v[0] < 0 || (uint64_t)v[0] > VX_SCENE_TEXT_MAX) {
		rc = vx_err_set(e, VX_EDATA, "length %lld outside 0..%zu",
		    (long long)v[0], VX_SCENE_TEXT_MAX);
		goto out;
	}
	if ((text = vx_malloc((size_t)v[0] + 1, e)) == NULL) {
		rc = VX_ENOMEM;
		goto out;
	}
	if ((rc = vx_body_decode(&h, body, bodylen, text, (size_t)v[0], e)) != 0)
		goto out;
	rc = vx_scene_parse(s, text, (size_t)v[0], e);
out:
	if (rc != 0) {
		vx_scene_init(s);
		vx_err_push(e, "scene chunk");
	}
	free(text);
	vx_hdr_free(&h);
	return rc;
}

int
vx_scene_from_stream(vx_scene *s, const vx_stream *st, long *index,
    vx_err *e)
{
	long i = vx_stream_find(st, VX_CHUNK_SCENE, 0);

	if (index != NULL)
		*index = i;
	if (i < 0) {
		vx_scene_init(s);
		return 0;
	}
	return vx_scene_from_chunk(s, &st->chunk[i], e);
}

int
vx_scene_to_stream(const vx_scene *s, vx_stream *st, vx_err *e)
{
	long i = vx_stream_find(st, VX_CHUNK_SCENE, 0);
	vx_chunk c;
	int rc;

	if ((rc = vx_scene_to_chunk(s, 0, &c, e)) != 0)
		return rc;
	if (i >= 0) {
		vx_stream_replace(st, (size_t)i, &c);
		return 0;
	}
	if ((rc = vx_stream_append(st, &c, e)) != 0)
		vx_chunk_free(&c);
	return rc;
}

/* ---- color maps: piecewise linear through control points ---- */

void
vx_colormap_eval(vx_colormap m, double t, double rgb[3])
{
	static const double hot[4][4] = {
		{ 0, 0, 0, 0 }, { 1.0 / 3, 1, 0, 0 }, { 2.0 / 3, 1, 1, 0 },
		{ 1, 1, 1, 1 }
	};
	static const double coolwarm[3][4] = {
		{ 0, 0.230, 0.299, 0.754 }, { 0.5, 0.865, 0.865, 0.865 },
		{ 1, 0.706, 0.016, 0.150 }
	};
	static const double viridis[5][4] = {
		{ 0, 0.267004, 0.004874, 0.329415 },
		{ 0.25, 0.229739, 0.322361, 0.545706 },
		{ 0.5, 0.127568, 0.566949, 0.550556 },
		{ 0.75, 0.369214, 0.788888, 0.382914 },
		{ 1, 0.993248, 0.906157, 0.143936 }
	};
	const double (*pt)[4];
	int n, i, k;

	if (!(t > 0))
		t = 0;      /* NaN too */
	if (t > 1)
		t = 1;
	switch (m) {
	case VX_COLORMAP_HOT: pt = hot; n = 4; break;
	case VX_COLORMAP_COOLWARM: pt = coolwarm; n = 3; break;
	case VX_COLORMAP_VIRIDIS: pt = viridis; n = 5; break;
	default:
		rgb[0] = rgb[1] = rgb[2] = t;
		return;
	}
	for (i = 1; i < n - 1 && t > pt[i][0]; i++)
		;
	{
		double f = (t - pt[i - 1][0]) / (pt[i][0] - pt[i - 1][0]);

		for (k = 0; k < 3; k++)
			rgb[k] = pt[i - 1][k + 1] +
			    f * (pt[i][k + 1] - pt[i - 1][k + 1]);
	}
}
