/* grid.c: rectilinear volumes, offset-table layouts, the VOLM chunk. */
#include "vx_grid.h"
#include "vx_vec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

size_t
vx_type_size(vx_type t)
{
	switch (t) {
	case VX_U8: return 1;
	case VX_U16: case VX_I16: return 2;
	case VX_F32: return 4;
	default: return 0;
	}
}

static const vx_enum_name type_names[] = {
	{ "u8", VX_U8 }, { "u16", VX_U16 }, { "i16", VX_I16 },
	{ "f32", VX_F32 }, { NULL, VX_TYPE_UNKNOWN }
};
const vx_enum vx_type_enum = { "type", type_names, "unknown", 0 };

static const vx_enum_name interp_names[] = {
	{ "nearest", VX_INTERP_NEAREST }, { "trilinear", VX_INTERP_TRILINEAR },
	{ "tricubic", VX_INTERP_TRICUBIC },
	{ "nearest-iso", VX_INTERP_NEAREST_ISO }, { NULL, VX_INTERP_UNKNOWN }
};
const vx_enum vx_interp_enum = { "interpolation", interp_names, "unknown",
    0 };

/* ---- layouts ---- */

void
vx_layout_free(vx_layout *lay)
{
	int a;

	for (a = 0; a < 3; a++)
		free(lay->off[a]);
	memset(lay, 0, sizeof *lay);
}

size_t
vx_layout_nsample(const vx_layout *lay)
{
	return (size_t)lay->pdims[0] * (size_t)lay->pdims[1] *
	    (size_t)lay->pdims[2];
}

static int
check_dims(const int64_t dims[3], vx_err *e)
{
	int a;

	for (a = 0; a < 3; a++)
		if (dims[a] < 1 || dims[a] > VX_GRID_MAX_DIM)
			return vx_err_set(e, VX_EDATA,
			    "dims %lld %lld %lld: each must be in 1..%lld",
			    (long long)dims[0], (long long)dims[1],
			    (long long)dims[2], (long long)VX_GRID_MAX_DIM);
	return 0;
}

static int
alloc_tables(vx_layout *lay, const int64_t dims[3], vx_err *e)
{
	int a;

	for (a = 0; a < 3; a++) {
		lay->off[a] = malloc(((size_t)dims[a] + 1) * sizeof(int64_t));
		if (lay->off[a] == NULL) {
			vx_layout_free(lay);
			return vx_err_set(e, VX_ENOMEM, "out of memory for layout");
		}
	}
	return 0;
}

static int
check_total(const vx_layout *lay, vx_err *e)
{
	uint64_t n = (uint64_t)lay->pdims[0] * (uint64_t)lay->pdims[1];

	/* each pdim <= 2^21, so the first product cannot overflow */
	if (n > VX_GRID_MAX_SAMPLES ||
	    n * (uint64_t)lay->pdims[2] > VX_GRID_MAX_SAMPLES)
		return vx_err_set(e, VX_EDATA,
		    "volume of %lld x %lld x %lld samples exceeds the limit of "
		    "%llu samples", (long long)lay->pdims[0],
		    (long long)lay->pdims[1], (long long)lay->pdims[2],
		    (unsigned long long)VX_GRID_MAX_SAMPLES);
	return 0;
}

int
vx_layout_linear(vx_layout *lay, const int64_t dims[3], vx_err *e)
{
	int64_t stride[3];
	int a, rc;

	memset(lay, 0, sizeof *lay);
	if ((rc = check_dims(dims, e)) != 0)
		return rc;
	memcpy(lay->pdims, dims, sizeof lay->pdims);
	if ((rc = check_total(lay, e)) != 0)
		return rc;
	if ((rc = alloc_tables(lay, dims, e)) != 0)
		return rc;
	stride[0] = 1;
	stride[1] = dims[0];
	stride[2] = dims[0] * dims[1];
	for (a = 0; a < 3; a++) {
		int64_t x;

		for (x = 0; x < dims[a]; x++)
			lay->off[a][x] = x * stride[a];
		lay->off[a][dims[a]] = lay->off[a][dims[a] - 1];
	}
	return 0;
}

