/* vx_gi.h: global illumination on isosurfaces by Monte Carlo path tracing:
 * the irradiance at a point of an isosurface, from the scene's lights and
 * the light its surfaces reflect (Wyman et al. 2006, eq. 1-3).  One
 * estimator serves the bakes (bake-irr: a texel's point on the isosurface
 * through its own value) and the path-traced reference (a pixel's hit).
 *
 * Units.  Irradiance E is the integral over the hemisphere of incident
 * radiance times the cosine.  A Lambertian surface of albedo a reflects
 * radiance a E / pi.  A point or directional light of colour C and
 * intensity I delivers E = pi C I cos(theta) (so a white surface facing it
 * has radiance C I, as in the local model of formats/scene.md); a sky of
 * radiance C I gives E = pi C I to an unoccluded surface; an environment
 * gives the radiance its map says.
 *
 * Isosurfaces are lit from one side, gi.high's: by default that of lower
 * values (f < iso), the outside of a structure in density data (CT, MRI).
 * A ray from that side is blocked where it crosses into the other.
 *
 * The estimator of one sample at point x with unit normal n pointing to
 * the lit side:
 *   E = D(x) + N_env(x) + sum over a cosine-weighted direction w:
 *         the ray escapes:     pi (L_env(w) w_bsdf + L_sky)
 *         the ray hits y:      a(iso) E(y) while bounces remain
 * D is the delta lights' term (shadow rays), N_env one importance sample
 * of the environment, both weighted by the power heuristic against the
 * cosine lobe (multiple importance sampling).  Every surface of a path is
 * the isosurface of the same value, so the albedo a is the scene's albedo
 * at that value.  Random numbers are vx_rng_ld2(seed, stream, sample,
 * pair): pair 3d + 0 draws the direction at depth d, 3d + 1 the
 * environment sample; the result is a pure function of (point, normal,
 * iso, stream, sample).
 *
 * Geometry is traced in the volume's index space (vx_iso.h); directions and
 * distances are sampled in world space and mapped. */
#ifndef VX_GI_H
#define VX_GI_H

#include <stdint.h>

#include "vx_grid.h"
#include "vx_iso.h"
#include "vx_macro.h"
#include "vx_scene.h"

#define VX_GI_MAX_LIGHTS   VX_SCENE_MAX_LIGHTS
#define VX_GI_MAX_BOUNCES  64
#define VX_GI_MAX_ALBEDO   VX_SCENE_MAX_SURFACES

/* A distant light given by functions (an environment map): eval(w) is the
 * radiance arriving from world direction w (unit, pointing away from the
 * surface); sample(u) draws such a direction with its radiance and returns
 * the pdf in solid angle (0 when none); pdf(w) gives that pdf. */
typedef struct vx_gi_env {
	void *ctx;
	void (*eval)(void *ctx, const double w[3], double rgb[3]);
	double (*sample)(void *ctx, const double u[2], double w[3],
	    double rgb[3]);
	double (*pdf)(void *ctx, const double w[3]);
} vx_gi_env;

typedef struct vx_gi_light {
	int point;                /* 1 point light, 0 directional */
	double pos[3];            /* point: world position */
	double dir[3];            /* directional: unit, toward the light */
	double rgb[3];            /* pi C I */
	int inverse_square;
	int shadows;
} vx_gi_light;

typedef struct vx_gi_stats {
	uint64_t samples;         /* estimates made */
	uint64_t rays;            /* bounce rays traced */
	uint64_t shadow_rays;     /* visibility rays (lights, environment) */
	uint64_t hits;            /* bounce rays that hit a surface */
	vx_iso_stats iso;         /* the traversal's counters */
} vx_gi_stats;

