/* raycast.c: the ray-cast isosurface renderer (see vx_raycast.h): a
 * primary ray per pixel sample, its hits composited front to back.  The
 * surfaces (source, hit records, shading and shadows) are vx_surface.h's,
 * the same for a volume and a tet mesh; the primary rays' bins are
 * vx_bins.h's; the tiles run on vx_par.h's threads. */
#include "vx_raycast.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vx_bins.h"
#include "vx_camera.h"
#include "vx_cellmask.h"
#include "vx_macrobox.h"
#include "vx_par.h"
#include "vx_surface.h"

/* What every thread reads. */
typedef struct rc_shared {
	const vx_scene *s;
	const vx_plan *p;
	const vx_raycast_opts *o;
	vx_surfaces sf;               /* the source (a volume, or a mesh), the
	                                 drawn isovalues, their shading */
	/* the primary rays' bins (vx_bins.h); off NULL: none */
	vx_bins bins;
} rc_shared;

#define BIN VX_BIN

#define EM_SLOTS 4   /* entry masks kept: a tile's bins (16 x 16 pixels) */

/* What each thread owns: on cache lines of its own (the counters are
 * written per cell; neighbours sharing a line would slow both threads). */
typedef struct rc_local {
	_Alignas(64) vx_surf_stats ss;   /* traces, shadow rays, shading */
	uint64_t primary, covered, binned;
	uint64_t first_pass;          /* pixels drawn by the sparse pass */
	uint64_t cyc_total, cyc_shade;
	/* the entry masks of the bins last walked (bin_em): em[s][p], bit
	 * k: the bin's k-th entry holds pixel p; em_bin[s]: the bin, -1
	 * none; em_ok[s]: 0 for a bin of more than 64 entries */
	int64_t em_bin[EM_SLOTS];
	int em_ok[EM_SLOTS], em_next;
	uint64_t em[EM_SLOTS][BIN * BIN];
} rc_local;

void
vx_raycast_opts_init(vx_raycast_opts *o)
{
	memset(o, 0, sizeof *o);
	o->solver = VX_CELL_EXACT;
	o->aa = 1;
	o->tile = 16;
	o->irr_interp = VX_INTERP_TRILINEAR;
	o->shadow_offset = 1e-3;
}

typedef struct layer_ctx {
	const rc_shared *S;
	rc_local *L;
	const double *ow, *dw;
	double C[3], A;
	int first;
	double depth, n[3];
} layer_ctx;

/* composite: shade surface point h and put it under the layers so far;
 * c0 is when the work on this hit began (timing). */
static int
composite(layer_ctx *x, const vx_hit *h, uint64_t c0)
{
	const rc_shared *S = x->S;
	double a = S->sf.opacity[h->iso], col[3];
	int i;

	vx_surf_shade(&S->sf, h, x->dw, col, &x->L->ss);
	if (S->o->timing)
		x->L->cyc_shade += vx_cycles() - c0;
	if (x->first) {
		x->first = 0;
		x->depth = h->t;
		memcpy(x->n, h->n, sizeof x->n);
	}
	for (i = 0; i < 3; i++)
		x->C[i] += (1 - x->A) * a * col[i];
	x->A += (1 - x->A) * a;
	return x->A >= 0.9999;
}

/* layer: a volume hit, as a surface point. */
static int
layer(void *ctx, const vx_iso_hit *h)
{
	layer_ctx *x = ctx;
	const rc_shared *S = x->S;
	uint64_t c0 = S->o->timing ? vx_cycles() : 0;
	vx_hit sp;

	vx_surf_hit_volume(&S->sf, h, x->dw, &sp);
	return composite(x, &sp, c0);
}

/* tet_layer: a mesh hit, as a surface point: the tet's constant gradient
 * turned to face the viewer. */
