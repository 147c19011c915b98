/* vx_stream.h: the voxlux chunked stream (formats/stream.md is the spec).
 *
 *   signature  89 56 58 4C 0D 0A 1A 0A   ("\x89VXL\r\n\x1a\n")
 *   chunk      type[4] | length u64 LE | payload | CRC-32(type+payload) u32 LE
 *   ...        last chunk: "VEND", length 0
 *
 * A stream is read whole into memory as a list of chunks (the end chunk is not
 * kept; the writer adds it).  Chunk payloads of content kinds are a text
 * header ("key: value" lines, then an empty line) followed by a body whose
 * encoding (raw or zlib) the header names; see vx_hdr and vx_body below. */
#ifndef VX_STREAM_H
#define VX_STREAM_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "vx_err.h"

#define VX_SIGNATURE "\x89VXL\r\n\x1a\n"
#define VX_SIGNATURE_LEN 8

/* Chunk types of the registry (formats/stream.md, "Chunk kinds"). */
#define VX_CHUNK_VOLUME   "VOLM" /* scalar volume: header + samples */
#define VX_CHUNK_IMAGE    "IMAG" /* float image */
#define VX_CHUNK_SCENE    "SCNE" /* scene description (text) */
#define VX_CHUNK_MACRO    "MCEL" /* multilevel min/max macrocells */
#define VX_CHUNK_TETMESH  "TETM" /* tetrahedral mesh */
#define VX_CHUNK_TETLEAF  "TLEF" /* a tet mesh's leaf grid and levels */
#define VX_CHUNK_IRRAD    "IRRV" /* irradiance volume (irradiance.md) */
#define VX_CHUNK_SHXFER   "SHTV" /* SH transfer volume (irradiance.md) */
#define VX_CHUNK_SHLIGHT  "SHLC" /* SH lighting (shlight.md) */
#define VX_CHUNK_END      "VEND" /* end of stream, empty */
#define VX_CHUNK_HISTORY  "hist" /* ancillary: one line per tool run */
#define VX_CHUNK_NOTE     "note" /* ancillary: free text */

/* Hard ceilings.  A chunk may claim up to VX_CHUNK_MAX bytes; memory is only
 * committed as payload bytes actually arrive, so a lying length costs at most
 * what the input really holds (plus slack).  Headers are small by rule. */
#define VX_CHUNK_MAX   ((uint64_t)1 << 40)   /* 1 TiB */
#define VX_HDR_MAX     ((size_t)1 << 16)     /* text header: 64 KiB */

typedef struct vx_chunk {
	char type[5];           /* 4 ASCII letters + NUL */
	uint64_t offset;        /* byte offset of the chunk in its input; 0 if new */
	size_t len;             /* payload length */
	unsigned char *data;    /* payload, owned by the chunk (may be NULL if len 0) */
	uint32_t crc;           /* the chunk's CRC, when crc_known */
	int crc_known;          /* 1: crc was read and checked with the payload
	                           (vx_stream_read); code that changes data in
	                           place sets it to 0 */
} vx_chunk;

typedef struct vx_stream {
	vx_chunk *chunk;        /* chunks in stream order, end chunk excluded */
	size_t n, cap;
	uint64_t max_chunk;     /* reader limit; 0 means VX_CHUNK_MAX */
} vx_stream;

/* Byte source for the reader: fill buf with up to n bytes, return count read,
 * 0 at end of input, or -1 on error (then errno is set). */
typedef long (*vx_read_fn)(void *ctx, void *buf, size_t n);

void vx_stream_init(vx_stream *s);
void vx_stream_free(vx_stream *s);

/* vx_stream_read: read a whole stream from f.  Checks signature, lengths
 * (before allocating), CRC of every chunk, rejects unknown critical chunks,
 * requires the end chunk.  Returns 0 or an error code (VX_EDATA for bad data,
 * VX_EIO for read errors, VX_ENOINPUT for empty input). */
