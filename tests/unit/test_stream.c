/* test_stream.c: the chunked stream: round trips, and every way a stream can
 * be malformed, each with the error code and message it must produce. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "vx_stream.h"

/* build: a stream image in memory from a list of (type, payload) pairs. */
typedef struct buf { unsigned char *p; size_t n; } buf;

static void
add(buf *b, const void *q, size_t n)
{
	b->p = realloc(b->p, b->n + n + 1);
	memcpy(b->p + b->n, q, n);
	b->n += n;
}

static void
add_chunk(buf *b, const char *type, const void *data, size_t len,
    uint64_t claimed, int crc_ok)
{
	unsigned char h[12], c[4];

	memcpy(h, type, 4);
	vx_put_le64(h + 4, claimed);
	vx_put_le32(c, vx_chunk_crc(type, data, len) ^ (crc_ok ? 0 : 1));
	add(b, h, 12);
	add(b, data, len);
	add(b, c, 4);
}

static buf
good_stream(void)
{
	buf b = { NULL, 0 };

	add(&b, VX_SIGNATURE, 8);
	add_chunk(&b, "note", "hello", 5, 5, 1);
	add_chunk(&b, "IMAG", "x: 1\n\n", 6, 6, 1);
	add_chunk(&b, "zzzz", "keep me", 7, 7, 1);
	add_chunk(&b, "VEND", "", 0, 0, 1);
	return b;
}

static void
roundtrip(void **state)
{
	buf b = good_stream();
	vx_stream s;
	vx_err e = { 0, "" };
	char *out = NULL;
	size_t outn = 0;
	FILE *f;

	(void)state;
	vx_stream_init(&s);
	assert_int_equal(vx_stream_read_mem(&s, b.p, b.n, &e), 0);
	assert_int_equal(s.n, 3);
	assert_memory_equal(s.chunk[2].type, "zzzz", 4);  /* unknown ancillary kept */
	assert_memory_equal(s.chunk[2].data, "keep me", 7);
	/* each chunk's CRC is kept as read (oracle: computed anew) */
	for (size_t i = 0; i < s.n; i++) {
		assert_int_equal(s.chunk[i].crc_known, 1);
		assert_int_equal(s.chunk[i].crc, vx_chunk_crc(s.chunk[i].type,
		    s.chunk[i].data, s.chunk[i].len));
		assert_int_equal(vx_chunk_crc_of(&s.chunk[i]), s.chunk[i].crc);
	}
	f = open_memstream(&out, &outn);
	assert_int_equal(vx_stream_write(&s, f, &e), 0);
	fclose(f);
	assert_int_equal(outn, b.n);
	assert_memory_equal(out, b.p, b.n);   /* byte-identical pass-through */
	free(out);
	/* a history line changes the chunk in place: its CRC is computed
	 * again, and the stream written reads back */
	{
		long h = vx_stream_find(&s, VX_CHUNK_HISTORY, 0);
		vx_stream s2;

		assert_int_equal(vx_stream_history_add(&s, "tool 1 --x", &e), 0);
		h = vx_stream_find(&s, VX_CHUNK_HISTORY, 0);
		assert_true(h >= 0);
		assert_int_equal(s.chunk[h].crc_known, 0);
		assert_int_equal(vx_chunk_crc_of(&s.chunk[h]),
		    vx_chunk_crc(s.chunk[h].type, s.chunk[h].data,
		    s.chunk[h].len));
		out = NULL;
		f = open_memstream(&out, &outn);
		assert_int_equal(vx_stream_write(&s, f, &e), 0);
		fclose(f);
		vx_stream_init(&s2);
		assert_int_equal(vx_stream_read_mem(&s2, (unsigned char *)out,
		    outn, &e), 0);
		vx_stream_free(&s2);
		free(out);
	}
	vx_stream_free(&s);
	free(b.p);
}

typedef struct bad_case {
	const char *name;
	int code;
	const char *msg;   /* substring of the message */
	void (*make)(buf *b);
} bad_case;