typedef struct vx_gi {
	const vx_grid *g;
	vx_iso_tracer tr;
	int nlight;
	vx_gi_light light[VX_GI_MAX_LIGHTS];
	int has_sky;
	double sky[3];            /* radiance */
	int has_env;
	vx_gi_env env;
	int env_mis;              /* 1: importance-sample the environment */
	char env_id[96];          /* names the environment in a bake's
	                             settings (its file's content hash) */
	int bounces;              /* indirect bounces: 0 = direct light only */
	int nalbedo;              /* albedo as a function of the value: */
	double albedo_v[VX_GI_MAX_ALBEDO];     /* at these values (sorted), */
	double albedo_c[VX_GI_MAX_ALBEDO][3];  /* these colours, linear
	                                           between, constant beyond */
	double eps;               /* bounce and shadow rays start this far off
	                             the surface (index units) */
	uint64_t seed;
	int high;                 /* the side bakes light: 0 that of lower
	                             values (density data: the outside of
	                             what the isosurface bounds), 1 that of
	                             higher values (distance-like fields);
	                             the calls take the side as an argument */
	int skipped_headlights;   /* headlights in the scene (view-dependent:
	                             not part of global illumination) */
	int occlusion;            /* the scene's occlusion directive: ambient
	                             occlusion, a white sky of radiance 1 in
	                             place of every light, no bounces */
	double vicinity;          /* world distance past which a path's ray
	                             counts as escaped (vicinity shading,
	                             obscurance); INFINITY: none */
} vx_gi;

/* vx_gi_setup: gi from scene s over volume g with hierarchy m (NULL: flat
 * walk): its point, directional and sky lights (headlights are counted in
 * skipped_headlights and left out), its surfaces' colours as the albedo
 * function (none: 0.8 grey), bounces from its interreflection directive
 * when the interreflection effect is on (else 0).  An environment light is
 * attached afterwards with vx_gi_set_env.  A scene with the occlusion
 * directive gets ambient occlusion instead: no light but a white sky of
 * radiance 1, no bounces, and its distance as the vicinity (then E / pi
 * is the cosine-weighted open fraction of the hemisphere).  Errors:
 * VX_EUSAGE. */
int vx_gi_setup(vx_gi *gi, const vx_scene *s, const vx_grid *g,
    const vx_macro *m, vx_err *e);
void vx_gi_set_env(vx_gi *gi, const vx_gi_env *env, int importance);

/* vx_gi_albedo: the albedo at data value v. */
void vx_gi_albedo(const vx_gi *gi, double v, double rgb[3]);
/* vx_gi_sh_channels: the channels an SH transfer of gi needs: 3 when
 * paths bounce (bounces > 0) off an albedo whose channels differ
 * somewhere, else 1. */
int vx_gi_sh_channels(const vx_gi *gi);

/* vx_gi_direct: the delta lights' irradiance D at world point pw (index
 * point pi) with world normal n toward the lit side (high: that of higher
 * values), iso the surface's value (shadow rays trace it). */
void vx_gi_direct(const vx_gi *gi, const double pw[3], const double pi[3],
    const double n[3], double iso, int high, double rgb[3],
    vx_gi_stats *st);

/* vx_gi_sample: sample `index` of the irradiance estimate at index-space
 * point pi with unit world normal n toward the lit side (high: that of
 * higher values) on the isosurface of value iso (the ray starts at pi
 * itself: offset it first).  D (may be NULL: then it
 * is computed) is vx_gi_direct at the same point, which does not change
 * from sample to sample.  rgb gets the estimate. */
void vx_gi_sample(const vx_gi *gi, const double pi[3], const double n[3],
    double iso, int high, const double D[3], uint64_t stream,
    uint64_t index, double rgb[3], vx_gi_stats *st);

/* vx_gi_transfer: sample `index` of the radiance-transfer path at index
 * point pi with unit world normal n toward the lit side, for SH transfer
 * volumes (Wyman et al. eq. 4-8): the lights of gi play no part.  From pi
 * (offset it first) a cosine-weighted direction (pair 3d, as
 * vx_gi_sample's) is traced; where it hits the isosurface and bounces
 * remain, the path continues from the hit with the throughput multiplied
 * by the albedo at iso.  Returns 1 when the path escapes, with w the world
 * direction it leaves in and thru its throughput (1 1 1 without a bounce);
 * 0 when it ends on a surface (w, thru unspecified).  The transfer
 * estimate of coefficient i is then pi thru Y_i(w). */
int vx_gi_transfer(const vx_gi *gi, const double pi[3], const double n[3],
    double iso, int high, uint64_t stream, uint64_t index, double w[3],
    double thru[3], vx_gi_stats *st);

void vx_gi_stats_add(vx_gi_stats *a, const vx_gi_stats *b);

#endif
