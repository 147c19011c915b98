/* vinfo.c: print what a voxlux stream holds: every chunk, the headers of
 * content chunks, statistics of volumes and images recomputed from their
 * samples, and the history; as text or as one JSON object. */
#include <getopt.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tool.h"
#include "vx_grid.h"
#include "vx_image.h"
#include "vx_irrvol.h"
#include "vx_macroio.h"
#include "vx_shlight.h"
#include "vx_stats.h"
#include "vx_stream.h"
#include "vx_tetimport.h"
#include "vx_tetleaf.h"
#include "vx_tfimport.h"

static const char usage[] =
    "vinfo [--json] [--histogram N] [--chunks] [--transfer FORMAT] [FILE|-]";

#define MAX_BINS 1000
#define BAR_WIDTH 40

typedef struct opts {
	int json;
	int chunks_only;
	int transfer;           /* a vx_tf_format: read FILE as one */
	long bins;
	const char *in;
} opts;

/* What vinfo learned about one volume chunk. */
typedef struct vol_info {
	vx_grid g;
	vx_stats st;
	int hdr_range;          /* the header has a range key */
	double hr[2];
	int agrees;             /* header range (if any) equals the samples' */
	uint64_t *hist;         /* bins counts, NULL when bins is 0 */
	size_t bodylen;
} vol_info;

/* What vinfo learned about one image chunk. */
typedef struct img_info {
	vx_image img;
	double min[4], max[4];  /* over finite values; NaN when none */
	uint64_t nnan, ninf;
} img_info;

/* The errors found while decoding chunks, reported at the end. */
static int first_code;
static int nerrors;

static void
chunk_error(const vx_chunk *c, const vx_err *e)
{
	fprintf(stderr, "%s: chunk %s at %llu: %s\n", tool_name, c->type,
	    (unsigned long long)c->offset, e->msg);
	if (first_code == 0)
		first_code = e->code ? e->code : VX_EINTERNAL;
	nerrors++;
}

static void
parse_args(opts *o, int argc, char **argv)
{
	static const struct option lo[] = {
		{ "json", no_argument, NULL, 'j' },
		{ "histogram", required_argument, NULL, 'H' },
		{ "chunks", no_argument, NULL, 'c' },
		{ "transfer", required_argument, NULL, 'T' },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 },
	};
	int ch;

	memset(o, 0, sizeof *o);
	o->bins = 16;
	while ((ch = getopt_long(argc, argv, ":", lo, NULL)) != -1) {
		switch (ch) {
		case 'j':
			o->json = 1;
			break;
		case 'H':
			o->bins = tool_parse_long("--histogram", optarg, 0,
			    MAX_BINS);
			break;
		case 'c':
			o->chunks_only = 1;
			break;
		case 'T':
			o->transfer = tool_parse_enum("--transfer",
			    &vx_tf_format_enum, optarg);
			break;
		default:
			tool_opt_other(ch, usage, argv);
		}
	}
	o->in = tool_opt_input(argc, argv, usage);
}

/* ---- text output helpers ---- */

/* put_text: n bytes as printable text: valid UTF-8 as is, control
 * characters and invalid bytes as \xNN (a stream is untrusted input; this
 * keeps a terminal safe). */
static void
put_text(const unsigned char *p, size_t n)
{
	size_t i = 0;

	while (i < n) {
		size_t ok = vx_utf8_check(p + i, n - i), k;

		for (k = 0; k < ok; k++) {
			unsigned char c = p[i + k];

			if ((c < 0x20 && c != '\t') || c == 0x7f)
				printf("\\x%02x", c);
			else
				putchar(c);
		}
		i += ok;
		if (i < n)
			printf("\\x%02x", p[i++]);
	}
}

static void
put_str(const char *s)
{
	put_text((const unsigned char *)s, strlen(s));
}

/* ---- JSON output helpers ---- */

/* json_text: n bytes as a JSON string; bytes that are not UTF-8 become
 * U+FFFD, so the output is always valid JSON. */
static void
json_text(const unsigned char *p, size_t n)
{
	size_t i = 0;

	putchar('"');
	while (i < n) {
		size_t ok = vx_utf8_check(p + i, n - i), k;

		for (k = 0; k < ok; k++) {
			unsigned char c = p[i + k];

			if (c == '"' || c == '\\')
				printf("\\%c", c);
			else if (c == '\n')
				fputs("\\n", stdout);
			else if (c == '\t')
				fputs("\\t", stdout);
			else if (c == '\r')
				fputs("\\r", stdout);
			else if (c < 0x20)
				printf("\\u%04x", c);
			else
				putchar(c);
		}
		i += ok;
		if (i < n) {
			fputs("\\ufffd", stdout);
			i++;
		}
	}
	putchar('"');
}

static void
json_str(const char *s)
{
	json_text((const unsigned char *)s, strlen(s));
}

/* json_num: a double, or null when it has no JSON spelling. */
static void
json_num(double v)
{
	if (isfinite(v))
		printf("%.17g", v);
	else
		fputs("null", stdout);
}

static void
json_nums(const double *v, int n)
{
	int i;

	putchar('[');
	for (i = 0; i < n; i++) {
		if (i)
			putchar(',');
		json_num(v[i]);
	}
	putchar(']');
}

/* ---- decoding ---- */

static int
is_content(const char *type)
{
	return vx_chunk_is_critical(type) && vx_chunk_is_known(type) &&
	    memcmp(type, VX_CHUNK_END, 4) != 0;
}

static int
decode_volume(const vx_chunk *c, const opts *o, vol_info *v, vx_err *e)
{
	const unsigned char *body;
	vx_hdr h;
	int rc, found;

	memset(v, 0, sizeof *v);
	vx_hdr_init(&h);
	if ((rc = vx_grid_view_chunk(&v->g, c, e)) != 0)
		return rc;
	/* the header's range, as written (the grid takes it as is) */
	if ((rc = vx_payload_parse(c, &h, &body, &v->bodylen, e)) == 0)
		rc = vx_hdr_get_f64_opt(&h, "range", v->hr, 2, &found, e);
	vx_hdr_free(&h);
	if (rc != 0)
		return rc;
	v->hdr_range = found;
	vx_grid_stats(&v->g, &v->st);
	if (found)
		v->agrees = v->st.has_range && v->hr[0] == v->st.vmin &&
		    v->hr[1] == v->st.vmax;
	else
		v->agrees = 1;
	if (o->bins > 0 && v->st.has_range) {
		if ((v->hist = vx_calloc((size_t)o->bins, sizeof *v->hist,
		    e)) == NULL)
			return VX_ENOMEM;
		if ((rc = vx_grid_histogram(&v->g, v->st.vmin, v->st.vmax,
		    (size_t)o->bins, v->hist, e)) != 0)
			return rc;
	}
	return 0;
}