static void mk_empty(buf *b) { (void)b; }
static void mk_badsig(buf *b) { add(b, "\x89VXM\r\n\x1a\n", 8); }
static void mk_nosig_end(buf *b) { add(b, VX_SIGNATURE, 8); }
static void mk_partial_head(buf *b) { add(b, VX_SIGNATURE, 8); add(b, "note\1\0", 6); }
static void mk_truncated_payload(buf *b)
{
	add(b, VX_SIGNATURE, 8);
	add_chunk(b, "note", "abc", 3, 100, 1);
}
static void mk_crc(buf *b)
{
	add(b, VX_SIGNATURE, 8);
	add_chunk(b, "note", "abc", 3, 3, 0);
}
static void mk_unknown_critical(buf *b)
{
	add(b, VX_SIGNATURE, 8);
	add_chunk(b, "QQQQ", "abc", 3, 3, 1);
}
static void mk_huge(buf *b)
{
	add(b, VX_SIGNATURE, 8);
	add_chunk(b, "note", "abc", 3, UINT64_MAX - 5, 1);
}
static void mk_near_limit(buf *b)
{
	/* a length the reader accepts as a claim but the input cannot back:
	 * must fail as truncated without allocating the claim */
	add(b, VX_SIGNATURE, 8);
	add_chunk(b, "note", "abc", 3, ((uint64_t)1 << 40) - 1, 1);
}
static void mk_badtype(buf *b)
{
	add(b, VX_SIGNATURE, 8);
	add_chunk(b, "no\x01e", "abc", 3, 3, 1);
}
static void mk_no_end(buf *b)
{
	add(b, VX_SIGNATURE, 8);
	add_chunk(b, "note", "abc", 3, 3, 1);
}
static void mk_end_nonempty(buf *b)
{
	add(b, VX_SIGNATURE, 8);
	add_chunk(b, "VEND", "x", 1, 1, 1);
}
static void mk_trailing(buf *b)
{
	add(b, VX_SIGNATURE, 8);
	add_chunk(b, "VEND", "", 0, 0, 1);
	add(b, "x", 1);
}
static void mk_missing_crc(buf *b)
{
	add(b, VX_SIGNATURE, 8);
	add(b, "note\3\0\0\0\0\0\0\0abc", 15);
}

static const bad_case bad[] = {
	{ "empty input", 66, "empty input", mk_empty },
	{ "bad signature", 65, "signature", mk_badsig },
	{ "signature only", 65, "no end chunk", mk_nosig_end },
	{ "partial chunk header", 65, "partial chunk header", mk_partial_head },
	{ "truncated payload", 65, "truncated", mk_truncated_payload },
	{ "crc mismatch", 65, "CRC mismatch", mk_crc },
	{ "unknown critical", 65, "unknown critical chunk", mk_unknown_critical },
	{ "length near 2^64", 65, "exceeds the limit", mk_huge },
	{ "length near limit", 65, "truncated", mk_near_limit },
	{ "invalid type", 65, "invalid type", mk_badtype },
	{ "no end chunk", 65, "no end chunk", mk_no_end },
	{ "non-empty end", 65, "must be empty", mk_end_nonempty },
	{ "trailing bytes", 65, "trailing bytes", mk_trailing },
	{ "missing crc", 65, "missing CRC", mk_missing_crc },
};

static void
malformed(void **state)
{
	size_t i;

	(void)state;
	for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		buf b = { NULL, 0 };
		vx_stream s;
		vx_err e = { 0, "" };
		int rc;

		bad[i].make(&b);
		vx_stream_init(&s);
		rc = vx_stream_read_mem(&s, b.p ? b.p : (unsigned char *)"", b.n, &e);
		if (rc != bad[i].code || strstr(e.msg, bad[i].msg) == NULL)
			fail_msg("%s: got %d '%s', want %d '%s'", bad[i].name, rc,
			    e.msg, bad[i].code, bad[i].msg);
		vx_stream_free(&s);
		free(b.p);
	}
}

