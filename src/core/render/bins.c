/* bins.c: the primary rays' bins (vx_bins.h): the bracketing macrocells'
 * boxes (or their blocks' boxes) placed on the image, sorted by a lower
 * bound of their entry time, and listed per bin of pixels. */
#include "vx_bins.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vx_par.h"

/* box_sort: *bx[0..n) in order of lb, ties in their given order (a stable
 * radix sort of lb's bits made monotone, RDX bits a pass, the passes'
 * counts made in one sweep, passes over a digit all keys share skipped);
 * *bx is replaced by the sorted copy.  0, or VX_ENOMEM (*bx unchanged). */
#define RDX 11
#define NDIG ((64 + RDX - 1) / RDX)
static int
box_sort(vx_cellbox **bxp, int64_t n)
{
	size_t nn = (size_t)(n > 0 ? n : 1);
	uint64_t *key = malloc(nn * 2 * sizeof *key);
	uint32_t *ix = malloc(nn * 2 * sizeof *ix);
	uint32_t *cnt = calloc((size_t)NDIG << RDX, sizeof *cnt);
	vx_cellbox *bx = *bxp, *out = malloc(nn * sizeof *out);
	uint64_t *k0 = key, *k1 = key + n;
	uint32_t *i0 = ix, *i1 = ix + n;
	const uint64_t dm = ((uint64_t)1 << RDX) - 1;
	int64_t i;

	if (key == NULL || ix == NULL || cnt == NULL || out == NULL) {
		free(key);
		free(ix);
		free(cnt);
		free(out);
		return VX_ENOMEM;
	}
	/* n < 2^32 (bins_cap): the counts fit */
	for (i = 0; i < n; i++) {
		uint64_t u;

		memcpy(&u, &bx[i].lb, sizeof u);
		/* negative: all bits flipped; else the sign bit set */
		u = u >> 63 ? ~u : u | (uint64_t)1 << 63;
		k0[i] = u;
		i0[i] = (uint32_t)i;
		for (int d = 0; d < NDIG; d++)
			cnt[(d << RDX) + (u >> (RDX * d) & dm)]++;
	}
	for (int d = 0; d < NDIG && n > 0; d++) {
		uint32_t *c = cnt + (d << RDX), sum = 0;
		int sh = RDX * d;
		uint64_t *kt;
		uint32_t *it;

		if (c[k0[0] >> sh & dm] == (uint64_t)n)
			continue;
		/* counts -> each digit's first place */
		for (i = 0; i <= (int64_t)dm; i++) {
			uint32_t t = c[i];

			c[i] = sum;
			sum += t;
		}
		for (i = 0; i < n; i++) {
			uint32_t p = c[k0[i] >> sh & dm]++;

			k1[p] = k0[i];
			i1[p] = i0[i];
		}
		kt = k0, k0 = k1, k1 = kt;
		it = i0, i0 = i1, i1 = it;
	}
	for (i = 0; i < n; i++)
		out[i] = bx[i0[i]];
	free(key);
	free(ix);
	free(cnt);
	free(bx);
	*bxp = out;
	return 0;
}
#undef RDX
#undef NDIG

/* floor_fin: floor(x) for finite x, but +0 for -0 (callers add or take 1,
 * which makes either zero the same number), without a library call: below
 * 2^52 in magnitude a conversion to int64_t truncates, above x is an
 * integer.  ceil(x) is -floor_fin(-x), up to the sign of zero. */
static inline double
floor_fin(double x)
{
	double t;

	if (!(fabs(x) < 0x1p52))
		return x;
	t = (double)(int64_t)x;
	return t > x ? t - 1 : t;
}

/* box_place: bx's lb (t is world distance along the unit ray: from the
 * eye to the box, or the box's least depth for an orthographic camera;
 * lowered by far more than rounding) and its footprint, the pixels its
 * projection covers widened by one (the whole image when a corner is not
 * in front of the eye).  A ray that enters the box passes through a point
 * of it, whose projection is its own sample point (x, y) and lies in the
 * hull of the corners' projections [lo, hi], up to rounding far below a
 * pixel: so floor(lo) - 1 <= (int)x <= ceil(hi), whatever the rounding.
 * The corners' pixel coordinates px = 0.5 w (1 + q / half_w), q = u / z
 * (u for orthographic), and py = 0.5 h (1 - r / half_h), are made of
 * correctly rounded steps, each monotone in q (r) as half_w, half_h, w
 * and h are > 0: so the least and greatest px are those of the least and
 * greatest q, and only those are converted (the same numbers as
 * converting all eight; a NaN q, whose px is not finite, is caught on its
 * own, and an infinite px is one of the extremes).  0: the box is off the
 * image. */
