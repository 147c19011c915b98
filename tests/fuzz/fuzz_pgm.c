/* fuzz_pgm.c: libFuzzer target for the binary PGM reader
 * (vx_pgm_read_mem, heightfield's maps); a decoded image is one channel
 * of values in [0,1], each a sample over the maxval. */
#include "fuzz.h"

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	volatile double sink = 0;
	vx_image img;
	vx_err e;
	int rc, maxval = 0;

	vx_err_clear(&e);
	rc = vx_pgm_read_mem(&img, data, size, &maxval, &e);
	fuzz_err_check(rc, &e);
	if (rc != 0)
		return 0;
	sink += fuzz_image_touch(&img);
	if (img.nc != 1 || maxval < 1 || maxval > 65535)
		fuzz_fail("pgm: not one channel, or maxval out of range");
	for (size_t i = 0; i < vx_image_nvalue(&img); i++) {
		double k = img.px[i] * (double)maxval;

		/* a float's rounding, times the maxval: up to 2^16 2^-24 */
		if (!(img.px[i] >= 0 && img.px[i] <= 1) ||
		    fabs(k - floor(k + 0.5)) > (double)maxval / (1 << 23))
			fuzz_fail("pgm: value outside [0,1] or not a sample over "
			    "the maxval");
	}
	vx_image_free(&img);
	(void)sink;
	return 0;
}