int
vx_layout_bricked(vx_layout *lay, const int64_t dims[3], int nlev,
    const int bricks[][3], vx_err *e)
{
	int64_t w[VX_LAYOUT_MAXLEV][3];  /* level-l brick width in samples */
	int64_t vol[VX_LAYOUT_MAXLEV];   /* level-l brick volume in samples */
	int64_t nb[3];
	int a, l, rc;

	if (nlev == 0)
		return vx_layout_linear(lay, dims, e);
	memset(lay, 0, sizeof *lay);
	if ((rc = check_dims(dims, e)) != 0)
		return rc;
	if (nlev < 0 || nlev > VX_LAYOUT_MAXLEV)
		return vx_err_set(e, VX_EDATA, "layout: %d brick levels (1..%d)",
		    nlev, VX_LAYOUT_MAXLEV);
	lay->nlev = nlev;
	for (l = 0; l < nlev; l++) {
		vol[l] = 1;
		for (a = 0; a < 3; a++) {
			int b = bricks[l][a];

			if (b < 1 || b > 1024 || (b & (b - 1)) != 0)
				return vx_err_set(e, VX_EDATA,
				    "layout: brick edge %d is not a power of two "
				    "in 1..1024", b);
			lay->brick[l][a] = b;
			w[l][a] = (l ? w[l - 1][a] : 1) * b;
			if (w[l][a] > VX_GRID_MAX_DIM)
				return vx_err_set(e, VX_EDATA,
				    "layout: bricks wider than %lld samples",
				    (long long)VX_GRID_MAX_DIM);
			vol[l] *= w[l][a];
		}
	}
	for (a = 0; a < 3; a++) {
		int64_t wt = w[nlev - 1][a];

		nb[a] = (dims[a] + wt - 1) / wt;
		lay->pdims[a] = nb[a] * wt;
	}
	if ((rc = check_total(lay, e)) != 0)
		return rc;
	if ((rc = alloc_tables(lay, dims, e)) != 0)
		return rc;
	for (a = 0; a < 3; a++) {
		int64_t x;

		for (x = 0; x < dims[a]; x++) {
			int64_t off, stride;

			/* innermost: sample within a level-0 brick */
			stride = a == 0 ? 1 : a == 1 ? w[0][0] : w[0][0] * w[0][1];
			off = (x % w[0][a]) * stride;
			/* level l: which level-(l-1) brick within a level-l brick */
			for (l = 1; l < nlev; l++) {
				int64_t r = (x / w[l - 1][a]) % lay->brick[l][a];

				stride = a == 0 ? 1 : a == 1 ? lay->brick[l][0] :
				    (int64_t)lay->brick[l][0] * lay->brick[l][1];
				off += r * stride * vol[l - 1];
			}
			/* top: which outermost brick */
			stride = a == 0 ? 1 : a == 1 ? nb[0] : nb[0] * nb[1];
			off += (x / w[nlev - 1][a]) * stride * vol[nlev - 1];
			lay->off[a][x] = off;
		}
		lay->off[a][dims[a]] = lay->off[a][dims[a] - 1];
	}
	return 0;
}

int
vx_layout_default_bricks(vx_type t, int bricks[][3])
{
	static const int line[][3] = {
		[VX_U8] = { 4, 4, 4 }, [VX_U16] = { 4, 4, 2 },
		[VX_I16] = { 4, 4, 2 }, [VX_F32] = { 4, 2, 2 },
	};

	if (t <= VX_TYPE_UNKNOWN || t >= VX_TYPE_LAST)
		return 0;
	for (int a = 0; a < 3; a++) {
		bricks[0][a] = line[t][a];
		bricks[1][a] = 4;
	}
	return 2;
}

void
vx_layout_string(const vx_layout *lay, char *buf, size_t n)
{
	size_t k;
	int l;

	if (lay->nlev == 0) {
		snprintf(buf, n, "linear");
		return;
	}
	k = (size_t)snprintf(buf, n, "bricked");
	for (l = 0; l < lay->nlev && k < n; l++)
		k += (size_t)snprintf(buf + k, n - k, " %dx%dx%d",
		    lay->brick[l][0], lay->brick[l][1], lay->brick[l][2]);
}

