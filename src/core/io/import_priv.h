/* import_priv.h: internals shared by the importers (not installed): byte
 * sources with bounded gunzip, loading files, sample conversion into grids,
 * frames, and small text helpers. */
#ifndef VX_IMPORT_PRIV_H
#define VX_IMPORT_PRIV_H

#include <stddef.h>
#include <stdint.h>
#include <zlib.h>

#include "vx_import.h"

/* ---- byte sources (import_src.c) ----
 * A source hands out the bytes of a memory buffer, or of the gzip stream in
 * another source, in order.  Headers are parsed from a contiguous window
 * (vx_imp_peek); samples are copied out (vx_imp_read), straight into the caller's
 * memory when the source is compressed.  A gzip source only inflates what
 * its caller asks for, so a header's size claim never makes it decompress
 * more than that claim plus the slack the caller asks to see. */

#define IMP_GZ_RATIO 1032     /* deflate's largest expansion ratio */
#define IMP_SLACK 4096        /* bytes tolerated after the samples */

typedef struct vx_imp_src {
	int gz;                       /* 0: memory, 1: gzip over `under` */
	const unsigned char *mem;     /* memory: the bytes */
	size_t n, pos;
	struct vx_imp_src *under;        /* gzip: compressed input */
	struct vx_imp_src *own;          /* an `under` this source allocated */
	z_stream zs;
	int zinit, zend;
	unsigned char *buf;           /* gzip: inflated, not yet consumed: */
	size_t cap, off, len;         /*   buf[off .. len) */
	uint64_t done;                /* bytes consumed so far */
} vx_imp_src;

/* vx_imp_src_mem: a source over n bytes at p (borrowed). */
void vx_imp_src_mem(vx_imp_src *s, const void *p, size_t n);
/* vx_imp_src_gzip: a source inflating the gzip stream read from under
 * (borrowed; must outlive s).  Concatenated members are read in turn. */
int vx_imp_src_gzip(vx_imp_src *s, vx_imp_src *under, vx_err *e);
/* vx_imp_src_auto: memory, or gzip over it when p starts with the gzip
 * magic (1f 8b 08). */
int vx_imp_src_auto(vx_imp_src *s, const void *p, size_t n, vx_err *e);
void vx_imp_src_close(vx_imp_src *s);
/* vx_imp_is_gzip: p starts with the gzip magic. */
int vx_imp_is_gzip(const void *p, size_t n);

/* vx_imp_peek: make up to `want` bytes contiguous at the current position;
 * *avail gets how many (fewer only at the end of input). */
int vx_imp_peek(vx_imp_src *s, size_t want, const unsigned char **p, size_t *avail,
    vx_err *e);
/* vx_imp_skip: consume k bytes; VX_EDATA "input ends after N bytes" if fewer. */
int vx_imp_skip(vx_imp_src *s, uint64_t k, vx_err *e);
/* vx_imp_read: copy up to n bytes to dst; *got < n only at the end of input. */
int vx_imp_read(vx_imp_src *s, void *dst, size_t n, size_t *got, vx_err *e);
/* vx_imp_left_max: an upper bound of the bytes left (exact for memory; for
 * gzip, what the compressed bytes left could inflate to). */
uint64_t vx_imp_left_max(const vx_imp_src *s);
/* vx_imp_need: VX_EDATA "truncated: ..." unless vx_imp_left_max(s) >= n. */
int vx_imp_need(const vx_imp_src *s, uint64_t n, const char *what, vx_err *e);
/* vx_imp_trailing: after the samples: *more gets 1 when more than slack
 * bytes follow.  Inflates at most slack + 1 bytes, so a gzip stream that
 * ends within the slack has its CRC checked. */
int vx_imp_trailing(vx_imp_src *s, size_t slack, int *more, vx_err *e);

/* ---- files (import_src.c) ---- */

typedef struct vx_imp_file {
	unsigned char *p;
	size_t n;
	int mapped;
} vx_imp_file;

/* vx_imp_file_load: the whole file ("-": standard input) in memory, mapped
 * when it is a regular file.  VX_ENOINPUT if it cannot be opened or is
 * empty, VX_EIO on read errors.  Messages start with the path. */
int vx_imp_file_load(vx_imp_file *f, const char *path, vx_err *e);
/* vx_imp_stem: path's file name without directory and extensions
 * ("a/b.vtk.gz" -> "b"), at most cap - 1 bytes (imported meshes are named
 * so). */
void vx_imp_stem(const char *path, char *out, size_t cap);
void vx_imp_file_free(vx_imp_file *f);

/* ---- frames (import_conv.c) ---- */

typedef struct vx_imp_frame {
	double spacing[3], origin[3];
	int flip[3];                  /* reverse the samples along this axis */
} vx_imp_frame;

