/* vx_scene.h: the scene description (formats/scene.md is the spec): camera
 * and image size, background, ambient term, lights, surfaces with their
 * materials per isovalue, the effects wanted, and reserved directives that
 * later renderers will compute (environment and sky lights, interreflection,
 * irradiance or SH lookup, DVR transfer functions, the medium).
 *
 * A scene is a plain struct of fixed size: it owns no memory, so it can be
 * copied by assignment.  Text in, text out: vx_scene_parse reads the
 * line-oriented format, vx_scene_format writes it, and
 * parse(format(s)) equals s (vx_scene_equal) with every double exact.
 * Renderers derive a plan from a scene (vx_plan.h) and compute only what it
 * calls for. */
#ifndef VX_SCENE_H
#define VX_SCENE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "vx_camera.h"
#include "vx_enum.h"
#include "vx_err.h"
#include "vx_grid.h"
#include "vx_stream.h"
#include "vx_tf.h"

#define VX_SCENE_VERSION      1
#define VX_SCENE_MAX_LIGHTS   16
#define VX_SCENE_MAX_SURFACES 16
#define VX_SCENE_MAX_TF       64        /* points per transfer function list */
#define VX_SCENE_MAX_EXT      16        /* x- extension lines kept */
#define VX_SCENE_EXT_LEN      256       /* bytes per kept extension line */
#define VX_SCENE_NAME_MAX     64        /* volume names, as vx_grid.name */
#define VX_SCENE_PATH_MAX     1024      /* file names */
#define VX_SCENE_LINE_MAX     16384     /* bytes per line */
#define VX_SCENE_TEXT_MAX     ((size_t)1 << 20)   /* bytes per scene */

/* Effects: bits of vx_scene.effects.  The first four are computed by the
 * ray-cast isosurface renderer; the others are reserved (parsed, stored,
 * reported as not supported yet). */
enum {
	VX_FX_SHADOWS            = 1u << 0,
	VX_FX_SPECULAR           = 1u << 1,
	VX_FX_TRANSPARENCY       = 1u << 2,
	VX_FX_TEXTURE            = 1u << 3,
	VX_FX_INTERREFLECTION    = 1u << 4,   /* reserved */
	VX_FX_VOLUMETRIC_SHADOWS = 1u << 5,   /* reserved */
	VX_FX_SCATTERING         = 1u << 6,   /* reserved */
	VX_FX_ALL                = (1u << 7) - 1,
	/* the set a scene has when it has no effects line */
	VX_FX_DEFAULT = VX_FX_SHADOWS | VX_FX_SPECULAR | VX_FX_TRANSPARENCY |
	    VX_FX_TEXTURE
};

typedef enum vx_light_type {
	VX_LIGHT_UNKNOWN = 0,
	VX_LIGHT_POINT,
	VX_LIGHT_DIRECTIONAL,
	VX_LIGHT_HEADLIGHT,       /* at the camera: a point light at the eye, or
	                             along forward for orthographic cameras */
	VX_LIGHT_ENVIRONMENT,     /* HDR environment map (vx_env.h) */
	VX_LIGHT_SKY,             /* constant sky (vx_env.h) */
	VX_LIGHT_LAST
} vx_light_type;

typedef enum vx_falloff {
	VX_FALLOFF_UNKNOWN = 0,
	VX_FALLOFF_NONE,
	VX_FALLOFF_INVERSE_SQUARE,
	VX_FALLOFF_LAST
} vx_falloff;

/* How an environment map's pixels cover the sphere (formats/scene.md). */
typedef enum vx_env_layout {
	VX_ENV_LAYOUT_UNKNOWN = 0,
	VX_ENV_LATLONG,           /* latitude-longitude (equirectangular) */
	VX_ENV_ANGULAR,           /* Debevec's angular map (light probe) */
	VX_ENV_LAYOUT_LAST
} vx_env_layout;