static void
headers(void **state)
{
	static const struct { const char *text; int ok; } t[] = {
		{ "a: 1\nb: two words\n\nBODY", 1 },
		{ "a: 1\n\n", 1 },
		{ "\n", 1 },
		{ "a: 1\na: 2\n\n", 0 },          /* duplicate */
		{ "A: 1\n\n", 0 },                /* upper-case key */
		{ "a 1\n\n", 0 },                 /* no colon */
		{ "a:1\n\n", 0 },                 /* no space */
		{ "a: 1\n", 0 },                  /* no empty line */
		{ "", 0 },
		{ "a: 1\0\n\n", 0 },              /* NUL */
		{ "a:\n\n", 1 },                  /* empty value */
		{ "name: K\xc3\xb6rper\n\n", 1 },  /* UTF-8 value */
		{ "name: \xff\n\n", 0 },          /* not UTF-8 */
		{ "\xc3\xa9: 1\n\n", 0 },          /* non-ASCII key */
		{ "a:  x\n\n", 1 },                /* value " x" */
		{ "a: x\r\n\n", 1 },               /* value "x\r" */
		{ "a b: 1\n\n", 0 },               /* space in key */
		{ ": 1\n\n", 0 },                  /* empty key */
		{ "a: 1\n\r\n", 0 },               /* "\r" is not an empty line */
	};
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_hdr h;
		vx_err e = { 0, "" };
		size_t body, n = strlen(t[i].text);
		int rc;

		if (i == 9)
			n = 8;
		vx_hdr_init(&h);
		rc = vx_hdr_parse(&h, (const unsigned char *)t[i].text, n, &body, &e);
		if ((rc == 0) != t[i].ok)
			fail_msg("header case %zu: rc %d (%s)", i, rc, e.msg);
		if (i == 0) {
			assert_string_equal(vx_hdr_get(&h, "b"), "two words");
			assert_string_equal(t[i].text + body, "BODY");
		}
		if (i == 14)
			assert_string_equal(vx_hdr_get(&h, "a"), " x");
		if (i == 15)
			assert_string_equal(vx_hdr_get(&h, "a"), "x\r");
		vx_hdr_free(&h);
	}
}

/* A header of exactly VX_HDR_MAX bytes (its empty line included) parses;
 * one byte more does not, even with the end in the data. */
static void
header_limit(void **state)
{
	size_t n = VX_HDR_MAX + 8, i;
	unsigned char *p = malloc(n);

	(void)state;
	for (int extra = 0; extra <= 1; extra++) {
		vx_hdr h;
		vx_err e = { 0, "" };
		size_t body = 0, len = VX_HDR_MAX + (size_t)extra;
		int rc;

		/* "a: xxx...x\n\n" of len bytes, then a body */
		memcpy(p, "a: ", 3);
		for (i = 3; i < len - 2; i++)
			p[i] = 'x';
		p[len - 2] = '\n';
		p[len - 1] = '\n';
		memset(p + len, 'B', n - len);
		vx_hdr_init(&h);
		rc = vx_hdr_parse(&h, p, n, &body, &e);
		if (extra == 0) {
			assert_int_equal(rc, 0);
			assert_int_equal(body, VX_HDR_MAX);
		} else {
			assert_int_equal(rc, VX_EDATA);
			assert_non_null(strstr(e.msg, "longer than"));
		}
		vx_hdr_free(&h);
	}
	free(p);
}

/* The writer's pad line: a raw body starts at a multiple of VX_BODY_ALIGN,
 * unless the pad would push the header past VX_HDR_MAX (then no pad); a
 * header over the limit is refused.  vx_payload_wrap gives the same bytes
 * or the same refusal.  Oracle: the header's length, from the
 * lengths of its lines ("a: " + L bytes + LF, "encoding: raw" + LF, LF:
 * L + 19 bytes before any pad). */
