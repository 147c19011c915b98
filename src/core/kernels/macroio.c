/* macroio.c: the min/max hierarchy's stream form, the MCEL chunk
 * (vx_macroio.h, formats/macrocell.md). */
#include "vx_macroio.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "macro_priv.h"

int
vx_macro_hdr_levels(const vx_macro *m, vx_hdr *h, vx_err *e)
{
	char sz[VX_MACRO_MAXLEV * 16 + 1], key[16];
	size_t k = 0;
	int l, rc;

	sz[0] = '\0';
	for (l = 1; l <= m->nlev; l++)
		k += (size_t)snprintf(sz + k, sizeof sz - k, "%s%dx%dx%d",
		    l > 1 ? " " : "", m->size[l][0], m->size[l][1],
		    m->size[l][2]);
	if ((rc = vx_hdr_set(h, "levels", e, "%d", m->nlev)) ||
	    (rc = vx_hdr_set(h, "sizes", e, "%s", sz)))
		return rc;
	for (l = 1; l <= m->nlev; l++) {
		snprintf(key, sizeof key, "dims-%d", l);
		if ((rc = vx_hdr_set(h, key, e, "%lld %lld %lld",
		    (long long)m->dims[l][0], (long long)m->dims[l][1],
		    (long long)m->dims[l][2])) != 0)
			return rc;
	}
	if (m->root[0] <= m->root[1])
		return vx_hdr_set(h, "range", e, "%.9g %.9g",
		    (double)m->root[0], (double)m->root[1]);
	return vx_hdr_set(h, "range", e, "empty");
}

int
vx_macro_to_chunk(const vx_macro *m, int zlevel, vx_chunk *c, vx_err *e)
{
	size_t nbytes = vx_macro_bytes(m), k;
	unsigned char *body = NULL;
	vx_hdr h;
	int l, rc;

	vx_hdr_init(&h);
	if ((rc = vx_hdr_set(&h, "leaves", e, "%s", m->explicit_leaves ?
	    "explicit" : "cells")) != 0)
		goto out;
	if (!m->explicit_leaves &&
	    ((rc = vx_hdr_set(&h, "volume", e, "%s", m->name)) ||
	    (rc = vx_hdr_set(&h, "volume-dims", e, "%lld %lld %lld",
	    (long long)m->vdims[0], (long long)m->vdims[1],
	    (long long)m->vdims[2])) ||
	    (rc = vx_hdr_set(&h, "volume-type", e, "%s",
	    vx_enum_str(&vx_type_enum, m->vtype))) ||
	    (rc = vx_hdr_set(&h, "volume-crc32", e, "%08x",
	    (unsigned)m->vcrc)) ||
	    (m->has_vchunk_crc && (rc = vx_hdr_set(&h, "volume-chunk-crc32",
	    e, "%08x", (unsigned)m->vchunk_crc)))))
		goto out;
	if ((rc = vx_hdr_set(&h, "leaf-dims", e, "%lld %lld %lld",
	    (long long)m->dims[0][0], (long long)m->dims[0][1],
	    (long long)m->dims[0][2])) ||
	    (rc = vx_macro_hdr_levels(m, &h, e)) ||
	    (rc = vx_hdr_set(&h, "nonfinite", e, "ignored")))
		goto out;
	if (nbytes > 0 && (body = vx_malloc(nbytes, e)) == NULL) {
		rc = VX_ENOMEM;
		goto out;
	}
	k = 0;
	for (l = m->explicit_leaves ? 0 : 1; l <= m->nlev; l++) {
		size_t i, nl = 2 * ncells(m, l);

		for (i = 0; i < nl; i++, k++) {
			uint32_t u;

			memcpy(&u, &m->mm[l][i], 4);
			vx_put_le32(body + 4 * k, u);
		}
	}
	rc = vx_payload_make(c, VX_CHUNK_MACRO, &h, body, nbytes, zlevel, e);
out:
	free(body);
	vx_hdr_free(&h);
	if (rc != 0)
		vx_err_push(e, "macrocells");
	return rc;
}

