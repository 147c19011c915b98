/* vx_tf.h: transfer functions for direct volume rendering (Kniss et al.
 * 2003; formats/transfer.md is the spec).
 *
 * A transfer function maps a sample's data value v (and, for 2D functions,
 * its gradient magnitude g) to optical properties:
 *   color      RGB albedo in [0,1]               (the paper's colour)
 *   opacity    alpha in [0,1] per reference step (see below)
 *   transport  RGB in [0,1]: the paper's "transport colour", the
 *              complement of the indirect alpha: the fraction of each
 *              channel of forward-scattered light that goes on through
 *              one reference step (so light in the material takes on this
 *              colour); absent: 1 - alpha in every channel (grey, the
 *              direct light's attenuation)
 *   surface    weight in [0,1] of the surface (Blinn-Phong on the
 *              gradient) term, over the value; absent: 0 (pure volume
 *              shading), or 1 when a surface ramp is given
 *   surface ramp  G0 < G1: the surface weight is multiplied by the
 *              gradient magnitude's ramp, 0 at and below G0 rising
 *              linearly to 1 at G1 and above (the paper's surface term
 *              "by gradient magnitude")
 *   gradient   opacity factor in [0,1] as a function of g alone (3D
 *              Slicer's gradient opacity); absent: 1
 * and, with no color list and no table, the colour is white (1, 1, 1).
 * Each of these is a piecewise-linear list of control points over its
 * variable (vx_tf_list), clamped to its end points outside them.  A list's
 * abscissae are non-decreasing; two equal abscissae make a step (the left
 * limit is the first point's value, the value at and right of it the
 * second's).
 *
 * Besides the lists, a function may hold a 2D table over value x gradient
 * magnitude of RGBA (teem miter's txf): then color and opacity come from
 * the table (bilinear between cell centres, clamped at the edges) and the
 * color and opacity lists must be absent.
 *
 * Opacity is given for a reference step ref_step (world units; 0 means one
 * voxel along the smallest spacing, resolved by the renderer).  A renderer
 * sampling at step d uses alpha' = 1 - (1 - alpha)^(d / ref_step), so the
 * picture's overall transparency does not depend on the step. */
#ifndef VX_TF_H
#define VX_TF_H

#include <stdint.h>
#include <string.h>

#include "vx_enum.h"

#include "vx_err.h"

#define VX_TF_MAX_POINTS  65536        /* per list */
#define VX_TF_MAX_TABLE   4096         /* cells per table axis */

/* The formats of transfer-function files (io/vx_tfimport.h reads them; a
 * scene names one in its transfer file line). */
typedef enum vx_tf_format {
	VX_TF_FORMAT_UNKNOWN = 0,
	VX_TF_FORMAT_AUTO,        /* by content: "NRRD" magic: miter; JSON
	                             with "volumeProperties": slicer, other
	                             JSON: paraview; text whose first byte
	                             is a digit: slicer (.vp) */
	VX_TF_FORMAT_PARAVIEW,
	VX_TF_FORMAT_SLICER,      /* .vp or .vp.json */
	VX_TF_FORMAT_MITER,
	VX_TF_FORMAT_LAST
} vx_tf_format;

extern const vx_enum vx_tf_format_enum;   /* auto paraview slicer miter */

typedef struct vx_tf_list {
	int n;                    /* points; 0: the list is absent */
	int dim;                  /* values per point: 1 or 3 */
	double *x;                /* n abscissae, finite, non-decreasing */
	double *y;                /* n * dim values, each in [0,1] */
} vx_tf_list;

typedef struct vx_tf {
	vx_tf_list color;         /* value -> RGB, dim 3 */
	vx_tf_list opacity;       /* value -> alpha, dim 1 */
	vx_tf_list transport;     /* value -> RGB, dim 3 */
	vx_tf_list surface;       /* value -> weight, dim 1 */
	vx_tf_list gradient;      /* gradient magnitude -> factor, dim 1 */
	/* 2D table (miter txf): size[0] cells along the value, size[1] along
	 * the gradient magnitude; cell (i, j)'s centre lies at value
	 * vrange[0] + (i + 0.5) (vrange[1] - vrange[0]) / size[0], likewise
	 * for g over grange; rgba[4 (i + size[0] j) + c], each in [0,1]. */
	int has_table;
	int size[2];
	double vrange[2], grange[2];
	float *rgba;
	double ref_step;          /* world units, >= 0; 0: one voxel */
	int has_surface_ramp;     /* 1: surface_ramp applies */
	double surface_ramp[2];   /* G0, G1: 0 <= G0 < G1, finite */
} vx_tf;

