/* tetleafio.c: the leaf grid of a tet mesh in the stream: the TLEF chunk
 * (formats/tetmesh.md), the mesh CRC that ties it to its mesh, and finding
 * the one that belongs to a mesh. */
#include "vx_tetleaf.h"
#include "vx_macroio.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <zlib.h>

/* crc_le: continue crc over count values of width bytes at p, as their
 * little-endian bytes. */
static uint32_t
crc_le(uint32_t crc, const void *p, size_t count, size_t width)
{
	const unsigned char *b = p;
	size_t n = count * width;

	if (vx_host_is_le()) {
		while (n > 0) {
			uInt k = n > 0x40000000u ? 0x40000000u : (uInt)n;
			crc = (uint32_t)crc32(crc, b, k);
			b += k;
			n -= k;
		}
		return crc;
	}
	unsigned char buf[4096];
	while (n > 0) {
		size_t k = n > sizeof buf ? sizeof buf : n;
		memcpy(buf, b, k);
		vx_swap_bytes(buf, k / width, width);
		crc = (uint32_t)crc32(crc, buf, (uInt)k);
		b += k;
		n -= k;
	}
	return crc;
}

uint32_t
vx_tetmesh_crc(const vx_tetmesh *m)
{
	uint32_t crc = (uint32_t)crc32(0L, Z_NULL, 0);

	crc = crc_le(crc, m->pts, 3 * m->npoint, sizeof(double));
	crc = crc_le(crc, m->tet, 4 * m->ntet, sizeof(uint32_t));
	return crc_le(crc, m->val, m->npoint, sizeof(float));
}

static size_t
level_cells(const vx_macro *mc, int l)
{
	return (size_t)mc->dims[l][0] * (size_t)mc->dims[l][1] *
	    (size_t)mc->dims[l][2];
}

int
vx_tetleaf_to_chunk(const vx_tetleaf *lg, const vx_tetmesh *m, int zlevel,
    vx_chunk *c, vx_err *e)
{
	const vx_macro *mc = &lg->mc;
	size_t noff = lg->nleaf + 1, nidx, ncell = 0, nbytes, k, i;
	unsigned char *body = NULL;
	vx_hdr h;
	int l, rc;

	if (lg->off == NULL)
		return vx_err_set(e, VX_EINTERNAL, "leaf grid: not built");
	nidx = lg->off[lg->nleaf];
	for (l = 0; l <= mc->nlev; l++)
		ncell += level_cells(mc, l);
	nbytes = 4 * (noff + nidx) + 8 * ncell;
	vx_hdr_init(&h);
	if ((rc = vx_hdr_set(&h, "mesh", e, "%s", m->name)) ||
	    (rc = vx_hdr_set(&h, "mesh-points", e, "%zu", m->npoint)) ||
	    (rc = vx_hdr_set(&h, "mesh-tets", e, "%zu", m->ntet)) ||
	    (rc = vx_hdr_set(&h, "mesh-crc32", e, "%08x",
	    (unsigned)vx_tetmesh_crc(m))) ||
	    (rc = vx_hdr_set(&h, "leaf-dims", e, "%lld %lld %lld",
	    (long long)lg->dims[0], (long long)lg->dims[1],
	    (long long)lg->dims[2])) ||
	    (rc = vx_hdr_set(&h, "leaf-origin", e, "%.17g %.17g %.17g",
	    lg->bmin[0], lg->bmin[1], lg->bmin[2])) ||
	    (rc = vx_hdr_set(&h, "leaf-size", e, "%.17g %.17g %.17g",
	    lg->cell[0], lg->cell[1], lg->cell[2])) ||
	    (rc = vx_hdr_set(&h, "entries", e, "%zu", nidx)) ||
	    (rc = vx_macro_hdr_levels(mc, &h, e)))
		goto out;
	if ((body = vx_malloc(nbytes, e)) == NULL) {
		rc = VX_ENOMEM;
		goto out;
	}
	for (i = 0; i < noff; i++)
		vx_put_le32(body + 4 * i, lg->off[i]);
	for (i = 0; i < nidx; i++)
		vx_put_le32(body + 4 * (noff + i), lg->idx[i]);
	k = 4 * (noff + nidx);
	for (l = 0; l <= mc->nlev; l++) {
		size_t nf = 2 * level_cells(mc, l);
		for (i = 0; i < nf; i++, k += 4) {
			uint32_t u;
			memcpy(&u, &mc->mm[l][i], 4);
			vx_put_le32(body + k, u);
		}
	}
	rc = vx_payload_make(c, VX_CHUNK_TETLEAF, &h, body, nbytes, zlevel, e);
out:
	free(body);
	vx_hdr_free(&h);
	if (rc != 0)
		vx_err_push(e, "leaf grid");
	return rc;
}

