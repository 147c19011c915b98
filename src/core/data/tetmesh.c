/* tetmesh.c: tetrahedral mesh storage, validation, volumes, the exact
 * coplanarity test and the TETM chunk (formats/tetmesh.md). */
#include "vx_tetmesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <zlib.h>

/* The exact predicates below rely on IEEE double rounding of each operation
 * as written. */
#ifdef __clang__
#pragma STDC FP_CONTRACT OFF   /* gcc: off already under -std=c11 */
#endif

void
vx_tetmesh_init(vx_tetmesh *m)
{
	memset(m, 0, sizeof *m);
	strcpy(m->name, "mesh");
	strcpy(m->scalar, "scalar");
}

void
vx_tetmesh_free(vx_tetmesh *m)
{
	free(m->pts);
	free(m->tet);
	free(m->val);
	vx_tetmesh_init(m);
}

int
vx_tetmesh_alloc(vx_tetmesh *m, size_t npoint, size_t ntet, vx_err *e)
{
	vx_tetmesh_init(m);
	if ((uint64_t)npoint > VX_TETMESH_MAX_POINTS)
		return vx_err_set(e, VX_EDATA, "tet mesh: %zu points (limit %llu)",
		    npoint, (unsigned long long)VX_TETMESH_MAX_POINTS);
	if ((uint64_t)ntet > VX_TETMESH_MAX_TETS)
		return vx_err_set(e, VX_EDATA, "tet mesh: %zu tets (limit %llu)",
		    ntet, (unsigned long long)VX_TETMESH_MAX_TETS);
	m->pts = vx_calloc(npoint, 3 * sizeof *m->pts, e);
	m->tet = m->pts ? vx_calloc(ntet, 4 * sizeof *m->tet, e) : NULL;
	m->val = m->tet ? vx_calloc(npoint, sizeof *m->val, e) : NULL;
	if (m->val == NULL) {
		vx_tetmesh_free(m);
		return VX_ENOMEM;
	}
	m->npoint = npoint;
	m->ntet = ntet;
	return 0;
}

static void
set_name(char *dst, const char *src, const char *dflt)
{
	size_t i, k = 0;

	for (i = 0; src != NULL && src[i] != '\0' && k < VX_TETMESH_NAME - 1;
	    i++) {
		unsigned char ch = (unsigned char)src[i];
		int ok = (ch > ' ' && ch < 127 && ch != ':') ||
		    (ch == ' ' && k > 0);
		dst[k++] = ok ? (char)ch : '_';
	}
	while (k > 0 && dst[k - 1] == ' ')
		k--;
	dst[k] = '\0';
	if (k == 0)
		strcpy(dst, dflt);
}

void
vx_tetmesh_set_name(vx_tetmesh *m, const char *name)
{
	set_name(m->name, name, "mesh");
}

void
vx_tetmesh_set_scalar(vx_tetmesh *m, const char *name)
{
	set_name(m->scalar, name, "scalar");
}

void
vx_tetmesh_bbox(vx_tetmesh *m)
{
	size_t i;
	int a;

	for (a = 0; a < 3; a++) {
		m->bmin[a] = m->npoint ? m->pts[a] : 0;
		m->bmax[a] = m->bmin[a];
	}
	for (i = 1; i < m->npoint; i++)
		for (a = 0; a < 3; a++) {
			double x = m->pts[3 * i + a];
			if (x < m->bmin[a])
				m->bmin[a] = x;
			if (x > m->bmax[a])
				m->bmax[a] = x;
		}
}

void
vx_tetmesh_range(vx_tetmesh *m)
{
	size_t i;

	m->has_range = 0;
	m->vmin = m->vmax = 0;
	for (i = 0; i < m->npoint; i++) {
		double v = m->val[i];
		if (!isfinite(v))
			continue;
		if (!m->has_range) {
			m->vmin = m->vmax = v;
			m->has_range = 1;
		} else if (v < m->vmin)
			m->vmin = v;
		else if (v > m->vmax)
			m->vmax = v;
	}
}

