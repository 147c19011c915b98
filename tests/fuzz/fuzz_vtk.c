/* fuzz_vtk.c: libFuzzer target for the VTK legacy STRUCTURED_POINTS reader
 * (vx_import_vtk_mem). */
#include "fuzz.h"
#include "vx_import.h"

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	volatile double sink = 0;
	vx_grid g;
	vx_err e;
	int rc;

	vx_err_clear(&e);
	rc = vx_import_vtk_mem(&g, data, size, &e);
	fuzz_err_check(rc, &e);
	if (rc == 0) {
		sink += fuzz_grid_touch(&g);
		vx_grid_free(&g);
	}
	(void)sink;
	return 0;
}