/* ident: the header's mesh identity. */
static int
ident(const vx_hdr *h, vx_tetleaf_ident *id, vx_err *e)
{
	const char *v = vx_hdr_get(h, "mesh");
	int64_t n[2];
	int rc;

	memset(id, 0, sizeof *id);
	if (v == NULL || v[0] == '\0' || strlen(v) >= sizeof id->mesh)
		return vx_err_set(e, VX_EDATA, "mesh name missing or longer "
		    "than %zu bytes", sizeof id->mesh - 1);
	strcpy(id->mesh, v);
	if ((rc = vx_hdr_get_i64(h, "mesh-points", &n[0], 1, e)) != 0 ||
	    (rc = vx_hdr_get_i64(h, "mesh-tets", &n[1], 1, e)) != 0)
		return rc;
	if (n[0] < 0 || (uint64_t)n[0] > VX_TETMESH_MAX_POINTS || n[1] < 0 ||
	    (uint64_t)n[1] > VX_TETMESH_MAX_TETS)
		return vx_err_set(e, VX_EDATA, "mesh counts out of range");
	id->npoint = (uint64_t)n[0];
	id->ntet = (uint64_t)n[1];
	v = vx_hdr_get(h, "mesh-crc32");
	if (v == NULL || strlen(v) != 8 || strspn(v, "0123456789abcdef") != 8)
		return vx_err_set(e, VX_EDATA, "mesh-crc32: expected 8 lower-case "
		    "hex digits");
	id->crc = (uint32_t)strtoul(v, NULL, 16);
	return 0;
}

