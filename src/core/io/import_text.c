/* import_text.c: small text helpers of the importers' headers (the
 * scanner and the numbers are vx_scan.h's). */
#include "import_priv.h"
#include "vx_scan.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

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
		if (*count == max ||
		    vx_num_f64(p + s, i - s, VX_NUM_NONFINITE, &v[*count]) != 0)
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
