/* test_pgm.c: the binary PGM reader (vx_pgm_read_mem).
 *
 * Oracles: each value is its sample over the maxval (8 and 16 bits, a
 * maxval below the type's largest, comments in the header), rows top
 * first; a table of malformed headers and sizes each refused with
 * VX_EDATA and nothing allocated; the sniffer tells P5 apart. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "vx_imageio.h"

static void
reads(void **state)
{
	static const unsigned char g8[] = "P5\n3 2\n255\n\x00\x01\x80\xfe\xff\x07";
	static const unsigned char g16[] = "P5 2 1\t65535\n\x00\x01\xff\xfe";
	static const unsigned char cm[] = "P5# magic\n#x\n2 1 # size\n100\n"
	    "\x00\x64";
	vx_image img;
	vx_err e = { 0, "" };
	int mv = 0;

	(void)state;
	assert_int_equal(vx_pgm_read_mem(&img, g8, sizeof g8 - 1, &mv, &e), 0);
	assert_int_equal(img.w, 3);
	assert_int_equal(img.h, 2);
	assert_int_equal(img.nc, 1);
	assert_int_equal(mv, 255);
	assert_true(img.px[0] == 0);
	assert_true(img.px[1] == (float)(1.0 / 255));
	assert_true(img.px[2] == (float)(128.0 / 255));
	assert_true(img.px[4] == 1);           /* row 1, column 1 */
	assert_true(img.px[5] == (float)(7.0 / 255));
	vx_image_free(&img);
	assert_int_equal(vx_pgm_read_mem(&img, g16, sizeof g16 - 1, &mv, &e),
	    0);
	assert_int_equal(mv, 65535);
	assert_true(img.px[0] == (float)(1.0 / 65535));   /* big-endian */
	assert_true(img.px[1] == (float)(65534.0 / 65535));
	vx_image_free(&img);
	assert_int_equal(vx_pgm_read_mem(&img, cm, sizeof cm - 1, &mv, &e), 0);
	assert_int_equal(mv, 100);
	assert_true(img.px[1] == 1);
	vx_image_free(&img);
	assert_int_equal(vx_image_sniff(g8, sizeof g8 - 1), VX_IMGFMT_PGM);
	assert_int_equal(vx_image_sniff(cm, sizeof cm - 1), VX_IMGFMT_PGM);
	assert_string_equal(vx_image_format_name(VX_IMGFMT_PGM), "PGM");
}

static void
refuses(void **state)
{
	static const struct { const char *data; size_t n; const char *msg; }
	    t[] = {
#define C(s, m) { s, sizeof s - 1, m }
		C("P2\n1 1\n255\n0\n", "no P5 magic"),
		C("P5", "size"),
		C("P5\n1\n", "size"),
		C("P5\n1 1\n", "maxval"),
		C("P5\n1 1 255", "one whitespace"),
		C("P5\n1 1\n0\n\x00", "maxval 0"),
		C("P5\n1 1\n70000\n\x00\x00", "maxval 70000"),
		C("P5\n0 1\n255\n", "size 0 x 1"),
		C("P5\n70000 1\n255\n\x00", "each side"),
		C("P5\n1234567890 1\n255\n", "size"),
		C("P5\n2 2\n255\n\x00\x00\x00", "needs 4 data bytes"),
		C("P5\n1 1\n255\n\x00\x00", "the file has 2"),
		C("P5\n1 1\n300\n\x00", "needs 2 data bytes"),
		C("P5\n2 1\n9\n\x01\x0a", "exceeds maxval 9"),
#undef C
	};
	vx_image img;

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_err e = { 0, "" };

		if (vx_pgm_read_mem(&img, t[i].data, t[i].n, NULL, &e) !=
		    VX_EDATA)
			fail_msg("case %zu accepted", i);
		if (strstr(e.msg, t[i].msg) == NULL)
			fail_msg("case %zu: '%s' lacks '%s'", i, e.msg, t[i].msg);
		assert_null(img.px);
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(reads),
		cmocka_unit_test(refuses),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
