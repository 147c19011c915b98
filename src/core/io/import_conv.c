/* import_conv.c: source sample types, axis-aligned frames, and placing
 * decoded samples into a grid (byte order, type conversion, scaling,
 * mirrored axes). */
#include "import_priv.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- source sample types ---- */

static const vx_enum_name scalar_names[] = {
	{ "u8", VX_S_U8 }, { "i8", VX_S_I8 }, { "u16", VX_S_U16 },
	{ "i16", VX_S_I16 }, { "u32", VX_S_U32 }, { "i32", VX_S_I32 },
	{ "u64", VX_S_U64 }, { "i64", VX_S_I64 }, { "f32", VX_S_F32 },
	{ "f64", VX_S_F64 }, { NULL, VX_SCALAR_UNKNOWN }
};
const vx_enum vx_scalar_enum = { "type", scalar_names, "unknown", 0 };

size_t
vx_scalar_size(vx_scalar t)
{
	static const size_t sz[VX_SCALAR_LAST] = { 0, 1, 1, 2, 2, 4, 4, 8, 8,
	    4, 8 };

	return t > VX_SCALAR_UNKNOWN && t < VX_SCALAR_LAST ? sz[t] : 0;
}

vx_type
vx_scalar_target(vx_scalar t)
{
	switch (t) {
	case VX_S_U8: return VX_U8;
	case VX_S_I8: case VX_S_I16: return VX_I16;
	case VX_S_U16: return VX_U16;
	case VX_S_U32: case VX_S_I32: case VX_S_U64: case VX_S_I64:
	case VX_S_F32: case VX_S_F64: return VX_F32;
	default: return VX_TYPE_UNKNOWN;
	}
}

/* ---- frames ---- */

int
vx_imp_frame_axes(vx_imp_frame *f, const double col[3][3], const double org[3],
    const int64_t dims[3], const char *what, vx_err *e)
{
	static const char axn[] = "xyz";
	int a, w;

	memset(f, 0, sizeof *f);
	for (a = 0; a < 3; a++) {
		double len = 0, step = col[a][a];

		if (!isfinite(org[a]))
			return vx_err_set(e, VX_EDATA, "%s: origin %c is not "
			    "finite", what, axn[a]);
		for (w = 0; w < 3; w++) {
			if (!isfinite(col[a][w]))
				return vx_err_set(e, VX_EDATA, "%s: axis %d has a "
				    "non-finite component", what, a);
			len += col[a][w] * col[a][w];
		}
		len = sqrt(len);
		if (!(len > 0))
			return vx_err_set(e, VX_EDATA, "%s: axis %d has zero "
			    "length", what, a);
		for (w = 0; w < 3; w++)
			if (w != a && fabs(col[a][w]) > 1e-6 * len)
				return vx_err_set(e, VX_EDATA, "%s: axis %d is not "
				    "aligned with world %c (rotated or permuted "
				    "frames are not supported)", what, a, axn[a]);
		f->spacing[a] = fabs(step);
		f->origin[a] = org[a];
		if (step < 0) {
			/* mirror: file sample n-1 becomes grid sample 0 */
			f->flip[a] = 1;
			f->origin[a] = org[a] + step * (double)(dims[a] - 1);
		}
	}
	return 0;
}

int
vx_imp_frame_plain(vx_imp_frame *f, const double sp[3], const double org[3],
    const int64_t dims[3], const char *what, vx_err *e)
{
	double col[3][3] = { { 0 } };
	int a;

	for (a = 0; a < 3; a++)
		col[a][a] = sp[a];
	return vx_imp_frame_axes(f, col, org, dims, what, e);
}

/* ---- sizes ---- */

