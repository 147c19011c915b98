/* fuzz_nifti.c: libFuzzer target for the NIfTI-1 readers: the single-file
 * form (vx_import_nifti_mem) of the whole input, and the .hdr/.img pair
 * (vx_import_nifti_pair_mem) with the first 348 bytes as the header. */
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
	vx_grid g;
	vx_err e;

	vx_err_clear(&e);
	one(vx_import_nifti_mem(&g, data, size, &e), &g, &e);
	if (size >= 348) {
		vx_err_clear(&e);
		one(vx_import_nifti_pair_mem(&g, data, 348, data + 348,
		    size - 348, &e), &g, &e);
	}
	return 0;
}