static void
payload_pad(void **state)
{
	static const struct {
		size_t hl;      /* the header's length without a pad */
		size_t want;    /* with it; 0: refused */
	} t[] = {
		{ 64, 64 }, { 65, 80 }, { 75, 96 }, { 106, 112 }, { 107, 128 },
		{ 58, 64 }, { VX_HDR_MAX - 40, VX_HDR_MAX - 32 },
		{ VX_HDR_MAX - 3, VX_HDR_MAX - 3 }, { VX_HDR_MAX, VX_HDR_MAX },
		{ VX_HDR_MAX + 1, 0 },
	};
	unsigned char body[4] = { 1, 2, 3, 4 };

	(void)state;
	for (size_t k = 0; k < sizeof t / sizeof t[0]; k++) {
		size_t L = t[k].hl - 19, off = 0;
		char *v = malloc(L + 1);
		const unsigned char *b;
		vx_err e = { 0, "" };
		vx_chunk c;
		vx_hdr h, h2;
		int rc;

		assert_non_null(v);
		memset(v, 'x', L);
		v[L] = '\0';
		vx_hdr_init(&h);
		assert_int_equal(vx_hdr_set_str(&h, "a", v, &e), 0);
		rc = vx_payload_make(&c, "VOLM", &h, body, sizeof body, 0, &e);
		{
			/* vx_payload_wrap: the same bytes from the body's own
			 * buffer, or the same refusal (the buffer freed) */
			unsigned char *own = malloc(sizeof body);
			vx_chunk cw;
			int rw;

			assert_non_null(own);
			memcpy(own, body, sizeof body);
			rw = vx_payload_wrap(&cw, "VOLM", &h, own, sizeof body, &e);
			assert_int_equal(rw, rc);
			if (rw == 0) {
				assert_int_equal(cw.len, c.len);
				assert_memory_equal(cw.data, c.data, c.len);
				vx_chunk_free(&cw);
			}
		}
		if (t[k].want == 0) {
			assert_int_equal(rc, VX_EINTERNAL);
		} else {
			assert_int_equal(rc, 0);
			vx_hdr_init(&h2);
			assert_int_equal(vx_hdr_parse(&h2, c.data, c.len, &off,
			    &e), 0);
			if (off != t[k].want)
				fail_msg("case %zu: header %zu bytes, want %zu", k,
				    off, t[k].want);
			assert_int_equal(c.len, off + sizeof body);
			b = c.data + off;
			assert_memory_equal(b, body, sizeof body);
			assert_int_equal(vx_hdr_get(&h2, "pad") != NULL,
			    off != t[k].hl);
			vx_hdr_free(&h2);
			vx_chunk_free(&c);
		}
		vx_hdr_free(&h);
		free(v);
	}
}

static void
payload_zlib(void **state)
{
	unsigned char body[10000], out[10000];
	vx_hdr h, h2;
	vx_chunk c;
	vx_err e = { 0, "" };
	const unsigned char *b;
	size_t bl;
	int level;

	(void)state;
	for (size_t i = 0; i < sizeof body; i++)
		body[i] = (unsigned char)(i * 7 % 13);
	for (level = 0; level <= 9; level += 9) {
		vx_hdr_init(&h);
		vx_hdr_init(&h2);
		assert_int_equal(vx_hdr_set(&h, "dims", &e, "%d", 10000), 0);
		assert_int_equal(vx_payload_make(&c, "VOLM", &h, body, sizeof body,
		    level, &e), 0);
		assert_int_equal(vx_payload_parse(&c, &h2, &b, &bl, &e), 0);
		assert_string_equal(vx_hdr_get(&h2, "encoding"), level ? "zlib" : "raw");
		assert_int_equal(vx_body_decode(&h2, b, bl, out, sizeof out, &e), 0);
		assert_memory_equal(out, body, sizeof body);
		/* the header's expectation, not the data, bounds the output */
		assert_int_equal(vx_body_decode(&h2, b, bl, out, sizeof out - 1, &e),
		    VX_EDATA);
		vx_chunk_free(&c);
		vx_hdr_free(&h);
		vx_hdr_free(&h2);
	}
}

static void
history(void **state)
{
	vx_stream s;
	vx_err e = { 0, "" };
	const char *t;
	size_t n;

	(void)state;
	vx_stream_init(&s);
	assert_int_equal(vx_stream_history_add(&s, "vread 0.1 --synth sphere", &e), 0);
	assert_int_equal(vx_stream_history_add(&s, "brick\nbad", &e), 0);
	t = vx_stream_history(&s, &n);
	assert_int_equal(n, strlen("vread 0.1 --synth sphere\nbrick bad\n"));
	assert_memory_equal(t, "vread 0.1 --synth sphere\nbrick bad\n", n);
	vx_stream_free(&s);
}

static void
crc_known(void **state)
{
	(void)state;
	/* CRC-32 of "IEND" with an empty payload is PNG's well-known ae426082 */
	assert_int_equal(vx_chunk_crc("IEND", "", 0), 0xae426082u);
	/* the catalogued check value of CRC-32/ISO-HDLC: crc("123456789") */
	assert_int_equal(vx_chunk_crc("1234", "56789", 5), 0xcbf43926u);
	/* formats/stream.md's vectors (python3 -c 'zlib.crc32(b"VEND")') */
	assert_int_equal(vx_chunk_crc("VEND", NULL, 0), 0xa638274bu);
	assert_int_equal(vx_chunk_crc("note", "hello", 5), 0xcb4fc7c5u);
}

