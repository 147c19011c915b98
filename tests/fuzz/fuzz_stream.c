/* fuzz_stream.c: libFuzzer target for the stream reader and every chunk
 * decoder: vx_stream_read_mem, then VOLM (vx_grid_from_chunk), IMAG
 * (vx_image_from_chunk), MCEL (vx_macro_from_chunk, and against its volume)
 * TETM (vx_tetmesh_from_chunk, and its TLEF leaf grid, one ray through it),
 * TLEF (vx_tetleaf_from_chunk), SCNE (vx_scene_from_chunk), IRRV and SHTV
 * (vx_irr_from_chunk: the lookups a renderer makes, the chunk written back
 * and read back equal, merged with that copy unchanged, made final f16
 * and read back) and SHLC
 * (vx_shlight_from_chunk, written back and read back equal); a stream
 * that reads is written back and must read back to the same chunks. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "fuzz.h"
#include "vx_irrvol.h"
#include "vx_macro.h"
#include "vx_macroio.h"
#include "vx_scene.h"
#include "vx_shlight.h"
#include "vx_tetimport.h"
#include "vx_tetleaf.h"

static double
touch_macro(const vx_macro *m)
{
	double sum = 0;

	if (m->nlev < 0 || m->nlev > VX_MACRO_MAXLEV)
		fuzz_fail("macro: nlev out of range");
	for (int l = m->explicit_leaves ? 0 : 1; l <= m->nlev; l++) {
		size_t n = 1;

		for (int a = 0; a < 3; a++) {
			if (m->dims[l][a] < 0)
				fuzz_fail("macro: negative dims");
			n *= (size_t)m->dims[l][a];
		}
		for (size_t i = 0; i < 2 * n; i++)
			sum += m->mm[l][i] == m->mm[l][i];
	}
	return sum + (m->root[0] <= m->root[1]);
}

/* same_f64: equal bits, or both NaN (a NaN's sign and payload need not
 * survive printing) */
static int
same_f64(double a, double b)
{
	return (isnan(a) && isnan(b)) || memcmp(&a, &b, sizeof a) == 0;
}

/* same_irr: the fields a chunk carries, and the texels */
static int
same_irr(const vx_irrvol *a, const vx_irrvol *b)
{
	size_t nt = a->nslot * VX_IRR_BRICK3, nb;

	if (strcmp(a->volume, b->volume) != 0 || a->vcrc != b->vcrc ||
	    memcmp(a->vdims, b->vdims, sizeof a->vdims) != 0 ||
	    memcmp(a->dims, b->dims, sizeof a->dims) != 0 ||
	    memcmp(a->bdims, b->bdims, sizeof a->bdims) != 0 ||
	    !same_f64(a->scale, b->scale) || a->nslot != b->nslot ||
	    a->store != b->store || a->sh_order != b->sh_order ||
	    a->channels != b->channels || a->ncomp != b->ncomp ||
	    a->fixed != b->fixed || a->first != b->first ||
	    strcmp(a->key, b->key) != 0 ||
	    strcmp(a->settings, b->settings) != 0 ||
	    !same_f64(a->offset, b->offset) || a->seed != b->seed ||
	    a->high != b->high || a->samples != b->samples)
		return 0;
	nb = (size_t)a->bdims[0] * (size_t)a->bdims[1] * (size_t)a->bdims[2];
	if (memcmp(a->slot, b->slot, nb * sizeof *a->slot) != 0 ||
	    memcmp(a->flags, b->flags, nt * sizeof *a->flags) != 0 ||
	    memcmp(a->mean, b->mean, nt * (size_t)a->ncomp *
	    sizeof *a->mean) != 0)
		return 0;
	return a->store != VX_IRR_ACCUM || memcmp(a->acc, b->acc, nt *
	    vx_irr_acc_bytes(a->ncomp)) == 0;
}

static void
count_reach(void *ctx, int64_t i, int64_t j, int64_t k)
{
	(void)i;
	(void)j;
	(void)k;
	++*(int *)ctx;
}

/* touch_irr: what a renderer reads of a decoded IRRV or SHTV (every stored
 * texel, lookups and weights in every mode at points in and around the
 * lattice), then the chunk written back must read back equal, and a merge
 * with that copy (the same samples) must change nothing. */