/* sizes_parse: a "sizes" value, exactly nlev space-separated AxBxC. */
static int
sizes_parse(const char *v, int nlev, int sizes[][3], vx_err *e)
{
	const char *p = v;
	int l, used;

	for (l = 0; l < nlev; l++) {
		if (l > 0 && *p++ != ' ')
			goto bad;
		if (*p < '0' || *p > '9' ||
		    sscanf(p, "%5dx%5dx%5d%n", &sizes[l][0], &sizes[l][1],
		    &sizes[l][2], &used) != 3)
			goto bad;
		p += used;
	}
	if (*p == '\0')
		return 0;
bad:
	return vx_err_set(e, VX_EDATA, "sizes '%.60s': expected %d sizes "
	    "AxBxC separated by spaces", v, nlev);
}

int
vx_macro_hdr_levels_get(const vx_hdr *h, int *nlev,
    int sizes[VX_MACRO_MAXLEV][3], int64_t dims[VX_MACRO_MAXLEV + 1][3],
    vx_err *e)
{
	const char *v;
	int64_t nl, dl[3];
	int l, a, rc;

	if ((rc = vx_hdr_get_i64(h, "levels", &nl, 1, e)) != 0)
		return rc;
	if (nl < 0 || nl > VX_MACRO_MAXLEV)
		return vx_err_set(e, VX_EDATA, "levels %lld: expected 0..%d",
		    (long long)nl, VX_MACRO_MAXLEV);
	if ((v = vx_hdr_get(h, "sizes")) == NULL)
		return vx_err_set(e, VX_EDATA, "missing sizes");
	if ((rc = sizes_parse(v, (int)nl, sizes, e)) != 0)
		return rc;
	for (l = 1; l <= nl; l++) {
		char key[16];

		for (a = 0; a < 3; a++) {
			int s = sizes[l - 1][a];

			if (s < 1 || s > VX_MACRO_MAXSIZE)
				return vx_err_set(e, VX_EDATA, "sizes: edge %d "
				    "out of 1..%d", s, VX_MACRO_MAXSIZE);
			dims[l][a] = (dims[l - 1][a] + s - 1) / s;
		}
		snprintf(key, sizeof key, "dims-%d", l);
		if ((rc = vx_hdr_get_i64(h, key, dl, 3, e)) != 0)
			return rc;
		if (dl[0] != dims[l][0] || dl[1] != dims[l][1] ||
		    dl[2] != dims[l][2])
			return vx_err_set(e, VX_EDATA, "%s does not follow from "
			    "leaf-dims and sizes", key);
	}
	*nlev = (int)nl;
	return 0;
}