/* brick_edge: a decimal integer of 1 to 4 digits at *s, advancing *s;
 * -1 if there is none (no sign, no space: the grammar of formats/stream.md). */
static int
brick_edge(const char **s)
{
	int v = 0, k;

	for (k = 0; k < 4 && **s >= '0' && **s <= '9'; k++, (*s)++)
		v = v * 10 + (**s - '0');
	if (k == 0 || (**s >= '0' && **s <= '9'))
		return -1;
	return v;
}

int
vx_layout_parse(vx_layout *lay, const int64_t dims[3], const char *s,
    vx_err *e)
{
	int bricks[VX_LAYOUT_MAXLEV][3];
	int nlev = 0, a;

	if (strcmp(s, "linear") == 0)
		return vx_layout_linear(lay, dims, e);
	if (strncmp(s, "bricked", 7) != 0)
		return vx_err_set(e, VX_EDATA, "layout '%.60s': expected linear "
		    "or bricked AxBxC ...", s);
	s += 7;
	/* "bricked" then one or more " AxBxC", innermost level first */
	while (*s == ' ') {
		const char *w = ++s;

		if (nlev == VX_LAYOUT_MAXLEV)
			return vx_err_set(e, VX_EDATA,
			    "layout: more than %d brick levels", VX_LAYOUT_MAXLEV);
		for (a = 0; a < 3; a++) {
			if (a > 0 && *s++ != 'x')
				break;
			if ((bricks[nlev][a] = brick_edge(&s)) < 0)
				break;
		}
		if (a < 3 || (*s != ' ' && *s != '\0'))
			return vx_err_set(e, VX_EDATA,
			    "layout: bad brick size '%.20s'", w);
		nlev++;
	}
	if (*s != '\0' || nlev == 0)
		return vx_err_set(e, VX_EDATA, "layout: bad brick list");
	return vx_layout_bricked(lay, dims, nlev, (const int (*)[3])bricks, e);
}

/* ---- grids ---- */

void
vx_grid_init(vx_grid *g)
{
	memset(g, 0, sizeof *g);
	snprintf(g->name, sizeof g->name, "density");
	g->spacing[0] = g->spacing[1] = g->spacing[2] = 1.0;
}

void
vx_grid_free(vx_grid *g)
{
	if (g == NULL)
		return;
	if (!g->borrowed)
		free(g->data);
	vx_layout_free(&g->lay);
	vx_grid_init(g);
}

/* grid_shape: g initialized with dims, type and the layout's tables, no
 * samples yet; *nbytes gets their size */
static int
grid_shape(vx_grid *g, const int64_t dims[3], vx_type type,
    const char *lay_spec, size_t *nbytes, vx_err *e)
{
	size_t ts = vx_type_size(type);
	int rc;

	vx_grid_init(g);
	if (ts == 0)
		return vx_err_set(e, VX_EDATA, "unknown sample type");
	rc = lay_spec ? vx_layout_parse(&g->lay, dims, lay_spec, e) :
	    vx_layout_linear(&g->lay, dims, e);
	if (rc != 0)
		return rc;
	g->nsample = vx_layout_nsample(&g->lay);
	if (vx_mul_size(nbytes, g->nsample, ts) != 0) {
		vx_layout_free(&g->lay);
		return vx_err_set(e, VX_EDATA, "volume size overflows");
	}
	memcpy(g->dims, dims, sizeof g->dims);
	g->type = type;
	return 0;
}

int
vx_grid_alloc(vx_grid *g, const int64_t dims[3], vx_type type,
    const char *lay_spec, vx_err *e)
{
	size_t ts = vx_type_size(type), nbytes;
	int rc;

	if ((rc = grid_shape(g, dims, type, lay_spec, &nbytes, e)) != 0)
		return rc;
	if ((g->data = calloc(g->nsample, ts)) == NULL) {
		vx_layout_free(&g->lay);
		return vx_err_set(e, VX_ENOMEM, "cannot allocate %zu bytes for "
		    "samples", nbytes);
	}
	return 0;
}