static int
box_place(const vx_grid *g, const vx_camera *cam, vx_cellbox *bx)
{
	double q0 = INFINITY, q1 = -INFINITY, r0 = INFINITY, r1 = -INFINITY;
	double dist2 = 0, depth = INFINITY, lo[2] = { 0, 0 }, hi[2] = { 0, 0 };
	double su = 0, sv = 0;
	double vz[3][2], va[3][2], vb[3][2], z01[4], u01[4], v01[4];
	int front = 1, nan, persp = cam->projection != VX_ORTHOGRAPHIC;
	int a, i;

	/* world = origin + index * spacing, axis by axis: a corner's
	 * camera coordinates are sums of one term per axis (vx_camera_project's
	 * dot products, in another order: the footprint's margin and lb's are
	 * far above the rounding) */
	for (a = 0; a < 3; a++) {
		double w0 = g->origin[a] + (double)bx->lo[a] *
		    g->spacing[a] - cam->o[a];
		double w1 = g->origin[a] + (double)bx->hi[a] *
		    g->spacing[a] - cam->o[a];

		if (w0 > 0)
			dist2 += w0 * w0;
		else if (w1 < 0)
			dist2 += w1 * w1;
		vz[a][0] = w0 * cam->fwd[a];
		vz[a][1] = w1 * cam->fwd[a];
		va[a][0] = w0 * cam->right[a];
		va[a][1] = w1 * cam->right[a];
		vb[a][0] = w0 * cam->upv[a];
		vb[a][1] = w1 * cam->upv[a];
	}
	/* corner i's sums (x + y) + z, the x + y shared by two corners */
	for (i = 0; i < 4; i++) {
		z01[i] = vz[0][i & 1] + vz[1][i >> 1];
		u01[i] = va[0][i & 1] + va[1][i >> 1];
		v01[i] = vb[0][i & 1] + vb[1][i >> 1];
	}
#pragma GCC unroll 8
	for (i = 0; i < 8; i++) {
		double z = z01[i & 3] + vz[2][i >> 2];
		double u = u01[i & 3] + va[2][i >> 2];
		double v = v01[i & 3] + vb[2][i >> 2];

		depth = z < depth ? z : depth;
		front &= z > 0;
		if (persp) {
			/* z <= 0: any u, v (the footprint is the image) */
			u /= z;
			v /= z;
		}
		su += u;
		sv += v;
		q0 = u < q0 ? u : q0;
		q1 = u > q1 ? u : q1;
		r0 = v < r0 ? v : r0;
		r1 = v > r1 ? v : r1;
	}
	/* a NaN u (v) makes su (sv) NaN, and so does a NaN sum of others,
	 * which needs an infinite u (v): a px (py) not finite either way */
	nan = su != su || sv != sv;
	bx->lb = persp ? sqrt(dist2) : depth;
	bx->lb -= 0x1p-30 * (fabs(bx->lb) + 1);
	if (front && !nan) {
		lo[0] = 0.5 * cam->w * (1 + q0 / cam->half_w);
		hi[0] = 0.5 * cam->w * (1 + q1 / cam->half_w);
		lo[1] = 0.5 * cam->h * (1 - r1 / cam->half_h);
		hi[1] = 0.5 * cam->h * (1 - r0 / cam->half_h);
		front = isfinite(lo[0]) && isfinite(hi[0]) &&
		    isfinite(lo[1]) && isfinite(hi[1]);
	}
	if (!front || nan) {
		bx->fp[0] = 0;
		bx->fp[1] = 0;
		bx->fp[2] = cam->w - 1;
		bx->fp[3] = cam->h - 1;
	} else {
		double x0 = floor_fin(lo[0]) - 1, x1 = -floor_fin(-hi[0]) + 1;
		double y0 = floor_fin(lo[1]) - 1, y1 = -floor_fin(-hi[1]) + 1;

		if (x1 < 0 || y1 < 0 || x0 > cam->w || y0 > cam->h)
			return 0;
		bx->fp[0] = x0 < 0 ? 0 : (int32_t)x0;
		bx->fp[1] = y0 < 0 ? 0 : (int32_t)y0;
		bx->fp[2] = x1 > cam->w - 1 ? cam->w - 1 : (int32_t)x1;
		bx->fp[3] = y1 > cam->h - 1 ? cam->h - 1 : (int32_t)y1;
	}
	return 1;
}