/* vx_imp_frame_axes: spacing and origin from per-axis world steps col[a]
 * (col[a][w]: world axis w) and the world position of sample 0; see
 * vx_import.h for the rules (axis-aligned, negative steps mirror).  what
 * names the field in messages ("space directions"). */
int vx_imp_frame_axes(vx_imp_frame *f, const double col[3][3], const double org[3],
    const int64_t dims[3], const char *what, vx_err *e);
/* vx_imp_frame_plain: spacing sp (each finite and nonzero), origin org. */
int vx_imp_frame_plain(vx_imp_frame *f, const double sp[3], const double org[3],
    const int64_t dims[3], const char *what, vx_err *e);

/* ---- samples into a grid (import_conv.c) ---- */

typedef struct vx_imp_conv {
	vx_grid *g;
	vx_scalar st;
	size_t ss;                    /* source sample size */
	int swap;                     /* source byte order differs from host */
	int scale;                    /* apply v * slope + inter (f32 target) */
	double slope, inter;
	int flip[3], anyflip;
	uint64_t next, total;         /* samples placed, expected */
	uint64_t stop;                /* read calls stop at this sample
	                                 (total unless a reader reads the
	                                 samples in pieces) */
	int64_t x, y, z;              /* file position of sample `next` */
	unsigned char *tmp;           /* staging buffers */
	void *out;
} vx_imp_conv;

/* vx_imp_conv_begin: allocate g (dims, the target type of st) with f's
 * spacing, origin and flips.  big_endian: the source byte order.  scale,
 * when not NULL, is {slope, intercept}: samples become v * slope +
 * intercept, stored as f32. */
int vx_imp_conv_begin(vx_imp_conv *c, vx_grid *g, const int64_t dims[3],
    vx_scalar st, int big_endian, const vx_imp_frame *f, const double *scale,
    vx_err *e);
#define IMP_STAGE ((size_t)1 << 16)  /* samples per staging batch; c->tmp
                                        holds IMP_STAGE * 8 bytes */

/* vx_imp_conv_binary: read the bytes of samples next .. stop from s and place
 * them. */
int vx_imp_conv_binary(vx_imp_conv *c, vx_imp_src *s, vx_err *e);
/* vx_imp_conv_ascii: parse samples next .. stop as whitespace- (or comma-)
 * separated numbers from s; integer types must get integers in range. */
int vx_imp_conv_ascii(vx_imp_conv *c, vx_imp_src *s, vx_err *e);
/* vx_imp_conv_bytes: place k decoded-but-raw source samples (in src byte
 * order) from p; used by readers that decode text into bytes (hex). */
int vx_imp_conv_bytes(vx_imp_conv *c, const unsigned char *p, size_t k, vx_err *e);
/* vx_imp_conv_end: check all samples arrived, compute the range, free the
 * staging buffers.  On any error the caller frees the grid. */
int vx_imp_conv_end(vx_imp_conv *c, vx_err *e);
void vx_imp_conv_abort(vx_imp_conv *c);

/* vx_imp_total: samples of dims, checked against VX_GRID_MAX_SAMPLES; *bytes
 * gets total * size.  Messages name `what`. */
int vx_imp_total(const int64_t dims[3], size_t size, uint64_t *total,
    uint64_t *bytes, const char *what, vx_err *e);

/* VX_IMP_INT_MAX: the largest magnitude of an integer in a mesh file
 * (tags, counts, indices): sums and differences of two stay in int64_t. */
#define VX_IMP_INT_MAX ((int64_t)1 << 62)

/* vx_imp_mesh_values: m->val (m->npoint floats, allocated here) from the
 * doubles val.  VX_EDATA, with the point's index in *bad and e left for
 * the caller to fill, when a finite value lies beyond the float range;
 * VX_ENOMEM. */
struct vx_tetmesh;
int vx_imp_mesh_values(struct vx_tetmesh *m, const double *val, size_t *bad,
    vx_err *e);

/* vx_imp_vtk_types: the data type names of VTK legacy files (any ASCII
 * case), as source sample types. */
extern const vx_enum vx_imp_vtk_types;

/* ---- text (import_text.c) ---- */

/* vx_imp_trim: strip leading and trailing blanks (space, tab, CR) of [*p, *p+*n). */
void vx_imp_trim(const char **p, size_t *n);
/* vx_imp_numbers: up to max numbers separated by blanks or commas in
 * [p, p+n); *count gets how many; -1 if a word is not a number (vx_scan.h's
 * grammar, nan and inf allowed). */
int vx_imp_numbers(const char *p, size_t n, double *v, int max, int *count);
/* vx_imp_show: a printable excerpt of [p, p+n) for messages (static buffer,
 * at most 40 characters). */
const char *vx_imp_show(const char *p, size_t n);
/* vx_imp_join: dir + "/" + name (name as is when absolute or dir NULL);
 * malloc'ed, NULL on overflow or no memory. */
char *vx_imp_join(const char *dir, const char *name, size_t namelen);

#endif
