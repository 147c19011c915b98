/* raycast.c: the ray-cast isosurface renderer (see vx_raycast.h).  One
 * shading and compositing path serves two surface sources: a volume
 * (vx_iso_trace in index space) and a tet mesh (vx_tetleaf_trace in world
 * space); each turns its hits into an rc_surf and traces its own shadow
 * rays. */
#include "vx_raycast.h"
#include "vx_gi.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vx_camera.h"
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#ifdef _OPENMP
#include <omp.h>
#endif

/* What every thread reads. */
typedef struct rc_shared {
	const vx_scene *s;
	const vx_plan *p;
	const vx_grid *g;
	const vx_grid *const *tex;
	const vx_raycast_opts *o;
	vx_iso_tracer tr;
	const vx_tetmesh *mesh;       /* non-NULL: draw this mesh, not g */
	const vx_tetleaf *lg;         /* its leaf grid */
	double mesh_off;              /* shadow-ray offset, world units */
	double isod[VX_ISO_MAX];      /* the isovalues as double (meshes) */
	float iso[VX_ISO_MAX];        /* drawn isovalues */
	int surf[VX_ISO_MAX];         /* iso index -> scene surface index */
	int niso;
	int composite;
	double tex_lo[VX_SCENE_MAX_SURFACES], tex_hi[VX_SCENE_MAX_SURFACES];
	/* binning: boxes holding every cell that brackets an isovalue
	 * (bins_build), listed per bin of BIN x BIN pixels whose primary
	 * rays may cross them, by a lower bound of their entry time (bin k:
	 * binlist[binoff[k] .. binoff[k + 1])); NULL: off */
	int nbx, nby;
	int bin_block;                /* the block edge, or 0: whole macrocells */
	int64_t bin_boxes;            /* boxes binned */
	int64_t bin_whole;            /* of them whole macrocells */
	int64_t *binoff;
	vx_cellbox *binbox;           /* the boxes, sorted by lb */
	uint32_t *binlist;            /* bins' entries: indices into binbox */
	double *binlb;                /* per entry: its box's lb */
	uint64_t *binmk;              /* per entry: the pixels of its bin its
	                                 box's footprint holds, as binpix */
	uint64_t *binpix;             /* per bin: bit (y % BIN) BIN + x % BIN
	                                 set where a box's footprint holds
	                                 pixel (x, y) (BIN 8: one word) */
	/* bins_build's, kept from one build to the next (the same view and
	 * macrocells): the bracketing level-1 macrocells and their whole
	 * boxes, placed (lb NaN: off the image); NULL: none yet */
	int64_t binnbr, *binbrk;
	vx_cellbox *binmc;
} rc_shared;

#define BIN 8

#define EM_SLOTS 4   /* entry masks kept: a tile's bins (16 x 16 pixels) */

/* What each thread owns: on cache lines of its own (the counters are
 * written per cell; neighbours sharing a line would slow both threads). */
typedef struct rc_local {
	_Alignas(64) vx_iso_stats st;
	vx_tettrace_stats tst;
	uint64_t primary, shadow, shaded, covered, binned, irr_missing;
	uint64_t paths, gi_rays;
	uint64_t cyc_total, cyc_shade, cyc_shadow;
	double busy;                  /* seconds in tiles */
	/* the entry masks of the bins last walked (bin_em): em[s][p], bit
	 * k: the bin's k-th entry holds pixel p; em_bin[s]: the bin, -1
	 * none; em_ok[s]: 0 for a bin of more than 64 entries */
	int64_t em_bin[EM_SLOTS];
	int em_ok[EM_SLOTS], em_next;
	uint64_t em[EM_SLOTS][BIN * BIN];
} rc_local;

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
box_place(const rc_shared *S, const vx_camera *cam, vx_cellbox *bx)
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
		double w0 = S->g->origin[a] + (double)bx->lo[a] *
		    S->g->spacing[a] - cam->o[a];
		double w1 = S->g->origin[a] + (double)bx->hi[a] *
		    S->g->spacing[a] - cam->o[a];

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

/* bins_fill: the bins of boxes bx[0..n) (placed, sorted by lb): each box
 * in every bin its footprint overlaps, in order, and the bins' pixel bits.
 * Parallel over bands of rows of bins, one a thread (a thread owns its
 * rows' counts and lists: the same lists whatever the threads).  1: more
 * entries than the bound (no bins made), 0 done, or VX_ENOMEM. */