static void
free_volume(vol_info *v)
{
	vx_grid_free(&v->g);
	free(v->hist);
	v->hist = NULL;
}

static int
decode_image(const vx_chunk *c, img_info *m, vx_err *e)
{
	size_t i, n;
	int rc, ch;

	memset(m, 0, sizeof *m);
	if ((rc = vx_image_from_chunk(&m->img, c, e)) != 0)
		return rc;
	for (ch = 0; ch < 4; ch++) {
		m->min[ch] = INFINITY;
		m->max[ch] = -INFINITY;
	}
	n = vx_image_nvalue(&m->img);
	for (i = 0; i < n; i++) {
		double v = m->img.px[i];

		ch = (int)(i % (size_t)m->img.nc);
		if (isnan(v))
			m->nnan++;
		else if (isinf(v))
			m->ninf++;
		else {
			if (v < m->min[ch])
				m->min[ch] = v;
			if (v > m->max[ch])
				m->max[ch] = v;
		}
	}
	for (ch = 0; ch < m->img.nc; ch++)
		if (m->min[ch] > m->max[ch])
			m->min[ch] = m->max[ch] = NAN;
	return 0;
}

/* decode_text_body: a content chunk whose body is text of `length` bytes
 * (SCNE): *text gets a malloc'ed copy, *n its length.  No length key: no
 * text, no error. */
static int
decode_text_body(const vx_chunk *c, unsigned char **text, size_t *n,
    vx_err *e)
{
	const unsigned char *body;
	size_t bodylen;
	int64_t len;
	vx_hdr h;
	int rc, found = 0;

	*text = NULL;
	*n = 0;
	vx_hdr_init(&h);
	if ((rc = vx_payload_parse(c, &h, &body, &bodylen, e)) != 0)
		goto out;
	if (vx_hdr_get(&h, "length") == NULL)
		goto out;
	found = 1;
	if ((rc = vx_hdr_get_i64(&h, "length", &len, 1, e)) != 0)
		goto out;
	if (len < 0 || (uint64_t)len > SIZE_MAX) {
		rc = vx_err_set(e, VX_EDATA, "length %lld", (long long)len);
		goto out;
	}
	if ((rc = vx_body_fits(&h, bodylen, (size_t)len, e)) != 0)
		goto out;
	if ((*text = vx_malloc((size_t)len + 1, e)) == NULL) {
		rc = VX_ENOMEM;
		goto out;
	}
	if ((rc = vx_body_decode(&h, body, bodylen, *text, (size_t)len, e))) {
		free(*text);
		*text = NULL;
		goto out;
	}
	*n = (size_t)len;
out:
	(void)found;
	vx_hdr_free(&h);
	return rc;
}

/* What vinfo learned about a macrocell chunk: its levels, and whether it
 * still matches the volume it was built over. */
typedef struct mcel_info {
	vx_macro m;
	const char *status;     /* "matches", "stale", "no such volume", or
	                           "explicit leaves" */
} mcel_info;

static int
decode_mcel(const vx_stream *s, const vx_chunk *c, mcel_info *mi, vx_err *e)
{
	vx_grid g;
	vx_err ge = { 0, "" };
	int rc;

	memset(mi, 0, sizeof *mi);
	if ((rc = vx_macro_from_chunk(&mi->m, c, e)) != 0)
		return rc;
	if (mi->m.explicit_leaves) {
		mi->status = "explicit leaves";
		return 0;
	}
	if (vx_grid_view_stream(&g, s, mi->m.name, NULL, &ge) != 0) {
		mi->status = "no such volume";
		return 0;
	}
	mi->status = vx_macro_matches(&mi->m, &g, NULL) ? "matches" : "stale";
	vx_grid_free(&g);
	return 0;
}

/* text_levels, json_levels: a hierarchy's levels above its leaves and its
 * root range (macrocells and leaf grids alike). */
static void
text_levels(const vx_macro *mc)
{
	int l;

	for (l = 1; l <= mc->nlev; l++)
		printf("    level %d: %dx%dx%d of level %d, %lld x %lld x %lld "
		    "cells\n", l, mc->size[l][0], mc->size[l][1],
		    mc->size[l][2], l - 1, (long long)mc->dims[l][0],
		    (long long)mc->dims[l][1], (long long)mc->dims[l][2]);
	printf("    root range: %.9g %.9g\n", (double)mc->root[0],
	    (double)mc->root[1]);
}

static void
json_levels(const vx_macro *mc)
{
	double r[2] = { mc->root[0], mc->root[1] };
	int l;

	printf("\"sizes\":[");
	for (l = 1; l <= mc->nlev; l++)
		printf("%s[%d,%d,%d]", l > 1 ? "," : "", mc->size[l][0],
		    mc->size[l][1], mc->size[l][2]);
	printf("],\"root\":");
	json_nums(r, 2);
}

static void
text_mcel(const mcel_info *mi)
{
	printf("  macrocells: %d level%s over %lld x %lld x %lld %s leaves\n",
	    mi->m.nlev, mi->m.nlev == 1 ? "" : "s",
	    (long long)mi->m.dims[0][0], (long long)mi->m.dims[0][1],
	    (long long)mi->m.dims[0][2],
	    mi->m.explicit_leaves ? "explicit" : "cell");
	text_levels(&mi->m);
	if (!mi->m.explicit_leaves) {
		printf("    volume: ");
		put_str(mi->m.name);
		printf(" (%s)\n", mi->status);
	}
}

static void
json_mcel(const mcel_info *mi)
{
	printf(",\"macrocells\":{\"levels\":%d,\"leaf_dims\":[%lld,%lld,%lld],"
	    "\"explicit\":%s,", mi->m.nlev,
	    (long long)mi->m.dims[0][0], (long long)mi->m.dims[0][1],
	    (long long)mi->m.dims[0][2],
	    mi->m.explicit_leaves ? "true" : "false");
	json_levels(&mi->m);
	if (!mi->m.explicit_leaves) {
		printf(",\"volume\":");
		json_str(mi->m.name);
	}
	printf(",\"status\":");
	json_str(mi->status);
	putchar('}');
}

static void
text_tetm(const vx_tetmesh *m)
{
	printf("  mesh: ");
	put_str(m->name);
	printf("\n    points: %zu, tets: %zu, scalar: ", m->npoint, m->ntet);
	put_str(m->scalar);
	putchar('\n');
	if (m->npoint > 0)
		printf("    bounds: %.9g %.9g %.9g to %.9g %.9g %.9g\n",
		    m->bmin[0], m->bmin[1], m->bmin[2], m->bmax[0], m->bmax[1],
		    m->bmax[2]);
	if (m->has_range)
		printf("    range: %.9g %.9g (recomputed)\n", m->vmin, m->vmax);
	else
		printf("    range: none (no finite value)\n");
}