static double
touch_irr(vx_irrvol *v, const vx_grid *g)
{
	size_t nb, nt, nused = 0;
	double sum = 0;
	int nc = v->ncomp;
	vx_err e;

	if (v->store < 0 || v->store >= VX_IRR_STORE_LAST)
		fuzz_fail("irr: store out of range");
	if (v->sh_order == 0 ? nc != 3 : (v->sh_order > 16 ||
	    (v->channels != 1 && v->channels != 3) ||
	    nc != v->channels * v->sh_order * v->sh_order))
		fuzz_fail("irr: order, channels and components disagree");
	for (int a = 0; a < 3; a++)
		if (v->dims[a] < 1 || v->dims[a] > VX_GRID_MAX_DIM ||
		    v->vdims[a] < 1 || !(v->step[a] > 0) ||
		    v->bdims[a] != (v->dims[a] + 7) / 8)
			fuzz_fail("irr: bad lattice");
	nb = (size_t)v->bdims[0] * (size_t)v->bdims[1] * (size_t)v->bdims[2];
	for (size_t b = 0; b < nb; b++) {
		if (v->slot[b] > v->nslot)
			fuzz_fail("irr: slot beyond the stored bricks");
		nused += v->slot[b] != 0;
	}
	if (nused != v->nslot || v->nslot > v->cap)
		fuzz_fail("irr: slots disagree with nslot");
	nt = v->nslot * VX_IRR_BRICK3;
	for (size_t t = 0; t < nt; t++) {
		int u = vx_irr_usable(v, (int64_t)t);

		if (u && v->store == VX_IRR_ACCUM &&
		    vx_irr_accp(v, (int64_t)t)->count == 0)
			fuzz_fail("irr: an accum texel without samples is usable");
		for (int c = 0; c < nc; c++) {
			float m = v->mean[(size_t)nc * t + (size_t)c];

			if (!isfinite(m) || (v->sh_order == 0 && m < 0))
				fuzz_fail("irr: a mean not finite (or negative)");
			sum += u * m;
		}
	}
	if (vx_irr_bytes(v) < nt * vx_irr_texel_memory(v->store, nc) ||
	    vx_irr_texel_bytes(v->store, nc) == 0)
		fuzz_fail("irr: sizes");
	/* lookups: the corners, the middle and points past the edges */
	for (int pt = 0; pt < 12; pt++) {
		static const double fr[12][3] = {
			{ 0, 0, 0 }, { 1, 1, 1 }, { .5, .5, .5 }, { 1, 0, 0 },
			{ .25, .75, .5 }, { .3, .1, .9 }, { -.2, 1.3, .5 },
			{ 2, -1, .7 }, { .49, .51, .5 }, { .125, .125, .125 },
			{ .9, .9, .1 }, { NAN, .5, INFINITY } };
		double p[3];

		for (int a = 0; a < 3; a++)
			p[a] = fr[pt][a] * (double)(v->vdims[a] - 1);
		for (int m = 0; m < VX_INTERP_LAST; m++) {
			double out[VX_IRR_MAX_COMP], w[64], ws = 0;
			int64_t idx[64];
			int n, got, nreach = 0;

			n = vx_irr_weights(v, p, (vx_interp)m, g, 0.5, idx, w);
			if (n < 0 || n > 64)
				fuzz_fail("irr: weights count");
			for (int k = 0; k < n; k++) {
				if (idx[k] < 0 || (size_t)idx[k] >= nt ||
				    !vx_irr_usable(v, idx[k]) || !(w[k] >= 0))
					fuzz_fail("irr: a weight or texel is bad");
				ws += w[k];
			}
			if (n > 0 && fabs(ws - 1) > 1e-9)
				fuzz_fail("irr: weights do not sum to 1");
			got = vx_irr_lookup(v, p, (vx_interp)m, g, 0.5, out);
			if (got != (n > 0))
				fuzz_fail("irr: lookup and weights disagree");
			for (int c = 0; c < nc; c++) {
				if (!isfinite(out[c]))
					fuzz_fail("irr: lookup not finite");
				sum += out[c];
			}
			vx_irr_reach(v, p, (vx_interp)m, count_reach,
			    &nreach);
			if (nreach > 64)
				fuzz_fail("irr: reach beyond 64 texels");
		}
	}
	/* written back, read back equal */
	vx_err_clear(&e);
	{
		vx_chunk c;
		vx_irrvol w;

		if (vx_irr_to_chunk(v, 0, &c, &e) != 0)
			fuzz_fail("irr: a volume that was read cannot be written");
		if (vx_irr_from_chunk(&w, &c, &e) != 0) {
			fprintf(stderr, "%s\n", e.msg);
			fuzz_fail("irr: a written volume does not read back");
		}
		vx_chunk_free(&c);
		if (!same_irr(v, &w))
			fuzz_fail("irr: chunk round trip changed the volume");
		/* a merge with the same samples keeps them once */
		if (v->store == VX_IRR_ACCUM) {
			if (vx_irr_merge(&w, v, &e) != 0) {
				fprintf(stderr, "%s\n", e.msg);
				fuzz_fail("irr: a merge with itself failed");
			}
			if (!same_irr(v, &w))
				fuzz_fail("irr: a merge with itself changed it");
			/* made final (as bake-irr --half), it reads back */
			if (vx_irr_finalize(&w, VX_IRR_F16, &e) != 0)
				fuzz_fail("irr: finalize failed");
			if (vx_irr_to_chunk(&w, 0, &c, &e) != 0)
				fuzz_fail("irr: a final volume cannot be written");
			{
				vx_irrvol x;

				if (vx_irr_from_chunk(&x, &c, &e) != 0) {
					fprintf(stderr, "%s\n", e.msg);
					fuzz_fail("irr: a final volume does not "
					    "read back");
				}
				x.fixed = w.fixed;   /* kept by accum only */
				/* f16 records keep the low 16 flag bits (the
				 * defined ones, 0 to 4, among them) */
				for (size_t t = 0; t < w.nslot * VX_IRR_BRICK3;
				    t++)
					w.flags[t] &= 0xffff;
				if (!same_irr(&w, &x))
					fuzz_fail("irr: final round trip changed "
					    "the volume");
				vx_irr_free(&x);
			}
			vx_chunk_free(&c);
		}
		vx_irr_free(&w);
	}
	return sum;
}

