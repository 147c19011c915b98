/* exr_priv.h: between exr.c (the C side: vx_exr_read_mem) and exr_lib.cc
 * (the OpenEXR library's C++ API).  The C++ side neither sees nor makes a
 * vx_image: it asks for the pixels through a callback and reports errors as
 * a code and a message, so it includes no header of the core. */
#ifndef VX_EXR_PRIV_H
#define VX_EXR_PRIV_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* vx_exr_alloc_fn: w x h x 3 zeroed floats (top row first), or NULL after
 * recording why in ctx. */
typedef float *(*vx_exr_alloc_fn)(void *ctx, int w, int h);

/* vx_exr_decode: decode the OpenEXR file buf[0..n) as vx_exr_read_mem
 * describes (vx_imageio.h), each window at most maxdim per side and maxpix
 * pixels.  Returns 0; 65 (bad data) or 71 (out of memory, the library's)
 * with a one-line message in msg (msgcap bytes); or 70 when alloc returned
 * NULL (its ctx says why). */
int vx_exr_decode(const void *buf, size_t n, int maxdim, size_t maxpix,
    vx_exr_alloc_fn alloc, void *ctx, char *msg, size_t msgcap);

#ifdef __cplusplus
}
#endif

#endif
