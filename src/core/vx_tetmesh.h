/* vx_tetmesh.h: tetrahedral meshes with one scalar per vertex: storage, the
 * TETM chunk, importers (VTK legacy, gmsh), synthetic meshes, the leaf grid
 * of tet lists (Parker et al. 1999, §4.2) and the watertight ray/tet
 * isosurface intersection (Appendix B, made crack-free).
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
#include "vx_import.h"
#include "vx_macro.h"
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

/* ---- import ----
 * Formats: VTK legacy UNSTRUCTURED_GRID (ASCII or BINARY, versions up to
 * 5.1 with OFFSETS/CONNECTIVITY) and gmsh .msh 2.x and 4.1 ASCII.  The
 * scalar is a one-component point array (VTK SCALARS or FIELD array in
 * POINT_DATA; gmsh $NodeData): the one named opt->scalar, else the first.
 * Cell policy, both formats: tetrahedra (VTK 10, gmsh 4) are kept; cells of
 * lower dimension (vertices, lines, triangles, quads, ...) are skipped and
 * counted; other volume cells (hexahedra, wedges, pyramids, quadratic
 * tets, ...) are an error naming the type, since dropping them would punch
 * holes in the volume, unless opt->skip_volume_cells (then counted). */
enum {
	VX_TETFMT_UNKNOWN = 0,
	VX_TETFMT_VTK_ASCII,
	VX_TETFMT_VTK_BINARY,
	VX_TETFMT_GMSH2,
	VX_TETFMT_GMSH4,
	VX_TETFMT_LAST
};

typedef struct vx_tetimport_opt {
	const char *scalar;      /* point array to use; NULL: the first */
	int skip_volume_cells;   /* 1: skip non-tet volume cells, counted */
} vx_tetimport_opt;

typedef struct vx_tetimport_info {
	int format;              /* VX_TETFMT_* */
	size_t ncell;            /* cells or elements in the file */
	size_t nskip_lower;      /* skipped: lower-dimensional cells */
	size_t nskip_volume;     /* skipped: non-tet volume cells (opt) */
	size_t narray;           /* candidate point arrays seen */
} vx_tetimport_info;

/* Limit on the decompressed size of a file read by vx_tetmesh_import. */
#define VX_TETMESH_FILE_MAX ((size_t)1 << 34)

/* vx_tetmesh_import_vtk / _gmsh: parse n bytes at buf (need not be
 * NUL-terminated) into m (initialized by the call, empty on error).  opt and
 * info may be NULL.  VX_EDATA for malformed or unsupported input, with
 * "vtk: ..." / "gmsh: ..." messages and a line number where one helps. */
int vx_tetmesh_import_vtk(vx_tetmesh *m, const void *buf, size_t n,
    const vx_tetimport_opt *opt, vx_tetimport_info *info, vx_err *e);
int vx_tetmesh_import_gmsh(vx_tetmesh *m, const void *buf, size_t n,
    const vx_tetimport_opt *opt, vx_tetimport_info *info, vx_err *e);
/* vx_tetmesh_import_mem: detect the format from the content ("# vtk
 * DataFile" or "$MeshFormat", after optional leading blank space). */
int vx_tetmesh_import_mem(vx_tetmesh *m, const void *buf, size_t n,
    const vx_tetimport_opt *opt, vx_tetimport_info *info, vx_err *e);
/* vx_tetmesh_import: read path (gzip-compressed or plain, decompressed
 * transparently; at most VX_TETMESH_FILE_MAX bytes), detect the format and
 * import; the mesh is named after the file (directory and extensions
 * stripped).  VX_ENOINPUT when the file cannot be opened, VX_EIO on read
 * errors. */
int vx_tetmesh_import(vx_tetmesh *m, const char *path,
    const vx_tetimport_opt *opt, vx_tetimport_info *info, vx_err *e);

/* ---- synthetic meshes (tests, demos) ---- */

/* Scalar function for synthetic meshes: value at world point p. */
typedef double (*vx_tetsynth_fn)(const double p[3], void *ctx);

enum { VX_TETSPLIT_5 = 5, VX_TETSPLIT_6 = 6 };

/* vx_tetsynth_grid: a rectilinear grid of nc[0] x nc[1] x nc[2] cells
 * spanning [lo, hi], vertex (i,j,k) at lo + (i,j,k) * (hi-lo)/nc, index
 * i + (nc0+1) * (j + (nc1+1) * k).  Each cell is split into 5 tets (split 5:
 * alternating with the parity of i+j+k, as in /work/shared/data's CFD
 * meshes) or 6 Kuhn tets (split 6: all sharing the cell diagonal from
 * (i,j,k) to (i+1,j+1,k+1)); both are face-conforming.  Tets are written
 * cell by cell, i fastest, with positive volume.  Values: fn(p, ctx). */
