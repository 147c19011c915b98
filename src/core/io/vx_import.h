/* vx_import.h: reading volumes from other formats, and synthetic fields.
 *
 * Formats: raw (dims and type given by the caller), NRRD (attached and
 * detached headers; raw, gzip, ascii and hex encodings), NIfTI-1 (.nii,
 * .nii.gz, .hdr/.img pairs) and VTK legacy STRUCTURED_POINTS (ASCII and
 * BINARY).  Every reader parses from a memory buffer (so fuzz targets can
 * call it); gzip-compressed input (magic 1f 8b) is decompressed on the fly,
 * never beyond what the header implies plus a small slack.  File wrappers
 * read a path ("-" is standard input) and call the memory readers.
 *
 * Results are always linear-layout grids with their range computed.  Source
 * sample types map onto voxlux types as vx_scalar_target says: u8, u16, i16
 * and f32 are kept; i8 widens to i16 (exact); u32, i32, u64, i64 and f64
 * become f32 (rounded to nearest; exact for integers up to 2^24 in
 * magnitude; an f64 beyond the f32 range is an error, NaN stays NaN).
 *
 * World frame: sample (i,j,k) sits at origin + (i,j,k) * spacing.  A file's
 * frame (NRRD space directions, NIfTI sform/qform) must be axis-aligned:
 * each index axis must step along the same world axis (components off that
 * axis below 1e-6 of the step's length are taken as zero).  A negative step
 * is a mirrored axis: the samples are reversed along it so the spacing is
 * positive and every sample keeps its world position.  Rotations and axis
 * permutations are refused.  World coordinates are the file's own space
 * (NIfTI: RAS+ mm; NRRD: whatever its "space" field names).
 *
 * Errors say which field is wrong ("nrrd: sizes: expected 3 positive
 * integers"); codes are VX_EDATA for malformed or unsupported input,
 * VX_ENOINPUT for a missing file, VX_EIO for read errors, VX_ENOMEM. */
#ifndef VX_IMPORT_H
#define VX_IMPORT_H

#include <stddef.h>
#include <stdint.h>

#include "vx_enum.h"
#include "vx_err.h"
#include "vx_grid.h"

/* ---- source sample types ---- */

typedef enum vx_scalar {
	VX_SCALAR_UNKNOWN = 0,
	VX_S_U8, VX_S_I8, VX_S_U16, VX_S_I16, VX_S_U32, VX_S_I32,
	VX_S_U64, VX_S_I64, VX_S_F32, VX_S_F64,
	VX_SCALAR_LAST
} vx_scalar;

size_t vx_scalar_size(vx_scalar t);          /* bytes per sample, 0 if unknown */
/* The names (vx_enum.h): "u8", "i8", ..., "f64"; VX_SCALAR_UNKNOWN and
 * "unknown" for the others. */
extern const vx_enum vx_scalar_enum;
vx_type vx_scalar_target(vx_scalar t);       /* the voxlux type it is stored as */

/* ---- formats ---- */

typedef enum vx_format {
	VX_FORMAT_UNKNOWN = 0,
	VX_FORMAT_RAW, VX_FORMAT_NRRD, VX_FORMAT_NIFTI, VX_FORMAT_VTK,
	VX_FORMAT_LAST
} vx_format;

/* The names (vx_enum.h): "raw", "nrrd", "nifti", "vtk"; VX_FORMAT_UNKNOWN
 * and "unknown" for the others. */
extern const vx_enum vx_format_enum;

/* vx_import_detect: the format of buf (decompressing a gzip prefix if need
 * be) from its magic bytes: "NRRD000x", a NIfTI-1 header (sizeof_hdr 348 in
 * either byte order, magic "n+1" or "ni1"), "# vtk DataFile".  Failing
 * those, from name's extension (.nrrd .nhdr .nii .hdr .vtk .raw, each maybe
 * followed by .gz); name may be NULL.  VX_FORMAT_UNKNOWN if neither tells. */
vx_format vx_import_detect(const void *buf, size_t n, const char *name);

/* ---- raw ---- */

typedef struct vx_raw_info {
	int64_t dims[3];     /* samples per axis, x fastest */
	vx_scalar type;
	int big_endian;      /* byte order of multi-byte samples */
	uint64_t skip;       /* bytes before the first sample (after gunzip) */
	double spacing[3];   /* default 1 */
	double origin[3];    /* default 0 */
} vx_raw_info;

/* The byte orders' names (vx_enum.h), as in raw_info.big_endian: "little"
 * 0, "big" 1, any ASCII case; -1 for another word. */
extern const vx_enum vx_endian_enum;

/* vx_raw_info_init: no dims, unknown type, little-endian, skip 0,
 * spacing 1, origin 0. */
void vx_raw_info_init(vx_raw_info *r);

/* vx_import_raw_mem: samples from buf (gzip or not) after r->skip bytes.
 * The input must hold exactly skip + product(dims) * size bytes: fewer is
 * "truncated", more is an error too (it usually means wrong dims or type).
 * g is initialized by this call; on error it is left empty. */
int vx_import_raw_mem(vx_grid *g, const void *buf, size_t n,
    const vx_raw_info *r, vx_err *e);

/* ---- NRRD ---- */

