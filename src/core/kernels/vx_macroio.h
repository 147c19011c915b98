/* vx_macroio.h: the stream form of the min/max hierarchy (vx_macro.h),
 * the MCEL chunk (formats/macrocell.md), and the level keys it shares with
 * the tet leaf grid's TLEF chunk. */
#ifndef VX_MACROIO_H
#define VX_MACROIO_H

#include <stdint.h>

#include "vx_err.h"
#include "vx_grid.h"
#include "vx_macro.h"
#include "vx_stream.h"

/* vx_macro_hdr_levels: the keys that describe m's levels in a chunk header
 * (MCEL and TLEF), in this order: levels, sizes, dims-1 .. dims-L, range. */
int vx_macro_hdr_levels(const vx_macro *m, vx_hdr *h, vx_err *e);

/* vx_macro_hdr_levels_get: what vx_macro_hdr_levels wrote, read back
 * from h (MCEL and TLEF) and checked, given the leaf dims dims[0] (each
 * 0..VX_GRID_MAX_DIM): *nlev from "levels" (0..VX_MACRO_MAXLEV), sizes[l -
 * 1] (level l's edges, each 1..VX_MACRO_MAXSIZE) from "sizes" (exactly
 * *nlev space-separated AxBxC), and dims[l] for l = 1..*nlev, each
 * dims[l - 1] over the edges rounded up, which "dims-l" must repeat; 0 or
 * VX_EDATA. */
int vx_macro_hdr_levels_get(const vx_hdr *h, int *nlev,
    int sizes[VX_MACRO_MAXLEV][3], int64_t dims[VX_MACRO_MAXLEV + 1][3],
    vx_err *e);

/* vx_macro_to_chunk: the MCEL chunk of m (zlevel 0 raw, 1..9 zlib). */
int vx_macro_to_chunk(const vx_macro *m, int zlevel, vx_chunk *c,
    vx_err *e);
/* vx_macro_from_chunk: parse an MCEL chunk; m is initialized by the call.
 * Checks every header word and the body's size before allocating. */
int vx_macro_from_chunk(vx_macro *m, const vx_chunk *c, vx_err *e);

/* vx_macro_matches: 1 if m was built over exactly this volume (name, dims,
 * type and sample CRC; the CRC costs one pass over the samples unless crc
 * is given: pass NULL to compute it). */
int vx_macro_matches(const vx_macro *m, const vx_grid *g,
    const uint32_t *crc);

/* vx_macro_find_owned: *index gets the index of the first chunk of type
 * `type`, VX_CHUNK_MACRO or VX_CHUNK_TETLEAF, that belongs to the volume
 * (MCEL: its "volume" key) or tet mesh (TLEF: "mesh") named `name`, or -1
 * when none does.  The one lookup of a hierarchy's owner: an MCEL over
 * explicit leaves belongs to no volume and is passed over; a chunk of the
 * type whose payload does not parse, or that lacks its owner's key, is
 * bad data nobody can place: VX_EDATA ("chunk TYPE at OFFSET: ..."). */
int vx_macro_find_owned(const vx_stream *s, const char *type,
    const char *name, long *index, vx_err *e);

enum {
	VX_MACRO_ABSENT = 0,     /* no MCEL chunk for this volume */
	VX_MACRO_LOADED,         /* found, matches the volume, loaded */
	VX_MACRO_STALE           /* found, but built over other samples */
};

/* vx_macro_stream_find: the opening of vx_macro_from_stream and
 * vx_tetleaf_from_stream: *status = VX_MACRO_ABSENT, and *i (and *index
 * when not NULL) the chunk vx_macro_find_owned finds, -1 when none; its
 * error is pushed under "macrocells" (MCEL) or "leaf grid" (TLEF). */
int vx_macro_stream_find(const vx_stream *s, const char *type,
    const char *name, int *status, long *index, long *i, vx_err *e);

/* vx_macro_from_stream: find the MCEL chunk belonging to volume g (same
 * name) and load it if it matches g (vx_macro_matches).  src: the index in
 * s of the VOLM chunk g was decoded from and not changed since, or -1: when
 * that chunk's CRC is known (read with it) and equals the MCEL chunk's
 * volume-chunk-crc32, the bytes the hierarchy was built from are these, and
 * the pass over the samples is skipped.  *status gets one of the values
 * above and *index the chunk's position (-1 if absent); m is initialized and
 * holds the hierarchy only when LOADED.  A malformed MCEL chunk is an error
 * (VX_EDATA), absence and staleness are not: the caller then builds the
 * hierarchy itself (and may say so). */
int vx_macro_from_stream(vx_macro *m, const vx_stream *s, const vx_grid *g,
    long src, int *status, long *index, vx_err *e);

#endif