/* touch_shlight: an SHLC written back reads back equal */
static double
touch_shlight(const vx_shlight *l)
{
	size_t nc = (size_t)l->order * (size_t)l->order * 3;
	double sum = 0;
	vx_shlight b;
	vx_chunk c;
	vx_err e;

	if (l->order < 1 || l->order > VX_SHLIGHT_MAX_ORDER)
		fuzz_fail("shlc: order out of range");
	for (size_t i = 0; i < nc; i++) {
		if (!isfinite(l->c[i]))
			fuzz_fail("shlc: a coefficient not finite");
		sum += l->c[i];
	}
	vx_err_clear(&e);
	if (vx_shlight_to_chunk(l, &c, &e) != 0)
		fuzz_fail("shlc: a lighting that was read cannot be written");
	if (vx_shlight_from_chunk(&b, &c, &e) != 0)
		fuzz_fail("shlc: a written lighting does not read back");
	vx_chunk_free(&c);
	if (b.order != l->order || b.phase != l->phase ||
	    b.has_hash != l->has_hash ||
	    (l->has_hash && b.env_hash != l->env_hash) ||
	    memcmp(b.rot, l->rot, sizeof b.rot) != 0 ||
	    memcmp(b.c, l->c, nc * sizeof *b.c) != 0)
		fuzz_fail("shlc: chunk round trip changed the lighting");
	return sum;
}

/* roundtrip: write s to memory, read it back, compare chunk by chunk. */
static void
roundtrip(const vx_stream *s)
{
	char *buf = NULL;
	size_t n = 0;
	vx_stream r;
	vx_err e;
	FILE *f;
	int rc;

	vx_err_clear(&e);
	if ((f = open_memstream(&buf, &n)) == NULL)
		return;
	rc = vx_stream_write(s, f, &e);
	fclose(f);
	if (rc != 0)
		fuzz_fail("a stream that was read cannot be written");
	vx_stream_init(&r);
	if (vx_stream_read_mem(&r, buf, n, &e) != 0)
		fuzz_fail("a written stream does not read back");
	if (r.n != s->n)
		fuzz_fail("roundtrip changed the chunk count");
	for (size_t i = 0; i < r.n; i++)
		if (strcmp(r.chunk[i].type, s->chunk[i].type) != 0 ||
		    r.chunk[i].len != s->chunk[i].len ||
		    (r.chunk[i].len &&
		    memcmp(r.chunk[i].data, s->chunk[i].data, r.chunk[i].len)))
			fuzz_fail("roundtrip changed a chunk");
	vx_stream_free(&r);
	free(buf);
}

