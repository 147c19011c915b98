/* test_locale.c: numbers in text (stream headers, scene files, NRRD and PFM
 * headers) read and written with a '.' whatever LC_NUMERIC says: run under
 * a decimal-comma locale, where plain strtod("0.5") stops at the '.' and
 * printf("%g", 0.5) writes "0,5".
 *
 * The comma locale: an installed one (de_DE, fr_FR, ...) if any, else a
 * minimal one (only LC_NUMERIC, decimal point ',') compiled with
 * localedef(1) into a temporary directory named by LOCPATH, else the tests
 * report a TAP skip. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <errno.h>
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "vx_err.h"
#include "vx_export.h"
#include "vx_grid.h"
#include "vx_image.h"
#include "vx_imageio.h"
#include "vx_import.h"
#include "vx_scene.h"
#include "vx_stream.h"
#include "vx_scan.h"

static char tmpdir[64];
static const char *comma;      /* name of the comma locale, NULL if none */

/* is_comma: the current LC_NUMERIC writes 0.5 as "0,5" (the oracle that
 * the locale is really in force, or the tests prove nothing). */
static int
is_comma(void)
{
	char b[16];

	snprintf(b, sizeof b, "%.1f", 0.5);
	return strcmp(b, "0,5") == 0;
}

static int
setup(void **state)
{
	static const char *const names[] = {
		"de_DE.UTF-8", "de_DE.utf8", "de_DE", "fr_FR.UTF-8", "fr_FR.utf8",
		"nl_NL.UTF-8", "ru_RU.UTF-8", "es_ES.UTF-8", "it_IT.UTF-8",
		"pt_BR.UTF-8", NULL,
	};
	char cmd[512], src[96];
	FILE *f;
	int i;

	(void)state;
	for (i = 0; names[i] != NULL; i++)
		if (setlocale(LC_NUMERIC, names[i]) != NULL && is_comma()) {
			comma = names[i];
			return 0;
		}
	/* none installed: compile one (a few milliseconds) */
	snprintf(tmpdir, sizeof tmpdir, "/tmp/vx-locale-XXXXXX");
	if (mkdtemp(tmpdir) == NULL) {
		tmpdir[0] = '\0';
		return 0;
	}
	snprintf(src, sizeof src, "%s/comma.src", tmpdir);
	if ((f = fopen(src, "w")) == NULL)
		return 0;
	fputs("LC_NUMERIC\ndecimal_point \"<U002C>\"\nthousands_sep "
	    "\"<U002E>\"\ngrouping 3;3\nEND LC_NUMERIC\n", f);
	fclose(f);
	snprintf(cmd, sizeof cmd, "localedef -c -i %s -f ANSI_X3.4-1968 "
	    "%s/xx_XX >/dev/null 2>&1", src, tmpdir);
	if (system(cmd) == -1)
		return 0;
	setenv("LOCPATH", tmpdir, 1);
	if (setlocale(LC_NUMERIC, "xx_XX") != NULL && is_comma())
		comma = "xx_XX (localedef)";
	return 0;
}

static int
teardown(void **state)
{
	char cmd[128];

	(void)state;
	setlocale(LC_NUMERIC, "C");
	if (tmpdir[0] != '\0') {
		snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
		if (system(cmd) != 0)
			return 0;
	}
	return 0;
}

/* need_comma: skip (with a TAP "# SKIP" line saying why) unless the comma
 * locale is in force. */
#define need_comma() do { \
	if (comma == NULL) { \
		printf("# SKIP no decimal-comma locale installed, and " \
		    "localedef could not make one\n"); \
		skip(); \
	} \
	assert_true(is_comma()); \
} while (0)