/* bins_cap: the most boxes, and bin entries, a frame's bins may hold: 8 a
 * pixel and a margin (beyond that they cost more than they save, and
 * their memory stays bounded by the image), and never past what a 4-byte
 * index reaches */
static int64_t
bins_cap(const vx_camera *cam)
{
	int64_t cap = 8 * (int64_t)cam->w * cam->h + 65536;

	return cap < (int64_t)UINT32_MAX ? cap : (int64_t)UINT32_MAX;
}

/* fill_ctx: what a band of bins_fill reads */
typedef struct fill_ctx {
	vx_bins *B;
	const vx_cellbox *bx;
	int64_t n;
	int nband, pass;
} fill_ctx;

/* fill_band: band t of bins_fill's pass: its rows' counts and pixel bits
 * (pass 0), or their lists (pass 1) */
static int
fill_band(void *ctx, void *lp, const vx_par_block *blk)
{
	const fill_ctx *F = ctx;
	vx_bins *B = F->B;
	const vx_cellbox *bx = F->bx;
	const int64_t n = F->n;
	const int pass = F->pass, nband = F->nband, t = (int)blk->index;
	int r0 = (int)((int64_t)B->nby * t / nband);
	int r1 = (int)((int64_t)B->nby * (t + 1) / nband);
	int64_t *cnt = B->off + 1, *cur = B->off;
	uint64_t *pix = B->pix;
	uint32_t *list = B->list;
	double *lbs = B->lb;
	uint64_t *mks = B->mk;

	(void)lp;
	for (int64_t b = 0; b < n; b++) {
		const uint32_t *fp = (const uint32_t *)bx[b].fp;
		int fy0 = (int)(fp[1] / VX_BIN), fy1 = (int)(fp[3] / VX_BIN);
		int x0 = (int)(fp[0] / VX_BIN), x1 = (int)(fp[2] / VX_BIN);
		int y0 = fy0 > r0 ? fy0 : r0;
		int y1 = fy1 < r1 - 1 ? fy1 : r1 - 1;
		/* the footprint's pixels of a bin, as pix
		 * lays them out: those of its columns (all but
		 * the first and last bins' columns: all of
		 * them) in each of its rows, one byte a row: a
		 * row's bits times a 1 in each of those rows'
		 * bytes (no carries: the bits fit a byte) */
		uint64_t xlo = (uint64_t)1 << fp[0] % VX_BIN;
		uint64_t xhi = (uint64_t)2 << fp[2] % VX_BIN;

		for (int r = y0; r <= y1; r++) {
			int64_t k0 = (int64_t)r * B->nbx;
			unsigned ya = r == fy0 ? fp[1] % VX_BIN : 0;
			unsigned yb = r == fy1 ? fp[3] % VX_BIN : VX_BIN - 1;
			uint64_t col;

			/* rows ya..yb (none: an empty footprint,
			 * one row past the image) */
			col = UINT64_C(0x0101010101010101) >>
			    VX_BIN * (VX_BIN - 1 - yb) &
			    UINT64_C(0x0101010101010101) << VX_BIN * ya;
			for (int x = x0; x <= x1; x++) {
				uint64_t row = (x == x1 ? xhi :
				    (uint64_t)1 << VX_BIN) -
				    (x == x0 ? xlo : 1);

				if (pass == 1) {
					int64_t p = cur[k0 + x]++;

					list[p] = (uint32_t)b;
					lbs[p] = bx[b].lb;
					mks[p] = row * col;
					continue;
				}
				cnt[k0 + x]++;
				pix[k0 + x] |= row * col;
			}
		}
	}
	return 0;
}

/* bins_fill: the bins of boxes bx[0..n) (placed, sorted by lb): each box
 * in every bin its footprint overlaps, in order, and the bins' pixel bits.
 * Parallel over bands of rows of bins, one a thread (a band owns its rows'
 * counts and lists: the same lists whatever the threads).  1: more entries
 * than the bound (no bins made), 0 done, or VX_ENOMEM. */
