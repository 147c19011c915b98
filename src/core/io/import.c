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

/* refused: why format f, detected from the n bytes at p, cannot be read
 * with options o (raw data without --raw and --type; a voxlux stream or an
 * unknown format), or 0 when its reader can take it. */
static int
refused(vx_format f, const vx_import_opts *o, const void *p, size_t n,
    vx_err *e)
{
	switch (f) {
	case VX_FORMAT_RAW:
		if (o->format != VX_FORMAT_RAW || o->raw.type ==
		    VX_SCALAR_UNKNOWN)
			return vx_err_set(e, VX_EUSAGE, "raw data: give its dims "
			    "and type (vread --raw NX,NY,NZ --type T)");
		return 0;
	case VX_FORMAT_NRRD:
	case VX_FORMAT_NIFTI:
	case VX_FORMAT_VTK:
		return 0;
	default:
		if (n >= VX_SIGNATURE_LEN && memcmp(p, VX_SIGNATURE,
		    VX_SIGNATURE_LEN) == 0)
			return vx_err_set(e, VX_EDATA, "this is a voxlux stream "
			    "already, not a volume to import");
		return vx_err_set(e, VX_EDATA, "unknown format (not NRRD, "
		    "NIfTI-1 or VTK; for raw data give --raw and --type)");
	}
}

int
vx_import_mem(vx_grid *g, const void *buf, size_t n, const char *name,
    const char *dir, const vx_import_opts *o, vx_err *e)
{
	vx_format f = o->format;
	int rc;

	vx_grid_init(g);
	if (f == VX_FORMAT_UNKNOWN)
		f = vx_import_detect(buf, n, name);
	if ((rc = refused(f, o, buf, n, e)) != 0)
		return rc;
	switch (f) {
	case VX_FORMAT_RAW:
		return vx_import_raw_mem(g, buf, n, &o->raw, e);
	case VX_FORMAT_NRRD:
		return vx_import_nrrd_mem(g, buf, n, dir, e);
	case VX_FORMAT_NIFTI:
		return vx_import_nifti_mem(g, buf, n, e);
	default:
		return vx_import_vtk_mem(g, buf, n, e);
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

/* import_stream: a volume from an input read as its reader asks (not
 * mapped): the format from the gunzipped start, then the reader over it */
static int
import_stream(vx_grid *g, vx_imp_in *in, const char *name, const char *dir,
    const vx_import_opts *o, vx_err *e)
{
	const unsigned char *p;
	size_t avail;
	vx_format f = o->format;
	int rc;

	if ((rc = vx_imp_peek(in->top, 352, &p, &avail, e)) != 0)
		return rc;
	if (f == VX_FORMAT_UNKNOWN)
		f = from_magic(p, avail);
	if (f == VX_FORMAT_UNKNOWN)
		f = from_name(name);
	if ((rc = refused(f, o, p, avail, e)) != 0)
		return rc;
	switch (f) {
	case VX_FORMAT_RAW:
		return vx_imp_read_raw(g, in->top, &o->raw, e);
	case VX_FORMAT_NRRD:
		return vx_imp_read_nrrd(g, in->top, dir, e);
	case VX_FORMAT_NIFTI:
		return vx_imp_read_nifti(g, in->top, e);
	default:
		return vx_imp_read_vtk(g, in->top, e);
	}
}

int
vx_imp_import_in(vx_grid *g, vx_imp_in *in, const char *name,
    const vx_import_opts *o, vx_err *e)
{
	char *dcopy = NULL, *img = NULL;
	const char *dir = ".";
	vx_format fmt;
	int rc;

	vx_grid_init(g);
	if (name != NULL) {
		if ((dcopy = strdup(name)) == NULL)
			return vx_err_set(e, VX_ENOMEM, "out of memory");
		dir = dirname(dcopy);
	}
	fmt = o->format != VX_FORMAT_UNKNOWN ? o->format : in->stream ?
	    VX_FORMAT_UNKNOWN : vx_import_detect(in->f.p, in->f.n, name);
	if (!in->stream && fmt == VX_FORMAT_NIFTI && name != NULL &&
	    (img = pair_image(name)) != NULL) {
		/* the image as its header implies, whatever kind of file */
		vx_imp_in ii;

		if ((rc = vx_imp_open(&ii, img, e)) == 0) {
			rc = vx_imp_read_nifti_pair(g, in->f.p, in->f.n, ii.top,
			    e);
			vx_imp_close(&ii);
		}
	} else if (in->stream) {
		rc = import_stream(g, in, name, dir, o, e);
	} else {
		vx_import_opts oo = *o;

		oo.format = fmt;
		rc = vx_import_mem(g, in->f.p, in->f.n, name, dir, &oo, e);
	}
	if (rc != 0 && rc != VX_ENOINPUT)
		vx_err_push(e, "%s", name ? name : "<stdin>");
	free(img);
	free(dcopy);
	return rc;
}

int
vx_import_file(vx_grid *g, const char *path, const vx_import_opts *o,
    vx_err *e)
{
	vx_imp_in in;
	int rc;

	vx_grid_init(g);
	if ((rc = vx_imp_open(&in, path, e)) != 0)
		return rc;
	rc = vx_imp_import_in(g, &in, strcmp(path, "-") == 0 ? NULL : path, o,
	    e);
	vx_imp_close(&in);
	return rc;
}
