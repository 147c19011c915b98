/* vx_enum.h: names of enumerated values, one table per enumeration.
 *
 * A table lists each value's name, then any aliases (more names with the
 * same value), and ends with an entry whose name is NULL and whose value
 * is the one an unknown name maps to:
 *
 *	static const vx_enum_name proj_names[] = {
 *		{ "perspective", VX_PERSPECTIVE },
 *		{ "orthographic", VX_ORTHOGRAPHIC },
 *		{ "ortho", VX_ORTHOGRAPHIC },
 *		{ NULL, VX_PROJECTION_UNKNOWN }
 *	};
 *	const vx_enum vx_projection_enum = { "projection", proj_names,
 *	    "unknown", 0 };
 *
 * The first entry of a value gives its name; aliases are only read.  One
 * lookup each way and one list of the valid names for messages serve
 * every enumeration of the library and its programs. */
#ifndef VX_ENUM_H
#define VX_ENUM_H

#include <stddef.h>

#include "vx_err.h"

typedef struct vx_enum_name {
	const char *name;
	int value;
} vx_enum_name;

typedef struct vx_enum {
	const char *what;          /* what a name names, in messages: "view" */
	const vx_enum_name *names; /* up to the entry with a NULL name */
	const char *unknown;       /* vx_enum_str of a value not listed */
	int fold;                  /* 1: names match in any ASCII case */
} vx_enum;

/* vx_enum_str: the name of value (its first entry), or en->unknown. */
const char *vx_enum_str(const vx_enum *en, int value);

/* vx_enum_val: the value named by s (a name or an alias), or the value of
 * the table's NULL entry.  vx_enum_val_n: the same for the n bytes at p
 * (not NUL-terminated; a NUL among them matches nothing). */
int vx_enum_val(const vx_enum *en, const char *s);
int vx_enum_val_n(const vx_enum *en, const char *p, size_t n);

/* vx_enum_list: the names, aliases left out, in table order, as "a, b, c"
 * into buf (size bytes, size >= 4), ending in "..." when they do not fit;
 * returns buf. */
const char *vx_enum_list(const vx_enum *en, char *buf, size_t size);

/* vx_enum_parse: *value = the value named by s; 0 on success, else code
 * with the message "unknown WHAT 'S' (one of: a, b, c)". */
int vx_enum_parse(const vx_enum *en, const char *s, int *value, int code,
    vx_err *e);

#endif