typedef struct vx_light {
	vx_light_type type;
	double color[3];          /* linear RGB, >= 0 */
	double intensity;         /* >= 0, scales color */
	double position[3];       /* point */
	double direction[3];      /* directional: the way the light travels,
	                             nonzero, not normalized */
	vx_falloff falloff;       /* point and headlight */
	int shadows;              /* 1: casts shadows when the effect is on */
	char file[VX_SCENE_PATH_MAX];  /* environment: image file (PFM, Radiance
	                             HDR or OpenEXR) */
	vx_env_layout layout;     /* environment: the map's layout */
	double rotation[3];       /* environment: degrees about x, then y, then
	                             z (world axes): R = Rz Ry Rx */
	int has_hash;             /* environment: 1 when hash is set */
	uint64_t hash;            /* environment: the pixels' content hash
	                             (vx_env.h), checked when the file is read */
} vx_light;

typedef enum vx_colormap {
	VX_COLORMAP_UNKNOWN = 0,
	VX_COLORMAP_GRAY,
	VX_COLORMAP_HOT,
	VX_COLORMAP_COOLWARM,
	VX_COLORMAP_VIRIDIS,
	VX_COLORMAP_LAST
} vx_colormap;

typedef struct vx_material {
	double color[3];          /* diffuse albedo, linear RGB in [0,1] */
	double opacity;           /* 1 opaque; < 1 a transparent layer; [0,1] */
	double kd, ks;            /* diffuse and specular weights, >= 0 */
	double shininess;         /* Blinn-Phong exponent, >= 0 */
	char texture[VX_SCENE_NAME_MAX];   /* volume mapped as color; "" none */
	vx_colormap colormap;     /* texture's color map */
	int has_window;           /* 0: the texture volume's value range */
	double window[2];         /* texture values mapped to 0 and 1, lo < hi */
} vx_material;

typedef struct vx_surface {
	double iso;               /* isovalue, finite */
	vx_material m;
} vx_surface;

/* Reserved: illumination lookup from a precomputed volume. */
typedef enum vx_illum {
	VX_ILLUM_UNKNOWN = 0,
	VX_ILLUM_LOCAL,           /* lights evaluated at the hit (the default) */
	VX_ILLUM_IRRADIANCE,      /* irradiance volume (IRRV) */
	VX_ILLUM_SH,              /* SH transfer volume (SHTV) and lighting */
	VX_ILLUM_PATHTRACE,       /* per-pixel path tracing (the reference) */
	VX_ILLUM_LAST
} vx_illum;

typedef enum vx_phase {
	VX_PHASE_UNKNOWN = 0,
	VX_PHASE_ISOTROPIC,
	VX_PHASE_HENYEY_GREENSTEIN,
	VX_PHASE_LAST
} vx_phase;

/* Volume perturbation (formats/scene.md, "perturb"; dvr's vx_perturb.h
 * computes it): what the noise moves, one slot each in vx_scene.perturb
 * (index target - 1). */
typedef enum vx_perturb_target {
	VX_PERTURB_UNKNOWN = 0,
	VX_PERTURB_COORDINATES,   /* the data coordinates a sample reads */
	VX_PERTURB_VALUE,         /* the sampled value, before classification */
	VX_PERTURB_DENSITY,       /* the extinction: opacity and transport */
	VX_PERTURB_LAST
} vx_perturb_target;

#define VX_PERTURB_N (VX_PERTURB_LAST - 1)
#define VX_PERTURB_MAX_SEED 1000000000L

typedef struct vx_scene_perturb {
	int on;                   /* 1: a perturb line set this target */
	double scale;             /* world units per lattice cell of the first
	                             octave, > 0, finite */
	double amplitude;         /* >= 0, finite: world units (coordinates),
	                             value units (value), a factor (density) */
	int octaves;              /* 1 .. 24 (default 4) */
	double lacunarity;        /* (0, 1000] (default 2) */
	double gain;              /* (0, 1000] (default 0.5) */
	long seed;                /* 0 .. VX_PERTURB_MAX_SEED (default 0) */
	int turbulence;           /* 1: turbulence (sums of |noise|, [0, 1]),
	                             0: fBm ([-1, 1], the default) */
} vx_scene_perturb;