double
vx_grid_get_index(const vx_grid *g, size_t i)
{
	switch (g->type) {
	case VX_U8: return ((const uint8_t *)g->data)[i];
	case VX_U16: return ((const uint16_t *)g->data)[i];
	case VX_I16: return ((const int16_t *)g->data)[i];
	case VX_F32: return ((const float *)g->data)[i];
	default: return NAN;
	}
}

double
vx_grid_get(const vx_grid *g, int64_t x, int64_t y, int64_t z)
{
	return vx_grid_get_index(g, vx_grid_index(g, x, y, z));
}

void
vx_grid_set(vx_grid *g, int64_t x, int64_t y, int64_t z, double v)
{
	size_t i = vx_grid_index(g, x, y, z);

	switch (g->type) {
	case VX_U8:
		((uint8_t *)g->data)[i] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 :
		    lrint(v));
		break;
	case VX_U16:
		((uint16_t *)g->data)[i] = (uint16_t)(v < 0 ? 0 : v > 65535 ?
		    65535 : lrint(v));
		break;
	case VX_I16:
		((int16_t *)g->data)[i] = (int16_t)(v < -32768 ? -32768 :
		    v > 32767 ? 32767 : lrint(v));
		break;
	case VX_F32:
		((float *)g->data)[i] = (float)v;
		break;
	default:
		break;
	}
}

void
vx_grid_cell(const vx_grid *g, int64_t x, int64_t y, int64_t z, float c[8])
{
	vx_grid_cell_inline(g, x, y, z, c);
}

void
vx_grid_range(vx_grid *g)
{
	double lo = INFINITY, hi = -INFINITY;
	int64_t x, y, z;

	for (z = 0; z < g->dims[2]; z++)
		for (y = 0; y < g->dims[1]; y++) {
			size_t base = (size_t)(g->lay.off[1][y] + g->lay.off[2][z]);

			for (x = 0; x < g->dims[0]; x++) {
				double v = vx_grid_get_index(g,
				    base + (size_t)g->lay.off[0][x]);

				if (!isfinite(v))
					continue;
				if (v < lo)
					lo = v;
				if (v > hi)
					hi = v;
			}
		}
	g->has_range = lo <= hi;
	g->vmin = g->has_range ? lo : 0;
	g->vmax = g->has_range ? hi : 0;
}

int
vx_grid_relayout(vx_grid *dst, const vx_grid *src, const char *spec,
    vx_err *e)
{
	size_t ts = vx_type_size(src->type);
	int64_t x, y, z;
	int rc;

	if ((rc = vx_grid_alloc(dst, src->dims, src->type, spec, e)) != 0)
		return rc;
	memcpy(dst->name, src->name, sizeof dst->name);
	memcpy(dst->spacing, src->spacing, sizeof dst->spacing);
	memcpy(dst->origin, src->origin, sizeof dst->origin);
	dst->has_range = src->has_range;
	dst->vmin = src->vmin;
	dst->vmax = src->vmax;
	for (z = 0; z < src->dims[2]; z++)
		for (y = 0; y < src->dims[1]; y++)
			for (x = 0; x < src->dims[0]; x++)
				memcpy((char *)dst->data +
				    vx_grid_index(dst, x, y, z) * ts,
				    (const char *)src->data +
				    vx_grid_index(src, x, y, z) * ts, ts);
	return 0;
}

/* ---- the VOLM chunk ---- */

/* the keys the VOLM writer writes itself (formats/stream.md 9.1) */
static const char *const volm_keys[] = {
	"name", "dims", "type", "spacing", "origin", "layout", "range",
	"encoding", "pad", NULL
};

int
vx_grid_key_known(const char *k)
{
	int i;

	for (i = 0; volm_keys[i] != NULL; i++)
		if (strcmp(k, volm_keys[i]) == 0)
			return 1;
	return 0;
}

int
vx_grid_to_chunk(const vx_grid *g, int zlevel, vx_chunk *c, vx_err *e)
{
	return vx_grid_to_chunk_extra(g, zlevel, NULL, c, e);
}

/* volm_hdr: the VOLM header of g, then extra's keys the writer does not
 * make itself (h initialized by the caller) */
