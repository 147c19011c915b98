/* fuzz_pfm.c: libFuzzer target for the PFM reader (vx_pfm_read_mem); an
 * image that reads is written back and must read back bit-identical. */
#include "fuzz.h"

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	volatile double sink = 0;
	vx_image img, back;
	char *buf = NULL;
	size_t n = 0;
	vx_err e;
	FILE *f;
	int rc;

	vx_err_clear(&e);
	rc = vx_pfm_read_mem(&img, data, size, &e);
	fuzz_err_check(rc, &e);
	if (rc != 0)
		return 0;
	sink += fuzz_image_touch(&img);
	if ((f = open_memstream(&buf, &n)) != NULL) {
		rc = vx_pfm_write(&img, f, &e);
		fclose(f);
		if (rc != 0)
			fuzz_fail("pfm: a read image cannot be written");
		if (vx_pfm_read_mem(&back, buf, n, &e) != 0)
			fuzz_fail("pfm: a written image does not read back");
		if (back.w != img.w || back.h != img.h || back.nc != img.nc ||
		    memcmp(back.px, img.px, vx_image_nvalue(&img) *
		    sizeof(float)) != 0)
			fuzz_fail("pfm: roundtrip changed the image");
		vx_image_free(&back);
		free(buf);
	}
	vx_image_free(&img);
	(void)sink;
	return 0;
}
