/* stream.c: read and write the chunked voxlux stream; text headers; bodies. */
#include "vx_stream.h"
#include "vx_scan.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

/* zlib counts bytes in uInt; bodies are fed to it in pieces of at most
 * ZPIECE bytes each way.  Small on purpose: the unit tests cross piece
 * boundaries in both directions with bodies of a few MiB. */
#define ZPIECE ((size_t)1 << 20)

/* ---- byte order ---- */

int
vx_host_is_le(void)
{
	const uint16_t one = 1;
	unsigned char b;

	memcpy(&b, &one, 1);
	return b == 1;
}

void
vx_swap_bytes(void *p, size_t count, size_t width)
{
	unsigned char *b = p, t;
	size_t i, j;

	if (width < 2)
		return;
	for (i = 0; i < count; i++, b += width)
		for (j = 0; j < width / 2; j++) {
			t = b[j];
			b[j] = b[width - 1 - j];
			b[width - 1 - j] = t;
		}
}

uint64_t
vx_le64(const unsigned char *p)
{
	uint64_t v = 0;
	int i;

	for (i = 7; i >= 0; i--)
		v = (v << 8) | p[i];
	return v;
}

uint32_t
vx_le32(const unsigned char *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
	    (uint32_t)p[3] << 24;
}

void
vx_put_le64(unsigned char *p, uint64_t v)
{
	int i;

	for (i = 0; i < 8; i++, v >>= 8)
		p[i] = (unsigned char)(v & 0xff);
}

void
vx_put_le32(unsigned char *p, uint32_t v)
{
	int i;

	for (i = 0; i < 4; i++, v >>= 8)
		p[i] = (unsigned char)(v & 0xff);
}

/* ---- chunk types ---- */

static const char *const registry[] = {
	VX_CHUNK_VOLUME, VX_CHUNK_IMAGE, VX_CHUNK_SCENE, VX_CHUNK_MACRO,
	VX_CHUNK_TETMESH, VX_CHUNK_TETLEAF, VX_CHUNK_IRRAD, VX_CHUNK_SHXFER, VX_CHUNK_SHLIGHT,
	VX_CHUNK_END, VX_CHUNK_HISTORY, VX_CHUNK_NOTE, NULL
};

int
vx_chunk_type_valid(const char *type)
{
	int i;

	for (i = 0; i < 4; i++)
		if (!((type[i] >= 'A' && type[i] <= 'Z') ||
		    (type[i] >= 'a' && type[i] <= 'z')))
			return 0;
	return 1;
}

int
vx_chunk_is_critical(const char *type)
{
	return type[0] >= 'A' && type[0] <= 'Z';
}

int
vx_chunk_is_known(const char *type)
{
	int i;

	for (i = 0; registry[i] != NULL; i++)
		if (memcmp(registry[i], type, 4) == 0)
			return 1;
	return 0;
}

uint32_t
vx_chunk_crc(const char *type, const void *data, size_t len)
{
	uLong crc = crc32(0L, Z_NULL, 0);
	const unsigned char *p = data;

	crc = crc32(crc, (const Bytef *)type, 4);
	while (len > 0) {   /* zlib's crc32 takes a uInt length */
		uInt k = (uInt)(len > ZPIECE ? ZPIECE : len);
		crc = crc32(crc, p, k);
		p += k;
		len -= k;
	}
	return (uint32_t)crc;
}

void
vx_chunk_free(vx_chunk *c)
{
	if (c == NULL)
		return;
	free(c->data);
	memset(c, 0, sizeof *c);
}

/* ---- stream container ---- */

void
vx_stream_init(vx_stream *s)
{
	memset(s, 0, sizeof *s);
}

void
vx_stream_free(vx_stream *s)
{
	size_t i;

	if (s == NULL)
		return;
	for (i = 0; i < s->n; i++)
		vx_chunk_free(&s->chunk[i]);
	free(s->chunk);
	memset(s, 0, sizeof *s);
}

int
vx_stream_insert(vx_stream *s, size_t i, vx_chunk *c, vx_err *e)
{
	if (i > s->n)
		i = s->n;
	if (s->n == s->cap) {
		size_t cap = s->cap ? 2 * s->cap : 8;
		vx_chunk *p = realloc(s->chunk, cap * sizeof *p);

		if (p == NULL)
			return vx_err_set(e, VX_ENOMEM, "out of memory for chunk list");
		s->chunk = p;
		s->cap = cap;
	}
	memmove(&s->chunk[i + 1], &s->chunk[i], (s->n - i) * sizeof *s->chunk);
	s->chunk[i] = *c;
	s->n++;
	memset(c, 0, sizeof *c);
	return 0;
}

