/* vx_dvr.h: direct volume rendering with volumetric light by half-angle
 * slicing, in software (Kniss et al. 2003, §3; dvr(1) and
 * formats/transfer.md are the user's side).
 *
 * The volume is cut by N parallel planes (slices) perpendicular to the
 * slicing axis s, dt apart.  With L the direction the light travels and V
 * the camera's forward axis: when L . V >= 0, s = unit(L + V) and the eye
 * composites the slices front to back; otherwise s = unit(L - V) (the
 * half-angle with the inverted view) and the eye composites back to front.
 * Either way slices are visited in increasing s . x, which is the order
 * the light meets them.  Two buffers advance slice by slice: the eye
 * buffer (one ray through each pixel centre) and the light buffer (one ray
 * through each texel centre of a light camera: orthographic along L for a
 * directional light, perspective from a point light).  At each slice the
 * eye first composites the slice's samples (where its rays cross the
 * plane), lit by the light buffer as it stands (bilinear at the point's
 * projection), then the slice's samples where the light rays cross the
 * plane attenuate the light buffer.  Sample spacing, and so the opacity
 * correction (formats/transfer.md), is taken along each ray between two
 * planes: dt / |s . d| for a ray of unit direction d, not dt.
 *
 * Lighting of a sample of colour E, surface weight S (the transfer
 * function's surface list times its gradient-magnitude ramp), at a point
 * where the light buffer holds the direct transmittance D and the indirect
 * transmittance I (RGB), with light radiance Ll (colour times intensity,
 * over the squared distance for an inverse-square point light) and
 * P = 4 pi p(cos theta) the phase function relative to isotropic
 * (vx_phase.h's table; cos theta between L at the point and the direction
 * toward the eye):
 *   C     = E ((1 - S) + S f)   f = kd max(n . l, 0) + ks (n . h)^shininess
 *           (Blinn-Phong on the unit gradient n, turned toward the eye;
 *           where the gradient is 0, f is not used: C = E;
 *           kd 1, ks 0.2 when the specular effect is on, else 0,
 *           shininess 32)
 *   light = Ll (D P + albedo max(I - D, 0))       with scattering
 *         = Ll D P                                 volumetric shadows only
 *         = Ll P                                   no light buffer
 *   radiance = C light + E ambient + the other lights (below)
 * The indirect term is the light the transport colour and the blur carry
 * beyond the direct light: a material whose transport is its default
 * (1 - alpha) and a blur of angle 0 give exactly the volumetric-shadows
 * picture.  The light buffer's update through a slice sample of corrected
 * alpha a and transport tr (both corrected for the light ray's spacing):
 *   D' = D (1 - a)
 *   I' = tr (1 - a) I + tr a Blur(I)
 * where Blur(I) averages the current buffer at blur_samples points
 * jittered over a disk of radius d tan(angle / 2) (d the light ray's
 * spacing; the paper's eq. 9), the jitter a pure function of (seed, texel,
 * slice): light scatters forward in proportion to the material that
 * scatters it, and empty space carries it on unchanged.
 *
 * Lights.  The first point, directional or headlight (a point light at the
 * eye, or directional along the view for orthographic cameras) drives the
 * light buffer; every other one of those types adds C Ll P at each sample,
 * unshadowed; environment and sky lights are not used.
 *
 * Only what the scene asks for: the light buffer exists only with the
 * effect volumetric-shadows or scattering (scattering implies the direct
 * attenuation); the blur and the indirect term only with scattering; the
 * gradient is computed only when the transfer function needs it
 * (vx_tf_needs_gradient).  Empty space: samples in level-1 macrocells
 * whose [min, max] is clear (vx_tf_range_clear) are skipped (an eye ray
 * moves on at once to the slice where it leaves such a macrocell); a
 * sample of alpha 0 and transport 1 changes nothing either way, so
 * skipping changes no pixel.
 *
 * Approximations, each with its knob (vx_dvr_opts): classification
 * through a table (vx_tf_lut) of tf_table intervals over the volume's
 * range, in the optical form (vx_tf_optic: one exponential corrects a
 * sample's opacity and transport for its spacing) unless the function
 * depends on the gradient; early ray termination front to back at the
 * transmittance cutoff; eye samples at p + k dp with their trilinear
 * weights and lerps in single precision; with jitter, each eye ray's
 * samples shifted along it by its own offset in [-1/2, 1/2) of a slice, a
 * pure function of (seed, pixel), so the planes' rings (wood grain) become
 * fine noise; the light buffer is read where the sample is.
 *
 * Perturbation: with the scene's perturb lines every sample, eye or
 * light, value and gradient, is taken of the perturbed field and its
 * optical properties scaled by the density factor (vx_perturb.h); the
 * clear macrocells are those that stay clear under the perturbation, so
 * skipping still changes no pixel.
 *
 * Determinism: each slice's eye pass and light pass run in parallel over
 * rows; every output value depends only on its pixel or texel and the
 * buffers of the slice before, so the picture is bit-identical at any
 * thread count. */
#ifndef VX_DVR_H
#define VX_DVR_H

#include <stdint.h>

#include "vx_camera.h"
#include "vx_err.h"
#include "vx_grid.h"
#include "vx_image.h"
#include "vx_macro.h"
#include "vx_plan.h"
#include "vx_scene.h"
#include "vx_tf.h"
#include "vx_vec.h"

/* The surface term's Blinn-Phong (the model above; dvr and its references
 * share it): kd 1, ks 0.2 with the specular effect, shininess 32. */
#define VX_DVR_KD 1.0
#define VX_DVR_KS 0.2

/* vx_dvr_normal: n = -grad / |grad| turned toward v (unit, toward the
 * eye); 0 (n unusable) where the gradient is 0 or not finite. */
