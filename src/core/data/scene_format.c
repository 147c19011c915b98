/* scene_format.c: writing the canonical scene text, every number printed
 * so that it reads back exactly, names quoted where the tokenizer needs. */
#include "vx_scene.h"
#include "scene_text.h"
#include "vx_scan.h"

#include <stdlib.h>
#include <string.h>

/* ---- numbers and names ---- */

/* fmt_num: the shortest of %.15g, %.16g, %.17g that reads back as exactly
 * v, with a '.' as decimal point. */
static void
fmt_num(char *b, size_t n, double v)
{
	double back;
	int prec;

	for (prec = 15; prec <= 17; prec++) {
		vx_snprintf_c(b, n, "%.*g", prec, v);
		if (vx_num_f64(b, strlen(b), 0, &back) == 0 &&
		    memcmp(&back, &v, sizeof v) == 0)
			return;
	}
}

static int
needs_quotes(const char *t)
{
	const char *q;

	if (*t == '\0' || strcmp(t, "none") == 0 || strcmp(t, "auto") == 0)
		return 1;
	for (q = t; *q != '\0'; q++)
		if (*q == ' ' || *q == '\t' || *q == '#' || *q == '"' || *q == '\\')
			return 1;
	return 0;
}

/* vx_scn_quote: see scene_text.h. */
int
vx_scn_quote(char *b, size_t n, const char *t, int force)
{
	size_t k = 0;

	if (!force && !needs_quotes(t)) {
		size_t l = strlen(t);

		if (l + 1 > n)
			return -1;
		memcpy(b, t, l + 1);
		return (int)l;
	}
	if (n < 3)
		return -1;
	b[k++] = '"';
	for (; *t != '\0'; t++) {
		if (*t == '"' || *t == '\\') {
			if (k + 1 >= n)
				return -1;
			b[k++] = '\\';
		}
		if (k + 2 >= n)
			return -1;
		b[k++] = *t;
	}
	b[k++] = '"';
	b[k] = '\0';
	return (int)k;
}


/* ---- the canonical text ---- */

typedef struct sbuf {
	char *p;
	size_t n, cap;
	int bad;
} sbuf;

static void
sb_grow(sbuf *b, size_t need)
{
	size_t cap;
	char *np;

	if (b->bad || b->n + need + 1 <= b->cap)
		return;
	cap = b->cap ? b->cap : 1024;
	while (cap < b->n + need + 1)
		cap *= 2;
	if ((np = realloc(b->p, cap)) == NULL) {
		b->bad = 1;
		return;
	}
	b->p = np;
	b->cap = cap;
}

static void
sb_put(sbuf *b, const char *s)
{
	size_t l = strlen(s);

	sb_grow(b, l);
	if (b->bad)
		return;
	memcpy(b->p + b->n, s, l + 1);
	b->n += l;
}

static void
sb_num(sbuf *b, double v)
{
	char t[64];

	fmt_num(t, sizeof t, v);
	sb_put(b, " ");
	sb_put(b, t);
}

static void
sb_key(sbuf *b, const char *key, const double *v, int n)
{
	int i;

	sb_put(b, " ");
	sb_put(b, key);
	for (i = 0; i < n; i++)
		sb_num(b, v[i]);
}

static void
sb_int(sbuf *b, const char *key, long v)
{
	char t[64];

	snprintf(t, sizeof t, " %s %ld", key, v);
	sb_put(b, t);
}

static void
sb_str(sbuf *b, const char *key, const char *v)
{
	char t[2 * VX_SCENE_PATH_MAX + 4];

	sb_put(b, " ");
	sb_put(b, key);
	sb_put(b, " ");
	if (vx_scn_quote(t, sizeof t, v, 0) < 0) {
		b->bad = 2;
		return;
	}
	sb_put(b, t);
}

/* format_tf: "transfer NAME" and n points of per numbers, when n > 0. */
static void
format_tf(sbuf *b, const char *name, int n, const double *pts, int per)
{
	int i, j;

	if (n <= 0)
		return;
	sb_put(b, "transfer ");
	sb_put(b, name);
	for (i = 0; i < n && i < VX_SCENE_MAX_TF; i++)
		for (j = 0; j < per; j++)
			sb_num(b, pts[i * per + j]);
	sb_put(b, "\n");
}