int
vx_stream_append(vx_stream *s, vx_chunk *c, vx_err *e)
{
	return vx_stream_insert(s, s->n, c, e);
}

void
vx_stream_replace(vx_stream *s, size_t i, vx_chunk *c)
{
	vx_chunk_free(&s->chunk[i]);
	s->chunk[i] = *c;
	memset(c, 0, sizeof *c);
}

void
vx_stream_remove(vx_stream *s, size_t i)
{
	if (i >= s->n)
		return;
	vx_chunk_free(&s->chunk[i]);
	memmove(&s->chunk[i], &s->chunk[i + 1],
	    (s->n - i - 1) * sizeof *s->chunk);
	s->n--;
}

long
vx_stream_find(const vx_stream *s, const char *type, size_t start)
{
	size_t i;

	for (i = start; i < s->n; i++)
		if (memcmp(s->chunk[i].type, type, 4) == 0)
			return (long)i;
	return -1;
}

/* ---- reading ---- */

typedef struct reader {
	vx_read_fn fn;
	void *ctx;
	uint64_t pos;
} reader;

/* get: read exactly n bytes; returns number read (short at end of input) or
 * -1 on error. */
static long
get(reader *r, void *buf, size_t n)
{
	size_t got = 0;

	while (got < n) {
		long k = r->fn(r->ctx, (char *)buf + got, n - got);

		if (k < 0)
			return -1;
		if (k == 0)
			break;
		got += (size_t)k;
	}
	r->pos += got;
	return (long)got;
}

static long
file_read(void *ctx, void *buf, size_t n)
{
	FILE *f = ctx;
	size_t k = fread(buf, 1, n, f);

	if (k == 0 && ferror(f))
		return -1;
	return (long)k;
}

typedef struct memsrc {
	const unsigned char *p;
	size_t n, pos;
} memsrc;

static long
mem_read(void *ctx, void *buf, size_t n)
{
	memsrc *m = ctx;
	size_t k = m->n - m->pos;

	if (k > n)
		k = n;
	memcpy(buf, m->p + m->pos, k);
	m->pos += k;
	return (long)k;
}

/* read_payload: read len bytes into a buffer that grows as data arrives, so a
 * length field larger than the input costs no more memory than the input. */
static int
read_payload(reader *r, uint64_t len, unsigned char **out, const char *type,
    uint64_t off, vx_err *e)
{
	unsigned char *buf = NULL, *p;
	size_t have = 0, cap = 0, want;

	*out = NULL;
	while ((uint64_t)have < len) {
		if (have == cap) {
			size_t ncap = cap ? cap * 2 : 65536;

			if ((uint64_t)ncap > len)
				ncap = (size_t)len;
			p = realloc(buf, ncap);
			if (p == NULL) {
				free(buf);
				return vx_err_set(e, VX_ENOMEM,
				    "chunk %s at %llu: cannot allocate %zu bytes",
				    type, (unsigned long long)off, ncap);
			}
			buf = p;
			cap = ncap;
		}
		want = cap - have;
		long k = get(r, buf + have, want);
		if (k < 0) {
			free(buf);
			return vx_err_set(e, VX_EIO, "chunk %s at %llu: read: %s",
			    type, (unsigned long long)off, strerror(errno));
		}
		have += (size_t)k;
		if ((size_t)k < want && (uint64_t)have < len) {
			free(buf);
			return vx_err_set(e, VX_EDATA,
			    "chunk %s at %llu: truncated stream: payload has %zu "
			    "of %llu bytes", type, (unsigned long long)off, have,
			    (unsigned long long)len);
		}
	}
	*out = buf;
	return 0;
}