static int
volm_hdr(const vx_grid *g, const vx_hdr *extra, vx_hdr *h, vx_err *e)
{
	char lay[128];
	int rc;

	if (g->name[0] == '\0')
		return vx_err_set(e, VX_EDATA, "volume: empty name");
	vx_layout_string(&g->lay, lay, sizeof lay);
	if ((rc = vx_hdr_set(h, "name", e, "%s", g->name)) ||
	    (rc = vx_hdr_set(h, "dims", e, "%lld %lld %lld",
	    (long long)g->dims[0], (long long)g->dims[1],
	    (long long)g->dims[2])) ||
	    (rc = vx_hdr_set(h, "type", e, "%s",
	    vx_enum_str(&vx_type_enum, g->type))) ||
	    (rc = vx_hdr_set(h, "spacing", e, "%.17g %.17g %.17g",
	    g->spacing[0], g->spacing[1], g->spacing[2])) ||
	    (rc = vx_hdr_set(h, "origin", e, "%.17g %.17g %.17g",
	    g->origin[0], g->origin[1], g->origin[2])) ||
	    (rc = vx_hdr_set(h, "layout", e, "%s", lay)))
		return rc;
	if (g->has_range &&
	    (rc = vx_hdr_set(h, "range", e, "%.17g %.17g", g->vmin, g->vmax)))
		return rc;
	for (size_t i = 0; extra != NULL && i < extra->n; i++)
		if (!vx_grid_key_known(extra->key[i]) &&
		    (rc = vx_hdr_set_str(h, extra->key[i], extra->val[i],
		    e)) != 0)
			return rc;
	return 0;
}

int
vx_grid_to_chunk_extra(const vx_grid *g, int zlevel, const vx_hdr *extra,
    vx_chunk *c, vx_err *e)
{
	size_t ts = vx_type_size(g->type), nbytes = g->nsample * ts;
	vx_hdr h;
	void *body = g->data, *tmp = NULL;
	int rc;

	vx_hdr_init(&h);
	if ((rc = volm_hdr(g, extra, &h, e)) != 0)
		goto out;
	if (!vx_host_is_le() && ts > 1) {
		if ((tmp = vx_malloc(nbytes, e)) == NULL) {
			rc = VX_ENOMEM;
			goto out;
		}
		memcpy(tmp, g->data, nbytes);
		vx_swap_bytes(tmp, g->nsample, ts);
		body = tmp;
	}
	rc = vx_payload_make(c, VX_CHUNK_VOLUME, &h, body, nbytes, zlevel, e);
out:
	free(tmp);
	vx_hdr_free(&h);
	return rc;
}

int
vx_grid_to_chunk_take(vx_grid *g, int zlevel, const vx_hdr *extra,
    vx_chunk *c, vx_err *e)
{
	size_t nbytes = g->nsample * vx_type_size(g->type);
	vx_hdr h;
	int rc;

	/* compressed, byte-swapped or not g's own memory: a copy, as ever */
	if (zlevel > 0 || !vx_host_is_le() || g->borrowed || g->data == NULL) {
		rc = vx_grid_to_chunk_extra(g, zlevel, extra, c, e);
		vx_grid_free(g);
		return rc;
	}
	vx_hdr_init(&h);
	if ((rc = volm_hdr(g, extra, &h, e)) == 0) {
		rc = vx_payload_wrap(c, VX_CHUNK_VOLUME, &h, g->data, nbytes, e);
		g->data = NULL;   /* the chunk's now (or freed) */
	}
	vx_hdr_free(&h);
	vx_grid_free(g);
	return rc;
}