static int
bins_fill(rc_shared *S, const vx_camera *cam, const vx_cellbox *bx,
    int64_t n, int nthr, vx_err *e)
{
	int64_t nbin = (int64_t)S->nbx * S->nby, i;
	int nband = nthr < S->nby ? nthr : S->nby, pass, t;

	memset(S->binoff, 0, (size_t)(nbin + 1) * sizeof *S->binoff);
	memset(S->binpix, 0, (size_t)nbin * sizeof *S->binpix);
	for (pass = 0; pass < 2; pass++) {
#ifdef _OPENMP
#pragma omp parallel for num_threads(nband) schedule(static, 1)
#endif
		for (t = 0; t < nband; t++) {
			int r0 = (int)((int64_t)S->nby * t / nband);
			int r1 = (int)((int64_t)S->nby * (t + 1) / nband);
			int64_t *cnt = S->binoff + 1, *cur = S->binoff;
			uint64_t *pix = S->binpix;
			uint32_t *list = S->binlist;
			double *lbs = S->binlb;
			uint64_t *mks = S->binmk;

			for (int64_t b = 0; b < n; b++) {
				const uint32_t *fp = (const uint32_t *)bx[b].fp;
				int fy0 = (int)(fp[1] / BIN), fy1 = (int)(fp[3] / BIN);
				int x0 = (int)(fp[0] / BIN), x1 = (int)(fp[2] / BIN);
				int y0 = fy0 > r0 ? fy0 : r0;
				int y1 = fy1 < r1 - 1 ? fy1 : r1 - 1;
				/* the footprint's pixels of a bin, as binpix
				 * lays them out: those of its columns (all but
				 * the first and last bins' columns: all of
				 * them) in each of its rows, one byte a row: a
				 * row's bits times a 1 in each of those rows'
				 * bytes (no carries: the bits fit a byte) */
				uint64_t xlo = (uint64_t)1 << fp[0] % BIN;
				uint64_t xhi = (uint64_t)2 << fp[2] % BIN;

				for (int r = y0; r <= y1; r++) {
					int64_t k0 = (int64_t)r * S->nbx;
					unsigned ya = r == fy0 ? fp[1] % BIN : 0;
					unsigned yb = r == fy1 ? fp[3] % BIN : BIN - 1;
					uint64_t col;

					/* rows ya..yb (none: an empty footprint,
					 * one row past the image) */
					col = UINT64_C(0x0101010101010101) >>
					    BIN * (BIN - 1 - yb) &
					    UINT64_C(0x0101010101010101) << BIN * ya;
					for (int x = x0; x <= x1; x++) {
						uint64_t row = (x == x1 ? xhi :
						    (uint64_t)1 << BIN) -
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
		}
		if (pass == 1)
			break;
		for (i = 0; i < nbin; i++)
			S->binoff[i + 1] += S->binoff[i];
		/* more entries than a few per pixel (an eye among the
		 * macrocells: boxes spanning the image) */
		if (S->binoff[nbin] > bins_cap(cam))
			return 1;
		i = S->binoff[nbin] > 0 ? S->binoff[nbin] : 1;
		if ((S->binlist = malloc((size_t)i * sizeof *S->binlist)) ==
		    NULL ||
		    (S->binlb = malloc((size_t)i * sizeof *S->binlb)) == NULL ||
		    (S->binmk = malloc((size_t)i * sizeof *S->binmk)) == NULL)
			return vx_err_set(e, VX_ENOMEM, "raycast: out of memory "
			    "(bins)");
		/* binoff[k], bin k's start, is its cursor as it fills */
	}
	/* binoff[k] is now bin k's end, the next one's start: shift back */
	memmove(S->binoff + 1, S->binoff, (size_t)nbin * sizeof *S->binoff);
	S->binoff[0] = 0;
	return 0;
}

/* bins_drop: no bins (S's lists freed, their pointers NULL; what
 * bins_build keeps from one build to the next stays) */
static void
bins_drop(rc_shared *S)
{
	free(S->binoff);
	free(S->binpix);
	free(S->binbox);
	free(S->binlist);
	free(S->binlb);
	free(S->binmk);
	S->binoff = NULL;
	S->binpix = NULL;
	S->binbox = NULL;
	S->binlist = NULL;
	S->binlb = NULL;
	S->binmk = NULL;
}

/* bins_free: no bins, and nothing kept for the next build */
static void
bins_free(rc_shared *S)
{
	bins_drop(S);
	free(S->binbrk);
	free(S->binmc);
	S->binbrk = NULL;
	S->binmc = NULL;
	S->binnbr = 0;
}

/* bin_buf: a thread's boxes in bins_build (on cache lines of its own) */
typedef struct bin_buf {
	_Alignas(64) vx_cellbox *b;
	int64_t n, cap;
} bin_buf;

/* bins_build: S->binoff / binbox / binlist / binpix: the primary rays'
 * bins of BIN x BIN pixels, each listing, by a lower bound of their entry
 * time, the boxes a ray of the bin may enter among those that hold every
 * leaf that brackets an isovalue: with a cell mask, the blocks of sub^3
 * leaves (sub: the option's bin_block, else VX_RAYCAST_BLOCK) that hold a
 * bracketing leaf, of the bracketing level-1 macrocells
 * whose bits are built; else (bits not built, no mask, or the blocks or
 * their lists would pass the bound of bins_fill) those macrocells whole.
 * Conservative: a primary ray that enters such a box lies in its
 * footprint.  More than the bound with whole macrocells too: no bins
 * (S->binoff NULL; the rays walk from the eye).  The work is one parallel
 * pass over the macrocells, each thread keeping the placed boxes on the
 * image of the macrocells it takes (and counting all of them, for the
 * bound, until the count passes it: then no more are looked at), then
 * the macrocells' boxes gathered in their order: so the order, and the
 * memory, are those of the boxes, whatever the threads.  The bracketing
 * macrocells, and their whole boxes placed, are kept in S for the next
 * build of the same frame (after bins_drop; bins_free frees them).
 * Returns 0, or VX_ENOMEM. */
static int
bins_build(rc_shared *S, const vx_camera *cam, vx_cellmask *mask, vx_err *e)
{
	const vx_macro *m = S->tr.m;
	int64_t nb = m->dims[1][0] * m->dims[1][1] * m->dims[1][2], b, n, k;
	int64_t nbr, *brk, *off = NULL, *keep = NULL, *at = NULL;
	int64_t cap = bins_cap(cam), nwhole = 0, nblk = 1;
	int *thr = NULL;
	bin_buf *buf = NULL;
	vx_cellbox *box = NULL;
	int sub = mask == NULL || !mask->ready ? 0 : S->o->bin_block > 0 ?
	    S->o->bin_block : VX_RAYCAST_BLOCK, rc = 0, nthr, t;

#ifdef _OPENMP
	nthr = S->o->nthreads > 0 ? S->o->nthreads : omp_get_num_procs();
#else
	nthr = 1;
#endif
	S->nbx = (cam->w + BIN - 1) / BIN;
	S->nby = (cam->h + BIN - 1) / BIN;
	if ((S->binoff = calloc((size_t)S->nbx * S->nby + 1,
	    sizeof *S->binoff)) == NULL ||
	    (S->binpix = calloc((size_t)S->nbx * S->nby,
	    sizeof *S->binpix)) == NULL ||
	    (buf = aligned_alloc(_Alignof(bin_buf), (size_t)nthr *
	    sizeof *buf)) == NULL)
		goto nomem;
	memset(buf, 0, (size_t)nthr * sizeof *buf);
	/* the bracketing macrocells (the parallel loop runs over them) and
	 * their whole boxes, placed: made by the first build */
	if (S->binbrk == NULL) {
		if ((S->binbrk = malloc((size_t)(nb > 0 ? nb : 1) *
		    sizeof *S->binbrk)) == NULL)
			goto nomem;
		if (mask != NULL && mask->ready) {
			/* the mask's list: the same test (its values are
			 * these isovalues), made once for all frames */
			nbr = mask->nset;
			memcpy(S->binbrk, mask->set, (size_t)nbr *
			    sizeof *S->binbrk);
		} else
			for (nbr = 0, b = 0; b < nb; b++)
				if (vx_macro_cell_brackets(m, 1, b, S->iso,
				    S->niso))
					S->binbrk[nbr++] = b;
		if ((S->binmc = malloc((size_t)(nbr > 0 ? nbr : 1) *
		    sizeof *S->binmc)) == NULL)
			goto nomem;
		S->binnbr = nbr;
#ifdef _OPENMP
#pragma omp parallel for num_threads(nthr) schedule(dynamic, 8)
#endif
		for (k = 0; k < nbr; k++) {
			vx_cellbox *w = &S->binmc[k];

			vx_macro_cell_box(m, 1, S->binbrk[k], w->lo, w->hi);
			if (!box_place(S, cam, w))
				w->lb = NAN;
		}
	}
	brk = S->binbrk;
	nbr = S->binnbr;
	if ((off = malloc((size_t)(nbr + 1) * sizeof *off)) == NULL ||
	    (keep = malloc((size_t)(nbr > 0 ? nbr : 1) * sizeof *keep)) ==
	    NULL || (at = malloc((size_t)(nbr > 0 ? nbr : 1) * sizeof *at)) ==
	    NULL || (thr = malloc((size_t)(nbr > 0 ? nbr : 1) * sizeof *thr)) ==
	    NULL)
		goto nomem;
	/* the most blocks a macrocell has */
	for (int a = 0; a < 3 && sub; a++)
		nblk *= (m->width[1][a] + sub - 1) / sub;
	for (;;) {
		_Atomic int64_t total = 0;
		int oom = 0;

		/* each bracketing macrocell in view: how many boxes (its
		 * blocks that hold a bracketing leaf, building its bits, or
		 * itself), and those on the image, placed */
		nwhole = 0;
		for (t = 0; t < nthr; t++)
			buf[t].n = 0;
#ifdef _OPENMP
#pragma omp parallel for num_threads(nthr) schedule(dynamic, 8) \
    reduction(+:nwhole) reduction(|:oom)
#endif
		for (k = 0; k < nbr; k++) {
			const int64_t mc = brk[k];    /* the macrocell */
#ifdef _OPENMP
			bin_buf *B = &buf[omp_get_thread_num()];
#else
			bin_buf *B = &buf[0];
#endif
			int blocks = sub && vx_cellmask_block_built(mask, mc);
			int64_t room = blocks ? nblk : 1, c, j, kept;
			const vx_cellbox *whole = &S->binmc[k];
			vx_cellbox *out;

			off[k + 1] = keep[k] = 0;
			if (whole->lb != whole->lb)
				continue;     /* off the image */
			if (!blocks)
				nwhole++;
			/* past the bound: the rest need not be counted (the
			 * count passes it whatever they hold) */
			if (atomic_load_explicit(&total, memory_order_relaxed) >
			    cap)
				continue;
			if (B->n + room > B->cap) {
				int64_t nc = 2 * B->cap > B->n + room ? 2 *
				    B->cap : B->n + room + 1024;
				vx_cellbox *nbuf = realloc(B->b, (size_t)nc *
				    sizeof *nbuf);

				if (nbuf == NULL) {
					oom = 1;
					continue;
				}
				B->b = nbuf;
				B->cap = nc;
			}
			out = B->b + B->n;
			if (!blocks) {
				/* placed: on the image */
				out[0] = *whole;
				c = kept = 1;
			} else {
				/* its bits are built and do not change */
				c = (int64_t)vx_cellmask_boxes(mask, mc, sub, out);
				for (j = 0, kept = 0; j < c; j++)
					if (box_place(S, cam, &out[j]))
						out[kept++] = out[j];
			}
			off[k + 1] = c;
			keep[k] = kept;
			at[k] = B->n;
#ifdef _OPENMP
			thr[k] = omp_get_thread_num();
#else
			thr[k] = 0;
#endif
			B->n += kept;
			atomic_fetch_add_explicit(&total, c,
			    memory_order_relaxed);
		}
		if (oom)
			goto nomem;
		for (off[0] = 0, k = 0; k < nbr; k++)
			off[k + 1] += off[k];
		if (off[nbr] > cap && sub) {
			sub = 0;     /* too many blocks: whole macrocells */
			continue;
		}
		if (off[nbr] > cap) {
			rc = 1;
			break;
		}
		/* the boxes on the image, in the macrocells' order */
		for (n = 0, k = 0; k < nbr; k++)
			n += keep[k];
		free(box);
		if ((box = malloc((size_t)(n > 0 ? n : 1) * sizeof *box)) ==
		    NULL)
			goto nomem;
		for (n = 0, k = 0; k < nbr; k++)
			if (keep[k] > 0) {
				memcpy(box + n, buf[thr[k]].b + at[k],
				    (size_t)keep[k] * sizeof *box);
				n += keep[k];
			}
		if (box_sort(&box, n) != 0)
			goto nomem;
		S->bin_block = sub;
		S->bin_boxes = n;
		S->bin_whole = nwhole;
		free(S->binlist);
		free(S->binlb);
		free(S->binmk);
		S->binlist = NULL;
		S->binlb = NULL;
		S->binmk = NULL;
		if ((rc = bins_fill(S, cam, box, n, nthr, e)) != 1 || !sub)
			break;
		sub = 0;     /* too many entries: whole macrocells */
	}
	for (t = 0; t < nthr; t++)
		free(buf[t].b);
	free(buf);
	free(thr);
	free(at);
	free(keep);
	free(off);
	if (rc != 0) {
		free(box);
		bins_free(S);
		return rc == 1 ? 0 : rc;
	}
	S->binbox = box;
	return 0;
nomem:
	for (t = 0; buf != NULL && t < nthr; t++)
		free(buf[t].b);
	free(buf);
	free(thr);
	free(at);
	free(keep);
	free(box);
	free(off);
	bins_free(S);
	return vx_err_set(e, VX_ENOMEM, "raycast: out of memory (bins)");
}

void
vx_raycast_opts_init(vx_raycast_opts *o)
{
	memset(o, 0, sizeof *o);
	o->solver = VX_CELL_EXACT;
	o->aa = 1;
	o->tile = 16;
	o->shadow_offset = 1e-3;
}

static double
dot3(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void
normalize3(double a[3])
{
	double l = sqrt(dot3(a, a));

	if (l > 0 && isfinite(l)) {
		a[0] /= l;
		a[1] /= l;
		a[2] /= l;
	}
}

/* sample: the trilinear value of g at world point w, clamped to the box;
 * NaN where a corner is not finite. */
static double
sample(const vx_grid *g, const double w[3])
{
	double p[3], l[3];
	int64_t i[3];
	float c[8];
	int a;

	vx_world_to_index(g, w, p);
	for (a = 0; a < 3; a++) {
		double hi = (double)(g->dims[a] - 1);

		if (!(p[a] >= 0))
			p[a] = 0;
		if (p[a] > hi)
			p[a] = hi;
		i[a] = (int64_t)p[a];
		if (i[a] > g->dims[a] - 2)
			i[a] = g->dims[a] - 2;
		if (i[a] < 0)
			i[a] = 0;
		l[a] = p[a] - (double)i[a];
		if (g->dims[a] == 1)
			l[a] = 0;
	}
	/* a dimension of 1 has no cells: fetch with x+1 clamped by the guard
	 * entry of the offset tables */
	vx_grid_cell(g, i[0], i[1], i[2], c);
	return vx_cell_trilinear(c, l);
}

/* rc_surf: a surface point to shade, whatever source found it. */
typedef struct rc_surf {
	double t;                 /* ray parameter (world distance) */
	int iso;                  /* index into S->iso */
	int entering;             /* the eye ray crossed from f < iso */
	double P[3];              /* world point */
	double n[3];              /* world unit normal, against the ray */
	const double *pi;         /* volume: the point in index space */
} rc_surf;

typedef struct shadow_ctx {
	const rc_shared *S;
	double T;                 /* transmission so far */
	int self_surface;         /* the surface the shadow ray starts on */
	int self_entering;        /* how the eye ray crossed it */
	int first;                /* no crossing seen yet */
} shadow_ctx;

static int
shadow_absorb(shadow_ctx *x, int iso, int entering)
{
	const vx_surface *sf = &x->S->s->surface[x->S->surf[iso]];
	double a = x->S->composite ? sf->m.opacity : 1.0;
	int first = x->first;

	x->first = 0;
	/* The shadow ray leaves the surface on the eye's side, where an
	 * occluder of the same surface is crossed the way the eye ray crossed
	 * it.  A first crossing of that surface the other way means the start
	 * point was a little inside (the root is only as exact as the solver):
	 * the ray is just leaving its own surface, not shadowed by it. */
	if (first && iso == x->self_surface && entering != x->self_entering)
		return 0;
	x->T *= 1.0 - a;
	return x->T <= 1e-4;      /* opaque enough: stop */
}

static int
shadow_hit(void *ctx, const vx_iso_hit *h)
{
	return shadow_absorb(ctx, h->surface, h->entering);
}

static int
shadow_tet_hit(void *ctx, const vx_tethit *h)
{
	return shadow_absorb(ctx, h->iso, h->enter);
}

/* visibility: transmission from surface point h toward a light in unit
 * world direction Ld at distance dist, through every drawn surface. */
static double
visibility(const rc_shared *S, rc_local *L, const rc_surf *h,
    const double Ld[3], double dist)
{
	shadow_ctx x = { S, 1.0, h->iso, h->entering, 1 };
	int a;

	L->shadow++;
	if (S->mesh != NULL) {
		double o[3];

		/* start a small step off the surface, on the lit side */
		for (a = 0; a < 3; a++)
			o[a] = h->P[a] + S->mesh_off * h->n[a];
		vx_tetleaf_trace(S->lg, S->mesh, o, Ld, S->isod, S->niso, 0,
		    dist, shadow_tet_hit, &x, &L->tst);
	} else {
		double oi[3], di[3], ni[3];

		/* start a small step off the surface, on the lit side */
		vx_world_to_index_dir(S->g, h->n, ni);
		normalize3(ni);
		for (a = 0; a < 3; a++)
			oi[a] = h->pi[a] + S->o->shadow_offset * ni[a];
		vx_world_to_index_dir(S->g, Ld, di);
		vx_iso_trace(&S->tr, oi, di, 0, dist, S->iso, S->niso,
		    shadow_hit, &x, &L->st);
	}
	return x.T;
}

/* light_dir: unit direction from world point P toward light k, its
 * distance (INFINITY for directional lights) and radiance. */
static void
light_at(const rc_shared *S, int k, const double P[3], double L[3],
    double *dist, double rad[3])
{
	const vx_light *lt = &S->s->light[k];
	const vx_camera *cam = &S->s->camera;
	double scale = lt->intensity;
	int a, point = 0;

	switch (lt->type) {
	case VX_LIGHT_POINT:
		for (a = 0; a < 3; a++)
			L[a] = lt->position[a] - P[a];
		point = 1;
		break;
	case VX_LIGHT_DIRECTIONAL:
		for (a = 0; a < 3; a++)
			L[a] = -lt->direction[a];
		break;
	case VX_LIGHT_HEADLIGHT:
	default:
		if (cam->projection == VX_ORTHOGRAPHIC) {
			for (a = 0; a < 3; a++)
				L[a] = -cam->fwd[a];
		} else {
			for (a = 0; a < 3; a++)
				L[a] = cam->o[a] - P[a];
			point = 1;
		}
		break;
	}
	/* normalize3(L), with the length it would compute taken from dist
	 * (the same expression: the same bits) */
	{
		double l = sqrt(dot3(L, L));

		*dist = point ? l : INFINITY;
		if (l > 0 && isfinite(l))
			for (a = 0; a < 3; a++)
				L[a] /= l;
	}
	if (point && lt->falloff == VX_FALLOFF_INVERSE_SQUARE && *dist > 0)
		scale /= *dist * *dist;
	for (a = 0; a < 3; a++)
		rad[a] = lt->color[a] * scale;
}

/* shade: outgoing radiance at surface point h seen along world direction
 * dw. */
static void
shade(const rc_shared *S, rc_local *L, const rc_surf *h,
    const double dw[3], double col[3])
{
	const vx_scene *s = S->s;
	const vx_plan *p = S->p;
	int k = S->surf[h->iso], a, l;
	const vx_material *m = &s->surface[k].m;
	const double *n = h->n, *P = h->P;
	double V[3] = { 0, 0, 0 }, alb[3], amb[3];

	/* the view direction only for a highlight (its square root and
	 * divisions are in each hit's chain of dependent operations) */
	if (p->specular && m->ks > 0) {
		for (a = 0; a < 3; a++)
			V[a] = -dw[a];
		normalize3(V);
	}
	if (p->texture_on[k] && S->tex[k] != NULL) {
		double v = sample(S->tex[k], P);
		double t = (v - S->tex_lo[k]) / (S->tex_hi[k] - S->tex_lo[k]);

		if (!isfinite(t))
			t = 0;
		vx_colormap_eval(m->colormap, t, alb);
	} else
		memcpy(alb, m->color, sizeof alb);
	if (p->pathtrace) {
		const vx_gi *gi = S->o->gi;
		vx_gi_stats gs;
		double E[3] = { 0, 0, 0 }, D[3], isov = S->iso[h->iso];
		int high = !h->entering;     /* the eye's side is lit */
		uint64_t stream = 0xcbf29ce484222325u, bits;

		/* a stream per hit point: the same for any thread count */
		for (a = 0; a < 3; a++) {
			memcpy(&bits, &h->pi[a], sizeof bits);
			stream = (stream ^ bits) * 0x100000001b3u;
		}
		memset(&gs, 0, sizeof gs);
		vx_gi_direct(gi, P, h->pi, n, isov, high, D, &gs);
		for (l = 0; l < s->pt_samples; l++) {
			double r[3];

			vx_gi_sample(gi, h->pi, n, isov, high, D, stream,
			    (uint64_t)l, r, &gs);
			for (a = 0; a < 3; a++)
				E[a] += r[a];
		}
		for (a = 0; a < 3; a++)
			col[a] = m->kd * alb[a] * E[a] / s->pt_samples *
			    (1 / 3.14159265358979323846);
		L->paths += gs.samples;
		L->gi_rays += gs.rays + gs.shadow_rays;
		L->shaded++;
		return;
	}
	if (p->irradiance) {
		double E[3];

		/* Lambertian under the baked irradiance: a kd E / pi */
		if (S->o->irr_need != NULL) {
			vx_irr_reach(S->o->irr, h->pi, S->o->irr_interp,
			    S->o->irr_need, S->o->irr_need_ctx);
			col[0] = col[1] = col[2] = 0;
			L->shaded++;
			return;
		}
		if (!vx_irr_lookup(S->o->irr, h->pi, S->o->irr_interp, S->g,
		    S->iso[h->iso], E))
			L->irr_missing++;
		for (a = 0; a < 3; a++)
			col[a] = m->kd * alb[a] * E[a] * (1 / 3.14159265358979323846);
		L->shaded++;
		return;
	}
	for (a = 0; a < 3; a++) {
		amb[a] = s->ambient[a] * s->ambient_intensity;
		col[a] = amb[a] * alb[a];
	}
	for (l = 0; l < s->nlight; l++) {
		double Ld[3], rad[3], dist, ndl, vis = 1, spec = 0;

		if (!p->light_on[l])
			continue;
		light_at(S, l, P, Ld, &dist, rad);
		ndl = dot3(n, Ld);
		if (!(ndl > 0))
			continue;
		if (p->shadow_on[l]) {
			uint64_t c0 = S->o->timing ? vx_cycles() : 0;

			vis = visibility(S, L, h, Ld, dist);
			if (S->o->timing)
				L->cyc_shadow += vx_cycles() - c0;
			if (vis <= 1e-4)
				continue;
		}
		if (p->specular && m->ks > 0) {
			double H[3];

			for (a = 0; a < 3; a++)
				H[a] = Ld[a] + V[a];
			normalize3(H);
			double ndh = dot3(n, H);
			if (ndh > 0)
				spec = m->ks * pow(ndh, m->shininess);
		}
		for (a = 0; a < 3; a++)
			col[a] += vis * rad[a] * (m->kd * alb[a] * ndl + spec);
	}
	L->shaded++;
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
composite(layer_ctx *x, const rc_surf *h, uint64_t c0)
{
	const rc_shared *S = x->S;
	const vx_surface *sf = &S->s->surface[S->surf[h->iso]];
	double a = S->composite ? sf->m.opacity : 1.0, col[3];
	int i;

	shade(S, x->L, h, x->dw, col);
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
	rc_surf sp;

	sp.t = h->t;
	sp.iso = h->surface;
	sp.entering = h->entering;
	vx_iso_normal(S->g, h, x->dw, sp.n);
	vx_index_to_world(S->g, h->p, sp.P);
	sp.pi = h->p;
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
	rc_surf sp;
	int a;

	sp.t = h->t;
	sp.iso = h->iso;
	sp.entering = h->enter;
	memcpy(sp.n, h->n, sizeof sp.n);
	if (dot3(sp.n, x->dw) > 0)
		for (a = 0; a < 3; a++)
			sp.n[a] = -sp.n[a];
	for (a = 0; a < 3; a++)
		sp.P[a] = x->ow[a] + h->t * x->dw[a];
	sp.pi = NULL;
	return composite(x, &sp, c0);
}

/* bin_row: the pixel bits of bin (bx, by) in its pixel row y (bit x % BIN
 * set where a box's footprint holds pixel (x, y)) */
static inline unsigned
bin_row(const rc_shared *S, int bx, int by, int y)
{
	return (unsigned)(S->binpix[(int64_t)by * S->nbx + bx] >>
	    (y - by * BIN) * BIN) & ((1u << BIN) - 1);
}

/* bin_of: the bin of sample point (px, py) in *bin; returns its bit in
 * binpix (0: no box's footprint holds the pixel) */
static inline int
bin_of(const rc_shared *S, double px, double py, int64_t *bin)
{
	int bx = (int)px / BIN, by = (int)py / BIN;

	bx = bx < 0 ? 0 : bx >= S->nbx ? S->nbx - 1 : bx;
	by = by < 0 ? 0 : by >= S->nby ? S->nby - 1 : by;
	*bin = (int64_t)by * S->nbx + bx;
	return (int)(bin_row(S, bx, by, (int)py) >> ((int)px - bx * BIN) & 1);
}

/* em_make: em[p], bit k set where the k-th entry of bin's list (of n <=
 * 64 entries, pixel bits mk[0..n)) holds pixel p: the 64 x n bit matrix
 * transposed, 16 entries at a time where SSE2 has movemask (a byte of
 * mk per row of the bin; bit x of row y's byte is pixel y BIN + x) */
static void
em_make(const uint64_t *mk, int64_t n, uint64_t em[BIN * BIN])
{
	memset(em, 0, BIN * BIN * sizeof *em);
#if defined(__SSE2__) && BIN == 8
	for (int64_t k0 = 0; k0 < n; k0 += 16) {
		_Alignas(16) unsigned char t[BIN][16];
		int nk = n - k0 < 16 ? (int)(n - k0) : 16;

		memset(t, 0, sizeof t);
		for (int k = 0; k < nk; k++)
			for (int y = 0; y < BIN; y++)
				t[y][k] = (unsigned char)(mk[k0 + k] >> BIN * y);
		for (int y = 0; y < BIN; y++) {
			__m128i v = _mm_load_si128((const __m128i *)(const void *)
			    t[y]);

			/* bit x of each byte to its top, for movemask (a
			 * 64-bit shift: what crosses into the next byte lands
			 * below its top) */
			for (int x = 0; x < BIN; x++)
				em[y * BIN + x] |= (uint64_t)(unsigned)
				    _mm_movemask_epi8(_mm_slli_epi64(v,
				    BIN - 1 - x)) << k0;
		}
	}
#else
	for (int64_t k = 0; k < n; k++)
		for (uint64_t b = mk[k]; b != 0; b &= b - 1)
			em[__builtin_ctzll(b)] |= (uint64_t)1 << k;
#endif
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
	em_make(S->binmk + t, n, L->em[s]);
	return L->em[s];
}

/* pixel: one camera sample; returns 1 if it hit a surface. */
static int
pixel(const rc_shared *S, rc_local *L, double px, double py, double out[4],
    double *depth, double n[3])
{
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
	if (S->binoff != NULL && !bin_of(S, px, py, &bin)) {
		/* no box's footprint holds the pixel: the ray would enter
		 * none (vx_macro_boxes_entry), nothing to walk or even set
		 * up */
		L->binned++;
		goto out;
	}
	vx_camera_ray(&S->s->camera, px, py, ow, dw);
	if (S->mesh != NULL)
		vx_tetleaf_trace(S->lg, S->mesh, ow, dw, S->isod, S->niso, 0,
		    INFINITY, tet_layer, &x, &L->tst);
	else {
		vx_world_to_index(S->g, ow, oi);
		vx_world_to_index_dir(S->g, dw, di);
		if (S->binoff != NULL) {
			/* the walk goes through the boxes the ray enters, one
			 * after the other, and nowhere when it enters none:
			 * the same leaves (vx_macro_traverse_boxes) */
			int64_t t = S->binoff[bin];
			int bx = (int)(bin % S->nbx), by = (int)(bin / S->nbx);
			uint64_t walked = L->st.trav.rays;
			/* the entries' pixel bits and lbs, read in order */
			int pb = ((int)py - by * BIN) * BIN + (int)px - bx * BIN;
			const uint64_t *em = bin_em(S, L, bin, t,
			    S->binoff[bin + 1] - t);
			/* the entries that hold the pixel, as a mask (lists
			 * of at most 64) */
			const vx_boxpick pk = { { (int32_t)px, (int32_t)py },
			    S->binlb + t, S->binmk + t, pb, em != NULL,
			    em != NULL ? em[pb] : 0 };

			vx_iso_trace_boxes(&S->tr, oi, di, S->binbox,
			    S->binlist + t, (size_t)(S->binoff[bin + 1] - t), &pk,
			    S->iso, S->niso, layer, &x, &L->st);
			L->binned += L->st.trav.rays == walked;
		} else
			vx_iso_trace(&S->tr, oi, di, 0, INFINITY, S->iso,
			    S->niso, layer, &x, &L->st);
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
		unsigned row = bin_row(S, bx, by, y);

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

static void
add_local(vx_raycast_stats *st, const rc_local *L, double *cyc)
{
	int l;

	st->primary += L->primary;
	st->shadow += L->shadow;
	st->cells += L->st.cells + L->tst.tets;
	st->roots += L->st.roots;
	st->bounded += L->st.bounded;
	st->certified += L->st.certified;
	st->hits += L->st.hits + L->tst.hits;
	st->leaves += L->tst.leaves;
	st->entries += L->tst.entries;
	st->nonfinite += L->st.nonfinite;
	st->shaded += L->shaded;
	st->irr_missing += L->irr_missing;
	st->paths += L->paths;
	st->gi_rays += L->gi_rays;
	st->covered += L->covered;
	st->binned += L->binned;
	for (l = 0; l <= VX_MACRO_MAXLEV; l++)
		st->macro[l] += L->st.trav.macro[l] + L->tst.trav.macro[l];
	st->culled += L->st.trav.culled;
	st->thread_seconds += L->busy;
	cyc[0] += (double)L->cyc_total;
	cyc[1] += (double)(L->st.cyc_isect + L->tst.cyc_isect);
	cyc[2] += (double)(L->cyc_shade - L->cyc_shadow);
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
	double cyc[3] = { 0, 0, 0 };
	struct timespec t0, t1;
	int k, tile, ntx, nty, ntile, nthr, rc;
	int aa = o->aa >= 1 ? o->aa : 1;

	if (st == NULL)
		st = &local_st;
	memset(st, 0, sizeof *st);
	st->mesh = S.mesh != NULL;
	if (!cam->ready)
		return vx_err_set(e, VX_EINTERNAL, "raycast: camera not resolved");
	if (o->bin_block > VX_RAYCAST_BLOCK_MAX)
		return vx_err_set(e, VX_EUSAGE, "raycast: bin block %d: at most "
		    "%d", o->bin_block, VX_RAYCAST_BLOCK_MAX);
	S.s = s;
	S.p = p;
	S.tex = tex;
	S.o = o;
	S.composite = p->composite;
	for (k = 0; k < s->nsurface && S.niso < VX_ISO_MAX; k++) {
		if (!p->surface_on[k])
			continue;
		S.iso[S.niso] = (float)s->surface[k].iso;
		S.isod[S.niso] = S.iso[S.niso];
		S.surf[S.niso++] = k;
		if (p->texture_on[k] && tex != NULL && tex[k] != NULL) {
			const vx_material *mt = &s->surface[k].m;

			S.tex_lo[k] = mt->has_window ? mt->window[0] : tex[k]->vmin;
			S.tex_hi[k] = mt->has_window ? mt->window[1] : tex[k]->vmax;
		}
	}
	if (S.niso == 0)
		return vx_err_set(e, VX_EDATA, "raycast: no surface to draw "
		    "(give --iso or a surface line in the scene)");
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
	clock_gettime(CLOCK_MONOTONIC, &t0);
	if (S.mesh == NULL && !S.tr.flat && S.tr.m != NULL &&
	    !o->no_cellmask) {
		if (!vx_cellmask_matches(mask, S.tr.m, S.iso, S.niso)) {
			vx_cellmask_free(mask);
			if ((rc = vx_cellmask_build(mask, S.tr.m, S.g, S.iso,
			    S.niso, 1, o->nthreads, e)) != 0)
				return rc;
		}
		if (mask->ready)
			S.tr.mask = mask;
	}
	tile = o->tile > 0 ? o->tile : 16;
	ntx = (cam->w + tile - 1) / tile;
	nty = (cam->h + tile - 1) / tile;
	ntile = ntx * nty;
#ifdef _OPENMP
	nthr = o->nthreads > 0 ? o->nthreads : omp_get_num_procs();
#else
	nthr = 1;
#endif
	rc_local *loc = aligned_alloc(_Alignof(rc_local),
	    (size_t)nthr * sizeof *loc);
	if (loc == NULL) {
		if (mask == &own)
			vx_cellmask_free(&own);
		return vx_err_set(e, VX_ENOMEM, "raycast: out of memory");
	}
	memset(loc, 0, (size_t)nthr * sizeof *loc);
	for (k = 0; k < nthr; k++) {
		loc[k].st.timing = o->timing;
		loc[k].tst.timing = o->timing;
		em_forget(&loc[k]);
	}
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
	struct timespec tb0, tb1;
	int binning = S.mesh == NULL && !S.tr.flat && S.tr.m != NULL &&
	    S.tr.m->nlev >= 1 && !o->no_binning, sparse = 0;
	int unseen = S.tr.mask != NULL && vx_cellmask_built(mask) == 0;

	clock_gettime(CLOCK_MONOTONIC, &tb0);
	if (binning && (rc = bins_build(&S, cam, S.tr.mask ? mask : NULL,
	    e)) != 0)
		goto fail;
	clock_gettime(CLOCK_MONOTONIC, &tb1);
	st->bin_seconds = (double)(tb1.tv_sec - tb0.tv_sec) +
	    1e-9 * (double)(tb1.tv_nsec - tb0.tv_nsec);
	if (binning && S.binoff != NULL && unseen && mask->nset > 0) {
		uint64_t drawn = 0;

		sparse = 1;
#ifdef _OPENMP
#pragma omp parallel for num_threads(nthr) schedule(dynamic, 16) \
    reduction(+:drawn)
#endif
		for (int64_t kb = 0; kb < (int64_t)S.nbx * S.nby; kb++) {
#ifdef _OPENMP
			rc_local *L = &loc[omp_get_thread_num()];
#else
			rc_local *L = &loc[0];
#endif
			int x = (int)(kb % S.nbx) * BIN + BIN / 2;
			int y = (int)(kb / S.nbx) * BIN + BIN / 2;

			if (x < cam->w && y < cam->h) {
				image_pixel(&S, L, x, y, aa, color, depth, normal);
				drawn++;
			}
		}
		st->first_pass = drawn;
		/* (unseen: no bits were built before the pass) */
		if (vx_cellmask_built(mask) > 0) {
			/* the bins' time: the first pass's rays are not in it */
			clock_gettime(CLOCK_MONOTONIC, &tb0);
			bins_drop(&S);
			if ((rc = bins_build(&S, cam, mask, e)) != 0)
				goto fail;
			for (k = 0; k < nthr; k++)
				em_forget(&loc[k]);   /* lists made again */
			clock_gettime(CLOCK_MONOTONIC, &tb1);
			st->bin_seconds += (double)(tb1.tv_sec - tb0.tv_sec) +
			    1e-9 * (double)(tb1.tv_nsec - tb0.tv_nsec);
		}
	}
	st->bins = S.binoff != NULL;
	st->bin_block = st->bins ? S.bin_block : 0;
	st->bin_boxes = st->bins ? (uint64_t)S.bin_boxes : 0;
	st->bin_whole = st->bins ? (uint64_t)S.bin_whole : 0;
	st->mask_bytes = S.tr.mask ? vx_cellmask_bytes(mask) : 0;
	st->mask_blocks = S.tr.mask ? (uint64_t)mask->nblock : 0;
	st->mask_set = S.tr.mask ? (uint64_t)mask->nset : 0;
	clock_gettime(CLOCK_MONOTONIC, &tb0);
#ifdef _OPENMP
#pragma omp parallel for num_threads(nthr) schedule(dynamic, 1)
#endif
	for (int ti = 0; ti < ntile; ti++) {
#ifdef _OPENMP
		rc_local *L = &loc[omp_get_thread_num()];
#else
		rc_local *L = &loc[0];
#endif
		int x0 = (ti % ntx) * tile, y0 = (ti / ntx) * tile;
		int x1 = x0 + tile < cam->w ? x0 + tile : cam->w;
		int y1 = y0 + tile < cam->h ? y0 + tile : cam->h;
		uint64_t c0 = o->timing ? vx_cycles() : 0;
		struct timespec w0, w1;

		clock_gettime(CLOCK_MONOTONIC, &w0);
		if (aa == 1 && S.binoff != NULL)
			for (int y = y0; y < y1; y++)
				tile_row(&S, L, x0, x1, y, sparse, color, depth,
				    normal);
		else
			for (int y = y0; y < y1; y++)
				for (int x = x0; x < x1; x++)
					if (!sparse || x % BIN != BIN / 2 ||
					    y % BIN != BIN / 2)
						image_pixel(&S, L, x, y, aa, color,
						    depth, normal);
		if (o->timing)
			L->cyc_total += vx_cycles() - c0;
		clock_gettime(CLOCK_MONOTONIC, &w1);
		L->busy += (double)(w1.tv_sec - w0.tv_sec) +
		    1e-9 * (double)(w1.tv_nsec - w0.tv_nsec);
	}
	clock_gettime(CLOCK_MONOTONIC, &t1);
	st->threads = nthr;
	st->tile_seconds = (double)(t1.tv_sec - tb0.tv_sec) +
	    1e-9 * (double)(t1.tv_nsec - tb0.tv_nsec);
	for (k = 0; k < nthr; k++)
		add_local(st, &loc[k], cyc);
	free(loc);
	st->mask_built = S.tr.mask ? (uint64_t)vx_cellmask_built(mask) : 0;
	if (mask == &own)
		vx_cellmask_free(&own);
	bins_free(&S);
	st->seconds = (double)(t1.tv_sec - t0.tv_sec) +
	    1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
	if (o->timing && cyc[0] > 0) {
		st->share_isect = cyc[1] / cyc[0];
		st->share_shade = cyc[2] / cyc[0];
		st->share_traverse = 1 - st->share_isect - st->share_shade;
	}
	return 0;
fail:
	free(loc);
	if (mask == &own)
		vx_cellmask_free(&own);
	bins_free(&S);
	return rc;
}

int
vx_raycast_render(const vx_scene *s, const vx_plan *p, const vx_grid *g,
    const vx_macro *m, const vx_grid *const *tex, const vx_raycast_opts *o,
    vx_image *color, vx_image *depth, vx_image *normal, vx_raycast_stats *st,
    vx_err *e)
{
	rc_shared S;

	memset(&S, 0, sizeof S);
	S.g = g;
	S.tr.g = g;
	S.tr.m = m;
	S.tr.flat = o->flat || m == NULL;
	S.tr.solver = o->solver;
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
	S.mesh = mesh;
	S.lg = lg;
	/* the offset is in units of the mean tet size, the cube root of the
	 * box's volume per tet (a property of the mesh, not of its leaf grid,
	 * so that pictures do not depend on the grid) */
	double vol = 1, ext = 0;
	for (int a = 0; a < 3; a++) {
		double x = mesh->npoint ? mesh->bmax[a] - mesh->bmin[a] : 0;
		vol *= x;
		ext = x > ext ? x : ext;
	}
	double size = vol > 0 && mesh->ntet > 0 ?
	    cbrt(vol / (double)mesh->ntet) : mesh->ntet > 0 ?
	    ext / cbrt((double)mesh->ntet) : 1;
	S.mesh_off = o->shadow_offset * (size > 0 ? size : 1);
	return render(&S, s, p, tex, o, color, depth, normal, st, e);
}
