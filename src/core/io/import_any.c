/* import_any.c: one entry point for files that may hold a volume or a tet
 * mesh (vread(1)): the file is read once and its content decides. */
#include "vx_tetimport.h"
#include "import_priv.h"
#include "vx_scan.h"

#include <string.h>
#include <strings.h>

int
vx_tetmesh_detect(const void *buf, size_t n)
{
	const unsigned char *p;
	const char *w;
	size_t avail, wn;
	vx_imp_src s;
	vx_scan k;
	int mesh = 0;

	if (vx_imp_src_auto(&s, buf, n, NULL) != 0)
		return 0;
	/* the VTK title line may take 256 bytes */
	if (vx_imp_peek(&s, 1024, &p, &avail, NULL) != 0)
		goto out;
	vx_scan_init(&k, p, avail);
	vx_scan_skip_blank(&k);
	if (vx_scan_left(&k) >= 11 && memcmp(k.p, "$MeshFormat", 11) == 0) {
		mesh = 1;
		goto out;
	}
	if (vx_scan_left(&k) < 22 || strncasecmp((const char *)k.p,
	    "# vtk DataFile Version", 22) != 0)
		goto out;
	/* past the version and title lines: ASCII|BINARY, DATASET, the
	 * dataset's type */
	vx_scan_next_line(&k);
	vx_scan_next_line(&k);
	wn = vx_scan_word(&k, &w);
	if (!vx_word_eq(w, wn, "ascii", 1) && !vx_word_eq(w, wn, "binary", 1))
		goto out;
	wn = vx_scan_word(&k, &w);
	if (!vx_word_eq(w, wn, "dataset", 1))
		goto out;
	wn = vx_scan_word(&k, &w);
	mesh = vx_word_eq(w, wn, "unstructured_grid", 1);
out:
	vx_imp_src_close(&s);
	return mesh;
}

int
vx_import_volume_or_mesh(vx_grid *g, vx_tetmesh *m, int *is_mesh,
    const char *path, const vx_import_opts *vopt,
    const vx_tetimport_opt *mopt, vx_tetimport_info *info, vx_err *e)
{
	int stdin_ = strcmp(path, "-") == 0;
	vx_imp_file f;
	int rc;

	vx_grid_init(g);
	vx_tetmesh_init(m);
	*is_mesh = 0;
	if ((rc = vx_imp_file_load(&f, path, e)) != 0)
		return rc;
	if ((vopt->format == VX_FORMAT_UNKNOWN ||
	    vopt->format == VX_FORMAT_VTK) && vx_tetmesh_detect(f.p, f.n)) {
		char name[VX_TETMESH_NAME];

		*is_mesh = 1;
		rc = vx_tetmesh_import_mem(m, f.p, f.n, mopt, info, e);
		vx_imp_file_free(&f);
		if (rc != 0)
			return vx_err_push(e, "%s", stdin_ ? "<stdin>" : path);
		vx_imp_stem(stdin_ ? "stdin" : path, name, sizeof name);
		vx_tetmesh_set_name(m, name);
		return 0;
	}
	if (!stdin_) {
		/* a volume: read it again by name (NIfTI pairs and detached
		 * NRRD data need the path) */
		vx_imp_file_free(&f);
		return vx_import_file(g, path, vopt, e);
	}
	rc = vx_import_mem(g, f.p, f.n, NULL, ".", vopt, e);
	vx_imp_file_free(&f);
	if (rc != 0 && rc != VX_ENOINPUT)
		vx_err_push(e, "<stdin>");
	return rc;
}
