/* miprender.c: the MIP picture, tile by tile on the threads of vx_par.h,
 * each ray through vx_mip_ray (or the exhaustive reference) (vx_mip.h). */
#include "vx_mip.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vx_par.h"

/* a thread's state: its workspace (queue, column cache, last t) and its
 * rays' counters */
typedef struct mip_local {
	_Alignas(64) vx_mip_work w;
	vx_mip_stats st;
	int ready;               /* w initialized */
} mip_local;

/* what the tiles read */
typedef struct mip_frame {
	const vx_camera *cam;
	const vx_grid *g;
	const vx_macro *m;
	const vx_mip_opts *o;
	double miss;             /* the value where a ray meets no sample */
	vx_image *val, *depth;
	vx_err *e;
} mip_frame;

void
vx_mip_opts_init(vx_mip_opts *o)
{
	memset(o, 0, sizeof *o);
	o->tile = 16;
	o->last_t = 1;
}

static int
local_init(void *ctx, void *lp, int t)
{
	const mip_frame *F = ctx;
	mip_local *L = lp;
	int rc;

	if ((rc = vx_mip_work_init(&L->w, F->m, F->e)) == 0)
		L->ready = 1;
	return rc;
}

static int
local_merge(void *ctx, void *lp, int t)
{
	vx_mip_stats *st = ctx;
	const mip_local *L = lp;

	st->rays += L->st.rays;
	st->pushes += L->st.pushes;
	st->pops += L->st.pops;
	st->macro_opened += L->st.macro_opened;
	st->cells += L->st.cells;
	st->cells_skipped += L->st.cells_skipped;
	st->bound_pruned += L->st.bound_pruned;
	if (L->st.max_queue > st->max_queue)
		st->max_queue = L->st.max_queue;
	return 0;
}

static int
local_free(void *ctx, void *lp, int t)
{
	mip_local *L = lp;

	if (L->ready)
		vx_mip_work_free(&L->w);
	L->ready = 0;
	return 0;
}

/* tile: the rays of one tile, row by row, the last-t bound from the
 * tile's first ray on (so a tile's pixels depend on the tile only) */
static int
tile(void *ctx, void *lp, const vx_par_block *b)
{
	const mip_frame *F = ctx;
	mip_local *L = lp;

	L->w.last_t = NAN;
	for (int y = (int)b->lo[1]; y < (int)b->hi[1]; y++)
		for (int x = (int)b->lo[0]; x < (int)b->hi[0]; x++) {
			double ow[3], dw[3], oi[3], di[3], v, t;
			int hit;

			vx_camera_ray(F->cam, x + 0.5, y + 0.5, ow, dw);
			vx_world_to_index(F->g, ow, oi);
			vx_world_to_index_dir(F->g, dw, di);
			hit = F->o->exhaustive ?
			    vx_mip_ray_exhaustive(F->g, oi, di, 0, INFINITY, &v,
			    &t) : vx_mip_ray(F->g, F->m, &L->w, oi, di, 0,
			    INFINITY, F->o->last_t, &v, &t, &L->st);
			*vx_image_pixel(F->val, x, y) = (float)(hit ? v :
			    F->miss);
			if (F->depth != NULL)
				*vx_image_pixel(F->depth, x, y) = (float)(hit ? t :
				    INFINITY);
		}
	return 0;
}

int
vx_mip_render(const vx_camera *cam, const vx_grid *g, const vx_macro *m,
    const vx_mip_opts *o, vx_image *val, vx_image *depth, vx_mip_stats *st,
    vx_err *e)
{
	mip_frame F;
	vx_par team;
	vx_par_time tm;
	vx_mip_stats local_st;
	int rc, tw = o->tile > 0 ? o->tile : 16;

	if (st == NULL)
		st = &local_st;
	memset(st, 0, sizeof *st);
	if (!cam->ready)
		return vx_err_set(e, VX_EINTERNAL, "mip: camera not resolved");
	F.cam = cam;
	F.g = g;
	F.m = m;
	F.o = o;
	F.miss = g->has_range ? g->vmin : 0;
	F.val = val;
	F.depth = depth;
	F.e = e;
	if ((rc = vx_par_init(&team, o->nthreads, sizeof(mip_local), e)) != 0)
		return vx_err_push(e, "mip");
	if ((rc = vx_par_each(&team, local_init, &F)) != 0)
		goto out;
	/* every pixel is written */
	if ((rc = vx_image_alloc_uninit(val, cam->w, cam->h, 1, e)) != 0)
		goto out;
	snprintf(val->name, sizeof val->name, "mip");
	if (depth != NULL) {
		if ((rc = vx_image_alloc_uninit(depth, cam->w, cam->h, 1,
		    e)) != 0) {
			vx_image_free(val);
			goto out;
		}
		snprintf(depth->name, sizeof depth->name, "depth");
	}
	vx_par_loop tiles = VX_PAR_TILES(cam->w, cam->h, tw);

	vx_par_run(&team, &tiles, tile, &F, &tm);
	vx_par_each(&team, local_merge, st);
	st->threads = tm.threads;
	st->seconds = tm.seconds;
	st->thread_seconds = tm.thread_seconds;
out:
	vx_par_each(&team, local_free, NULL);
	vx_par_free(&team);
	return rc;
}
