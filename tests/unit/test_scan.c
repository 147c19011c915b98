/* test_scan.c: the number grammar and the text scanner (vx_scan.h) that
 * scene files, stream headers and the importers read with.  The oracles:
 * the grammar in vx_scan.h (and formats/stream.md, formats/scene.md), the
 * decimal values of the literals, IEEE 754 double limits. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "vx_scan.h"

/* Reals: each literal in or out of the grammar, with and without
 * VX_NUM_NONFINITE. */
static void
reals(void **state)
{
	static const struct {
		const char *s;
		int ok, ok_nonfinite;    /* accepted without / with the flag */
		double v;
	} t[] = {
		{ "0", 1, 1, 0 },
		{ "-0", 1, 1, -0.0 },
		{ "+12", 1, 1, 12 },
		{ "3.", 1, 1, 3 },
		{ ".25", 1, 1, 0.25 },
		{ "-2.5e-3", 1, 1, -0.0025 },
		{ "1E+2", 1, 1, 100 },
		{ "007.50", 1, 1, 7.5 },
		{ "1.7976931348623157e308", 1, 1, DBL_MAX },
		{ "4.9406564584124654e-324", 1, 1, 4.9406564584124654e-324 },
		{ "1e-400", 1, 1, 0 },         /* underflow rounds to 0 */
		{ "-1e-400", 1, 1, -0.0 },
		/* overflow: an error, never an infinity, flag or not */
		{ "1e999", 0, 0, 0 },
		{ "-1e309", 0, 0, 0 },
		{ "1.8e308", 0, 0, 0 },
		{ "17976931348623158000000000000000000000000000000000000000"
		  "00000000000000000000000000000000000000000000000000000000"
		  "00000000000000000000000000000000000000000000000000000000"
		  "00000000000000000000000000000000000000000000000000000000"
		  "00000000000000000000000000000000000000000000000000000000"
		  "000000000000000000000000000000000000000", 0, 0, 0 },
		/* outside the grammar */
		{ "", 0, 0, 0 },
		{ ".", 0, 0, 0 },
		{ "-", 0, 0, 0 },
		{ "e5", 0, 0, 0 },
		{ "1e", 0, 0, 0 },
		{ "1e+", 0, 0, 0 },
		{ "1.5.2", 0, 0, 0 },
		{ "0x10", 0, 0, 0 },
		{ "0x1p3", 0, 0, 0 },
		{ "1,5", 0, 0, 0 },
		{ " 1", 0, 0, 0 },
		{ "1 ", 0, 0, 0 },
		{ "--1", 0, 0, 0 },
		{ "1d0", 0, 0, 0 },
		{ "nan(1)", 0, 0, 0 },
		{ "infin", 0, 0, 0 },
		/* the words VX_NUM_NONFINITE adds */
		{ "nan", 0, 1, NAN },
		{ "NaN", 0, 1, NAN },
		{ "-nan", 0, 1, NAN },
		{ "inf", 0, 1, INFINITY },
		{ "-Inf", 0, 1, -INFINITY },
		{ "+INFINITY", 0, 1, INFINITY },
	};
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		size_t n = strlen(t[i].s);
		int f;

		for (f = 0; f < 2; f++) {
			int want = f ? t[i].ok_nonfinite : t[i].ok;
			double v = 42;
			int rc = vx_num_f64(t[i].s, n, f ? VX_NUM_NONFINITE : 0,
			    &v);

			if ((rc == 0) != want)
				fail_msg("'%s' flag %d: rc %d", t[i].s, f, rc);
			if (!want && v != 42)
				fail_msg("'%s': *v written on failure", t[i].s);
			if (want && !(isnan(t[i].v) ? isnan(v) : v == t[i].v &&
			    signbit(v) == signbit(t[i].v)))
				fail_msg("'%s': %.17g, want %.17g", t[i].s, v,
			    t[i].v);
		}
	}
}

/* Reals from spans: only the n bytes count; a NUL among them, or more
 * than VX_NUM_MAX characters, is not a number. */
static void
real_spans(void **state)
{
	static const char buf[] = "2.5e1xyz";
	static const char nul[] = { '1', '\0', '5' };
	char longer[VX_NUM_MAX + 2];
	double v;

	(void)state;
	assert_int_equal(vx_num_f64(buf, 5, 0, &v), 0);
	assert_true(v == 25);
	assert_int_equal(vx_num_f64(buf, 3, 0, &v), 0);
	assert_true(v == 2.5);
	assert_int_equal(vx_num_f64(buf, 6, 0, &v), -1);
	assert_int_equal(vx_num_f64(nul, 3, 0, &v), -1);
	assert_int_equal(vx_num_f64(nul, 1, 0, &v), 0);
	memset(longer, '0', sizeof longer);
	longer[0] = '1';
	assert_int_equal(vx_num_f64(longer, VX_NUM_MAX, 0, &v), -1); /* 1e399 */
	longer[1] = '.';
	assert_int_equal(vx_num_f64(longer, VX_NUM_MAX, 0, &v), 0);
	assert_true(v == 1);
	assert_int_equal(vx_num_f64(longer, VX_NUM_MAX + 1, 0, &v), -1);
}

