/* vx_plan.h: what a renderer will compute for a scene, and why.
 *
 * A renderer derives a plan from its scene before doing any work, then
 * follows it: the plan's decision fields are what it reads (not the scene's
 * raw flags), so "no shadow rays without a light that casts them" holds by
 * construction.  Each item says what is computed or skipped and why, with a
 * predicted cost in rays per pixel; --explain prints vx_plan_format's text.
 * The core never prints: vx_plan_format fills a caller's buffer. */
#ifndef VX_PLAN_H
#define VX_PLAN_H

#include <stddef.h>

#include "vx_scene.h"

#define VX_PLAN_MAX_ITEMS 64
#define VX_PLAN_NAME      40
#define VX_PLAN_REASON    160

typedef enum vx_plan_state {
	VX_PLAN_UNKNOWN = 0,
	VX_PLAN_ON,               /* computed */
	VX_PLAN_OFF,              /* skipped: the scene does not call for it */
	VX_PLAN_UNSUPPORTED,      /* called for, but this renderer cannot yet */
	VX_PLAN_LAST
} vx_plan_state;

typedef struct vx_plan_item {
	char name[VX_PLAN_NAME];        /* "shadows", "light 2 directional" */
	vx_plan_state state;
	char reason[VX_PLAN_REASON];    /* one line, no newline */
	double rays;                    /* rays per pixel this item adds */
} vx_plan_item;

typedef struct vx_plan {
	char renderer[VX_PLAN_NAME];    /* "raycast isosurface" */
	int n;
	vx_plan_item item[VX_PLAN_MAX_ITEMS];
	int dropped;                    /* items beyond VX_PLAN_MAX_ITEMS */
	double rays_per_pixel;          /* predicted total (sum of item rays) */
	int nunsupported;               /* items in state VX_PLAN_UNSUPPORTED */

	/* ---- decisions, for the ray-cast isosurface renderer ---- */
	int surface_on[VX_SCENE_MAX_SURFACES]; /* draw surface k */
	int nsurface_on;
	int light_on[VX_SCENE_MAX_LIGHTS];     /* shade with light k */
	int shadow_on[VX_SCENE_MAX_LIGHTS];    /* trace shadow rays to light k */
	int nshadow;                           /* lights with shadow_on */
	int composite;      /* 1: composite transparent layers front to back;
	                       0: stop at the first hit, treat all as opaque */
	int specular;       /* 1: add the Blinn-Phong term */
	int texture_on[VX_SCENE_MAX_SURFACES]; /* map surface k's texture */
	double layers;      /* predicted surface hits shaded per covered pixel */
	int irradiance;     /* 1: each hit is shaded by albedo E / pi, E read
	                       from the irradiance volume (IRRV): lights,
	                       shadows, ambient and specular are baked in or
	                       left out */
	int sh;             /* 1 (with irradiance 1): E is the dot product of
	                       SH lighting with the transfer vector read from
	                       an SH transfer volume (SHTV) */
	int pathtrace;      /* 1: each hit is shaded by albedo E / pi, E
	                       estimated by path tracing (vx_gi.h) with
	                       pt_samples paths: the reference */
} vx_plan;

/* vx_plan_init: an empty plan for the named renderer. */
void vx_plan_init(vx_plan *p, const char *renderer);

/* vx_plan_add: append an item (name and a printf-formatted reason, both cut
 * to fit) and add its rays to the total.  Beyond VX_PLAN_MAX_ITEMS items are
 * counted in p->dropped but the total still includes their rays. */
void vx_plan_add(vx_plan *p, const char *name, vx_plan_state state,
    double rays, const char *fmt, ...)
	__attribute__((format(printf, 5, 6)));

/* vx_plan_format: the plan as text, one item a line, then the predicted
 * cost, into buf (n bytes, always NUL-terminated when n > 0).  Returns the
 * length the whole text needs (as snprintf), so a caller can size buf. */
size_t vx_plan_format(const vx_plan *p, char *buf, size_t n);

/* The states' names (vx_enum.h): "on", "off", "unsupported"; "?" for
 * another value. */
extern const vx_enum vx_plan_state_enum;

/* vx_scene_plan_isosurface: the plan of the ray-cast isosurface renderer
 * for s.  The rules (formats/scene.md, "Effects and plans"):
 *  - surfaces: every surface is drawn (none: nothing to draw, noted);
 *  - lights: point, directional and headlight shade; environment and sky
 *    lights are not supported yet;
 *  - shadows: shadow rays go to light k only if the effects include shadows
 *    and light k has shadows on; a headlight's shadows are skipped when every
 *    drawn surface is opaque (they fall exactly behind what the eye sees);
 *  - transparency: layers are composited only if the effect is on and a
 *    drawn surface has opacity < 1;
 *  - specular: on if the effect is on and a drawn surface has ks > 0;
 *  - texture: per surface, if the effect is on and it names a texture;
 *  - interreflection, volumetric shadows, scattering, environment and sky
 *    lights, irradiance or SH lookup: reported unsupported when asked for;
 *    DVR transfer functions and the medium: reported as not used.
 * Predicted rays per covered pixel: 1 primary + 2 continuation segments per
 * transparent surface when compositing, plus one shadow ray per shadowing
 * light per shaded layer. */
void vx_scene_plan_isosurface(const vx_scene *s, vx_plan *p);

#endif