int
vx_tetmesh_validate(vx_tetmesh *m, vx_err *e)
{
	size_t i;

	for (i = 0; i < 3 * m->npoint; i++) {
		double x = m->pts[i];
		if (isnan(x))
			return vx_err_set(e, VX_EDATA, "tet mesh: point %zu has "
			    "a NaN coordinate", i / 3);
		if (!(fabs(x) <= VX_TETMESH_COORD_MAX))
			return vx_err_set(e, VX_EDATA, "tet mesh: point %zu has "
			    "coordinate %g (limit +-%g)", i / 3, x,
			    VX_TETMESH_COORD_MAX);
	}
	for (i = 0; i < 4 * m->ntet; i++)
		if (m->tet[i] >= m->npoint)
			return vx_err_set(e, VX_EDATA, "tet mesh: tet %zu refers "
			    "to point %lu of %zu", i / 4,
			    (unsigned long)m->tet[i], m->npoint);
	vx_tetmesh_bbox(m);
	vx_tetmesh_range(m);
	return 0;
}

double
vx_tetmesh_volume(const vx_tetmesh *m, size_t t)
{
	const uint32_t *v = m->tet + 4 * t;
	const double *a = m->pts + 3 * (size_t)v[0];
	double u[3][3];
	int i, k;

	for (i = 0; i < 3; i++)
		for (k = 0; k < 3; k++)
			u[i][k] = m->pts[3 * (size_t)v[i + 1] + k] - a[k];
	return (u[0][0] * (u[1][1] * u[2][2] - u[1][2] * u[2][1]) -
	    u[0][1] * (u[1][0] * u[2][2] - u[1][2] * u[2][0]) +
	    u[0][2] * (u[1][0] * u[2][1] - u[1][1] * u[2][0])) / 6.0;
}

/* ---- exact orientation (Shewchuk's expansion arithmetic) ----
 * An expansion is a sum of doubles of increasing magnitude that do not
 * overlap; its sign is the sign of its last component. */

static void
two_sum(double a, double b, double *x, double *y)
{
	double s = a + b, bv = s - a, av = s - bv;

	*x = s;
	*y = (a - av) + (b - bv);
}

/* grow: h = e + b (h may not alias e); returns h's length (>= 1). */
static int
grow(const double *e, int n, double b, double *h)
{
	double q = b, hh;
	int i, k = 0;

	for (i = 0; i < n; i++) {
		two_sum(q, e[i], &q, &hh);
		if (hh != 0)
			h[k++] = hh;
	}
	if (q != 0 || k == 0)
		h[k++] = q;
	return k;
}

/* Exact sign of det [a 1; b 1; c 1; d 1] (the 4x4 orientation determinant)
 * as a sum of 24 triple products, each exact as 4 doubles (fma). */
static int
orient3d_exact(const double *p[4])
{
	static const int perm[6][3] = {
		{ 0, 1, 2 }, { 1, 2, 0 }, { 2, 0, 1 },
		{ 0, 2, 1 }, { 2, 1, 0 }, { 1, 0, 2 },
	};
	double buf[2][512];
	int n = 0, cur = 0, r, s, k;

	buf[0][0] = 0;
	n = 1;
	for (r = 0; r < 4; r++) {
		/* expansion along the column of ones: (-1)^(r+3) det3(others) */
		const double *q[3];
		int j = 0, rs = (r % 2 == 0) ? -1 : 1;
		for (k = 0; k < 4; k++)
			if (k != r)
				q[j++] = p[k];
		for (s = 0; s < 6; s++) {
			double x = q[0][perm[s][0]], y = q[1][perm[s][1]];
			double z = q[2][perm[s][2]], xy = x * y;
			double xye = fma(x, y, -xy);
			double t[4];
			int sg = (s < 3 ? 1 : -1) * rs;
			t[0] = xy * z;
			t[1] = fma(xy, z, -t[0]);
			t[2] = xye * z;
			t[3] = fma(xye, z, -t[2]);
			for (k = 0; k < 4; k++) {
				n = grow(buf[cur], n, sg * t[k], buf[!cur]);
				cur = !cur;
			}
		}
	}
	return (buf[cur][n - 1] > 0) - (buf[cur][n - 1] < 0);
}