/* vx_strtod and vx_snprintf_c themselves.  Oracle: the decimal values. */
static void
strtod_and_printf(void **state)
{
	static const struct { const char *s; double v; size_t used; } t[] = {
		{ "0.5", 0.5, 3 },
		{ "-2.25e2", -225, 7 },
		{ "1e-3", 0.001, 4 },
		{ "0,5", 0, 1 },        /* stops at the comma */
		{ "3.", 3, 2 },
		{ ".25", 0.25, 3 },
	};
	char b[64], *end;
	size_t i;

	(void)state;
	need_comma();
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		double v = vx_strtod(t[i].s, &end);

		assert_true(v == t[i].v);
		assert_int_equal(end - t[i].s, t[i].used);
	}
	errno = 0;
	assert_true(isinf(vx_strtod("1e999", &end)) && errno == ERANGE);
	errno = EINVAL;
	vx_strtod("1", &end);
	assert_int_equal(errno, 0);
	vx_snprintf_c(b, sizeof b, "%.17g %g %.2f", 0.1, 0.5, 1.25);
	assert_string_equal(b, "0.10000000000000001 0.5 1.25");
	assert_true(is_comma());        /* the thread's locale is back */
}

/* The number grammar every text format reads with (vx_scan.h): the same
 * values under a comma locale, a comma refused, overflow refused.  Oracle:
 * the decimal values. */
static void
number_grammar(void **state)
{
	static const struct { const char *s; int ok; double v; } t[] = {
		{ "0.5", 1, 0.5 },
		{ "-2.25e2", 1, -225 },
		{ ".25", 1, 0.25 },
		{ "3.", 1, 3 },
		{ "1e-400", 1, 0 },          /* underflow rounds to 0 */
		{ "0,5", 0, 0 },
		{ "1,5e3", 0, 0 },
		{ "1e999", 0, 0 },           /* overflow: never +Inf */
		{ "-1e309", 0, 0 },
	};
	size_t i;
	double v;

	(void)state;
	need_comma();
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		v = -7;
		if ((vx_num_f64(t[i].s, strlen(t[i].s), VX_NUM_NONFINITE,
		    &v) == 0) != t[i].ok || (t[i].ok && v != t[i].v))
			fail_msg("'%s': %g", t[i].s, v);
	}
	assert_true(is_comma());
}

/* Stream headers: numbers with a '.' parse, with a ',' are malformed;
 * vx_hdr_set writes '.'.  Oracle: formats/stream.md 7.2. */
static void
stream_headers(void **state)
{
	static const char good[] = "spacing: 0.5 0.25 2\norigin: -1.5e1 .5 3.\n\n";
	static const char *const bad[] = {
		"spacing: 0,5 1 1\n\n", "spacing: 1 1 0,25\n\n", "spacing: 1,5\n\n",
	};
	vx_err e = { 0, "" };
	double v[3];
	size_t body, i;
	vx_hdr h;

	(void)state;
	need_comma();
	vx_hdr_init(&h);
	assert_int_equal(vx_hdr_parse(&h, (const unsigned char *)good,
	    strlen(good), &body, &e), 0);
	assert_int_equal(vx_hdr_get_f64(&h, "spacing", v, 3, &e), 0);
	assert_true(v[0] == 0.5 && v[1] == 0.25 && v[2] == 2);
	assert_int_equal(vx_hdr_get_f64(&h, "origin", v, 3, &e), 0);
	assert_true(v[0] == -15 && v[1] == 0.5 && v[2] == 3);
	assert_int_equal(vx_hdr_set(&h, "x", &e, "%.17g %g", 0.1, 2.5), 0);
	assert_string_equal(vx_hdr_get(&h, "x"), "0.10000000000000001 2.5");
	vx_hdr_free(&h);
	for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		vx_hdr_init(&h);
		assert_int_equal(vx_hdr_parse(&h, (const unsigned char *)bad[i],
		    strlen(bad[i]), &body, &e), 0);
		assert_int_equal(vx_hdr_get_f64(&h, "spacing", v, 3, &e),
		    VX_EDATA);
		vx_hdr_free(&h);
	}
}

/* A VOLM chunk round trip keeps spacing 0.5 and origin -0.25 exactly, and
 * its header text has '.'.  Oracle: the values set. */
