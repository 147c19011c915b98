/* fuzz_tetvtk.c: libFuzzer target for the VTK legacy UNSTRUCTURED_GRID
 * tet-mesh importer (vx_tetmesh_import_vtk); a mesh that imports is touched
 * whole, round-tripped through a TETM chunk, and ray cast through its leaf
 * grid (fuzz_tetmesh_touch).  The first byte picks the options. */
#include "fuzz.h"

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	volatile double sink = 0;
	vx_tetimport_opt opt = { NULL, 0 };
	vx_tetimport_info info;
	vx_tetmesh m;
	vx_err e;
	int rc;

	if (size < 1)
		return 0;
	opt.skip_volume_cells = data[0] & 1;
	if (data[0] & 2)
		opt.scalar = "density";
	vx_err_clear(&e);
	rc = vx_tetmesh_import_vtk(&m, data + 1, size - 1, &opt, &info, &e);
	fuzz_err_check(rc, &e);
	if (rc == 0) {
		sink += fuzz_tetmesh_touch(&m, 1);
		vx_tetmesh_free(&m);
	}
	(void)sink;
	return 0;
}