int
vx_stream_read_fn(vx_stream *s, vx_read_fn fn, void *ctx, vx_err *e)
{
	reader r = { fn, ctx, 0 };
	unsigned char sig[VX_SIGNATURE_LEN], head[12], crcb[4];
	uint64_t maxc = s->max_chunk ? s->max_chunk : VX_CHUNK_MAX;
	long k;
	int rc;

	k = get(&r, sig, sizeof sig);
	if (k < 0)
		return vx_err_set(e, VX_EIO, "read: %s", strerror(errno));
	if (k == 0)
		return vx_err_set(e, VX_ENOINPUT, "empty input: no stream");
	if (k < (long)sizeof sig || memcmp(sig, VX_SIGNATURE, sizeof sig) != 0)
		return vx_err_set(e, VX_EDATA,
		    "not a voxlux stream (bad signature)");
	for (;;) {
		vx_chunk c;
		uint64_t len, off = r.pos;

		memset(&c, 0, sizeof c);
		k = get(&r, head, sizeof head);
		if (k < 0)
			return vx_err_set(e, VX_EIO, "read: %s", strerror(errno));
		if (k == 0)
			return vx_err_set(e, VX_EDATA,
			    "truncated stream: no end chunk after %llu bytes",
			    (unsigned long long)off);
		if (k < (long)sizeof head)
			return vx_err_set(e, VX_EDATA,
			    "truncated stream: partial chunk header at %llu",
			    (unsigned long long)off);
		memcpy(c.type, head, 4);
		if (!vx_chunk_type_valid(c.type))
			return vx_err_set(e, VX_EDATA,
			    "chunk at %llu: invalid type bytes %02x %02x %02x %02x",
			    (unsigned long long)off, head[0], head[1], head[2],
			    head[3]);
		len = vx_le64(head + 4);
		if (len > maxc || len > (uint64_t)SIZE_MAX)
			return vx_err_set(e, VX_EDATA,
			    "chunk %s at %llu: length %llu exceeds the limit %llu",
			    c.type, (unsigned long long)off,
			    (unsigned long long)len, (unsigned long long)maxc);
		if (vx_chunk_is_critical(c.type) && !vx_chunk_is_known(c.type))
			return vx_err_set(e, VX_EDATA,
			    "chunk %s at %llu: unknown critical chunk",
			    c.type, (unsigned long long)off);
		if (memcmp(c.type, VX_CHUNK_END, 4) == 0 && len != 0)
			return vx_err_set(e, VX_EDATA,
			    "chunk VEND at %llu: end chunk must be empty",
			    (unsigned long long)off);
		if ((rc = read_payload(&r, len, &c.data, c.type, off, e)) != 0)
			return rc;
		c.len = (size_t)len;
		c.offset = off;
		k = get(&r, crcb, 4);
		if (k != 4) {
			free(c.data);
			if (k < 0)
				return vx_err_set(e, VX_EIO, "read: %s",
				    strerror(errno));
			return vx_err_set(e, VX_EDATA,
			    "chunk %s at %llu: truncated stream: missing CRC",
			    c.type, (unsigned long long)off);
		}
		if (vx_le32(crcb) != vx_chunk_crc(c.type, c.data, c.len)) {
			free(c.data);
			return vx_err_set(e, VX_EDATA,
			    "chunk %s at %llu: CRC mismatch", c.type,
			    (unsigned long long)off);
		}
		c.crc = vx_le32(crcb);
		c.crc_known = 1;
		if (memcmp(c.type, VX_CHUNK_END, 4) == 0) {
			free(c.data);
			break;
		}
		if ((rc = vx_stream_append(s, &c, e)) != 0) {
			free(c.data);
			return rc;
		}
	}
	/* Anything after the end chunk is an error: a concatenation of two
	 * streams must not be silently half-read. */
	k = get(&r, head, 1);
	if (k > 0)
		return vx_err_set(e, VX_EDATA,
		    "trailing bytes after the end chunk at %llu",
		    (unsigned long long)(r.pos - 1));
	return 0;
}

int
vx_stream_read(vx_stream *s, FILE *f, vx_err *e)
{
	return vx_stream_read_fn(s, file_read, f, e);
}

int
vx_stream_read_mem(vx_stream *s, const void *buf, size_t n, vx_err *e)
{
	memsrc m = { buf, n, 0 };

	return vx_stream_read_fn(s, mem_read, &m, e);
}

/* ---- writing ---- */

static int
put(FILE *f, const void *p, size_t n, vx_err *e)
{
	const unsigned char *b = p;

	while (n > 0) {
		size_t k = fwrite(b, 1, n, f);

		if (k == 0)
			return vx_err_set(e, VX_EIO, "write: %s",
			    errno ? strerror(errno) : "short write");
		b += k;
		n -= k;
	}
	return 0;
}