static int
tet_layer(void *ctx, const vx_tethit *h)
{
	layer_ctx *x = ctx;
	const rc_shared *S = x->S;
	uint64_t c0 = S->o->timing ? vx_cycles() : 0;
	vx_hit sp;

	vx_surf_hit_mesh(h, x->ow, x->dw, &sp);
	return composite(x, &sp, c0);
}

/* em_forget: L keeps no entry masks */
static void
em_forget(rc_local *L)
{
	for (int s = 0; s < EM_SLOTS; s++)
		L->em_bin[s] = -1;
}

/* bin_em: L's entry masks of bin (its list at t, n entries), made if not
 * kept; NULL for more than 64 entries */
static const uint64_t *
bin_em(const rc_shared *S, rc_local *L, int64_t bin, int64_t t, int64_t n)
{
	int s;

	for (s = 0; s < EM_SLOTS; s++)
		if (L->em_bin[s] == bin)
			return L->em_ok[s] ? L->em[s] : NULL;
	s = L->em_next;
	L->em_next = (s + 1) % EM_SLOTS;
	L->em_bin[s] = bin;
	L->em_ok[s] = n <= 64;
	if (!L->em_ok[s])
		return NULL;
	vx_bins_entry_masks(S->bins.mk + t, n, L->em[s]);
	return L->em[s];
}

/* pixel: one camera sample; returns 1 if it hit a surface. */
static int
pixel(const rc_shared *S, rc_local *L, double px, double py, double out[4],
    double *depth, double n[3])
{
	const vx_surfaces *sf = &S->sf;
	double ow[3], dw[3], oi[3], di[3];
	int64_t bin = 0;
	layer_ctx x;

	memset(&x, 0, sizeof x);
	x.S = S;
	x.L = L;
	x.ow = ow;
	x.dw = dw;
	x.first = 1;
	x.depth = INFINITY;
	L->primary++;
	if (S->bins.off != NULL && !vx_bins_of(&S->bins, px, py, &bin)) {
		/* no box's footprint holds the pixel: the ray would enter
		 * none (vx_macro_boxes_entry), nothing to walk or even set
		 * up */
		L->binned++;
		goto out;
	}
	vx_camera_ray(&S->s->camera, px, py, ow, dw);
	if (sf->mesh != NULL)
		vx_tetleaf_trace(sf->lg, sf->mesh, ow, dw, sf->isod, sf->niso, 0,
		    INFINITY, tet_layer, &x, &L->ss.tet);
	else {
		vx_world_to_index(sf->g, ow, oi);
		vx_world_to_index_dir(sf->g, dw, di);
		if (S->bins.off != NULL) {
			/* the walk goes through the boxes the ray enters, one
			 * after the other, and nowhere when it enters none:
			 * the same leaves (vx_macro_traverse_boxes) */
			int64_t t = S->bins.off[bin];
			int bx = (int)(bin % S->bins.nbx);
			int by = (int)(bin / S->bins.nbx);
			uint64_t walked = L->ss.iso.trav.rays;
			/* the entries' pixel bits and lbs, read in order */
			int pb = ((int)py - by * BIN) * BIN + (int)px - bx * BIN;
			const uint64_t *em = bin_em(S, L, bin, t,
			    S->bins.off[bin + 1] - t);
			/* the entries that hold the pixel, as a mask (lists
			 * of at most 64) */
			const vx_boxpick pk = { { (int32_t)px, (int32_t)py },
			    S->bins.lb + t, S->bins.mk + t, pb, em != NULL,
			    em != NULL ? em[pb] : 0 };

			vx_iso_trace_boxes(&sf->tr, oi, di, S->bins.box,
			    S->bins.list + t, (size_t)(S->bins.off[bin + 1] - t),
			    &pk, sf->isod, sf->niso, layer, &x, &L->ss.iso);
			L->binned += L->ss.iso.trav.rays == walked;
		} else
			vx_iso_trace(&sf->tr, oi, di, 0, INFINITY, sf->isod,
			    sf->niso, layer, &x, &L->ss.iso);
	}
out:
	for (int i = 0; i < 3; i++)
		out[i] = x.C[i];          /* premultiplied (formats/image.md) */
	out[3] = x.A;
	*depth = x.depth;
	memcpy(n, x.n, sizeof x.n);
	return !x.first;
}

