/* fuzz_exr.c: libFuzzer target for the OpenEXR reader (vx_exr_read_mem,
 * the OpenEXR library behind it); an image that reads is made an
 * environment map (fuzz_env.h): NaN and infinite pixels must be refused
 * cleanly there. */
#include "fuzz_env.h"

/* big_window: some dataWindow or displayWindow attribute of the input
 * claims more than 2^20 pixels.  Such inputs are legal up to the image
 * limits (2^28 pixels), but decoding gigabytes makes the target crawl, so
 * the target skips them; vx_exr_read_mem's own limits are checked in
 * test_hdr.c. */
static int
big_window(const uint8_t *d, size_t n)
{
	static const char k0[] = "dataWindow\0box2i", k1[] =
	    "displayWindow\0box2i";
	static const char *const keys[2] = { k0, k1 };
	static const size_t klen[2] = { sizeof k0, sizeof k1 };  /* NULs in */

	for (int k = 0; k < 2; k++) {
		size_t kl = klen[k];
		const uint8_t *p = d;

		while ((p = memmem(p, n - (size_t)(p - d), keys[k], kl)) != NULL) {
			int32_t b[4];

			p += kl;
			if ((size_t)(d + n - p) < 20)
				break;
			memcpy(b, p + 4, 16);
			{
				/* each side is below 2^33: compare them before
				 * their product can overflow */
				int64_t w = (int64_t)b[2] - b[0] + 1;
				int64_t h = (int64_t)b[3] - b[1] + 1;

				if (w > ((int64_t)1 << 20) || h > ((int64_t)1 << 20) ||
				    (w > 0 && h > 0 && w * h > ((int64_t)1 << 20)))
					return 1;
			}
		}
	}
	return 0;
}

/* big_attribute: an attribute of the first header claims more bytes than
 * the input has.  The library (3.1) allocates what the size says before it
 * reads, which takes a second for a gigabyte: skipped for speed, as above
 * (the library then only fails to read). */
static int
big_attribute(const uint8_t *d, size_t n)
{
	size_t i = 8;

	while (i < n && d[i] != 0) {
		int32_t len;

		for (int part = 0; part < 2; part++) {    /* name, type */
			const uint8_t *z = memchr(d + i, 0, n - i);

			if (z == NULL)
				return 0;
			i = (size_t)(z - d) + 1;
		}
		if (n - i < 4)
			return 0;
		memcpy(&len, d + i, 4);
		i += 4;
		if (len < 0 || (size_t)len > n - i)
			return 1;
		i += (size_t)len;
	}
	return 0;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	volatile double sink = 0;
	vx_image img;
	vx_err e;
	int rc;

	if (big_window(data, size) || big_attribute(data, size))
		return 0;
	vx_err_clear(&e);
	rc = vx_exr_read_mem(&img, data, size, &e);
	fuzz_err_check(rc, &e);
	if (rc != 0)
		return 0;
	sink += fuzz_image_touch(&img);
	if (img.nc != 3)
		fuzz_fail("exr: not 3 channels");
	fuzz_env_check(&img);
	vx_image_free(&img);
	(void)sink;
	return 0;
}