static int
bins_fill(vx_bins *B, vx_par *team, const vx_camera *cam,
    const vx_cellbox *bx, int64_t n, vx_err *e)
{
	int64_t nbin = (int64_t)B->nbx * B->nby, i;
	fill_ctx F = { B, bx, n, team->nthreads < B->nby ? team->nthreads :
	    B->nby, 0 };
	vx_par_loop bands = VX_PAR_ITEMS(F.nband, 1);

	memset(B->off, 0, (size_t)(nbin + 1) * sizeof *B->off);
	memset(B->pix, 0, (size_t)nbin * sizeof *B->pix);
	for (F.pass = 0; F.pass < 2; F.pass++) {
		vx_par_run(team, &bands, fill_band, &F, NULL);
		if (F.pass == 1)
			break;
		for (i = 0; i < nbin; i++)
			B->off[i + 1] += B->off[i];
		/* more entries than a few per pixel (an eye among the
		 * macrocells: boxes spanning the image) */
		if (B->off[nbin] > bins_cap(cam))
			return 1;
		i = B->off[nbin] > 0 ? B->off[nbin] : 1;
		if ((B->list = malloc((size_t)i * sizeof *B->list)) ==
		    NULL ||
		    (B->lb = malloc((size_t)i * sizeof *B->lb)) == NULL ||
		    (B->mk = malloc((size_t)i * sizeof *B->mk)) == NULL)
			return vx_err_set(e, VX_ENOMEM, "bins: out of memory");
		/* binoff[k], bin k's start, is its cursor as it fills */
	}
	/* binoff[k] is now bin k's end, the next one's start: shift back */
	memmove(B->off + 1, B->off, (size_t)nbin * sizeof *B->off);
	B->off[0] = 0;
	return 0;
}

/* lists_free: the bins' entries freed (their pointers NULL) */
static void
lists_free(vx_bins *B)
{
	free(B->list);
	free(B->lb);
	free(B->mk);
	B->list = NULL;
	B->lb = NULL;
	B->mk = NULL;
}

void
vx_bins_drop(vx_bins *B)
{
	lists_free(B);
	free(B->off);
	free(B->pix);
	free(B->box);
	B->off = NULL;
	B->pix = NULL;
	B->box = NULL;
}

void
vx_bins_free(vx_bins *B)
{
	if (B == NULL)
		return;
	vx_bins_drop(B);
	free(B->brk);
	free(B->mc);
	B->brk = NULL;
	B->mc = NULL;
	B->nbr = 0;
}

/* bin_buf: a thread's state in vx_bins_build: its boxes, and what its
 * macrocells added to the counts */
typedef struct bin_buf {
	_Alignas(64) vx_cellbox *b;
	int64_t n, cap;
	int64_t nwhole;          /* macrocells binned whole */
	int id;                  /* the thread */
} bin_buf;

/* What the parallel passes of vx_bins_build read and write. */
typedef struct build_ctx {
	vx_bins *B;
	const vx_grid *g;
	const vx_macro *m;
	const vx_camera *cam;
	vx_cellmask *mask;
	int sub;                 /* the block edge, or 0: whole macrocells */
	int64_t nblk;            /* the most blocks a macrocell has */
	int64_t cap;             /* bins_cap */
	_Atomic int64_t total;   /* boxes counted so far */
	int64_t *off, *keep, *at;
	int *thr;
} build_ctx;

/* place_whole: bracketing macrocell k's whole box, placed (lb NaN: off
 * the image) */
static int
place_whole(void *ctx, void *lp, const vx_par_block *blk)
{
	build_ctx *C = ctx;
	vx_cellbox *w = &C->B->mc[blk->index];

	(void)lp;
	vx_macro_cell_box(C->m, 1, C->B->brk[blk->index], w->lo, w->hi);
	if (!box_place(C->g, C->cam, w))
		w->lb = NAN;
	return 0;
}

/* count_boxes: bracketing macrocell k in view: how many boxes (its blocks
 * that hold a bracketing leaf, building its bits, or itself) into
 * off[k + 1], and those on the image, placed, into the thread's buffer
 * (keep[k] of them from at[k] of thread thr[k]'s) */