int vx_tetsynth_grid(vx_tetmesh *m, const int64_t nc[3], const double lo[3],
    const double hi[3], int split, vx_tetsynth_fn fn, void *ctx, vx_err *e);

/* vx_tetsynth_cube: the unit cell [lo, hi] as the 6 Kuhn tets (same as
 * vx_tetsynth_grid with nc = 1 1 1, split 6). */
int vx_tetsynth_cube(vx_tetmesh *m, const double lo[3], const double hi[3],
    vx_tetsynth_fn fn, void *ctx, vx_err *e);

/* vx_tetsynth_from_grid: the tet split of a volume: vertex (i,j,k) at the
 * sample's world position origin + (i,j,k) * spacing, value the sample's,
 * cells (dims - 1 per axis, each >= 1) split as in vx_tetsynth_grid.  The
 * mesh's scalar gets g's name. */
int vx_tetsynth_from_grid(vx_tetmesh *m, const vx_grid *g, int split,
    vx_err *e);

/* ---- the leaf grid (Parker §4.2) and its min/max hierarchy ----
 * A rectilinear grid over the mesh's bounding box (grown by VX_TETLEAF_PAD
 * leaf widths on every side) with about `density` leaves per tet (1 in the
 * paper).  Leaf (i,j,k), index i + n0 * (j + n1 * k), covers the box from
 * bmin + (i,j,k) * cell to bmin + (i+1,j+1,k+1) * cell.  Its tets are
 * idx[off[l] .. off[l+1]-1] (ascending): every tet that overlaps the leaf's
 * box padded by VX_TETLEAF_PAD leaf widths, by an exact separating-axis
 * test (the default) or by the tet's bounding box (VX_TETLEAF_BBOX).  On
 * the CFD meshes of /work/shared/data the exact lists are 1.6 to 2.1 times
 * shorter (9 to 12 entries per tet instead of 15 to 22) and nearest-hit
 * queries 1.6 times faster, for a build 2.3 to 3 times slower
 * (formats/tetmesh.md has the numbers).  Tets that can never hit (a
 * non-finite vertex value, zero volume) are not listed.  The padding makes a hit at a leaf boundary safe against the rounding of
 * the traversal's t values.  The leaf ranges (min/max of the vertex values
 * of the listed tets; empty leaf: +inf, -inf) are level 0 of a vx_macro
 * hierarchy with explicit leaves (vx_macro.h), whose leaf index space is
 * (world - bmin) / cell. */
#define VX_TETLEAF_PAD 1e-6
#define VX_TETLEAF_MAX_LEAVES ((uint64_t)1 << 31)
#define VX_TETLEAF_BBOX 1      /* flag: list by bounding box only */

typedef struct vx_tetleaf {
	int64_t dims[3];       /* leaves per axis */
	double bmin[3];        /* mesh bmin - VX_TETLEAF_PAD * cell */
	double cell[3];        /* leaf size per axis (> 0) */
	size_t nleaf;          /* product of dims */
	uint32_t *off;         /* nleaf + 1 offsets into idx, owned */
	uint32_t *idx;         /* tet indices, off[nleaf] of them, owned */
	vx_macro mc;           /* min/max hierarchy; leaf l's range is
	                          mc.mm[0][2l], mc.mm[0][2l+1] */
} vx_tetleaf;

void vx_tetleaf_init(vx_tetleaf *lg);
void vx_tetleaf_free(vx_tetleaf *lg);

/* vx_tetleaf_dims: the leaf counts the builder picks for a box of extent
 * ext holding ntet tets at `density` leaves per tet: cubical leaves as far as
 * the box allows, each axis in 1 .. 2^20, the product near ntet * density. */
void vx_tetleaf_dims(const double ext[3], size_t ntet, double density,
    int64_t dims[3]);

/* vx_tetleaf_build: build the leaf grid of a validated mesh (density <= 0
 * means 1) with exact overlap, and over it the default hierarchy
 * (VX_MACRO_DEFAULT_LEVELS levels of vx_macro_default_sizes(VX_F32, ...)),
 * on all threads.  The result is the same for any thread count.  The mesh
 * is not referenced afterwards.  Besides the result, the build holds 12
 * bytes per tet and 4 per bounding-box overlap for a while.  VX_EDATA when
 * the lists would exceed 2^32 - 1 entries, VX_ENOMEM. */
