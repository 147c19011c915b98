/* imagefile.c: which image format a file's first bytes announce, and
 * reading a linear (HDR) image file of any format the core reads. */
#include "vx_imageio.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

int
vx_image_sniff(const void *buf, size_t n)
{
	const unsigned char *p = buf;

	if (n >= VX_SIGNATURE_LEN && memcmp(p, VX_SIGNATURE,
	    VX_SIGNATURE_LEN) == 0)
		return VX_IMGFMT_STREAM;
	if (n >= 8 && memcmp(p, "\x89PNG\r\n\x1a\n", 8) == 0)
		return VX_IMGFMT_PNG;
	if (n >= 3 && p[0] == 'P' && (p[1] == 'F' || p[1] == 'f') &&
	    (p[2] == ' ' || p[2] == '\t' || p[2] == '\n' || p[2] == '\r'))
		return VX_IMGFMT_PFM;
	if (n >= 2 && p[0] == '#' && p[1] == '?')
		return VX_IMGFMT_HDR;
	if (n >= 4 && memcmp(p, "\x76\x2f\x31\x01", 4) == 0)
		return VX_IMGFMT_EXR;
	if (n >= 3 && p[0] == 'P' && p[1] == '5' && (p[2] == ' ' ||
	    p[2] == '\t' || p[2] == '\n' || p[2] == '\r' || p[2] == '#'))
		return VX_IMGFMT_PGM;
	return VX_IMGFMT_UNKNOWN;
}

const char *
vx_image_format_name(int fmt)
{
	static const char *const names[VX_IMGFMT_LAST] = {
		"unknown", "voxlux stream", "PFM", "PNG", "Radiance HDR",
		"OpenEXR", "PGM"
	};

	return fmt > 0 && fmt < VX_IMGFMT_LAST ? names[fmt] : names[0];
}

int
vx_image_read_linear_mem(vx_image *img, const void *buf, size_t n, int *fmt,
    vx_err *e)
{
	int f = vx_image_sniff(buf, n);

	vx_image_init(img);
	if (fmt != NULL)
		*fmt = f;
	switch (f) {
	case VX_IMGFMT_PFM:
		return vx_pfm_read_mem(img, buf, n, e);
	case VX_IMGFMT_HDR:
		return vx_hdr_read_mem(img, buf, n, NULL, e);
	case VX_IMGFMT_EXR:
		return vx_exr_read_mem(img, buf, n, e);
	default:
		return vx_err_set(e, VX_EDATA, "not a PFM, Radiance HDR or "
		    "OpenEXR file (%s)", f == VX_IMGFMT_UNKNOWN ? "unknown "
		    "format" : vx_image_format_name(f));
	}
}

int
vx_image_read_linear_file(vx_image *img, const char *path, int *fmt,
    vx_err *e)
{
	unsigned char *buf;
	size_t n;
	FILE *f;
	int rc;

	vx_image_init(img);
	if ((f = fopen(path, "rb")) == NULL)
		return vx_err_set(e, VX_ENOINPUT, "%s: %s", path,
		    strerror(errno));
	rc = vx_file_read_all(f, VX_IMAGE_FILE_MAX, &buf, &n, e);
	fclose(f);
	if (rc != 0)
		return vx_err_push(e, "%s", path);
	if (n == 0)
		rc = vx_err_set(e, VX_EDATA, "empty file");
	else
		rc = vx_image_read_linear_mem(img, buf, n, fmt, e);
	free(buf);
	if (rc != 0)
		vx_err_push(e, "%s", path);
	return rc;
}