/* The smallest stream, byte for byte as formats/stream.md spells it out. */
static void
empty_stream_bytes(void **state)
{
	static const unsigned char want[24] = {
		0x89, 'V', 'X', 'L', '\r', '\n', 0x1a, '\n',
		'V', 'E', 'N', 'D', 0, 0, 0, 0, 0, 0, 0, 0,
		0x4b, 0x27, 0x38, 0xa6,
	};
	vx_stream s;
	vx_err e = { 0, "" };
	char *out = NULL;
	size_t outn = 0;
	FILE *f;

	(void)state;
	vx_stream_init(&s);
	f = open_memstream(&out, &outn);
	assert_int_equal(vx_stream_write(&s, f, &e), 0);
	fclose(f);
	assert_int_equal(outn, sizeof want);
	assert_memory_equal(out, want, sizeof want);
	assert_int_equal(vx_stream_read_mem(&s, want, sizeof want, &e), 0);
	assert_int_equal(s.n, 0);
	free(out);
}

/* The writer refuses what no reader would take back, before writing. */
static void
write_refuses(void **state)
{
	static const char *types[] = { "VEND", "no e", "ab1d" };
	size_t i;

	(void)state;
	for (i = 0; i < sizeof types / sizeof types[0]; i++) {
		vx_stream s;
		vx_chunk c;
		vx_err e = { 0, "" };
		char *out = NULL;
		size_t outn = 0;
		FILE *f;

		vx_stream_init(&s);
		memset(&c, 0, sizeof c);
		memcpy(c.type, types[i], 5);
		assert_int_equal(vx_stream_append(&s, &c, &e), 0);
		f = open_memstream(&out, &outn);
		assert_int_equal(vx_stream_write(&s, f, &e), VX_EINTERNAL);
		fclose(f);
		assert_int_equal(outn, 0);
		free(out);
		vx_stream_free(&s);
	}
}

/* UTF-8 validity; oracle: RFC 3629 section 4's syntax and Markus Kuhn's
 * decoder stress test cases (overlongs, surrogates, beyond U+10FFFF). */
static void
utf8(void **state)
{
	static const struct { const char *s; size_t valid; } t[] = {
		{ "plain ascii", 11 },
		{ "K\xc3\xb6rper", 7 },                  /* U+00F6 */
		{ "\xe2\x82\xac", 3 },                   /* U+20AC */
		{ "\xf0\x9f\x98\x80", 4 },               /* U+1F600 */
		{ "\xf4\x8f\xbf\xbf", 4 },               /* U+10FFFF */
		{ "a\xf4\x90\x80\x80", 1 },              /* U+110000 */
		{ "a\xc0\xaf", 1 },                      /* overlong '/' */
		{ "\xe0\x80\xaf", 0 },                   /* overlong '/' */
		{ "\xf0\x80\x80\xaf", 0 },               /* overlong '/' */
		{ "ab\xed\xa0\x80", 2 },                 /* surrogate D800 */
		{ "\xed\x9f\xbf", 3 },                   /* U+D7FF */
		{ "x\x80", 1 },                          /* lone continuation */
		{ "\xc3", 0 },                           /* truncated */
		{ "\xe2\x82", 0 },                       /* truncated */
		{ "\xc3(", 0 },                          /* bad continuation */
		{ "\xff", 0 },
		{ "\xf5\x80\x80\x80", 0 },
	};
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++)
		if (vx_utf8_check(t[i].s, strlen(t[i].s)) != t[i].valid)
			fail_msg("utf8 case %zu: %zu, want %zu", i,
			    vx_utf8_check(t[i].s, strlen(t[i].s)), t[i].valid);
}

/* Numbers in header values: the decimal grammar of formats/stream.md, not
 * whatever strtod takes.  Oracle: the grammar, by hand. */