uint32_t
vx_chunk_crc_of(const vx_chunk *c)
{
	return c->crc_known ? c->crc : vx_chunk_crc(c->type, c->data, c->len);
}

static int
write_chunk(FILE *f, const char *type, const void *data, size_t len,
    uint32_t crc, vx_err *e)
{
	unsigned char head[12], crcb[4];
	int rc;

	memcpy(head, type, 4);
	vx_put_le64(head + 4, (uint64_t)len);
	vx_put_le32(crcb, crc);
	if ((rc = put(f, head, sizeof head, e)) != 0)
		return rc;
	if (len > 0 && (rc = put(f, data, len, e)) != 0)
		return rc;
	return put(f, crcb, 4, e);
}

int
vx_stream_write(const vx_stream *s, FILE *f, vx_err *e)
{
	size_t i;
	int rc;

	/* refuse what no reader would take back */
	for (i = 0; i < s->n; i++) {
		const vx_chunk *c = &s->chunk[i];

		if (!vx_chunk_type_valid(c->type) ||
		    memcmp(c->type, VX_CHUNK_END, 4) == 0)
			return vx_err_set(e, VX_EINTERNAL, "chunk %zu: type '%.4s' "
			    "cannot be written", i, c->type);
		if ((uint64_t)c->len > VX_CHUNK_MAX)
			return vx_err_set(e, VX_EINTERNAL, "chunk %.4s: %zu bytes "
			    "exceed the limit %llu", c->type, c->len,
			    (unsigned long long)VX_CHUNK_MAX);
	}
	errno = 0;
	if ((rc = put(f, VX_SIGNATURE, VX_SIGNATURE_LEN, e)) != 0)
		return rc;
	for (i = 0; i < s->n; i++)
		if ((rc = write_chunk(f, s->chunk[i].type, s->chunk[i].data,
		    s->chunk[i].len, vx_chunk_crc_of(&s->chunk[i]), e)) != 0)
			return rc;
	if ((rc = write_chunk(f, VX_CHUNK_END, NULL, 0,
	    vx_chunk_crc(VX_CHUNK_END, NULL, 0), e)) != 0)
		return rc;
	if (fflush(f) != 0 || ferror(f))
		return vx_err_set(e, VX_EIO, "write: %s",
		    errno ? strerror(errno) : "stream error");
	return 0;
}

/* ---- history ---- */

int
vx_stream_history_add(vx_stream *s, const char *line, vx_err *e)
{
	long i = vx_stream_find(s, VX_CHUNK_HISTORY, 0);
	size_t n = strlen(line), k;
	unsigned char *p;
	vx_chunk c;

	if (i < 0) {
		memset(&c, 0, sizeof c);
		memcpy(c.type, VX_CHUNK_HISTORY, 5);
		if (vx_stream_insert(s, 0, &c, e) != 0)
			return e ? e->code : VX_ENOMEM;
		i = 0;
	}
	vx_chunk *h = &s->chunk[i];
	p = realloc(h->data, h->len + n + 1);
	if (p == NULL)
		return vx_err_set(e, VX_ENOMEM, "out of memory for history");
	memcpy(p + h->len, line, n);
	for (k = 0; k < n; k++)      /* one line per run, whatever the args */
		if (p[h->len + k] == '\n' || p[h->len + k] == '\0')
			p[h->len + k] = ' ';
	p[h->len + n] = '\n';
	h->data = p;
	h->len += n + 1;
	h->crc_known = 0;
	return 0;
}

const char *
vx_stream_history(const vx_stream *s, size_t *len)
{
	long i = vx_stream_find(s, VX_CHUNK_HISTORY, 0);

	if (i < 0) {
		*len = 0;
		return NULL;
	}
	*len = s->chunk[i].len;
	return (const char *)s->chunk[i].data;
}

/* ---- UTF-8 ---- */

size_t
vx_utf8_check(const void *buf, size_t n)
{
	const unsigned char *p = buf;
	size_t i = 0;

	while (i < n) {
		unsigned c = p[i], need, min, cp, k;

		if (c < 0x80) {
			i++;
			continue;
		}
		if (c >= 0xc2 && c <= 0xdf) {
			need = 1; min = 0x80; cp = c & 0x1f;
		} else if (c >= 0xe0 && c <= 0xef) {
			need = 2; min = 0x800; cp = c & 0x0f;
		} else if (c >= 0xf0 && c <= 0xf4) {
			need = 3; min = 0x10000; cp = c & 0x07;
		} else
			return i;      /* continuation byte, C0, C1 or F5..FF lead */
		if (n - i <= need)
			return i;
		for (k = 1; k <= need; k++) {
			if ((p[i + k] & 0xc0) != 0x80)
				return i;
			cp = cp << 6 | (p[i + k] & 0x3f);
		}
		if (cp < min || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff))
			return i;      /* overlong, beyond Unicode, surrogate */
		i += need + 1;
	}
	return n;
}