static void
json_tetm(const vx_tetmesh *m)
{
	printf(",\"mesh\":{\"name\":");
	json_str(m->name);
	printf(",\"scalar\":");
	json_str(m->scalar);
	printf(",\"points\":%zu,\"tets\":%zu,\"bounds\":", m->npoint, m->ntet);
	if (m->npoint > 0) {
		double b[6] = { m->bmin[0], m->bmin[1], m->bmin[2], m->bmax[0],
		    m->bmax[1], m->bmax[2] };

		json_nums(b, 6);
	} else
		fputs("null", stdout);
	printf(",\"range\":");
	if (m->has_range) {
		double r[2] = { m->vmin, m->vmax };

		json_nums(r, 2);
	} else
		fputs("null", stdout);
	putchar('}');
}

/* What vinfo learned about a leaf-grid chunk: the grid, the mesh it
 * names, and whether it still matches that mesh. */
typedef struct tlef_info {
	vx_tetleaf lg;
	vx_tetleaf_ident id;
	const char *status;     /* "matches", "stale" or "no such mesh" */
} tlef_info;

static int
decode_tlef(const vx_stream *s, const vx_chunk *c, tlef_info *ti, vx_err *e)
{
	vx_tetmesh m;
	vx_err me = { 0, "" };
	int rc;

	memset(ti, 0, sizeof *ti);
	if ((rc = vx_tetleaf_from_chunk(&ti->lg, &ti->id, c, e)) != 0)
		return rc;
	if (vx_tetmesh_from_stream(&m, s, ti->id.mesh, NULL, &me) != 0) {
		ti->status = "no such mesh";
		return 0;
	}
	ti->status = m.npoint == ti->id.npoint && m.ntet == ti->id.ntet &&
	    vx_tetmesh_crc(&m) == ti->id.crc ? "matches" : "stale";
	vx_tetmesh_free(&m);
	return 0;
}

static void
text_tlef(const tlef_info *ti)
{
	const vx_macro *mc = &ti->lg.mc;
	double nt = ti->id.ntet ? (double)ti->id.ntet : 1;

	printf("  leaf grid: %lld x %lld x %lld leaves, %lu list entries "
	    "(%.2f per tet), %d level%s\n", (long long)ti->lg.dims[0],
	    (long long)ti->lg.dims[1], (long long)ti->lg.dims[2],
	    (unsigned long)ti->lg.off[ti->lg.nleaf],
	    (double)ti->lg.off[ti->lg.nleaf] / nt, mc->nlev,
	    mc->nlev == 1 ? "" : "s");
	text_levels(mc);
	printf("    memory: %zu bytes (%.1f per tet)\n",
	    vx_tetleaf_bytes(&ti->lg), (double)vx_tetleaf_bytes(&ti->lg) / nt);
	printf("    mesh: ");
	put_str(ti->id.mesh);
	printf(" (%s)\n", ti->status);
}

static void
json_tlef(const tlef_info *ti)
{
	const vx_macro *mc = &ti->lg.mc;

	printf(",\"leaf_grid\":{\"leaf_dims\":[%lld,%lld,%lld],\"entries\":%lu,"
	    "\"levels\":%d,", (long long)ti->lg.dims[0],
	    (long long)ti->lg.dims[1], (long long)ti->lg.dims[2],
	    (unsigned long)ti->lg.off[ti->lg.nleaf], mc->nlev);
	json_levels(mc);
	printf(",\"bytes\":%zu,\"mesh\":", vx_tetleaf_bytes(&ti->lg));
	json_str(ti->id.mesh);
	printf(",\"status\":");
	json_str(ti->status);
	putchar('}');
}

/* What vinfo learned about an irradiance volume: the lattice, the volume
 * it belongs to (for the lattice's world spacing) and counts over the
 * texels of its stored bricks. */
typedef struct irrv_info {
	vx_irrvol v;
	const char *status;     /* "matches", "stale" or "no such volume" */
	int has_world;          /* the volume is in the stream */
	double spacing[3];      /* world distance between texels per axis */
	double origin[3];       /* world position of texel (0,0,0) */
	uint64_t lattice;       /* texels of the lattice */
	uint64_t bricks;        /* bricks of the lattice, stored or not */
	uint64_t stored;        /* texels inside the lattice in stored bricks */
	uint64_t wanted, baked, usable, flat, nan, overflow, border;
	uint64_t smin, smax;    /* samples per baked texel (accum) */
	double samples;         /* samples over all texels (accum) */
	double emin[3], emax[3], emean[3];   /* over usable texels */
} irrv_info;

/* irrv_usable: texel s is wanted, holds an irradiance and is neither flat
 * nor NaN (a final store keeps no count: wanted is the test there). */
static int
irrv_usable(const vx_irrvol *v, int64_t s)
{
	return (v->flags[s] & VX_TEXEL_WANTED) && vx_irr_usable(v, s);
}

/* irrv_rgb: texel s's RGB: the irradiance, or an SH transfer's constant
 * coefficient per channel (one channel: repeated) */
static void
irrv_rgb(const vx_irrvol *v, int64_t s, double e[3])
{
	double m[VX_IRR_MAX_COMP];
	size_t cs = v->sh_order ? (size_t)(v->sh_order * v->sh_order) : 1;

	if (v->store == VX_IRR_ACCUM)
		vx_irr_acc_mean(v, vx_irr_accp(v, s), m);
	else
		for (int c = 0; c < v->ncomp; c++)
			m[c] = v->mean[(size_t)v->ncomp * (size_t)s + (size_t)c];
	for (int c = 0; c < 3; c++)
		e[c] = m[v->channels == 1 ? 0 : c * cs];
}

