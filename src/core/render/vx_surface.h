/* vx_surface.h: the isosurfaces of a scene as every renderer and baker
 * sees them, whatever their source.
 *
 *  - The source: a volume, traced in index space through its hierarchy
 *    (vx_iso.h: analytic roots of the trilinear cells), or a tet mesh,
 *    traced in world space through its leaf grid (vx_tetleaf.h: watertight
 *    crossings, the tet's constant gradient as normal).
 *  - The isovalues, each with its scene surface (the material) and the
 *    fraction of light a visibility ray loses crossing it.
 *  - The hit record (vx_hit): world point, unit normal facing against the
 *    ray, which isovalue, which way it was crossed; one record for both
 *    sources, so shading, shadows and compositing are written once.
 *  - Visibility: the transmission from a surface point toward a light
 *    through every isovalue of the set (shadow rays).
 *  - Light evaluation: a scene light's direction, distance and radiance at
 *    a point.
 *  - Shading: the albedo (the material's color, or a texture volume through
 *    its colormap), ambient light, and per light Lambert and Blinn-Phong
 *    with its shadow (vx_surf_shade, what raycast draws); or, as the plan
 *    says, Lambert under an irradiance in place of the lights: baked in an
 *    irradiance volume (vx_irrvol.h) or path-traced at the hit (vx_gi.h);
 *    vx_surf_shade_irradiance for an irradiance from elsewhere.
 *
 * A baker or a path tracer makes its own vx_surfaces for the isovalues it
 * needs (vx_surfaces_add: any isovalue, not only the drawn ones), traces
 * with vx_surf_trace, evaluates the lights at a hit with vx_surf_light and
 * their visibility with vx_surf_visibility.  Everything here reads the
 * vx_surfaces and writes only the caller's vx_surf_stats: any number of
 * threads share one vx_surfaces, each with its own stats. */
#ifndef VX_SURFACE_H
#define VX_SURFACE_H

#include <stdint.h>

#include "vx_err.h"
#include "vx_grid.h"
#include "vx_gi.h"
#include "vx_irrvol.h"
#include "vx_iso.h"
#include "vx_macro.h"
#include "vx_plan.h"
#include "vx_scene.h"
#include "vx_tetleaf.h"
#include "vx_tetmesh.h"

typedef struct vx_surfaces {
	/* the source: a volume (g non-NULL) ... */
	const vx_grid *g;
	vx_iso_tracer tr;        /* its tracer (hierarchy, solver, mask) */
	/* ... or a tet mesh (mesh non-NULL) and its leaf grid */
	const vx_tetmesh *mesh;
	const vx_tetleaf *lg;
	double offset;           /* visibility rays start this far off the
	                            surface, along its normal toward the
	                            light: voxels (volume), world units
	                            (mesh) */
	/* the isovalues */
	int niso;
	double isod[VX_ISO_MAX]; /* drawn isovalues, as given (the tracers
	                            take them so) */
	float iso[VX_ISO_MAX];   /* each rounded to float: the cell mask's
	                            and bins' bracket tests (a superset of
	                            isod's, vx_iso.h) */
	int surf[VX_ISO_MAX];    /* the scene surface of each (its material) */
	double opacity[VX_ISO_MAX];   /* light lost crossing it, 0..1 */
	/* shading: the scene (lights, ambient, materials), the plan (which
	 * lights, shadows, textures, highlights), textures per surface and
	 * their windows */
	const vx_scene *s;
	const vx_plan *p;
	const vx_grid *const *tex;
	double tex_lo[VX_SCENE_MAX_SURFACES], tex_hi[VX_SCENE_MAX_SURFACES];
	int timing;              /* 1: count the shadow rays' cycles */
	/* illumination in place of the lights (volumes; the plan says
	 * which): */
	const vx_irrvol *irr;    /* irradiance: the baked volume, or an SH
	                            transfer volume (irr->sh_order > 0), */
	vx_interp irr_interp;     /* read so; */
	const double *shl;       /* SH: the lighting's radiance coefficients
	                            in vx_sh.h's basis, 3 channels of
	                            irr->sh_order^2 each (r's first): E of
	                            channel c = sum over i of shl[c n^2 + i]
	                            times the transfer's coefficient i of
	                            channel c (of channel 0 when it has one) */
	float *sh_e;             /* SH: per stored texel, its E (3 floats),
	                            computed the first time a lookup reads it
	                            (the dot product once a texel, not once a
	                            hit); sh_done[s] says it is there.  Set up
	                            by the renderer for the frame */
	unsigned char *sh_done;
	vx_irr_need_fn irr_need; /* non-NULL: a collecting pass (lazy
	                            illumination): each shaded point reports
	                            the texels its lookup reads (vx_irr_reach;
	                            from every thread) and is drawn black */
	void *irr_need_ctx;
	const vx_gi *gi;         /* pathtrace: the estimator */
} vx_surfaces;

/* A surface point, whatever source found it. */
typedef struct vx_hit {
	double t;                /* ray parameter (world distance along the
	                            unit ray) */
	int iso;                 /* index into the vx_surfaces' isovalues */
	int entering;            /* the ray crossed from f < iso to f >= iso */
	double P[3];             /* world point */
	double n[3];             /* world unit normal, against the ray */
	double pi[3];            /* volume: the point in index space */
} vx_hit;

/* vx_hit_fn: called for each hit of a trace, in order; nonzero stops it. */
typedef int (*vx_hit_fn)(void *ctx, const vx_hit *h);

