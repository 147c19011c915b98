/* vx_err.h: error values of the core library.
 *
 * The core never prints and never exits.  A function that can fail takes a
 * vx_err * (last argument), fills it on failure and returns its code; 0 means
 * success.  Codes are sysexits(3) values so a tool can exit with them as is.
 * Context is prepended as the error travels up: "chunk VOLM at 120: crc
 * mismatch".  The tool prints "tool: message" and exits with e->code. */
#ifndef VX_ERR_H
#define VX_ERR_H

#include <stdarg.h>
#include <stddef.h>

enum {
	VX_OK = 0,
	VX_EUSAGE = 64,    /* bad command line */
	VX_EDATA = 65,     /* malformed or unsupported input data */
	VX_ENOINPUT = 66,  /* input missing or unreadable */
	VX_ENOMEM = 71,    /* out of memory (EX_OSERR) */
	VX_EINTERNAL = 70, /* a bug: an invariant did not hold */
	VX_ECANTCREAT = 73,/* output file cannot be created */
	VX_EIO = 74        /* read or write failed */
};

#define VX_ERR_MSG 512

typedef struct vx_err {
	int code;              /* 0 while no error was recorded */
	char msg[VX_ERR_MSG];  /* "what: why", no trailing newline */
} vx_err;

/* vx_err_set: record code and a printf-formatted message; returns code.
 * e may be NULL (the error is then only returned). */
int vx_err_set(vx_err *e, int code, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* vx_err_push: prepend "context: " to the message; returns e->code. */
int vx_err_push(vx_err *e, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

/* vx_err_clear: reset to no error. */
void vx_err_clear(vx_err *e);

/* vx_err_name: short name of a code ("data error", ...). */
const char *vx_err_name(int code);

/* Checked arithmetic for sizes that come from headers.  Return 0 on success,
 * nonzero on overflow (then *out is unspecified). */
int vx_mul_size(size_t *out, size_t a, size_t b);
int vx_add_size(size_t *out, size_t a, size_t b);

/* vx_malloc / vx_calloc: allocation with an error on failure (VX_ENOMEM). */
void *vx_malloc(size_t n, vx_err *e);
void *vx_calloc(size_t count, size_t size, vx_err *e);

/* Numbers in the C locale ('.' as decimal point), whatever the process or
 * thread locale (LC_NUMERIC) says: every number the library reads or writes
 * in text goes through these.  Thread-safe.
 * vx_strtod: strtod(3) as in the C locale: same *end and result; errno is
 * 0 or ERANGE (callers need not clear it).  Like strtod it also takes
 * hex, inf and nan: callers check their own grammar first.
 * vx_snprintf_c / vx_vsnprintf_c: snprintf(3) / vsnprintf(3) likewise. */
double vx_strtod(const char *s, char **end);
int vx_snprintf_c(char *buf, size_t n, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));
int vx_vsnprintf_c(char *buf, size_t n, const char *fmt, va_list ap)
	__attribute__((format(printf, 3, 0)));

#endif
