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
	f = open_memstream(&out, &outn);
	assert_int_equal(vx_stream_write(&s, f, &e), 0);
	fclose(f);
	assert_int_equal(outn, b.n);
	assert_memory_equal(out, b.p, b.n);   /* byte-identical pass-through */
	vx_stream_free(&s);
	free(out);
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
		vx_hdr_free(&h);
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
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(roundtrip),
		cmocka_unit_test(malformed),
		cmocka_unit_test(headers),
		cmocka_unit_test(payload_zlib),
		cmocka_unit_test(history),
		cmocka_unit_test(crc_known),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
