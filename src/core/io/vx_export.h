/* vx_export.h: writing voxlux data in other tools' formats.  For now NRRD
 * (Teem's format, read by unu, ParaView and 3D Slicer) for scalar volumes;
 * multi-component volumes (irradiance, SH) will join through the same
 * header and body writers (export_nrrd.c). */
#ifndef VX_EXPORT_H
#define VX_EXPORT_H

#include <stddef.h>
#include <stdio.h>

#include "vx_err.h"
#include "vx_grid.h"

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

/* vx_nrrd_type: the NRRD type name of a sample type ("uint8", "uint16",
 * "int16", "float"), or NULL. */
const char *vx_nrrd_type(vx_type t);

#endif
