/* vx_tetmesh.h: tetrahedral meshes with one scalar per vertex: storage,
 * validation, exact orientation, and the TETM chunk.  Importers and
 * synthetic meshes are in vx_tetimport.h (io); the leaf grid of tet lists
 * and the ray/tet isosurface in vx_tetleaf.h (kernels).
 *
 * Points are stored as double: every importer's coordinates (float or
 * double) are kept exactly, the intersection computes in double anyway, and
 * points are ~1/5 of the tets in a 5-split grid, so they cost ~5 bytes per
 * tet (against 16 for the indices).  Converting double input to float could
 * flatten thin tets, which the watertight test would then have to skip.
 *
 * formats/tetmesh.md specifies the TETM chunk. */
#ifndef VX_TETMESH_H
#define VX_TETMESH_H

#include <stddef.h>
#include <stdint.h>

#include "vx_err.h"
#include "vx_grid.h"
#include "vx_stream.h"

/* Limits, checked before anything is allocated.  Indices are uint32, so
 * points stay below 2^32 - 1; tets below 2^31 keep 4 * ntet in range of the
 * leaf lists' uint32 offsets for typical overlap.  Coordinates must be finite
 * and at most VX_TETMESH_COORD_MAX in magnitude, so that the products of the
 * intersection test neither overflow nor lose their exact-sign fallback. */
#define VX_TETMESH_MAX_POINTS ((uint64_t)UINT32_MAX - 1)
#define VX_TETMESH_MAX_TETS   ((uint64_t)1 << 31)
#define VX_TETMESH_COORD_MAX  1e30
#define VX_TETMESH_NAME       64

typedef struct vx_tetmesh {
	char name[VX_TETMESH_NAME];    /* mesh name, "mesh" by default */
	char scalar[VX_TETMESH_NAME];  /* scalar name, "scalar" by default */
	size_t npoint, ntet;
	double *pts;          /* 3 * npoint: x y z, owned */
	uint32_t *tet;        /* 4 * ntet vertex indices, owned */
	float *val;           /* npoint scalar values, owned */
	double bmin[3], bmax[3]; /* bounding box of all points (valid if npoint) */
	int has_range;
	double vmin, vmax;    /* finite value range over all points */
} vx_tetmesh;

void vx_tetmesh_init(vx_tetmesh *m);
/* vx_tetmesh_free: release the arrays (m may be zeroed or initialized);
 * leaves m initialized. */
void vx_tetmesh_free(vx_tetmesh *m);

/* vx_tetmesh_alloc: initialize m with npoint points and ntet tets, arrays
 * zeroed, names defaulted.  VX_EDATA when a count exceeds the limits above,
 * VX_ENOMEM. */
int vx_tetmesh_alloc(vx_tetmesh *m, size_t npoint, size_t ntet, vx_err *e);

/* vx_tetmesh_set_name / vx_tetmesh_set_scalar: copy a name (truncated to 63
 * bytes; bytes outside printable ASCII and ':' become '_', an empty name
 * becomes the default) so it can travel in a chunk header. */
void vx_tetmesh_set_name(vx_tetmesh *m, const char *name);
void vx_tetmesh_set_scalar(vx_tetmesh *m, const char *name);

/* vx_tetmesh_validate: check indices < npoint and coordinates finite and
 * within VX_TETMESH_COORD_MAX; then compute the bounding box and value
 * range.  Every importer and vx_tetmesh_from_chunk calls it; code that
 * fills a mesh by hand calls it before use.  VX_EDATA naming the first
 * offending tet or point. */
int vx_tetmesh_validate(vx_tetmesh *m, vx_err *e);

/* vx_tetmesh_bbox / vx_tetmesh_range: recompute bmin/bmax, and vmin/vmax
 * over the finite values (has_range 0 when there is none). */
void vx_tetmesh_bbox(vx_tetmesh *m);
void vx_tetmesh_range(vx_tetmesh *m);

/* vx_tetmesh_volume: signed volume of tet t, det(b-a, c-a, d-a) / 6 in
 * double arithmetic (positive for a right-handed vertex order). */
double vx_tetmesh_volume(const vx_tetmesh *m, size_t t);

/* vx_orient3d: the exact sign (-1, 0, 1) of det(b - a, c - a, d - a): a
 * filtered double evaluation (Shewchuk's first-stage bound), exact
 * expansion arithmetic when the filter cannot decide. */
int vx_orient3d(const double *a, const double *b, const double *c,
    const double *d);

/* vx_tetmesh_degenerate: 1 if the four vertices of tet t are exactly
 * coplanar (vx_orient3d is 0), else 0. */
int vx_tetmesh_degenerate(const vx_tetmesh *m, size_t t);

/* ---- the TETM chunk (formats/tetmesh.md) ----
 * Header: name, points, tets, scalar, range, encoding.  Body (LE): points
 * f64 x 3 x npoint, tets u32 x 4 x ntet, scalars f32 x npoint.
 * vx_tetmesh_from_chunk bounds the counts by the body's bytes (raw: exact;
 * zlib: at most 1032 times the compressed size, zlib's largest ratio) before
 * allocating, then validates (vx_tetmesh_validate). */
int vx_tetmesh_to_chunk(const vx_tetmesh *m, int zlevel, vx_chunk *c,
    vx_err *e);
int vx_tetmesh_from_chunk(vx_tetmesh *m, const vx_chunk *c, vx_err *e);
/* vx_tetmesh_from_stream: the first TETM chunk (or the one whose name
 * matches when name is non-NULL); *index (may be NULL) gets its position. */
int vx_tetmesh_from_stream(vx_tetmesh *m, const vx_stream *s,
    const char *name, long *index, vx_err *e);

#endif
