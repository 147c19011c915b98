/* vx_tfimport.h: transfer functions from the files users already have
 * (formats/transfer.md, "Imports"):
 *   paraview  ParaView's colour-map/opacity JSON (the preset array written
 *             by "Save presets": RGBPoints, Points, ColorSpace, ...)
 *   slicer    3D Slicer's volume property: the .vp text file (scalar
 *             opacity, gradient opacity, colour transfer function) and the
 *             .vp.json form
 *   miter     teem miter's txf: a NRRD whose first axis holds RGBA (or A)
 *             over a value axis and optionally a gradient-magnitude axis
 * Every reader is bounded (a file of at most VX_TF_FILE_MAX bytes, at most
 * VX_TF_MAX_POINTS points per list, VX_TF_MAX_TABLE cells per table axis)
 * and refuses malformed input with one message naming what and where. */
#ifndef VX_TFIMPORT_H
#define VX_TFIMPORT_H

#include "vx_enum.h"
#include "vx_err.h"
#include "vx_tf.h"

#define VX_TF_FILE_MAX ((size_t)64 << 20)   /* bytes */


/* vx_tf_import: read the file at path ("-": standard input) in format fmt
 * into tf (initialized by the call; on error tf is left empty).  A
 * successful import passes vx_tf_check.  Errors: VX_ENOINPUT (cannot
 * open, a directory, empty), VX_EDATA (malformed or unsupported: one line
 * "PATH: line N: key \"RGBPoints\" element 7: ..." saying what and
 * where), VX_EUSAGE (fmt not a format), VX_ENOMEM, VX_EIO. */
int vx_tf_import(const char *path, vx_tf_format fmt, vx_tf *tf, vx_err *e);

/* vx_tf_import_mem: the same from the n bytes at buf (messages without a
 * path); dir is where a txf's detached data file is looked for (NULL:
 * such a header is refused, so fuzzing opens no files). */
int vx_tf_import_mem(const void *buf, size_t n, vx_tf_format fmt,
    const char *dir, vx_tf *tf, vx_err *e);

#endif
