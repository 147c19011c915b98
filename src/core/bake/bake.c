/* bake.c: irradiance volumes by path tracing at every wanted texel
 * (vx_bake.h). */
#include "vx_bake.h"
#include "vx_smooth.h"
#include "vx_vec.h"

#include "vx_par.h"
#include "vx_sh.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

void
vx_bake_opts_init(vx_bake_opts *o)
{
	memset(o, 0, sizeof *o);
	o->scale = 1;
	o->offset = 0.5;
	o->samples = 64;
	o->round = 16;
	o->min_samples = 16;
	o->all = 1;
}

void
vx_bake_key(const char *settings, char key[17])
{
	uint64_t h = 0xcbf29ce484222325u;

	for (const unsigned char *p = (const unsigned char *)settings; *p; p++) {
		h ^= *p;
		h *= 0x100000001b3u;
	}
	for (int k = 15; k >= 0; k--) {
		key[k] = "0123456789abcdef"[h & 15];
		h >>= 4;
	}
	key[16] = 0;
}

void
vx_bake_settings(const vx_irrvol *v, const vx_gi *gi, const vx_bake_opts *o,
    char *buf, size_t n)
{
	size_t k = 0;

#define PUT(...) do { int w_ = snprintf(buf + k, n - k, __VA_ARGS__); \
	if (w_ > 0) k += (size_t)w_ < n - k ? (size_t)w_ : n - k - 1; } while (0)
	buf[0] = 0;
	PUT("scale %.17g offset %.17g seed %llu bounces %d eps %.17g "
	    "solver exact fixed %d side %s", v->scale, o->offset,
	    (unsigned long long)gi->seed, gi->bounces, gi->eps, v->fixed,
	    gi->high ? "high" : "low");
	if (v->sh_order > 0) {
		/* a transfer volume holds no light: only the geometry, the
		 * albedo and the bounces determine it */
		PUT("; transfer sh order %d channels %d", v->sh_order,
		    v->channels);
		if (gi->vicinity < INFINITY)
			PUT("; vicinity %.17g", gi->vicinity);
		goto albedo;
	}
	for (int i = 0; i < gi->nlight; i++) {
		const vx_gi_light *l = &gi->light[i];

		if (l->point)
			PUT("; point %.17g %.17g %.17g", l->pos[0], l->pos[1],
			    l->pos[2]);
		else
			PUT("; directional %.17g %.17g %.17g", l->dir[0],
			    l->dir[1], l->dir[2]);
		PUT(" rgb %.17g %.17g %.17g%s%s", l->rgb[0], l->rgb[1],
		    l->rgb[2], l->inverse_square ? " inverse-square" : "",
		    l->shadows ? " shadows" : "");
	}
	if (gi->has_sky)
		PUT("; sky %.17g %.17g %.17g", gi->sky[0], gi->sky[1],
		    gi->sky[2]);
	if (gi->occlusion)
		PUT("; occlusion");
	if (gi->vicinity < INFINITY)
		PUT(" distance %.17g", gi->vicinity);
	if (gi->has_env)
		PUT("; environment %s%s", gi->env_id, gi->env_mis ? " mis" : "");
albedo:
	PUT("; albedo");
	for (int i = 0; i < gi->nalbedo; i++)
		PUT(" %.17g:%.17g,%.17g,%.17g", gi->albedo_v[i],
		    gi->albedo_c[i][0], gi->albedo_c[i][1], gi->albedo_c[i][2]);
#undef PUT
}

void
vx_bake_sign(vx_irrvol *v, const vx_gi *gi, const vx_bake_opts *o)
{
	vx_bake_settings(v, gi, o, v->settings, sizeof v->settings);
	vx_bake_key(v->settings, v->key);
	v->offset = o->offset;
	v->seed = gi->seed;
	v->high = gi->high;
}

static double
wall(void)
{
	return vx_par_seconds();
}

/* the volume samples' range over the index box [lo, hi] (inclusive,
 * clamped); NaN samples ignored */