int
vx_macro_from_chunk(vx_macro *m, const vx_chunk *c, vx_err *e)
{
	int sizes[VX_MACRO_MAXLEV][3];
	int64_t dims[VX_MACRO_MAXLEV + 1][3], *n = dims[0];
	const unsigned char *body;
	size_t bodylen, nbytes, k;
	const char *v;
	unsigned char *tmp = NULL;
	int explicit_leaves, nl, l, a, rc;
	vx_hdr h;

	vx_macro_init(m);
	vx_hdr_init(&h);
	if ((rc = vx_payload_parse(c, &h, &body, &bodylen, e)) != 0)
		goto out;
	v = vx_hdr_get(&h, "leaves");
	if (v == NULL || (strcmp(v, "cells") && strcmp(v, "explicit"))) {
		rc = vx_err_set(e, VX_EDATA, "leaves '%.20s': expected cells "
		    "or explicit", v ? v : "");
		goto out;
	}
	explicit_leaves = strcmp(v, "explicit") == 0;
	if ((rc = vx_hdr_get_i64(&h, "leaf-dims", n, 3, e)) != 0)
		goto out;
	/* vx_macro_setup checks every size and dim before anything is
	 * allocated (its allocation is the body's size, checked below first) */
	for (a = 0; a < 3; a++)
		if (n[a] < 0 || n[a] > VX_GRID_MAX_DIM) {
			rc = vx_err_set(e, VX_EDATA, "leaf-dims: %lld out of "
			    "0..%lld", (long long)n[a],
			    (long long)VX_GRID_MAX_DIM);
			goto out;
		}
	if ((rc = vx_macro_hdr_levels_get(&h, &nl, sizes, dims, e)) != 0)
		goto out;
	{
		/* the body size, computed as vx_macro_setup will, checked first */
		vx_macro g;

		vx_macro_init(&g);
		nbytes = 0;
		memcpy(g.dims, dims, (size_t)(nl + 1) * sizeof dims[0]);
		for (l = explicit_leaves ? 0 : 1; l <= nl; l++)
			if (vx_mul_size(&k, ncells(&g, l), 2 * sizeof(float)) ||
			    vx_add_size(&nbytes, nbytes, k)) {
				rc = vx_err_set(e, VX_EDATA, "too many cells");
				goto out;
			}
		if ((rc = vx_body_fits(&h, bodylen, nbytes, e)) != 0)
			goto out;
	}
	if ((rc = vx_macro_setup(m, n, nl, sizes, explicit_leaves,
	    e)) != 0)
		goto out;
	if (!explicit_leaves) {
		int64_t vd[3];

		if ((v = vx_hdr_get(&h, "volume")) == NULL || v[0] == '\0' ||
		    strlen(v) >= sizeof m->name) {
			rc = vx_err_set(e, VX_EDATA, "volume name missing or "
			    "longer than %zu bytes", sizeof m->name - 1);
			goto out;
		}
		snprintf(m->name, sizeof m->name, "%s", v);
		if ((rc = vx_hdr_get_i64(&h, "volume-dims", vd, 3, e)) != 0)
			goto out;
		for (a = 0; a < 3; a++)
			if (vd[a] < 1 || vd[a] > VX_GRID_MAX_DIM ||
			    (n[0] > 0 && vd[a] - 1 != n[a]) ||
			    (n[0] == 0 && vd[0] > 1 && vd[1] > 1 && vd[2] > 1)) {
				rc = vx_err_set(e, VX_EDATA, "volume-dims do not "
				    "match leaf-dims (cells = samples - 1)");
				goto out;
			}
		memcpy(m->vdims, vd, sizeof vd);
		if ((v = vx_hdr_get(&h, "volume-type")) == NULL ||
		    (m->vtype = (vx_type)vx_enum_val(&vx_type_enum, v)) ==
		    VX_TYPE_UNKNOWN) {
			rc = vx_err_set(e, VX_EDATA, "volume-type '%.20s' unknown",
			    v ? v : "");
			goto out;
		}
		v = vx_hdr_get(&h, "volume-crc32");
		if (v == NULL || strlen(v) != 8 ||
		    strspn(v, "0123456789abcdef") != 8) {
			rc = vx_err_set(e, VX_EDATA, "volume-crc32: expected 8 "
			    "lower-case hex digits");
			goto out;
		}
		m->vcrc = (uint32_t)strtoul(v, NULL, 16);
		if ((v = vx_hdr_get(&h, "volume-chunk-crc32")) != NULL) {
			if (strlen(v) != 8 ||
			    strspn(v, "0123456789abcdef") != 8) {
				rc = vx_err_set(e, VX_EDATA, "volume-chunk-crc32: "
				    "expected 8 lower-case hex digits");
				goto out;
			}
			m->vchunk_crc = (uint32_t)strtoul(v, NULL, 16);
			m->has_vchunk_crc = 1;
		}
	}
	if ((v = vx_hdr_get(&h, "range")) == NULL) {
		rc = vx_err_set(e, VX_EDATA, "missing range");
		goto out;
	}
	if (strcmp(v, "empty") != 0) {
		double r[2];

		if ((rc = vx_hdr_get_f64(&h, "range", r, 2, e)) != 0)
			goto out;
		if (!(r[0] <= r[1])) {
			rc = vx_err_set(e, VX_EDATA, "range: min > max");
			goto out;
		}
		m->root[0] = (float)r[0];
		m->root[1] = (float)r[1];
	}
	if (nbytes > 0) {
		if ((tmp = vx_malloc(nbytes, e)) == NULL) {
			rc = VX_ENOMEM;
			goto out;
		}
		if ((rc = vx_body_decode(&h, body, bodylen, tmp, nbytes, e)) != 0)
			goto out;
		k = 0;
		for (l = explicit_leaves ? 0 : 1; l <= nl; l++) {
			size_t i, nc = 2 * ncells(m, l);

			for (i = 0; i < nc; i++, k++) {
				uint32_t u = vx_le32(tmp + 4 * k);

				memcpy(&m->mm[l][i], &u, 4);
				if (isnan(m->mm[l][i])) {
					rc = vx_err_set(e, VX_EDATA, "level %d "
					    "holds NaN", l);
					goto out;
				}
			}
		}
	}
out:
	free(tmp);
	vx_hdr_free(&h);
	if (rc != 0) {
		vx_macro_free(m);
		vx_err_push(e, "macrocells");
	}
	return rc;
}

