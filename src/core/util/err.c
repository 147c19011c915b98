/* err.c: error values, checked size arithmetic, allocation with errors,
 * numbers read and written in the C locale. */
#include "vx_err.h"

#include <errno.h>
#include <locale.h>
#include <pthread.h>
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

/* ---- numbers in the C locale ----
 *
 * Stream headers, scene files, NRRD and PFM headers write numbers with a
 * '.', but strtod and printf follow LC_NUMERIC, which a program linking the
 * library may set (a decimal comma under de_DE).  How: a "C" locale object,
 * made once, installed for the calling thread around each strtod/vsnprintf
 * with uselocale (POSIX.1-2008).  Not setlocale (process-wide, races with
 * other threads), not rewriting '.' into localeconv()'s decimal point (not
 * thread-safe either), not a hand-written strtod (correct rounding needs
 * big-number arithmetic: glibc's strtod is exact).  Should the locale
 * object be impossible to make (out of memory), the thread's own locale is
 * used, as before. */

static locale_t c_locale;
static pthread_once_t c_once = PTHREAD_ONCE_INIT;

static void
c_locale_make(void)
{
	c_locale = newlocale(LC_ALL_MASK, "C", (locale_t)0);
}

/* c_locale_enter: install the C locale for this thread; returns what to
 * give c_locale_leave (0: nothing was changed). */
static locale_t
c_locale_enter(void)
{
	pthread_once(&c_once, c_locale_make);
	if (c_locale == (locale_t)0)
		return (locale_t)0;
	return uselocale(c_locale);
}

static void
c_locale_leave(locale_t old)
{
	int saved = errno;

	if (old != (locale_t)0)
		uselocale(old);
	errno = saved;
}

double
vx_strtod(const char *s, char **end)
{
	locale_t old = c_locale_enter();
	double v;

	errno = 0;
	v = strtod(s, end);
	c_locale_leave(old);
	return v;
}

int
vx_vsnprintf_c(char *buf, size_t n, const char *fmt, va_list ap)
{
	locale_t old = c_locale_enter();
	int k = vsnprintf(buf, n, fmt, ap);

	c_locale_leave(old);
	return k;
}

int
vx_snprintf_c(char *buf, size_t n, const char *fmt, ...)
{
	va_list ap;
	int k;

	va_start(ap, fmt);
	k = vx_vsnprintf_c(buf, n, fmt, ap);
	va_end(ap);
	return k;
}
