/* scene_text.h: helpers the scene modules share (scene.c, scene_parse.c,
 * scene_format.c); not installed, not part of the public API. */
#ifndef VX_SCENE_TEXT_H
#define VX_SCENE_TEXT_H

#include <stddef.h>

/* vx_scn_number: a finite double written as [+-]digits[.digits]
 * [e[+-]digits], read in the C locale whatever the process locale; 0 on
 * success, -1 otherwise (hex, inf, nan, overflow, trailing bytes). */
int vx_scn_number(const char *t, double *out);

/* vx_scn_int: a decimal integer in [lo, hi]; 0 on success. */
int vx_scn_int(const char *t, long lo, long hi, long *out);

/* vx_scn_quote: token t into b (n bytes with the NUL), in double quotes
 * with \" and \\ escapes when force is set or the tokenizer needs them
 * (empty, blanks, '#', quotes, backslashes, or the keywords none and auto);
 * returns the length written, or -1 when it does not fit. */
int vx_scn_quote(char *b, size_t n, const char *t, int force);

#endif
