/* vx_grid.h: rectilinear scalar volumes and their memory layout.
 *
 * Every voxel access goes through per-axis offset tables (Parker et al. 1999,
 * §3.1): index(x,y,z) = off[0][x] + off[1][y] + off[2][z].  A linear layout
 * is the same tables with plain strides (x fastest); a bricked layout nests
 * bricks level by level, innermost first.  So bricked and linear volumes share
 * one code path and give bit-identical results.
 *
 * World coordinates: sample (i,j,k) sits at origin + (i,j,k) * spacing.  The
 * "index space" used by the kernels has sample (i,j,k) at (i,j,k). */
#ifndef VX_GRID_H
#define VX_GRID_H

#include <stddef.h>
#include <stdint.h>

#include "vx_enum.h"
#include "vx_err.h"
#include "vx_stream.h"

typedef enum vx_type {
	VX_TYPE_UNKNOWN = 0,
	VX_U8,
	VX_U16,
	VX_I16,
	VX_F32,
	VX_TYPE_LAST
} vx_type;

size_t vx_type_size(vx_type t);
/* The names (vx_enum.h): "u8", "u16", "i16", "f32"; VX_TYPE_UNKNOWN and
 * "unknown" for the others. */
extern const vx_enum vx_type_enum;

/* vx_interp: how a value between the points of a lattice is read: the
 * scene's "illumination ... interpolation" (formats/scene.md) and the
 * lookups of the irradiance and SH transfer volumes (vx_irrvol.h), which
 * read VX_INTERP_UNKNOWN as trilinear.  No chunk stores it.  The names
 * (vx_enum.h): "nearest", "trilinear", "tricubic", "nearest-iso";
 * VX_INTERP_UNKNOWN and "unknown" for the others. */
typedef enum vx_interp {
	VX_INTERP_UNKNOWN = 0,
	VX_INTERP_NEAREST,
	VX_INTERP_TRILINEAR,
	VX_INTERP_TRICUBIC,
	VX_INTERP_NEAREST_ISO,     /* of the 8 texels around, the one whose own
	                              isovalue is closest to the hit's */
	VX_INTERP_LAST
} vx_interp;
extern const vx_enum vx_interp_enum;

/* Largest volume a grid may hold, in samples (padded).  Protects against
 * header words that claim absurd sizes before anything is allocated. */
#define VX_GRID_MAX_SAMPLES ((uint64_t)1 << 36)
#define VX_GRID_MAX_DIM     ((int64_t)1 << 20)
#define VX_LAYOUT_MAXLEV    4

typedef struct vx_layout {
	int nlev;                          /* 0: linear */
	int brick[VX_LAYOUT_MAXLEV][3];    /* level l brick edge, in units of
	                                      level l-1 bricks (level 0: samples) */
	int64_t pdims[3];                  /* padded dims (multiples of the
	                                      outermost brick edge in samples) */
	int64_t *off[3];                   /* offset tables, dims[a] + 1 entries
	                                      (the last repeats the edge so a cell
	                                      fetch at the border stays in range) */
} vx_layout;

typedef struct vx_grid {
	char name[64];         /* "density" unless told otherwise */
	int64_t dims[3];       /* samples per axis, each >= 1 */
	double spacing[3];     /* world units per sample step, > 0 */
	double origin[3];      /* world position of sample (0,0,0) */
	vx_type type;
	void *data;            /* samples in layout order, owned unless
	                          borrowed */
	int borrowed;          /* 1: data lies in a chunk's payload
	                          (vx_grid_view_chunk); not freed here */
	size_t nsample;        /* samples allocated (padded product) */
	vx_layout lay;
	int has_range;
	double vmin, vmax;     /* finite value range (NaN/Inf ignored) */
} vx_grid;

void vx_grid_init(vx_grid *g);
void vx_grid_free(vx_grid *g);

/* vx_layout_linear / vx_layout_bricked: build tables for dims.  bricks[l] is
 * level l's brick edge per axis; each entry must be a power of two >= 1.
 * vx_layout_free releases the tables.  Errors: VX_EDATA for sizes out of
 * range, VX_ENOMEM. */
int vx_layout_linear(vx_layout *lay, const int64_t dims[3], vx_err *e);
int vx_layout_bricked(vx_layout *lay, const int64_t dims[3], int nlev,
    const int bricks[][3], vx_err *e);
void vx_layout_free(vx_layout *lay);
/* vx_layout_default_bricks: Parker's two-level bricking for sample type t:
 * level 0 is one 64-byte cache line of samples (u8 4x4x4, u16/i16 4x4x2,
 * f32 4x2x2), level 1 one 4 KiB page of those (4x4x4 of them).  Fills
 * bricks[0..1] and returns 2, or 0 for an unknown type. */
