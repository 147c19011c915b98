/* vx_tf.h: transfer functions for direct volume rendering (Kniss et al.
 * 2003; formats/transfer.md is the spec).
 *
 * A transfer function maps a sample's data value v (and, for 2D functions,
 * its gradient magnitude g) to optical properties:
 *   color      RGB albedo in [0,1]               (the paper's colour)
 *   opacity    alpha in [0,1] per reference step (see below)
 *   transport  RGB in [0,1]: the indirect attenuation colour (the paper's
 *              "transport colour": what fraction of each channel forward-
 *              scattered light loses per reference step); absent: equal to
 *              the opacity in every channel (grey attenuation)
 *   surface    weight in [0,1] of the surface (Blinn-Phong on the
 *              gradient) term; absent: 0 (pure volume shading)
 *   gradient   opacity factor in [0,1] as a function of g alone (3D
 *              Slicer's gradient opacity); absent: 1
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

#include "vx_err.h"

#define VX_TF_MAX_POINTS  65536        /* per list */
#define VX_TF_MAX_TABLE   4096         /* cells per table axis */

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

#endif