int
vx_orient3d(const double *pa, const double *pb, const double *pc,
    const double *pd)
{
	const double *p[4] = { pa, pb, pc, pd };
	double a[3], b[3], c[3], det, perm;
	/* Shewchuk's first-stage bound for orient3d: (7 + 56 eps) eps */
	const double eps = 0x1p-53, bound = (7.0 + 56.0 * eps) * eps;
	int k;

	/* det(a-d, b-d, c-d) = det [a 1; b 1; c 1; d 1] = -det(b-a, c-a, d-a) */
	for (k = 0; k < 3; k++) {
		a[k] = pa[k] - pd[k];
		b[k] = pb[k] - pd[k];
		c[k] = pc[k] - pd[k];
	}
	double bc = b[0] * c[1], cb = c[0] * b[1];
	double ca = c[0] * a[1], ac = a[0] * c[1];
	double ab = a[0] * b[1], ba = b[0] * a[1];
	det = a[2] * (bc - cb) + b[2] * (ca - ac) + c[2] * (ab - ba);
	perm = (fabs(bc) + fabs(cb)) * fabs(a[2]) +
	    (fabs(ca) + fabs(ac)) * fabs(b[2]) +
	    (fabs(ab) + fabs(ba)) * fabs(c[2]);
	if (det > bound * perm)
		return -1;
	if (-det > bound * perm)
		return 1;
	return -orient3d_exact(p);
}

int
vx_tetmesh_degenerate(const vx_tetmesh *m, size_t t)
{
	const uint32_t *v = m->tet + 4 * t;

	return vx_orient3d(m->pts + 3 * (size_t)v[0], m->pts + 3 * (size_t)v[1],
	    m->pts + 3 * (size_t)v[2], m->pts + 3 * (size_t)v[3]) == 0;
}

/* ---- the TETM chunk ---- */

/* zlib never expands more than 1032:1 (RFC 1951 stored/fixed limits). */
#define ZLIB_MAX_RATIO 1032

int
vx_tetmesh_to_chunk(const vx_tetmesh *m, int zlevel, vx_chunk *c, vx_err *e)
{
	size_t np = 3 * m->npoint * sizeof(double);
	size_t nt = 4 * m->ntet * sizeof(uint32_t);
	size_t nv = m->npoint * sizeof(float);
	unsigned char *body;
	vx_hdr h;
	int rc;

	vx_hdr_init(&h);
	if ((body = vx_malloc(np + nt + nv, e)) == NULL)
		return VX_ENOMEM;
	if (np)
		memcpy(body, m->pts, np);
	if (nt)
		memcpy(body + np, m->tet, nt);
	if (nv)
		memcpy(body + np + nt, m->val, nv);
	if (!vx_host_is_le()) {
		vx_swap_bytes(body, 3 * m->npoint, sizeof(double));
		vx_swap_bytes(body + np, 4 * m->ntet, sizeof(uint32_t));
		vx_swap_bytes(body + np + nt, m->npoint, sizeof(float));
	}
	if ((rc = vx_hdr_set(&h, "name", e, "%s", m->name)) ||
	    (rc = vx_hdr_set(&h, "points", e, "%zu", m->npoint)) ||
	    (rc = vx_hdr_set(&h, "tets", e, "%zu", m->ntet)) ||
	    (rc = vx_hdr_set(&h, "scalar", e, "%s", m->scalar)))
		goto out;
	if (m->has_range && (rc = vx_hdr_set(&h, "range", e, "%.9g %.9g",
	    m->vmin, m->vmax)))
		goto out;
	rc = vx_payload_make(c, VX_CHUNK_TETMESH, &h, body, np + nt + nv,
	    zlevel, e);
out:
	free(body);
	vx_hdr_free(&h);
	return rc;
}

