/* vx_tetimport.h: tetrahedral meshes from files (VTK legacy, gmsh),
 * synthetic meshes, and the one call that reads a volume or a mesh from a
 * file by its content. */
#ifndef VX_TETIMPORT_H
#define VX_TETIMPORT_H

#include <stddef.h>
#include <stdint.h>

#include "vx_err.h"
#include "vx_grid.h"
#include "vx_import.h"
#include "vx_tetmesh.h"

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