static void
volume_chunk(void **state)
{
	int64_t d[3] = { 2, 2, 2 };
	vx_err e = { 0, "" };
	vx_grid g, h;
	vx_chunk c;

	(void)state;
	need_comma();
	assert_int_equal(vx_grid_alloc(&g, d, VX_F32, NULL, &e), 0);
	g.spacing[0] = g.spacing[1] = g.spacing[2] = 0.5;
	g.origin[0] = -0.25;
	vx_grid_set(&g, 1, 1, 1, 1.5);
	vx_grid_range(&g);
	assert_int_equal(vx_grid_to_chunk(&g, 0, &c, &e), 0);
	assert_non_null(memmem(c.data, c.len, "spacing: 0.5 0.5 0.5\n", 21));
	assert_non_null(memmem(c.data, c.len, "origin: -0.25 0 0\n", 18));
	assert_non_null(memmem(c.data, c.len, "range: 0 1.5\n", 13));
	assert_int_equal(vx_grid_from_chunk(&h, &c, &e), 0);
	assert_true(h.spacing[1] == 0.5 && h.origin[0] == -0.25 &&
	    h.vmax == 1.5);
	vx_grid_free(&h);
	vx_chunk_free(&c);
	vx_grid_free(&g);
}

/* Scene text: numbers read and written with '.', a ',' is an error.
 * Oracle: formats/scene.md (numbers). */
static void
scene_text(void **state)
{
	static const char text[] = "surface iso 0.5 opacity 0.25\n";
	vx_err e = { 0, "" };
	vx_scene s;
	char *out;
	size_t n;

	(void)state;
	need_comma();
	vx_scene_init(&s);
	assert_int_equal(vx_scene_parse(&s, text, strlen(text), &e), 0);
	assert_true(s.nsurface == 1 && s.surface[0].iso == 0.5);
	assert_int_equal(vx_scene_format(&s, &out, &n, &e), 0);
	assert_non_null(strstr(out, "iso 0.5"));
	assert_non_null(strstr(out, "0.25"));
	assert_null(strchr(out, ','));
	free(out);
	vx_scene_init(&s);
	assert_int_not_equal(vx_scene_parse(&s, "surface iso 0,5\n", 16, &e), 0);
}

/* NRRD: "spacings: 0.5 ..." imports as 0.5; the export writes '.'.
 * PFM: the scale "-1.0" reads.  Oracle: the NRRD and PFM specifications. */
static void
nrrd_and_pfm(void **state)
{
	static const char nrrd[] = "NRRD0004\ntype: uchar\ndimension: 3\n"
	    "sizes: 2 1 1\nspacings: 0.5 0.25 2\nencoding: raw\n\n\x01\x02";
	static const char pfm[] = "Pf\n1 1\n-1.0\n\0\0\0\x3f";
	vx_err e = { 0, "" };
	vx_image img;
	vx_grid g;
	char buf[1024];
	size_t n;
	FILE *f;

	(void)state;
	need_comma();
	assert_int_equal(vx_import_nrrd_mem(&g, nrrd, sizeof nrrd - 1, NULL,
	    &e), 0);
	assert_true(g.spacing[0] == 0.5 && g.spacing[1] == 0.25 &&
	    g.spacing[2] == 2);
	g.origin[1] = 1.5;
	assert_non_null(f = tmpfile());
	assert_int_equal(vx_export_nrrd(&g, f, 0, &e), 0);
	rewind(f);
	n = fread(buf, 1, sizeof buf - 1, f);
	buf[n] = '\0';
	fclose(f);
	assert_non_null(strstr(buf, "space directions: (0.5,0,0) (0,0.25,0) "
	    "(0,0,2)\n"));
	assert_non_null(strstr(buf, "space origin: (0,1.5,0)\n"));
	vx_grid_free(&g);
	assert_int_equal(vx_pfm_read_mem(&img, pfm, sizeof pfm - 1, &e), 0);
	assert_true(img.w == 1 && img.h == 1 && img.px[0] == 0.5f);
	vx_image_free(&img);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(strtod_and_printf),
		cmocka_unit_test(number_grammar),
		cmocka_unit_test(stream_headers),
		cmocka_unit_test(volume_chunk),
		cmocka_unit_test(scene_text),
		cmocka_unit_test(nrrd_and_pfm),
	};
	return cmocka_run_group_tests(tests, setup, teardown);
}