typedef struct vx_scene {
	vx_camera camera;         /* includes the image size (camera.w, .h) */
	char volume[VX_SCENE_NAME_MAX];   /* isosurface volume; "" the first */
	double background[3];
	double ambient[3];        /* ambient light color */
	double ambient_intensity;
	unsigned effects;         /* VX_FX_* bits */

	int default_lights;       /* 1: lights are the defaults (a headlight);
	                             the first light line replaces them */
	int nlight;
	vx_light light[VX_SCENE_MAX_LIGHTS];
	int nsurface;
	vx_surface surface[VX_SCENE_MAX_SURFACES];

	/* ---- reserved: parsed and stored, computed by no renderer yet ---- */
	int has_interreflection;
	int bounces, samples;     /* interreflection: bounces >= 0, samples >= 1 */
	int has_occlusion;        /* ambient occlusion / vicinity shading: */
	double occlusion_distance;/* > 0: rays longer than this (world units)
	                             count as open; 0: unlimited */
	int has_illumination;
	vx_illum illumination;
	int sh_order;             /* SH: order n >= 1 (n^2 coefficients) */
	int pt_samples;           /* pathtrace: paths per pixel sample, >= 1 */
	vx_interp interp;
	/* the transfer function of direct volume rendering (formats/
	 * transfer.md); each list 0 points when absent, abscissae
	 * non-decreasing, values in [0,1] */
	int ntf_opacity;          /* value, opacity */
	double tf_opacity[VX_SCENE_MAX_TF][2];
	int ntf_color;            /* value, r, g, b */
	double tf_color[VX_SCENE_MAX_TF][4];
	int ntf_transport;        /* value, r, g, b (the transport colour) */
	double tf_transport[VX_SCENE_MAX_TF][4];
	int ntf_surface;          /* value, surface-shading weight */
	double tf_surface[VX_SCENE_MAX_TF][2];
	int ntf_gradient;         /* gradient magnitude (>= 0), factor */
	double tf_gradient[VX_SCENE_MAX_TF][2];
	int has_tf_surface_ramp;  /* 1: "transfer surface gradient G0 G1" */
	double tf_surface_ramp[2];/* surface weight 0 at gradient magnitude
	                             G0, 1 at G1: 0 <= G0 < G1, finite */
	int has_tf_step;          /* 1: tf_step was given */
	double tf_step;           /* reference step, world units, >= 0 (0: one
	                             voxel along the smallest spacing) */
	char tf_file[VX_SCENE_PATH_MAX];  /* "transfer file": "" none */
	vx_tf_format tf_file_format; /* with tf_file */
	int has_medium;
	vx_phase phase;
	double phase_g;           /* Henyey-Greenstein asymmetry, (-1, 1) */
	double albedo[3];         /* scattering albedo, [0,1] */
	vx_scene_perturb perturb[VX_PERTURB_N];   /* by target - 1 */

	/* ---- extension lines (x-...) kept verbatim, written back ---- */
	int next;
	char ext[VX_SCENE_MAX_EXT][VX_SCENE_EXT_LEN];
} vx_scene;

/* vx_scene_init: the default scene: auto camera (front view, perspective,
 * fov 30, distance 1.1), 512 x 512, black background, ambient white at 0.1,
 * one headlight (white, intensity 1, no falloff, no shadows), no surfaces,
 * effects VX_FX_DEFAULT, nothing reserved set. */
void vx_scene_init(vx_scene *s);
/* vx_surface_init: a surface at iso with the default material: color 0.8,
 * opacity 1, kd 1, ks 0.2, shininess 32, no texture, colormap gray. */
void vx_surface_init(vx_surface *sf, double iso);
/* vx_light_init: a light of this type with the defaults: white, intensity 1,
 * falloff none, shadows on for point and directional lights, off for
 * headlight, environment and sky lights. */
void vx_light_init(vx_light *l, vx_light_type type);

/* vx_scene_parse: initialize s to the defaults and apply text (n bytes, not
 * necessarily NUL-terminated).  Errors: VX_EDATA with "line N: ..." naming
 * the first bad line (s is then left at the defaults), VX_ENOMEM. */
int vx_scene_parse(vx_scene *s, const char *text, size_t n, vx_err *e);

/* vx_scene_read: vx_scene_parse of everything f holds (at most
 * VX_SCENE_TEXT_MAX bytes; VX_EIO on a read error). */
