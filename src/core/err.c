/* err.c: error values, checked size arithmetic, allocation with errors. */
#include "vx_err.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int
vx_err_set(vx_err *e, int code, const char *fmt, ...)
{
	va_list ap;

	if (e == NULL)
		return code;
	e->code = code;
	va_start(ap, fmt);
	vsnprintf(e->msg, sizeof e->msg, fmt, ap);
	va_end(ap);
	return code;
}

int
vx_err_push(vx_err *e, const char *fmt, ...)
{
	char ctx[VX_ERR_MSG], old[VX_ERR_MSG];
	va_list ap;

	if (e == NULL)
		return VX_EINTERNAL;
	va_start(ap, fmt);
	vsnprintf(ctx, sizeof ctx, fmt, ap);
	va_end(ap);
	memcpy(old, e->msg, sizeof old);
	size_t k = strlen(ctx);
	if (k > sizeof e->msg - 3)
		k = sizeof e->msg - 3;
	memcpy(e->msg, ctx, k);
	memcpy(e->msg + k, ": ", 2);
	k += 2;
	size_t r = strlen(old);
	if (r > sizeof e->msg - 1 - k)
		r = sizeof e->msg - 1 - k;
	memcpy(e->msg + k, old, r);
	e->msg[k + r] = '\0';
	return e->code;
}

void
vx_err_clear(vx_err *e)
{
	if (e != NULL) {
		e->code = 0;
		e->msg[0] = '\0';
	}
}

const char *
vx_err_name(int code)
{
	switch (code) {
	case VX_OK: return "ok";
	case VX_EUSAGE: return "usage error";
	case VX_EDATA: return "data error";
	case VX_ENOINPUT: return "cannot open input";
	case VX_ENOMEM: return "out of memory";
	case VX_EINTERNAL: return "internal error";
	case VX_ECANTCREAT: return "cannot create output";
	case VX_EIO: return "input/output error";
	default: return "error";
	}
}

int
vx_mul_size(size_t *out, size_t a, size_t b)
{
	if (a != 0 && b > SIZE_MAX / a)
		return 1;
	*out = a * b;
	return 0;
}

int
vx_add_size(size_t *out, size_t a, size_t b)
{
	if (b > SIZE_MAX - a)
		return 1;
	*out = a + b;
	return 0;
}

void *
vx_malloc(size_t n, vx_err *e)
{
	void *p = malloc(n ? n : 1);

	if (p == NULL)
		vx_err_set(e, VX_ENOMEM, "cannot allocate %zu bytes", n);
	return p;
}

void *
vx_calloc(size_t count, size_t size, vx_err *e)
{
	void *p = calloc(count ? count : 1, size ? size : 1);

	if (p == NULL)
		vx_err_set(e, VX_ENOMEM, "cannot allocate %zu x %zu bytes",
		    count, size);
	return p;
}