/* empty_run: pixels x0..x1-1 of row y as image_pixel leaves a pixel no
 * box's footprint covers (one sample): transparent black, depth +Inf,
 * normal 0 */
static void
empty_run(rc_local *L, int x0, int x1, int y, vx_image *color,
    vx_image *depth, vx_image *normal)
{
	int n = x1 - x0;

	L->primary += (uint64_t)n;
	L->binned += (uint64_t)n;
	memset(vx_image_pixel(color, x0, y), 0, (size_t)n * 4 * sizeof(float));
	if (depth != NULL) {
		float *d = vx_image_pixel(depth, x0, y);

		for (int i = 0; i < n; i++)
			d[i] = INFINITY;
	}
	if (normal != NULL)
		memset(vx_image_pixel(normal, x0, y), 0,
		    (size_t)n * 3 * sizeof(float));
}

/* image_pixel: pixel (x, y) of the images, from its aa x aa samples */
static void
image_pixel(const rc_shared *S, rc_local *L, int x, int y, int aa,
    vx_image *color, vx_image *depth, vx_image *normal)
{
	double acc[4] = { 0, 0, 0, 0 }, px[4], dep, n[3];
	double best = INFINITY, bn[3] = { 0, 0, 0 };
	int hit = 0;

	/* (runs of pixels no box covers are written by tile_row; pixel()
	 * leaves one the same) */
	for (int sy = 0; sy < aa; sy++)
		for (int sx = 0; sx < aa; sx++) {
			if (pixel(S, L, x + (sx + 0.5) / aa, y + (sy + 0.5) / aa,
			    px, &dep, n)) {
				hit = 1;
				if (dep < best) {
					best = dep;
					memcpy(bn, n, sizeof bn);
				}
			}
			for (int c = 0; c < 4; c++)
				acc[c] += px[c];
		}
	float *out = vx_image_pixel(color, x, y);
	for (int c = 0; c < 4; c++)
		out[c] = (float)(acc[c] / (aa * aa));
	if (depth != NULL)
		*vx_image_pixel(depth, x, y) = (float)best;
	if (normal != NULL)
		for (int c = 0; c < 3; c++)
			vx_image_pixel(normal, x, y)[c] = (float)bn[c];
	L->covered += hit;
}

/* tile_row: pixels x0..x1-1 of row y (one sample each, bins made), a bin's
 * row of pixel bits at a time: runs of pixels no footprint covers are
 * written at once (most of an image), the others drawn by image_pixel;
 * skip: the bins' centres, drawn first (the sparse pass) */
static void
tile_row(const rc_shared *S, rc_local *L, int x0, int x1, int y, int skip,
    vx_image *color, vx_image *depth, vx_image *normal)
{
	int by = y / BIN;

	for (int x = x0; x < x1;) {
		int bx = x / BIN, xe = (bx + 1) * BIN < x1 ? (bx + 1) * BIN : x1;
		unsigned row = vx_bins_row(&S->bins, bx, by, y);

		if (skip && y % BIN == BIN / 2)
			row |= 1u << BIN / 2;   /* the centre: not drawn here */
		while (x < xe) {
			int e = x;

			if (!(row >> (x - bx * BIN) & 1)) {
				while (e < xe && !(row >> (e - bx * BIN) & 1))
					e++;
				empty_run(L, x, e, y, color, depth, normal);
				x = e;
				continue;
			}
			if (!skip || y % BIN != BIN / 2 || x % BIN != BIN / 2)
				image_pixel(S, L, x, y, 1, color, depth, normal);
			x++;
		}
	}
}

