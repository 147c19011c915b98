/* test_stats.c: volume statistics: counts, range, mean, the layout-independent
 * checksum and the histogram's bin edges. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>
#include <zlib.h>

#include "vx_stats.h"

/* Same samples in linear and bricked layouts give the same statistics; the
 * checksum is zlib's crc32 of the samples written out by hand in x-fastest
 * little-endian order (the oracle), padding left out. */
static void
layout_independent(void **state)
{
	static const char *specs[] = { "linear", "bricked 2x2x2",
	    "bricked 4x2x1 2x2x2" };
	static const vx_type types[] = { VX_U8, VX_U16, VX_I16, VX_F32 };
	int64_t d[3] = { 5, 3, 7 };

	(void)state;
	for (size_t ti = 0; ti < 4; ti++) {
		unsigned char want[5 * 3 * 7 * 4], *w = want;
		double sum = 0;

		for (int z = 0; z < 7; z++)
			for (int y = 0; y < 3; y++)
				for (int x = 0; x < 5; x++) {
					int v = x * 7 - y * 5 + z * 3;

					if (types[ti] == VX_U8 || types[ti] == VX_U16)
						v += 20;
					sum += v;
					if (types[ti] == VX_U8)
						*w++ = (unsigned char)v;
					else if (types[ti] == VX_F32) {
						float f = (float)v;
						uint32_t u;

						memcpy(&u, &f, 4);
						for (int b = 0; b < 4; b++)
							*w++ = (unsigned char)(u >> 8 * b);
					} else {
						*w++ = (unsigned char)(v & 0xff);
						*w++ = (unsigned char)((v >> 8) & 0xff);
					}
				}
		uint32_t crc = (uint32_t)crc32(crc32(0, Z_NULL, 0), want,
		    (uInt)(w - want));

		for (size_t si = 0; si < 3; si++) {
			vx_grid g;
			vx_stats st;
			vx_err e = { 0, "" };

			assert_int_equal(vx_grid_alloc(&g, d, types[ti], specs[si],
			    &e), 0);
			for (int z = 0; z < 7; z++)
				for (int y = 0; y < 3; y++)
					for (int x = 0; x < 5; x++)
						vx_grid_set(&g, x, y, z, x * 7 - y * 5 +
						    z * 3 + (types[ti] == VX_U8 ||
						    types[ti] == VX_U16 ? 20 : 0));
			/* garbage in the padding (the last stored sample of
			 * both bricked layouts here) must not count */
			if (g.nsample > 105)
				memset((char *)g.data + (g.nsample - 1) *
				    vx_type_size(g.type), 0x7f,
				    vx_type_size(g.type));
			vx_grid_stats(&g, &st);
			assert_int_equal(st.count, 105);
			assert_int_equal(st.nfinite, 105);
			assert_int_equal(st.crc, crc);
			assert_true(st.has_range);
			double off = types[ti] == VX_U8 || types[ti] == VX_U16 ? 20 : 0;
			assert_true(st.vmin == -10 + off && st.vmax == 28 + 18 + off);
			assert_true(fabs(st.mean - sum / 105) < 1e-12);
			vx_grid_free(&g);
		}
	}
}

/* NaN and infinities are counted apart and stay out of range and mean. */
static void
nonfinite(void **state)
{
	int64_t d[3] = { 3, 2, 1 };
	vx_grid g;
	vx_stats st;
	vx_err e = { 0, "" };
	uint64_t h[8];

	(void)state;
	assert_int_equal(vx_grid_alloc(&g, d, VX_F32, NULL, &e), 0);
	vx_grid_set(&g, 0, 0, 0, NAN);
	vx_grid_set(&g, 1, 0, 0, INFINITY);
	vx_grid_set(&g, 2, 0, 0, -INFINITY);
	vx_grid_set(&g, 0, 1, 0, -1);
	vx_grid_set(&g, 1, 1, 0, 2);
	vx_grid_set(&g, 2, 1, 0, 5);
	vx_grid_stats(&g, &st);
	assert_true(st.nnan == 1 && st.nposinf == 1 && st.nneginf == 1);
	assert_true(st.nfinite == 3 && st.vmin == -1 && st.vmax == 5);
	assert_true(st.mean == 2);
	/* bins over [-1, 5] of width 1.5: -1 in 0, 2 in bin 2, 5 (the top
	 * edge) in the last */
	assert_int_equal(vx_grid_histogram(&g, -1, 5, 4, h, &e), 0);
	assert_true(h[0] == 1 && h[1] == 0 && h[2] == 1 && h[3] == 1);
	/* values outside the bounds are not counted */
	assert_int_equal(vx_grid_histogram(&g, 0, 3, 3, h, &e), 0);
	assert_true(h[0] == 0 && h[1] == 0 && h[2] == 1);
	/* a single value: everything equal to it in bin 0 */
	assert_int_equal(vx_grid_histogram(&g, 2, 2, 5, h, &e), 0);
	assert_true(h[0] == 1 && h[1] + h[2] + h[3] + h[4] == 0);
	/* extreme widths (oracle: the bin formula in exact arithmetic): a
	 * subnormal one, whose scale nbins / (hi - lo) overflows, and one
	 * beyond the double range */
	vx_grid_set(&g, 0, 1, 0, 0);       /* lo itself: bin 0 */
	vx_grid_set(&g, 1, 1, 0, 0x1p-149);   /* both beyond hi */
	vx_grid_set(&g, 2, 1, 0, 1);
	assert_int_equal(vx_grid_histogram(&g, 0, 0x1p-1073, 4, h, &e), 0);
	assert_true(h[0] == 1 && h[1] == 0 && h[2] == 0 && h[3] == 0);
	assert_int_equal(vx_grid_histogram(&g, -0x1p-1074, 0x1p-1074, 2, h,
	    &e), 0);
	assert_true(h[0] == 0 && h[1] == 1);
	vx_grid_set(&g, 0, 1, 0, -3e38);   /* all at the middle, to within */
	vx_grid_set(&g, 1, 1, 0, 0);       /* 2^-900 of the width */
	vx_grid_set(&g, 2, 1, 0, 3e38);
	assert_int_equal(vx_grid_histogram(&g, -1.7e308, 1.7e308, 4, h, &e), 0);
	assert_true(h[0] == 0 && h[1] == 0 && h[2] == 3 && h[3] == 0);
	assert_int_equal(vx_grid_histogram(&g, -1.7e308, 0, 2, h, &e), 0);
	assert_true(h[0] == 0 && h[1] == 2);
	vx_grid_set(&g, 0, 1, 0, -1);
	vx_grid_set(&g, 1, 1, 0, 2);
	vx_grid_set(&g, 2, 1, 0, 5);
	assert_int_equal(vx_grid_histogram(&g, 2, 1, 5, h, &e), VX_EUSAGE);
	assert_int_equal(vx_grid_histogram(&g, 0, INFINITY, 5, h, &e),
	    VX_EUSAGE);
	assert_int_equal(vx_grid_histogram(&g, 0, 1, 0, h, &e), VX_EUSAGE);
	/* all non-finite: no range */
	for (int x = 0; x < 3; x++)
		vx_grid_set(&g, x, 1, 0, NAN);
	vx_grid_stats(&g, &st);
	assert_true(!st.has_range && st.vmin == 0 && st.vmax == 0 &&
	    st.mean == 0 && st.nnan == 4);
	vx_grid_free(&g);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(layout_independent),
		cmocka_unit_test(nonfinite),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