/* ---- text headers ---- */

void
vx_hdr_init(vx_hdr *h)
{
	memset(h, 0, sizeof *h);
}

void
vx_hdr_free(vx_hdr *h)
{
	size_t i;

	if (h == NULL)
		return;
	for (i = 0; i < h->n; i++) {
		free(h->key[i]);
		free(h->val[i]);
	}
	free(h->key);
	free(h->val);
	memset(h, 0, sizeof *h);
}

const char *
vx_hdr_get(const vx_hdr *h, const char *key)
{
	size_t i;

	for (i = 0; i < h->n; i++)
		if (strcmp(h->key[i], key) == 0)
			return h->val[i];
	return NULL;
}

/* key_char: the key alphabet, [a-z0-9_-], whatever the C locale says. */
static int
key_char(unsigned char c)
{
	return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
	    c == '-';
}

static int
hdr_put(vx_hdr *h, const char *key, size_t klen, const char *val,
    size_t vlen, int replace, vx_err *e)
{
	size_t i;
	char *v;

	for (i = 0; i < h->n; i++)
		if (strncmp(h->key[i], key, klen) == 0 &&
		    h->key[i][klen] == '\0') {
			if (!replace)
				return vx_err_set(e, VX_EDATA,
				    "header: duplicate key '%.*s'", (int)klen, key);
			if ((v = strndup(val, vlen)) == NULL)
				return vx_err_set(e, VX_ENOMEM, "header: out of memory");
			free(h->val[i]);
			h->val[i] = v;
			return 0;
		}
	if (h->n == h->cap) {
		size_t cap = h->cap ? 2 * h->cap : 16;
		char **k = realloc(h->key, cap * sizeof *k);

		if (k == NULL)
			return vx_err_set(e, VX_ENOMEM, "header: out of memory");
		h->key = k;
		k = realloc(h->val, cap * sizeof *k);
		if (k == NULL)
			return vx_err_set(e, VX_ENOMEM, "header: out of memory");
		h->val = k;
		h->cap = cap;
	}
	h->key[h->n] = strndup(key, klen);
	h->val[h->n] = strndup(val, vlen);
	if (h->key[h->n] == NULL || h->val[h->n] == NULL) {
		free(h->key[h->n]);
		free(h->val[h->n]);
		return vx_err_set(e, VX_ENOMEM, "header: out of memory");
	}
	h->n++;
	return 0;
}

int
vx_hdr_set(vx_hdr *h, const char *key, vx_err *e, const char *fmt, ...)
{
	char buf[4096];
	va_list ap;
	int n;

	va_start(ap, fmt);
	n = vx_vsnprintf_c(buf, sizeof buf, fmt, ap);   /* '.' whatever
	                                                  LC_NUMERIC says */
	va_end(ap);
	if (n < 0 || (size_t)n >= sizeof buf)
		return vx_err_set(e, VX_EINTERNAL, "header: value of '%s' too long",
		    key);
	return vx_hdr_set_str(h, key, buf, e);
}

int
vx_hdr_set_str(vx_hdr *h, const char *key, const char *val, vx_err *e)
{
	size_t i, n = strlen(val);

	for (i = 0; key[i] != '\0' && key_char((unsigned char)key[i]); i++)
		;
	if (i == 0 || key[i] != '\0')
		return vx_err_set(e, VX_EINTERNAL, "header: bad key '%.40s'", key);
	if (strchr(val, '\n') != NULL)
		return vx_err_set(e, VX_EINTERNAL,
		    "header: value of '%s' contains a newline", key);
	if (vx_utf8_check(val, n) != n)
		return vx_err_set(e, VX_EDATA,
		    "header: value of '%s' is not valid UTF-8", key);
	return hdr_put(h, key, strlen(key), val, n, 1, e);
}