int
vx_imp_total(const int64_t dims[3], size_t size, uint64_t *total,
    uint64_t *bytes, const char *what, vx_err *e)
{
	uint64_t t = 1;
	int a;

	for (a = 0; a < 3; a++) {
		if (dims[a] < 1 || dims[a] > VX_GRID_MAX_DIM)
			return vx_err_set(e, VX_EDATA, "%s: size %lld of axis %d "
			    "out of range 1..%lld", what, (long long)dims[a], a,
			    (long long)VX_GRID_MAX_DIM);
		t *= (uint64_t)dims[a];   /* each <= 2^20: no overflow */
	}
	if (t > VX_GRID_MAX_SAMPLES)
		return vx_err_set(e, VX_EDATA, "%s: %lld x %lld x %lld samples "
		    "exceed the limit of %llu", what, (long long)dims[0],
		    (long long)dims[1], (long long)dims[2],
		    (unsigned long long)VX_GRID_MAX_SAMPLES);
	*total = t;
	*bytes = t * size;             /* <= 2^36 * 8 */
	return 0;
}

/* ---- conversion ---- */

#define STAGE IMP_STAGE

int
vx_imp_conv_begin(vx_imp_conv *c, vx_grid *g, const int64_t dims[3],
    vx_scalar st, int big_endian, const vx_imp_frame *f, const double *scale,
    vx_err *e)
{
	vx_type tt = vx_scalar_target(st);
	int rc, a;

	memset(c, 0, sizeof *c);
	if (tt == VX_TYPE_UNKNOWN)
		return vx_err_set(e, VX_EINTERNAL, "import: unknown sample type");
	if (scale != NULL) {
		tt = VX_F32;
		c->scale = 1;
		c->slope = scale[0];
		c->inter = scale[1];
	}
	if ((rc = vx_grid_alloc(g, dims, tt, NULL, e)) != 0)
		return rc;
	c->g = g;
	c->st = st;
	c->ss = vx_scalar_size(st);
	c->swap = c->ss > 1 && (big_endian ? vx_host_is_le() : !vx_host_is_le());
	c->total = (uint64_t)dims[0] * (uint64_t)dims[1] * (uint64_t)dims[2];
	c->stop = c->total;
	for (a = 0; a < 3; a++) {
		g->spacing[a] = f->spacing[a];
		g->origin[a] = f->origin[a];
		c->flip[a] = f->flip[a];
		c->anyflip |= f->flip[a];
	}
	c->tmp = malloc(STAGE * 8);
	c->out = malloc(STAGE * 4);
	if (c->tmp == NULL || c->out == NULL) {
		vx_imp_conv_abort(c);
		vx_grid_free(g);
		return vx_err_set(e, VX_ENOMEM, "import: out of memory");
	}
	return 0;
}

void
vx_imp_conv_abort(vx_imp_conv *c)
{
	free(c->tmp);
	free(c->out);
	c->tmp = NULL;
	c->out = NULL;
}

/* place: k target-typed samples from c->out into the grid at c->next. */
static void
place(vx_imp_conv *c, const void *src, size_t k)
{
	vx_grid *g = c->g;
	size_t ts = vx_type_size(g->type), i;
	const unsigned char *p = src;

	if (!c->anyflip) {
		/* linear layout: grid index == file order */
		memcpy((unsigned char *)g->data + c->next * ts, p, k * ts);
		c->next += k;
		return;
	}
	for (i = 0; i < k; i++) {
		int64_t x = c->flip[0] ? g->dims[0] - 1 - c->x : c->x;
		int64_t y = c->flip[1] ? g->dims[1] - 1 - c->y : c->y;
		int64_t z = c->flip[2] ? g->dims[2] - 1 - c->z : c->z;

		memcpy((unsigned char *)g->data + vx_grid_index(g, x, y, z) * ts,
		    p + i * ts, ts);
		if (++c->x == g->dims[0]) {
			c->x = 0;
			if (++c->y == g->dims[1]) {
				c->y = 0;
				c->z++;
			}
		}
	}
	c->next += k;
}