static void
box_range(const vx_grid *g, const int64_t lo[3], const int64_t hi[3],
    double *mn, double *mx)
{
	*mn = INFINITY;
	*mx = -INFINITY;
	for (int64_t z = lo[2]; z <= hi[2]; z++)
		for (int64_t y = lo[1]; y <= hi[1]; y++)
			for (int64_t x = lo[0]; x <= hi[0]; x++) {
				double f = vx_grid_get(g, x, y, z);

				if (f < *mn)
					*mn = f;
				if (f > *mx)
					*mx = f;
			}
}

static int
meets(const vx_bake_opts *o, double mn, double mx)
{
	for (int b = 0; b < o->nband; b++)
		if (mn <= o->band[b][1] && mx >= o->band[b][0])
			return 1;
	return 0;
}

static void
want(vx_irrvol *v, int64_t i, int64_t j, int64_t k)
{
	int64_t s = vx_irr_texel(v, i, j, k);

	if (s >= 0)
		v->flags[s] |= VX_TEXEL_WANTED;
}

/* what the plan's parallel pass reads and writes */
typedef struct plan_ctx {
	const vx_irrvol *v;
	const vx_grid *g;
	const vx_bake_opts *o;
	const int64_t *cd;       /* lattice cells per axis */
	uint8_t *cellw;          /* per cell: 1 where it meets a band */
} plan_ctx;

/* plan_slab: which lattice cells of slab k meet a band */
static int
plan_slab(void *ctx, void *lp, const vx_par_block *b)
{
	const plan_ctx *C = ctx;
	const vx_irrvol *v = C->v;
	const vx_grid *g = C->g;
	const int64_t *cd = C->cd;
	int64_t k = b->lo[2];

	(void)lp;
	for (int64_t j = 0; j < cd[1]; j++)
		for (int64_t i = 0; i < cd[0]; i++) {
			int64_t lo[3], hi[3], c[3] = { i, j, k };
			double mn, mx;

			for (int a = 0; a < 3; a++) {
				double p0 = (double)c[a] * v->step[a];
				double p1 = v->dims[a] > 1 ?
				    (double)(c[a] + 1) * v->step[a] : p0;

				lo[a] = (int64_t)floor(p0);
				hi[a] = (int64_t)ceil(p1);
				if (hi[a] > g->dims[a] - 1)
					hi[a] = g->dims[a] - 1;
				if (lo[a] > hi[a])
					lo[a] = hi[a];
			}
			box_range(g, lo, hi, &mn, &mx);
			if (meets(C->o, mn, mx))
				C->cellw[(size_t)i + (size_t)cd[0] *
				    ((size_t)j + (size_t)cd[1] * (size_t)k)] = 1;
		}
	return 0;
}

/* the brick of lattice cell corner (x, y, z) */
static size_t
brick_of(const vx_irrvol *v, int64_t x, int64_t y, int64_t z)
{
	return (size_t)(x / VX_IRR_BRICK) + (size_t)v->bdims[0] *
	    ((size_t)(y / VX_IRR_BRICK) + (size_t)v->bdims[1] *
	    (size_t)(z / VX_IRR_BRICK));
}

/* corners: fn(v, x, y, z) for each corner inside the lattice of each
 * lattice cell whose byte in cellw (cd cells per axis) is set, in cell
 * order; stops at the first nonzero return, and returns it */
typedef int (*corner_fn)(vx_irrvol *v, int64_t x, int64_t y, int64_t z,
    void *ctx, vx_err *e);

static int
corners(vx_irrvol *v, const int64_t cd[3], const uint8_t *cellw,
    corner_fn fn, void *ctx, vx_err *e)
{
	for (int64_t k = 0; k < cd[2]; k++)
		for (int64_t j = 0; j < cd[1]; j++)
			for (int64_t i = 0; i < cd[0]; i++) {
				if (!cellw[(size_t)i + (size_t)cd[0] * ((size_t)j +
				    (size_t)cd[1] * (size_t)k)])
					continue;
				for (int q = 0; q < 8; q++) {
					int64_t x = i + (q & 1), y = j + ((q >> 1) & 1),
					    z = k + ((q >> 2) & 1);
					int rc;

					if (x >= v->dims[0] || y >= v->dims[1] ||
					    z >= v->dims[2])
						continue;
					if ((rc = fn(v, x, y, z, ctx, e)) != 0)
						return rc;
				}
			}
	return 0;
}

