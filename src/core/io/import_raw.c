/* import_raw.c: header-less volumes whose dims and type the caller gives. */
#include "import_priv.h"

#include <string.h>

void
vx_raw_info_init(vx_raw_info *r)
{
	memset(r, 0, sizeof *r);
	r->spacing[0] = r->spacing[1] = r->spacing[2] = 1;
}

int
vx_import_raw_mem(vx_grid *g, const void *buf, size_t n,
    const vx_raw_info *r, vx_err *e)
{
	uint64_t total, bytes;
	vx_imp_frame f;
	vx_imp_conv c;
	vx_imp_src s;
	int rc, more;

	vx_grid_init(g);
	if (vx_scalar_size(r->type) == 0)
		return vx_err_set(e, VX_EDATA, "raw: unknown sample type");
	if ((rc = vx_imp_total(r->dims, vx_scalar_size(r->type), &total, &bytes,
	    "raw: dims", e)) != 0)
		return rc;
	if ((rc = vx_imp_frame_plain(&f, r->spacing, r->origin, r->dims,
	    "raw: spacing", e)) != 0)
		return rc;
	for (int a = 0; a < 3; a++)
		if (f.flip[a])
			return vx_err_set(e, VX_EDATA, "raw: spacing must be "
			    "positive");
	if ((rc = vx_imp_src_auto(&s, buf, n, e)) != 0)
		return rc;
	if ((rc = vx_imp_need(&s, r->skip, "raw: skip", e)) != 0 ||
	    (rc = vx_imp_skip(&s, r->skip, e)) != 0) {
		if (rc == VX_EDATA)
			vx_err_push(e, "raw: skip %llu",
			    (unsigned long long)r->skip);
		goto out;
	}
	if ((rc = vx_imp_need(&s, bytes, "raw", e)) != 0)
		goto out;
	if ((rc = vx_imp_conv_begin(&c, g, r->dims, r->type, r->big_endian, &f,
	    NULL, e)) != 0)
		goto out;
	if ((rc = vx_imp_conv_binary(&c, &s, e)) != 0 ||
	    (rc = vx_imp_conv_end(&c, e)) != 0) {
		vx_imp_conv_abort(&c);
		vx_err_push(e, "raw: %lld x %lld x %lld %s",
		    (long long)r->dims[0], (long long)r->dims[1],
		    (long long)r->dims[2],
		    vx_enum_str(&vx_scalar_enum, r->type));
		goto out;
	}
	/* the input must end here: extra bytes mean wrong dims or type */
	if ((rc = vx_imp_trailing(&s, 0, &more, e)) != 0) {
		vx_err_push(e, "raw");
		goto out;
	}
	if (more)
		rc = vx_err_set(e, VX_EDATA, "raw: input is longer than skip + "
		    "%lld x %lld x %lld %s samples (%llu bytes): check the dims "
		    "and type", (long long)r->dims[0], (long long)r->dims[1],
		    (long long)r->dims[2],
		    vx_enum_str(&vx_scalar_enum, r->type),
		    (unsigned long long)(r->skip + bytes));
out:
	vx_imp_src_close(&s);
	if (rc != 0)
		vx_grid_free(g);
	return rc;
}
