/* import_any.c: one entry point for files that may hold a volume or a tet
 * mesh (vread(1)): the file is read once and its content decides. */
#include "vx_tetimport.h"
#include "import_priv.h"
#include "vx_scan.h"

#include <stdlib.h>
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
	const unsigned char *p;
	unsigned char *buf = NULL;
	size_t n;
	vx_imp_in in;
	int rc;

	vx_grid_init(g);
	vx_tetmesh_init(m);
	*is_mesh = 0;
	if ((rc = vx_imp_open(&in, path, e)) != 0)
		return rc;
	/* the content decides: the gunzipped start of a stream, the whole
	 * mapped file */
	if (in.stream)
		rc = vx_imp_peek(in.top, 1024, &p, &n, e);
	else {
		p = in.f.p;
		n = in.f.n;
	}
	if (rc == 0 && (vopt->format == VX_FORMAT_UNKNOWN ||
	    vopt->format == VX_FORMAT_VTK) && vx_tetmesh_detect(p, n)) {
		char name[VX_TETMESH_NAME];

		*is_mesh = 1;
		/* a mesh's header names no size: from a pipe or device it is
		 * read up to VX_IMP_TEXT_MAX */
		if (in.stream && (rc = vx_imp_slurp(in.top, VX_IMP_TEXT_MAX,
		    &buf, &n, e)) == 0)
			p = buf;
		if (rc == 0)
			rc = vx_tetmesh_import_mem(m, p, n, mopt, info, e);
		free(buf);
		vx_imp_close(&in);
		if (rc != 0)
			return vx_err_push(e, "%s", stdin_ ? "<stdin>" : path);
		vx_imp_stem(stdin_ ? "stdin" : path, name, sizeof name);
		vx_tetmesh_set_name(m, name);
		return 0;
	}
	if (rc == 0)
		rc = vx_imp_import_in(g, &in, stdin_ ? NULL : path, vopt, e);
	else
		vx_err_push(e, "%s", stdin_ ? "<stdin>" : path);
	vx_imp_close(&in);
	return rc;
}