static void
irrv_count(irrv_info *ii)
{
	const vx_irrvol *v = &ii->v;
	double sum[3] = { 0, 0, 0 };
	uint64_t b;
	int64_t i, j, k;
	int c;

	ii->lattice = (uint64_t)v->dims[0] * (uint64_t)v->dims[1] *
	    (uint64_t)v->dims[2];
	ii->bricks = (uint64_t)v->bdims[0] * (uint64_t)v->bdims[1] *
	    (uint64_t)v->bdims[2];
	for (c = 0; c < 3; c++) {
		ii->emin[c] = INFINITY;
		ii->emax[c] = -INFINITY;
	}
	ii->smin = UINT64_MAX;
	/* stored bricks only: a sparse bake of a huge lattice is quick */
	for (b = 0; b < ii->bricks; b++) {
		int64_t b0[3];

		if (v->slot[b] == 0)
			continue;
		b0[0] = (int64_t)(b % (uint64_t)v->bdims[0]) * VX_IRR_BRICK;
		b0[1] = (int64_t)(b / (uint64_t)v->bdims[0] %
		    (uint64_t)v->bdims[1]) * VX_IRR_BRICK;
		b0[2] = (int64_t)(b / (uint64_t)v->bdims[0] /
		    (uint64_t)v->bdims[1]) * VX_IRR_BRICK;
		for (k = b0[2]; k < b0[2] + VX_IRR_BRICK; k++)
		    for (j = b0[1]; j < b0[1] + VX_IRR_BRICK; j++)
			for (i = b0[0]; i < b0[0] + VX_IRR_BRICK; i++) {
				int64_t s = vx_irr_texel(v, i, j, k);
				uint32_t f;
				double e[3];

				if (s < 0)     /* past the lattice's edge */
					continue;
				f = v->flags[s];
				ii->stored++;
				ii->wanted += (f & VX_TEXEL_WANTED) != 0;
				ii->flat += (f & VX_TEXEL_FLAT) != 0;
				ii->nan += (f & VX_TEXEL_NAN) != 0;
				ii->overflow += (f & VX_TEXEL_OVERFLOW) != 0;
				ii->border += (f & VX_TEXEL_BORDER) != 0;
				if (v->store == VX_IRR_ACCUM) {
					uint32_t n = vx_irr_accp(v, s)->count;

					if (n > 0) {
						ii->baked++;
						ii->samples += n;
						if (n < ii->smin)
							ii->smin = n;
						if (n > ii->smax)
							ii->smax = n;
					}
				} else if ((f & VX_TEXEL_WANTED) &&
				    !(f & (VX_TEXEL_FLAT | VX_TEXEL_NAN)))
					ii->baked++;
				if (!irrv_usable(v, s))
					continue;
				ii->usable++;
				irrv_rgb(v, s, e);
				for (c = 0; c < 3; c++) {
					sum[c] += e[c];
					if (e[c] < ii->emin[c])
						ii->emin[c] = e[c];
					if (e[c] > ii->emax[c])
						ii->emax[c] = e[c];
				}
			}
	}
	for (c = 0; c < 3; c++)
		if (ii->usable > 0)
			ii->emean[c] = sum[c] / (double)ii->usable;
		else
			ii->emin[c] = ii->emax[c] = ii->emean[c] = NAN;
	if (ii->baked == 0 || v->store != VX_IRR_ACCUM)
		ii->smin = 0;
}

static int
decode_irrv(const vx_stream *s, const vx_chunk *c, irrv_info *ii, vx_err *e)
{
	vx_grid g;
	vx_err ge = { 0, "" };
	int rc, a;

	memset(ii, 0, sizeof *ii);
	if ((rc = vx_irr_from_chunk(&ii->v, c, e)) != 0)
		return rc;
	irrv_count(ii);
	if (vx_grid_view_stream(&g, s, ii->v.volume, NULL, &ge) != 0) {
		ii->status = "no such volume";
		return 0;
	}
	ii->status = g.dims[0] == ii->v.vdims[0] &&
	    g.dims[1] == ii->v.vdims[1] && g.dims[2] == ii->v.vdims[2] &&
	    vx_macro_grid_crc(&g) == ii->v.vcrc ? "matches" : "stale";
	ii->has_world = 1;
	for (a = 0; a < 3; a++) {
		ii->spacing[a] = ii->v.step[a] * g.spacing[a];
		ii->origin[a] = g.origin[a];
	}
	vx_grid_free(&g);
	return 0;
}

static double
pct(uint64_t a, uint64_t b)
{
	return b ? 100.0 * (double)a / (double)b : 0;
}

static void
text_irrv(const irrv_info *ii)
{
	const vx_irrvol *v = &ii->v;
	static const char rgb[] = "RGB";
	int c;

	if (v->sh_order > 0)
		printf("  SH transfer volume: order %d, %d channel%s, of ",
		    v->sh_order, v->channels, v->channels == 1 ? "" : "s");
	else
		printf("  irradiance volume: of ");
	put_str(v->volume);
	printf(" (%s)\n", ii->status);
	printf("    lattice: %lld x %lld x %lld texels (%llu) at scale %.9g, "
	    "%.9g %.9g %.9g samples apart\n", (long long)v->dims[0],
	    (long long)v->dims[1], (long long)v->dims[2],
	    (unsigned long long)ii->lattice, v->scale, v->step[0], v->step[1],
	    v->step[2]);
	if (ii->has_world)
		printf("    world spacing: %.17g %.17g %.17g, origin %.17g %.17g "
		    "%.17g\n", ii->spacing[0], ii->spacing[1], ii->spacing[2],
		    ii->origin[0], ii->origin[1], ii->origin[2]);
	else
		printf("    world spacing: unknown (the volume is not in the "
		    "stream)\n");
	printf("    store: %s, %zu bytes a texel",
	    vx_enum_str(&vx_irr_store_enum, v->store),
	    vx_irr_texel_bytes(v->store, v->ncomp));
	if (v->store == VX_IRR_ACCUM)
		printf(", %d fraction bits\n", v->fixed);
	else
		printf(" (final: no counts, not resumable)\n");
	printf("    bricks: %zu of %llu stored (%.1f%%), %llu texels of the "
	    "lattice in them\n", v->nslot, (unsigned long long)ii->bricks,
	    pct(v->nslot, ii->bricks), (unsigned long long)ii->stored);
	printf("    texels: %llu wanted, %llu baked, %llu usable, %llu flat, "
	    "%llu NaN, %llu overflow, %llu at the border\n",
	    (unsigned long long)ii->wanted, (unsigned long long)ii->baked,
	    (unsigned long long)ii->usable, (unsigned long long)ii->flat,
	    (unsigned long long)ii->nan, (unsigned long long)ii->overflow,
	    (unsigned long long)ii->border);
	if (v->store == VX_IRR_ACCUM)
		printf("    samples per baked texel: %llu to %llu, %.17g in all "
		    "(from sample %u; the bake asked %u)\n",
		    (unsigned long long)ii->smin,
		    (unsigned long long)ii->smax, ii->samples, v->first,
		    v->samples);
	else
		printf("    samples per texel: not kept (the bake asked %u)\n",
		    v->samples);
	if (ii->usable > 0) {
		printf("    %s over the %llu usable texels:\n", v->sh_order ?
		    "constant coefficient" : "irradiance",
		    (unsigned long long)ii->usable);
		for (c = 0; c < 3; c++)
			printf("      %c: min %.9g max %.9g mean %.9g\n", rgb[c],
			    ii->emin[c], ii->emax[c], ii->emean[c]);
	} else
		printf("    irradiance: no usable texel\n");
	printf("    memory: %zu bytes\n", vx_irr_bytes(v));
	printf("    bake: key %s, offset %.9g voxels, seed %llu, lit side "
	    "%s\n", v->key, v->offset, (unsigned long long)v->seed,
	    v->high ? "high" : "low");
	printf("    settings: ");
	put_str(v->settings);
	putchar('\n');
}