/* load: source sample i of p (already in host order) as double. */
static double
load(vx_scalar st, const unsigned char *p, size_t i)
{
	union { uint8_t u8; int8_t i8; uint16_t u16; int16_t i16;
		uint32_t u32; int32_t i32; uint64_t u64; int64_t i64;
		float f32; double f64; } u;
	size_t ss = vx_scalar_size(st);

	memcpy(&u, p + i * ss, ss);
	switch (st) {
	case VX_S_U8: return u.u8;
	case VX_S_I8: return u.i8;
	case VX_S_U16: return u.u16;
	case VX_S_I16: return u.i16;
	case VX_S_U32: return u.u32;
	case VX_S_I32: return u.i32;
	case VX_S_U64: return (double)u.u64;
	case VX_S_I64: return (double)u.i64;
	case VX_S_F32: return u.f32;
	case VX_S_F64: return u.f64;
	default: return NAN;
	}
}

/* to_f32: a double into f32, refusing finite values beyond its range. */
static int
to_f32(vx_imp_conv *c, double v, float *out, vx_err *e)
{
	if (isfinite(v) && fabs(v) > FLT_MAX)
		return vx_err_set(e, VX_EDATA, "sample %llu: value %g is beyond "
		    "the f32 range", (unsigned long long)c->next, v);
	*out = (float)v;
	return 0;
}

#define CONVERT(ST, TT)                                                  \
	do {                                                             \
		const ST *s_ = (const ST *)(const void *)p;              \
		TT *o_ = (TT *)c->out;                                   \
		for (i = 0; i < k; i++) {                                \
			ST v_;                                           \
			memcpy(&v_, s_ + i, sizeof v_);                  \
			o_[i] = (TT)v_;                                  \
		}                                                        \
	} while (0)

int
vx_imp_conv_bytes(vx_imp_conv *c, const unsigned char *p, size_t k, vx_err *e)
{
	vx_type tt = c->g->type;
	size_t i;
	int rc;

	if (k > c->stop - c->next)
		return vx_err_set(e, VX_EINTERNAL, "import: too many samples");
	while (k > STAGE) {
		if ((rc = vx_imp_conv_bytes(c, p, STAGE, e)) != 0)
			return rc;
		p += STAGE * c->ss;
		k -= STAGE;
	}
	if (c->swap) {
		if (p != c->tmp) {
			memcpy(c->tmp, p, k * c->ss);
			p = c->tmp;
		}
		vx_swap_bytes(c->tmp, k, c->ss);
	}
	if (c->scale) {
		float *o = c->out;

		for (i = 0; i < k; i++) {
			double v = load(c->st, p, i) * c->slope + c->inter;

			if ((rc = to_f32(c, v, &o[i], e)) != 0)
				return rc;
		}
		place(c, c->out, k);
		return 0;
	}
	if (vx_type_size(tt) == c->ss && (c->st == VX_S_U8 ||
	    c->st == VX_S_U16 || c->st == VX_S_I16 || c->st == VX_S_F32)) {
		place(c, p, k);         /* same representation */
		return 0;
	}
	switch (c->st) {
	case VX_S_I8: CONVERT(int8_t, int16_t); break;
	case VX_S_U32: CONVERT(uint32_t, float); break;
	case VX_S_I32: CONVERT(int32_t, float); break;
	case VX_S_U64: CONVERT(uint64_t, float); break;
	case VX_S_I64: CONVERT(int64_t, float); break;
	case VX_S_F64: {
		const unsigned char *q = p;
		float *o = c->out;

		for (i = 0; i < k; i++) {
			double v;

			memcpy(&v, q + 8 * i, 8);
			if ((rc = to_f32(c, v, &o[i], e)) != 0)
				return rc;
		}
		break;
	}
	default:
		return vx_err_set(e, VX_EINTERNAL, "import: bad conversion");
	}
	place(c, c->out, k);
	return 0;
}

