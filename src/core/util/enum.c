/* enum.c: names of enumerated values (vx_enum.h). */
#include "vx_enum.h"
#include "vx_scan.h"

#include <stdio.h>
#include <string.h>

const char *
vx_enum_str(const vx_enum *en, int value)
{
	const vx_enum_name *k;

	for (k = en->names; k->name != NULL; k++)
		if (k->value == value)
			return k->name;
	return en->unknown;
}

int
vx_enum_val_n(const vx_enum *en, const char *p, size_t n)
{
	const vx_enum_name *k;

	for (k = en->names; k->name != NULL; k++)
		if (vx_word_eq(p, n, k->name, en->fold))
			return k->value;
	return k->value;
}

int
vx_enum_val(const vx_enum *en, const char *s)
{
	return vx_enum_val_n(en, s, strlen(s));
}

const char *
vx_enum_list(const vx_enum *en, char *buf, size_t size)
{
	const vx_enum_name *k, *j;
	size_t m = 0, keep = 0;    /* keep: whole names that leave room for
	                              ", ..." */

	buf[0] = '\0';
	for (k = en->names; k->name != NULL; k++) {
		size_t need;

		for (j = en->names; j < k && j->value != k->value; j++)
			;
		if (j < k)
			continue;               /* an alias */
		need = strlen(k->name) + (m > 0 ? 2 : 0);
		if (m + need >= size) {
			memcpy(buf + keep, keep > 0 ? ", ..." : "...",
			    keep > 0 ? 6 : 4);
			return buf;
		}
		m += (size_t)snprintf(buf + m, size - m, "%s%s", m > 0 ? ", " :
		    "", k->name);
		if (m + 6 <= size)
			keep = m;
	}
	return buf;
}

int
vx_enum_parse(const vx_enum *en, const char *s, int *value, int code,
    vx_err *e)
{
	const vx_enum_name *k;
	char list[256];

	for (k = en->names; k->name != NULL; k++)
		if (vx_word_eq(s, strlen(s), k->name, en->fold)) {
			*value = k->value;
			return 0;
		}
	return vx_err_set(e, code, "unknown %s '%.40s' (one of: %s)", en->what,
	    s, vx_enum_list(en, list, sizeof list));
}
