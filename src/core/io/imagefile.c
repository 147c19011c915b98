/* imagefile.c: which image format a file's first bytes announce. */
#include "vx_imageio.h"
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
	return VX_IMGFMT_UNKNOWN;
}