int
vx_hdr_parse(vx_hdr *h, const unsigned char *p, size_t n, size_t *body,
    vx_err *e)
{
	size_t i = 0, lim = n < VX_HDR_MAX ? n : VX_HDR_MAX;
	int rc;

	while (i < lim) {
		size_t ls = i, ke, vs, le;

		while (i < lim && p[i] != '\n') {
			if (p[i] == '\0')
				return vx_err_set(e, VX_EDATA,
				    "header: NUL byte at offset %zu", i);
			i++;
		}
		if (i == lim)
			break;
		le = i++;          /* p[le] == '\n' */
		if (le == ls) {    /* empty line: end of header */
			*body = i;
			return 0;
		}
		for (ke = ls; ke < le && key_char(p[ke]); ke++)
			;
		/* "key:" then either the end of the line or one space */
		if (ke == ls || ke == le || p[ke] != ':' ||
		    (ke + 1 < le && p[ke + 1] != ' '))
			return vx_err_set(e, VX_EDATA,
			    "header: line '%.*s': expected 'key: value'",
			    (int)((le - ls) > 60 ? 60 : (le - ls)),
			    (const char *)p + ls);
		vs = ke + 1 < le ? ke + 2 : le;
		if (vx_utf8_check(p + vs, le - vs) != le - vs)
			return vx_err_set(e, VX_EDATA,
			    "header: value of '%.*s' is not valid UTF-8",
			    (int)(ke - ls), (const char *)p + ls);
		if ((rc = hdr_put(h, (const char *)p + ls, ke - ls,
		    (const char *)p + vs, le - vs, 0, e)) != 0)
			return rc;
	}
	if (n > VX_HDR_MAX && lim == VX_HDR_MAX)
		return vx_err_set(e, VX_EDATA,
		    "header: longer than %zu bytes", VX_HDR_MAX);
	return vx_err_set(e, VX_EDATA, "header: no empty line ends it");
}

static int
hdr_numbers(const vx_hdr *h, const char *key, size_t count, int isint,
    int64_t *oi, double *of, int *found, vx_err *e)
{
	const char *v = vx_hdr_get(h, key), *s;
	size_t i, n;

	if (v == NULL) {
		if (found != NULL) {
			*found = 0;
			return 0;
		}
		return vx_err_set(e, VX_EDATA, "header: missing key '%s'", key);
	}
	s = v;
	for (i = 0; i < count; i++) {      /* vx_scan.h's grammar */
		while (*s == ' ' || *s == '\t')
			s++;
		n = strcspn(s, " \t");
		if (isint ? vx_num_i64(s, n, INT64_MIN, INT64_MAX, &oi[i]) :
		    vx_num_f64(s, n, 0, &of[i]))
			goto bad;
		s += n;
	}
	while (*s == ' ' || *s == '\t')
		s++;
	if (*s != '\0')
		goto bad;
	if (found != NULL)
		*found = 1;
	return 0;
bad:
	return vx_err_set(e, VX_EDATA, "header: %s: expected %zu %s, got '%.60s'",
	    key, count, isint ? "integers" : "numbers", v);
}

int
vx_hdr_get_i64(const vx_hdr *h, const char *key, int64_t *out, size_t count,
    vx_err *e)
{
	return hdr_numbers(h, key, count, 1, out, NULL, NULL, e);
}

int
vx_hdr_get_f64(const vx_hdr *h, const char *key, double *out, size_t count,
    vx_err *e)
{
	return hdr_numbers(h, key, count, 0, NULL, out, NULL, e);
}

int
vx_hdr_get_f64_opt(const vx_hdr *h, const char *key, double *out,
    size_t count, int *found, vx_err *e)
{
	return hdr_numbers(h, key, count, 0, NULL, out, found, e);
}

/* ---- payloads ---- */

/* deflate_body: compress n bytes into a new buffer *out (*outn bytes), a
 * zlib (RFC 1950) stream.  Input and output are fed to zlib in pieces, since
 * its counters are uInt; the output buffer is deflateBound's worst case. */