static void
json_irrv(const irrv_info *ii)
{
	const vx_irrvol *v = &ii->v;

	printf(",\"%s\":{", v->sh_order ? "sh_transfer" : "irradiance");
	if (v->sh_order > 0)
		printf("\"order\":%d,\"channels\":%d,", v->sh_order,
		    v->channels);
	printf("\"volume\":");
	json_str(v->volume);
	printf(",\"status\":");
	json_str(ii->status);
	printf(",\"lattice_dims\":[%lld,%lld,%lld],\"scale\":",
	    (long long)v->dims[0], (long long)v->dims[1],
	    (long long)v->dims[2]);
	json_num(v->scale);
	printf(",\"step\":");
	json_nums(v->step, 3);
	printf(",\"spacing\":");
	if (ii->has_world)
		json_nums(ii->spacing, 3);
	else
		fputs("null", stdout);
	printf(",\"origin\":");
	if (ii->has_world)
		json_nums(ii->origin, 3);
	else
		fputs("null", stdout);
	printf(",\"store\":\"%s\",\"texel_bytes\":%zu,\"fixed\":",
	    vx_enum_str(&vx_irr_store_enum, v->store),
	    vx_irr_texel_bytes(v->store, v->ncomp));
	if (v->store == VX_IRR_ACCUM)
		printf("%d", v->fixed);
	else
		fputs("null", stdout);
	printf(",\"bricks\":%zu,\"bricks_total\":%llu,\"texels\":%llu,"
	    "\"stored\":%llu,\"wanted\":%llu,\"baked\":%llu,\"usable\":%llu,"
	    "\"flat\":%llu,\"nan\":%llu,\"overflow\":%llu,\"border\":%llu",
	    v->nslot, (unsigned long long)ii->bricks,
	    (unsigned long long)ii->lattice, (unsigned long long)ii->stored,
	    (unsigned long long)ii->wanted, (unsigned long long)ii->baked,
	    (unsigned long long)ii->usable, (unsigned long long)ii->flat,
	    (unsigned long long)ii->nan, (unsigned long long)ii->overflow,
	    (unsigned long long)ii->border);
	if (v->store == VX_IRR_ACCUM)
		printf(",\"samples_min\":%llu,\"samples_max\":%llu,"
		    "\"samples_total\":%.17g", (unsigned long long)ii->smin,
		    (unsigned long long)ii->smax, ii->samples);
	else
		printf(",\"samples_min\":null,\"samples_max\":null,"
		    "\"samples_total\":null");
	printf(",\"first_sample\":%u,\"samples_asked\":%u,\"e_min\":",
	    v->first, v->samples);
	json_nums(ii->emin, 3);
	printf(",\"e_max\":");
	json_nums(ii->emax, 3);
	printf(",\"e_mean\":");
	json_nums(ii->emean, 3);
	printf(",\"bytes\":%zu,\"key\":", vx_irr_bytes(v));
	json_str(v->key);
	printf(",\"offset\":");
	json_num(v->offset);
	printf(",\"seed\":%llu,\"side\":\"%s\",\"settings\":",
	    (unsigned long long)v->seed, v->high ? "high" : "low");
	json_str(v->settings);
	putchar('}');
}

/* ---- SH lighting (SHLC, formats/shlight.md) ---- */

/* band_energy: the sum of the squares of channel k's coefficients of band
 * l (its rotation-invariant part). */
static double
band_energy(const vx_shlight *l, int k, int band)
{
	const double *c = l->c + (size_t)k * (size_t)l->order * (size_t)l->order;
	double e = 0;

	for (int i = band * band; i < (band + 1) * (band + 1); i++)
		e += c[i] * c[i];
	return e;
}

static int
is_identity(const double r[3][3])
{
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			if (r[i][j] != (i == j))
				return 0;
	return 1;
}

static void
text_shlc(const vx_shlight *l)
{
	int n = l->order * l->order;

	printf("  SH lighting: order %d (%d coefficients a channel, r g b), "
	    "phase %s\n", l->order, n, l->phase == VX_SHLIGHT_PHASE_CS ?
	    "condon-shortley" : "none");
	if (l->has_hash)
		printf("    source map: content hash %016llx\n",
		    (unsigned long long)l->env_hash);
	else
		printf("    source map: none recorded\n");
	if (is_identity(l->rot))
		printf("    rotation: identity\n");
	else
		printf("    rotation: %.9g %.9g %.9g / %.9g %.9g %.9g / %.9g %.9g "
		    "%.9g (rows)\n", l->rot[0][0], l->rot[0][1], l->rot[0][2],
		    l->rot[1][0], l->rot[1][1], l->rot[1][2], l->rot[2][0],
		    l->rot[2][1], l->rot[2][2]);
	printf("    c00: %.9g %.9g %.9g (the mean radiance times sqrt(4 pi))\n",
	    l->c[0], l->c[n], l->c[2 * n]);
	for (int b = 0; b < l->order; b++)
		printf("    band %d energy: %.9g %.9g %.9g\n", b,
		    band_energy(l, 0, b), band_energy(l, 1, b),
		    band_energy(l, 2, b));
}

static void
json_shlc(const vx_shlight *l)
{
	int n = l->order * l->order;
	double c00[3] = { l->c[0], l->c[n], l->c[2 * n] };

	printf(",\"sh_lighting\":{\"order\":%d,\"phase\":\"%s\",\"hash\":",
	    l->order, l->phase == VX_SHLIGHT_PHASE_CS ? "condon-shortley" :
	    "none");
	if (l->has_hash)
		printf("\"%016llx\"", (unsigned long long)l->env_hash);
	else
		fputs("null", stdout);
	printf(",\"rotation\":");
	json_nums(&l->rot[0][0], 9);
	printf(",\"c00\":");
	json_nums(c00, 3);
	printf(",\"band_energy\":[");
	for (int b = 0; b < l->order; b++) {
		double e3[3] = { band_energy(l, 0, b), band_energy(l, 1, b),
		    band_energy(l, 2, b) };

		if (b > 0)
			putchar(',');
		json_nums(e3, 3);
	}
	printf("]}");
}

/* What vinfo decoded of a content chunk, for either report. */
enum { K_OTHER, K_VOLUME, K_IMAGE, K_SCENE, K_MCEL, K_TETM, K_TLEF,
    K_IRRV, K_SHLC };

typedef struct content {
	int kind;
	vol_info v;
	img_info m;
	unsigned char *text;    /* K_SCENE: NULL when the chunk has none */
	size_t ntext;
	mcel_info mi;
	vx_tetmesh tm;
	tlef_info ti;
	irrv_info ii;
	vx_shlight sl;
} content;