static int
mark_brick(vx_irrvol *v, int64_t x, int64_t y, int64_t z, void *ctx,
    vx_err *e)
{
	(void)e;
	((uint8_t *)ctx)[brick_of(v, x, y, z)] = 1;
	return 0;
}

static int
want_corner(vx_irrvol *v, int64_t x, int64_t y, int64_t z, void *ctx,
    vx_err *e)
{
	(void)ctx;
	return vx_irr_want_texel(v, x, y, z, e) < 0 ? e->code : 0;
}

/* the memory check: nb bricks stored in all (those v has included) */
static int
fits(const vx_irrvol *v, const vx_bake_opts *o, size_t nb, vx_bake_stats *st,
    vx_err *e)
{
	size_t nall = (size_t)v->bdims[0] * (size_t)v->bdims[1] *
	    (size_t)v->bdims[2];

	/* the storage, the brick table, and the chunk written at the end:
	 * its body and the payload made of it (vx_irr_to_chunk) */
	st->need_bytes = (uint64_t)nb * VX_IRR_BRICK3 *
	    (vx_irr_texel_memory(v->store, v->ncomp) +
	    2 * vx_irr_texel_bytes(v->store, v->ncomp)) + (uint64_t)nall *
	    sizeof *v->slot + o->held_bytes;
	if (o->max_bytes > 0 && st->need_bytes > o->max_bytes)
		return vx_err_set(e, VX_ENOMEM, "the bake would take %.3g GB "
		    "of memory at its peak (%zu bricks of %d^3 texels, %zu "
		    "bytes a texel, the chunk written of them, the input), "
		    "more than the %.3g GB allowed", (double)st->need_bytes /
		    1e9, nb, VX_IRR_BRICK, vx_irr_texel_memory(v->store,
		    v->ncomp), (double)o->max_bytes / 1e9);
	return 0;
}

int
vx_bake_plan(vx_irrvol *v, const vx_grid *g, const vx_bake_opts *o,
    vx_bake_stats *st, vx_err *e)
{
	double t0 = wall();
	int64_t cd[3];
	uint8_t *cellw = NULL, *bneed = NULL;
	size_t ncell, nb = (size_t)v->bdims[0] * (size_t)v->bdims[1] *
	    (size_t)v->bdims[2], need = 0;
	int rc;

	st->lattice = (uint64_t)v->dims[0] * (uint64_t)v->dims[1] *
	    (uint64_t)v->dims[2];
	if (o->all) {
		if ((rc = fits(v, o, nb, st, e)) != 0 ||
		    (rc = vx_irr_reserve(v, nb, e)) != 0)
			return rc;
		for (size_t b = 0; b < nb; b++)
			if ((rc = vx_irr_want_brick(v, b, e)) != 0)
				return rc;
		for (int64_t k = 0; k < v->dims[2]; k++)
			for (int64_t j = 0; j < v->dims[1]; j++)
				for (int64_t i = 0; i < v->dims[0]; i++)
					want(v, i, j, k);
		st->wanted = st->lattice;
		st->bricks = v->nslot;
		st->plan_s += wall() - t0;
		return 0;
	}
	/* lattice cells (an axis of one texel has one "cell", its texel) */
	for (int a = 0; a < 3; a++)
		cd[a] = v->dims[a] > 1 ? v->dims[a] - 1 : 1;
	ncell = (size_t)cd[0] * (size_t)cd[1] * (size_t)cd[2];
	if ((cellw = vx_calloc(ncell, 1, e)) == NULL ||
	    (bneed = vx_calloc(nb, 1, e)) == NULL) {
		free(cellw);
		return VX_ENOMEM;
	}
	/* which lattice cells meet a band: the range of the samples their
	 * box covers (a slab of cells a block) */
	{
		plan_ctx C = { v, g, o, cd, cellw };
		vx_par_loop slabs = { { cd[0], cd[1], cd[2] },
		    { cd[0], cd[1], 1 }, 1 };
		vx_par team;

		if ((rc = vx_par_init(&team, o->threads, 0, e)) != 0) {
			free(cellw);
			free(bneed);
			return rc;
		}
		vx_par_run(&team, &slabs, plan_slab, &C, NULL);
		vx_par_free(&team);
	}
	/* the bricks it needs, and the memory they take, before any is
	 * allocated */
	for (size_t b = 0; b < nb; b++)
		bneed[b] = v->slot[b] != 0;
	corners(v, cd, cellw, mark_brick, bneed, e);
	for (size_t b = 0; b < nb; b++)
		need += bneed[b];
	free(bneed);
	if ((rc = fits(v, o, need, st, e)) != 0 ||
	    (rc = vx_irr_reserve(v, need, e)) != 0 ||
	    /* bricks first (serially, in brick order), then the texels */
	    (rc = corners(v, cd, cellw, want_corner, NULL, e)) != 0) {
		free(cellw);
		return rc;
	}
	free(cellw);
	st->wanted = 0;
	for (size_t s = 0; s < v->nslot * VX_IRR_BRICK3; s++)
		st->wanted += (v->flags[s] & VX_TEXEL_WANTED) != 0;
	st->bricks = v->nslot;
	st->plan_s += wall() - t0;
	return 0;
}