int
vx_tetleaf_from_chunk(vx_tetleaf *lg, vx_tetleaf_ident *idp,
    const vx_chunk *c, vx_err *e)
{
	int sizes[VX_MACRO_MAXLEV][3];
	const unsigned char *body;
	unsigned char *tmp = NULL;
	float *leaf = NULL;
	size_t bodylen, nleaf, noff, nidx, ncell, nbytes, k, i;
	int64_t n[3], ne, cdims[VX_MACRO_MAXLEV + 1][3];
	double org[3], cell[3];
	vx_tetleaf_ident id;
	vx_hdr h;
	int nl, l, a, rc;

	vx_tetleaf_init(lg);
	vx_hdr_init(&h);
	if ((rc = vx_payload_parse(c, &h, &body, &bodylen, e)) != 0 ||
	    (rc = ident(&h, &id, e)) != 0)
		goto out;
	if ((rc = vx_hdr_get_i64(&h, "leaf-dims", n, 3, e)) != 0 ||
	    (rc = vx_hdr_get_f64(&h, "leaf-origin", org, 3, e)) != 0 ||
	    (rc = vx_hdr_get_f64(&h, "leaf-size", cell, 3, e)) != 0 ||
	    (rc = vx_hdr_get_i64(&h, "entries", &ne, 1, e)) != 0)
		goto out;
	nleaf = 1;
	for (a = 0; a < 3; a++) {
		if (n[a] < 1 || n[a] > ((int64_t)1 << 20)) {
			rc = vx_err_set(e, VX_EDATA, "leaf-dims: %lld out of "
			    "1..2^20", (long long)n[a]);
			goto out;
		}
		if (!(fabs(org[a]) <= VX_TETMESH_COORD_MAX * 2) ||
		    !(cell[a] > 0) || !isfinite(cell[a])) {
			rc = vx_err_set(e, VX_EDATA, "leaf-origin or leaf-size: "
			    "not finite, or a size not positive");
			goto out;
		}
		nleaf *= (size_t)n[a];  /* at most 2^60: no overflow */
		cdims[0][a] = n[a];
	}
	if ((uint64_t)nleaf > VX_TETLEAF_MAX_LEAVES) {
		rc = vx_err_set(e, VX_EDATA, "leaf-dims: %zu leaves (limit "
		    "%llu)", nleaf, (unsigned long long)VX_TETLEAF_MAX_LEAVES);
		goto out;
	}
	if (ne < 0 || (uint64_t)ne > UINT32_MAX) {
		rc = vx_err_set(e, VX_EDATA, "entries: %lld out of 0..2^32-1",
		    (long long)ne);
		goto out;
	}
	if ((rc = vx_macro_hdr_levels_get(&h, &nl, sizes, cdims, e)) != 0)
		goto out;
	ncell = nleaf;
	for (l = 1; l <= nl; l++)
		ncell += (size_t)(cdims[l][0] * cdims[l][1] * cdims[l][2]);
	noff = nleaf + 1;
	nidx = (size_t)ne;
	/* at most 4 (2^31 + 1) + 4 (2^32) + 8 * 7 * 2^31 bytes: fits */
	nbytes = 4 * (noff + nidx) + 8 * ncell;
	if ((rc = vx_body_fits(&h, bodylen, nbytes, e)) != 0)
		goto out;
	if ((tmp = vx_malloc(nbytes, e)) == NULL ||
	    (lg->off = vx_malloc(noff * sizeof *lg->off, e)) == NULL ||
	    (lg->idx = vx_malloc(nidx * sizeof *lg->idx + 1, e)) == NULL ||
	    (leaf = vx_malloc(2 * nleaf * sizeof *leaf, e)) == NULL) {
		rc = VX_ENOMEM;
		goto out;
	}
	if ((rc = vx_body_decode(&h, body, bodylen, tmp, nbytes, e)) != 0)
		goto out;
	for (i = 0; i < noff; i++)
		lg->off[i] = vx_le32(tmp + 4 * i);
	for (i = 0; i < nidx; i++)
		lg->idx[i] = vx_le32(tmp + 4 * (noff + i));
	if (lg->off[0] != 0 || lg->off[nleaf] != nidx) {
		rc = vx_err_set(e, VX_EDATA, "offsets must run from 0 to the "
		    "entry count");
		goto out;
	}
	for (i = 0; i < nleaf; i++)
		if (lg->off[i + 1] < lg->off[i]) {
			rc = vx_err_set(e, VX_EDATA, "offsets decrease at leaf "
			    "%zu", i);
			goto out;
		}
	/* now every offset lies in 0 .. nidx */
	for (i = 0; i < nleaf; i++) {
		for (k = lg->off[i]; k < lg->off[i + 1]; k++)
			if (lg->idx[k] >= id.ntet || (k > lg->off[i] &&
			    lg->idx[k] <= lg->idx[k - 1])) {
				rc = vx_err_set(e, VX_EDATA, "leaf %zu: tet %u out "
				    "of range or out of order", i,
				    (unsigned)lg->idx[k]);
				goto out;
			}
	}
	k = 4 * (noff + nidx);
	for (i = 0; i < 2 * nleaf; i++, k += 4) {
		uint32_t u = vx_le32(tmp + k);
		memcpy(&leaf[i], &u, 4);
		if (isnan(leaf[i])) {
			rc = vx_err_set(e, VX_EDATA, "level 0 holds NaN");
			goto out;
		}
	}
	for (a = 0; a < 3; a++) {
		lg->dims[a] = n[a];
		lg->bmin[a] = org[a];
		lg->cell[a] = cell[a];
	}
	lg->nleaf = nleaf;
	/* the geometry of the levels, then their stored ranges */
	if ((rc = vx_macro_build_explicit(&lg->mc, n, leaf, nl,
	    (const int (*)[3])sizes, 1, e)) != 0)
		goto out;
	for (l = 1; l <= nl; l++) {
		size_t nf = 2 * level_cells(&lg->mc, l);
		for (i = 0; i < nf; i++, k += 4) {
			uint32_t u = vx_le32(tmp + k);
			memcpy(&lg->mc.mm[l][i], &u, 4);
			if (isnan(lg->mc.mm[l][i])) {
				rc = vx_err_set(e, VX_EDATA, "level %d holds NaN",
				    l);
				goto out;
			}
		}
	}
	/* the root from the stored top level */
	{
		int top = (int)nl;
		size_t nf = level_cells(&lg->mc, top);
		float lo = INFINITY, hi = -INFINITY;
		for (i = 0; i < nf; i++) {
			lo = fminf(lo, lg->mc.mm[top][2 * i]);
			hi = fmaxf(hi, lg->mc.mm[top][2 * i + 1]);
		}
		lg->mc.root[0] = lo;
		lg->mc.root[1] = hi;
	}
	if (idp != NULL)
		*idp = id;
out:
	free(tmp);
	free(leaf);
	vx_hdr_free(&h);
	if (rc != 0) {
		vx_tetleaf_free(lg);
		vx_err_push(e, "leaf grid");
	}
	return rc;
}