int vx_stream_read(vx_stream *s, FILE *f, vx_err *e);
int vx_stream_read_fn(vx_stream *s, vx_read_fn fn, void *ctx, vx_err *e);
int vx_stream_read_mem(vx_stream *s, const void *buf, size_t n, vx_err *e);

/* vx_stream_write: write signature, all chunks, end chunk.  Does not close f
 * but does fflush it and checks ferror.  A chunk with an invalid type, a VEND
 * chunk in the list or one longer than VX_CHUNK_MAX is VX_EINTERNAL, checked
 * before anything is written. */
int vx_stream_write(const vx_stream *s, FILE *f, vx_err *e);

/* vx_chunk_is_critical: 1 if the type's first letter is upper case. */
int vx_chunk_is_critical(const char *type);
/* vx_chunk_is_known: 1 if the type is in the registry above. */
int vx_chunk_is_known(const char *type);
/* vx_chunk_type_valid: 1 if 4 ASCII letters. */
int vx_chunk_type_valid(const char *type);

/* vx_stream_find: index of the first chunk of this type at or after start,
 * or -1. */
long vx_stream_find(const vx_stream *s, const char *type, size_t start);

/* vx_stream_append: add a chunk at the end; the stream takes ownership of
 * c->data (c is zeroed).  vx_stream_insert puts it at index i. */
int vx_stream_append(vx_stream *s, vx_chunk *c, vx_err *e);
int vx_stream_insert(vx_stream *s, size_t i, vx_chunk *c, vx_err *e);
/* vx_stream_replace: free chunk i's payload and put c there. */
void vx_stream_replace(vx_stream *s, size_t i, vx_chunk *c);
/* vx_stream_remove: free and remove chunk i. */
void vx_stream_remove(vx_stream *s, size_t i);

/* vx_stream_history_add: append one line (no newline inside) to the history
 * chunk, creating it at the front of the stream when absent. */
int vx_stream_history_add(vx_stream *s, const char *line, vx_err *e);
/* vx_stream_history: the history text (lines separated by '\n'), or NULL.
 * Points into the chunk, which is not NUL-terminated: *len gets the length. */
const char *vx_stream_history(const vx_stream *s, size_t *len);

void vx_chunk_free(vx_chunk *c);

/* CRC-32 (ISO-HDLC, as in PNG and zlib) of type + payload. */
uint32_t vx_chunk_crc(const char *type, const void *data, size_t len);
/* vx_chunk_crc_of: chunk c's CRC: the one read with it while crc_known (no
 * pass over the payload), else computed */
uint32_t vx_chunk_crc_of(const vx_chunk *c);

/* ---- text headers: "key: value\n" lines, ended by an empty line ---- */

typedef struct vx_hdr {
	size_t n, cap;
	char **key;
	char **val;
} vx_hdr;

void vx_hdr_init(vx_hdr *h);
void vx_hdr_free(vx_hdr *h);

/* vx_hdr_parse: parse the header at the start of a payload.  Keys are
 * [a-z0-9_-]+, a line is "key: value" or "key:" (empty value), values are
 * UTF-8; the header ends at the first empty line; *body gets the offset of
 * the byte after it.  Duplicate keys, lines without ": ", invalid UTF-8, NUL
 * bytes, a header (empty line included) longer than VX_HDR_MAX and a missing
 * empty line are errors (VX_EDATA). */
int vx_hdr_parse(vx_hdr *h, const unsigned char *p, size_t n, size_t *body,
    vx_err *e);
/* vx_hdr_get: value for key or NULL. */
const char *vx_hdr_get(const vx_hdr *h, const char *key);
/* vx_hdr_set: set key to a formatted value (replacing an existing one).
 * A key outside [a-z0-9_-]+ or a value with a newline is VX_EINTERNAL (a
 * bug in the caller), a value that is not UTF-8 is VX_EDATA. */
