/* scan.c: the number grammar and the text scanner (vx_scan.h). */
#include "vx_scan.h"
#include "vx_err.h"

#include <math.h>
#include <string.h>

/* ---- numbers ---- */

static int
digit(int c)
{
	return c >= '0' && c <= '9';
}

static int
lower(int c)
{
	return c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c;
}

/* real_end: the length of the real at the start of t (NUL-terminated)
 * under the grammar, or 0. */
static size_t
real_end(const char *t)
{
	const char *q = t;
	size_t d = 0;

	if (*q == '+' || *q == '-')
		q++;
	for (; digit(*q); q++)
		d++;
	if (*q == '.')
		for (q++; digit(*q); q++)
			d++;
	if (d == 0)
		return 0;
	if (*q == 'e' || *q == 'E') {
		q++;
		if (*q == '+' || *q == '-')
			q++;
		if (!digit(*q))
			return 0;
		while (digit(*q))
			q++;
	}
	return (size_t)(q - t);
}

/* nonfinite: t is [+-]?(nan|inf|infinity), any case. */
static int
nonfinite(const char *t)
{
	size_t n;

	if (*t == '+' || *t == '-')
		t++;
	n = strlen(t);
	return vx_word_eq(t, n, "nan", 1) || vx_word_eq(t, n, "inf", 1) ||
	    vx_word_eq(t, n, "infinity", 1);
}

int
vx_num_f64(const char *p, size_t n, int flags, double *v)
{
	char t[VX_NUM_MAX + 1], *end;
	double x;

	if (n == 0 || n > VX_NUM_MAX || memchr(p, '\0', n) != NULL)
		return -1;
	memcpy(t, p, n);
	t[n] = '\0';
	if (real_end(t) != n) {
		if (!(flags & VX_NUM_NONFINITE) || !nonfinite(t))
			return -1;
		x = vx_strtod(t, &end);      /* nan, inf: sign kept */
	} else {
		x = vx_strtod(t, &end);
		if (isinf(x))
			return -1;           /* overflow */
	}
	if (end != t + n)
		return -1;
	*v = x;
	return 0;
}

int
vx_num_i64(const char *p, size_t n, int64_t lo, int64_t hi, int64_t *v)
{
	uint64_t x = 0, lim = INT64_MAX;
	size_t i = 0;
	int neg = 0;
	int64_t r;

	if (n > 0 && (p[0] == '+' || p[0] == '-')) {
		neg = p[0] == '-';
		lim += neg;                   /* |INT64_MIN| */
		i = 1;
	}
	if (i == n)
		return -1;
	for (; i < n; i++) {
		unsigned d = (unsigned char)p[i] - '0';

		if (d > 9 || x > (lim - d) / 10)
			return -1;
		x = x * 10 + d;
	}
	r = !neg ? (int64_t)x : x == (uint64_t)INT64_MAX + 1 ? INT64_MIN :
	    -(int64_t)x;
	if (r < lo || r > hi)
		return -1;
	*v = r;
	return 0;
}

/* ---- words ---- */

int
vx_blank(int c)
{
	return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' ||
	    c == '\v';
}

int
vx_word_eq(const char *p, size_t n, const char *word, int fold)
{
	size_t i;

	for (i = 0; i < n; i++) {
		if (word[i] == '\0')
			return 0;
		if (fold ? lower((unsigned char)p[i]) !=
		    lower((unsigned char)word[i]) : p[i] != word[i])
			return 0;
	}
	return word[n] == '\0';
}

/* ---- the scanner ---- */

void
vx_scan_init(vx_scan *s, const void *buf, size_t n)
{
	s->base = s->p = buf;
	s->end = s->base + n;
}

size_t
vx_scan_left(const vx_scan *s)
{
	return (size_t)(s->end - s->p);
}

size_t
vx_scan_lineno(const vx_scan *s)
{
	const unsigned char *q;
	size_t n = 1;

	for (q = s->base; q < s->p; q++)
		n += *q == '\n';
	return n;
}

void
vx_scan_skip_blank(vx_scan *s)
{
	while (s->p < s->end && vx_blank(*s->p))
		s->p++;
}

int
vx_scan_eol(vx_scan *s)
{
	while (s->p < s->end && *s->p != '\n' && vx_blank(*s->p))
		s->p++;
	return s->p == s->end || *s->p == '\n';
}

int
vx_scan_next_line(vx_scan *s)
{
	const unsigned char *nl = memchr(s->p, '\n', vx_scan_left(s));

	s->p = nl != NULL ? nl + 1 : s->end;
	return nl != NULL;
}

int
vx_scan_line(vx_scan *s, int at_end, const char **line, size_t *len)
{
	const unsigned char *nl, *e;

	if (s->p == s->end)
		return 0;
	nl = memchr(s->p, '\n', vx_scan_left(s));
	if (nl == NULL && !at_end)
		return 0;
	e = nl != NULL ? nl : s->end;
	*line = (const char *)s->p;
	*len = (size_t)(e - s->p) - (e > s->p && e[-1] == '\r');
	s->p = nl != NULL ? nl + 1 : s->end;
	return 1;
}

size_t
vx_scan_word(vx_scan *s, const char **w)
{
	vx_scan_skip_blank(s);
	*w = (const char *)s->p;
	while (s->p < s->end && !vx_blank(*s->p))
		s->p++;
	return (size_t)((const char *)s->p - *w);
}

size_t
vx_scan_word_line(vx_scan *s, const char **w)
{
	if (vx_scan_eol(s)) {
		*w = (const char *)s->p;
		return 0;
	}
	return vx_scan_word(s, w);
}

int
vx_scan_token(vx_scan *s, char *t, size_t cap)
{
	const char *w;
	size_t n = vx_scan_word(s, &w);

	if (n >= cap) {
		t[0] = '\0';
		return -1;
	}
	memcpy(t, w, n);
	t[n] = '\0';
	return (int)n;
}

int
vx_scan_f64(vx_scan *s, int flags, double *v)
{
	const char *w;
	size_t n = vx_scan_word(s, &w);

	return n > 0 ? vx_num_f64(w, n, flags, v) : -1;
}

int
vx_scan_i64(vx_scan *s, int64_t lo, int64_t hi, int64_t *v)
{
	const char *w;
	size_t n = vx_scan_word(s, &w);

	return n > 0 ? vx_num_i64(w, n, lo, hi, v) : -1;
}