/* vx_tf_init: an empty transfer function (every list absent, no table,
 * ref_step 0).  Owns nothing until a setter succeeds. */
void vx_tf_init(vx_tf *tf);
/* vx_tf_free: release what tf owns and leave it empty. */
void vx_tf_free(vx_tf *tf);

/* vx_tf_list_set: make l a copy of n points (n in [1, VX_TF_MAX_POINTS])
 * of dim values each (1 or 3): x[0..n-1], y[0..n*dim-1].  Errors, l
 * unchanged: VX_EDATA (n out of range, an abscissa not finite or smaller
 * than the one before it, a value outside [0,1] or NaN; the message names
 * the point), VX_ENOMEM. */
int vx_tf_list_set(vx_tf_list *l, int n, int dim, const double *x,
    const double *y, vx_err *e);
/* vx_tf_list_free: release l and leave it absent. */
void vx_tf_list_free(vx_tf_list *l);

/* vx_tf_list_eval: l at t into out[0..l->dim-1]: clamped to the end
 * points outside [x[0], x[n-1]], linear between neighbours, the step rule
 * at equal abscissae.  t NaN gives the first point's value.  l must be
 * present (n >= 1). */
void vx_tf_list_eval(const vx_tf_list *l, double t, double *out);

/* vx_tf_table_set: give tf the 2D RGBA table described above (copied).
 * Errors, tf unchanged: VX_EDATA (a size outside [1, VX_TF_MAX_TABLE], a
 * range not finite or empty (lo >= hi), a value outside [0,1] or NaN),
 * VX_ENOMEM. */
int vx_tf_table_set(vx_tf *tf, const int size[2], const double vrange[2],
    const double grange[2], const float *rgba, vx_err *e);

/* vx_tf_check: VX_EDATA when tf is not usable by a renderer: no opacity
 * (neither the list nor a table), a table beside a color or opacity list,
 * a list of the wrong dim, a negative or non-finite ref_step. */
int vx_tf_check(const vx_tf *tf, vx_err *e);

/* ---- classification (what a renderer calls per sample) ---- */

/* A classified sample, for the reference step. */
typedef struct vx_tf_sample {
	double color[3];          /* albedo */
	double alpha;             /* opacity (gradient factor applied) */
	double transport[3];      /* transport colour */
	double surface;           /* surface-shading weight */
} vx_tf_sample;

/* vx_tf_classify: the optical properties at value v and gradient
 * magnitude g (ignored unless tf has a table or a gradient list) of a
 * function that passed vx_tf_check: color from the color list (white when
 * absent) or the table; alpha from the opacity list or the table, times
 * the gradient list's factor at g; transport from its list, else 1 - alpha
 * per channel; surface from its list (else 1 with a surface ramp, 0
 * without) times vx_tf_surface_ramp(tf, g).  v NaN: an empty sample
 * (color 0, alpha 0, transport 1, surface 0). */
void vx_tf_classify(const vx_tf *tf, double v, double g, vx_tf_sample *o);

/* vx_tf_surface_ramp: the surface ramp's factor at gradient magnitude g:
 * 0 for g <= G0 (and g NaN), (g - G0) / (G1 - G0) between, 1 for
 * g >= G1; 1 when tf has no ramp. */
double vx_tf_surface_ramp(const vx_tf *tf, double g);

/* vx_tf_has_surface: 1 when samples may have a surface weight > 0 (a
 * surface list or a surface ramp): the renderer's surface term is on. */
int vx_tf_has_surface(const vx_tf *tf);

/* vx_tf_class_gradient: 1 when vx_tf_classify looks at g: a table, a
 * gradient list or a surface ramp. */
int vx_tf_class_gradient(const vx_tf *tf);

/* vx_tf_needs_gradient: 1 when vx_tf_classify looks at g or the renderer
 * needs the gradient for the surface term: vx_tf_class_gradient or
 * vx_tf_has_surface. */
int vx_tf_needs_gradient(const vx_tf *tf);

/* vx_tf_range_clear: 1 when every value in [lo, hi] (any g) classifies to
 * alpha 0 and transport (1, 1, 1): a sample there changes neither the eye
 * nor the light, so a renderer may skip it.  Exact for the lists (the
 * maximum of a piecewise-linear function over an interval is at an end or
 * a control point inside); for a table, conservative (every alpha in the
 * columns the interval's bilinear lookups can touch).  lo > hi (an empty
 * range, as a macrocell with no finite sample has) gives 1; a NaN bound
 * gives 0. */
int vx_tf_range_clear(const vx_tf *tf, double lo, double hi);