static int
deflate_body(const void *body, size_t n, int level, unsigned char **out,
    size_t *outn, vx_err *e)
{
	const unsigned char *src = body;
	size_t in_left = n, out_left, bound;
	unsigned char *z;
	z_stream zs;
	int zr;

	*out = NULL;
	*outn = 0;
	memset(&zs, 0, sizeof zs);
	if ((uint64_t)n > (uint64_t)(uLong)-1)
		return vx_err_set(e, VX_EINTERNAL, "body too large for zlib");
	if (deflateInit(&zs, level > 9 ? 9 : level) != Z_OK)
		return vx_err_set(e, VX_EINTERNAL, "zlib: deflateInit failed");
	bound = (size_t)deflateBound(&zs, (uLong)n);
	if ((z = malloc(bound ? bound : 1)) == NULL) {
		deflateEnd(&zs);
		return vx_err_set(e, VX_ENOMEM, "cannot allocate %zu bytes", bound);
	}
	out_left = bound;
	zs.next_in = (Bytef *)(uintptr_t)src;
	zs.next_out = z;
	do {
		uInt ki = (uInt)(in_left > ZPIECE ? ZPIECE : in_left);
		uInt ko = (uInt)(out_left > ZPIECE ? ZPIECE : out_left);

		zs.avail_in = ki;
		zs.avail_out = ko;
		/* Z_FINISH once the last piece of input is in, and from then on */
		zr = deflate(&zs, in_left == ki ? Z_FINISH : Z_NO_FLUSH);
		in_left -= ki - zs.avail_in;
		out_left -= ko - zs.avail_out;
	} while (zr == Z_OK);
	*outn = bound - out_left;
	deflateEnd(&zs);
	if (zr != Z_STREAM_END || in_left != 0) {
		free(z);
		return vx_err_set(e, VX_EINTERNAL, "zlib: deflate failed");
	}
	*out = z;
	return 0;
}

/* payload_build: vx_payload_make, or vx_payload_wrap when own is the body's
 * own buffer (raw; taken over, freed on error): it grows in place and the
 * body moves up behind the header, instead of being copied */
static int
payload_build(vx_chunk *c, const char *type, vx_hdr *h, const void *body,
    size_t n, int level, void *own, vx_err *e)
{
	unsigned char *z = NULL, *p;
	size_t zn = 0, hl = 0, i, total;
	int rc, pad = -1;

	memset(c, 0, sizeof *c);
	if (level > 0) {
		if ((rc = deflate_body(body, n, level, &z, &zn, e)) != 0)
			return rc;
		if ((rc = vx_hdr_set(h, "encoding", e, "zlib")) != 0) {
			free(z);
			return rc;
		}
	} else if ((rc = vx_hdr_set(h, "encoding", e, "raw")) != 0) {
		free(own);
		return rc;
	}
	/* the writer's own "pad" line replaces any in h: spaces that put a
	 * raw body at a multiple of VX_BODY_ALIGN bytes into the payload, so a
	 * reader can use its samples where they lie (formats/stream.md 7.1) */
	for (i = 0; i < h->n; i++)
		if (strcmp(h->key[i], "pad") != 0)
			hl += strlen(h->key[i]) + 2 + strlen(h->val[i]) + 1;
	hl += 1;
	if (level == 0 && n > 0 && hl % VX_BODY_ALIGN != 0) {
		pad = (VX_BODY_ALIGN - (hl + 6) % VX_BODY_ALIGN) % VX_BODY_ALIGN;
		if (hl + 6 + (size_t)pad <= VX_HDR_MAX)
			hl += 6 + (size_t)pad;
		else
			pad = -1;   /* a header at the limit stays unpadded */
	}
	if (hl > VX_HDR_MAX) {
		free(z);
		free(own);
		return vx_err_set(e, VX_EINTERNAL, "header of %zu bytes is longer "
		    "than %zu", hl, VX_HDR_MAX);
	}
	if (vx_add_size(&total, hl, level > 0 ? zn : n) != 0) {
		free(z);
		free(own);
		return vx_err_set(e, VX_ENOMEM, "cannot allocate chunk payload");
	}
	if (own != NULL) {
		if ((p = realloc(own, total)) == NULL) {
			free(own);
			return vx_err_set(e, VX_ENOMEM, "cannot allocate chunk "
			    "payload");
		}
		memmove(p + hl, p, n);
	} else if ((p = malloc(total)) == NULL) {
		free(z);
		return vx_err_set(e, VX_ENOMEM, "cannot allocate chunk payload");
	}
	c->data = p;
	for (i = 0; i < h->n; i++)
		if (strcmp(h->key[i], "pad") != 0)
			p += sprintf((char *)p, "%s: %s\n", h->key[i],
			    h->val[i]);
	if (pad >= 0) {
		p += sprintf((char *)p, "pad: ");
		memset(p, ' ', (size_t)pad);
		p += pad;
		*p++ = '\n';
	}
	*p++ = '\n';
	if (level > 0)
		memcpy(p, z, zn);
	else if (own == NULL && n > 0)
		memcpy(p, body, n);
	free(z);
	memcpy(c->type, type, 4);
	c->type[4] = '\0';
	c->len = total;
	c->crc_known = 0;
	return 0;
}