int
vx_tetleaf_from_stream(vx_tetleaf *lg, const vx_stream *s,
    const vx_tetmesh *m, int *status, long *index, vx_err *e)
{
	vx_tetleaf_ident id;
	long i;
	int rc;

	vx_tetleaf_init(lg);
	if ((rc = vx_macro_stream_find(s, VX_CHUNK_TETLEAF, m->name, status,
	    index, &i, e)) != 0 || i < 0)
		return rc;
	if (vx_tetleaf_from_chunk(lg, &id, &s->chunk[i], e) != 0)
		return vx_err_push(e, "chunk TLEF at %llu",
		    (unsigned long long)s->chunk[i].offset);
	if (id.npoint == m->npoint && id.ntet == m->ntet &&
	    id.crc == vx_tetmesh_crc(m)) {
		*status = VX_MACRO_LOADED;
		return 0;
	}
	vx_tetleaf_free(lg);
	*status = VX_MACRO_STALE;
	return 0;
}

long
vx_tetmesh_find_source(const vx_stream *s, const char *name, int *is_mesh)
{
	size_t i;

	for (i = 0; i < s->n; i++) {
		const char *t = s->chunk[i].type, *v;
		const unsigned char *body;
		size_t bodylen;
		int mesh, match;
		vx_hdr h;

		mesh = memcmp(t, VX_CHUNK_TETMESH, 4) == 0;
		if (!mesh && memcmp(t, VX_CHUNK_VOLUME, 4) != 0)
			continue;
		if (name == NULL) {
			*is_mesh = mesh;
			return (long)i;
		}
		vx_hdr_init(&h);
		match = 0;
		if (vx_payload_parse(&s->chunk[i], &h, &body, &bodylen, NULL) == 0) {
			v = vx_hdr_get(&h, "name");
			if (v == NULL)
				v = mesh ? "mesh" : "density";
			match = strcmp(v, name) == 0;
		}
		vx_hdr_free(&h);
		if (match) {
			*is_mesh = mesh;
			return (long)i;
		}
	}
	return -1;
}
