/* scene_parse.c: reading the scene text (formats/scene.md): the words of
 * the format, numbers in the C locale, the tokenizer, one handler per
 * directive, vx_scene_parse and vx_scene_apply. */
#include "vx_scene.h"
#include "scene_text.h"
#include "vx_scan.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define MAXTOK 1024        /* words per line */

/* ---- names ---- */

static const vx_enum_name light_names[] = {
	{ "point", VX_LIGHT_POINT }, { "directional", VX_LIGHT_DIRECTIONAL },
	{ "headlight", VX_LIGHT_HEADLIGHT },
	{ "environment", VX_LIGHT_ENVIRONMENT }, { "sky", VX_LIGHT_SKY },
	{ NULL, VX_LIGHT_UNKNOWN }
};
const vx_enum vx_light_type_enum = { "light type", light_names, "unknown",
    0 };

static const vx_enum_name layout_names[] = {
	{ "latlong", VX_ENV_LATLONG }, { "angular", VX_ENV_ANGULAR },
	{ NULL, VX_ENV_LAYOUT_UNKNOWN }
};
const vx_enum vx_env_layout_enum = { "layout", layout_names, "unknown", 0 };

static const vx_enum_name falloff_names[] = {
	{ "none", VX_FALLOFF_NONE },
	{ "inverse-square", VX_FALLOFF_INVERSE_SQUARE },
	{ NULL, VX_FALLOFF_UNKNOWN }
};
const vx_enum vx_falloff_enum = { "falloff", falloff_names, "unknown", 0 };

static const vx_enum_name colormap_names[] = {
	{ "gray", VX_COLORMAP_GRAY }, { "hot", VX_COLORMAP_HOT },
	{ "coolwarm", VX_COLORMAP_COOLWARM }, { "viridis", VX_COLORMAP_VIRIDIS },
	{ NULL, VX_COLORMAP_UNKNOWN }
};
const vx_enum vx_colormap_enum = { "colormap", colormap_names, "unknown",
    0 };

static const vx_enum_name illum_names[] = {
	{ "local", VX_ILLUM_LOCAL }, { "irradiance", VX_ILLUM_IRRADIANCE },
	{ "sh", VX_ILLUM_SH }, { "pathtrace", VX_ILLUM_PATHTRACE },
	{ NULL, VX_ILLUM_UNKNOWN }
};
const vx_enum vx_illum_enum = { "illumination", illum_names, "unknown", 0 };

static const vx_enum_name phase_names[] = {
	{ "isotropic", VX_PHASE_ISOTROPIC },
	{ "henyey-greenstein", VX_PHASE_HENYEY_GREENSTEIN },
	{ NULL, VX_PHASE_UNKNOWN }
};
const vx_enum vx_phase_enum = { "phase", phase_names, "unknown", 0 };

static const vx_enum_name perturb_names[] = {
	{ "coordinates", VX_PERTURB_COORDINATES },
	{ "value", VX_PERTURB_VALUE }, { "density", VX_PERTURB_DENSITY },
	{ NULL, VX_PERTURB_UNKNOWN }
};
const vx_enum vx_perturb_target_enum = { "perturbation", perturb_names,
    "unknown", 0 };

static const vx_enum_name effect_names[] = {
	{ "shadows", VX_FX_SHADOWS }, { "specular", VX_FX_SPECULAR },
	{ "transparency", VX_FX_TRANSPARENCY }, { "texture", VX_FX_TEXTURE },
	{ "interreflection", VX_FX_INTERREFLECTION },
	{ "volumetric-shadows", VX_FX_VOLUMETRIC_SHADOWS },
	{ "scattering", VX_FX_SCATTERING }, { NULL, 0 }
};
const vx_enum vx_effect_enum = { "effect", effect_names, NULL, 0 };

/* ---- numbers (vx_scan.h's grammar, finite) ---- */

static int
number(const char *t, double *out)
{
	return vx_num_f64(t, strlen(t), 0, out);
}

static int
integer(const char *t, long lo, long hi, long *out)
{
	int64_t v;

	if (vx_num_i64(t, strlen(t), lo, hi, &v) != 0)
		return -1;
	*out = (long)v;
	return 0;
}

/* ---- the parser ---- */

typedef struct pctx {
	vx_scene *s;
	int code;             /* VX_EDATA for files, VX_EUSAGE for overrides */
	long line;            /* 1-based line number */
	int numbered;         /* 1: messages name the line (files) */
	int ndirective;       /* directives seen so far */
	int ntok;
	char *tok[MAXTOK];
	int quoted[MAXTOK];
	char *buf;            /* token storage, 2 * VX_SCENE_LINE_MAX + 2 */
	vx_err *e;
} pctx;

