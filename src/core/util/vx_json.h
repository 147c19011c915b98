/* vx_json.h: a small bounded JSON reader (RFC 8259) for the files other
 * programs write: ParaView's colour-map presets, 3D Slicer's .vp.json.
 *
 * The whole text is parsed into a tree of nodes held in one array (a
 * node's children follow its `first` and `next` indices).  Bounds: at
 * most max_depth nested arrays and objects, at most max_nodes values
 * (a count checked before each node is stored, so memory grows only with
 * the input, never with a count the input claims), strings of at most
 * VX_JSON_STR_MAX bytes.  Numbers follow JSON's grammar exactly (no NaN,
 * no Infinity, no hexadecimal, no leading '+' or zeros) and must lie in
 * the double range.  Strings are decoded (escapes, \u surrogate pairs)
 * into NUL-terminated UTF-8; a \u0000 escape and raw control characters
 * are refused.  A UTF-8 byte-order mark before the value is skipped;
 * anything but blanks after it is an error.  Errors (VX_EDATA) say what
 * and where: "line 3, column 14: ...". */
#ifndef VX_JSON_H
#define VX_JSON_H

#include <stddef.h>

#include "vx_err.h"

#define VX_JSON_STR_MAX ((size_t)1 << 20)

typedef enum vx_json_type {
	VX_JSON_NULL = 0, VX_JSON_FALSE, VX_JSON_TRUE, VX_JSON_NUMBER,
	VX_JSON_STRING, VX_JSON_ARRAY, VX_JSON_OBJECT
} vx_json_type;

typedef struct vx_json_node {
	vx_json_type type;
	int line;               /* 1-based line of the value's first byte */
	int first, next;        /* first child, next sibling; -1: none */
	int n;                  /* children (array items, object members) */
	double num;             /* VX_JSON_NUMBER */
	const char *str;        /* VX_JSON_STRING: decoded, NUL-terminated */
	size_t len;             /*   its length in bytes */
	const char *key;        /* a member of an object: its key, decoded */
} vx_json_node;

typedef struct vx_json {
	vx_json_node *node;     /* node[0] is the top value */
	int n, cap;
	char *pool;             /* decoded strings and keys */
	size_t pool_len, pool_cap;
} vx_json;

/* vx_json_parse: parse the n bytes at buf into j (initialized by the
 * call; on error j is left empty).  Errors: VX_EDATA (malformed, or a
 * bound passed; the message names line and column), VX_ENOMEM. */
int vx_json_parse(vx_json *j, const void *buf, size_t n, int max_depth,
    int max_nodes, vx_err *e);
/* vx_json_free: release j and leave it empty. */
void vx_json_free(vx_json *j);

/* vx_json_at: node i, or NULL for i < 0. */
const vx_json_node *vx_json_at(const vx_json *j, int i);

/* vx_json_get: the member of object obj whose key is key, or NULL when
 * none is; *dup (may be NULL) gets 1 when the key is given more than once
 * (the first is returned). */
const vx_json_node *vx_json_get(const vx_json *j, const vx_json_node *obj,
    const char *key, int *dup);

/* vx_json_type_name: "null", "false", ..., "object". */
const char *vx_json_type_name(vx_json_type t);

#endif
