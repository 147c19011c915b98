/* fuzz_png.c: libFuzzer target for the PNG reader (vx_image_png_read_mem,
 * libpng underneath); a decoded image must have values in [0,1]. */
#include "fuzz.h"

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	volatile double sink = 0;
	vx_image img;
	vx_err e;
	int rc, bits = 0;

	vx_err_clear(&e);
	rc = vx_image_png_read_mem(&img, data, size, &bits, &e);
	fuzz_err_check(rc, &e);
	if (rc != 0)
		return 0;
	sink += fuzz_image_touch(&img);
	if (bits != 8 && bits != 16)
		fuzz_fail("png: bits neither 8 nor 16");
	for (size_t i = 0; i < vx_image_nvalue(&img); i++)
		if (!(img.px[i] >= 0 && img.px[i] <= 1))
			fuzz_fail("png: value outside [0,1]");
	vx_image_free(&img);
	(void)sink;
	return 0;
}