int vx_tetleaf_build(vx_tetleaf *lg, const vx_tetmesh *m, double density,
    vx_err *e);
/* vx_tetleaf_build_levels: the same with flags (0 or VX_TETLEAF_BBOX), nlev
 * (0..VX_MACRO_MAXLEV) levels of the given sizes (see
 * vx_macro_build_explicit) and nthreads (<= 0: OpenMP's default). */
int vx_tetleaf_build_levels(vx_tetleaf *lg, const vx_tetmesh *m,
    double density, int flags, int nlev, const int sizes[][3], int nthreads,
    vx_err *e);

/* vx_tetleaf_bytes: memory held by the leaf grid and its hierarchy. */
size_t vx_tetleaf_bytes(const vx_tetleaf *lg);

/* vx_tetleaf_range: stored min/max of leaf l. */
static inline void
vx_tetleaf_range(const vx_tetleaf *lg, size_t l, float *lo, float *hi)
{
	*lo = lg->mc.mm[0][2 * l];
	*hi = lg->mc.mm[0][2 * l + 1];
}

/* ---- ray vs tet isosurface ----
 * Within a tet the field is linear, so along a ray it is linear between the
 * ray's entry and exit points.  Entry and exit faces are found by a
 * watertight ray/triangle test in the spirit of Woop, Benthin and Wald
 * (2013): vertices are sheared into ray space (the ray becomes the +z axis
 * through the origin), each edge gets a 2D edge function whose sign is
 * exact (the rounded value's sign, with an exact fallback when it rounds to
 * zero) and whose zeros are resolved by a fixed symbolic perturbation of the
 * ray; every quantity of a face is computed from its three vertices taken in
 * a canonical order (by position, then index).  So a face shared by two
 * tets gives both the same decision, t and value, bit for bit (also across
 * an unmerged seam, where the two faces have equal positions and values
 * but different vertex indices), and a ray through a shared face, edge or
 * vertex of a conforming mesh crosses a chain of tets with no gap and no
 * overlap: every change of sign of (f - iso) along it is reported by exactly
 * one tet.  "Inside" is f >= iso (sign(0) = +): an isovalue equal to a
 * vertex value puts that vertex inside, so where the field only touches iso
 * (a vertex at a local maximum equal to iso, say) a ray through that point
 * reports nothing or an even number of hits at that t (up to rounding),
 * never one; the parity of the crossings along a ray is always right.
 * Tets with exactly coplanar vertices (zero volume) and tets with a
 * non-finite vertex value never hit.  A zero-volume tet still links its
 * neighbours' faces in the chain; where its faces carry different values
 * (coincident points with different values: a jump of the field), a
 * crossing inside that jump is not reported. */

typedef struct vx_tetray {
	double o[3], d[3];     /* origin, direction (not necessarily unit) */
	int kx, ky, kz;        /* kz: axis of largest |d|; kx, ky the others */
	double sx, sy, sz;     /* shear: x' = a[kx] - sx a[kz], z' = sz a[kz] */
} vx_tetray;

/* vx_tetray_init: set up the ray-space transform for o + t d (d nonzero,
 * finite). */
void vx_tetray_init(vx_tetray *r, const double o[3], const double d[3]);

/* vx_tet_segment: where ray r crosses tet t: 1 with the depths t0, t1 and
 * field values f0, f1 where the ray enters and leaves it (computed from the
 * crossed faces alone), or 0 when the ray misses the tet (or only grazes
 * it: faces seen edge-on are never crossed).  Entry and exit are told apart
 * by orientation, not by depth, so they are right for a zero-length
 * crossing too (a ray through an edge or vertex); t0 <= t1 but for rounding
 * in slivers.  At an edge or vertex the ray meets exactly, depth and value
 * come from that edge or vertex alone.  f0, f1 lie within the values of
 * their faces' vertices.  For a flat tet (no orientation) the ends are
 * ordered by depth; such tets never hit (vx_tet_nearest). */
int vx_tet_segment(const vx_tetmesh *m, size_t t, const vx_tetray *r,
    double *t0, double *f0, double *t1, double *f1);

/* vx_tet_normal: unit gradient of the linear field of tet t (points
 * towards larger values).  When the gradient is zero or not finite, gives
 * the unit vector along sgn * d (sgn = +1 when the field grows along the
 * ray).  Returns 1 when the gradient was used, 0 for the fallback. */
int vx_tet_normal(const vx_tetmesh *m, size_t t, const vx_tetray *r,
    int sgn, double n[3]);