static void
numbers(void **state)
{
	static const struct {
		const char *v; int isint; size_t count; int ok; double x0;
	} t[] = {
		{ "1 2 3", 1, 3, 1, 1 },
		{ "  -7\t+8 9  ", 1, 3, 1, -7 },
		{ "1 2", 1, 3, 0, 0 },
		{ "1 2 3 4", 1, 3, 0, 0 },
		{ "1.0 2 3", 1, 3, 0, 0 },
		{ "0x10 2 3", 1, 3, 0, 0 },
		{ "9223372036854775807", 1, 1, 1, 9223372036854775807.0 },
		{ "9223372036854775808", 1, 1, 0, 0 },   /* overflow */
		{ "1,2,3", 1, 3, 0, 0 },
		{ "1.5 .5 5.", 0, 3, 1, 1.5 },
		{ "-2.5e-3 1E+2 0", 0, 3, 1, -2.5e-3 },
		{ "0.10000000000000001", 0, 1, 1, 0.1 },
		{ "nan", 0, 1, 0, 0 },
		{ "inf", 0, 1, 0, 0 },
		{ "0x1p3", 0, 1, 0, 0 },
		{ "1e", 0, 1, 0, 0 },
		{ ".", 0, 1, 0, 0 },
		{ "e5", 0, 1, 0, 0 },
		{ "1,5", 0, 1, 0, 0 },                   /* a locale's comma */
		{ "1e400", 0, 1, 0, 0 },                 /* overflow */
		{ "4.9406564584124654e-324", 0, 1, 1, 4.9406564584124654e-324 },
		{ "1e-400", 0, 1, 1, 0 },                /* underflow: zero */
		{ "", 0, 1, 0, 0 },
		{ "", 0, 0, 1, 0 },
	};
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_hdr h;
		vx_err e = { 0, "" };
		int64_t vi[4] = { 0 };
		double vf[4] = { 0 };
		int rc;

		vx_hdr_init(&h);
		assert_int_equal(vx_hdr_set(&h, "k", &e, "%s", t[i].v), 0);
		rc = t[i].isint ? vx_hdr_get_i64(&h, "k", vi, t[i].count, &e) :
		    vx_hdr_get_f64(&h, "k", vf, t[i].count, &e);
		if ((rc == 0) != t[i].ok)
			fail_msg("number case %zu '%s': rc %d (%s)", i, t[i].v, rc,
			    e.msg);
		if (rc == 0 && t[i].count > 0 &&
		    (t[i].isint ? (double)vi[0] : vf[0]) != t[i].x0)
			fail_msg("number case %zu: value %.17g", i,
			    t[i].isint ? (double)vi[0] : vf[0]);
		vx_hdr_free(&h);
	}
}

/* vx_hdr_set refuses keys and values no reader would take back. */
static void
hdr_set_refuses(void **state)
{
	vx_hdr h;
	vx_err e = { 0, "" };

	(void)state;
	vx_hdr_init(&h);
	assert_int_equal(vx_hdr_set(&h, "Name", &e, "x"), VX_EINTERNAL);
	assert_int_equal(vx_hdr_set(&h, "", &e, "x"), VX_EINTERNAL);
	assert_int_equal(vx_hdr_set(&h, "a b", &e, "x"), VX_EINTERNAL);
	assert_int_equal(vx_hdr_set(&h, "a", &e, "x\ny"), VX_EINTERNAL);
	assert_int_equal(vx_hdr_set(&h, "a", &e, "\xff"), VX_EDATA);
	assert_int_equal(vx_hdr_set(&h, "a-b_9", &e, "K\xc3\xb6rper"), 0);
	assert_int_equal(h.n, 1);
	vx_hdr_free(&h);
}

/* A few MiB crosses the zlib piece size (1 MiB) on both the input and the
 * output side; oracle: the bytes that went in. */
static void
payload_large(void **state)
{
	size_t n = (size_t)3 << 20 | 12345, i;
	unsigned char *body = malloc(n), *out = malloc(n);
	uint32_t x = 2463534242u;
	vx_hdr h, h2;
	vx_chunk c;
	vx_err e = { 0, "" };
	const unsigned char *b;
	size_t bl;

	(void)state;
	for (i = 0; i < n; i++) {       /* xorshift noise: barely compressible */
		x ^= x << 13;
		x ^= x >> 17;
		x ^= x << 5;
		body[i] = (unsigned char)(i < n / 2 ? x : (x & 3));
	}
	vx_hdr_init(&h);
	vx_hdr_init(&h2);
	assert_int_equal(vx_payload_make(&c, "VOLM", &h, body, n, 1, &e), 0);
	assert_int_equal(vx_payload_parse(&c, &h2, &b, &bl, &e), 0);
	assert_true(bl > ((size_t)1 << 20));
	assert_int_equal(vx_body_decode(&h2, b, bl, out, n, &e), 0);
	assert_memory_equal(out, body, n);
	vx_chunk_free(&c);
	vx_hdr_free(&h);
	vx_hdr_free(&h2);
	free(body);
	free(out);
}