static inline int
vx_dvr_normal(const double grad[3], const double v[3], double n[3])
{
	n[0] = -grad[0];
	n[1] = -grad[1];
	n[2] = -grad[2];
	vx_unit3(n);
	if (!(vx_dot3(n, n) > 0.5 && vx_finite3(n)))
		return 0;
	if (vx_dot3(n, v) < 0)
		for (int a = 0; a < 3; a++)
			n[a] = -n[a];
	return 1;
}

/* vx_dvr_blinn_phong: f = kd max(n . l, 0) + ks max(n . h, 0)^32 (ks
 * only when specular) for unit n, l (toward the light), v (toward the
 * eye), h = unit(l + v); the power by five squarings. */
static inline double
vx_dvr_blinn_phong(const double n[3], const double l[3], const double v[3],
    int specular)
{
	double nl = vx_dot3(n, l), r = VX_DVR_KD * (nl > 0 ? nl : 0);

	if (specular) {
		double h[3] = { l[0] + v[0], l[1] + v[1], l[2] + v[2] }, x;

		vx_unit3(h);
		x = vx_dot3(n, h);
		x = x > 0 ? x : 0;
		for (int i = 0; i < 5; i++)
			x *= x;
		r += VX_DVR_KS * x;
	}
	return r;
}

#define VX_DVR_MAX_SLICES     65536
#define VX_DVR_MAX_LIGHT_SIZE 8192
#define VX_DVR_MAX_BLUR       16

typedef struct vx_dvr_opts {
	int nthreads;             /* <= 0: OpenMP's default */
	int slices;               /* 0: dt = one voxel (smallest spacing) */
	int light_size;           /* light buffer edge, texels (default 256) */
	double blur_angle;        /* cone apex angle, degrees, [0, 90) (20) */
	int blur_samples;         /* 1..VX_DVR_MAX_BLUR (4) */
	uint64_t seed;            /* the jitters: the eye rays' and the
	                             blur's (1) */
	int no_skip;              /* 1: sample inside clear macrocells too */
	int tf_table;             /* classification table intervals over
	                             the volume's range (vx_tf_lut; 4096);
	                             0: vx_tf_classify at every sample */
	int jitter;               /* 1: each eye ray's samples shifted along
	                             it by a pixel's own fraction of a slice
	                             (default 1) */
	double cutoff;            /* front to back: a pixel is done when its
	                             transmittance falls below it (1e-3);
	                             0: never */
} vx_dvr_opts;

/* vx_dvr_opts_init: the defaults above. */
void vx_dvr_opts_init(vx_dvr_opts *o);

/* What the renderer computes, from the scene and transfer function. */
typedef struct vx_dvr_decide {
	int driver;               /* index of the light that drives the light
	                             buffer, -1 none */
	int light_buffer;         /* 1: a light buffer (direct attenuation) */
	int scatter;              /* 1: blurred, chromatic indirect light */
	int gradient;             /* 1: gradients computed */
	int surface;              /* 1: the surface term (a surface list) */
	int specular;             /* 1: ks 0.2 in the surface term */
	int local[VX_SCENE_MAX_LIGHTS];   /* 1: light k adds unshadowed light */
	double g;                 /* Henyey-Greenstein g (0: isotropic) */
} vx_dvr_decide;

/* vx_dvr_plan: decide, and describe the decisions in p (for --explain). */
void vx_dvr_plan(const vx_scene *s, const vx_tf *tf, const vx_dvr_opts *o,
    vx_dvr_decide *d, vx_plan *p);

/* The slicing geometry of a frame. */
typedef struct vx_dvr_geom {
	double axis[3];           /* s, unit */
	double light_dir[3];      /* L (at the box centre for a point light) */
	double view_dir[3];       /* V */
	int back_to_front;        /* 1: the eye composites back to front */
	int nslices;
	double tmin, dt;          /* slice k at s . x = tmin + (k + 0.5) dt */
	double ref_step;          /* the transfer function's, resolved */
	vx_camera light;          /* the light camera (light_buffer only) */
} vx_dvr_geom;

/* vx_dvr_geometry: the geometry for scene s (camera resolved) over g.
 * Errors: VX_EDATA (a slice count over VX_DVR_MAX_SLICES, a light camera
 * that cannot be made), VX_EINTERNAL. */
int vx_dvr_geometry(const vx_scene *s, const vx_dvr_decide *d,
    const vx_tf *tf, const vx_grid *g, const vx_dvr_opts *o,
    vx_dvr_geom *geo, vx_err *e);

typedef struct vx_dvr_stats {
	int threads, nslices, light_size;
	uint64_t eye_samples;     /* eye ray / slice crossings inside the box */
	uint64_t eye_skipped;     /* of them, in clear macrocells */
	uint64_t eye_done;        /* of them, behind the cutoff */
	uint64_t light_samples, light_skipped;
	double seconds;           /* the whole frame */
	double setup_s, eye_s, light_s;   /* its phases */
} vx_dvr_stats;

/* vx_dvr_render: the picture of g through tf as scene s says (camera
 * resolved, d from vx_dvr_plan), into out (RGBA, linear radiance
 * premultiplied by coverage 1 - transmittance; allocated here, named
 * "color").  m: g's
 * hierarchy for empty-space skipping, or NULL.  st may be NULL.  Errors:
 * VX_EDATA, VX_ENOMEM. */
int vx_dvr_render(const vx_scene *s, const vx_dvr_decide *d, const vx_tf *tf,
    const vx_grid *g, const vx_macro *m, const vx_dvr_opts *o,
    vx_image *out, vx_dvr_stats *st, vx_err *e);

#endif
