/* tetimport.c: tet mesh import by content (VTK legacy or gmsh), gzip
 * decompression, and the path wrapper (files are loaded with the volume
 * importers' helpers, import_priv.h). */
#include "vx_tetimport.h"
#include "import_priv.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int
vx_imp_mesh_values(vx_tetmesh *m, const double *val, size_t *bad, vx_err *e)
{
	size_t i;

	if ((m->val = vx_malloc((m->npoint ? m->npoint : 1) * sizeof *m->val,
	    e)) == NULL)
		return VX_ENOMEM;
	for (i = 0; i < m->npoint; i++) {
		if (isfinite(val[i]) && fabs(val[i]) > FLT_MAX) {
			*bad = i;
			return VX_EDATA;
		}
		m->val[i] = (float)val[i];
	}
	return 0;
}

/* Inflate a gzip buffer completely (at most VX_TETMESH_FILE_MAX bytes). */
static int
gunzip_all(const void *buf, size_t n, unsigned char **out, size_t *outn,
    vx_err *e)
{
	vx_imp_src s;
	unsigned char *p = NULL;
	size_t cap = 0, len = 0, got;
	int rc;

	*out = NULL;
	*outn = 0;
	if ((rc = vx_imp_src_auto(&s, buf, n, e)) != 0)
		return rc;
	for (;;) {
		if (len == cap) {
			size_t nc = cap ? 2 * cap : (size_t)1 << 20;
			unsigned char *q;
			if (cap >= VX_TETMESH_FILE_MAX) {
				rc = vx_err_set(e, VX_EDATA, "gzip: decompresses to "
				    "more than %zu bytes", VX_TETMESH_FILE_MAX);
				break;
			}
			if (nc > VX_TETMESH_FILE_MAX)
				nc = VX_TETMESH_FILE_MAX;
			if ((q = realloc(p, nc)) == NULL) {
				rc = vx_err_set(e, VX_ENOMEM, "cannot allocate %zu "
				    "bytes", nc);
				break;
			}
			p = q;
			cap = nc;
		}
		if ((rc = vx_imp_read(&s, p + len, cap - len, &got, e)) != 0)
			break;
		len += got;
		if (len < cap)
			break;  /* end of input */
	}
	vx_imp_src_close(&s);
	if (rc != 0) {
		free(p);
		return rc;
	}
	*out = p;
	*outn = len;
	return 0;
}

int
vx_tetmesh_import_mem(vx_tetmesh *m, const void *buf, size_t n,
    const vx_tetimport_opt *opt, vx_tetimport_info *info, vx_err *e)
{
	const unsigned char *p = buf;
	unsigned char *z = NULL;
	size_t i = 0;
	int rc;

	vx_tetmesh_init(m);
	if (vx_imp_is_gzip(buf, n)) {
		if ((rc = gunzip_all(buf, n, &z, &n, e)) != 0)
			return rc;
		p = z;
	}
	while (i < n && (p[i] == ' ' || p[i] == '\t' || p[i] == '\r' ||
	    p[i] == '\n'))
		i++;
	if (n - i >= 14 && memcmp(p + i, "# vtk DataFile", 14) == 0)
		rc = vx_tetmesh_import_vtk(m, p + i, n - i, opt, info, e);
	else if (n - i >= 11 && memcmp(p + i, "$MeshFormat", 11) == 0)
		rc = vx_tetmesh_import_gmsh(m, p + i, n - i, opt, info, e);
	else
		rc = vx_err_set(e, VX_EDATA, "unknown mesh format (expected a "
		    "VTK legacy file or a gmsh .msh file)");
	free(z);
	return rc;
}


int
vx_tetmesh_import(vx_tetmesh *m, const char *path,
    const vx_tetimport_opt *opt, vx_tetimport_info *info, vx_err *e)
{
	vx_imp_file f;
	char name[VX_TETMESH_NAME];
	int rc;

	vx_tetmesh_init(m);
	if ((rc = vx_imp_file_load(&f, path, e)) != 0)
		return rc;
	rc = vx_tetmesh_import_mem(m, f.p, f.n, opt, info, e);
	vx_imp_file_free(&f);
	if (rc != 0)
		return vx_err_push(e, "%s", path);
	vx_imp_stem(strcmp(path, "-") == 0 ? "stdin" : path, name, sizeof name);
	vx_tetmesh_set_name(m, name);
	return 0;
}
