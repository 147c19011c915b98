/* import.c: format names, detection from magic bytes and names, and the
 * file and any-format entry points of the importers. */
#include "import_priv.h"
#include "vx_scan.h"

#include <libgen.h>
#include <unistd.h>
#include <stdlib.h>
#include <string.h>

static const vx_enum_name format_names[] = {
	{ "raw", VX_FORMAT_RAW }, { "nrrd", VX_FORMAT_NRRD },
	{ "nifti", VX_FORMAT_NIFTI }, { "vtk", VX_FORMAT_VTK },
	{ NULL, VX_FORMAT_UNKNOWN }
};
const vx_enum vx_format_enum = { "format", format_names, "unknown", 0 };

static const vx_enum_name endian_names[] = {
	{ "little", 0 }, { "big", 1 }, { NULL, -1 }
};
const vx_enum vx_endian_enum = { "byte order", endian_names, "unknown", 1 };

void
vx_import_opts_init(vx_import_opts *o)
{
	memset(o, 0, sizeof *o);
	vx_raw_info_init(&o->raw);
}

/* ends: name ends with suffix, ignoring case. */
static int
ends(const char *name, size_t n, const char *suffix)
{
	size_t k = strlen(suffix);

	return n >= k && vx_word_eq(name + n - k, k, suffix, 1);
}

static vx_format
from_name(const char *name)
{
	size_t n;

	if (name == NULL)
		return VX_FORMAT_UNKNOWN;
	n = strlen(name);
	if (ends(name, n, ".gz"))
		n -= 3;
	if (ends(name, n, ".nrrd") || ends(name, n, ".nhdr"))
		return VX_FORMAT_NRRD;
	if (ends(name, n, ".nii") || ends(name, n, ".hdr"))
		return VX_FORMAT_NIFTI;
	if (ends(name, n, ".vtk"))
		return VX_FORMAT_VTK;
	if (ends(name, n, ".raw"))
		return VX_FORMAT_RAW;
	return VX_FORMAT_UNKNOWN;
}

static vx_format
from_magic(const unsigned char *p, size_t n)
{
	if (n >= 7 && memcmp(p, "NRRD000", 7) == 0)
		return VX_FORMAT_NRRD;
	if (n >= 9 && memcmp(p, "NRRD00.01", 9) == 0)
		return VX_FORMAT_NRRD;
	if (n >= 14 && memcmp(p, "# vtk DataFile", 14) == 0)
		return VX_FORMAT_VTK;
	if (n >= 348 && ((p[0] == 0x5c && p[1] == 1 && p[2] == 0 &&
	    p[3] == 0) || (p[0] == 0 && p[1] == 0 && p[2] == 1 &&
	    p[3] == 0x5c)) && (memcmp(p + 344, "n+1", 4) == 0 ||
	    memcmp(p + 344, "ni1", 4) == 0))
		return VX_FORMAT_NIFTI;
	return VX_FORMAT_UNKNOWN;
}

vx_format
vx_import_detect(const void *buf, size_t n, const char *name)
{
	const unsigned char *p;
	size_t avail;
	vx_format f = VX_FORMAT_UNKNOWN;
	vx_imp_src s;

	/* a decompression error here just means "not recognized" */
	if (vx_imp_src_auto(&s, buf, n, NULL) == 0) {
		if (vx_imp_peek(&s, 352, &p, &avail, NULL) == 0)
			f = from_magic(p, avail);
		vx_imp_src_close(&s);
	}
	return f != VX_FORMAT_UNKNOWN ? f : from_name(name);
}

int
vx_import_mem(vx_grid *g, const void *buf, size_t n, const char *name,
    const char *dir, const vx_import_opts *o, vx_err *e)
{
	vx_format f = o->format;

	vx_grid_init(g);
	if (f == VX_FORMAT_UNKNOWN)
		f = vx_import_detect(buf, n, name);
	switch (f) {
	case VX_FORMAT_RAW:
		if (o->format != VX_FORMAT_RAW || o->raw.type ==
		    VX_SCALAR_UNKNOWN)
			return vx_err_set(e, VX_EUSAGE, "raw data: give its dims "
			    "and type (vread --raw NX,NY,NZ --type T)");
		return vx_import_raw_mem(g, buf, n, &o->raw, e);
	case VX_FORMAT_NRRD:
		return vx_import_nrrd_mem(g, buf, n, dir, e);
	case VX_FORMAT_NIFTI:
		return vx_import_nifti_mem(g, buf, n, e);
	case VX_FORMAT_VTK:
		return vx_import_vtk_mem(g, buf, n, e);
	default:
		if (n >= VX_SIGNATURE_LEN && memcmp(buf, VX_SIGNATURE,
		    VX_SIGNATURE_LEN) == 0)
			return vx_err_set(e, VX_EDATA, "this is a voxlux stream "
			    "already, not a volume to import");
		return vx_err_set(e, VX_EDATA, "unknown format (not NRRD, "
		    "NIfTI-1 or VTK; for raw data give --raw and --type)");
	}
}

/* pair_image: the .img beside a .hdr (or .hdr.gz): tries .img then
 * .img.gz; NULL when the name is not a .hdr. */
static char *
pair_image(const char *path)
{
	size_t n = strlen(path), base;
	char *s;

	if (ends(path, n, ".hdr"))
		base = n - 4;
	else if (ends(path, n, ".hdr.gz"))
		base = n - 7;
	else
		return NULL;
	if ((s = malloc(base + 8)) == NULL)
		return NULL;
	memcpy(s, path, base);
	memcpy(s + base, ".img", 5);
	if (access(s, R_OK) != 0)
		memcpy(s + base, ".img.gz", 8);
	return s;
}

int
vx_import_file(vx_grid *g, const char *path, const vx_import_opts *o,
    vx_err *e)
{
	const char *name = strcmp(path, "-") == 0 ? NULL : path;
	char *dcopy = NULL, *img = NULL;
	const char *dir = ".";
	vx_imp_file f, fi;
	vx_format fmt;
	int rc;

	vx_grid_init(g);
	if ((rc = vx_imp_file_load(&f, path, e)) != 0)
		return rc;
	fmt = o->format != VX_FORMAT_UNKNOWN ? o->format :
	    vx_import_detect(f.p, f.n, name);
	if (name != NULL) {
		if ((dcopy = strdup(name)) == NULL) {
			vx_imp_file_free(&f);
			return vx_err_set(e, VX_ENOMEM, "out of memory");
		}
		dir = dirname(dcopy);
	}
	if (fmt == VX_FORMAT_NIFTI && name != NULL &&
	    (img = pair_image(name)) != NULL) {
		if ((rc = vx_imp_file_load(&fi, img, e)) == 0) {
			rc = vx_import_nifti_pair_mem(g, f.p, f.n, fi.p, fi.n, e);
			vx_imp_file_free(&fi);
		}
	} else {
		vx_import_opts oo = *o;

		oo.format = fmt;
		rc = vx_import_mem(g, f.p, f.n, name, dir, &oo, e);
	}
	if (rc != 0 && rc != VX_ENOINPUT)
		vx_err_push(e, "%s", name ? name : "<stdin>");
	free(img);
	free(dcopy);
	vx_imp_file_free(&f);
	return rc;
}