int
vx_imp_conv_binary(vx_imp_conv *c, vx_imp_src *s, vx_err *e)
{
	size_t ts = vx_type_size(c->g->type);
	int rc;

	/* fast path: same representation, host order, no mirroring: read
	 * straight into the grid */
	if (!c->swap && !c->scale && !c->anyflip && ts == c->ss &&
	    (c->st == VX_S_U8 || c->st == VX_S_U16 || c->st == VX_S_I16 ||
	    c->st == VX_S_F32)) {
		size_t want = (size_t)(c->stop - c->next) * ts, got;

		if ((rc = vx_imp_read(s, (unsigned char *)c->g->data + c->next * ts,
		    want, &got, e)) != 0)
			return rc;
		c->next += got / ts;
		if (got < want)
			return vx_err_set(e, VX_EDATA, "truncated: %llu of %llu "
			    "sample bytes", (unsigned long long)got,
			    (unsigned long long)want);
		return 0;
	}
	uint64_t first = c->next;

	while (c->next < c->stop) {
		uint64_t left = c->stop - c->next;
		size_t k = left < STAGE ? (size_t)left : STAGE, got;

		if ((rc = vx_imp_read(s, c->tmp, k * c->ss, &got, e)) != 0)
			return rc;
		if (got < k * c->ss)
			return vx_err_set(e, VX_EDATA, "truncated: %llu of %llu "
			    "sample bytes", (unsigned long long)((c->next -
			    first) * c->ss + got), (unsigned long long)((c->stop -
			    first) * c->ss));
		if ((rc = vx_imp_conv_bytes(c, c->tmp, k, e)) != 0)
			return rc;
	}
	return 0;
}

/* ascii_store: one parsed number as source sample `idx` in host order at
 * q; integer types must get integers in their range. */
static int
ascii_store(const vx_imp_conv *c, double v, unsigned char *q, const char *tok,
    uint64_t idx, vx_err *e)
{
	static const double lo[VX_SCALAR_LAST] = { 0, 0, -128, 0, -32768, 0,
	    -2147483648.0, 0, -9223372036854775808.0, 0, 0 };
	static const double hi[VX_SCALAR_LAST] = { 0, 255, 127, 65535, 32767,
	    4294967295.0, 2147483647.0, 18446744073709551615.0,
	    9223372036854775807.0, 0, 0 };
	union { uint8_t u8; int8_t i8; uint16_t u16; int16_t i16;
		uint32_t u32; int32_t i32; uint64_t u64; int64_t i64;
		float f32; double f64; } u;

	if (c->st != VX_S_F32 && c->st != VX_S_F64 &&
	    (v != floor(v) || v < lo[c->st] || v > hi[c->st]))
		return vx_err_set(e, VX_EDATA, "value %llu '%s' is not a %s",
		    (unsigned long long)idx, vx_imp_show(tok, strlen(tok)),
		    vx_enum_str(&vx_scalar_enum, c->st));
	switch (c->st) {
	case VX_S_U8: u.u8 = (uint8_t)v; break;
	case VX_S_I8: u.i8 = (int8_t)v; break;
	case VX_S_U16: u.u16 = (uint16_t)v; break;
	case VX_S_I16: u.i16 = (int16_t)v; break;
	case VX_S_U32: u.u32 = (uint32_t)v; break;
	case VX_S_I32: u.i32 = (int32_t)v; break;
	case VX_S_U64: u.u64 = v >= 18446744073709551615.0 ? UINT64_MAX :
	    (uint64_t)v; break;
	case VX_S_I64: u.i64 = v >= 9223372036854775807.0 ? INT64_MAX :
	    (int64_t)v; break;
	case VX_S_F32:
		if (isfinite(v) && fabs(v) > FLT_MAX)
			return vx_err_set(e, VX_EDATA, "value %llu '%s' is beyond "
			    "the float range", (unsigned long long)idx,
			    vx_imp_show(tok, strlen(tok)));
		u.f32 = (float)v;
		break;
	case VX_S_F64: u.f64 = v; break;
	default: return VX_EINTERNAL;
	}
	memcpy(q, &u, c->ss);
	return 0;
}

static int
sep(unsigned char ch)
{
	return ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r' ||
	    ch == ',' || ch == '\f' || ch == '\v';
}

#define WIN ((size_t)1 << 16)     /* text window */

