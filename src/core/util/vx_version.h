/* vx_version.h: the toolkit's version, written into every history line. */
#ifndef VX_VERSION_H
#define VX_VERSION_H
#define VX_VERSION "0.1.0"
#endif