static int
count_boxes(void *ctx, void *lp, const vx_par_block *blk)
{
	build_ctx *C = ctx;
	bin_buf *T = lp;
	const int64_t k = blk->index, mc = C->B->brk[k];   /* the macrocell */
	int blocks = C->sub && vx_cellmask_block_built(C->mask, mc);
	int64_t room = blocks ? C->nblk : 1, c, j, kept;
	const vx_cellbox *whole = &C->B->mc[k];
	vx_cellbox *out;

	C->off[k + 1] = C->keep[k] = 0;
	if (whole->lb != whole->lb)
		return 0;     /* off the image */
	if (!blocks)
		T->nwhole++;
	/* past the bound: the rest need not be counted (the count passes it
	 * whatever they hold) */
	if (atomic_load_explicit(&C->total, memory_order_relaxed) > C->cap)
		return 0;
	if (T->n + room > T->cap) {
		int64_t nc = 2 * T->cap > T->n + room ? 2 * T->cap :
		    T->n + room + 1024;
		vx_cellbox *nbuf = realloc(T->b, (size_t)nc * sizeof *nbuf);

		if (nbuf == NULL)
			return VX_ENOMEM;
		T->b = nbuf;
		T->cap = nc;
	}
	out = T->b + T->n;
	if (!blocks) {
		/* placed: on the image */
		out[0] = *whole;
		c = kept = 1;
	} else {
		/* its bits are built and do not change */
		c = (int64_t)vx_cellmask_boxes(C->mask, mc, C->sub, out);
		for (j = 0, kept = 0; j < c; j++)
			if (box_place(C->g, C->cam, &out[j]))
				out[kept++] = out[j];
	}
	C->off[k + 1] = c;
	C->keep[k] = kept;
	C->at[k] = T->n;
	C->thr[k] = T->id;
	T->n += kept;
	atomic_fetch_add_explicit(&C->total, c, memory_order_relaxed);
	return 0;
}

/* buf_start: thread t's buffer, emptied for a pass (its memory kept) */
static int
buf_start(void *ctx, void *lp, int t)
{
	bin_buf *T = lp;

	(void)ctx;
	T->id = t;
	T->n = 0;
	T->nwhole = 0;
	return 0;
}

/* buf_whole: the threads' counts of whole macrocells, summed */
static int
buf_whole(void *ctx, void *lp, int t)
{
	*(int64_t *)ctx += ((bin_buf *)lp)->nwhole;
	return 0;
}

static int
buf_free(void *ctx, void *lp, int t)
{
	bin_buf *T = lp;

	(void)ctx;
	free(T->b);
	T->b = NULL;
	T->n = T->cap = 0;
	return 0;
}

void
vx_bins_init(vx_bins *B)
{
	memset(B, 0, sizeof *B);
}

/* The work is one parallel pass over the bracketing macrocells, each
 * thread keeping the placed boxes on the image of the macrocells it takes
 * (and counting all of them, for the bound, until the count passes it:
 * then no more are looked at), then the macrocells' boxes gathered in
 * their order: so the order, and the memory, are those of the boxes,
 * whatever the threads. */
