/* vx_perturb.h: volume perturbation by noise for direct volume rendering
 * (Kniss et al. 2003, section 5; the scene's perturb lines, formats/
 * scene.md, are the user's side).
 *
 * Three targets, each from its own perturb line, each a fractal sum of
 * vx_noise.h's counter-based gradient noise n(x) over world points x at
 * frequency 1 / scale (fBm, in [-1, 1], or turbulence, in [0, 1]):
 *   coordinates  the sample at x reads the volume at x + A (n1, n2, n3)(x),
 *                three decorrelated sums (the paper's texture-coordinate
 *                perturbation); A in world units
 *   value        the value read becomes v + A n(x), before classification
 *   density      the classified sample's extinction is multiplied by
 *                m = max(0, 1 + A n(x)): alpha' = 1 - (1 - alpha)^m and
 *                transport' = transport^m per channel (the paper's
 *                perturbation of optical properties; the default
 *                transport 1 - alpha follows)
 * The perturbed field is F'(x) = F(x + D(x)) + A_v n_v(x), F the volume
 * trilinearly interpolated; its gradient (for 2D transfer functions and
 * the surface term) is F's gradient by central differences at x + D(x),
 * one voxel either side as unperturbed, carried through the displacement
 * by the chain rule with the noise's exact derivative:
 *   grad F'(x) = (I + J_D(x))^T grad F(x + D(x)) + A_v grad n_v(x).
 * A target is on when its line is given with amplitude > 0; with none on,
 * no noise is evaluated and every function here computes exactly what the
 * unperturbed renderer does (the same operations, bit for bit).
 *
 * Noise seeds: the line's seed K, mixed with the target and component, so
 * the three coordinate fields and the value and density fields are
 * decorrelated; a value is a pure function of (K, target, component, x),
 * the same at any thread count and in any order. */
#ifndef VX_PERTURB_H
#define VX_PERTURB_H

#include <stdint.h>

#include "vx_err.h"
#include "vx_grid.h"
#include "vx_macro.h"
#include "vx_noise.h"
#include "vx_plan.h"
#include "vx_scene.h"
#include "vx_tf.h"

typedef struct vx_perturb {
	int any;                  /* 1: some target is on */
	int on[VX_PERTURB_N];     /* by target - 1 */
	double amp[VX_PERTURB_N];
	int turb[VX_PERTURB_N];   /* 1: turbulence, 0: fBm */
	vx_noise_fbm coord[3];    /* the displacement's components */
	vx_noise_fbm value, density;
} vx_perturb;

/* vx_perturb_init: the perturbation scene s asks for.  Errors (pt then
 * off): VX_EDATA naming the line's knob out of range (a scene that went
 * through vx_scene_parse has none). */
int vx_perturb_init(vx_perturb *pt, const vx_scene *s, vx_err *e);

/* vx_perturb_none: no perturbation (what a renderer uses without one). */
void vx_perturb_none(vx_perturb *pt);

/* vx_perturb_plan: the plan items of scene s's perturbation: one per
 * target that is on (its noise and knobs), or one saying nothing is
 * perturbed (and why) when none is. */
void vx_perturb_plan(const vx_scene *s, vx_plan *p);

/* vx_perturb_field: the perturbed field F' at index point p of g; with
 * grad non-NULL its world gradient (above); *density (may be NULL) the
 * density factor m (1 without density perturbation).  Without
 * perturbation: vx_grid_trilinear(g, p), and grad[a] =
 * (F(p + e_a) - F(p - e_a)) / (2 spacing[a]) in index steps. */
double vx_perturb_field(const vx_perturb *pt, const vx_grid *g,
    const double p[3], double grad[3], double *density);

/* vx_perturb_optics: the classified sample c with its extinction
 * multiplied by m >= 0 (above); m == 1 leaves c exactly as it is. */
void vx_perturb_optics(vx_tf_sample *c, double m);

/* vx_perturb_classify: the sample at index point p classified by tf:
 * F' (and its gradient magnitude when want_grad; grad gets the gradient
 * then, zeros otherwise) through vx_tf_classify, then vx_perturb_optics
 * with the density factor.  What dvr and its references call per sample. */
void vx_perturb_classify(const vx_perturb *pt, const vx_tf *tf,
    const vx_grid *g, const double p[3], int want_grad, vx_tf_sample *c,
    double grad[3]);

/* vx_perturb_value_margin: how far the value perturbation can move a
 * value: [lo, hi] widens to [lo - *below, hi + *above] (0, 0 when off). */
void vx_perturb_value_margin(const vx_perturb *pt, double *below,
    double *above);

/* vx_perturb_density_max: the largest density factor (1 + A, or 1). */
double vx_perturb_density_max(const vx_perturb *pt);

/* vx_perturb_clear: make clear, a byte per level-1 macrocell of m over g
 * (1: its [min, max] classifies clear by tf), right for the perturbed
 * field: with value perturbation a cell is clear when its range widened
 * by the value margin is; with coordinate perturbation a cell is clear
 * only when every cell a displaced sample in it can read from is (the
 * mask eroded by ceil(A / (spacing width)) macrocells per axis).  Without
 * either, clear is unchanged.  Errors: VX_ENOMEM (clear then unchanged). */
int vx_perturb_clear(const vx_perturb *pt, const vx_tf *tf,
    const vx_grid *g, const vx_macro *m, uint8_t *clear, vx_err *e);

#endif
