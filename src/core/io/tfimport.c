/* tfimport.c: transfer-function files (vx_tfimport.h).  The readers of the
 * three formats are not written yet: every file is refused. */
#include "vx_tfimport.h"

static const vx_enum_name tf_format_names[] = {
	{ "auto", VX_TF_FORMAT_AUTO },
	{ "paraview", VX_TF_FORMAT_PARAVIEW },
	{ "slicer", VX_TF_FORMAT_SLICER },
	{ "miter", VX_TF_FORMAT_MITER },
	{ NULL, VX_TF_FORMAT_UNKNOWN }
};
const vx_enum vx_tf_format_enum = { "transfer-function format",
    tf_format_names, "unknown", 0 };

int
vx_tf_import(const char *path, vx_tf_format fmt, vx_tf *tf, vx_err *e)
{
	(void)fmt;
	vx_tf_init(tf);
	return vx_err_set(e, VX_EDATA, "%s: transfer-function files are not "
	    "read yet", path);
}