/* from_chunk: vx_grid_from_chunk, or vx_grid_view_chunk when view */
static int
from_chunk(vx_grid *g, const vx_chunk *c, int view, vx_err *e)
{
	const unsigned char *body;
	size_t bodylen, ts, nbytes;
	int64_t dims[3];
	double r[2];
	vx_layout lay;
	vx_type type;
	const char *v, *lay_spec, *enc;
	vx_hdr h;
	int rc, found;

	vx_grid_init(g);
	vx_hdr_init(&h);
	if ((rc = vx_payload_parse(c, &h, &body, &bodylen, e)) != 0)
		goto out;
	if ((rc = vx_hdr_get_i64(&h, "dims", dims, 3, e)) != 0)
		goto out;
	if ((v = vx_hdr_get(&h, "type")) == NULL ||
	    (type = (vx_type)vx_enum_val(&vx_type_enum, v)) ==
	    VX_TYPE_UNKNOWN) {
		rc = vx_err_set(e, VX_EDATA, "missing or unknown type '%.20s'",
		    v ? v : "");
		goto out;
	}
	ts = vx_type_size(type);
	lay_spec = vx_hdr_get(&h, "layout");
	if (lay_spec == NULL)
		lay_spec = "linear";
	/* size the body from the header, and check the data can back it,
	 * before allocating anything on the header's word */
	if ((rc = vx_layout_parse(&lay, dims, lay_spec, e)) != 0)
		goto out;
	nbytes = vx_layout_nsample(&lay) * ts;  /* <= 2^38: no overflow */
	vx_layout_free(&lay);
	if ((rc = vx_body_fits(&h, bodylen, nbytes, e)) != 0)
		goto out;
	if ((v = vx_hdr_get(&h, "name")) != NULL &&
	    (v[0] == '\0' || strlen(v) >= sizeof g->name)) {
		rc = vx_err_set(e, VX_EDATA, "name must have 1 to %zu bytes",
		    sizeof g->name - 1);
		goto out;
	}
	/* a raw body of little-endian samples, aligned for the type, is used
	 * where it lies (its length is nbytes: vx_body_fits) */
	enc = vx_hdr_get(&h, "encoding");
	if (view && vx_host_is_le() && (enc == NULL || strcmp(enc, "raw") == 0)
	    && (uintptr_t)body % ts == 0) {
		if ((rc = grid_shape(g, dims, type, lay_spec, &nbytes, e)) != 0)
			goto out;
		g->data = (void *)(uintptr_t)body;
		g->borrowed = 1;
	} else if ((rc = vx_grid_alloc(g, dims, type, lay_spec, e)) != 0)
		goto out;
	if (v != NULL)
		snprintf(g->name, sizeof g->name, "%s", v);
	if ((rc = vx_hdr_get_f64_opt(&h, "spacing", g->spacing, 3, &found,
	    e)) != 0 ||
	    (rc = vx_hdr_get_f64_opt(&h, "origin", g->origin, 3, &found,
	    e)) != 0)
		goto out;
	if ((rc = vx_grid_check_box(g, e)) != 0)
		goto out;
	if ((rc = vx_hdr_get_f64_opt(&h, "range", r, 2, &found, e)) != 0)
		goto out;
	if (found && !(isfinite(r[0]) && isfinite(r[1]) && r[0] <= r[1])) {
		rc = vx_err_set(e, VX_EDATA, "range must be two finite numbers, "
		    "min <= max");
		goto out;
	}
	if (!g->borrowed) {
		if ((rc = vx_body_decode(&h, body, bodylen, g->data, nbytes,
		    e)) != 0)
			goto out;
		if (!vx_host_is_le())
			vx_swap_bytes(g->data, g->nsample, ts);
	}
	if (found) {
		g->has_range = 1;
		g->vmin = r[0];
		g->vmax = r[1];
	} else
		vx_grid_range(g);
out:
	vx_hdr_free(&h);
	if (rc != 0) {
		vx_grid_free(g);
		vx_err_push(e, "volume");
	}
	return rc;
}

int
vx_grid_from_chunk(vx_grid *g, const vx_chunk *c, vx_err *e)
{
	return from_chunk(g, c, 0, e);
}

int
vx_grid_view_chunk(vx_grid *g, const vx_chunk *c, vx_err *e)
{
	return from_chunk(g, c, 1, e);
}

/* from_stream: vx_grid_from_stream or vx_grid_view_stream.  Each volume is
 * looked at in place (all its checks, no copy of a raw body); the one named
 * is then copied if a copy is asked for. */