/* Decode a raw or zlib body into three consecutive destinations. */
static int
body_decode3(const char *enc, const unsigned char *body, size_t n,
    void *const dst[3], const size_t len[3], vx_err *e)
{
	size_t total = len[0] + len[1] + len[2], k;
	int i;

	if (enc == NULL || strcmp(enc, "raw") == 0) {
		if (n != total)
			return vx_err_set(e, VX_EDATA, "body has %zu bytes, "
			    "header implies %zu", n, total);
		for (i = 0, k = 0; i < 3; k += len[i], i++)
			if (len[i])
				memcpy(dst[i], body + k, len[i]);
		return 0;
	}
	if (strcmp(enc, "zlib") != 0)
		return vx_err_set(e, VX_EDATA, "unknown encoding '%.40s'", enc);

	z_stream zs;
	int zr = Z_OK;
	size_t left_in = n;

	memset(&zs, 0, sizeof zs);
	if (inflateInit(&zs) != Z_OK)
		return vx_err_set(e, VX_EINTERNAL, "zlib: inflateInit failed");
	zs.next_in = (Bytef *)(uintptr_t)body;
	for (i = 0; i < 3 && zr == Z_OK; i++) {
		unsigned char *o = dst[i];
		size_t left_out = len[i];
		while (left_out > 0) {
			uInt ki = left_in > 0x40000000u ? 0x40000000u :
			    (uInt)left_in;
			uInt ko = left_out > 0x40000000u ? 0x40000000u :
			    (uInt)left_out;
			zs.avail_in = ki;
			zs.next_out = o;
			zs.avail_out = ko;
			zr = inflate(&zs, Z_NO_FLUSH);
			left_in -= ki - zs.avail_in;
			left_out -= ko - zs.avail_out;
			o += ko - zs.avail_out;
			if (zr != Z_OK)
				break;
			if (ki - zs.avail_in == 0 && ko - zs.avail_out == 0) {
				zr = Z_BUF_ERROR;
				break;
			}
		}
		if (left_out > 0) {
			inflateEnd(&zs);
			if (zr == Z_OK || zr == Z_STREAM_END || zr == Z_BUF_ERROR)
				return vx_err_set(e, VX_EDATA, "zlib body decodes "
				    "to fewer than the %zu bytes the header "
				    "implies", total);
			return vx_err_set(e, VX_EDATA, "zlib body is corrupt: "
			    "%s", zs.msg ? zs.msg : "inflate error");
		}
	}
	int more = 0;
	if (zr == Z_OK) {
		/* all output placed: the stream must end here, exactly */
		unsigned char extra;
		uInt ki = left_in > 0x40000000u ? 0x40000000u : (uInt)left_in;
		zs.avail_in = ki;
		zs.next_out = &extra;
		zs.avail_out = 1;
		zr = inflate(&zs, Z_NO_FLUSH);
		left_in -= ki - zs.avail_in;
		more = zs.avail_out == 0;
	}
	size_t got = (size_t)zs.total_out;
	inflateEnd(&zs);
	if (zr == Z_STREAM_END && left_in == 0 && !more && got == total)
		return 0;
	if (zr == Z_STREAM_END && got < total)
		return vx_err_set(e, VX_EDATA, "zlib body decodes to fewer than "
		    "the %zu bytes the header implies", total);
	if (more || zr == Z_STREAM_END)
		return vx_err_set(e, VX_EDATA, "zlib body decodes to more than "
		    "the %zu bytes the header implies (or has trailing data)",
		    total);
	return vx_err_set(e, VX_EDATA, "zlib body is corrupt or truncated");
}