/* vx_tet_intersect: the isosurface crossing of ray o + t d in tet `tet`:
 * 1 with *t in [tmin, tmax) and the unit normal n (the field's gradient
 * direction; n may be NULL), or 0.  The crossing is at the linear
 * interpolation of the entry and exit values, clamped into the tet's
 * [t0, t1].  Convenience form; vx_tet_nearest is the one for many tets. */
int vx_tet_intersect(const vx_tetmesh *m, uint32_t tet, const double o[3],
    const double d[3], double iso, double tmin, double tmax, double *t,
    double n[3]);

typedef struct vx_tethit {
	double t;              /* ray parameter of the hit */
	double n[3];           /* unit normal (gradient direction) */
	uint32_t tet;          /* tet that reported it */
	int iso;               /* index of the isovalue crossed */
	int enter;             /* 1: f goes from < iso to >= iso along the ray */
} vx_tethit;

/* vx_tet_nearest: the nearest crossing in [tmin, tmax) of ray r with the
 * isosurfaces iso[0..niso-1] among the n tets list[0..n-1] (e.g. one leaf's
 * list: lg->idx + lg->off[l], lg->off[l+1] - lg->off[l]).  Ties in t go to
 * the smaller tet index, then the smaller isovalue index, so the result does
 * not depend on the list's order.  Returns 1 and fills *hit, or 0.  A
 * traversal calls it per leaf with the leaf's [t_enter, t_exit) and stops at
 * the first leaf that hits. */
int vx_tet_nearest(const vx_tetmesh *m, const uint32_t *list, size_t n,
    const vx_tetray *r, const double *iso, int niso, double tmin,
    double tmax, vx_tethit *hit);

/* vx_tetleaf_nearest: the nearest crossing in [tmin, tmax) of the ray
 * o + t d (world space) with the isosurfaces iso[0..niso-1] of mesh m, found
 * by walking lg's hierarchy (vx_macro_traverse; leaves whose range brackets
 * no isovalue are skipped) and testing each visited leaf's tets over the
 * leaf's own [t0, t1) (closed at the grid's far side), stopping at the first
 * leaf that hits.  The result (t, tet, iso, normal) is the one
 * vx_tet_nearest gives over all tets of the mesh.  lg must have been built
 * from m.  st (may be NULL) gets the traversal's counters added.  Returns 1
 * and fills *hit, or 0.  Reentrant.  Up to 64 isovalues are culled by the
 * hierarchy; with more, every leaf on the way is tested. */
int vx_tetleaf_nearest(const vx_tetleaf *lg, const vx_tetmesh *m,
    const double o[3], const double d[3], const double *iso, int niso,
    double tmin, double tmax, vx_tethit *hit, vx_trav_stats *st);

/* ---- every crossing along a ray (tettrace.c) ---- */

typedef struct vx_tettrace_stats {
	uint64_t rays;           /* traces started */
	uint64_t leaves;         /* leaf searches (leaves whose lists were
	                            scanned, the end extensions included) */
	uint64_t entries;        /* list entries scanned */
	uint64_t tets;           /* tets whose segment was computed (their
	                            values bracket an isovalue) */
	uint64_t hits;           /* crossings handed to the callback */
	uint64_t cyc_isect;      /* ticks inside the tet tests (timing only) */
	int timing;              /* 1: count cyc_isect (a clock read per leaf) */
	vx_trav_stats trav;      /* the hierarchy walk */
} vx_tettrace_stats;

/* vx_tethit_fn: called for each crossing in order; return nonzero to stop
 * the trace (which then returns that value). */
typedef int (*vx_tethit_fn)(void *ctx, const vx_tethit *h);

/* vx_tetleaf_trace: every crossing in [tmin, tmax) of the ray o + t d
 * (world space) with the isosurfaces iso[0..niso-1] of mesh m, each exactly
 * once, in increasing order of (t, tet, iso), handed to fn with its normal
 * (vx_tet_normal, towards larger values) and entering flag.  A crossing is
 * a (tet, isovalue) pair whose segment (vx_tet_segment) changes side of
 * the isovalue at t, t computed exactly as vx_tet_nearest does, so the
 * first one handed over is vx_tetleaf_nearest's hit.  Each visited leaf
 * reports the crossings of its tets whose t lies in the leaf's own
 * [t0, t1) of the walk (the first leaf from tmin, the last one again up to
 * tmax, as vx_tetleaf_nearest does); these intervals tile [tmin, tmax), so
 * a crossing listed by many leaves is reported by one.  A transparent
 * layer or a shadow ray sees every crossing once: the count along a ray
 * through a closed isosurface of a conforming mesh is even (see the
 * watertightness contract above, and its limit for an isovalue equal to a
 * vertex value).  Returns 0 when the ray ended, fn's nonzero value when
 * it stopped.  lg must have been built from (or matched to) m.  st may be
 * NULL.  Reentrant; no allocation. */
