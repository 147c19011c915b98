/* vx_tetleaf.h: the leaf grid of tet lists (Parker et al. 1999, §4.2) with
 * its min/max hierarchy, the watertight ray/tet isosurface intersection
 * (Appendix B, made crack-free), every crossing along a ray, and the TLEF
 * chunk (formats/tetmesh.md). */
#ifndef VX_TETLEAF_H
#define VX_TETLEAF_H

#include <stddef.h>
#include <stdint.h>

#include "vx_err.h"
#include "vx_grid.h"
#include "vx_macrowalk.h"
#include "vx_macroio.h"
#include "vx_stream.h"
#include "vx_tetmesh.h"

/* ---- the leaf grid (Parker §4.2) and its min/max hierarchy ----
 * A rectilinear grid over the mesh's bounding box (grown by VX_TETLEAF_PAD
 * leaf widths on every side) with about `density` leaves per tet (1 in the
 * paper).  Leaf (i,j,k), index i + n0 * (j + n1 * k), covers the box from
 * bmin + (i,j,k) * cell to bmin + (i+1,j+1,k+1) * cell.  Its tets are
 * idx[off[l] .. off[l+1]-1] (ascending): every tet that overlaps the leaf's
 * box padded by VX_TETLEAF_PAD leaf widths, by an exact separating-axis
 * test (the default) or by the tet's bounding box (VX_TETLEAF_BBOX): the
 * exact lists are shorter, for a slower build (formats/tetmesh.md has the
 * measurements).  Tets that can never hit (a non-finite vertex value, zero
 * volume) are not listed.  The padding makes a hit at a leaf boundary safe
 * against the rounding of the traversal's t values.  The leaf ranges
 * (min/max of the vertex values of the listed tets; empty leaf: +inf, -inf)
 * are level 0 of a vx_macro hierarchy with explicit leaves (vx_macro.h),
 * whose leaf index space is (world - bmin) / cell. */
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

/* vx_tetleaf_walk_setup: what vx_tetleaf_nearest and vx_tetleaf_trace
 * hand vx_macro_traverse: the ray o + t d in lg's leaf-index space (lo,
 * ld) and the isovalues as floats in vals (rounding is monotone and leaf
 * bounds are floats, so min <= iso <= max implies the same for (float)iso,
 * and the interpolated values stay within the vertex values); returns
 * their count, niso, or 0 (no culling) when there are more than 64. */
int vx_tetleaf_walk_setup(const vx_tetleaf *lg, const double o[3],
    const double d[3], const double *iso, int niso, double lo[3],
    double ld[3], float vals[64]);

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

#endif