static int
perr(pctx *P, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

static int
perr(pctx *P, const char *fmt, ...)
{
	char m[VX_ERR_MSG];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(m, sizeof m, fmt, ap);
	va_end(ap);
	if (P->numbered)
		return vx_err_set(P->e, P->code, "line %ld: %s", P->line, m);
	return vx_err_set(P->e, P->code, "%s", m);
}

static int
is_space(int c)
{
	return c == ' ' || c == '\t';
}

/* tokenize: split a line into words; "..." quotes (with \" and \\), '#'
 * outside quotes starts a comment. */
static int
tokenize(pctx *P, const char *p, size_t n)
{
	char *out = P->buf;
	size_t i = 0;

	P->ntok = 0;
	while (i < n) {
		unsigned char ch = (unsigned char)p[i];

		if (is_space(ch)) {
			i++;
			continue;
		}
		if (ch == '#')
			break;
		if (P->ntok == MAXTOK)
			return perr(P, "more than %d words", MAXTOK);
		P->tok[P->ntok] = out;
		P->quoted[P->ntok] = ch == '"';
		if (ch == '"') {
			for (i++;;) {
				if (i >= n)
					return perr(P, "unterminated quoted string");
				ch = (unsigned char)p[i++];
				if (ch == '"')
					break;
				if (ch == '\\') {
					if (i >= n)
						return perr(P, "unterminated quoted "
						    "string");
					ch = (unsigned char)p[i++];
					if (ch != '"' && ch != '\\')
						return perr(P, "unknown escape "
						    "'\\%c' in a quoted string",
						    ch >= 0x20 && ch < 0x7f ? ch : '?');
				}
				if (ch < 0x20 || ch == 0x7f)
					return perr(P, "control character 0x%02x",
					    ch);
				*out++ = (char)ch;
			}
			if (i < n && !is_space(p[i]) && p[i] != '#')
				return perr(P, "a quoted string must be followed "
				    "by a space");
		} else {
			while (i < n && !is_space(p[i]) && p[i] != '#') {
				ch = (unsigned char)p[i];
				if (ch < 0x20 || ch == 0x7f)
					return perr(P, "control character 0x%02x",
					    ch);
				if (ch == '"')
					return perr(P, "a quote inside a word");
				*out++ = p[i++];
			}
		}
		*out++ = '\0';
		P->ntok++;
	}
	return 0;
}

/* Key-value pairs after a directive's leading words. */
enum { K_NUM1 = 1, K_NUM2, K_NUM3, K_INT, K_WORD, K_STR, K_ONOFF, K_WINDOW };

typedef struct keydef {
	const char *name;
	int kind;
} keydef;

typedef struct kval {
	int seen;
	double v[3];
	long i;             /* K_INT value; K_ONOFF 1/0; K_WINDOW 1 numbers */
	const char *w;      /* K_WORD, K_STR */
	int quoted;
} kval;

static int
parse_keys(pctx *P, const char *dir, int start, const keydef *defs,
    kval *kv)
{
	int i = start, k, nk;

	for (nk = 0; defs[nk].name != NULL; nk++)
		memset(&kv[nk], 0, sizeof kv[nk]);
	while (i < P->ntok) {
		const char *key = P->tok[i];
		int want = 0, j;

		for (k = 0; k < nk; k++)
			if (strcmp(defs[k].name, key) == 0)
				break;
		if (k == nk || P->quoted[i]) {
			char known[256];
			size_t m = 0;

			known[0] = '\0';
			for (j = 0; j < nk && m < sizeof known; j++)
				m += (size_t)snprintf(known + m, sizeof known - m,
				    "%s%s", j ? ", " : "", defs[j].name);
			return perr(P, "%s: unknown key '%.40s' (keys: %s)", dir,
			    key, known);
		}
		if (kv[k].seen)
			return perr(P, "%s: key '%s' given twice", dir, key);
		kv[k].seen = 1;
		i++;
		switch (defs[k].kind) {
		case K_NUM1: want = 1; break;
		case K_NUM2: want = 2; break;
		case K_NUM3: want = 3; break;
		default: want = 0; break;
		}
		for (j = 0; j < want; j++, i++)
			if (i >= P->ntok || P->quoted[i] ||
			    number(P->tok[i], &kv[k].v[j]) != 0)
				return perr(P, "%s: %s: expected %d number%s, got "
				    "'%.40s'", dir, key, want, want > 1 ? "s" : "",
				    i < P->ntok ? P->tok[i] : "");
		switch (defs[k].kind) {
		case K_INT:
			if (i >= P->ntok || P->quoted[i] ||
			    integer(P->tok[i], -1000000000L, 1000000000L,
			    &kv[k].i) != 0)
				return perr(P, "%s: %s: expected an integer, got "
				    "'%.40s'", dir, key,
				    i < P->ntok ? P->tok[i] : "");
			i++;
			break;
		case K_WORD:
		case K_STR:
			if (i >= P->ntok || (defs[k].kind == K_WORD &&
			    P->quoted[i]))
				return perr(P, "%s: %s: expected a %s", dir, key,
				    defs[k].kind == K_WORD ? "word" : "name");
			kv[k].w = P->tok[i];
			kv[k].quoted = P->quoted[i];
			i++;
			break;
		case K_ONOFF:
			if (i < P->ntok && !P->quoted[i] &&
			    strcmp(P->tok[i], "on") == 0)
				kv[k].i = 1;
			else if (i < P->ntok && !P->quoted[i] &&
			    strcmp(P->tok[i], "off") == 0)
				kv[k].i = 0;
			else
				return perr(P, "%s: %s: expected on or off, got "
				    "'%.40s'", dir, key,
				    i < P->ntok ? P->tok[i] : "");
			i++;
			break;
		case K_WINDOW:
			if (i < P->ntok && !P->quoted[i] &&
			    strcmp(P->tok[i], "auto") == 0) {
				kv[k].i = 0;
				i++;
				break;
			}
			for (j = 0; j < 2; j++, i++)
				if (i >= P->ntok || P->quoted[i] ||
				    number(P->tok[i], &kv[k].v[j]) != 0)
					return perr(P, "%s: %s: expected auto or 2 "
					    "numbers, got '%.40s'", dir, key,
					    i < P->ntok ? P->tok[i] : "");
			kv[k].i = 1;
			break;
		default:
			break;
		}
	}
	return 0;
}

/* Range checks; each returns 0 or the error. */
static int
need_color(pctx *P, const char *dir, const char *key, const double v[3],
    double hi)
{
	int k;

	for (k = 0; k < 3; k++)
		if (!(v[k] >= 0 && v[k] <= hi))
			return perr(P, "%s: %s: component %g outside [0, %g]", dir,
			    key, v[k], hi);
	return 0;
}

static int
need_range(pctx *P, const char *dir, const char *key, double v, double lo,
    double hi, int open_lo, int open_hi)
{
	if (v < lo || v > hi || (open_lo && v == lo) || (open_hi && v == hi))
		return perr(P, "%s: %s: %g outside %s%g, %g%s", dir, key, v,
		    open_lo ? "(" : "[", lo, hi, open_hi ? ")" : "]");
	return 0;
}

static int
need_nonzero(pctx *P, const char *dir, const char *key, const double v[3])
{
	if (v[0] == 0 && v[1] == 0 && v[2] == 0)
		return perr(P, "%s: %s: must not be the zero vector", dir, key);
	return 0;
}

/* need_word: *out = the value w names in en (whose unknown value is 0). */
static int
need_word(pctx *P, const char *dir, const char *key, const char *w,
    const vx_enum *en, int *out)
{
	char list[256];

	if ((*out = vx_enum_val(en, w)) != 0)
		return 0;
	return perr(P, "%s: %s: unknown value '%.40s' (one of: %s)", dir, key, w,
	    vx_enum_list(en, list, sizeof list));
}

/* copy_name: NUL-terminated copy into a fixed field, whole field written. */
static int
copy_name(pctx *P, const char *dir, char *dst, size_t cap, const char *src)
{
	size_t n = strlen(src);

	if (n >= cap)
		return perr(P, "%s: name longer than %zu bytes", dir, cap - 1);
	memset(dst, 0, cap);
	memcpy(dst, src, n);
	return 0;
}

/* ---- directives ---- */

static int
do_version(pctx *P)
{
	long v;

	if (P->ndirective != 0)
		return perr(P, "voxlux-scene: only as the first directive");
	if (P->ntok != 2 || P->quoted[1] ||
	    integer(P->tok[1], 1, 1000000, &v) != 0)
		return perr(P, "voxlux-scene: expected a version number");
	if (v > VX_SCENE_VERSION)
		return perr(P, "voxlux-scene: version %ld is newer than this "
		    "reader (%d)", v, VX_SCENE_VERSION);
	return 0;
}

static int
do_camera(pctx *P)
{
	enum { C_PROJ, C_VIEW, C_AZ, C_EL, C_DIST, C_FOV, C_EYE, C_LOOK, C_UP,
	    C_WIDTH, C_N };
	static const keydef defs[] = {
		{ "projection", K_WORD }, { "view", K_WORD },
		{ "azimuth", K_NUM1 }, { "elevation", K_NUM1 },
		{ "distance", K_NUM1 }, { "fov", K_NUM1 }, { "eye", K_NUM3 },
		{ "look", K_NUM3 }, { "up", K_NUM3 }, { "width", K_NUM1 },
		{ NULL, 0 }
	};
	static const int auto_only[] = { C_PROJ, C_VIEW, C_AZ, C_EL, C_DIST };
	static const int explicit_only[] = { C_EYE, C_LOOK, C_WIDTH };
	vx_camera c = P->s->camera;
	kval kv[C_N];
	int start = 1, rc, k, proj;
	const char *kind;

	if (P->ntok < 2)
		return perr(P, "camera: expected auto, perspective, orthographic "
		    "or keys");
	if (!P->quoted[1] && strcmp(P->tok[1], "auto") == 0) {
		c.is_auto = 1;
		start = 2;
	} else if (!P->quoted[1] && (proj = vx_enum_val(&vx_projection_enum,
	    P->tok[1])) != VX_PROJECTION_UNKNOWN) {
		c.is_auto = 0;
		c.projection = (vx_projection)proj;
		start = 2;
	}
	if ((rc = parse_keys(P, "camera", start, defs, kv)) != 0)
		return rc;
	kind = c.is_auto ? "camera auto" : vx_enum_str(&vx_projection_enum,
	    c.projection);
	for (k = 0; k < 5; k++)
		if (kv[auto_only[k]].seen && !c.is_auto)
			return perr(P, "camera: key '%s' applies to auto cameras "
			    "only", defs[auto_only[k]].name);
	for (k = 0; k < 3; k++)
		if (kv[explicit_only[k]].seen && c.is_auto)
			return perr(P, "camera: key '%s' does not apply to auto "
			    "cameras", defs[explicit_only[k]].name);
	if (kv[C_PROJ].seen) {
		if ((rc = need_word(P, kind, "projection", kv[C_PROJ].w,
		    &vx_projection_enum, &proj)) != 0)
			return rc;
		c.projection = (vx_projection)proj;
	}
	if (kv[C_VIEW].seen) {
		vx_view v = (vx_view)vx_enum_val(&vx_view_enum, kv[C_VIEW].w);

		if (v == VX_VIEW_UNKNOWN || v == VX_VIEW_ANGLES)
			return perr(P, "%s: view: unknown view '%.40s' (front, "
			    "back, left, right, top, bottom; or azimuth and "
			    "elevation)", kind, kv[C_VIEW].w);
		if (kv[C_AZ].seen || kv[C_EL].seen)
			return perr(P, "%s: give a view or azimuth and "
			    "elevation, not both", kind);
		c.view = v;
	}
	if (kv[C_AZ].seen || kv[C_EL].seen) {
		if (c.view != VX_VIEW_ANGLES) {
			c.azimuth = 0;
			c.elevation = 0;
		}
		c.view = VX_VIEW_ANGLES;
		if (kv[C_AZ].seen)
			c.azimuth = kv[C_AZ].v[0];
		if (kv[C_EL].seen) {
			if ((rc = need_range(P, kind, "elevation", kv[C_EL].v[0],
			    -90, 90, 0, 0)) != 0)
				return rc;
			c.elevation = kv[C_EL].v[0];
		}
	}
	if (kv[C_DIST].seen) {
		if ((rc = need_range(P, kind, "distance", kv[C_DIST].v[0], 0,
		    1e6, 1, 0)) != 0)
			return rc;
		c.distance = kv[C_DIST].v[0];
	}
	if (kv[C_FOV].seen) {
		if (c.projection != VX_PERSPECTIVE)
			return perr(P, "%s: fov applies to perspective cameras "
			    "only", kind);
		if ((rc = need_range(P, kind, "fov", kv[C_FOV].v[0], 0, 180, 1,
		    1)) != 0)
			return rc;
		c.fov = kv[C_FOV].v[0];
	}
	if (kv[C_WIDTH].seen) {
		if (c.projection != VX_ORTHOGRAPHIC)
			return perr(P, "%s: width applies to orthographic cameras "
			    "only (the image size is the image directive)", kind);
		if ((rc = need_range(P, kind, "width", kv[C_WIDTH].v[0], 0,
		    HUGE_VAL, 1, 0)) != 0)
			return rc;
		c.view_width = kv[C_WIDTH].v[0];
	}
	if (kv[C_EYE].seen)
		memcpy(c.eye, kv[C_EYE].v, sizeof c.eye);
	if (kv[C_LOOK].seen)
		memcpy(c.look, kv[C_LOOK].v, sizeof c.look);
	if (kv[C_UP].seen) {
		if ((rc = need_nonzero(P, kind, "up", kv[C_UP].v)) != 0)
			return rc;
		memcpy(c.up, kv[C_UP].v, sizeof c.up);
	}
	/* An up given to an auto camera overrides its view's default up; an
	 * explicit camera's up is not carried into auto framing. */
	if (c.is_auto) {
		if (kv[C_UP].seen)
			c.has_up = 1;
	} else {
		c.has_up = 0;
		if (c.eye[0] == c.look[0] && c.eye[1] == c.look[1] &&
		    c.eye[2] == c.look[2])
			return perr(P, "%s: eye and look coincide (give both)",
			    kind);
		if (c.projection == VX_ORTHOGRAPHIC && !(c.view_width > 0))
			return perr(P, "orthographic: width missing");
		if (c.up[0] == 0 && c.up[1] == 0 && c.up[2] == 0)
			return perr(P, "%s: up missing", kind);
	}
	P->s->camera = c;
	return 0;
}

static int
do_image(pctx *P)
{
	enum { I_W, I_H, I_N };
	static const keydef defs[] = {
		{ "width", K_INT }, { "height", K_INT }, { NULL, 0 }
	};
	kval kv[I_N];
	int rc, k;

	if (P->ntok < 2)
		return perr(P, "image: expected width and/or height");
	if ((rc = parse_keys(P, "image", 1, defs, kv)) != 0)
		return rc;
	for (k = 0; k < I_N; k++)
		if (kv[k].seen && (kv[k].i < 1 || kv[k].i > VX_CAMERA_MAX_PIXELS))
			return perr(P, "image: %s: %ld outside 1..%d",
			    defs[k].name, kv[k].i, VX_CAMERA_MAX_PIXELS);
	if (kv[I_W].seen)
		P->s->camera.w = (int)kv[I_W].i;
	if (kv[I_H].seen)
		P->s->camera.h = (int)kv[I_H].i;
	return 0;
}

static int
do_background(pctx *P)
{
	static const keydef defs[] = { { "color", K_NUM3 }, { NULL, 0 } };
	kval kv[1];
	int rc;

	if (P->ntok < 2)
		return perr(P, "background: expected color R G B");
	if ((rc = parse_keys(P, "background", 1, defs, kv)) != 0 ||
	    (rc = need_color(P, "background", "color", kv[0].v, HUGE_VAL)) != 0)
		return rc;
	memcpy(P->s->background, kv[0].v, sizeof P->s->background);
	return 0;
}

static int
do_ambient(pctx *P)
{
	static const keydef defs[] = {
		{ "color", K_NUM3 }, { "intensity", K_NUM1 }, { NULL, 0 }
	};
	kval kv[2];
	int rc;

	if (P->ntok < 2)
		return perr(P, "ambient: expected color and/or intensity");
	if ((rc = parse_keys(P, "ambient", 1, defs, kv)) != 0)
		return rc;
	if (kv[0].seen && (rc = need_color(P, "ambient", "color", kv[0].v,
	    HUGE_VAL)) != 0)
		return rc;
	if (kv[1].seen && (rc = need_range(P, "ambient", "intensity",
	    kv[1].v[0], 0, HUGE_VAL, 0, 0)) != 0)
		return rc;
	if (kv[0].seen)
		memcpy(P->s->ambient, kv[0].v, sizeof P->s->ambient);
	if (kv[1].seen)
		P->s->ambient_intensity = kv[1].v[0];
	return 0;
}

static int
do_effects(pctx *P)
{
	unsigned set = P->s->effects;
	int i, signless = 0;
	char list[256];

	if (P->ntok < 2)
		return perr(P, "effects: expected effect names or none");
	if (P->ntok == 2 && !P->quoted[1] && strcmp(P->tok[1], "none") == 0) {
		P->s->effects = 0;
		return 0;
	}
	for (i = 1; i < P->ntok; i++)
		if (P->tok[i][0] != '+' && P->tok[i][0] != '-')
			signless = 1;
	if (signless)
		set = 0;
	for (i = 1; i < P->ntok; i++) {
		const char *w = P->tok[i];
		int remove = w[0] == '-';
		unsigned bit;

		if (w[0] == '+' || w[0] == '-')
			w++;
		bit = (unsigned)vx_enum_val(&vx_effect_enum, w);
		if (bit == 0 || P->quoted[i])
			return perr(P, "effects: unknown effect '%.40s' (%s; or "
			    "none)", P->tok[i], vx_enum_list(&vx_effect_enum,
			    list, sizeof list));
		if (remove)
			set &= ~bit;
		else
			set |= bit;
	}
	P->s->effects = set;
	return 0;
}

static int
do_volume(pctx *P)
{
	static const keydef defs[] = { { "name", K_STR }, { NULL, 0 } };
	kval kv[1];
	int rc;

	if (P->ntok < 2)
		return perr(P, "volume: expected name NAME");
	if ((rc = parse_keys(P, "volume", 1, defs, kv)) != 0)
		return rc;
	return copy_name(P, "volume", P->s->volume, sizeof P->s->volume,
	    kv[0].w);
}

static int
do_light(pctx *P)
{
	enum { L_POS, L_DIR, L_COLOR, L_INT, L_FALL, L_SHAD, L_FILE, L_ROT,
	    L_LAYOUT, L_HASH, L_N };
	static const keydef defs[] = {
		{ "position", K_NUM3 }, { "direction", K_NUM3 },
		{ "color", K_NUM3 }, { "intensity", K_NUM1 },
		{ "falloff", K_WORD }, { "shadows", K_ONOFF },
		{ "file", K_STR }, { "rotation", K_NUM3 }, { "layout", K_WORD },
		{ "hash", K_WORD }, { NULL, 0 }
	};
	/* keys each type accepts (bit per key), and the one it requires */
	static const unsigned allow[VX_LIGHT_LAST] = {
		0,
		1u << L_POS | 1u << L_COLOR | 1u << L_INT | 1u << L_FALL |
		    1u << L_SHAD,
		1u << L_DIR | 1u << L_COLOR | 1u << L_INT | 1u << L_SHAD,
		1u << L_COLOR | 1u << L_INT | 1u << L_FALL | 1u << L_SHAD,
		1u << L_FILE | 1u << L_ROT | 1u << L_LAYOUT | 1u << L_HASH |
		    1u << L_COLOR | 1u << L_INT | 1u << L_SHAD,
		1u << L_COLOR | 1u << L_INT | 1u << L_SHAD,
	};
	static const int require[VX_LIGHT_LAST] = { -1, L_POS, L_DIR, -1, L_FILE,
	    -1 };
	vx_scene *s = P->s;
	kval kv[L_N];
	vx_light l;
	int type, rc, k;
	char dir[40], list[256];

	if (P->ntok < 2 || P->quoted[1])
		return perr(P, "light: expected a type (%s) or none",
		    vx_enum_list(&vx_light_type_enum, list, sizeof list));
	if (strcmp(P->tok[1], "none") == 0) {
		if (P->ntok != 2)
			return perr(P, "light none: takes no keys");
		s->nlight = 0;
		s->default_lights = 0;
		return 0;
	}
	if ((rc = need_word(P, "light", "type", P->tok[1],
	    &vx_light_type_enum, &type)) != 0)
		return rc;
	snprintf(dir, sizeof dir, "light %s",
	    vx_enum_str(&vx_light_type_enum, type));
	if ((rc = parse_keys(P, dir, 2, defs, kv)) != 0)
		return rc;
	for (k = 0; k < L_N; k++)
		if (kv[k].seen && !(allow[type] & 1u << k))
			return perr(P, "%s: key '%s' does not apply", dir,
			    defs[k].name);
	if (require[type] >= 0 && !kv[require[type]].seen)
		return perr(P, "%s: key '%s' missing", dir,
		    defs[require[type]].name);
	vx_light_init(&l, (vx_light_type)type);
	if (kv[L_POS].seen)
		memcpy(l.position, kv[L_POS].v, sizeof l.position);
	if (kv[L_DIR].seen) {
		if ((rc = need_nonzero(P, dir, "direction", kv[L_DIR].v)) != 0)
			return rc;
		memcpy(l.direction, kv[L_DIR].v, sizeof l.direction);
	}
	if (kv[L_COLOR].seen) {
		if ((rc = need_color(P, dir, "color", kv[L_COLOR].v,
		    HUGE_VAL)) != 0)
			return rc;
		memcpy(l.color, kv[L_COLOR].v, sizeof l.color);
	}
	if (kv[L_INT].seen) {
		if ((rc = need_range(P, dir, "intensity", kv[L_INT].v[0], 0,
		    HUGE_VAL, 0, 0)) != 0)
			return rc;
		l.intensity = kv[L_INT].v[0];
	}
	if (kv[L_FALL].seen) {
		int f;

		if ((rc = need_word(P, dir, "falloff", kv[L_FALL].w,
		    &vx_falloff_enum, &f)) != 0)
			return rc;
		l.falloff = (vx_falloff)f;
	}
	if (kv[L_SHAD].seen)
		l.shadows = (int)kv[L_SHAD].i;
	if (kv[L_FILE].seen) {
		if (kv[L_FILE].w[0] == '\0')
			return perr(P, "%s: file: empty name", dir);
		if ((rc = copy_name(P, dir, l.file, sizeof l.file,
		    kv[L_FILE].w)) != 0)
			return rc;
	}
	if (kv[L_ROT].seen)
		memcpy(l.rotation, kv[L_ROT].v, sizeof l.rotation);
	if (kv[L_LAYOUT].seen) {
		int ly;

		if ((rc = need_word(P, dir, "layout", kv[L_LAYOUT].w,
		    &vx_env_layout_enum, &ly)) != 0)
			return rc;
		l.layout = (vx_env_layout)ly;
	}
	if (kv[L_HASH].seen) {
		const char *w = kv[L_HASH].w;
		uint64_t h = 0;
		int nd;

		for (nd = 0; w[nd] != '\0' && nd < 16; nd++) {
			char c = w[nd];
			int d = c >= '0' && c <= '9' ? c - '0' :
			    c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;

			if (d < 0)
				break;
			h = h << 4 | (uint64_t)d;
		}
		if (nd != 16 || w[nd] != '\0')
			return perr(P, "%s: hash: expected 16 hexadecimal digits "
			    "(0-9, a-f), got '%.40s'", dir, w);
		l.has_hash = 1;
		l.hash = h;
	}
	if (s->default_lights) {
		s->nlight = 0;
		s->default_lights = 0;
	}
	if (s->nlight == VX_SCENE_MAX_LIGHTS)
		return perr(P, "light: more than %d lights", VX_SCENE_MAX_LIGHTS);
	s->light[s->nlight++] = l;
	return 0;
}

static int
do_surface(pctx *P)
{
	enum { S_COLOR, S_OPAC, S_KD, S_KS, S_SHINE, S_TEX, S_CMAP, S_WIN,
	    S_N };
	static const keydef defs[] = {
		{ "color", K_NUM3 }, { "opacity", K_NUM1 }, { "kd", K_NUM1 },
		{ "ks", K_NUM1 }, { "shininess", K_NUM1 }, { "texture", K_STR },
		{ "colormap", K_WORD }, { "window", K_WINDOW }, { NULL, 0 }
	};
	vx_scene *s = P->s;
	vx_surface sf;
	kval kv[S_N];
	double iso;
	int rc, k, found = -1;
	char dir[64];

	if (P->ntok == 2 && !P->quoted[1] && strcmp(P->tok[1], "none") == 0) {
		s->nsurface = 0;
		return 0;
	}
	if (P->ntok < 3 || P->quoted[1] || strcmp(P->tok[1], "iso") != 0)
		return perr(P, "surface: expected iso VALUE (or none)");
	if (P->quoted[2] || number(P->tok[2], &iso) != 0)
		return perr(P, "surface: iso: expected a number, got '%.40s'",
		    P->tok[2]);
	snprintf(dir, sizeof dir, "surface iso %.20s", P->tok[2]);
	if ((rc = parse_keys(P, dir, 3, defs, kv)) != 0)
		return rc;
	for (k = 0; k < s->nsurface; k++)
		if (s->surface[k].iso == iso)
			found = k;
	if (found >= 0)
		sf = s->surface[found];
	else
		vx_surface_init(&sf, iso);
	if (kv[S_COLOR].seen) {
		if ((rc = need_color(P, dir, "color", kv[S_COLOR].v, 1)) != 0)
			return rc;
		memcpy(sf.m.color, kv[S_COLOR].v, sizeof sf.m.color);
	}
	if (kv[S_OPAC].seen) {
		if ((rc = need_range(P, dir, "opacity", kv[S_OPAC].v[0], 0, 1,
		    0, 0)) != 0)
			return rc;
		sf.m.opacity = kv[S_OPAC].v[0];
	}
	if (kv[S_KD].seen) {
		if ((rc = need_range(P, dir, "kd", kv[S_KD].v[0], 0, HUGE_VAL,
		    0, 0)) != 0)
			return rc;
		sf.m.kd = kv[S_KD].v[0];
	}
	if (kv[S_KS].seen) {
		if ((rc = need_range(P, dir, "ks", kv[S_KS].v[0], 0, HUGE_VAL,
		    0, 0)) != 0)
			return rc;
		sf.m.ks = kv[S_KS].v[0];
	}
	if (kv[S_SHINE].seen) {
		if ((rc = need_range(P, dir, "shininess", kv[S_SHINE].v[0], 0,
		    1e6, 0, 0)) != 0)
			return rc;
		sf.m.shininess = kv[S_SHINE].v[0];
	}
	if (kv[S_TEX].seen) {
		const char *t = kv[S_TEX].w;

		if (!kv[S_TEX].quoted && strcmp(t, "none") == 0)
			t = "";
		else if (t[0] == '\0')
			return perr(P, "%s: texture: empty name (none removes "
			    "it)", dir);
		if ((rc = copy_name(P, dir, sf.m.texture, sizeof sf.m.texture,
		    t)) != 0)
			return rc;
	}
	if (kv[S_CMAP].seen) {
		int m;

		if ((rc = need_word(P, dir, "colormap", kv[S_CMAP].w,
		    &vx_colormap_enum, &m)) != 0)
			return rc;
		sf.m.colormap = (vx_colormap)m;
	}
	if (kv[S_WIN].seen) {
		sf.m.has_window = (int)kv[S_WIN].i;
		sf.m.window[0] = sf.m.window[1] = 0;
		if (sf.m.has_window) {
			if (!(kv[S_WIN].v[0] < kv[S_WIN].v[1]))
				return perr(P, "%s: window: low %g not below high "
				    "%g", dir, kv[S_WIN].v[0], kv[S_WIN].v[1]);
			sf.m.window[0] = kv[S_WIN].v[0];
			sf.m.window[1] = kv[S_WIN].v[1];
		}
	}
	if (found >= 0) {
		s->surface[found] = sf;
		return 0;
	}
	if (s->nsurface == VX_SCENE_MAX_SURFACES)
		return perr(P, "surface: more than %d surfaces",
		    VX_SCENE_MAX_SURFACES);
	s->surface[s->nsurface++] = sf;
	return 0;
}

static int
do_interreflection(pctx *P)
{
	static const keydef defs[] = {
		{ "bounces", K_INT }, { "samples", K_INT }, { NULL, 0 }
	};
	kval kv[2];
	int rc;

	if ((rc = parse_keys(P, "interreflection", 1, defs, kv)) != 0)
		return rc;
	if (kv[0].seen && (kv[0].i < 0 || kv[0].i > 1000))
		return perr(P, "interreflection: bounces: %ld outside 0..1000",
		    kv[0].i);
	if (kv[1].seen && (kv[1].i < 1 || kv[1].i > 1000000))
		return perr(P, "interreflection: samples: %ld outside "
		    "1..1000000", kv[1].i);
	if (kv[0].seen)
		P->s->bounces = (int)kv[0].i;
	if (kv[1].seen)
		P->s->samples = (int)kv[1].i;
	P->s->has_interreflection = 1;
	return 0;
}

static int
do_occlusion(pctx *P)
{
	static const keydef defs[] = { { "distance", K_NUM1 }, { NULL, 0 } };
	kval kv[1];
	int rc;

	if ((rc = parse_keys(P, "occlusion", 1, defs, kv)) != 0)
		return rc;
	if (kv[0].seen && (rc = need_range(P, "occlusion", "distance",
	    kv[0].v[0], 0, HUGE_VAL, 1, 0)) != 0)
		return rc;
	if (kv[0].seen)
		P->s->occlusion_distance = kv[0].v[0];
	P->s->has_occlusion = 1;
	return 0;
}

static int
do_illumination(pctx *P)
{
	static const keydef defs[] = {
		{ "order", K_INT }, { "interpolation", K_WORD },
		{ "samples", K_INT }, { NULL, 0 }
	};
	kval kv[3];
	int rc, mode, in;
	char list[256];

	if (P->ntok < 2 || P->quoted[1])
		return perr(P, "illumination: expected a mode (%s)",
		    vx_enum_list(&vx_illum_enum, list, sizeof list));
	if ((rc = need_word(P, "illumination", "mode", P->tok[1],
	    &vx_illum_enum, &mode)) != 0)
		return rc;
	if ((rc = parse_keys(P, "illumination", 2, defs, kv)) != 0)
		return rc;
	if (kv[0].seen) {
		if (mode != VX_ILLUM_SH)
			return perr(P, "illumination: order applies to sh only");
		if (kv[0].i < 1 || kv[0].i > 16)
			return perr(P, "illumination: order: %ld outside 1..16",
			    kv[0].i);
		P->s->sh_order = (int)kv[0].i;
	}
	if (kv[2].seen) {
		if (mode != VX_ILLUM_PATHTRACE)
			return perr(P, "illumination: samples applies to "
			    "pathtrace only");
		if (kv[2].i < 1 || kv[2].i > 1000000)
			return perr(P, "illumination: samples: %ld outside "
			    "1..1000000", kv[2].i);
		P->s->pt_samples = (int)kv[2].i;
	}
	if (kv[1].seen) {
		if (mode == VX_ILLUM_LOCAL || mode == VX_ILLUM_PATHTRACE)
			return perr(P, "illumination: interpolation does not "
			    "apply to %s", vx_enum_str(&vx_illum_enum, mode));
		if ((rc = need_word(P, "illumination", "interpolation", kv[1].w,
		    &vx_interp_enum, &in)) != 0)
			return rc;
		P->s->interp = (vx_interp)in;
	}
	P->s->illumination = (vx_illum)mode;
	P->s->has_illumination = 1;
	return 0;
}

/* The lists of "transfer": name, numbers per point, what they are. */
static const struct {
	const char *name;
	int per;
	const char *what;
} tf_lists[] = {
	{ "opacity", 2, "value opacity" },
	{ "color", 4, "value r g b" },
	{ "transport", 4, "value r g b" },
	{ "surface", 2, "value weight" },
	{ "gradient", 2, "gradient-magnitude factor" },
};


/* tf_slot: where list k of the scene lives and how many points it has. */
static double *
tf_slot(vx_scene *s, int k, int **np)
{
	switch (k) {
	case 0: *np = &s->ntf_opacity; return &s->tf_opacity[0][0];
	case 1: *np = &s->ntf_color; return &s->tf_color[0][0];
	case 2: *np = &s->ntf_transport; return &s->tf_transport[0][0];
	case 3: *np = &s->ntf_surface; return &s->tf_surface[0][0];
	default: *np = &s->ntf_gradient; return &s->tf_gradient[0][0];
	}
}

static int
do_transfer_file(pctx *P)
{
	static const keydef defs[] = { { "format", K_WORD }, { NULL, 0 } };
	kval kv[1];
	int rc, f = VX_TF_FORMAT_AUTO;

	if (P->ntok < 3)
		return perr(P, "transfer file: expected a file name");
	if (P->tok[2][0] == '\0')
		return perr(P, "transfer file: empty name");
	if ((rc = parse_keys(P, "transfer file", 3, defs, kv)) != 0)
		return rc;
	if (kv[0].seen && (rc = need_word(P, "transfer file", "format",
	    kv[0].w, &vx_tf_format_enum, &f)) != 0)
		return rc;
	if ((rc = copy_name(P, "transfer file", P->s->tf_file,
	    sizeof P->s->tf_file, P->tok[2])) != 0)
		return rc;
	P->s->tf_file_format = (vx_tf_format)f;
	return 0;
}

/* "transfer surface gradient G0 G1": the surface weight's ramp over the
 * gradient magnitude. */
static int
do_surface_ramp(pctx *P)
{
	double g[2];

	if (P->ntok != 5 || P->quoted[3] || P->quoted[4] ||
	    number(P->tok[3], &g[0]) != 0 || number(P->tok[4], &g[1]) != 0)
		return perr(P, "transfer surface gradient: expected two numbers "
		    "(the gradient magnitudes where the weight is 0 and 1)");
	if (!(g[0] >= 0) || !isfinite(g[0]) || !isfinite(g[1]) ||
	    !(g[1] > g[0]))
		return perr(P, "transfer surface gradient: %g %g: need 0 <= G0 "
		    "< G1, finite", g[0], g[1]);
	P->s->tf_surface_ramp[0] = g[0];
	P->s->tf_surface_ramp[1] = g[1];
	P->s->has_tf_surface_ramp = 1;
	return 0;
}

static int
do_transfer(pctx *P)
{
	int k, per, npt, i, j, rc, *np;
	double pts[VX_SCENE_MAX_TF][4], *dst;
	const char *what;

	if (P->ntok == 2 && !P->quoted[1] && strcmp(P->tok[1], "none") == 0) {
		P->s->ntf_opacity = P->s->ntf_color = P->s->ntf_transport = 0;
		P->s->ntf_surface = P->s->ntf_gradient = 0;
		P->s->has_tf_surface_ramp = 0;
		P->s->tf_surface_ramp[0] = P->s->tf_surface_ramp[1] = 0;
		P->s->has_tf_step = 0;
		P->s->tf_step = 0;
		memset(P->s->tf_file, 0, sizeof P->s->tf_file);
		P->s->tf_file_format = VX_TF_FORMAT_UNKNOWN;
		return 0;
	}
	if (P->ntok >= 2 && !P->quoted[1] && strcmp(P->tok[1], "file") == 0)
		return do_transfer_file(P);
	if (P->ntok >= 3 && !P->quoted[1] && strcmp(P->tok[1], "surface") == 0 &&
	    !P->quoted[2] && strcmp(P->tok[2], "gradient") == 0)
		return do_surface_ramp(P);
	if (P->ntok >= 2 && !P->quoted[1] && strcmp(P->tok[1], "step") == 0) {
		double v;

		if (P->ntok != 3 || P->quoted[2] || number(P->tok[2], &v) != 0)
			return perr(P, "transfer step: expected one number (the "
			    "reference step in world units, 0: one voxel)");
		if ((rc = need_range(P, "transfer", "step", v, 0, HUGE_VAL, 0,
		    0)) != 0)
			return rc;
		P->s->tf_step = v;
		P->s->has_tf_step = 1;
		return 0;
	}
	for (k = 0; k < (int)(sizeof tf_lists / sizeof tf_lists[0]); k++)
		if (P->ntok >= 2 && !P->quoted[1] &&
		    strcmp(P->tok[1], tf_lists[k].name) == 0)
			break;
	if (k == (int)(sizeof tf_lists / sizeof tf_lists[0]))
		return perr(P, "transfer: expected opacity, color, transport, "
		    "surface, gradient, step, file or none");
	per = tf_lists[k].per;
	what = k == 4 ? "factor" : k == 3 ? "weight" : tf_lists[k].name;
	if ((P->ntok - 2) % per != 0 || P->ntok == 2)
		return perr(P, "transfer %s: expected groups of %d numbers (%s)",
		    P->tok[1], per, tf_lists[k].what);
	npt = (P->ntok - 2) / per;
	if (npt > VX_SCENE_MAX_TF)
		return perr(P, "transfer %s: more than %d points", P->tok[1],
		    VX_SCENE_MAX_TF);
	for (i = 0; i < npt; i++) {
		for (j = 0; j < per; j++) {
			int t = 2 + i * per + j;

			if (P->quoted[t] || number(P->tok[t], &pts[i][j]) != 0)
				return perr(P, "transfer %s: expected a number, got "
				    "'%.40s'", P->tok[1], P->tok[t]);
			if (j > 0 && (rc = need_range(P, "transfer", what,
			    pts[i][j], 0, 1, 0, 0)) != 0)
				return rc;
		}
		if (k == 4 && pts[i][0] < 0)
			return perr(P, "transfer gradient: gradient magnitude %g "
			    "is negative", pts[i][0]);
		if (i > 0 && pts[i][0] < pts[i - 1][0])
			return perr(P, "transfer %s: values must not decrease "
			    "(%g after %g)", P->tok[1], pts[i][0], pts[i - 1][0]);
	}
	dst = tf_slot(P->s, k, &np);
	/* the scene's arrays are [VX_SCENE_MAX_TF][per] */
	for (i = 0; i < npt; i++)
		for (j = 0; j < per; j++)
			dst[i * per + j] = pts[i][j];
	*np = npt;
	return 0;
}

static int
do_medium(pctx *P)
{
	static const keydef defs[] = {
		{ "phase", K_WORD }, { "g", K_NUM1 }, { "albedo", K_NUM3 },
		{ NULL, 0 }
	};
	kval kv[3];
	vx_phase ph = P->s->phase;
	int rc, p;

	if (P->ntok < 2)
		return perr(P, "medium: expected phase, g or albedo");
	if ((rc = parse_keys(P, "medium", 1, defs, kv)) != 0)
		return rc;
	if (kv[0].seen) {
		if ((rc = need_word(P, "medium", "phase", kv[0].w,
		    &vx_phase_enum, &p)) != 0)
			return rc;
		ph = (vx_phase)p;
	}
	if (kv[1].seen) {
		if (ph != VX_PHASE_HENYEY_GREENSTEIN)
			return perr(P, "medium: g applies to the "
			    "henyey-greenstein phase only");
		if ((rc = need_range(P, "medium", "g", kv[1].v[0], -1, 1, 1,
		    1)) != 0)
			return rc;
		P->s->phase_g = kv[1].v[0];
	}
	if (kv[2].seen) {
		if ((rc = need_color(P, "medium", "albedo", kv[2].v, 1)) != 0)
			return rc;
		memcpy(P->s->albedo, kv[2].v, sizeof P->s->albedo);
	}
	P->s->phase = ph;
	if (ph != VX_PHASE_HENYEY_GREENSTEIN)
		P->s->phase_g = 0;
	P->s->has_medium = 1;
	return 0;
}

/* "perturb TARGET scale S amplitude A [octaves N] [lacunarity L] [gain G]
 * [seed K] [noise fbm|turbulence]", "perturb TARGET none", "perturb
 * none". */
static int
do_perturb(pctx *P)
{
	static const keydef defs[] = {
		{ "scale", K_NUM1 }, { "amplitude", K_NUM1 },
		{ "octaves", K_INT }, { "lacunarity", K_NUM1 },
		{ "gain", K_NUM1 }, { "seed", K_INT }, { "noise", K_WORD },
		{ NULL, 0 }
	};
	kval kv[7];
	vx_scene_perturb q;
	int rc, t;

	if (P->ntok == 2 && !P->quoted[1] && strcmp(P->tok[1], "none") == 0) {
		memset(P->s->perturb, 0, sizeof P->s->perturb);
		return 0;
	}
	if (P->ntok < 2 || P->quoted[1])
		return perr(P, "perturb: expected coordinates, value, density "
		    "or none");
	if ((rc = need_word(P, "perturb", "target", P->tok[1],
	    &vx_perturb_target_enum, &t)) != 0)
		return rc;
	if (P->ntok == 3 && !P->quoted[2] && strcmp(P->tok[2], "none") == 0) {
		memset(&P->s->perturb[t - 1], 0, sizeof P->s->perturb[t - 1]);
		return 0;
	}
	if ((rc = parse_keys(P, "perturb", 2, defs, kv)) != 0)
		return rc;
	if (!kv[0].seen || !kv[1].seen)
		return perr(P, "perturb %s: scale and amplitude are required",
		    P->tok[1]);
	memset(&q, 0, sizeof q);
	q.on = 1;
	q.scale = kv[0].v[0];
	q.amplitude = kv[1].v[0];
	q.octaves = kv[2].seen ? (int)kv[2].i : 4;
	q.lacunarity = kv[3].seen ? kv[3].v[0] : 2;
	q.gain = kv[4].seen ? kv[4].v[0] : 0.5;
	q.seed = kv[5].seen ? kv[5].i : 0;
	if (!(q.scale > 0) || !isfinite(q.scale))
		return perr(P, "perturb: scale: %g is not a positive number",
		    q.scale);
	if (!(q.amplitude >= 0) || !isfinite(q.amplitude))
		return perr(P, "perturb: amplitude: %g is not a number >= 0",
		    q.amplitude);
	if (q.octaves < 1 || q.octaves > 24)
		return perr(P, "perturb: octaves: %d outside [1, 24]", q.octaves);
	if ((rc = need_range(P, "perturb", "lacunarity", q.lacunarity, 0,
	    1000, 1, 0)) != 0 || (rc = need_range(P, "perturb", "gain", q.gain,
	    0, 1000, 1, 0)) != 0)
		return rc;
	if (q.seed < 0 || q.seed > VX_PERTURB_MAX_SEED)
		return perr(P, "perturb: seed: %ld outside [0, %ld]", q.seed,
		    VX_PERTURB_MAX_SEED);
	if (kv[6].seen) {
		if (strcmp(kv[6].w, "turbulence") == 0)
			q.turbulence = 1;
		else if (strcmp(kv[6].w, "fbm") != 0)
			return perr(P, "perturb: noise: unknown value '%.40s' "
			    "(one of: fbm, turbulence)", kv[6].w);
	}
	P->s->perturb[t - 1] = q;
	return 0;
}

static int
do_extension(pctx *P)
{
	char line[VX_SCENE_EXT_LEN];
	size_t k = 0;
	int i, m;

	/* kept word for word (bare words bare, quoted ones quoted) when it
	 * fits and there is room; otherwise ignored */
	if (P->s->next == VX_SCENE_MAX_EXT)
		return 0;
	for (i = 0; i < P->ntok; i++) {
		if (i > 0) {
			if (k + 1 >= sizeof line)
				return 0;
			line[k++] = ' ';
		}
		if (P->quoted[i]) {
			if ((m = vx_scn_quote(line + k, sizeof line - k, P->tok[i],
			    1)) < 0)
				return 0;
		} else {
			m = (int)strlen(P->tok[i]);
			if (k + (size_t)m + 1 > sizeof line)
				return 0;
			memcpy(line + k, P->tok[i], (size_t)m);
		}
		k += (size_t)m;
	}
	line[k] = '\0';
	memset(P->s->ext[P->s->next], 0, VX_SCENE_EXT_LEN);
	memcpy(P->s->ext[P->s->next], line, k);
	P->s->next++;
	return 0;
}

static const struct {
	const char *name;
	int (*fn)(pctx *);
} directives[] = {
	{ "voxlux-scene", do_version },
	{ "camera", do_camera },
	{ "image", do_image },
	{ "background", do_background },
	{ "ambient", do_ambient },
	{ "effects", do_effects },
	{ "volume", do_volume },
	{ "light", do_light },
	{ "surface", do_surface },
	{ "interreflection", do_interreflection },
	{ "occlusion", do_occlusion },
	{ "illumination", do_illumination },
	{ "transfer", do_transfer },
	{ "medium", do_medium },
	{ "perturb", do_perturb },
	{ NULL, NULL }
};

static int
dispatch(pctx *P)
{
	const char *kw = P->tok[0];
	int i, rc;

	if (P->quoted[0])
		return perr(P, "a directive starts with a bare word, not a quoted "
		    "string");
	if (strncmp(kw, "x-", 2) == 0 && kw[2] != '\0')
		rc = do_extension(P);
	else {
		for (i = 0; directives[i].name != NULL; i++)
			if (strcmp(directives[i].name, kw) == 0)
				break;
		if (directives[i].name == NULL)
			return perr(P, "unknown directive '%.40s'", kw);
		rc = directives[i].fn(P);
	}
	P->ndirective++;
	return rc;
}

/* parse_lines: apply text to P->s line by line. */
static int
parse_lines(pctx *P, const char *text, size_t n)
{
	const char *l;
	size_t len;
	vx_scan s;
	int rc;

	vx_scan_init(&s, text, n);
	while (vx_scan_line(&s, 1, &l, &len)) {
		P->line++;
		if (memchr(l, '\0', len) != NULL)
			return perr(P, "NUL byte");
		if (len > VX_SCENE_LINE_MAX)
			return perr(P, "longer than %d bytes", VX_SCENE_LINE_MAX);
		if ((rc = tokenize(P, l, len)) != 0)
			return rc;
		if (P->ntok > 0 && (rc = dispatch(P)) != 0)
			return rc;
	}
	return 0;
}

static int
pctx_open(pctx *P, vx_scene *s, int code, vx_err *e)
{
	memset(P, 0, sizeof *P);
	P->s = s;
	P->code = code;
	P->e = e;
	P->buf = vx_malloc(2 * (size_t)VX_SCENE_LINE_MAX + 2, e);
	return P->buf == NULL ? VX_ENOMEM : 0;
}

int
vx_scene_parse(vx_scene *s, const char *text, size_t n, vx_err *e)
{
	vx_scene *t;
	pctx P;
	int rc;

	if (n > VX_SCENE_TEXT_MAX) {
		vx_scene_init(s);
		return vx_err_set(e, VX_EDATA, "scene longer than %zu bytes",
		    VX_SCENE_TEXT_MAX);
	}
	if ((t = vx_malloc(sizeof *t, e)) == NULL) {
		vx_scene_init(s);
		return VX_ENOMEM;
	}
	vx_scene_init(t);
	if ((rc = pctx_open(&P, t, VX_EDATA, e)) == 0) {
		P.numbered = 1;
		rc = parse_lines(&P, text, n);
	}
	free(P.buf);
	if (rc == 0)
		*s = *t;
	else
		vx_scene_init(s);
	free(t);
	return rc;
}

/* ---- one line on top of a scene (command-line overrides) ---- */

int
vx_scene_apply(vx_scene *s, const char *line, vx_err *e)
{
	vx_scene *t;
	pctx P;
	int rc;

	if (strchr(line, '\n') != NULL)
		return vx_err_set(e, VX_EUSAGE, "'%.60s': one directive, no "
		    "newline", line);
	if ((t = vx_malloc(sizeof *t, e)) == NULL)
		return VX_ENOMEM;
	*t = *s;
	if ((rc = pctx_open(&P, t, VX_EUSAGE, e)) == 0) {
		P.ndirective = 1;   /* voxlux-scene is for files only */
		rc = parse_lines(&P, line, strlen(line));
	}
	free(P.buf);
	if (rc == 0)
		*s = *t;
	free(t);
	return rc;
}