int
vx_imp_conv_ascii(vx_imp_conv *c, vx_imp_src *s, vx_err *e)
{
	int swap = c->swap, rc;
	size_t nb = 0;              /* parsed values staged in c->tmp */

	c->swap = 0;                /* values are stored in host order */
	/* each value needs a byte and all but the last a separator */
	if ((rc = vx_imp_need(s, 2 * (c->stop - c->next) - 1, "ascii data",
	    e)) != 0)
		goto out;
	while (c->next + nb < c->stop) {
		const unsigned char *p;
		size_t avail, i = 0;

		if ((rc = vx_imp_peek(s, WIN, &p, &avail, e)) != 0)
			goto out;
		if (avail == 0) {
			rc = vx_err_set(e, VX_EDATA, "truncated: %llu of %llu "
			    "values", (unsigned long long)(c->next + nb),
			    (unsigned long long)c->stop);
			goto out;
		}
		while (c->next + nb < c->stop) {
			size_t t0;
			char buf[80], *end;
			double v;

			while (i < avail && sep(p[i]))
				i++;
			if (i == avail)
				break;
			t0 = i;
			while (i < avail && !sep(p[i]))
				i++;
			if (i == avail && avail == WIN) {
				i = t0;     /* the token may go on: refill */
				break;
			}
			if (i - t0 >= sizeof buf) {
				rc = vx_err_set(e, VX_EDATA, "value %llu is too "
				    "long", (unsigned long long)(c->next + nb));
				goto out;
			}
			memcpy(buf, p + t0, i - t0);
			buf[i - t0] = '\0';
			v = vx_strtod(buf, &end);
			if (end == buf || *end != '\0') {
				rc = vx_err_set(e, VX_EDATA, "value %llu '%s' is "
				    "not a number", (unsigned long long)(c->next +
				    nb), vx_imp_show(buf, i - t0));
				goto out;
			}
			/* a number beyond the double range is refused as one
			 * beyond the float range is (ascii_store), whatever
			 * the type; "inf" written out is taken as it is, and
			 * underflow rounds */
			if (errno == ERANGE && isinf(v)) {
				rc = vx_err_set(e, VX_EDATA, "value %llu '%s' is "
				    "beyond the double range", (unsigned long long)
				    (c->next + nb), vx_imp_show(buf, i - t0));
				goto out;
			}
			if ((rc = ascii_store(c, v, c->tmp + nb * c->ss, buf,
			    c->next + nb, e)) != 0)
				goto out;
			if (++nb == STAGE) {
				if ((rc = vx_imp_conv_bytes(c, c->tmp, nb, e)) != 0)
					goto out;
				nb = 0;
			}
		}
		if (i == 0) {
			rc = vx_err_set(e, VX_EDATA, "value %llu is too long",
			    (unsigned long long)(c->next + nb));
			goto out;
		}
		if ((rc = vx_imp_skip(s, i, e)) != 0)
			goto out;
	}
	if (nb > 0)
		rc = vx_imp_conv_bytes(c, c->tmp, nb, e);
out:
	c->swap = swap;
	return rc;
}

#define RANGE(T)                                                         \
	do {                                                             \
		const T *d_ = g->data;                                   \
		T lo_ = d_[0], hi_ = d_[0];                              \
		for (i = 1; i < n; i++) {                                \
			lo_ = d_[i] < lo_ ? d_[i] : lo_;                 \
			hi_ = d_[i] > hi_ ? d_[i] : hi_;                 \
		}                                                        \
		g->vmin = lo_;                                           \
		g->vmax = hi_;                                           \
		g->has_range = 1;                                        \
	} while (0)

/* range: vx_grid_range for the linear, unpadded grids built here, with
 * typed loops (the generic one costs as much as the whole import). */
static void
range(vx_grid *g)
{
	size_t n = g->nsample, i;

	switch (g->type) {
	case VX_U8: RANGE(uint8_t); break;
	case VX_U16: RANGE(uint16_t); break;
	case VX_I16: RANGE(int16_t); break;
	default: vx_grid_range(g); break;    /* f32: NaN and inf excluded */
	}
}

int
vx_imp_conv_end(vx_imp_conv *c, vx_err *e)
{
	vx_imp_conv_abort(c);
	if (c->next != c->total)
		return vx_err_set(e, VX_EDATA, "truncated: %llu of %llu samples",
		    (unsigned long long)c->next, (unsigned long long)c->total);
	range(c->g);
	return 0;
}