int
vx_macro_matches(const vx_macro *m, const vx_grid *g, const uint32_t *crc)
{
	if (m->explicit_leaves || strcmp(m->name, g->name) != 0 ||
	    m->vtype != g->type || m->vdims[0] != g->dims[0] ||
	    m->vdims[1] != g->dims[1] || m->vdims[2] != g->dims[2] ||
	    !fits(m, g))
		return 0;
	return (crc ? *crc : vx_macro_grid_crc(g)) == m->vcrc;
}

int
vx_macro_find_owned(const vx_stream *s, const char *type, const char *name,
    long *index, vx_err *e)
{
	const char *key = memcmp(type, VX_CHUNK_TETLEAF, 4) == 0 ? "mesh" :
	    "volume";
	long i = -1;

	*index = -1;
	while ((i = vx_stream_find(s, type, (size_t)(i + 1))) >= 0) {
		const unsigned char *body;
		const char *v, *lv;
		size_t bodylen;
		vx_hdr h;
		int mine, rc;

		vx_hdr_init(&h);
		if ((rc = vx_payload_parse(&s->chunk[i], &h, &body, &bodylen,
		    e)) != 0) {
			vx_hdr_free(&h);
			return vx_err_push(e, "chunk %.4s at %llu", type,
			    (unsigned long long)s->chunk[i].offset);
		}
		v = vx_hdr_get(&h, key);
		lv = vx_hdr_get(&h, "leaves");
		mine = v != NULL && name != NULL && strcmp(v, name) == 0;
		/* an MCEL over explicit leaves belongs to no volume; any
		 * other chunk without its owner is one nobody can place */
		if (v == NULL && (memcmp(type, VX_CHUNK_MACRO, 4) != 0 ||
		    lv == NULL || strcmp(lv, "explicit") != 0)) {
			vx_hdr_free(&h);
			vx_err_set(e, VX_EDATA, "no '%s' key", key);
			return vx_err_push(e, "chunk %.4s at %llu", type,
			    (unsigned long long)s->chunk[i].offset);
		}
		vx_hdr_free(&h);
		if (mine) {
			*index = i;
			return 0;
		}
	}
	return 0;
}

int
vx_macro_stream_find(const vx_stream *s, const char *type, const char *name,
    int *status, long *index, long *i, vx_err *e)
{
	*status = VX_MACRO_ABSENT;
	if (index != NULL)
		*index = -1;
	if (vx_macro_find_owned(s, type, name, i, e) != 0)
		return vx_err_push(e, memcmp(type, VX_CHUNK_TETLEAF, 4) == 0 ?
		    "leaf grid" : "macrocells");
	if (index != NULL)
		*index = *i;
	return 0;
}

int
vx_macro_from_stream(vx_macro *m, const vx_stream *s, const vx_grid *g,
    long src, int *status, long *index, vx_err *e)
{
	long i;
	int rc;

	vx_macro_init(m);
	if ((rc = vx_macro_stream_find(s, VX_CHUNK_MACRO, g->name, status,
	    index, &i, e)) != 0 || i < 0)
		return rc;
	if ((rc = vx_macro_from_chunk(m, &s->chunk[i], e)) != 0)
		return rc;
	/* the very bytes it was built from: their samples' CRC is the one
	 * recorded (the other checks still run) */
	if (src >= 0 && (size_t)src < s->n && m->has_vchunk_crc &&
	    s->chunk[src].crc_known &&
	    memcmp(s->chunk[src].type, VX_CHUNK_VOLUME, 4) == 0 &&
	    s->chunk[src].crc == m->vchunk_crc) {
		if (vx_macro_matches(m, g, &m->vcrc)) {
			*status = VX_MACRO_LOADED;
			return 0;
		}
	} else if (vx_macro_matches(m, g, NULL)) {
		*status = VX_MACRO_LOADED;
		return 0;
	}
	vx_macro_free(m);
	*status = VX_MACRO_STALE;
	return 0;
}
