/* import_any.c: one entry point for files that may hold a volume or a tet
 * mesh (vread(1)): the file is read once and its content decides. */
#include "vx_tetimport.h"
#include "import_priv.h"

#include <string.h>
#include <strings.h>

/* token: the next blank-separated word of p[*i..n) into w (cut to cap-1);
 * 0 at the end. */
static int
token(const unsigned char *p, size_t n, size_t *i, char *w, size_t cap)
{
	size_t k = 0;

	while (*i < n && (p[*i] == ' ' || p[*i] == '\t' || p[*i] == '\r' ||
	    p[*i] == '\n'))
		(*i)++;
	while (*i < n && !(p[*i] == ' ' || p[*i] == '\t' || p[*i] == '\r' ||
	    p[*i] == '\n')) {
		if (k + 1 < cap)
			w[k++] = (char)p[*i];
		(*i)++;
	}
	w[k] = '\0';
	return k > 0;
}

int
vx_tetmesh_detect(const void *buf, size_t n)
{
	const unsigned char *p;
	size_t avail, i = 0, line;
	char w[32];
	vx_imp_src s;
	int mesh = 0;

	if (vx_imp_src_auto(&s, buf, n, NULL) != 0)
		return 0;
	/* the VTK title line may take 256 bytes */
	if (vx_imp_peek(&s, 1024, &p, &avail, NULL) != 0)
		goto out;
	while (i < avail && (p[i] == ' ' || p[i] == '\t' || p[i] == '\r' ||
	    p[i] == '\n'))
		i++;
	if (avail - i >= 11 && memcmp(p + i, "$MeshFormat", 11) == 0) {
		mesh = 1;
		goto out;
	}
	if (avail - i < 22 || strncasecmp((const char *)p + i,
	    "# vtk DataFile Version", 22) != 0)
		goto out;
	/* skip the version and title lines: then ASCII|BINARY, DATASET,
	 * the dataset's type */
	for (line = 0; line < 2; line++) {
		while (i < avail && p[i] != '\n')
			i++;
		if (i < avail)
			i++;
	}
	if (token(p, avail, &i, w, sizeof w) &&
	    (strcasecmp(w, "ASCII") == 0 || strcasecmp(w, "BINARY") == 0) &&
	    token(p, avail, &i, w, sizeof w) && strcasecmp(w, "DATASET") == 0 &&
	    token(p, avail, &i, w, sizeof w))
		mesh = strcasecmp(w, "UNSTRUCTURED_GRID") == 0;
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