/* vx_import_nrrd_mem: a NRRD file (NRRD0001..NRRD0006) in buf.  dir is the
 * directory that relative "data file:" names are taken from; when NULL,
 * headers with detached data are refused (so fuzzing never opens files).
 * Dimension 1..3 (missing axes get size 1).  Details: vread(1). */
int vx_import_nrrd_mem(vx_grid *g, const void *buf, size_t n,
    const char *dir, vx_err *e);

/* ---- NIfTI-1 ---- */

/* vx_import_nifti_mem: a single-file NIfTI-1 (.nii, magic "n+1") in buf.
 * A header with magic "ni1" (of a .hdr/.img pair) is refused here; use
 * vx_import_nifti_pair_mem or vx_import_file with the .hdr name. */
int vx_import_nifti_mem(vx_grid *g, const void *buf, size_t n, vx_err *e);

/* vx_import_nifti_pair_mem: header (.hdr, 348 bytes or more) and image
 * (.img) of a NIfTI-1 pair; vox_offset counts into the image. */
int vx_import_nifti_pair_mem(vx_grid *g, const void *hdr, size_t hn,
    const void *img, size_t in, vx_err *e);

/* ---- VTK legacy ---- */

/* vx_import_vtk_mem: DATASET STRUCTURED_POINTS with POINT_DATA and a
 * one-component SCALARS array (the first one), ASCII or BINARY
 * (big-endian).  Anything after that array is ignored. */
int vx_import_vtk_mem(vx_grid *g, const void *buf, size_t n, vx_err *e);

/* ---- any format ---- */

typedef struct vx_import_opts {
	vx_format format;    /* VX_FORMAT_UNKNOWN: vx_import_detect */
	vx_raw_info raw;     /* dims, type, ... when format is VX_FORMAT_RAW */
} vx_import_opts;

void vx_import_opts_init(vx_import_opts *o);

/* vx_import_mem: dispatch on o->format (or detect it, with name's
 * extension as the fallback; name may be NULL).  dir as for NRRD. */
int vx_import_mem(vx_grid *g, const void *buf, size_t n, const char *name,
    const char *dir, const vx_import_opts *o, vx_err *e);

/* vx_import_file: read path ("-": standard input) and import it.  Detached
 * NRRD data files are found relative to path's directory (the current
 * directory for "-"); a NIfTI .hdr (or .hdr.gz) reads its .img (or .img.gz).
 * Errors are prefixed with the path. */
int vx_import_file(vx_grid *g, const char *path, const vx_import_opts *o,
    vx_err *e);

/* ---- synthetic fields (synth.c) ----
 * All are f32 grids on the world box [-1,1]^3: along an axis of n >= 2
 * samples, sample i sits at x_i = vx_synth_coord(i, n) = (2i - (n-1))/(n-1)
 * (origin -1, spacing 2/(n-1)); an axis of one sample sits at 0 (origin 0,
 * spacing 1).  Sample values are (float)vx_synth_eval(kind, x_i, y_j, z_k)
 * exactly, so tests can recompute them.
 *
 *   sphere  f = sqrt(x^2 + y^2 + z^2): distance from the centre; the level
 *           set f = r is the sphere of radius r.
 *   torus   f = sqrt((sqrt(x^2 + y^2) - 1/2)^2 + z^2): distance from the
 *           circle of radius 1/2 in the plane z = 0; f = r is a torus of
 *           tube radius r.
 *   linear  f = x + 2y + 3z + 1/2 (a . x + b with a = (1,2,3), b = 1/2);
 *           trilinear interpolation reproduces it exactly.
 *   ml      Marschner and Lobb's test signal (1994), f_M = 6, alpha = 1/4:
 *           f = (1 - sin(pi z / 2) + alpha (1 + cos(2 pi f_M
 *               cos(pi r / 2)))) / (2 (1 + alpha)),  r = sqrt(x^2 + y^2);
 *           values in [0, 1], the usual isovalue is 1/2.
 *   saddle  f = x y z + (x y + y z + z x) / 2: trilinear, so trilinear
 *           interpolation reproduces it exactly and the density along any
 *           ray is a true cubic; a non-degenerate saddle at the origin
 *           (Hessian eigenvalues 1, -1/2, -1/2) where the level set f = 0
 *           pinches into a double cone, another critical point at
 *           (-1,-1,-1). */

typedef enum vx_synth_kind {
	VX_SYNTH_UNKNOWN = 0,
	VX_SYNTH_SPHERE, VX_SYNTH_TORUS, VX_SYNTH_LINEAR, VX_SYNTH_ML,
	VX_SYNTH_SADDLE,
	VX_SYNTH_LAST
} vx_synth_kind;

/* The names (vx_enum.h): "sphere", "torus", "linear", "ml", "saddle";
 * VX_SYNTH_UNKNOWN and "unknown" for the others. */
extern const vx_enum vx_synth_enum;
/* vx_synth_coord: world coordinate of sample i of n along one axis. */
double vx_synth_coord(int64_t i, int64_t n);
/* vx_synth_eval: the field at a world point (NaN for an unknown kind). */
double vx_synth_eval(vx_synth_kind k, double x, double y, double z);
/* vx_synth_make: an f32 grid of dims samples (each >= 1) as above, name
 * "density", range computed.  g is initialized by this call. */
int vx_synth_make(vx_grid *g, vx_synth_kind k, const int64_t dims[3],
    vx_err *e);

#endif
