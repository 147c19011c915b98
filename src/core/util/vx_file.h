/* vx_file.h: reading a whole file into memory with a bound. */
#ifndef VX_FILE_H
#define VX_FILE_H

#include <stddef.h>
#include <stdio.h>

#include "vx_err.h"

/* vx_file_read_all: read f to its end into *buf (malloc'ed, caller frees),
 * *n bytes.  Memory grows only as bytes arrive; more than max bytes is an
 * error (VX_EDATA).  VX_EIO on read errors. */
int vx_file_read_all(FILE *f, size_t max, unsigned char **buf, size_t *n,
    vx_err *e);

#endif