uint32_t
vx_bake_texel_setup(const vx_irrvol *v, const vx_grid *g, double offset,
    int high, int64_t i, int64_t j, int64_t k, double *rho, double start[3],
    double n[3])
{
	double p[3], grad[3], gw[3], ni[3], len, scale;
	uint32_t fl = 0;
	int sf;

	vx_irr_texel_point(v, i, j, k, p);
	*rho = vx_grid_trilinear(g, p);
	sf = vx_bspline_gradient(g, p, grad);
	if (sf & VX_SMOOTH_BORDER)
		fl |= VX_TEXEL_BORDER;
	if (!isfinite(*rho) || (sf & VX_SMOOTH_NAN))
		return fl | VX_TEXEL_NAN;
	scale = g->has_range ? fmax(fabs(g->vmax - g->vmin), 0) : 0;
	len = sqrt(vx_dot3(grad, grad));
	if (!(len > ldexp(scale, -30)) || !isfinite(len))
		return fl | VX_TEXEL_FLAT;
	/* toward the lit side, in world space */
	for (int a = 0; a < 3; a++)
		gw[a] = (high ? grad[a] : -grad[a]) / g->spacing[a];
	vx_unit3(gw);
	memcpy(n, gw, sizeof gw);
	/* the start point: offset voxels along the normal's index-space
	 * direction */
	vx_world_to_index_dir(g, n, ni);
	vx_unit3(ni);
	for (int a = 0; a < 3; a++)
		start[a] = p[a] + offset * ni[a];
	return fl;
}

static uint64_t
texel_id(const vx_irrvol *v, int64_t i, int64_t j, int64_t k)
{
	return (uint64_t)i + (uint64_t)v->dims[0] * ((uint64_t)j +
	    (uint64_t)v->dims[1] * (uint64_t)k);
}

/* one_sample: sample `index` of texel id into a: the irradiance estimate,
 * or the SH transfer estimate pi thru Y(w) of an escaping path (zeros for
 * a path that ends on a surface) */
static void
one_sample(const vx_irrvol *v, const vx_gi *gi, const double start[3],
    const double n[3], double rho, const double D[3], uint64_t id,
    vx_irr_acc *a, vx_gi_stats *st)
{
	uint64_t index = (uint64_t)v->first + a->count;
	double val[VX_IRR_MAX_COMP];

	if (v->sh_order == 0) {
		vx_gi_sample(gi, start, n, rho, gi->high, D, id, index, val, st);
	} else {
		int nn = v->sh_order * v->sh_order;
		double w[3], thru[3], y[VX_IRR_MAX_COMP / 3];

		if (!vx_gi_transfer(gi, start, n, rho, gi->high, id, index, w,
		    thru, st)) {
			memset(val, 0, (size_t)v->ncomp * sizeof *val);
		} else {
			vx_sh_eval(v->sh_order, w, y);
			if (v->channels == 1)
				thru[0] = 0.2126 * thru[0] + 0.7152 * thru[1] +
				    0.0722 * thru[2];
			for (int c = 0; c < v->channels; c++)
				for (int i = 0; i < nn; i++)
					val[c * nn + i] = VX_PI * thru[c] * y[i];
		}
	}
	vx_irr_acc_add(v, a, val);
}

