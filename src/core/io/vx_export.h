/* vx_export.h: writing voxlux data in other tools' formats: NRRD (Teem's
 * format, read by unu, ParaView and 3D Slicer) for scalar volumes and for
 * irradiance volumes (RGB texels and their flags), through the same header
 * and body writers (export_nrrd.c). */
#ifndef VX_EXPORT_H
#define VX_EXPORT_H

#include <stddef.h>
#include <stdio.h>

#include "vx_err.h"
#include "vx_grid.h"
#include "vx_irrvol.h"

/* Options of the NRRD writer.  A zeroed struct means raw, no comments. */
typedef struct vx_nrrd_opts {
	int gzip;                      /* 0: encoding raw; 1: encoding gzip */
	int level;                     /* gzip level 1..9; 0: zlib's default */
	const char *const *comments;   /* lines written as "# line" */
	size_t ncomments;
	const vx_hdr *keys;            /* pairs written as "key:=value" lines
	                                  (NULL: none) */
} vx_nrrd_opts;

/* vx_export_nrrd: write g as an attached-header NRRD0004 file on f:
 *
 *   NRRD0004
 *   # comment lines
 *   content: NAME
 *   type: uint8 | uint16 | int16 | float
 *   dimension: 3
 *   space: 3D-right-handed
 *   sizes: NX NY NZ
 *   space directions: (SX,0,0) (0,SY,0) (0,0,SZ)
 *   kinds: domain domain domain
 *   centerings: node node node
 *   endian: little
 *   encoding: raw | gzip
 *   space origin: (OX,OY,OZ)
 *   key:=value lines, one per pair of o->keys
 *   <empty line>
 *   samples, x fastest, little-endian (gzip: one RFC 1952 member)
 *
 * The samples are written in linear order whatever g's layout, padding left
 * out.  Numbers are %.17g, so spacing and origin are exact.  Comment bytes
 * that are control characters become '?'; in key/value pairs a backslash
 * is written "\\\\" and a newline "\\n", as the NRRD format escapes them.  f is flushed, not closed; write
 * errors are VX_EIO.  vx_export_nrrd is vx_export_nrrd_opts with only gzip
 * set. */
int vx_export_nrrd(const vx_grid *g, FILE *f, int gzip, vx_err *e);
int vx_export_nrrd_opts(const vx_grid *g, FILE *f, const vx_nrrd_opts *o,
    vx_err *e);

/* vx_export_nrrd_irr: write irradiance volume v, laid over volume g (whose
 * dims must be v's volume-dims: VX_EDATA otherwise), as a 4-D NRRD of
 * binary32 RGB texels that overlays g in world space:
 *
 *   content: the volume's name
 *   type: float
 *   dimension: 4
 *   sizes: 3 N0 N1 N2                  (the lattice's dims)
 *   space directions: none (H0,0,0) (0,H1,0) (0,0,H2)
 *   kinds: RGB-color domain domain domain
 *   centerings: ??? node node node
 *   space origin: g's origin          (texel 0 sits on sample 0)
 *
 * with Ha = v->step[a] * g->spacing[a], the lattice's world spacing; the
 * rest of the header as vx_export_nrrd_opts.  The body: the mean E (R, G, B)
 * of each texel, x fastest; texels that are absent or not usable
 * (vx_irr_usable) are 0 0 0.
 *
 * vx_export_nrrd_irr_flags: the texels' VX_TEXEL_* flags as a 3-D NRRD of
 * the same geometry (dimension 3, kinds domain, centerings node), type
 * uint8 (bytes 1; VX_EDATA if a texel has a flag past bit 7) or uint32
 * (bytes 4); absent texels are 0.  Other bytes: VX_EUSAGE. */
int vx_export_nrrd_irr(const vx_irrvol *v, const vx_grid *g, FILE *f,
    const vx_nrrd_opts *o, vx_err *e);
int vx_export_nrrd_irr_flags(const vx_irrvol *v, const vx_grid *g, int bytes,
    FILE *f, const vx_nrrd_opts *o, vx_err *e);

/* vx_nrrd_type: the NRRD type name of a sample type ("uint8", "uint16",
 * "int16", "float"), or NULL. */
const char *vx_nrrd_type(vx_type t);

#endif