/* What the calls of one thread count (added to, never reset). */
typedef struct vx_surf_stats {
	vx_iso_stats iso;        /* volume traces (cells, roots, hits, walk) */
	vx_tettrace_stats tet;   /* mesh traces */
	uint64_t shadow;         /* visibility rays */
	uint64_t shaded;         /* points shaded */
	uint64_t cyc_shadow;     /* with timing: cycles in visibility rays */
	uint64_t irr_missing;    /* irradiance lookups that found no usable
	                            texel (drawn black) */
	uint64_t paths, gi_rays; /* pathtrace: paths, and the rays they traced
	                            (bounce and shadow) */
} vx_surf_stats;

/* vx_surfaces_init: no source, no isovalues, no scene. */
void vx_surfaces_init(vx_surfaces *sf);

/* vx_surfaces_volume: the source is volume g with hierarchy m (NULL or
 * flat: every cell walked), cell solver `solver` (vx_cell_solver);
 * visibility rays start offset voxels off the surface. */
void vx_surfaces_volume(vx_surfaces *sf, const vx_grid *g,
    const vx_macro *m, int solver, int flat, double offset);

/* vx_surfaces_mesh: the source is tet mesh `mesh` with leaf grid lg;
 * visibility rays start offset mean tet sizes off the surface (the cube
 * root of the mesh box's volume per tet: a property of the mesh, not of
 * its leaf grid, so pictures do not depend on the grid). */
void vx_surfaces_mesh(vx_surfaces *sf, const vx_tetmesh *mesh,
    const vx_tetleaf *lg, double offset);

/* vx_surfaces_add: isovalue iso, shaded with scene surface `surface`'s
 * material (when there is a scene), losing `opacity` of the light a
 * visibility ray carries across it.  Returns its index, or -1 (VX_EDATA in
 * e) past VX_ISO_MAX. */
int vx_surfaces_add(vx_surfaces *sf, double iso, int surface, double opacity,
    vx_err *e);

/* vx_surfaces_scene: shade with scene s as plan p says, textures tex[k]
 * for surface k where the plan has them (tex may be NULL), and add the
 * isovalues the plan draws (opacity: the material's when the plan
 * composites layers, else 1).  Errors: VX_EDATA (no surface to draw). */
int vx_surfaces_scene(vx_surfaces *sf, const vx_scene *s, const vx_plan *p,
    const vx_grid *const *tex, vx_err *e);

/* vx_surf_hit_volume: the record of volume hit h of the ray with world
 * direction dw (the volume's normal turned against dw, vx_iso_normal). */
void vx_surf_hit_volume(const vx_surfaces *sf, const vx_iso_hit *h,
    const double dw[3], vx_hit *out);

/* vx_surf_hit_mesh: the record of mesh hit h of the world ray ow + t dw
 * (the tet's gradient turned against dw). */
void vx_surf_hit_mesh(const vx_tethit *h, const double ow[3],
    const double dw[3], vx_hit *out);

/* vx_surf_trace: every crossing of the isovalues along the world ray
 * ow + t dw (dw unit) for t in [0, tmax], in order, as records handed to
 * fn.  Returns 0, or fn's nonzero value. */
int vx_surf_trace(const vx_surfaces *sf, const double ow[3],
    const double dw[3], double tmax, vx_hit_fn fn, void *ctx,
    vx_surf_stats *st);

/* vx_surf_visibility: the transmission from surface point h toward the
 * unit world direction Ld, up to distance dist (INFINITY: a directional
 * light), through every isovalue: the product of (1 - opacity) of the
 * surfaces crossed, 0 once below 1e-4.  The ray starts sf->offset off the
 * surface on the lit side; a first crossing of h's own surface the other
 * way than the eye ray crossed it is the ray leaving that surface (its
 * start was a little inside: the root is only as exact as the solver), not
 * an occluder. */
double vx_surf_visibility(const vx_surfaces *sf, const vx_hit *h,
    const double Ld[3], double dist, vx_surf_stats *st);

/* vx_surf_light: scene s's light k seen from world point P: unit direction
 * L toward it, its distance (INFINITY for directional lights, and for a
 * headlight of an orthographic camera) and the radiance arriving (color
 * times intensity, over the squared distance where it falls off so). */
void vx_surf_light(const vx_scene *s, int k, const double P[3], double L[3],
    double *dist, double rad[3]);

/* vx_surf_albedo: the diffuse color at h: its surface's texture through
 * the material's colormap where the plan has one, else its color. */
void vx_surf_albedo(const vx_surfaces *sf, const vx_hit *h, double alb[3]);

/* vx_surf_shade: outgoing radiance at h seen along world direction dw.
 * With the local lights: ambient times albedo, plus for each light the
 * plan switches on that faces the surface, its radiance times its
 * visibility (where the plan shadows it) times Lambert (kd albedo n.L) and
 * Blinn-Phong (ks (n.H)^s, where the plan has highlights).  Where the plan
 * has irradiance: Lambert under the irradiance volume's value at h
 * (vx_surf_shade_irradiance; with irr_need, the texels reported and
 * black); where it path-traces: Lambert under the mean of the scene's
 * pt_samples estimates of vx_gi at h, lit from the eye's side, their
 * random numbers a stream per hit point (the same at any thread count). */
void vx_surf_shade(const vx_surfaces *sf, const vx_hit *h, const double dw[3],
    double col[3], vx_surf_stats *st);

/* vx_surf_shade_irradiance: the radiance a Lambertian surface reflects at
 * h under irradiance E (vx_gi.h's units: the hemisphere's integral of
 * radiance times cosine): kd albedo E / pi.  A light delivers E = pi rad
 * n.L (vx_gi.h), and this gives vx_surf_shade's diffuse term for it. */
void vx_surf_shade_irradiance(const vx_surfaces *sf, const vx_hit *h,
    const double E[3], double col[3]);

#endif
