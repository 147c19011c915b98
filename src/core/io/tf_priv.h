/* tf_priv.h: internals of the transfer-function imports (not installed):
 * a growing list of control points, VTK's midpoint/sharpness segments
 * made piecewise linear, and the readers of each format. */
#ifndef VX_TF_PRIV_H
#define VX_TF_PRIV_H

#include <stddef.h>

#include "vx_json.h"
#include "vx_tf.h"

#define VX_TFI_JSON_DEPTH 32           /* nested arrays and objects */
#define VX_TFI_JSON_NODES (1 << 21)    /* JSON values in a file */
/* the most a sharpness segment's linear approximation may differ from
 * VTK's curve at the points it checks (formats/transfer.md, Imports) */
#define VX_TFI_SHARP_TOL 1e-3

/* A list being built: n points of dim values (1 or 3), at most
 * VX_TF_MAX_POINTS. */
typedef struct vx_tfi_pts {
	int n, cap, dim;
	double *x, *y;
} vx_tfi_pts;

void vx_tfi_pts_init(vx_tfi_pts *p, int dim);
void vx_tfi_pts_free(vx_tfi_pts *p);
/* vx_tfi_pts_add: append a point (x, y[0..dim-1]); VX_EDATA past
 * VX_TF_MAX_POINTS ("more than N control points"), VX_ENOMEM. */
int vx_tfi_pts_add(vx_tfi_pts *p, double x, const double *y, vx_err *e);

/* A curve over one segment: fn(ctx, s, out) gives the dim values at the
 * fraction s in [0,1] of the way along it. */
typedef void (*vx_tfi_fn)(const void *ctx, double s, double *out);

/* vx_tfi_curve: append to p the points strictly inside the segment
 * [x0, x1] that make the piecewise-linear form within VX_TFI_SHARP_TOL
 * of fn at the quarter points of each piece (pieces halved at most 16
 * times); the segment's ends are the caller's to add. */
int vx_tfi_curve(vx_tfi_pts *p, double x0, double x1, vx_tfi_fn fn,
    const void *ctx, vx_err *e);

/* vx_tfi_vtk: append to p the piecewise-linear form of VTK's function
 * through n nodes (x[i], y[i*dim..]) whose segment from node i to i + 1
 * has midpoint mid[i] and sharpness sharp[i] (mid and sharp may be NULL:
 * 0.5 and 0 everywhere).  The nodes are checked by the caller (x finite,
 * non-decreasing; y, mid, sharp in [0,1]).  Exact for sharpness 0 (a
 * point inserted at the midpoint) and for sharpness 1 (a step there);
 * otherwise points are inserted until the linear form is within
 * VX_TFI_SHARP_TOL of VTK's curve at each piece's quarter points. */
int vx_tfi_vtk(vx_tfi_pts *p, int n, int dim, const double *x,
    const double *y, const double *mid, const double *sharp, vx_err *e);
/* vx_tfi_vtk_eval: VTK's function on one segment at s in [0,1] (the
 * fraction of the way from its left node), channel values y0 -> y1. */
double vx_tfi_vtk_eval(double y0, double y1, double mid, double sharp,
    double s);

/* vx_tfi_set: l = the points of p (vx_tf_list_set). */
int vx_tfi_set(vx_tf_list *l, const vx_tfi_pts *p, vx_err *e);

/* vx_tfi_at: VX_EDATA with "line N: " (the node's) before the message. */
int vx_tfi_at(vx_err *e, const vx_json_node *at, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* vx_tfi_unit: v is a number in [0,1] (else VX_EDATA, what names it). */
int vx_tfi_unit(double v, const char *what, vx_err *e);

/* The readers: tf initialized (empty) by the caller; messages without
 * the file name (the caller prefixes it). */
int vx_tfi_paraview(const vx_json *j, vx_tf *tf, vx_err *e);
int vx_tfi_slicer_json(const vx_json *j, vx_tf *tf, vx_err *e);
int vx_tfi_slicer_vp(const char *buf, size_t n, vx_tf *tf, vx_err *e);
/* dir: where a detached data file is looked for (NULL: refused) */
int vx_tfi_miter(const unsigned char *buf, size_t n, const char *dir,
    vx_tf *tf, vx_err *e);

#endif
