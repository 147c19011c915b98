/* import_text.c: small text helpers for the importers' headers: lines,
 * case-insensitive words, numbers from buffers that are not NUL-terminated. */
#include "import_priv.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int
vx_imp_word_eq(const char *p, size_t n, const char *word)
{
	size_t i;

	if (strlen(word) != n)
		return 0;
	for (i = 0; i < n; i++)
		if (tolower((unsigned char)p[i]) !=
		    tolower((unsigned char)word[i]))
			return 0;
	return 1;
}

static int
blank(char c)
{
	return c == ' ' || c == '\t' || c == '\r';
}

void
vx_imp_trim(const char **p, size_t *n)
{
	while (*n > 0 && blank(**p)) {
		(*p)++;
		(*n)--;
	}
	while (*n > 0 && blank((*p)[*n - 1]))
		(*n)--;
}

int
vx_imp_next_line(const unsigned char *p, size_t n, size_t *pos, int at_end,
    const char **line, size_t *len)
{
	const unsigned char *nl;
	size_t start = *pos, end;

	if (start >= n)
		return 0;
	nl = memchr(p + start, '\n', n - start);
	if (nl == NULL) {
		if (!at_end)
			return 0;
		end = n;
		*pos = n;
	} else {
		end = (size_t)(nl - p);
		*pos = end + 1;
	}
	if (end > start && p[end - 1] == '\r')
		end--;
	*line = (const char *)p + start;
	*len = end - start;
	return 1;
}

/* token: copy [p, p+n) into a NUL-terminated buffer (short tokens only). */
static int
token(const char *p, size_t n, char *buf, size_t cap)
{
	vx_imp_trim(&p, &n);
	if (n == 0 || n >= cap)
		return -1;
	memcpy(buf, p, n);
	buf[n] = '\0';
	return 0;
}

int
vx_imp_parse_i64(const char *p, size_t n, int64_t *v)
{
	char buf[64], *end;
	long long x;

	if (token(p, n, buf, sizeof buf) != 0)
		return -1;
	errno = 0;
	x = strtoll(buf, &end, 10);
	if (end == buf || *end != '\0' || errno == ERANGE)
		return -1;
	*v = x;
	return 0;
}

int
vx_imp_parse_f64(const char *p, size_t n, double *v)
{
	char buf[64], *end;
	double x;

	if (token(p, n, buf, sizeof buf) != 0)
		return -1;
	x = vx_strtod(buf, &end);
	if (end == buf || *end != '\0' || (errno == ERANGE && isinf(x)))
		return -1;
	*v = x;
	return 0;
}

int
vx_imp_numbers(const char *p, size_t n, double *v, int max, int *count)
{
	size_t i = 0;

	*count = 0;
	for (;;) {
		size_t s;

		while (i < n && (blank(p[i]) || p[i] == ','))
			i++;
		if (i == n)
			return 0;
		s = i;
		while (i < n && !blank(p[i]) && p[i] != ',')
			i++;
		if (*count == max)
			return -1;
		if (vx_imp_parse_f64(p + s, i - s, &v[*count]) != 0)
			return -1;
		(*count)++;
	}
}

const char *
vx_imp_show(const char *p, size_t n)
{
	static _Thread_local char buf[48];
	size_t i, k = 0;

	for (i = 0; i < n && k < 40; i++)
		buf[k++] = isprint((unsigned char)p[i]) ? p[i] : '?';
	if (i < n) {
		memcpy(buf + 37, "...", 3);
		k = 40;
	}
	buf[k] = '\0';
	return buf;
}

char *
vx_imp_join(const char *dir, const char *name, size_t namelen)
{
	size_t dl = (dir == NULL || name[0] == '/') ? 0 : strlen(dir);
	char *s;

	if (namelen > 4096 || dl > 4096 || memchr(name, '\0', namelen))
		return NULL;
	if ((s = malloc(dl + namelen + 2)) == NULL)
		return NULL;
	if (dl > 0) {
		memcpy(s, dir, dl);
		s[dl] = '/';
		memcpy(s + dl + 1, name, namelen);
		s[dl + 1 + namelen] = '\0';
	} else {
		memcpy(s, name, namelen);
		s[namelen] = '\0';
	}
	return s;
}
