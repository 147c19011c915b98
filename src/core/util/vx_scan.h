/* vx_scan.h: reading text: the number grammar every text format of the
 * library shares, and a bounded scanner (lines, blank-separated words) over
 * bytes that need not end in a NUL.  Scene files, stream headers and the
 * importers' headers and ASCII data all read through these.
 *
 * Numbers are decimal and read as in the C locale whatever LC_NUMERIC says
 * (a '.' is the decimal point, vx_strtod rounds correctly):
 *   integer  [+-]?[0-9]+
 *   real     [+-]?([0-9]+(\.[0-9]*)?|\.[0-9]+)([eE][+-]?[0-9]+)?
 * nothing else: no blanks around the number, no hexadecimal, no decimal
 * comma, no "inf" or "nan" (unless VX_NUM_NONFINITE asks for them).  A real
 * beyond the range of a double is an error, never taken as an infinity; one
 * below the smallest double rounds to a subnormal or to zero, so a number
 * written with %.17g always reads back. */
#ifndef VX_SCAN_H
#define VX_SCAN_H

#include <stddef.h>
#include <stdint.h>

/* ---- numbers ---- */

#define VX_NUM_MAX 400          /* characters of a real at most */
#define VX_NUM_NONFINITE 1      /* flag: also nan, inf and infinity, in any
                                   case, with an optional sign */

/* vx_num_f64: the real that the n bytes at p spell; 0, or -1 when they are
 * not one (outside the grammar, longer than VX_NUM_MAX, or too large). */
int vx_num_f64(const char *p, size_t n, int flags, double *v);

/* vx_num_i64: the integer that the n bytes at p spell, in [lo, hi]; 0, or
 * -1 when they are not one or it lies outside (any length of digits is
 * read; overflow is outside). */
int vx_num_i64(const char *p, size_t n, int64_t lo, int64_t hi, int64_t *v);

/* ---- words ---- */

/* vx_blank: space, tab, CR, LF, FF or VT. */
int vx_blank(int c);

/* vx_word_eq: the n bytes at p are word (case folded in ASCII when fold). */
int vx_word_eq(const char *p, size_t n, const char *word, int fold);

/* ---- the scanner ---- */

typedef struct vx_scan {
	const unsigned char *base, *p, *end;   /* the text, the position */
} vx_scan;

void vx_scan_init(vx_scan *s, const void *buf, size_t n);

/* vx_scan_left: bytes after the position. */
size_t vx_scan_left(const vx_scan *s);

/* vx_scan_lineno: the 1-based line of the position (counted when asked:
 * for messages). */
size_t vx_scan_lineno(const vx_scan *s);

/* vx_scan_skip_blank: past blanks, newlines included. */
void vx_scan_skip_blank(vx_scan *s);

/* vx_scan_eol: past blanks other than newlines; 1 if the line (or the text)
 * ends there.  The newline is not consumed. */
int vx_scan_eol(vx_scan *s);

/* vx_scan_next_line: past the next newline: 1, or 0 when the text ends
 * first (the position is then its end). */
int vx_scan_next_line(vx_scan *s);

/* vx_scan_line: the line at the position, without its "\n" or "\r\n", and
 * the position past it; 1, or 0 when no line is left.  A last line without
 * a newline counts only when at_end says the buffer holds the whole text
 * (a window of a longer input may end inside a line). */
int vx_scan_line(vx_scan *s, int at_end, const char **line, size_t *len);

/* vx_scan_word: the next run of non-blank bytes, on any line: its start in
 * *w and its length, 0 at the end of the text.  vx_scan_word_line: the same
 * on the current line only (0 at its end; the newline is not consumed). */
size_t vx_scan_word(vx_scan *s, const char **w);
size_t vx_scan_word_line(vx_scan *s, const char **w);

/* vx_scan_token: the next word copied into t (cap bytes with the NUL); its
 * length, 0 at the end, -1 when it does not fit (it is passed, t is ""). */
int vx_scan_token(vx_scan *s, char *t, size_t cap);

/* vx_scan_f64, vx_scan_i64: the next word as a number (vx_num_f64,
 * vx_num_i64); 0, or -1 at the end or when it is not one. */
int vx_scan_f64(vx_scan *s, int flags, double *v);
int vx_scan_i64(vx_scan *s, int64_t lo, int64_t hi, int64_t *v);

#endif
