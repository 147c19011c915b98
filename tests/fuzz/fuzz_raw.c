/* fuzz_raw.c: libFuzzer target for the raw reader (vx_import_raw_mem) and
 * format detection (vx_import_mem with no format given).  The first 8 bytes
 * choose the raw parameters: three signed 16-bit dims (zero and negative
 * included), the source type, the byte order and a skip; the rest is the
 * file. */
#include "fuzz.h"
#include "vx_import.h"

static void
one(int rc, vx_grid *g, vx_err *e)
{
	volatile double sink = 0;

	fuzz_err_check(rc, e);
	if (rc == 0) {
		sink += fuzz_grid_touch(g);
		vx_grid_free(g);
	}
	(void)sink;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	vx_import_opts o;
	vx_raw_info r;
	vx_grid g;
	vx_err e;

	vx_err_clear(&e);
	vx_import_opts_init(&o);
	one(vx_import_mem(&g, data, size, NULL, NULL, &o, &e), &g, &e);
	if (size < 8)
		return 0;
	vx_raw_info_init(&r);
	for (int a = 0; a < 3; a++)
		r.dims[a] = (int16_t)(data[2 * a] | data[2 * a + 1] << 8);
	r.type = (vx_scalar)(data[6] % (VX_SCALAR_LAST + 1));
	r.big_endian = data[7] & 1;
	r.skip = data[7] >> 1;
	vx_err_clear(&e);
	one(vx_import_raw_mem(&g, data + 8, size - 8, &r, &e), &g, &e);
	return 0;
}