void
vx_bake_texel(const vx_irrvol *v, const vx_gi *gi, const vx_grid *g,
    const vx_bake_opts *o, int64_t i, int64_t j, int64_t k, vx_irr_acc *a,
    vx_gi_stats *st)
{
	double rho, start[3], n[3], D[3], sw[3];
	uint64_t id = texel_id(v, i, j, k);
	uint32_t fl, goal;

	fl = vx_bake_texel_setup(v, g, o->offset, gi->high, i, j, k, &rho,
	    start, n);
	a->flags |= fl;
	if (fl & (VX_TEXEL_NAN | VX_TEXEL_FLAT))
		return;
	if (v->sh_order == 0) {
		vx_index_to_world(g, start, sw);
		vx_gi_direct(gi, sw, start, n, rho, gi->high, D, st);
	}
	if (o->target > 0) {
		uint32_t cap = o->samples, r = o->round ? o->round : 16;

		while (a->count < cap) {
			if (a->count >= o->min_samples &&
			    vx_irr_acc_relerr(v, a) <= o->target)
				break;
			goal = a->count + (cap - a->count < r ? cap - a->count : r);
			while (a->count < goal)
				one_sample(v, gi, start, n, rho, D, id, a, st);
		}
		return;
	}
	goal = o->topup ? o->samples : a->count + o->samples;
	if (!o->topup && goal < a->count)
		goal = UINT32_MAX;
	while (a->count < goal)
		one_sample(v, gi, start, n, rho, D, id, a, st);
}

/* what the bake's parallel pass reads */
typedef struct run_ctx {
	vx_irrvol *v;
	const vx_gi *gi;
	const vx_grid *g;
	const vx_bake_opts *o;
	const uint64_t *todo;    /* the texels, packed i | j << 21 | k << 42 */
	size_t n;
	_Atomic uint64_t done;   /* texels done, for the progress report */
} run_ctx;

/* a thread's state: its estimator's counters and its texels', and the
 * accumulators of a final store's texel */
typedef struct run_local {
	vx_gi_stats ls;
	vx_irr_acc *tmp;
	uint64_t sampled, baked, flat, nan, border;
	double last;             /* when it last reported progress */
	int t;                   /* the thread */
} run_local;

static int
run_start(void *ctx, void *lp, int t)
{
	run_local *L = lp;

	run_ctx *C = ctx;

	memset(L, 0, sizeof *L);
	L->t = t;
	L->last = wall();
	if (C->v->store != VX_IRR_ACCUM &&
	    (L->tmp = malloc(vx_irr_acc_bytes(C->v->ncomp))) == NULL)
		return VX_ENOMEM;
	return 0;
}

static int
run_merge(void *ctx, void *lp, int t)
{
	run_local *L = lp;

	vx_gi_stats_add(ctx, &L->ls);
	free(L->tmp);
	L->tmp = NULL;
	return 0;
}

/* run_texel: the samples of texel q of the list (thread 0 reports the
 * progress) */
static int
run_texel(void *ctx, void *lp, const vx_par_block *b)
{
	run_ctx *C = ctx;
	run_local *L = lp;
	vx_irrvol *v = C->v;
	size_t q = (size_t)b->index;
	int64_t i = (int64_t)(C->todo[q] & 0x1fffff);
	int64_t j = (int64_t)(C->todo[q] >> 21 & 0x1fffff);
	int64_t k = (int64_t)(C->todo[q] >> 42);
	int64_t s = vx_irr_texel(v, i, j, k);
	vx_irr_acc *a;
	uint32_t before;

	if (v->store == VX_IRR_ACCUM) {
		a = vx_irr_accp(v, s);
	} else {                   /* a final store: from zero, then kept */
		a = L->tmp;
		memset(a, 0, vx_irr_acc_bytes(v->ncomp));
	}
	before = a->count;
	vx_bake_texel(v, C->gi, C->g, C->o, i, j, k, a, &L->ls);
	/* the wanted bit lives in the accumulators' flags too, so a stored
	 * bake keeps its plan */
	a->flags |= VX_TEXEL_WANTED;
	if (v->store != VX_IRR_ACCUM)
		vx_irr_settle(v, s, a);
	L->sampled += a->count - before;
	L->baked += a->count > before;
	L->flat += (a->flags & VX_TEXEL_FLAT) != 0;
	L->nan += (a->flags & VX_TEXEL_NAN) != 0;
	L->border += (a->flags & VX_TEXEL_BORDER) != 0;
	if (C->o->progress != NULL) {
		uint64_t d = atomic_fetch_add_explicit(&C->done, 1,
		    memory_order_relaxed) + 1;

		if (L->t == 0 && wall() - L->last > 0.25) {
			L->last = wall();
			C->o->progress(C->o->progress_ctx, d, C->n);
		}
	}
	return 0;
}

