/* file.c: whole files into memory, bounded. */
#include "vx_file.h"
#include <errno.h>
#include <stdlib.h>
#include <string.h>

int
vx_file_read_all(FILE *f, size_t max, unsigned char **buf, size_t *n,
    vx_err *e)
{
	unsigned char *p = NULL, *q;
	size_t len = 0, cap = 0, got;

	*buf = NULL;
	*n = 0;
	for (;;) {
		if (len == cap) {
			size_t ncap = cap ? cap * 2 : 65536;

			if (cap > max)
				break;
			if ((q = realloc(p, ncap)) == NULL) {
				free(p);
				return vx_err_set(e, VX_ENOMEM, "out of memory "
				    "reading input");
			}
			p = q;
			cap = ncap;
		}
		got = fread(p + len, 1, cap - len, f);
		len += got;
		if (got == 0)
			break;
	}
	if (ferror(f)) {
		int err = errno;

		free(p);
		return vx_err_set(e, VX_EIO, "read error: %s", strerror(err));
	}
	if (len > max) {
		free(p);
		return vx_err_set(e, VX_EDATA, "input larger than %zu bytes", max);
	}
	*buf = p;
	*n = len;
	return 0;
}