int vx_layout_default_bricks(vx_type t, int bricks[][3]);
/* vx_layout_nsample: samples the layout needs (product of pdims). */
size_t vx_layout_nsample(const vx_layout *lay);
/* vx_layout_string: "linear" or "bricked 4x4x4 4x4x4" (innermost first). */
void vx_layout_string(const vx_layout *lay, char *buf, size_t n);
/* vx_layout_parse: inverse of vx_layout_string; builds the tables. */
int vx_layout_parse(vx_layout *lay, const int64_t dims[3], const char *s,
    vx_err *e);

/* vx_grid_alloc: set dims and type, build a linear layout (or the given one
 * when lay_spec is non-NULL, as in vx_layout_parse) and allocate zeroed
 * samples.  Spacing 1, origin 0, name "density". */
int vx_grid_alloc(vx_grid *g, const int64_t dims[3], vx_type type,
    const char *lay_spec, vx_err *e);

static inline size_t
vx_grid_index(const vx_grid *g, int64_t x, int64_t y, int64_t z)
{
	return (size_t)(g->lay.off[0][x] + g->lay.off[1][y] + g->lay.off[2][z]);
}

/* vx_grid_get / vx_grid_set: one sample as double (no bounds check). */
double vx_grid_get(const vx_grid *g, int64_t x, int64_t y, int64_t z);
void vx_grid_set(vx_grid *g, int64_t x, int64_t y, int64_t z, double v);
/* vx_grid_get_index: sample at a layout index as double. */
double vx_grid_get_index(const vx_grid *g, size_t i);

/* vx_grid_cell: the eight corners of cell (x,y,z) (0 <= x < dims[0]-1, ...)
 * with six table look-ups; c[i] is corner (i&1, (i>>1)&1, (i>>2)&1). */
void vx_grid_cell(const vx_grid *g, int64_t x, int64_t y, int64_t z,
    float c[8]);

/* vx_grid_trilinear: the trilinear value at index-space point p, clamped
 * into the volume (an axis of one sample contributes its sample); NaN
 * where a corner it weighs is not finite. */
double vx_grid_trilinear(const vx_grid *g, const double p[3]);

/* vx_grid_cell_inline, vx_grid_trilinear_inline: the same functions (the
 * same bits), inline for inner loops. */
#define VX_GRID_CELL_FETCH_(T)                                           \
	do {                                                             \
		const T *d_ = (const T *)g->data;                        \
		c[0] = (float)d_[x0 + y0 + z0]; c[1] = (float)d_[x1 + y0 + z0]; \
		c[2] = (float)d_[x0 + y1 + z0]; c[3] = (float)d_[x1 + y1 + z0]; \
		c[4] = (float)d_[x0 + y0 + z1]; c[5] = (float)d_[x1 + y0 + z1]; \
		c[6] = (float)d_[x0 + y1 + z1]; c[7] = (float)d_[x1 + y1 + z1]; \
	} while (0)

static inline __attribute__((always_inline)) void
vx_grid_cell_inline(const vx_grid *g, int64_t x, int64_t y, int64_t z,
    float c[8])
{
	int64_t x0 = g->lay.off[0][x], x1 = g->lay.off[0][x + 1];
	int64_t y0 = g->lay.off[1][y], y1 = g->lay.off[1][y + 1];
	int64_t z0 = g->lay.off[2][z], z1 = g->lay.off[2][z + 1];

	switch (g->type) {
	case VX_U8: VX_GRID_CELL_FETCH_(uint8_t); break;
	case VX_U16: VX_GRID_CELL_FETCH_(uint16_t); break;
	case VX_I16: VX_GRID_CELL_FETCH_(int16_t); break;
	case VX_F32: VX_GRID_CELL_FETCH_(float); break;
	default:
		for (int i = 0; i < 8; i++)
			c[i] = 0;
		break;
	}
}

static inline double
vx_grid_lerp_(double a, double b, double s)
{
	return a + (b - a) * s;
}

static inline double
vx_grid_trilinear_inline(const vx_grid *g, const double pin[3])
{
	double l[3], e0, e1, e2, e3;
	int64_t i[3];
	float c[8];

	for (int a = 0; a < 3; a++) {
		double hi = (double)(g->dims[a] - 1), p = pin[a];

		if (!(p >= 0))
			p = 0;
		if (p > hi)
			p = hi;
		i[a] = (int64_t)p;
		if (i[a] > g->dims[a] - 2)
			i[a] = g->dims[a] - 2;
		if (i[a] < 0)
			i[a] = 0;
		l[a] = p - (double)i[a];
		if (g->dims[a] == 1)
			l[a] = 0;
	}
	/* a dimension of 1 has no cells: fetch with x+1 clamped by the guard
	 * entry of the offset tables */
	vx_grid_cell_inline(g, i[0], i[1], i[2], c);
	e0 = vx_grid_lerp_(c[0], c[1], l[0]);
	e1 = vx_grid_lerp_(c[2], c[3], l[0]);
	e2 = vx_grid_lerp_(c[4], c[5], l[0]);
	e3 = vx_grid_lerp_(c[6], c[7], l[0]);
	return vx_grid_lerp_(vx_grid_lerp_(e0, e1, l[1]),
	    vx_grid_lerp_(e2, e3, l[1]), l[2]);
}