int
vx_tetmesh_from_chunk(vx_tetmesh *m, const vx_chunk *c, vx_err *e)
{
	const unsigned char *body;
	size_t bodylen, total, cap;
	int64_t cnt[2];
	const char *enc;
	vx_hdr h;
	int rc;

	vx_tetmesh_init(m);
	vx_hdr_init(&h);
	if ((rc = vx_payload_parse(c, &h, &body, &bodylen, e)) != 0)
		goto out;
	if ((rc = vx_hdr_get_i64(&h, "points", &cnt[0], 1, e)) != 0 ||
	    (rc = vx_hdr_get_i64(&h, "tets", &cnt[1], 1, e)) != 0)
		goto out;
	if (cnt[0] < 0 || cnt[1] < 0 ||
	    (uint64_t)cnt[0] > VX_TETMESH_MAX_POINTS ||
	    (uint64_t)cnt[1] > VX_TETMESH_MAX_TETS) {
		rc = vx_err_set(e, VX_EDATA, "counts out of range: %lld points, "
		    "%lld tets", (long long)cnt[0], (long long)cnt[1]);
		goto out;
	}
	/* 28 bytes per point, 16 per tet */
	{
		size_t a, b;
		if (vx_mul_size(&a, (size_t)cnt[0], 28) ||
		    vx_mul_size(&b, (size_t)cnt[1], 16) ||
		    vx_add_size(&total, a, b)) {
			rc = vx_err_set(e, VX_EDATA, "counts too large");
			goto out;
		}
	}
	enc = vx_hdr_get(&h, "encoding");
	cap = bodylen;
	if (enc != NULL && strcmp(enc, "zlib") == 0)
		cap = bodylen > SIZE_MAX / ZLIB_MAX_RATIO ? SIZE_MAX :
		    bodylen * ZLIB_MAX_RATIO;
	if (total > cap) {
		rc = vx_err_set(e, VX_EDATA, "%lld points and %lld tets need "
		    "%zu bytes, the body (%zu bytes%s) cannot hold them",
		    (long long)cnt[0], (long long)cnt[1], total, bodylen,
		    cap != bodylen ? " compressed" : "");
		goto out;
	}
	if ((rc = vx_tetmesh_alloc(m, (size_t)cnt[0], (size_t)cnt[1], e)) != 0)
		goto out;
	vx_tetmesh_set_name(m, vx_hdr_get(&h, "name"));
	vx_tetmesh_set_scalar(m, vx_hdr_get(&h, "scalar"));
	{
		void *dst[3] = { m->pts, m->tet, m->val };
		size_t len[3] = { m->npoint * 24, m->ntet * 16, m->npoint * 4 };
		if ((rc = body_decode3(enc, body, bodylen, dst, len, e)) != 0)
			goto out;
	}
	if (!vx_host_is_le()) {
		vx_swap_bytes(m->pts, 3 * m->npoint, sizeof(double));
		vx_swap_bytes(m->tet, 4 * m->ntet, sizeof(uint32_t));
		vx_swap_bytes(m->val, m->npoint, sizeof(float));
	}
	rc = vx_tetmesh_validate(m, e);
out:
	vx_hdr_free(&h);
	if (rc != 0) {
		vx_tetmesh_free(m);
		vx_err_push(e, "tet mesh");
	}
	return rc;
}

int
vx_tetmesh_from_stream(vx_tetmesh *m, const vx_stream *s, const char *name,
    long *index, vx_err *e)
{
	long i = -1;
	int rc;

	while ((i = vx_stream_find(s, VX_CHUNK_TETMESH, (size_t)(i + 1))) >= 0) {
		if (name != NULL) {
			/* peek at the name before decoding the whole body */
			vx_hdr h;
			const unsigned char *b;
			size_t bl;
			int match;
			vx_hdr_init(&h);
			if ((rc = vx_payload_parse(&s->chunk[i], &h, &b, &bl,
			    e)) != 0) {
				vx_hdr_free(&h);
				return vx_err_push(e, "tet mesh");
			}
			const char *v = vx_hdr_get(&h, "name");
			char nm[VX_TETMESH_NAME];
			set_name(nm, v, "mesh");
			match = strcmp(nm, name) == 0;
			vx_hdr_free(&h);
			if (!match)
				continue;
		}
		if ((rc = vx_tetmesh_from_chunk(m, &s->chunk[i], e)) != 0)
			return rc;
		if (index != NULL)
			*index = i;
		return 0;
	}
	vx_tetmesh_init(m);
	if (name != NULL)
		return vx_err_set(e, VX_EDATA, "no tet mesh named '%s' in the "
		    "stream", name);
	return vx_err_set(e, VX_EDATA, "no tet mesh in the stream");
}