int vx_scene_read(vx_scene *s, FILE *f, vx_err *e);

/* vx_scene_format: the canonical text of s, with every double printed so it
 * reads back exactly.  *text is malloc'd, NUL-terminated, owned by the
 * caller; *n gets its length (without the NUL). */
int vx_scene_format(const vx_scene *s, char **text, size_t *n, vx_err *e);

/* vx_scene_equal: 1 if a and b describe the same scene: every field that the
 * description uses (for its camera kind and light types) bit-identical;
 * derived camera fields are ignored. */
int vx_scene_equal(const vx_scene *a, const vx_scene *b);

/* ---- overrides from the command line ----
 * All apply on top of s, as if the line were appended to the scene file, and
 * leave s unchanged on error (VX_EUSAGE, the message names the option). */

/* vx_scene_apply: one directive line ("surface iso 90 opacity 0.5"). */
int vx_scene_apply(vx_scene *s, const char *line, vx_err *e);

/* vx_scene_set_iso: make the surfaces exactly iso[0..n-1] (1 <= n <=
 * VX_SCENE_MAX_SURFACES): surface k keeps the material of the scene's
 * surface k if it has one, else takes the last one's (or the default). */
int vx_scene_set_iso(vx_scene *s, const double *iso, int n, vx_err *e);

/* vx_scene_set_view: switch to auto framing from a named view; projection,
 * fov, distance factor and a given up vector are kept.  v may be
 * VX_VIEW_ANGLES (then azimuth and elevation are used). */
int vx_scene_set_view(vx_scene *s, vx_view v, double azimuth,
    double elevation, vx_err *e);

/* vx_scene_option: the command-line options tools share, by name:
 *   set LINE         vx_scene_apply
 *   iso V[,V...]     vx_scene_set_iso
 *   size WxH         image size
 *   view NAME|AZ,EL  vx_scene_set_view (named view or degrees)
 *   light SPEC       append "light SPEC" (e.g. "directional direction 0 1 -1")
 *   lights none      remove every light
 *   effects WORDS    "effects WORDS" ("-shadows", "shadows specular", "none")
 *   background R,G,B background color
 *   fov DEG          camera field of view
 * Unknown names are VX_EINTERNAL (a bug in the tool). */
int vx_scene_option(vx_scene *s, const char *name, const char *value,
    vx_err *e);

/* ---- stream form: the SCNE chunk ----
 * Payload: a text header ("version: 1", "length: N" bytes of scene text,
 * "encoding: raw|zlib"), an empty line, then the scene text (formats/scene.md,
 * "In a stream"). */
int vx_scene_to_chunk(const vx_scene *s, int zlevel, vx_chunk *c, vx_err *e);
int vx_scene_from_chunk(vx_scene *s, const vx_chunk *c, vx_err *e);
/* vx_scene_from_stream: the first SCNE chunk of st; *index gets its position,
 * or -1 when the stream has none (then s gets the defaults and 0 is
 * returned).  index may be NULL. */
int vx_scene_from_stream(vx_scene *s, const vx_stream *st, long *index,
    vx_err *e);
/* vx_scene_to_stream: replace st's first SCNE chunk by s, or append one. */
int vx_scene_to_stream(const vx_scene *s, vx_stream *st, vx_err *e);

/* ---- names and helpers ----
 * The words of the format (vx_enum.h): light types, environment layouts,
 * falloffs, illumination modes, phases, colormaps, perturbation targets
 * (an unknown name has the UNKNOWN value, an unknown value the name
 * "unknown"); effects, named by their VX_FX_ bit (an unknown bit has no
 * name, NULL). */
extern const vx_enum vx_light_type_enum, vx_env_layout_enum, vx_falloff_enum,
    vx_illum_enum, vx_phase_enum, vx_colormap_enum,
    vx_effect_enum, vx_perturb_target_enum;
/* vx_colormap_eval: color for t (clamped to [0,1]) under map m; unknown
 * maps give gray.  The maps are piecewise linear (formats/scene.md). */
void vx_colormap_eval(vx_colormap m, double t, double rgb[3]);

#endif