static void
format_camera(sbuf *b, const vx_camera *c)
{
	if (c->is_auto) {
		sb_put(b, "camera auto projection ");
		sb_put(b, vx_enum_str(&vx_projection_enum, c->projection));
		if (c->view == VX_VIEW_ANGLES) {
			sb_key(b, "azimuth", &c->azimuth, 1);
			sb_key(b, "elevation", &c->elevation, 1);
		} else {
			sb_put(b, " view ");
			sb_put(b, vx_enum_str(&vx_view_enum, c->view));
		}
		sb_key(b, "distance", &c->distance, 1);
		if (c->projection == VX_PERSPECTIVE)
			sb_key(b, "fov", &c->fov, 1);
		if (c->has_up)
			sb_key(b, "up", c->up, 3);
	} else {
		sb_put(b, "camera ");
		sb_put(b, vx_enum_str(&vx_projection_enum, c->projection));
		sb_key(b, "eye", c->eye, 3);
		sb_key(b, "look", c->look, 3);
		sb_key(b, "up", c->up, 3);
		if (c->projection == VX_PERSPECTIVE)
			sb_key(b, "fov", &c->fov, 1);
		else
			sb_key(b, "width", &c->view_width, 1);
	}
	sb_put(b, "\nimage");
	sb_int(b, "width", c->w);
	sb_int(b, "height", c->h);
	sb_put(b, "\n");
}

static void
format_light(sbuf *b, const vx_light *l)
{
	sb_put(b, "light ");
	sb_put(b, vx_enum_str(&vx_light_type_enum, l->type));
	switch (l->type) {
	case VX_LIGHT_POINT:
		sb_key(b, "position", l->position, 3);
		break;
	case VX_LIGHT_DIRECTIONAL:
		sb_key(b, "direction", l->direction, 3);
		break;
	case VX_LIGHT_ENVIRONMENT:
		sb_str(b, "file", l->file);
		sb_put(b, " layout ");
		sb_put(b, vx_enum_str(&vx_env_layout_enum, l->layout));
		sb_key(b, "rotation", l->rotation, 3);
		if (l->has_hash) {
			char t[24];

			snprintf(t, sizeof t, " hash %016llx",
			    (unsigned long long)l->hash);
			sb_put(b, t);
		}
		break;
	default:
		break;
	}
	sb_key(b, "color", l->color, 3);
	sb_key(b, "intensity", &l->intensity, 1);
	if (l->type == VX_LIGHT_POINT || l->type == VX_LIGHT_HEADLIGHT) {
		sb_put(b, " falloff ");
		sb_put(b, vx_enum_str(&vx_falloff_enum, l->falloff));
	}
	sb_put(b, l->shadows ? " shadows on\n" : " shadows off\n");
}

static void
format_surface(sbuf *b, const vx_surface *sf)
{
	const vx_material *m = &sf->m;

	sb_put(b, "surface");
	sb_key(b, "iso", &sf->iso, 1);
	sb_key(b, "color", m->color, 3);
	sb_key(b, "opacity", &m->opacity, 1);
	sb_key(b, "kd", &m->kd, 1);
	sb_key(b, "ks", &m->ks, 1);
	sb_key(b, "shininess", &m->shininess, 1);
	if (m->texture[0] != '\0')
		sb_str(b, "texture", m->texture);
	if (m->texture[0] != '\0' || m->colormap != VX_COLORMAP_GRAY) {
		sb_put(b, " colormap ");
		sb_put(b, vx_enum_str(&vx_colormap_enum, m->colormap));
	}
	if (m->has_window)
		sb_key(b, "window", m->window, 2);
	sb_put(b, "\n");
}