int vx_tetleaf_trace(const vx_tetleaf *lg, const vx_tetmesh *m,
    const double o[3], const double d[3], const double *iso, int niso,
    double tmin, double tmax, vx_tethit_fn fn, void *ctx,
    vx_tettrace_stats *st);

/* ---- the leaf grid in the stream: the TLEF chunk (tetleafio.c) ----
 * formats/tetmesh.md, "TLEF": the leaf grid's geometry, its tet lists and
 * its min/max levels (level 0 = the leaves, then levels 1..nlev as in an
 * MCEL body), tied to its mesh by name, counts and vx_tetmesh_crc. */

/* vx_tetmesh_crc: CRC-32 (zlib's) of the mesh's TETM body in raw form:
 * points as f64, tets as u32, values as f32, all little-endian.  Equal for
 * equal meshes whatever the chunk's encoding. */
uint32_t vx_tetmesh_crc(const vx_tetmesh *m);

/* vx_tetleaf_to_chunk: the TLEF chunk of lg, built from m (zlevel 0 raw,
 * 1..9 zlib); c is filled (its payload owned by the caller). */
int vx_tetleaf_to_chunk(const vx_tetleaf *lg, const vx_tetmesh *m,
    int zlevel, vx_chunk *c, vx_err *e);

/* vx_tetleaf_ident: the identity a TLEF chunk names: its mesh's name,
 * point and tet counts and CRC. */
typedef struct vx_tetleaf_ident {
	char mesh[VX_TETMESH_NAME];
	uint64_t npoint, ntet;
	uint32_t crc;
} vx_tetleaf_ident;

/* vx_tetleaf_from_chunk: parse a TLEF chunk into lg (initialized by the
 * call) and *id (may be NULL).  Every count is bounded by the body's
 * bytes before allocating; offsets must start at 0, never decrease and end
 * at the entry count; each leaf's tets strictly ascending and below the
 * named tet count; no NaN in the levels.  VX_EDATA, VX_ENOMEM. */
int vx_tetleaf_from_chunk(vx_tetleaf *lg, vx_tetleaf_ident *id,
    const vx_chunk *c, vx_err *e);

/* vx_tetleaf_from_stream: the TLEF chunk of mesh m (same name), loaded when
 * its counts and CRC match m (*status VX_MACRO_LOADED), else
 * VX_MACRO_STALE (lg empty), or VX_MACRO_ABSENT; *index (may be NULL) gets
 * the chunk's position or -1.  A malformed chunk of that name is an
 * error. */
int vx_tetleaf_from_stream(vx_tetleaf *lg, const vx_stream *s,
    const vx_tetmesh *m, int *status, long *index, vx_err *e);

/* vx_tetmesh_find_source: the chunk a renderer draws: the first VOLM or
 * TETM chunk of s, or with name non-NULL the first whose name (header
 * "name"; default "density" for volumes, "mesh" for meshes) equals it.
 * Returns its index and sets *is_mesh (1 for TETM), or -1 when there is
 * none (a chunk whose header cannot be read matches no name). */
long vx_tetmesh_find_source(const vx_stream *s, const char *name,
    int *is_mesh);

/* ---- volumes or meshes from one file (import_any.c) ---- */

/* vx_tetmesh_detect: 1 if buf (gzip-compressed or not) holds a mesh file
 * that vx_tetmesh_import_mem reads: a gmsh file ("$MeshFormat") or a VTK
 * legacy file whose DATASET line (the fourth line) names
 * UNSTRUCTURED_GRID; else 0. */
int vx_tetmesh_detect(const void *buf, size_t n);

/* vx_import_volume_or_mesh: read path ("-": standard input) once; when its
 * content is a mesh (vx_tetmesh_detect) and vopt->format is unknown or
 * VTK, import the mesh into m (named after the file) and set *is_mesh = 1;
 * otherwise import a volume into g exactly as vx_import_file does (*is_mesh
 * = 0).  Both g and m are initialized by the call; the other stays empty.
 * Errors are prefixed with the path. */
int vx_import_volume_or_mesh(vx_grid *g, vx_tetmesh *m, int *is_mesh,
    const char *path, const vx_import_opts *vopt,
    const vx_tetimport_opt *mopt, vx_tetimport_info *info, vx_err *e);

#endif
