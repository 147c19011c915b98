/* fuzz_hdr.c: libFuzzer target for the Radiance RGBE reader
 * (vx_hdr_read_mem).  An image that reads is written back (run-length
 * scanlines) and, when its header scaled nothing, must read back
 * bit-identical (RGBE values are fixed points of the writer); then it is
 * made an environment map (fuzz_env.h). */
#include "fuzz_env.h"

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	volatile double sink = 0;
	vx_hdr_info in;
	vx_image img, back;
	char *buf = NULL;
	size_t n = 0;
	vx_err e;
	FILE *f;
	int rc;

	vx_err_clear(&e);
	rc = vx_hdr_read_mem(&img, data, size, &in, &e);
	fuzz_err_check(rc, &e);
	if (rc != 0)
		return 0;
	sink += fuzz_image_touch(&img);
	if (img.nc != 3 || in.nrle + in.nflat != (in.orient[1] == 'X' ?
	    img.w : img.h))
		fuzz_fail("hdr: channel or scanline count");
	if (in.exposure == 1 && in.colorcorr[0] == 1 && in.colorcorr[1] == 1 &&
	    in.colorcorr[2] == 1 && (f = open_memstream(&buf, &n)) != NULL) {
		rc = vx_hdr_write(&img, f, 1, &e);
		fclose(f);
		if (rc != 0)
			fuzz_fail("hdr: a read image cannot be written");
		if (vx_hdr_read_mem(&back, buf, n, NULL, &e) != 0)
			fuzz_fail("hdr: a written image does not read back");
		if (back.w != img.w || back.h != img.h ||
		    memcmp(back.px, img.px, vx_image_nvalue(&img) *
		    sizeof(float)) != 0)
			fuzz_fail("hdr: roundtrip changed the image");
		vx_image_free(&back);
		free(buf);
	}
	fuzz_env_check(&img);
	vx_image_free(&img);
	(void)sink;
	return 0;
}