int
vx_bins_build(vx_bins *B, const vx_camera *cam, const vx_grid *g,
    const vx_macro *m, const float *vals, int nvals, vx_cellmask *mask,
    int block, int nthreads, vx_err *e)
{
	int64_t nb = m->dims[1][0] * m->dims[1][1] * m->dims[1][2], b, n, k;
	int64_t nbr, nwhole;
	vx_cellbox *box = NULL;
	vx_par team;
	build_ctx C;
	int rc = 0;

	memset(&C, 0, sizeof C);
	C.B = B;
	C.g = g;
	C.m = m;
	C.cam = cam;
	C.mask = mask;
	C.cap = bins_cap(cam);
	C.nblk = 1;
	C.sub = mask == NULL || !mask->ready ? 0 : block;
	if (vx_par_init(&team, nthreads, sizeof(bin_buf), e) != 0) {
		vx_bins_free(B);
		return vx_err_push(e, "bins");
	}
	B->nbx = (cam->w + VX_BIN - 1) / VX_BIN;
	B->nby = (cam->h + VX_BIN - 1) / VX_BIN;
	if ((B->off = calloc((size_t)B->nbx * B->nby + 1,
	    sizeof *B->off)) == NULL ||
	    (B->pix = calloc((size_t)B->nbx * B->nby,
	    sizeof *B->pix)) == NULL)
		goto nomem;
	/* the bracketing macrocells (the parallel passes run over them) and
	 * their whole boxes, placed: made by the first build */
	if (B->brk == NULL) {
		if ((B->brk = malloc((size_t)(nb > 0 ? nb : 1) *
		    sizeof *B->brk)) == NULL)
			goto nomem;
		if (mask != NULL && mask->ready) {
			/* the mask's list: the same test (its values are
			 * these isovalues), made once for all frames */
			nbr = mask->nset;
			memcpy(B->brk, mask->set, (size_t)nbr *
			    sizeof *B->brk);
		} else
			for (nbr = 0, b = 0; b < nb; b++)
				if (vx_macro_cell_brackets(m, 1, b, vals, nvals))
					B->brk[nbr++] = b;
		if ((B->mc = malloc((size_t)(nbr > 0 ? nbr : 1) *
		    sizeof *B->mc)) == NULL)
			goto nomem;
		B->nbr = nbr;
		vx_par_loop mcs = VX_PAR_ITEMS(nbr, 8);

		vx_par_run(&team, &mcs, place_whole, &C, NULL);
	}
	nbr = B->nbr;
	if ((C.off = malloc((size_t)(nbr + 1) * sizeof *C.off)) == NULL ||
	    (C.keep = malloc((size_t)(nbr > 0 ? nbr : 1) * sizeof *C.keep)) ==
	    NULL || (C.at = malloc((size_t)(nbr > 0 ? nbr : 1) *
	    sizeof *C.at)) == NULL || (C.thr = malloc((size_t)(nbr > 0 ?
	    nbr : 1) * sizeof *C.thr)) == NULL)
		goto nomem;
	/* the most blocks a macrocell has */
	for (int a = 0; a < 3 && C.sub; a++)
		C.nblk *= (m->width[1][a] + C.sub - 1) / C.sub;
	for (;;) {
		vx_par_loop mcs = VX_PAR_ITEMS(nbr, 8);

		atomic_store_explicit(&C.total, 0, memory_order_relaxed);
		vx_par_each(&team, buf_start, NULL);
		if (vx_par_run(&team, &mcs, count_boxes, &C, NULL) != 0)
			goto nomem;
		nwhole = 0;
		vx_par_each(&team, buf_whole, &nwhole);
		for (C.off[0] = 0, k = 0; k < nbr; k++)
			C.off[k + 1] += C.off[k];
		if (C.off[nbr] > C.cap && C.sub) {
			C.sub = 0;   /* too many blocks: whole macrocells */
			continue;
		}
		if (C.off[nbr] > C.cap) {
			rc = 1;
			break;
		}
		/* the boxes on the image, in the macrocells' order */
		for (n = 0, k = 0; k < nbr; k++)
			n += C.keep[k];
		free(box);
		if ((box = malloc((size_t)(n > 0 ? n : 1) * sizeof *box)) ==
		    NULL)
			goto nomem;
		for (n = 0, k = 0; k < nbr; k++)
			if (C.keep[k] > 0) {
				const bin_buf *T = vx_par_local(&team,
				    C.thr[k]);

				memcpy(box + n, T->b + C.at[k], (size_t)C.keep[k] *
				    sizeof *box);
				n += C.keep[k];
			}
		if (box_sort(&box, n) != 0)
			goto nomem;
		B->block = C.sub;
		B->nboxes = n;
		B->nwhole = nwhole;
		lists_free(B);
		if ((rc = bins_fill(B, &team, cam, box, n, e)) != 1 || !C.sub)
			break;
		C.sub = 0;   /* too many entries: whole macrocells */
	}
	vx_par_each(&team, buf_free, NULL);
	vx_par_free(&team);
	free(C.thr);
	free(C.at);
	free(C.keep);
	free(C.off);
	if (rc != 0) {
		free(box);
		vx_bins_free(B);
		return rc == 1 ? 0 : rc;
	}
	B->box = box;
	return 0;
nomem:
	vx_par_each(&team, buf_free, NULL);
	vx_par_free(&team);
	free(C.thr);
	free(C.at);
	free(C.keep);
	free(box);
	free(C.off);
	vx_bins_free(B);
	return vx_err_set(e, VX_ENOMEM, "bins: out of memory");
}