/* Bodies that cannot match the header's size, each with its message. */
static void
body_errors(void **state)
{
	static const unsigned char empty_z[] = {   /* zlib.compress(b"") */
		0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01 };
	static const unsigned char abc_z[] = {     /* zlib.compress(b"abc") */
		0x78, 0x9c, 0x4b, 0x4c, 0x4a, 0x06, 0x00, 0x02, 0x4d, 0x01, 0x27 };
	static const struct {
		const char *enc; const unsigned char *b; size_t n, expect;
		int rc; const char *msg;
	} t[] = {
		{ "raw", (const unsigned char *)"abc", 3, 3, 0, "" },
		{ NULL, (const unsigned char *)"abc", 3, 3, 0, "" },
		{ "raw", (const unsigned char *)"abc", 3, 4, 65, "body has 3" },
		{ "zlib", empty_z, sizeof empty_z, 0, 0, "" },
		{ "zlib", abc_z, sizeof abc_z, 3, 0, "" },
		{ "zlib", abc_z, sizeof abc_z, 2, 65, "more than" },
		{ "zlib", abc_z, sizeof abc_z, 4, 65, "fewer than" },
		{ "zlib", abc_z, sizeof abc_z - 2, 3, 65, "truncated" },
		{ "zlib", abc_z, sizeof abc_z - 4, 3, 65, "truncated" },
		{ "zlib", abc_z, 2, 3, 65, "truncated" },
		{ "zlib", (const unsigned char *)"garbage", 7, 3, 65, "corrupt" },
		{ "zlib", abc_z, sizeof abc_z, (size_t)1 << 40, 65, "cannot hold" },
		{ "gzip", abc_z, sizeof abc_z, 3, 65, "unknown encoding" },
	};
	unsigned char big[sizeof abc_z + 1];
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		unsigned char out[8];
		vx_hdr h;
		vx_err e = { 0, "" };
		int rc;

		vx_hdr_init(&h);
		if (t[i].enc != NULL)
			assert_int_equal(vx_hdr_set(&h, "encoding", &e, "%s",
			    t[i].enc), 0);
		rc = vx_body_fits(&h, t[i].n, t[i].expect, &e);
		if (rc == 0)
			rc = vx_body_decode(&h, t[i].b, t[i].n, out, t[i].expect,
			    &e);
		if (rc != t[i].rc || strstr(e.msg, t[i].msg) == NULL)
			fail_msg("body case %zu: got %d '%s', want %d '%s'", i, rc,
			    e.msg, t[i].rc, t[i].msg);
		if (rc == 0 && t[i].expect == 3)
			assert_memory_equal(out, "abc", 3);
		vx_hdr_free(&h);
	}
	/* trailing bytes after the zlib stream */
	{
		vx_hdr h;
		vx_err e = { 0, "" };
		unsigned char out[3];

		memcpy(big, abc_z, sizeof abc_z);
		big[sizeof abc_z] = 0;
		vx_hdr_init(&h);
		assert_int_equal(vx_hdr_set(&h, "encoding", &e, "zlib"), 0);
		assert_int_equal(vx_body_decode(&h, big, sizeof big, out, 3, &e),
		    VX_EDATA);
		assert_non_null(strstr(e.msg, "trailing"));
		vx_hdr_free(&h);
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(roundtrip),
		cmocka_unit_test(malformed),
		cmocka_unit_test(headers),
		cmocka_unit_test(payload_pad),
		cmocka_unit_test(header_limit),
		cmocka_unit_test(payload_zlib),
		cmocka_unit_test(history),
		cmocka_unit_test(crc_known),
		cmocka_unit_test(empty_stream_bytes),
		cmocka_unit_test(write_refuses),
		cmocka_unit_test(utf8),
		cmocka_unit_test(numbers),
		cmocka_unit_test(hdr_set_refuses),
		cmocka_unit_test(payload_large),
		cmocka_unit_test(body_errors),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