/* vx_grid_range: compute vmin/vmax over the real (unpadded) samples,
 * ignoring NaN and infinities; sets has_range (0 if no finite sample). */
void vx_grid_range(vx_grid *g);

/* vx_grid_relayout: copy src's samples into dst with layout spec `spec`
 * ("linear" or "bricked ..."); dst gets src's metadata.  dst is initialized
 * by this call. */
int vx_grid_relayout(vx_grid *dst, const vx_grid *src, const char *spec,
    vx_err *e);

/* ---- stream form: the VOLM chunk ----
 * Header keys: name, dims, type, spacing, origin, layout, range, encoding
 * (and the writer's pad line).  Body: nsample samples, little-endian, in
 * layout order (pads are zero). */
/* vx_grid_key_known: 1 if the VOLM writer writes key k itself (the keys
 * above and "pad"): a header's other keys are the ones to carry along. */
int vx_grid_key_known(const char *k);
int vx_grid_to_chunk(const vx_grid *g, int zlevel, vx_chunk *c, vx_err *e);
/* vx_grid_to_chunk_extra: the same, and then every key of `extra` (a
 * header, e.g. of the chunk g was read from; NULL: none) that the VOLM
 * writer does not write itself, with its value, in extra's order.  For tools
 * that rewrite a volume without changing what its samples mean (brick):
 * unknown keys then pass through (formats/stream.md 9.1). */
int vx_grid_to_chunk_extra(const vx_grid *g, int zlevel, const vx_hdr *extra,
    vx_chunk *c, vx_err *e);
/* vx_grid_to_chunk_take: vx_grid_to_chunk_extra's chunk, byte for byte, made
 * from g's own memory (raw, on a little-endian host: no second copy of the
 * samples, vx_payload_wrap); g is consumed (freed, also on error).  For
 * tools that write a volume they are done with (vread, brick). */
int vx_grid_to_chunk_take(vx_grid *g, int zlevel, const vx_hdr *extra,
    vx_chunk *c, vx_err *e);
int vx_grid_from_chunk(vx_grid *g, const vx_chunk *c, vx_err *e);
/* vx_grid_view_chunk: the same checks and grid, but a raw body of samples
 * aligned for their type on a little-endian host (every body the reference
 * writer makes: formats/stream.md 7.1) is not copied: g->data points into
 * c's payload (g->borrowed = 1), which must then outlive g, and neither may
 * be changed while both live.  Other bodies are decoded into g's own
 * memory, as vx_grid_from_chunk does.  For renderers: no second copy of
 * the samples, no pass over them. */
int vx_grid_view_chunk(vx_grid *g, const vx_chunk *c, vx_err *e);

/* Convenience: the first VOLM chunk in a stream (or the one whose name
 * matches when name is non-NULL); *index gets its position. */
int vx_grid_from_stream(vx_grid *g, const vx_stream *s, const char *name,
    long *index, vx_err *e);
/* vx_grid_view_stream: the same with vx_grid_view_chunk. */
int vx_grid_view_stream(vx_grid *g, const vx_stream *s, const char *name,
    long *index, vx_err *e);

/* ---- grids: world <-> index space ----
 * world = origin + index * spacing per axis (no rotation).  Directions map
 * by the same scaling without normalization, so a ray o + t d in world space
 * is o' + t d' in index space with the same t. */

/* vx_grid_box: the world box spanned by the samples: lo = origin,
 * hi = origin + (dims - 1) * spacing. */
void vx_grid_box(const vx_grid *g, double lo[3], double hi[3]);

/* vx_grid_check_box: 0 when g's geometry is usable: spacing finite and
 * positive, origin finite, and the box finite: each hi, each side hi - lo
 * and the diagonal's length (what a camera frames) do not overflow.
 * Else VX_EDATA, "extent overflows on axis A: origin X + (N - 1) x
 * spacing S" (or the spacing's or origin's fault). */
int vx_grid_check_box(const vx_grid *g, vx_err *e);
void vx_world_to_index(const vx_grid *g, const double w[3], double i[3]);
void vx_index_to_world(const vx_grid *g, const double i[3], double w[3]);
void vx_world_to_index_dir(const vx_grid *g, const double w[3], double i[3]);
void vx_index_to_world_dir(const vx_grid *g, const double i[3], double w[3]);
/* vx_index_to_world_normal: a normal (e.g. a gradient) in index space to
 * world space: divide by spacing (the inverse transpose), then normalize;
 * a zero vector stays zero. */
void vx_index_to_world_normal(const vx_grid *g, const double i[3],
    double w[3]);

#endif
