/* exr.c: vx_exr_read_mem, the C side of the OpenEXR reader: the image and
 * its errors around exr_lib.cc's decoder (exr_priv.h). */
#include "vx_imageio.h"
#include "exr_priv.h"

typedef struct actx {
	vx_image *img;
	vx_err *e;
} actx;

static float *
exr_alloc(void *ctx, int w, int h)
{
	actx *a = ctx;

	return vx_image_alloc(a->img, w, h, 3, a->e) == 0 ? a->img->px : NULL;
}

int
vx_exr_read_mem(vx_image *img, const void *buf, size_t n, vx_err *e)
{
	char msg[VX_ERR_MSG];
	actx a = { img, e };
	int rc;

	vx_image_init(img);
	msg[0] = '\0';
	rc = vx_exr_decode(buf, n, VX_IMAGE_MAX_DIM, VX_IMAGE_MAX_PIXELS,
	    exr_alloc, &a, msg, sizeof msg);
	if (rc == 0)
		return 0;
	vx_image_free(img);
	if (rc == 70)          /* the allocation failed: e says why */
		return e->code;
	return vx_err_set(e, rc == 71 ? VX_ENOMEM : VX_EDATA, "%s", msg);
}
