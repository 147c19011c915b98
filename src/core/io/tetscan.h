/* tetscan.h: a bounded text scanner over a memory buffer (not necessarily
 * NUL-terminated), shared by the tet mesh importers.  Internal: not
 * installed.  Tokens are runs of non-blank bytes; numbers are parsed from
 * a token copied into a small local buffer, so nothing reads past the end. */
#ifndef VX_TETSCAN_H
#define VX_TETSCAN_H

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define SCAN_TOK 256

typedef struct scan {
	const unsigned char *base, *p, *end;
} scan;

static inline int
scan_blank(int c)
{
	return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' ||
	    c == '\v';
}

static inline void
scan_init(scan *s, const void *buf, size_t n)
{
	s->base = s->p = buf;
	s->end = s->base + n;
}

/* 1-based line number of the scanner's position (counted on demand). */
static inline size_t
scan_line(const scan *s)
{
	size_t n = 1;
	for (const unsigned char *q = s->base; q < s->p; q++)
		n += *q == '\n';
	return n;
}

static inline size_t
scan_left(const scan *s)
{
	return (size_t)(s->end - s->p);
}

static inline void
scan_skip_blank(scan *s)
{
	while (s->p < s->end && scan_blank(*s->p))
		s->p++;
}

/* Skip blanks other than newlines. */
static inline void
scan_skip_space(scan *s)
{
	while (s->p < s->end && *s->p != '\n' && scan_blank(*s->p))
		s->p++;
}

/* 1 if only blanks remain on the current line (or at the end). */
static inline int
scan_eol(scan *s)
{
	scan_skip_space(s);
	return s->p >= s->end || *s->p == '\n';
}

/* Move past the next newline (or to the end). */
static inline void
scan_next_line(scan *s)
{
	while (s->p < s->end && *s->p != '\n')
		s->p++;
	if (s->p < s->end)
		s->p++;
}

/* scan_token: copy the next token (after any blanks, newlines included)
 * into t (SCAN_TOK bytes, NUL-terminated).  Returns its length, 0 at the end
 * of input, -1 when it is longer than SCAN_TOK - 1 (then skipped). */
static inline int
scan_token(scan *s, char *t)
{
	size_t k = 0;

	scan_skip_blank(s);
	while (s->p < s->end && !scan_blank(*s->p)) {
		if (k < SCAN_TOK - 1)
			t[k] = (char)*s->p;
		k++;
		s->p++;
	}
	if (k >= SCAN_TOK) {
		t[0] = '\0';
		return -1;
	}
	t[k] = '\0';
	return (int)k;
}

/* scan_token_line: the next token on the current line only; 0 at the end
 * of the line (the newline is not consumed). */
static inline int
scan_token_line(scan *s, char *t)
{
	if (scan_eol(s)) {
		t[0] = '\0';
		return 0;
	}
	return scan_token(s, t);
}

/* Numbers: 1 on success; 0 at the end of input or on a malformed token. */
static inline int
scan_parse_double(const char *t, double *v)
{
	char *q;

	if (t[0] == '\0')
		return 0;
	*v = vx_strtod(t, &q);
	/* overflow is malformed, as everywhere (underflow rounds) */
	return *q == '\0' && !(errno == ERANGE && isinf(*v));
}

static inline int
scan_parse_i64(const char *t, int64_t *v)
{
	const char *q = t;
	uint64_t x = 0;
	int neg = 0;

	if (*q == '-' || *q == '+')
		neg = *q++ == '-';
	if (*q == '\0')
		return 0;
	for (; *q; q++) {
		if (*q < '0' || *q > '9' || x > (UINT64_C(1) << 62))
			return 0;
		x = x * 10 + (uint64_t)(*q - '0');
	}
	if (x > (UINT64_C(1) << 62))
		return 0;
	*v = neg ? -(int64_t)x : (int64_t)x;
	return 1;
}

static inline int
scan_double(scan *s, double *v)
{
	char t[SCAN_TOK];
	return scan_token(s, t) > 0 && scan_parse_double(t, v);
}

static inline int
scan_i64(scan *s, int64_t *v)
{
	char t[SCAN_TOK];
	return scan_token(s, t) > 0 && scan_parse_i64(t, v);
}

/* Case-insensitive keyword comparison. */
static inline int
scan_is(const char *t, const char *kw)
{
	return strcasecmp(t, kw) == 0;
}

#endif