size_t LLVMFuzzerMutate(uint8_t *data, size_t size, size_t max);
size_t LLVMFuzzerCustomMutator(uint8_t *data, size_t size, size_t max,
    unsigned int seed);

/* The libFuzzer mutation, then (seven times in eight: the rest keep a bad
 * CRC for the reader to find) every chunk framed by the signature and the
 * lengths gets the CRC of its type and payload. */
size_t
LLVMFuzzerCustomMutator(uint8_t *data, size_t size, size_t max,
    unsigned int seed)
{
	size_t off = 8;

	size = LLVMFuzzerMutate(data, size, max);
	if (seed % 8 == 0)
		return size;
	while (off + 12 <= size) {
		uint64_t n = 0;
		uLong crc;

		for (int b = 0; b < 8; b++)
			n |= (uint64_t)data[off + 4 + b] << (8 * b);
		if (n > size - off - 12 || size - off - 12 - n < 4)
			break;
		crc = crc32(0L, Z_NULL, 0);
		crc = crc32(crc, data + off, 4);
		crc = crc32(crc, data + off + 12, (uInt)n);
		for (int b = 0; b < 4; b++)
			data[off + 12 + n + b] = (uint8_t)(crc >> (8 * b));
		off += 16 + n;
	}
	return size;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static vx_grid isogrid;
	volatile double sink = 0;
	vx_stream s;
	vx_err e;
	size_t hl;
	int rc;

	vx_err_clear(&e);
	/* the volume a nearest-iso lookup reads the texels' values from
	 * (points beyond it are clamped): a ramp */
	if (isogrid.data == NULL) {
		int64_t gd[3] = { 3, 3, 3 };

		if (vx_grid_alloc(&isogrid, gd, VX_F32, NULL, &e) != 0)
			fuzz_fail("cannot make the iso grid");
		for (int64_t z = 0; z < 3; z++)
			for (int64_t y = 0; y < 3; y++)
				for (int64_t x = 0; x < 3; x++)
					vx_grid_set(&isogrid, x, y, z,
					    (double)(x + y + z) / 6);
	}
	vx_stream_init(&s);
	rc = vx_stream_read_mem(&s, data, size, &e);
	fuzz_err_check(rc, &e);
	if (rc != 0) {
		vx_stream_free(&s);
		return 0;
	}
	roundtrip(&s);
	if (vx_stream_history(&s, &hl) != NULL)
		sink += (double)hl;
	for (size_t i = 0; i < s.n; i++) {
		const vx_chunk *c = &s.chunk[i];

		if (!vx_chunk_type_valid(c->type))
			fuzz_fail("reader kept an invalid chunk type");
		vx_err_clear(&e);
		if (strcmp(c->type, VX_CHUNK_VOLUME) == 0) {
			vx_grid g;
			vx_macro m;
			int status;
			long idx;

			rc = vx_grid_from_chunk(&g, c, &e);
			fuzz_err_check(rc, &e);
			if (rc == 0) {
				vx_grid gv;
				vx_err ev = { 0, "" };

				sink += fuzz_grid_touch(&g);
				/* the samples in place: the same grid, or the
				 * same error */
				if (vx_grid_view_chunk(&gv, c, &ev) != 0)
					fuzz_fail("view refused what the copy took");
				sink += fuzz_grid_touch(&gv);
				if (gv.nsample != g.nsample || memcmp(gv.data,
				    g.data, g.nsample * vx_type_size(g.type)) != 0)
					fuzz_fail("view and copy differ");
				vx_grid_free(&gv);
				vx_err_clear(&e);
				rc = vx_macro_from_stream(&m, &s, &g, (long)i,
				    &status, &idx, &e);
				fuzz_err_check(rc, &e);
				/* m holds memory only when loaded */
				if (rc == 0 && status == VX_MACRO_LOADED) {
					sink += touch_macro(&m);
					vx_macro_free(&m);
				}
				vx_grid_free(&g);
			} else {
				vx_grid gv;
				vx_err ev = { 0, "" };

				if (vx_grid_view_chunk(&gv, c, &ev) == 0)
					fuzz_fail("view took what the copy refused");
			}
		} else if (strcmp(c->type, VX_CHUNK_IMAGE) == 0) {
			vx_image img;

			rc = vx_image_from_chunk(&img, c, &e);
			fuzz_err_check(rc, &e);
			if (rc == 0) {
				sink += fuzz_image_touch(&img);
				vx_image_free(&img);
			}
		} else if (strcmp(c->type, VX_CHUNK_MACRO) == 0) {
			vx_macro m;

			rc = vx_macro_from_chunk(&m, c, &e);
			fuzz_err_check(rc, &e);
			if (rc == 0) {
				sink += touch_macro(&m);
				vx_macro_free(&m);
			}
		} else if (strcmp(c->type, VX_CHUNK_SCENE) == 0) {
			vx_scene sc;

			rc = vx_scene_from_chunk(&sc, c, &e);
			fuzz_err_check(rc, &e);
			if (rc == 0)
				sink += sc.nsurface + sc.nlight;
		} else if (strcmp(c->type, VX_CHUNK_TETMESH) == 0) {
			vx_tetmesh m;

			rc = vx_tetmesh_from_chunk(&m, c, &e);
			fuzz_err_check(rc, &e);
			if (rc == 0) {
				vx_tetleaf lg;
				int status;
				long idx;

				sink += fuzz_tetmesh_touch(&m, 0);
				/* its leaf grid, when the stream has one that
				 * matches: trace one ray through it */
				vx_err_clear(&e);
				rc = vx_tetleaf_from_stream(&lg, &s, &m, &status,
				    &idx, &e);
				fuzz_err_check(rc, &e);
				if (rc == 0 && status == VX_MACRO_LOADED) {
					double o[3], d[3] = { 0.3, 0.5, 0.8 };
					double iso = (m.vmin + m.vmax) / 2;
					vx_tethit h;
					for (int a = 0; a < 3; a++)
						o[a] = m.bmin[a] - d[a];
					sink += vx_tetleaf_nearest(&lg, &m, o, d, &iso,
					    1, 0, INFINITY, &h, NULL);
					vx_tetleaf_free(&lg);
				}
				vx_tetmesh_free(&m);
			}
		} else if (strcmp(c->type, VX_CHUNK_IRRAD) == 0 ||
		    strcmp(c->type, VX_CHUNK_SHXFER) == 0) {
			vx_irrvol v;

			rc = vx_irr_from_chunk(&v, c, &e);
			fuzz_err_check(rc, &e);
			if (rc == 0) {
				if ((v.sh_order > 0) !=
				    (strcmp(c->type, VX_CHUNK_SHXFER) == 0))
					fuzz_fail("irr: chunk type and order disagree");
				sink += touch_irr(&v, &isogrid);
				vx_irr_free(&v);
			}
		} else if (strcmp(c->type, VX_CHUNK_SHLIGHT) == 0) {
			vx_shlight l;

			rc = vx_shlight_from_chunk(&l, c, &e);
			fuzz_err_check(rc, &e);
			if (rc == 0)
				sink += touch_shlight(&l);
		} else if (strcmp(c->type, VX_CHUNK_TETLEAF) == 0) {
			vx_tetleaf lg;
			vx_tetleaf_ident id;

			rc = vx_tetleaf_from_chunk(&lg, &id, c, &e);
			fuzz_err_check(rc, &e);
			if (rc == 0) {
				/* every list entry and every stored range */
				for (size_t l = 0; l < lg.nleaf; l++)
					for (uint32_t k = lg.off[l]; k < lg.off[l + 1];
					    k++)
						if (lg.idx[k] >= id.ntet)
							fuzz_fail("tlef: index out of range");
				sink += touch_macro(&lg.mc);
				vx_tetleaf_free(&lg);
			}
		}
	}
	vx_stream_free(&s);
	(void)sink;
	return 0;
}