int vx_hdr_set(vx_hdr *h, const char *key, vx_err *e, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));
/* vx_hdr_set_str: set key to the string val verbatim, of any length (the
 * same checks as vx_hdr_set; the writer still bounds the whole header). */
int vx_hdr_set_str(vx_hdr *h, const char *key, const char *val, vx_err *e);

/* Typed getters: parse exactly `count` numbers separated by spaces or tabs,
 * in the grammar of formats/stream.md (decimal only: no hex, inf or nan).  A
 * missing key is an error unless the getter is *_opt (then returns 0 and
 * leaves out untouched, *found = 0). */
int vx_hdr_get_i64(const vx_hdr *h, const char *key, int64_t *out,
    size_t count, vx_err *e);
int vx_hdr_get_f64(const vx_hdr *h, const char *key, double *out,
    size_t count, vx_err *e);
int vx_hdr_get_f64_opt(const vx_hdr *h, const char *key, double *out,
    size_t count, int *found, vx_err *e);

/* ---- payloads: header + body ---- */

enum { VX_ENC_UNKNOWN = 0, VX_ENC_RAW, VX_ENC_ZLIB, VX_ENC_LAST };

/* a raw body starts at a multiple of this many bytes into its payload */
#define VX_BODY_ALIGN 16

/* vx_payload_make: fill chunk c (type, data, len) with h's text, an empty
 * line and body (n bytes), compressing with zlib at `level` (1..9) or raw when
 * level is 0; sets the "encoding" key in h accordingly.  A raw body gets a
 * "pad" line of spaces that starts it at a multiple of VX_BODY_ALIGN (a
 * "pad" key in h is not written: the writer makes its own).  A header
 * longer than VX_HDR_MAX is VX_EINTERNAL. */
int vx_payload_make(vx_chunk *c, const char *type, vx_hdr *h,
    const void *body, size_t n, int level, vx_err *e);
/* vx_payload_wrap: the same payload as vx_payload_make at level 0 (raw),
 * byte for byte, from body, a malloc'd buffer holding the n body bytes at
 * its start, which the chunk takes over (freed on error too): the buffer
 * grows in place and the body moves up behind the header, with no second
 * buffer of the body's size. */
int vx_payload_wrap(vx_chunk *c, const char *type, vx_hdr *h, void *body,
    size_t n, vx_err *e);

/* vx_payload_parse: parse c's header into h; *body / *bodylen point into c. */
int vx_payload_parse(const vx_chunk *c, vx_hdr *h, const unsigned char **body,
    size_t *bodylen, vx_err *e);

/* vx_body_fits: 0 if a body of n bytes in h's encoding can decode to
 * exactly `expect` bytes: raw must have that length, zlib at least
 * expect / VX_ZLIB_MAX_RATIO bytes; otherwise VX_EDATA (also for an unknown
 * encoding).  Call it before allocating `expect` bytes on a header's word. */
#define VX_ZLIB_MAX_RATIO 1032
int vx_body_fits(const vx_hdr *h, size_t n, size_t expect, vx_err *e);

/* vx_body_decode: decode a body whose header says encoding raw or zlib into
 * out, which must receive exactly `expect` bytes (an expect computed by the
 * caller from the header's dims, never from the compressed size). */
int vx_body_decode(const vx_hdr *h, const unsigned char *body, size_t n,
    void *out, size_t expect, vx_err *e);

/* vx_utf8_check: length of the longest prefix of p[0..n) that is valid
 * UTF-8 (RFC 3629: no overlong forms, no surrogates, at most U+10FFFF);
 * equals n when all of it is. */
size_t vx_utf8_check(const void *p, size_t n);

/* Little-endian helpers and host order. */
int vx_host_is_le(void);
void vx_swap_bytes(void *p, size_t count, size_t width);
uint64_t vx_le64(const unsigned char *p);
uint32_t vx_le32(const unsigned char *p);
void vx_put_le64(unsigned char *p, uint64_t v);
void vx_put_le32(unsigned char *p, uint32_t v);

#endif