static int
from_stream(vx_grid *g, const vx_stream *s, const char *name, long *index,
    int view, vx_err *e)
{
	long i = -1;
	int rc;

	while ((i = vx_stream_find(s, VX_CHUNK_VOLUME, (size_t)(i + 1))) >= 0) {
		if ((rc = from_chunk(g, &s->chunk[i], 1, e)) != 0)
			return rc;
		if (name == NULL || strcmp(g->name, name) == 0) {
			/* a copy asked for: a body decoded by the look
			 * (zlib) already is one */
			if (!view && g->borrowed) {
				vx_grid_free(g);
				if ((rc = from_chunk(g, &s->chunk[i], 0, e)) != 0)
					return rc;
			}
			if (index != NULL)
				*index = i;
			return 0;
		}
		vx_grid_free(g);
	}
	vx_grid_init(g);
	if (name != NULL)
		return vx_err_set(e, VX_EDATA, "no volume named '%s' in the "
		    "stream", name);
	return vx_err_set(e, VX_EDATA, "no volume in the stream");
}

int
vx_grid_from_stream(vx_grid *g, const vx_stream *s, const char *name,
    long *index, vx_err *e)
{
	return from_stream(g, s, name, index, 0, e);
}

int
vx_grid_view_stream(vx_grid *g, const vx_stream *s, const char *name,
    long *index, vx_err *e)
{
	return from_stream(g, s, name, index, 1, e);
}

/* ---- grids ---- */

void
vx_grid_box(const vx_grid *g, double lo[3], double hi[3])
{
	int k;

	for (k = 0; k < 3; k++) {
		lo[k] = g->origin[k];
		hi[k] = g->origin[k] + (double)(g->dims[k] - 1) * g->spacing[k];
	}
}

int
vx_grid_check_box(const vx_grid *g, vx_err *e)
{
	double lo[3], hi[3], m = 0, r = 0;
	int k;

	for (k = 0; k < 3; k++)
		if (!(g->spacing[k] > 0) || !isfinite(g->spacing[k]) ||
		    !isfinite(g->origin[k]))
			return vx_err_set(e, VX_EDATA, "spacing must be finite "
			    "and positive, origin finite");
	vx_grid_box(g, lo, hi);
	for (k = 0; k < 3; k++) {
		double s = hi[k] - lo[k];

		if (!isfinite(hi[k]) || !isfinite(s))
			return vx_err_set(e, VX_EDATA, "extent overflows on axis "
			    "%d: origin %.17g + (%lld - 1) x spacing %.17g", k,
			    g->origin[k], (long long)g->dims[k], g->spacing[k]);
		m = s > m ? s : m;
	}
	/* the diagonal, scaled by the longest side (no overflow in the
	 * squares): finite unless it exceeds the double range itself */
	for (k = 0; k < 3 && m > 0; k++)
		r += ((hi[k] - lo[k]) / m) * ((hi[k] - lo[k]) / m);
	if (!isfinite(m * sqrt(r)))
		return vx_err_set(e, VX_EDATA, "extent overflows: the box's "
		    "diagonal is beyond the double range");
	return 0;
}

void
vx_world_to_index(const vx_grid *g, const double w[3], double i[3])
{
	int k;

	for (k = 0; k < 3; k++)
		i[k] = (w[k] - g->origin[k]) / g->spacing[k];
}

void
vx_index_to_world(const vx_grid *g, const double i[3], double w[3])
{
	int k;

	for (k = 0; k < 3; k++)
		w[k] = g->origin[k] + i[k] * g->spacing[k];
}

void
vx_world_to_index_dir(const vx_grid *g, const double w[3], double i[3])
{
	int k;

	for (k = 0; k < 3; k++)
		i[k] = w[k] / g->spacing[k];
}

void
vx_index_to_world_dir(const vx_grid *g, const double i[3], double w[3])
{
	int k;

	for (k = 0; k < 3; k++)
		w[k] = i[k] * g->spacing[k];
}

void
vx_index_to_world_normal(const vx_grid *g, const double i[3], double w[3])
{
	int k;

	for (k = 0; k < 3; k++)
		w[k] = i[k] / g->spacing[k];
	vx_unit3(w);
}

double
vx_grid_trilinear(const vx_grid *g, const double p[3])
{
	return vx_grid_trilinear_inline(g, p);
}
