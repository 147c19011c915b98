/* scene_text.h: what the scene's reader and writer share (scene_parse.c,
 * scene_format.c); not installed, not part of the public API.  Numbers
 * are vx_scan.h's, finite. */
#ifndef VX_SCENE_TEXT_H
#define VX_SCENE_TEXT_H

#include <stddef.h>

/* vx_scn_quote: token t into b (n bytes with the NUL), in double quotes
 * with \" and \\ escapes when force is set or the tokenizer needs them
 * (empty, blanks, '#', quotes, backslashes, or the keywords none and auto);
 * returns the length written, or -1 when it does not fit. */
int vx_scn_quote(char *b, size_t n, const char *t, int force);

#endif
