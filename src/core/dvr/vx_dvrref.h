/* vx_dvrref.h: references for direct volume rendering, to measure
 * half-angle slicing (vx_dvr.h) against: a ray marcher with an exact
 * shadow ray per sample, and a volumetric path tracer (dvr(1)'s
 * --reference).  Both read the same scene, transfer function (vx_tf.h),
 * camera and decisions (vx_dvr_plan) as the slicer, sample the grid by
 * vx_grid_trilinear and use Henyey-Greenstein exactly (vx_phase_hg, not
 * the slicer's table).
 *
 * Ray march (VX_DVRREF_RAYMARCH).  One ray through each pixel centre,
 * clipped to the volume's box, is cut into segments of the march step h
 * (the transfer function's reference step unless told otherwise) from
 * where it enters; the last segment is what is left (shorter).  Each
 * segment is one sample at its midpoint, of opacity corrected for its own
 * length d (formats/transfer.md: 1 - (1 - alpha)^(d / ref)), composited
 * front to back.  A sample of opacity > 0 is lit as vx_dvr.h's colour
 * model states for "volumetric shadows only":
 *   radiance = C Ll D P + E ambient + C Ll_k P_k (each other light)
 * with C the sample's colour times the surface term, P = 4 pi p(cos) the
 * exact Henyey-Greenstein phase relative to isotropic, and D the
 * transmittance toward the driving light by a second march from the
 * sample: segments of h along the direction to the light (the first
 * starting at the sample), up to where it leaves the box (a directional
 * light, an orthographic headlight) or up to the light (a point light),
 * each segment's midpoint attenuating by its corrected opacity (Beer-
 * Lambert with the corrected alphas).  D is 1 when the plan has no light
 * buffer (no volumetric-shadows or scattering effect): then the reference
 * is the slicer's unshadowed picture.  Cost: O(n) samples per pixel, each
 * with a shadow ray of O(n) samples: O(n^2) per pixel.  Through a
 * homogeneous slab the coverage is 1 - exp(-sigma d) to rounding (the
 * segments add up to the path); the slicer's scattering term is not
 * computed (what the slicer approximates there is the path tracer's).
 *
 * Path tracer (VX_DVRREF_PATHTRACE).  The medium's extinction is
 * sigma_t(x) = -ln(1 - alpha(x)) / ref, alpha the transfer function's
 * opacity at x (capped at VX_DVRREF_ALPHA_CAP, so fully opaque material is
 * dense but finite).  Paths start at the pixel centre's camera ray and
 * find their vertices by delta tracking (Woodcock) against a majorant
 * sigma_max from the largest opacity the transfer function gives over the
 * grid's value range.  At each vertex x seen from direction v:
 *   next-event estimation toward the driving light, its transmittance by
 *   ratio tracking (up to the box's edge or the point light):
 *     vertex 1:  the ray marcher's radiance, D the ratio-tracking estimate
 *                (C, surface term, ambient, unshadowed other lights);
 *     vertex k > 1: C Ll D P (the driving light only);
 *   then, up to `bounces` vertices, the path goes on in a direction
 *   sampled from Henyey-Greenstein (vx_phase_hg_sample: weight 1) with its
 *   throughput multiplied by C_rgb x the scene's medium albedo (the
 *   fraction of scattered light that scatters again; dvr's indirect term
 *   carries the same factor).
 * So `bounces` 1 is single scattering, the ray marcher's picture with
 * exact (continuous) attenuation and no step; more bounces add multiple
 * scattering.  A path leaving the box ends (the background is not a
 * light).  The pixel is the mean over spp paths numbered first ..
 * first + spp - 1: colour the mean contribution, coverage the fraction of
 * paths with a vertex (an unbiased estimate of 1 - transmittance).
 *
 * Determinism: a pixel depends only on itself; the path tracer's numbers
 * are vx_rng_uniform(seed, pixel index y W + x, path number, draw number
 * along the path): bit-identical at any thread count, and sample n is the
 * same whatever spp or first. */
#ifndef VX_DVRREF_H
#define VX_DVRREF_H

#include <stdint.h>

#include "vx_dvr.h"

#define VX_DVRREF_RAYMARCH   1
#define VX_DVRREF_PATHTRACE  2
#define VX_DVRREF_MAX_SPP     (1 << 24)
#define VX_DVRREF_MAX_BOUNCES 1024
#define VX_DVRREF_ALPHA_CAP   (1 - 1.0 / (1 << 20))

typedef struct vx_dvrref_opts {
	int method;               /* VX_DVRREF_RAYMARCH or _PATHTRACE */
	int nthreads;             /* <= 0: OpenMP's default */
	double step;              /* ray march step (world); 0: reference step */
	int spp;                  /* paths per pixel (16) */
	int bounces;              /* vertices per path, >= 1 (1) */
	uint64_t first;           /* number of the first path (0) */
	uint64_t seed;            /* (1) */
} vx_dvrref_opts;

/* vx_dvrref_opts_init: the defaults above, method raymarch. */
void vx_dvrref_opts_init(vx_dvrref_opts *o);

/* vx_dvrref_plan: describe the reference's work for the decisions d of
 * vx_dvr_plan (which it reads, not changes) into p (for --explain). */
void vx_dvrref_plan(const vx_scene *s, const vx_tf *tf,
    const vx_dvr_decide *d, const vx_dvrref_opts *o, vx_plan *p);

typedef struct vx_dvrref_stats {
	int threads;
	double step;              /* ray march step, world */
	double sigma_max;         /* path tracer's majorant, 1 / world */
	uint64_t samples;         /* ray march: eye samples; paths */
	uint64_t shadow_steps;    /* shadow march segments, ratio-tracking
	                             steps */
	uint64_t vertices;        /* path tracer: real collisions */
	uint64_t tentative;       /* path tracer: delta-tracking steps */
	double seconds;
} vx_dvrref_stats;

/* vx_dvrref_render: the reference picture of g through tf as scene s says
 * (camera resolved, d from vx_dvr_plan), into out (RGBA, linear radiance
 * premultiplied by coverage, "color", allocated here).  st may be NULL.
 * Errors: VX_EDATA (a box that is not finite), VX_EINTERNAL (options out
 * of range), VX_ENOMEM. */
int vx_dvrref_render(const vx_scene *s, const vx_dvr_decide *d,
    const vx_tf *tf, const vx_grid *g, const vx_dvrref_opts *o,
    vx_image *out, vx_dvrref_stats *st, vx_err *e);

#endif