/* Integers: grammar, the caller's range, overflow at the int64_t ends. */
static void
integers(void **state)
{
	static const struct {
		const char *s;
		int64_t lo, hi;
		int ok;
		int64_t v;
	} t[] = {
		{ "0", INT64_MIN, INT64_MAX, 1, 0 },
		{ "+17", INT64_MIN, INT64_MAX, 1, 17 },
		{ "-17", INT64_MIN, INT64_MAX, 1, -17 },
		{ "000000000000000000000000000042", 0, 100, 1, 42 },
		{ "9223372036854775807", INT64_MIN, INT64_MAX, 1, INT64_MAX },
		{ "-9223372036854775808", INT64_MIN, INT64_MAX, 1, INT64_MIN },
		{ "9223372036854775808", INT64_MIN, INT64_MAX, 0, 0 },
		{ "-9223372036854775809", INT64_MIN, INT64_MAX, 0, 0 },
		{ "99999999999999999999999", INT64_MIN, INT64_MAX, 0, 0 },
		{ "5", 1, 4, 0, 0 },
		{ "4", 1, 4, 1, 4 },
		{ "0", 1, 4, 0, 0 },
		{ "-1", -1, 4, 1, -1 },
		{ "", INT64_MIN, INT64_MAX, 0, 0 },
		{ "+", INT64_MIN, INT64_MAX, 0, 0 },
		{ "1.0", INT64_MIN, INT64_MAX, 0, 0 },
		{ "1e3", INT64_MIN, INT64_MAX, 0, 0 },
		{ "0x10", INT64_MIN, INT64_MAX, 0, 0 },
		{ " 1", INT64_MIN, INT64_MAX, 0, 0 },
		{ "1 ", INT64_MIN, INT64_MAX, 0, 0 },
	};
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		int64_t v = 42;
		int rc = vx_num_i64(t[i].s, strlen(t[i].s), t[i].lo, t[i].hi,
		    &v);

		if ((rc == 0) != t[i].ok || (t[i].ok ? v != t[i].v : v != 42))
			fail_msg("'%s': rc %d v %lld", t[i].s, rc,
			    (long long)v);
	}
}

/* Lines: "\n" and "\r\n" ends, an empty line, a last line without a
 * newline only when the buffer holds the whole text. */
static void
lines(void **state)
{
	static const char text[] = "one\r\n\ntwo  \nlast";
	const char *l;
	size_t n;
	vx_scan s;
	int whole;

	(void)state;
	for (whole = 0; whole < 2; whole++) {
		vx_scan_init(&s, text, sizeof text - 1);
		assert_int_equal(vx_scan_line(&s, whole, &l, &n), 1);
		assert_true(n == 3 && memcmp(l, "one", 3) == 0);
		assert_int_equal(vx_scan_line(&s, whole, &l, &n), 1);
		assert_int_equal(n, 0);
		assert_int_equal(vx_scan_lineno(&s), 3);
		assert_int_equal(vx_scan_line(&s, whole, &l, &n), 1);
		assert_true(n == 5 && memcmp(l, "two  ", 5) == 0);
		assert_int_equal(vx_scan_line(&s, whole, &l, &n), whole);
		if (whole)
			assert_true(n == 4 && memcmp(l, "last", 4) == 0);
		else
			assert_int_equal(vx_scan_left(&s), 4);  /* not taken */
	}
	assert_int_equal(vx_scan_line(&s, 1, &l, &n), 0);
	vx_scan_init(&s, "", 0);
	assert_int_equal(vx_scan_line(&s, 1, &l, &n), 0);
}

/* Words: across lines and within a line, the end of a line, moving to the
 * next line, copies that fit and that do not, numbers. */
static void
words(void **state)
{
	static const char text[] = "  POINTS 3\tfloat \n\f1.5 -2 x\n\n  \n7";
	const char *w;
	char t[8];
	size_t n;
	vx_scan s;
	double f;
	int64_t i;

	(void)state;
	vx_scan_init(&s, text, sizeof text - 1);
	n = vx_scan_word(&s, &w);
	assert_true(n == 6 && vx_word_eq(w, n, "points", 1) &&
	    !vx_word_eq(w, n, "points", 0) && vx_word_eq(w, n, "POINTS", 0));
	assert_int_equal(vx_scan_i64(&s, 0, 10, &i), 0);
	assert_int_equal(i, 3);
	n = vx_scan_word_line(&s, &w);
	assert_true(n == 5 && memcmp(w, "float", 5) == 0);
	assert_int_equal(vx_scan_word_line(&s, &w), 0);   /* line ends */
	assert_int_equal(vx_scan_eol(&s), 1);
	assert_int_equal(vx_scan_lineno(&s), 1);
	assert_int_equal(vx_scan_f64(&s, 0, &f), 0);      /* crosses it */
	assert_true(f == 1.5);
	assert_int_equal(vx_scan_lineno(&s), 2);
	assert_int_equal(vx_scan_i64(&s, 0, 10, &i), -1); /* -2: out */
	assert_int_equal(vx_scan_eol(&s), 0);
	assert_int_equal(vx_scan_f64(&s, VX_NUM_NONFINITE, &f), -1); /* x */
	assert_int_equal(vx_scan_next_line(&s), 1);
	assert_int_equal(vx_scan_token(&s, t, sizeof t), 1);
	assert_string_equal(t, "7");
	assert_int_equal(vx_scan_lineno(&s), 5);
	assert_int_equal(vx_scan_word(&s, &w), 0);        /* the end */
	assert_int_equal(vx_scan_f64(&s, 0, &f), -1);
	assert_int_equal(vx_scan_next_line(&s), 0);
	assert_int_equal(vx_scan_eol(&s), 1);

	vx_scan_init(&s, "abcdefgh abcdefg", 16);
	assert_int_equal(vx_scan_token(&s, t, sizeof t), -1);  /* 8 bytes */
	assert_string_equal(t, "");
	assert_int_equal(vx_scan_token(&s, t, sizeof t), 7);
	assert_string_equal(t, "abcdefg");
	assert_int_equal(vx_scan_token(&s, t, sizeof t), 0);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(reals),
		cmocka_unit_test(real_spans),
		cmocka_unit_test(integers),
		cmocka_unit_test(lines),
		cmocka_unit_test(words),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