/* rc_merge: what vx_par_each merges a thread's state into */
typedef struct rc_merge {
	vx_raycast_stats *st;
	double cyc[3];
} rc_merge;

/* add_local: thread t's counters into the frame's (vx_par_each) */
static int
add_local(void *ctx, void *lp, int t)
{
	rc_merge *M = ctx;
	vx_raycast_stats *st = M->st;
	const rc_local *L = lp;
	const vx_iso_stats *is = &L->ss.iso;
	const vx_tettrace_stats *ts = &L->ss.tet;
	double *cyc = M->cyc;
	int l;

	st->primary += L->primary;
	st->shadow += L->ss.shadow;
	st->cells += is->cells + ts->tets;
	st->roots += is->roots;
	st->bounded += is->bounded;
	st->certified += is->certified;
	st->exact += is->exact;
	st->hits += is->hits + ts->hits;
	st->leaves += ts->leaves;
	st->entries += ts->entries;
	st->nonfinite += is->nonfinite;
	st->shaded += L->ss.shaded;
	st->irr_missing += L->ss.irr_missing;
	st->paths += L->ss.paths;
	st->gi_rays += L->ss.gi_rays;
	st->covered += L->covered;
	st->binned += L->binned;
	for (l = 0; l <= VX_MACRO_MAXLEV; l++)
		st->macro[l] += is->trav.macro[l] + ts->trav.macro[l];
	st->culled += is->trav.culled;
	st->first_pass += L->first_pass;
	cyc[0] += (double)L->cyc_total;
	cyc[1] += (double)(is->cyc_isect + ts->cyc_isect);
	cyc[2] += (double)(L->cyc_shade - L->ss.cyc_shadow);
	return 0;
}

/* local_init: a thread's state for a frame (vx_par_each) */
static int
local_init(void *ctx, void *lp, int t)
{
	const vx_raycast_opts *o = ctx;
	rc_local *L = lp;

	L->ss.iso.timing = o->timing;
	L->ss.tet.timing = o->timing;
	em_forget(L);
	return 0;
}

/* local_forget: no entry masks kept (the bins were made again) */
static int
local_forget(void *ctx, void *lp, int t)
{
	em_forget(lp);
	return 0;
}

/* What the frame's loops read: the shared state, the images, and the
 * passes' layout. */
typedef struct rc_frame {
	const rc_shared *S;
	int aa;                       /* samples per pixel edge */
	int sparse;                   /* 1: the bins' centres are drawn */
	vx_image *color, *depth, *normal;
} rc_frame;

/* centre_pixel: the sparse pass, bin b's centre pixel (a block of the
 * bins' grid) */
static int
centre_pixel(void *ctx, void *lp, const vx_par_block *b)
{
	const rc_frame *F = ctx;
	const rc_shared *S = F->S;
	const vx_camera *cam = &S->s->camera;
	rc_local *L = lp;
	int x = (int)b->lo[0] * BIN + BIN / 2;
	int y = (int)b->lo[1] * BIN + BIN / 2;

	if (x < cam->w && y < cam->h) {
		image_pixel(S, L, x, y, F->aa, F->color, F->depth, F->normal);
		L->first_pass++;
	}
	return 0;
}

/* tile_pixels: the main pass over one tile (the bins' centres left out
 * after a sparse pass) */
static int
tile_pixels(void *ctx, void *lp, const vx_par_block *b)
{
	const rc_frame *F = ctx;
	const rc_shared *S = F->S;
	rc_local *L = lp;
	int x0 = (int)b->lo[0], y0 = (int)b->lo[1];
	int x1 = (int)b->hi[0], y1 = (int)b->hi[1];
	uint64_t c0 = S->o->timing ? vx_cycles() : 0;

	if (F->aa == 1 && S->bins.off != NULL)
		for (int y = y0; y < y1; y++)
			tile_row(S, L, x0, x1, y, F->sparse, F->color,
			    F->depth, F->normal);
	else
		for (int y = y0; y < y1; y++)
			for (int x = x0; x < x1; x++)
				if (!F->sparse || x % BIN != BIN / 2 ||
				    y % BIN != BIN / 2)
					image_pixel(S, L, x, y, F->aa, F->color,
					    F->depth, F->normal);
	if (S->o->timing)
		L->cyc_total += vx_cycles() - c0;
	return 0;
}