/* decode_content: the payload of c as its type says (K_OTHER: nothing to
 * decode beyond the header); 0 or the decoder's error.  d is freed by
 * free_content either way. */
static int
decode_content(const vx_stream *s, const vx_chunk *c, const opts *o,
    content *d, vx_err *e)
{
	memset(d, 0, sizeof *d);
	vx_tetmesh_init(&d->tm);
	if (memcmp(c->type, VX_CHUNK_VOLUME, 4) == 0) {
		d->kind = K_VOLUME;
		return decode_volume(c, o, &d->v, e);
	}
	if (memcmp(c->type, VX_CHUNK_IMAGE, 4) == 0) {
		d->kind = K_IMAGE;
		return decode_image(c, &d->m, e);
	}
	if (memcmp(c->type, VX_CHUNK_SCENE, 4) == 0) {
		d->kind = K_SCENE;
		return decode_text_body(c, &d->text, &d->ntext, e);
	}
	if (memcmp(c->type, VX_CHUNK_MACRO, 4) == 0) {
		d->kind = K_MCEL;
		return decode_mcel(s, c, &d->mi, e);
	}
	if (memcmp(c->type, VX_CHUNK_TETMESH, 4) == 0) {
		d->kind = K_TETM;
		return vx_tetmesh_from_chunk(&d->tm, c, e);
	}
	if (memcmp(c->type, VX_CHUNK_TETLEAF, 4) == 0) {
		d->kind = K_TLEF;
		return decode_tlef(s, c, &d->ti, e);
	}
	if (memcmp(c->type, VX_CHUNK_IRRAD, 4) == 0 ||
	    memcmp(c->type, VX_CHUNK_SHXFER, 4) == 0) {
		d->kind = K_IRRV;
		return decode_irrv(s, c, &d->ii, e);
	}
	if (memcmp(c->type, VX_CHUNK_SHLIGHT, 4) == 0) {
		d->kind = K_SHLC;
		return vx_shlight_from_chunk(&d->sl, c, e);
	}
	return 0;
}

static void
free_content(content *d)
{
	switch (d->kind) {
	case K_VOLUME: free_volume(&d->v); break;
	case K_IMAGE: vx_image_free(&d->m.img); break;
	case K_SCENE: free(d->text); break;
	case K_MCEL: vx_macro_free(&d->mi.m); break;
	case K_TETM: vx_tetmesh_free(&d->tm); break;
	case K_TLEF: vx_tetleaf_free(&d->ti.lg); break;
	case K_IRRV: vx_irr_free(&d->ii.v); break;
	default: break;
	}
}

/* check_range: a volume whose header's range is not its samples' is an
 * error of the stream (reported after the chunk). */
static void
check_range(const vx_chunk *c, const content *d)
{
	vx_err e = { 0, "" };

	if (d->kind == K_VOLUME && !d->v.agrees) {
		vx_err_set(&e, VX_EDATA, "volume: the header's range differs "
		    "from the samples'");
		chunk_error(c, &e);
	}
}

/* ---- text report ---- */

static void
text_histogram(const vol_info *v, long bins)
{
	double lo = v->st.vmin, hi = v->st.vmax, w = (hi - lo) / (double)bins;
	uint64_t top = 0;
	long b;

	for (b = 0; b < bins; b++)
		if (v->hist[b] > top)
			top = v->hist[b];
	printf("    histogram: %ld bins of width %.6g over [%.9g, %.9g]\n",
	    bins, w, lo, hi);
	for (b = 0; b < bins; b++) {
		char label[64];
		int bar = top ? (int)((v->hist[b] * BAR_WIDTH + top - 1) / top) : 0;

		snprintf(label, sizeof label, "[%.6g, %.6g%c", lo + w * (double)b,
		    b + 1 == bins ? hi : lo + w * (double)(b + 1),
		    b + 1 == bins ? ']' : ')');
		printf("      %-26s %12llu%s%.*s\n", label,
		    (unsigned long long)v->hist[b], bar ? " " : "", bar,
		    "########################################");
	}
}

static void
text_volume(const vol_info *v, long bins)
{
	const vx_grid *g = &v->g;
	const vx_stats *st = &v->st;
	char lay[128];

	vx_layout_string(&g->lay, lay, sizeof lay);
	printf("  volume: ");
	put_str(g->name);
	printf("\n    dims: %lld x %lld x %lld %s (%llu samples)\n",
	    (long long)g->dims[0], (long long)g->dims[1],
	    (long long)g->dims[2], vx_enum_str(&vx_type_enum, g->type),
	    (unsigned long long)st->count);
	printf("    spacing: %.17g %.17g %.17g\n", g->spacing[0], g->spacing[1],
	    g->spacing[2]);
	printf("    origin: %.17g %.17g %.17g\n", g->origin[0], g->origin[1],
	    g->origin[2]);
	printf("    layout: %s (%zu samples stored, %llu padding)\n", lay,
	    g->nsample, (unsigned long long)(g->nsample - st->count));
	printf("    body: %zu bytes for %zu decoded\n", v->bodylen,
	    g->nsample * vx_type_size(g->type));
	if (st->has_range)
		printf("    range: %.9g %.9g", st->vmin, st->vmax);
	else
		printf("    range: none (no finite sample)");
	if (!v->hdr_range)
		printf(" (recomputed; the header has none)\n");
	else if (v->agrees)
		printf(" (recomputed; the header agrees)\n");
	else
		printf(" (recomputed; DIFFERS from the header's %.17g %.17g)\n",
		    v->hr[0], v->hr[1]);
	if (st->has_range)
		printf("    mean: %.9g\n", st->mean);
	printf("    non-finite: %llu NaN, %llu +Inf, %llu -Inf\n",
	    (unsigned long long)st->nnan, (unsigned long long)st->nposinf,
	    (unsigned long long)st->nneginf);
	printf("    crc32: %08x (samples in x-fastest order, little-endian)\n",
	    (unsigned)st->crc);
	if (v->hist != NULL)
		text_histogram(v, bins);
}

static void
text_image(const img_info *m)
{
	int ch;

	printf("  image: ");
	put_str(m->img.name);
	printf("\n    size: %d x %d, %d channel%s\n", m->img.w, m->img.h,
	    m->img.nc, m->img.nc == 1 ? "" : "s");
	for (ch = 0; ch < m->img.nc; ch++)
		printf("    channel %d: min %.9g max %.9g\n", ch, m->min[ch],
		    m->max[ch]);
	printf("    non-finite: %llu NaN, %llu Inf\n",
	    (unsigned long long)m->nnan, (unsigned long long)m->ninf);
}