int
vx_payload_make(vx_chunk *c, const char *type, vx_hdr *h, const void *body,
    size_t n, int level, vx_err *e)
{
	return payload_build(c, type, h, body, n, level, NULL, e);
}

int
vx_payload_wrap(vx_chunk *c, const char *type, vx_hdr *h, void *body,
    size_t n, vx_err *e)
{
	if (body == NULL && n > 0)
		return vx_err_set(e, VX_EINTERNAL, "payload: no body");
	return payload_build(c, type, h, body, n, 0, body, e);
}

int
vx_payload_parse(const vx_chunk *c, vx_hdr *h, const unsigned char **body,
    size_t *bodylen, vx_err *e)
{
	size_t off;
	int rc;

	if ((rc = vx_hdr_parse(h, c->data, c->len, &off, e)) != 0)
		return rc;
	*body = c->data + off;
	*bodylen = c->len - off;
	return 0;
}

int
vx_body_fits(const vx_hdr *h, size_t n, size_t expect, vx_err *e)
{
	const char *enc = vx_hdr_get(h, "encoding");

	if (enc == NULL || strcmp(enc, "raw") == 0) {
		if (n != expect)
			return vx_err_set(e, VX_EDATA,
			    "body has %zu bytes, header implies %zu", n, expect);
		return 0;
	}
	if (strcmp(enc, "zlib") == 0) {
		/* deflate's best ratio is 1032:1 (a 258-byte match in two bits) */
		if (expect / VX_ZLIB_MAX_RATIO > n)
			return vx_err_set(e, VX_EDATA, "zlib body of %zu bytes cannot "
			    "hold the %zu bytes the header implies", n, expect);
		return 0;
	}
	return vx_err_set(e, VX_EDATA, "unknown encoding '%.40s'", enc);
}

int
vx_body_decode(const vx_hdr *h, const unsigned char *body, size_t n,
    void *out, size_t expect, vx_err *e)
{
	const char *enc = vx_hdr_get(h, "encoding");
	int rc;

	if ((rc = vx_body_fits(h, n, expect, e)) != 0)
		return rc;
	if (enc == NULL || strcmp(enc, "raw") == 0) {
		if (n > 0)
			memcpy(out, body, n);
		return 0;
	}
	z_stream zs;
	int zr;
	size_t left_in = n, left_out = expect;
	unsigned char dummy, *o = expect > 0 ? out : &dummy;

	memset(&zs, 0, sizeof zs);
	if (inflateInit(&zs) != Z_OK)
		return vx_err_set(e, VX_EINTERNAL, "zlib: inflateInit failed");
	zs.next_in = (Bytef *)(uintptr_t)body;
	zs.next_out = o;
	do {
		uInt ki = (uInt)(left_in > ZPIECE ? ZPIECE : left_in);
		uInt ko = (uInt)(left_out > ZPIECE ? ZPIECE : left_out);

		zs.avail_in = ki;
		zs.avail_out = ko;
		zr = inflate(&zs, Z_NO_FLUSH);
		left_in -= ki - zs.avail_in;
		left_out -= ko - zs.avail_out;
	} while (zr == Z_OK);
	inflateEnd(&zs);
	if (zr == Z_STREAM_END && left_out == 0 && left_in == 0)
		return 0;
	if (zr == Z_STREAM_END && left_out > 0)
		return vx_err_set(e, VX_EDATA, "zlib body decodes to fewer than "
		    "the %zu bytes the header implies", expect);
	if (zr == Z_STREAM_END)
		return vx_err_set(e, VX_EDATA, "zlib body: %zu bytes of trailing "
		    "data", left_in);
	if (zr == Z_BUF_ERROR && left_in == 0)
		return vx_err_set(e, VX_EDATA, "zlib body is truncated");
	if (zr == Z_BUF_ERROR)
		return vx_err_set(e, VX_EDATA, "zlib body decodes to more than "
		    "the %zu bytes the header implies", expect);
	return vx_err_set(e, VX_EDATA, "zlib body is corrupt: %s",
	    zs.msg ? zs.msg : "inflate error");
}