int
vx_scene_format(const vx_scene *s, char **text, size_t *n, vx_err *e)
{
	sbuf b = { NULL, 0, 0, 0 };
	unsigned k;
	int i;

	*text = NULL;
	*n = 0;
	sb_put(&b, "voxlux-scene 1\n");
	if (s->volume[0] != '\0') {
		sb_put(&b, "volume");
		sb_str(&b, "name", s->volume);
		sb_put(&b, "\n");
	}
	format_camera(&b, &s->camera);
	sb_put(&b, "background");
	sb_key(&b, "color", s->background, 3);
	sb_put(&b, "\nambient");
	sb_key(&b, "color", s->ambient, 3);
	sb_key(&b, "intensity", &s->ambient_intensity, 1);
	sb_put(&b, "\neffects");
	if ((s->effects & VX_FX_ALL) == 0)
		sb_put(&b, " none");
	for (k = 0; vx_enum_str(&vx_effect_enum, 1u << k) != NULL; k++)
		if (s->effects & 1u << k) {
			sb_put(&b, " ");
			sb_put(&b, vx_enum_str(&vx_effect_enum, 1u << k));
		}
	sb_put(&b, "\n");
	if (!s->default_lights) {
		if (s->nlight == 0)
			sb_put(&b, "light none\n");
		for (i = 0; i < s->nlight && i < VX_SCENE_MAX_LIGHTS; i++)
			format_light(&b, &s->light[i]);
	}
	for (i = 0; i < s->nsurface && i < VX_SCENE_MAX_SURFACES; i++)
		format_surface(&b, &s->surface[i]);
	if (s->has_interreflection) {
		sb_put(&b, "interreflection");
		sb_int(&b, "bounces", s->bounces);
		sb_int(&b, "samples", s->samples);
		sb_put(&b, "\n");
	}
	if (s->has_occlusion) {
		sb_put(&b, "occlusion");
		if (s->occlusion_distance > 0)
			sb_key(&b, "distance", &s->occlusion_distance, 1);
		sb_put(&b, "\n");
	}
	if (s->has_illumination) {
		sb_put(&b, "illumination ");
		sb_put(&b, vx_enum_str(&vx_illum_enum, s->illumination));
		if (s->illumination == VX_ILLUM_SH)
			sb_int(&b, "order", s->sh_order);
		if (s->illumination == VX_ILLUM_PATHTRACE)
			sb_int(&b, "samples", s->pt_samples);
		else if (s->illumination != VX_ILLUM_LOCAL) {
			sb_put(&b, " interpolation ");
			sb_put(&b, vx_enum_str(&vx_interp_enum, s->interp));
		}
		sb_put(&b, "\n");
	}
	if (s->ntf_opacity > 0) {
		sb_put(&b, "transfer opacity");
		for (i = 0; i < s->ntf_opacity && i < VX_SCENE_MAX_TF; i++) {
			sb_num(&b, s->tf_opacity[i][0]);
			sb_num(&b, s->tf_opacity[i][1]);
		}
		sb_put(&b, "\n");
	}
	if (s->ntf_color > 0) {
		sb_put(&b, "transfer color");
		for (i = 0; i < s->ntf_color && i < VX_SCENE_MAX_TF; i++) {
			int j;

			for (j = 0; j < 4; j++)
				sb_num(&b, s->tf_color[i][j]);
		}
		sb_put(&b, "\n");
	}
	format_tf(&b, "transport", s->ntf_transport, &s->tf_transport[0][0], 4);
	format_tf(&b, "surface", s->ntf_surface, &s->tf_surface[0][0], 2);
	format_tf(&b, "gradient", s->ntf_gradient, &s->tf_gradient[0][0], 2);
	if (s->has_tf_surface_ramp) {
		sb_put(&b, "transfer surface gradient");
		sb_num(&b, s->tf_surface_ramp[0]);
		sb_num(&b, s->tf_surface_ramp[1]);
		sb_put(&b, "\n");
	}
	if (s->has_tf_step) {
		sb_put(&b, "transfer");
		sb_key(&b, "step", &s->tf_step, 1);
		sb_put(&b, "\n");
	}
	if (s->tf_file[0] != '\0') {
		sb_put(&b, "transfer");
		sb_str(&b, "file", s->tf_file);
		if (s->tf_file_format != VX_TF_FORMAT_AUTO) {
			sb_put(&b, " format ");
			sb_put(&b, vx_enum_str(&vx_tf_format_enum,
			    s->tf_file_format));
		}
		sb_put(&b, "\n");
	}
	if (s->has_medium) {
		sb_put(&b, "medium phase ");
		sb_put(&b, vx_enum_str(&vx_phase_enum, s->phase));
		if (s->phase == VX_PHASE_HENYEY_GREENSTEIN)
			sb_key(&b, "g", &s->phase_g, 1);
		sb_key(&b, "albedo", s->albedo, 3);
		sb_put(&b, "\n");
	}
	for (i = 0; i < VX_PERTURB_N; i++) {
		const vx_scene_perturb *q = &s->perturb[i];

		if (!q->on)
			continue;
		sb_put(&b, "perturb ");
		sb_put(&b, vx_enum_str(&vx_perturb_target_enum, i + 1));
		sb_key(&b, "scale", &q->scale, 1);
		sb_key(&b, "amplitude", &q->amplitude, 1);
		sb_int(&b, "octaves", q->octaves);
		sb_key(&b, "lacunarity", &q->lacunarity, 1);
		sb_key(&b, "gain", &q->gain, 1);
		sb_int(&b, "seed", q->seed);
		sb_put(&b, q->turbulence ? " noise turbulence\n" :
		    " noise fbm\n");
	}
	for (i = 0; i < s->next && i < VX_SCENE_MAX_EXT; i++) {
		sb_put(&b, s->ext[i]);
		sb_put(&b, "\n");
	}
	if (b.bad) {
		free(b.p);
		if (b.bad == 2)
			return vx_err_set(e, VX_EINTERNAL, "scene: name too long "
			    "to write");
		return vx_err_set(e, VX_ENOMEM, "scene: out of memory");
	}
	*text = b.p;
	*n = b.n;
	return 0;
}