/* text_lines: payload text, one indented line per LF-ended line. */
static void
text_lines(const unsigned char *p, size_t n, const char *indent)
{
	size_t i = 0;

	while (i < n) {
		const unsigned char *nl = memchr(p + i, '\n', n - i);
		size_t k = nl ? (size_t)(nl - (p + i)) : n - i;

		fputs(indent, stdout);
		put_text(p + i, k);
		putchar('\n');
		i += k + 1;
	}
}

static void
text_chunk(const vx_stream *s, size_t idx, const vx_chunk *c, const opts *o)
{
	vx_err e = { 0, "" };
	content d;
	int rc;

	printf("chunk %zu: %s at %llu, length %zu, %s, %s\n", idx, c->type,
	    (unsigned long long)c->offset, c->len,
	    vx_chunk_is_critical(c->type) ? "critical" : "ancillary",
	    vx_chunk_is_known(c->type) ? "known" : "unknown");
	if (o->chunks_only)
		return;
	if (memcmp(c->type, VX_CHUNK_HISTORY, 4) == 0) {
		printf("  history:\n");
		text_lines(c->data, c->len, "    ");
		return;
	}
	if (memcmp(c->type, VX_CHUNK_NOTE, 4) == 0) {
		printf("  note:\n");
		text_lines(c->data, c->len, "    ");
		return;
	}
	if (!is_content(c->type))
		return;
	{
		const unsigned char *body;
		size_t bodylen, i;
		vx_hdr h;

		vx_hdr_init(&h);
		if ((rc = vx_payload_parse(c, &h, &body, &bodylen, &e)) != 0) {
			printf("  error: %s\n", e.msg);
			chunk_error(c, &e);
			vx_hdr_free(&h);
			return;
		}
		printf("  header:\n");
		for (i = 0; i < h.n; i++) {
			printf("    %s: ", h.key[i]);
			put_str(h.val[i]);
			putchar('\n');
		}
		vx_hdr_free(&h);
	}
	if (decode_content(s, c, o, &d, &e) != 0) {
		printf("  error: %s\n", e.msg);
		chunk_error(c, &e);
		free_content(&d);
		return;
	}
	switch (d.kind) {
	case K_VOLUME: text_volume(&d.v, o->bins); break;
	case K_IMAGE: text_image(&d.m); break;
	case K_SCENE:
		if (d.text != NULL) {
			printf("  scene:\n");
			text_lines(d.text, d.ntext, "    ");
		}
		break;
	case K_MCEL: text_mcel(&d.mi); break;
	case K_TETM: text_tetm(&d.tm); break;
	case K_TLEF: text_tlef(&d.ti); break;
	case K_IRRV: text_irrv(&d.ii); break;
	case K_SHLC: text_shlc(&d.sl); break;
	default: break;
	}
	check_range(c, &d);
	free_content(&d);
}

/* ---- JSON report ---- */

static void
json_volume(const vol_info *v, long bins)
{
	const vx_grid *g = &v->g;
	const vx_stats *st = &v->st;
	char lay[128];
	long b;

	vx_layout_string(&g->lay, lay, sizeof lay);
	printf(",\"volume\":{\"name\":");
	json_str(g->name);
	printf(",\"dims\":[%lld,%lld,%lld],\"type\":\"%s\",\"spacing\":",
	    (long long)g->dims[0], (long long)g->dims[1],
	    (long long)g->dims[2], vx_enum_str(&vx_type_enum, g->type));
	json_nums(g->spacing, 3);
	printf(",\"origin\":");
	json_nums(g->origin, 3);
	printf(",\"layout\":\"%s\",\"samples\":%llu,\"stored\":%zu,"
	    "\"body_bytes\":%zu,\"range\":", lay,
	    (unsigned long long)st->count, g->nsample, v->bodylen);
	if (st->has_range) {
		double r[2] = { st->vmin, st->vmax };

		json_nums(r, 2);
	} else
		fputs("null", stdout);
	printf(",\"header_range\":");
	if (v->hdr_range)
		json_nums(v->hr, 2);
	else
		fputs("null", stdout);
	printf(",\"range_agrees\":%s,\"mean\":", v->agrees ? "true" : "false");
	if (st->has_range)
		json_num(st->mean);
	else
		fputs("null", stdout);
	printf(",\"nan\":%llu,\"posinf\":%llu,\"neginf\":%llu,"
	    "\"crc32\":\"%08x\"", (unsigned long long)st->nnan,
	    (unsigned long long)st->nposinf, (unsigned long long)st->nneginf,
	    (unsigned)st->crc);
	if (v->hist != NULL) {
		printf(",\"histogram\":{\"bins\":%ld,\"lo\":", bins);
		json_num(st->vmin);
		printf(",\"hi\":");
		json_num(st->vmax);
		printf(",\"counts\":[");
		for (b = 0; b < bins; b++)
			printf("%s%llu", b ? "," : "",
			    (unsigned long long)v->hist[b]);
		printf("]}");
	}
	putchar('}');
}

static void
json_image(const img_info *m)
{
	printf(",\"image\":{\"name\":");
	json_str(m->img.name);
	printf(",\"width\":%d,\"height\":%d,\"channels\":%d,\"min\":",
	    m->img.w, m->img.h, m->img.nc);
	json_nums(m->min, m->img.nc);
	printf(",\"max\":");
	json_nums(m->max, m->img.nc);
	printf(",\"nan\":%llu,\"inf\":%llu}", (unsigned long long)m->nnan,
	    (unsigned long long)m->ninf);
}

/* json_lines: LF-ended lines as a JSON array of strings. */
static void
json_lines(const unsigned char *p, size_t n)
{
	size_t i = 0;

	putchar('[');
	while (i < n) {
		const unsigned char *nl = memchr(p + i, '\n', n - i);
		size_t k = nl ? (size_t)(nl - (p + i)) : n - i;

		if (i)
			putchar(',');
		json_text(p + i, k);
		i += k + 1;
	}
	putchar(']');
}

static void
json_error(const vx_chunk *c, const vx_err *e)
{
	printf(",\"error\":");
	json_str(e->msg);
	chunk_error(c, e);
}