/* render: the picture of S's source (filled in by the caller: g and tr, or
 * mesh, lg and mesh_off); the scene, plan, textures and options here. */
static int
render(rc_shared *S_, const vx_scene *s, const vx_plan *p,
    const vx_grid *const *tex, const vx_raycast_opts *o, vx_image *color,
    vx_image *depth, vx_image *normal, vx_raycast_stats *st, vx_err *e)
{
	const vx_camera *cam = &s->camera;
	rc_shared S = *S_;
	vx_raycast_stats local_st;
	rc_merge M;
	rc_frame F;
	vx_par team;
	vx_par_time tm;
	vx_gi gim;               /* the estimator with the frame's cell mask */
	double t0, tb0;
	int tile, rc;
	int aa = o->aa >= 1 ? o->aa : 1;

	if (st == NULL)
		st = &local_st;
	memset(st, 0, sizeof *st);
	st->mesh = S.sf.mesh != NULL;
	if (!cam->ready)
		return vx_err_set(e, VX_EINTERNAL, "raycast: camera not resolved");
	if (o->bin_block > VX_RAYCAST_BLOCK_MAX)
		return vx_err_set(e, VX_EUSAGE, "raycast: bin block %d: at most "
		    "%d", o->bin_block, VX_RAYCAST_BLOCK_MAX);
	S.s = s;
	S.p = p;
	S.o = o;
	S.sf.timing = o->timing;
	S.sf.irr = o->irr;
	S.sf.irr_interp = o->irr_interp;
	S.sf.shl = o->shl;
	S.sf.irr_need = o->irr_need;
	S.sf.irr_need_ctx = o->irr_need_ctx;
	S.sf.gi = o->gi;
	if ((rc = vx_surfaces_scene(&S.sf, s, p, tex, e)) != 0)
		return vx_err_push(e, "raycast");
	S.sf.sh_e = NULL;
	S.sf.sh_done = NULL;
	if (S.sf.irr != NULL && S.sf.irr->sh_order > 0 && S.sf.irr_need == NULL) {
		size_t nt = S.sf.irr->nslot * VX_IRR_BRICK3;

		if (S.sf.shl == NULL)
			return vx_err_set(e, VX_EINTERNAL, "raycast: SH "
			    "illumination without lighting");
		S.sf.sh_done = vx_calloc(nt ? nt : 1, 1, e);
		S.sf.sh_e = S.sf.sh_done ? vx_malloc(3 * (nt ? nt : 1) *
		    sizeof *S.sf.sh_e, e) : NULL;
		if (S.sf.sh_e == NULL) {
			free(S.sf.sh_done);
			return vx_err_push(e, "raycast");
		}
	}
	/* not cleared: the tiles write every pixel (empty runs and
	 * image_pixel; the sparse pass's centres), and a clear of 4 MB would
	 * be serial work in every frame */
	if ((rc = vx_image_alloc_uninit(color, cam->w, cam->h, 4, e)) != 0)
		return rc;
	snprintf(color->name, sizeof color->name, "color");
	if (depth != NULL) {
		if ((rc = vx_image_alloc_uninit(depth, cam->w, cam->h, 1,
		    e)) != 0)
			return rc;
		snprintf(depth->name, sizeof depth->name, "depth");
	}
	if (normal != NULL) {
		if ((rc = vx_image_alloc_uninit(normal, cam->w, cam->h, 3,
		    e)) != 0)
			return rc;
		snprintf(normal->name, sizeof normal->name, "normal");
	}
	/* the cell mask for the isovalues drawn (volumes, hierarchical) */
	vx_cellmask own, *mask = o->mask_keep != NULL ? o->mask_keep : &own;
	if (mask == &own)
		vx_cellmask_init(&own);
	t0 = vx_par_seconds();
	if (S.sf.mesh == NULL && !S.sf.tr.flat && S.sf.tr.m != NULL &&
	    !o->no_cellmask) {
		if (!vx_cellmask_matches(mask, S.sf.tr.m, S.sf.iso,
		    S.sf.niso)) {
			vx_cellmask_free(mask);
			if ((rc = vx_cellmask_build(mask, S.sf.tr.m, S.sf.g,
			    S.sf.iso, S.sf.niso, 1, o->nthreads, e)) != 0)
				return rc;
		}
		if (mask->ready)
			S.sf.tr.mask = mask;
	}
	/* path tracing: the bounce and shadow rays trace one of the frame's
	 * isovalues through the same hierarchy, so they decide cells by the
	 * frame's mask too (the same cells visited: vx_macrowalk.h); with
	 * several isovalues the mask does not match one and they walk as
	 * without it */
	if (S.sf.gi != NULL && S.sf.tr.mask != NULL &&
	    S.sf.gi->tr.m == S.sf.tr.m && S.sf.gi->tr.mask == NULL) {
		gim = *S.sf.gi;
		gim.tr.mask = S.sf.tr.mask;
		S.sf.gi = &gim;
	}
	tile = o->tile > 0 ? o->tile : 16;
	if ((rc = vx_par_init(&team, o->nthreads, sizeof(rc_local), e)) != 0) {
		if (mask == &own)
			vx_cellmask_free(&own);
		return vx_err_push(e, "raycast");
	}
	vx_par_each(&team, local_init, (void *)o);
	/* bins of the boxes that hold the bracketing cells (a volume walked
	 * hierarchically).  Blocks of cells are binned only for macrocells
	 * whose mask bits are built: when some bracketing ones are not, the
	 * centre pixel of each bin is drawn first, with the bins as they are
	 * (its rays build the bits of the macrocells they enter: those in
	 * sight), and the bins are made again.  Macrocells no ray reaches
	 * stay whole and unmasked (hidden ones, mostly).  That first pass
	 * is for a mask no ray has entered yet (made for this frame): a mask
	 * kept from earlier frames has the bits of what they saw, and its
	 * hidden macrocells stay unbuilt however often the pass runs (about
	 * 1-4% of a kept-mask frame at 1 thread, for nothing).  After a camera
	 * move, a kept mask's newly seen macrocells are walked whole in the
	 * frame whose rays build their bits; the pictures are the same
	 * either way. */
	int block = o->bin_block > 0 ? o->bin_block : VX_RAYCAST_BLOCK;
	int binning = S.sf.mesh == NULL && !S.sf.tr.flat && S.sf.tr.m != NULL &&
	    S.sf.tr.m->nlev >= 1 && !o->no_binning;
	int unseen = S.sf.tr.mask != NULL && vx_cellmask_built(mask) == 0;

	F.S = &S;
	F.aa = aa;
	F.sparse = 0;
	F.color = color;
	F.depth = depth;
	F.normal = normal;
	tb0 = vx_par_seconds();
	vx_bins_init(&S.bins);
	if (binning && (rc = vx_bins_build(&S.bins, cam, S.sf.g, S.sf.tr.m,
	    S.sf.iso, S.sf.niso, S.sf.tr.mask ? mask : NULL, block, o->nthreads, e)) != 0)
		goto fail;
	st->bin_seconds = vx_par_seconds() - tb0;
	if (binning && S.bins.off != NULL && unseen && mask->nset > 0) {
		vx_par_loop centres = { { S.bins.nbx, S.bins.nby, 1 }, { 1, 1, 1 }, 16 };

		F.sparse = 1;
		vx_par_run(&team, &centres, centre_pixel, &F, NULL);
		/* (unseen: no bits were built before the pass) */
		if (vx_cellmask_built(mask) > 0) {
			/* the bins' time: the first pass's rays are not in it */
			tb0 = vx_par_seconds();
			vx_bins_drop(&S.bins);
			if ((rc = vx_bins_build(&S.bins, cam, S.sf.g,
			    S.sf.tr.m, S.sf.iso, S.sf.niso, mask, block, o->nthreads, e)) != 0)
				goto fail;
			/* lists made again */
			vx_par_each(&team, local_forget, NULL);
			st->bin_seconds += vx_par_seconds() - tb0;
		}
	}
	st->bins = S.bins.off != NULL;
	st->bin_block = st->bins ? S.bins.block : 0;
	st->bin_boxes = st->bins ? (uint64_t)S.bins.nboxes : 0;
	st->bin_whole = st->bins ? (uint64_t)S.bins.nwhole : 0;
	st->mask_bytes = S.sf.tr.mask ? vx_cellmask_bytes(mask) : 0;
	st->mask_blocks = S.sf.tr.mask ? (uint64_t)mask->nblock : 0;
	st->mask_set = S.sf.tr.mask ? (uint64_t)mask->nset : 0;
	vx_par_loop tiles = VX_PAR_TILES(cam->w, cam->h, tile);

	vx_par_run(&team, &tiles, tile_pixels, &F, &tm);
	st->seconds = vx_par_seconds() - t0;
	st->threads = tm.threads;
	st->tile_seconds = tm.seconds;
	st->thread_seconds = tm.thread_seconds;
	M.st = st;
	M.cyc[0] = M.cyc[1] = M.cyc[2] = 0;
	vx_par_each(&team, add_local, &M);
	vx_par_free(&team);
	free(S.sf.sh_e);
	free(S.sf.sh_done);
	st->mask_built = S.sf.tr.mask ? (uint64_t)vx_cellmask_built(mask) : 0;
	if (mask == &own)
		vx_cellmask_free(&own);
	vx_bins_free(&S.bins);
	if (o->timing && M.cyc[0] > 0) {
		st->share_isect = M.cyc[1] / M.cyc[0];
		st->share_shade = M.cyc[2] / M.cyc[0];
		st->share_traverse = 1 - st->share_isect - st->share_shade;
	}
	return 0;
fail:
	vx_par_free(&team);
	free(S.sf.sh_e);
	free(S.sf.sh_done);
	if (mask == &own)
		vx_cellmask_free(&own);
	vx_bins_free(&S.bins);
	return vx_err_push(e, "raycast");
}

int
vx_raycast_render(const vx_scene *s, const vx_plan *p, const vx_grid *g,
    const vx_macro *m, const vx_grid *const *tex, const vx_raycast_opts *o,
    vx_image *color, vx_image *depth, vx_image *normal, vx_raycast_stats *st,
    vx_err *e)
{
	rc_shared S;

	memset(&S, 0, sizeof S);
	vx_surfaces_init(&S.sf);
	vx_surfaces_volume(&S.sf, g, m, o->solver, o->flat, o->shadow_offset);
	return render(&S, s, p, tex, o, color, depth, normal, st, e);
}

int
vx_raycast_render_mesh(const vx_scene *s, const vx_plan *p,
    const vx_tetmesh *mesh, const vx_tetleaf *lg, const vx_grid *const *tex,
    const vx_raycast_opts *o, vx_image *color, vx_image *depth,
    vx_image *normal, vx_raycast_stats *st, vx_err *e)
{
	rc_shared S;

	memset(&S, 0, sizeof S);
	vx_surfaces_init(&S.sf);
	vx_surfaces_mesh(&S.sf, mesh, lg, o->shadow_offset);
	return render(&S, s, p, tex, o, color, depth, normal, st, e);
}