int
vx_bake_run(vx_irrvol *v, const vx_gi *gi, const vx_grid *g,
    const vx_bake_opts *o, vx_bake_stats *st, vx_err *e)
{
	size_t nb = (size_t)v->bdims[0] * (size_t)v->bdims[1] *
	    (size_t)v->bdims[2], nt = 0, n = 0;
	uint64_t *todo, sampled = 0, baked = 0, flat = 0, nan = 0, border = 0;
	double t0 = wall();
	vx_gi_stats gs;

	/* the wanted texels, in brick order then texel order */
	for (size_t s = 0; s < v->nslot * VX_IRR_BRICK3; s++)
		nt += (v->flags[s] & VX_TEXEL_WANTED) != 0;
	if ((todo = vx_calloc(nt ? nt : 1, sizeof *todo, e)) == NULL)
		return VX_ENOMEM;
	for (size_t b = 0; b < nb; b++) {
		int64_t bx, by, bz;

		if (v->slot[b] == 0)
			continue;
		bx = (int64_t)(b % (size_t)v->bdims[0]);
		by = (int64_t)(b / (size_t)v->bdims[0] % (size_t)v->bdims[1]);
		bz = (int64_t)(b / ((size_t)v->bdims[0] * (size_t)v->bdims[1]));
		for (int t = 0; t < VX_IRR_BRICK3; t++) {
			int64_t i = bx * VX_IRR_BRICK + t % VX_IRR_BRICK;
			int64_t j = by * VX_IRR_BRICK + t / VX_IRR_BRICK %
			    VX_IRR_BRICK;
			int64_t k = bz * VX_IRR_BRICK + t / (VX_IRR_BRICK *
			    VX_IRR_BRICK);
			size_t s = (size_t)(v->slot[b] - 1) * VX_IRR_BRICK3 +
			    (size_t)t;

			if (i >= v->dims[0] || j >= v->dims[1] ||
			    k >= v->dims[2] || !(v->flags[s] & VX_TEXEL_WANTED))
				continue;
			if (o->only != NULL && !o->only[texel_id(v, i, j, k)])
				continue;
			todo[n++] = (uint64_t)i | (uint64_t)j << 21 |
			    (uint64_t)k << 42;
		}
	}
	{
		run_ctx C;
		vx_par team;
		int rc;

		memset(&C, 0, sizeof C);
		memset(&gs, 0, sizeof gs);
		C.v = v;
		C.gi = gi;
		C.g = g;
		C.o = o;
		C.todo = todo;
		C.n = n;
		if ((rc = vx_par_init(&team, o->threads, sizeof(run_local),
		    e)) != 0) {
			free(todo);
			return rc;
		}
		if ((rc = vx_par_each(&team, run_start, &C)) != 0) {
			vx_par_each(&team, run_merge, &gs);
			vx_par_free(&team);
			free(todo);
			return vx_err_set(e, rc, "out of memory");
		}
		vx_par_loop texels = VX_PAR_ITEMS((int64_t)n, 16);

		vx_par_run(&team, &texels, run_texel, &C, NULL);
		vx_par_each(&team, run_merge, &gs);
		for (int t = 0; t < team.nthreads; t++) {
			const run_local *L = vx_par_local(&team, t);

			sampled += L->sampled;
			baked += L->baked;
			flat += L->flat;
			nan += L->nan;
			border += L->border;
		}
		vx_par_free(&team);
	}
	free(todo);
	if (o->progress != NULL)
		o->progress(o->progress_ctx, n, n);
	vx_irr_finish(v);
	st->samples += sampled;
	st->baked += baked;
	st->flat += flat;
	st->nan += nan;
	st->border += border;
	st->bricks = v->nslot;
	vx_gi_stats_add(&st->gi, &gs);
	st->bake_s += wall() - t0;
	return 0;
}