static void
json_chunk(const vx_stream *s, size_t idx, const vx_chunk *c, const opts *o)
{
	vx_err e = { 0, "" };
	content d;

	printf("%s{\"index\":%zu,\"type\":", idx ? "," : "", idx);
	json_text((const unsigned char *)c->type, 4);
	printf(",\"offset\":%llu,\"length\":%zu,\"critical\":%s,\"known\":%s",
	    (unsigned long long)c->offset, c->len,
	    vx_chunk_is_critical(c->type) ? "true" : "false",
	    vx_chunk_is_known(c->type) ? "true" : "false");
	if (o->chunks_only)
		goto done;
	if (memcmp(c->type, VX_CHUNK_HISTORY, 4) == 0) {
		printf(",\"history\":");
		json_lines(c->data, c->len);
		goto done;
	}
	if (memcmp(c->type, VX_CHUNK_NOTE, 4) == 0) {
		printf(",\"text\":");
		json_text(c->data, c->len);
		goto done;
	}
	if (!is_content(c->type))
		goto done;
	{
		const unsigned char *body;
		size_t bodylen, i;
		vx_hdr h;

		vx_hdr_init(&h);
		if (vx_payload_parse(c, &h, &body, &bodylen, &e) != 0) {
			vx_hdr_free(&h);
			json_error(c, &e);
			goto done;
		}
		printf(",\"header\":{");
		for (i = 0; i < h.n; i++) {
			if (i)
				putchar(',');
			json_str(h.key[i]);
			putchar(':');
			json_str(h.val[i]);
		}
		putchar('}');
		vx_hdr_free(&h);
	}
	if (decode_content(s, c, o, &d, &e) != 0) {
		json_error(c, &e);
		free_content(&d);
		goto done;
	}
	switch (d.kind) {
	case K_VOLUME: json_volume(&d.v, o->bins); break;
	case K_IMAGE: json_image(&d.m); break;
	case K_SCENE:
		if (d.text != NULL) {
			printf(",\"text\":");
			json_text(d.text, d.ntext);
		}
		break;
	case K_MCEL: json_mcel(&d.mi); break;
	case K_TETM: json_tetm(&d.tm); break;
	case K_TLEF: json_tlef(&d.ti); break;
	case K_IRRV: json_irrv(&d.ii); break;
	case K_SHLC: json_shlc(&d.sl); break;
	default: break;
	}
	check_range(c, &d);
	free_content(&d);
done:
	putchar('}');
}

/* ---- transfer functions (--transfer) ---- */

static void
text_list(const char *name, const vx_tf_list *l)
{
	if (l->n == 0)
		return;
	printf("%s: %d point%s over [%.17g, %.17g]\n", name, l->n,
	    l->n == 1 ? "" : "s", l->x[0], l->x[l->n - 1]);
	for (int i = 0; i < l->n; i++) {
		printf("  %.17g", l->x[i]);
		for (int c = 0; c < l->dim; c++)
			printf(" %.17g", l->y[l->dim * i + c]);
		printf("\n");
	}
}

static void
json_list(const char *name, const vx_tf_list *l)
{
	printf(",\"%s\":", name);
	if (l->n == 0) {
		printf("null");
		return;
	}
	printf("[");
	for (int i = 0; i < l->n; i++) {
		printf("%s[", i ? "," : "");
		json_num(l->x[i]);
		for (int c = 0; c < l->dim; c++) {
			printf(",");
			json_num(l->y[l->dim * i + c]);
		}
		printf("]");
	}
	printf("]");
}

/* transfer: read in as a transfer function and print it: each list's
 * points, the table's size, ranges and the range of each channel. */
static void
transfer(const opts *o)
{
	double lo[4] = { 1, 1, 1, 1 }, hi[4] = { 0, 0, 0, 0 };
	const char *name = strcmp(o->in, "-") ? o->in : "<stdin>";
	vx_err e;
	vx_tf tf;

	vx_err_clear(&e);
	if (vx_tf_import(o->in, (vx_tf_format)o->transfer, &tf, &e) != 0)
		tool_fail_err(&e);
	if (tf.has_table)
		for (size_t i = 0; i < (size_t)tf.size[0] * (size_t)tf.size[1];
		    i++)
			for (int c = 0; c < 4; c++) {
				lo[c] = fmin(lo[c], tf.rgba[4 * i + c]);
				hi[c] = fmax(hi[c], tf.rgba[4 * i + c]);
			}
	if (o->json) {
		printf("{\"input\":");
		json_str(name);
		printf(",\"transfer\":{\"ref_step\":");
		json_num(tf.ref_step);
		json_list("color", &tf.color);
		json_list("opacity", &tf.opacity);
		json_list("gradient", &tf.gradient);
		printf(",\"table\":");
		if (tf.has_table) {
			printf("{\"size\":[%d,%d],\"value_range\":", tf.size[0],
			    tf.size[1]);
			json_nums(tf.vrange, 2);
			printf(",\"gradient_range\":");
			json_nums(tf.grange, 2);
			printf(",\"min\":");
			json_nums(lo, 4);
			printf(",\"max\":");
			json_nums(hi, 4);
			printf("}");
		} else
			printf("null");
		printf("}}\n");
	} else {
		printf("transfer: ");
		put_str(name);
		printf("\nref_step: %.17g%s\n", tf.ref_step, tf.ref_step == 0 ?
		    " (one voxel)" : "");
		text_list("color", &tf.color);
		text_list("opacity", &tf.opacity);
		text_list("gradient", &tf.gradient);
		if (tf.has_table)
			printf("table: %d x %d cells over value [%.17g, %.17g] and "
			    "gradient magnitude [%.17g, %.17g]; RGBA from "
			    "(%g, %g, %g, %g) to (%g, %g, %g, %g)\n", tf.size[0],
			    tf.size[1], tf.vrange[0], tf.vrange[1], tf.grange[0],
			    tf.grange[1], lo[0], lo[1], lo[2], lo[3], hi[0], hi[1],
			    hi[2], hi[3]);
	}
	vx_tf_free(&tf);
	exit(tool_finish());
}

int
main(int argc, char **argv)
{
	vx_stream s;
	uint64_t total = VX_SIGNATURE_LEN + 16;   /* signature, end chunk */
	size_t i;
	opts o;

	tool_init("vinfo", argc, argv);
	parse_args(&o, argc, argv);
	if (o.transfer != VX_TF_FORMAT_UNKNOWN)
		transfer(&o);
	vx_stream_init(&s);
	tool_read_stream(&s, o.in);
	for (i = 0; i < s.n; i++)
		total += 16 + (uint64_t)s.chunk[i].len;
	if (o.json) {
		printf("{\"input\":");
		json_str(strcmp(o.in, "-") ? o.in : "<stdin>");
		printf(",\"bytes\":%llu,\"chunks\":[", (unsigned long long)total);
		for (i = 0; i < s.n; i++)
			json_chunk(&s, i, &s.chunk[i], &o);
		printf("]}\n");
	} else {
		printf("stream: ");
		put_str(strcmp(o.in, "-") ? o.in : "<stdin>");
		printf(": %llu bytes, %zu chunk%s and the end chunk\n",
		    (unsigned long long)total, s.n, s.n == 1 ? "" : "s");
		for (i = 0; i < s.n; i++)
			text_chunk(&s, i, &s.chunk[i], &o);
	}
	vx_stream_free(&s);
	tool_finish();
	if (nerrors > 0)
		exit(first_code);
	return 0;
}
