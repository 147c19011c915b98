/* import_nifti.c: NIfTI-1 volumes (.nii single files, .hdr/.img pairs),
 * header in either byte order, gzip or not. */
#include "import_priv.h"

#include <math.h>
#include <string.h>

#define NII_HDR 348

/* the fields we use, at their offsets in the 348-byte header */
typedef struct nii {
	int swap;                /* 1: big-endian file (get16/getf decode
	                            explicitly, whatever the host) */
	int16_t dim[8], datatype, bitpix, qform_code, sform_code;
	float pixdim[8], vox_offset, scl_slope, scl_inter;
	float quatern[3], qoffset[3], srow[3][4];
	char magic[4];
} nii;

static int16_t
get16(const unsigned char *p, int swap)
{
	uint16_t v = swap ? (uint16_t)(p[0] << 8 | p[1]) :
	    (uint16_t)(p[1] << 8 | p[0]);

	return (int16_t)v;
}

static uint32_t
get32u(const unsigned char *p, int swap)
{
	return swap ? (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 |
	    (uint32_t)p[2] << 8 | p[3] :
	    (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 |
	    (uint32_t)p[1] << 8 | p[0];
}

static float
getf(const unsigned char *p, int swap)
{
	uint32_t u = get32u(p, swap);
	float f;

	memcpy(&f, &u, 4);
	return f;
}

/* nii_parse: the header in h[0..348); the file's byte order is found from
 * sizeof_hdr.  *big_endian gets the byte order of the data. */
static int
nii_parse(nii *x, const unsigned char *h, int *big_endian, vx_err *e)
{
	uint32_t le = get32u(h, 0), be = get32u(h, 1);
	int i, a;

	memset(x, 0, sizeof *x);
	if (le == NII_HDR)
		x->swap = 0;
	else if (be == NII_HDR)
		x->swap = 1;
	else if (le == 540 || be == 540)
		return vx_err_set(e, VX_EDATA, "nifti: NIfTI-2 is not supported");
	else
		return vx_err_set(e, VX_EDATA, "nifti: sizeof_hdr is %u, not 348",
		    le);
	*big_endian = x->swap;   /* the data share the header's byte order */
	for (i = 0; i < 8; i++) {
		x->dim[i] = get16(h + 40 + 2 * i, x->swap);
		x->pixdim[i] = getf(h + 76 + 4 * i, x->swap);
	}
	x->datatype = get16(h + 70, x->swap);
	x->bitpix = get16(h + 72, x->swap);
	x->vox_offset = getf(h + 108, x->swap);
	x->scl_slope = getf(h + 112, x->swap);
	x->scl_inter = getf(h + 116, x->swap);
	x->qform_code = get16(h + 252, x->swap);
	x->sform_code = get16(h + 254, x->swap);
	for (a = 0; a < 3; a++) {
		x->quatern[a] = getf(h + 256 + 4 * a, x->swap);
		x->qoffset[a] = getf(h + 268 + 4 * a, x->swap);
		for (i = 0; i < 4; i++)
			x->srow[a][i] = getf(h + 280 + 16 * a + 4 * i, x->swap);
	}
	memcpy(x->magic, h + 344, 4);
	return 0;
}

static vx_scalar
nii_type(int dt, const char **name)
{
	switch (dt) {
	case 2: *name = "uint8"; return VX_S_U8;
	case 4: *name = "int16"; return VX_S_I16;
	case 8: *name = "int32"; return VX_S_I32;
	case 16: *name = "float32"; return VX_S_F32;
	case 64: *name = "float64"; return VX_S_F64;
	case 256: *name = "int8"; return VX_S_I8;
	case 512: *name = "uint16"; return VX_S_U16;
	case 768: *name = "uint32"; return VX_S_U32;
	case 1024: *name = "int64"; return VX_S_I64;
	case 1280: *name = "uint64"; return VX_S_U64;
	case 1: *name = "binary"; break;
	case 32: *name = "complex64"; break;
	case 128: *name = "RGB24"; break;
	case 1536: *name = "float128"; break;
	case 1792: *name = "complex128"; break;
	case 2048: *name = "complex256"; break;
	case 2304: *name = "RGBA32"; break;
	default: *name = "unknown"; break;
	}
	return VX_SCALAR_UNKNOWN;
}

/* nii_frame: spacing, origin and mirroring from sform (sform_code > 0),
 * else qform (qform_code > 0), else pixdim alone (NIfTI "method 1"). */
static int
nii_frame(const nii *x, const int64_t dims[3], vx_imp_frame *f, vx_err *e)
{
	double col[3][3], org[3];
	int a, w;

	if (x->sform_code > 0) {
		for (a = 0; a < 3; a++) {
			for (w = 0; w < 3; w++)
				col[a][w] = x->srow[w][a];
			org[a] = x->srow[a][3];
		}
		return vx_imp_frame_axes(f, col, org, dims, "nifti: sform", e);
	}
	if (x->qform_code > 0) {
		double b = x->quatern[0], c = x->quatern[1], d = x->quatern[2];
		double aa = 1.0 - (b * b + c * c + d * d), R[3][3];
		double qfac = x->pixdim[0] < 0 ? -1 : 1;

		/* the quaternion's real part; tiny negatives are rounding */
		aa = aa < 1e-7 ? 0 : sqrt(aa);
		R[0][0] = aa * aa + b * b - c * c - d * d;
		R[0][1] = 2 * (b * c - aa * d);
		R[0][2] = 2 * (b * d + aa * c);
		R[1][0] = 2 * (b * c + aa * d);
		R[1][1] = aa * aa + c * c - b * b - d * d;
		R[1][2] = 2 * (c * d - aa * b);
		R[2][0] = 2 * (b * d - aa * c);
		R[2][1] = 2 * (c * d + aa * b);
		R[2][2] = aa * aa + d * d - c * c - b * b;
		for (a = 0; a < 3; a++) {
			double s = x->pixdim[a + 1] * (a == 2 ? qfac : 1);

			for (w = 0; w < 3; w++)
				col[a][w] = R[w][a] * s;
			org[a] = x->qoffset[a];
		}
		return vx_imp_frame_axes(f, col, org, dims, "nifti: qform", e);
	}
	{
		double sp[3], zero[3] = { 0, 0, 0 };

		for (a = 0; a < 3; a++) {
			double p = x->pixdim[a + 1];

			/* unset pixdims are common in this mode: take 1 */
			sp[a] = isfinite(p) && p != 0 ? fabs(p) : 1;
		}
		return vx_imp_frame_plain(f, sp, zero, dims, "nifti: pixdim", e);
	}
}

/* nii_read: header h (348 bytes) and data source d positioned at the
 * start of the file whose offset vox_offset counts from (already past
 * `consumed` bytes of it). */
static int
nii_read(vx_grid *g, const unsigned char *h, vx_imp_src *d, uint64_t consumed,
    int pair, vx_err *e)
{
	int64_t dims[3];
	uint64_t total, bytes, off;
	const char *tname;
	double scale[2];
	int big = 0, rc, a, more;
	vx_imp_frame f;
	vx_imp_conv c;
	vx_scalar st;
	nii x;

	if ((rc = nii_parse(&x, h, &big, e)) != 0)
		return rc;
	if (pair ? memcmp(x.magic, "ni1", 4) != 0 : memcmp(x.magic, "n+1",
	    4) != 0) {
		if (!pair && memcmp(x.magic, "ni1", 4) == 0)
			return vx_err_set(e, VX_EDATA, "nifti: magic 'ni1': the "
			    "header of a .hdr/.img pair; read it by its .hdr "
			    "name");
		return vx_err_set(e, VX_EDATA, "nifti: magic '%s' is not '%s' "
		    "(Analyze 7.5 is not supported)", vx_imp_show(x.magic, 3),
		    pair ? "ni1" : "n+1");
	}
	if (x.dim[0] < 1 || x.dim[0] > 7)
		return vx_err_set(e, VX_EDATA, "nifti: dim[0] = %d: must be "
		    "1..7", x.dim[0]);
	for (a = 1; a <= x.dim[0]; a++)
		if (x.dim[a] < 1)
			return vx_err_set(e, VX_EDATA, "nifti: dim[%d] = %d: must "
			    "be positive", a, x.dim[a]);
	for (a = 4; a <= x.dim[0]; a++)
		if (x.dim[a] != 1)
			return vx_err_set(e, VX_EDATA, "nifti: dim[%d] = %d: only "
			    "single 3D volumes are supported", a, x.dim[a]);
	for (a = 0; a < 3; a++)
		dims[a] = a < x.dim[0] ? x.dim[a + 1] : 1;
	if ((st = nii_type(x.datatype, &tname)) == VX_SCALAR_UNKNOWN)
		return vx_err_set(e, VX_EDATA, "nifti: datatype %d (%s) is not "
		    "supported", x.datatype, tname);
	if ((size_t)x.bitpix != 8 * vx_scalar_size(st))
		return vx_err_set(e, VX_EDATA, "nifti: bitpix %d does not match "
		    "datatype %d (%s)", x.bitpix, x.datatype, tname);
	if ((rc = vx_imp_total(dims, vx_scalar_size(st), &total, &bytes,
	    "nifti: dim", e)) != 0)
		return rc;
	if (!isfinite(x.vox_offset) || x.vox_offset < (pair ? 0 : NII_HDR) ||
	    x.vox_offset != floorf(x.vox_offset) || x.vox_offset > 1e15)
		return vx_err_set(e, VX_EDATA, "nifti: vox_offset %g: must be a "
		    "whole number >= %d", x.vox_offset, pair ? 0 : NII_HDR);
	off = (uint64_t)x.vox_offset;
	if ((rc = nii_frame(&x, dims, &f, e)) != 0)
		return rc;
	/* scl_slope 0 (or NaN) means unscaled, as do slope 1 intercept 0 */
	scale[0] = x.scl_slope;
	scale[1] = isfinite(x.scl_inter) ? x.scl_inter : 0;
	int scaled = isfinite(x.scl_slope) && x.scl_slope != 0 &&
	    !(x.scl_slope == 1 && scale[1] == 0);

	if ((rc = vx_imp_need(d, off - consumed, "nifti: vox_offset", e)) != 0 ||
	    (rc = vx_imp_skip(d, off - consumed, e)) != 0) {
		if (rc == VX_EDATA)
			vx_err_push(e, "nifti: vox_offset %llu",
			    (unsigned long long)off);
		return rc;
	}
	if ((rc = vx_imp_need(d, bytes, "nifti: data", e)) != 0)
		return rc;
	if ((rc = vx_imp_conv_begin(&c, g, dims, st, big, &f, scaled ? scale :
	    NULL, e)) != 0)
		return rc;
	if ((rc = vx_imp_conv_binary(&c, d, e)) != 0 ||
	    (rc = vx_imp_conv_end(&c, e)) != 0) {
		vx_imp_conv_abort(&c);
		return vx_err_push(e, "nifti: data");
	}
	if ((rc = vx_imp_trailing(d, IMP_SLACK, &more, e)) != 0)
		return vx_err_push(e, "nifti");
	if (more)
		return vx_err_set(e, VX_EDATA, "nifti: more than %d bytes follow "
		    "the %llu bytes of samples that dim and datatype imply",
		    IMP_SLACK, (unsigned long long)bytes);
	return 0;
}

int
vx_imp_read_nifti(vx_grid *g, vx_imp_src *s, vx_err *e)
{
	unsigned char h[NII_HDR];
	const unsigned char *p;
	size_t avail;
	int rc;

	vx_grid_init(g);
	if ((rc = vx_imp_peek(s, NII_HDR, &p, &avail, e)) != 0)
		goto out;
	if (avail < NII_HDR) {
		rc = vx_err_set(e, VX_EDATA, "nifti: header truncated (%zu of "
		    "348 bytes)", avail);
		goto out;
	}
	memcpy(h, p, NII_HDR);
	if ((rc = vx_imp_skip(s, NII_HDR, e)) != 0)
		goto out;
	rc = nii_read(g, h, s, NII_HDR, 0, e);
out:
	if (rc != 0)
		vx_grid_free(g);
	return rc;
}

int
vx_import_nifti_mem(vx_grid *g, const void *buf, size_t n, vx_err *e)
{
	vx_imp_src s;
	int rc;

	vx_grid_init(g);
	if ((rc = vx_imp_src_auto(&s, buf, n, e)) != 0)
		return rc;
	rc = vx_imp_read_nifti(g, &s, e);
	vx_imp_src_close(&s);
	return rc;
}

int
vx_import_nifti_pair_mem(vx_grid *g, const void *hdr, size_t hn,
    const void *img, size_t in, vx_err *e)
{
	vx_imp_src s;
	int rc;

	vx_grid_init(g);
	if ((rc = vx_imp_src_auto(&s, img, in, e)) != 0)
		return rc;
	rc = vx_imp_read_nifti_pair(g, hdr, hn, &s, e);
	vx_imp_src_close(&s);
	return rc;
}

int
vx_imp_read_nifti_pair(vx_grid *g, const void *hdr, size_t hn,
    vx_imp_src *img, vx_err *e)
{
	unsigned char h[NII_HDR];
	const unsigned char *p;
	size_t avail;
	vx_imp_src hs;
	int rc;

	vx_grid_init(g);
	if ((rc = vx_imp_src_auto(&hs, hdr, hn, e)) != 0)
		return rc;
	rc = vx_imp_peek(&hs, NII_HDR, &p, &avail, e);
	if (rc == 0 && avail < NII_HDR)
		rc = vx_err_set(e, VX_EDATA, "nifti: header truncated (%zu of "
		    "348 bytes)", avail);
	if (rc == 0)
		memcpy(h, p, NII_HDR);
	vx_imp_src_close(&hs);
	if (rc != 0)
		return rc;
	rc = nii_read(g, h, img, 0, 1, e);
	if (rc != 0)
		vx_grid_free(g);
	return rc;
}