/* vx_tf_correct: alpha for a step of ratio r = d / ref_step (r >= 0):
 * 1 - (1 - alpha)^r; alpha 0 gives exactly 0, alpha 1 exactly 1. */
double vx_tf_correct(double alpha, double r);

/* ---- the optical form and the classification table ---- */

/* A classified sample in the form a renderer corrects by exponentials:
 * sigma = -ln(1 - alpha) and ltr[c] = ln(transport[c]), per reference
 * step, each capped at VX_TF_SIGMA_MAX (alpha 1 and transport 0 become
 * the cap: e^-cap is below the smallest double), so that a step of ratio
 * r has alpha 1 - e^(-sigma r) and transport e^(ltr r). */
#define VX_TF_SIGMA_MAX 800.0

typedef struct vx_tf_optic {
	double sigma;             /* >= 0 */
	double color[3];
	double ltr[3];            /* <= 0 */
	double surface;
} vx_tf_optic;

/* vx_tf_optic_of: c in the optical form (exact). */
void vx_tf_optic_of(const vx_tf_sample *c, vx_tf_optic *o);

/* A 1D classification table: the optical form of a transfer function
 * without a gradient dependence (no table, gradient list or surface
 * ramp) at n + 1 evenly spaced values over [lo, hi], linear between them;
 * values outside take the end nodes' (a renderer builds it over its
 * volume's range, where every interpolated value lies, widened by a value
 * perturbation's reach).  Between two nodes the error against
 * vx_tf_classify is that of linear interpolation over one spacing
 * (hi - lo) / n, in sigma rather than alpha: none where the lists are
 * linear in sigma or constant across the spacing, second order in the
 * spacing elsewhere, first order in a spacing that holds a control point. */
#define VX_TF_MAX_LUT (1 << 20)

typedef struct vx_tf_lut {
	int n;                    /* intervals; 0: absent */
	double lo, scale;         /* node i at value lo + i / scale */
	float *node;              /* (n + 1) x 8: sigma, color, ltr, surface */
} vx_tf_lut;

/* vx_tf_lut_build: t for tf over [lo, hi] with n intervals, n in [1,
 * VX_TF_MAX_LUT] (lo == hi: one node repeated).  Errors, t absent:
 * VX_EDATA (tf depends on the gradient: vx_tf_class_gradient; a bound
 * not finite, lo > hi, n out of range), VX_ENOMEM. */
int vx_tf_lut_build(vx_tf_lut *t, const vx_tf *tf, double lo, double hi,
    int n, vx_err *e);
void vx_tf_lut_free(vx_tf_lut *t);

/* Four floats, for the table's inner loop (GCC and clang vector
 * extension; plain element-wise arithmetic). */
typedef float vx_f4 __attribute__((vector_size(16)));

/* vx_tf_lut_at: the table at value v as two quads: q[0] = sigma, color
 * r, g, b; q[1] = ltr r, g, b, surface (NaN: the empty sample, all 0). */
static inline void
vx_tf_lut_at(const vx_tf_lut *t, double v, vx_f4 q[2])
{
	double x = (v - t->lo) * t->scale;
	vx_f4 a0, a1, b0, b1, f;
	const float *a;
	int i;

	if (!(x == x)) {
		q[0] = q[1] = (vx_f4){ 0, 0, 0, 0 };
		return;
	}
	if (x <= 0) {
		i = 0;
		x = 0;
	} else if (x >= t->n) {
		i = t->n - 1;
		x = t->n;
	} else
		i = (int)x;
	a = t->node + 8 * (size_t)i;
	memcpy(&a0, a, sizeof a0);
	memcpy(&a1, a + 4, sizeof a1);
	memcpy(&b0, a + 8, sizeof b0);
	memcpy(&b1, a + 12, sizeof b1);
	f = (vx_f4){ 1, 1, 1, 1 } * (float)(x - i);
	q[0] = a0 + f * (b0 - a0);
	q[1] = a1 + f * (b1 - a1);
}

/* vx_tf_apply_scene: the scene's transfer lines over tf (which may hold
 * an imported file's function): each list the scene gives replaces tf's
 * list of that channel (a color or opacity list drops a 2D table: the
 * table is colour and opacity together), "transfer surface gradient" sets
 * the surface ramp and "transfer step" replaces ref_step.  The scene's file is not read here (vx_tfimport.h, from a
 * tool).  Errors, tf then partly changed: VX_EDATA, VX_ENOMEM. */
struct vx_scene;
int vx_tf_apply_scene(vx_tf *tf, const struct vx_scene *s, vx_err *e);

#endif
