/* macro.c: the multilevel min/max grid, its hierarchical 3D-DDA, and the
 * MCEL chunk (see vx_macro.h and formats/macrocell.md). */
#include "vx_macro.h"

#include <float.h>
#include <stdatomic.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#ifdef _OPENMP
#include <omp.h>
#endif
/* SSE2 where the platform has it: the cell mask's build (MASK_SIMD) and a
 * visit's corners (corners_i, corners_f) */
#if defined(__SSE2__)
#include <emmintrin.h>
#define MASK_SIMD 1
#endif

/* Widths beyond this are clamped: a macrocell wider than the leaf grid
 * covers all of it, and the clamp keeps width products from overflowing. */
#define WIDTH_CAP ((int64_t)1 << 32)

void
vx_macro_init(vx_macro *m)
{
	int l;

	memset(m, 0, sizeof *m);
	for (l = 0; l <= VX_MACRO_MAXLEV; l++)
		m->size[l][0] = m->size[l][1] = m->size[l][2] = 1;
	m->root[0] = INFINITY;
	m->root[1] = -INFINITY;
}

void
vx_macro_free(vx_macro *m)
{
	if (m == NULL)
		return;
	free(m->block_);
	vx_macro_init(m);
}

int
vx_macro_default_sizes(vx_type t, int nlev, int sizes[][3])
{
	static const int l1[][3] = {
		[VX_U8] = { 16, 16, 8 }, [VX_U16] = { 16, 8, 8 },
		[VX_I16] = { 16, 8, 8 }, [VX_F32] = { 8, 8, 8 },
	};
	int l, a;

	if (t <= VX_TYPE_UNKNOWN || t >= VX_TYPE_LAST || nlev < 1 ||
	    nlev > VX_MACRO_MAXLEV)
		return 0;
	for (l = 0; l < nlev; l++)
		for (a = 0; a < 3; a++)
			sizes[l][a] = l == 0 ? l1[t][a] : l == 1 ?
			    64 / l1[t][a] : 4;
	return nlev;
}

int
vx_macro_parse_sizes(const char *s, int sizes[][3], vx_err *e)
{
	int n = 0, used;
	const char *p = s;

	for (;;) {
		if (n == VX_MACRO_MAXLEV) {
			vx_err_set(e, VX_EUSAGE, "sizes '%.60s': more than %d "
			    "levels", s, VX_MACRO_MAXLEV);
			return -1;
		}
		if (*p < '0' || *p > '9' ||
		    sscanf(p, "%5dx%5dx%5d%n", &sizes[n][0], &sizes[n][1],
		    &sizes[n][2], &used) != 3) {
			vx_err_set(e, VX_EUSAGE, "sizes '%.60s': expected "
			    "AxBxC[,DxExF...]", s);
			return -1;
		}
		for (int a = 0; a < 3; a++)
			if (sizes[n][a] < 1 || sizes[n][a] > VX_MACRO_MAXSIZE) {
				vx_err_set(e, VX_EUSAGE, "sizes '%.60s': each "
				    "edge must be in 1..%d", s, VX_MACRO_MAXSIZE);
				return -1;
			}
		p += used;
		n++;
		if (*p == '\0')
			return n;
		if (*p != ',' || p[1] < '0' || p[1] > '9') {
			vx_err_set(e, VX_EUSAGE, "sizes '%.60s': expected "
			    "AxBxC[,DxExF...]", s);
			return -1;
		}
		p++;
	}
}

static size_t
ncells(const vx_macro *m, int l)
{
	return (size_t)m->dims[l][0] * (size_t)m->dims[l][1] *
	    (size_t)m->dims[l][2];
}

size_t
vx_macro_bytes(const vx_macro *m)
{
	size_t n = 0;
	int l;

	for (l = m->explicit_leaves ? 0 : 1; l <= m->nlev; l++)
		n += 2 * sizeof(float) * ncells(m, l);
	return n;
}

/* setup: geometry of every level over an n[0] x n[1] x n[2] leaf grid, and
 * one zeroed allocation for the stored levels (level 0 too when leaf0).
 * m is initialized here. */
static int
setup(vx_macro *m, const int64_t n[3], int nlev, const int sizes[][3],
    int leaf0, vx_err *e)
{
	size_t total = 0, k;
	float *p;
	int l, a;

	vx_macro_init(m);
	if (nlev < 0 || nlev > VX_MACRO_MAXLEV)
		return vx_err_set(e, VX_EDATA, "macrocells: %d levels (0..%d)",
		    nlev, VX_MACRO_MAXLEV);
	for (a = 0; a < 3; a++) {
		if (n[a] < 0 || n[a] > VX_GRID_MAX_DIM)
			return vx_err_set(e, VX_EDATA, "macrocells: %lld leaves "
			    "along an axis (0..%lld)", (long long)n[a],
			    (long long)VX_GRID_MAX_DIM);
		m->dims[0][a] = n[a];
		m->width[0][a] = 1;
		m->iwidth[0][a] = 1.0;
	}
	m->nlev = nlev;
	m->explicit_leaves = leaf0;
	for (l = 1; l <= nlev; l++)
		for (a = 0; a < 3; a++) {
			int s = sizes[l - 1][a];

			if (s < 1 || s > VX_MACRO_MAXSIZE)
				return vx_err_set(e, VX_EDATA, "macrocells: "
				    "level %d edge %d (1..%d)", l, s,
				    VX_MACRO_MAXSIZE);
			m->size[l][a] = s;
			m->dims[l][a] = (m->dims[l - 1][a] + s - 1) / s;
			m->width[l][a] = m->width[l - 1][a] * s;
			if (m->width[l][a] > WIDTH_CAP)
				m->width[l][a] = WIDTH_CAP;
			m->iwidth[l][a] = 1.0 / (double)m->width[l][a];
		}
	for (l = leaf0 ? 0 : 1; l <= nlev; l++) {
		/* each level has at most as many cells as the leaves, whose
		 * count is below 2^60: no overflow in 64 bits */
		if (vx_mul_size(&k, ncells(m, l), 2) != 0 ||
		    vx_add_size(&total, total, k) != 0)
			return vx_err_set(e, VX_EDATA, "macrocells: too many");
	}
	if (total == 0)
		return 0;
	if ((p = vx_calloc(total, sizeof(float), e)) == NULL)
		return vx_err_push(e, "macrocells");
	m->block_ = p;
	for (l = leaf0 ? 0 : 1; l <= nlev; l++) {
		m->mm[l] = p;
		p += 2 * ncells(m, l);
	}
	return 0;
}

static int
threads(int nthreads)
{
#ifdef _OPENMP
	return nthreads > 0 ? nthreads : omp_get_max_threads();
#else
	(void)nthreads;
	return 1;
#endif
}

/* box_range: min and max of the finite samples of g in the inclusive index
 * box lo..hi (min > max when there is none). */
#define BOX_RANGE(T, FINITE)                                             \
	do {                                                             \
		const T *d = (const T *)g->data;                         \
		for (z = lo[2]; z <= hi[2]; z++)                         \
			for (y = lo[1]; y <= hi[1]; y++) {               \
				const T *row = d + g->lay.off[1][y] +    \
				    g->lay.off[2][z];                    \
				for (x = lo[0]; x <= hi[0]; x++) {       \
					float v = (float)row[ox[x]];     \
					if (!(FINITE))                   \
						continue;                \
					if (v < mn)                      \
						mn = v;                  \
					if (v > mx)                      \
						mx = v;                  \
				}                                        \
			}                                                \
	} while (0)

static void
box_range(const vx_grid *g, const int64_t lo[3], const int64_t hi[3],
    float *out)
{
	const int64_t *ox = g->lay.off[0];
	float mn = INFINITY, mx = -INFINITY;
	int64_t x, y, z;

	switch (g->type) {
	case VX_U8: BOX_RANGE(uint8_t, 1); break;
	case VX_U16: BOX_RANGE(uint16_t, 1); break;
	case VX_I16: BOX_RANGE(int16_t, 1); break;
	case VX_F32: BOX_RANGE(float, isfinite(v)); break;
	default: break;
	}
	out[0] = mn;
	out[1] = mx;
}

/* reduce: level l's ranges from level l-1's. */
static void
reduce(vx_macro *m, int l, int nt)
{
	int64_t n = (int64_t)ncells(m, l);

	(void)nt;
#pragma omp parallel for schedule(dynamic, 64) num_threads(nt)
	for (int64_t c = 0; c < n; c++) {
		int64_t q[3], lo[3], hi[3], x, y, z;
		float mn = INFINITY, mx = -INFINITY;
		const float *below = m->mm[l - 1];

		q[0] = c % m->dims[l][0];
		q[1] = c / m->dims[l][0] % m->dims[l][1];
		q[2] = c / m->dims[l][0] / m->dims[l][1];
		for (int a = 0; a < 3; a++) {
			lo[a] = q[a] * m->size[l][a];
			hi[a] = lo[a] + m->size[l][a];
			if (hi[a] > m->dims[l - 1][a])
				hi[a] = m->dims[l - 1][a];
		}
		for (z = lo[2]; z < hi[2]; z++)
			for (y = lo[1]; y < hi[1]; y++)
				for (x = lo[0]; x < hi[0]; x++) {
					size_t k = 2 * (size_t)(x +
					    m->dims[l - 1][0] * (y +
					    m->dims[l - 1][1] * z));

					if (below[k] < mn)
						mn = below[k];
					if (below[k + 1] > mx)
						mx = below[k + 1];
				}
		m->mm[l][2 * c] = mn;
		m->mm[l][2 * c + 1] = mx;
	}
}

static void
root_from(vx_macro *m, int l)
{
	size_t k, n = ncells(m, l);

	m->root[0] = INFINITY;
	m->root[1] = -INFINITY;
	for (k = 0; k < n; k++) {
		if (m->mm[l][2 * k] < m->root[0])
			m->root[0] = m->mm[l][2 * k];
		if (m->mm[l][2 * k + 1] > m->root[1])
			m->root[1] = m->mm[l][2 * k + 1];
	}
}

int
vx_macro_build(vx_macro *m, const vx_grid *g, int nlev, const int sizes[][3],
    int nthreads, vx_err *e)
{
	int64_t n[3];
	int a, l, rc, nt = threads(nthreads);

	for (a = 0; a < 3; a++)
		n[a] = g->dims[a] > 1 ? g->dims[a] - 1 : 0;
	if (n[0] == 0 || n[1] == 0 || n[2] == 0)
		n[0] = n[1] = n[2] = 0;
	if ((rc = setup(m, n, nlev, sizes, 0, e)) != 0)
		return rc;
	snprintf(m->name, sizeof m->name, "%s", g->name);
	memcpy(m->vdims, g->dims, sizeof m->vdims);
	m->vtype = g->type;
	m->vcrc = vx_macro_grid_crc(g);
	if (n[0] == 0)
		return 0;
	if (nlev == 0) {
		/* no stored level: the root is the range over all cells */
		int64_t lo[3] = { 0, 0, 0 }, hi[3];
		float r[2];

		for (a = 0; a < 3; a++)
			hi[a] = n[a];
		box_range(g, lo, hi, r);
		m->root[0] = r[0];
		m->root[1] = r[1];
		return 0;
	}
	/* level 1 straight from the samples: a macrocell over cells
	 * [q w, (q+1) w) covers samples q w .. (q+1) w inclusive */
	int64_t n1 = (int64_t)ncells(m, 1);
#pragma omp parallel for schedule(dynamic, 16) num_threads(nt)
	for (int64_t c = 0; c < n1; c++) {
		int64_t q[3], lo[3], hi[3];

		q[0] = c % m->dims[1][0];
		q[1] = c / m->dims[1][0] % m->dims[1][1];
		q[2] = c / m->dims[1][0] / m->dims[1][1];
		for (int b = 0; b < 3; b++) {
			lo[b] = q[b] * m->width[1][b];
			hi[b] = lo[b] + m->width[1][b];
			if (hi[b] > n[b])
				hi[b] = n[b];
		}
		box_range(g, lo, hi, m->mm[1] + 2 * c);
	}
	for (l = 2; l <= nlev; l++)
		reduce(m, l, nt);
	root_from(m, nlev);
	return 0;
}

int
vx_macro_build_explicit(vx_macro *m, const int64_t n[3],
    const float *leaf_mm, int nlev, const int sizes[][3], int nthreads,
    vx_err *e)
{
	int l, rc, nt = threads(nthreads);

	if ((rc = setup(m, n, nlev, sizes, 1, e)) != 0)
		return rc;
	if (ncells(m, 0) == 0)
		return 0;
	memcpy(m->mm[0], leaf_mm, 2 * sizeof(float) * ncells(m, 0));
	for (l = 1; l <= nlev; l++)
		reduce(m, l, nt);
	root_from(m, nlev);
	return 0;
}

/* ---- the volume's identity ---- */

/* A run of samples contiguous in memory along x: the layout's x offsets
 * x0 .. x0+len-1 are start .. start+len-1 (whole rows when linear, one
 * brick edge when bricked).  The runs are the same for every row. */
typedef struct xrun {
	int64_t start, len;
} xrun;

/* slab_crc: CRC-32 of the samples of slab z in logical order, as
 * little-endian bytes: runs are gathered into a buffer (byte-swapped on a
 * big-endian host) and fed to zlib 16 KiB at a time. */
static uint32_t
slab_crc(const vx_grid *g, const xrun *run, size_t nrun, int64_t z)
{
	unsigned char buf[16384];
	size_t ts = vx_type_size(g->type), k = 0, r;
	uLong crc = crc32(0L, Z_NULL, 0);
	int swap = !vx_host_is_le() && ts > 1;
	int64_t y;

	for (y = 0; y < g->dims[1]; y++) {
		const unsigned char *row = (const unsigned char *)g->data +
		    (size_t)(g->lay.off[1][y] + g->lay.off[2][z]) * ts;

		for (r = 0; r < nrun; r++) {
			/* without a run table, one sample at a time */
			size_t left = (run ? (size_t)run[r].len : 1) * ts;
			const unsigned char *p = row + (size_t)(run ?
			    run[r].start : g->lay.off[0][r]) * ts;

			while (left > 0) {
				size_t n = sizeof buf - k < left ? sizeof buf - k :
				    left;

				memcpy(buf + k, p, n);
				if (swap)
					vx_swap_bytes(buf + k, n / ts, ts);
				k += n;
				p += n;
				left -= n;
				if (k == sizeof buf) {
					crc = crc32(crc, buf, (uInt)k);
					k = 0;
				}
			}
		}
	}
	return (uint32_t)crc32(crc, buf, (uInt)k);
}

uint32_t
vx_macro_grid_crc(const vx_grid *g)
{
	size_t ts = vx_type_size(g->type), nrun = 0;
	z_off_t slab = (z_off_t)(g->dims[0] * g->dims[1] * (int64_t)ts);
	int64_t nz = g->dims[2], z, x;
	uint32_t *part;
	xrun *run;
	uLong crc = crc32(0L, Z_NULL, 0);

	if (ts == 0 || g->data == NULL)
		return 0;
	/* sizeof buf (16384) is a multiple of every sample size, so no sample
	 * is split between two buffers */
	if ((run = malloc((size_t)g->dims[0] * sizeof *run)) != NULL) {
		for (x = 0; x < g->dims[0]; x++) {
			if (nrun > 0 && g->lay.off[0][x] ==
			    run[nrun - 1].start + run[nrun - 1].len)
				run[nrun - 1].len++;
			else {
				run[nrun].start = g->lay.off[0][x];
				run[nrun].len = 1;
				nrun++;
			}
		}
	} else
		nrun = (size_t)g->dims[0];
	if ((part = malloc((size_t)nz * sizeof *part)) == NULL) {
		/* no memory for the slab table: serially */
		for (z = 0; z < nz; z++)
			crc = crc32_combine(crc, slab_crc(g, run, nrun, z), slab);
		free(run);
		return (uint32_t)crc;
	}
#pragma omp parallel for schedule(dynamic, 1)
	for (int64_t k = 0; k < nz; k++)
		part[k] = slab_crc(g, run, nrun, k);
	for (z = 0; z < nz; z++)
		crc = crc32_combine(crc, part[z], slab);
	free(part);
	free(run);
	return (uint32_t)crc;
}

/* ---- traversal ---- */

typedef struct ray {
	double o[3], d[3], inv[3];
	int s[3];              /* direction sign per axis: 1, -1 or 0 */
	int div[3];            /* 1: crossing times by division */
	int up[3];             /* 1 where s >= 0: the far plane is the upper */
	int flip;              /* bit a set where s[a] < 0 (see leaves) */
	int64_t fixed[3];      /* leaf index along axes with s == 0 */
	int64_t n[3];          /* leaf grid dims */
	const int64_t (*w)[3];  /* w[l]: level-l cell edge in leaves */
	const double (*iw)[3];  /* 1 / w: only for guesses */
} ray;

/* the edges of a flat walk without a hierarchy: one leaf */
static const int64_t unit_w[1][3] = { { 1, 1, 1 } };
static const double unit_iw[1][3] = { { 1.0, 1.0, 1.0 } };

/* tcross: the time the ray crosses plane x_a = p.  One formula for every
 * level and walk, so equal planes give bit-identical times. */
static inline double
tcross(const ray *r, int a, int64_t p)
{
	double x = (double)p - r->o[a];

	return r->div[a] ? x / r->d[a] : x * r->inv[a];
}

/* the planes bounding level-l cell c along a, in leaves (the last cell of
 * a level may be partial: its upper plane is the grid's) */
static inline int64_t
plane_lo(const ray *r, int l, int a, int64_t c)
{
	return c * r->w[l][a];
}

static inline int64_t
plane_hi(const ray *r, int l, int a, int64_t c)
{
	int64_t p = (c + 1) * r->w[l][a];

	return p < r->n[a] ? p : r->n[a];
}

/* t_exit_of: crossing time of the face level-l cell c leaves through. */
static inline double
t_exit_of(const ray *r, int l, int a, int64_t c)
{
	if (r->s[a] == 0)
		return INFINITY;
	return tcross(r, a, r->up[a] ? plane_hi(r, l, a, c) :
	    plane_lo(r, l, a, c));
}

/* The walk's loops keep a cell's per-axis state in three variables (in
 * registers: a step picks its axis with selects, no store and reload
 * through an indexed array).  AXIS: the one of axis ax; SET_AXIS: it set
 * to v. */
#define AXIS(ax, v0, v1, v2) ((ax) == 0 ? (v0) : (ax) == 1 ? (v1) : (v2))
#define SET_AXIS(ax, v0, v1, v2, v)                                      \
	do {                                                             \
		(v0) = (ax) == 0 ? (v) : (v0);                           \
		(v1) = (ax) == 1 ? (v) : (v1);                           \
		(v2) = (ax) == 2 ? (v) : (v2);                           \
	} while (0)

/* min_axis: the axis whose next crossing comes first (the lowest on a
 * tie, the walk's order), its time in *t */
static inline int
min_axis(double n0, double n1, double n2, double *t)
{
	int ax = n1 < n0;

	*t = ax ? n1 : n0;
	if (n2 < *t) {
		ax = 2;
		*t = n2;
	}
	return ax;
}

/* find_cell: among level-l cells k0..k1-1 along axis a (s != 0), the one
 * the ray is in at time t: the last one in walking order whose entry face
 * is crossed at or before t (post != 0) or strictly before t (post == 0);
 * the first one if none is.  Crossing times are monotone in the plane, so
 * that test is monotone in the cell index: start from the cell holding the
 * point o + t d (right or one off, whatever the rounding) and walk to the
 * answer; the result is the same as a binary search's, in one or two
 * crossing times instead of log2(k1 - k0). */
static inline int64_t
find_cell(const ray *r, int l, int a, int64_t k0, int64_t k1, double t,
    int post)
{
	double td = t * r->d[a], x = r->o[a] + td, q = x * r->iw[l][a], tc;
	int64_t k;

	/* the guess, clamped into [k0, k1 - 1] (NaN goes to k0) */
	if (!(q > (double)k0))
		k = k0;
	else if (q >= (double)(k1 - 1))
		k = k1 - 1;
	else
		k = (int64_t)q;
	/* Most guesses are far inside their cell: if x lies inside the
	 * guess's slab by more than mg, the tests below keep k, whatever the
	 * rounding.  Proof: a plane p's crossing time T = (p - o) / d is
	 * computed with an error under 4 ulp(|p| + |o|) / |d|, x = o + t d
	 * under 3 ulp(|o| + |t d|), while |x - p| > mg = 2^-40 (|o| + |t d|
	 * + |hi|) puts T at least (mg - that) / |d| from t, 2^11 times more:
	 * the computed crossing is on the same side of t as the true one,
	 * and never equal to it (so post does not matter).  Rays whose
	 * crossing times are divided (d near under- or overflow) and
	 * non-finite x take the tests. */
	if (!r->div[a]) {
		double lo = (double)plane_lo(r, l, a, k);
		double hi = (double)plane_hi(r, l, a, k);
		double mg = 0x1p-40 * (fabs(r->o[a]) + fabs(td) + hi);

		if ((k == k0 || x - lo > mg) && (k == k1 - 1 || hi - x > mg))
			return k;
	}
#define ENTERED(p) (tc = tcross(r, a, (p)), post ? tc <= t : tc < t)
	if (r->s[a] > 0) {
		/* entered(k): k's entry face, its lower plane, crossed by t */
		while (k < k1 - 1 && ENTERED(plane_lo(r, l, a, k + 1)))
			k++;
		while (k > k0 && !ENTERED(plane_lo(r, l, a, k)))
			k--;
	} else {
		while (k > k0 && ENTERED(plane_hi(r, l, a, k - 1)))
			k--;
		while (k < k1 - 1 && !ENTERED(plane_hi(r, l, a, k)))
			k++;
	}
#undef ENTERED
	return k;
}

static inline int
brackets(float lo, float hi, const float *vals, int nvals)
{
	int k;

	if (nvals <= 0)
		return 1;
	if (nvals == 1)
		return lo <= vals[0] && vals[0] <= hi;
	for (k = 0; k < nvals; k++)
		if (lo <= vals[k] && vals[k] <= hi)
			return 1;
	return 0;
}

/* ---- the leaf loop over volume leaves ----
 * A leaf's 8 samples are loaded, from the layout offsets of its lower and
 * upper sample planes per axis, in vx_grid_cell's order, and written to
 * the visit as floats by two 16-byte stores: the visitor reads them with
 * wide loads (finite8, the hit's copy), and a wide load of narrow stores
 * waits for them to retire. */

/* min and max keeping the first of equal values, as a left-to-right scan
 * with a strict comparison does */
static inline float
min_first(float a, float b)
{
	return b < a ? b : a;
}

static inline float
max_first(float a, float b)
{
	return b > a ? b : a;
}

static inline int32_t
imin(int32_t a, int32_t b)
{
	return b < a ? b : a;
}

static inline int32_t
imax(int32_t a, int32_t b)
{
	return b > a ? b : a;
}

/* corners: c[0..8) = a0..a7, two 16-byte stores where SSE2 has them
 * (integer samples, exact in float, or floats) */
static inline void
corners_i(float c[8], int32_t a0, int32_t a1, int32_t a2, int32_t a3,
    int32_t a4, int32_t a5, int32_t a6, int32_t a7)
{
#if defined(__SSE2__)
	_mm_storeu_ps(c, _mm_cvtepi32_ps(_mm_setr_epi32(a0, a1, a2, a3)));
	_mm_storeu_ps(c + 4, _mm_cvtepi32_ps(_mm_setr_epi32(a4, a5, a6, a7)));
#else
	c[0] = (float)a0; c[1] = (float)a1; c[2] = (float)a2;
	c[3] = (float)a3; c[4] = (float)a4; c[5] = (float)a5;
	c[6] = (float)a6; c[7] = (float)a7;
#endif
}

static inline void
corners_f(float c[8], float a0, float a1, float a2, float a3, float a4,
    float a5, float a6, float a7)
{
#if defined(__SSE2__)
	_mm_storeu_ps(c, _mm_setr_ps(a0, a1, a2, a3));
	_mm_storeu_ps(c + 4, _mm_setr_ps(a4, a5, a6, a7));
#else
	c[0] = a0; c[1] = a1; c[2] = a2; c[3] = a3;
	c[4] = a4; c[5] = a5; c[6] = a6; c[7] = a7;
#endif
}

/* integer samples: the range from the loaded values themselves */
#define LEAF_INT(T)                                                      \
	do {                                                             \
		const T *d = (const T *)g->data;                         \
		int32_t a0 = d[x0 + yz00], a1 = d[x1 + yz00];            \
		int32_t a2 = d[x0 + yz10], a3 = d[x1 + yz10];            \
		int32_t a4 = d[x0 + yz01], a5 = d[x1 + yz01];            \
		int32_t a6 = d[x0 + yz11], a7 = d[x1 + yz11];            \
		corners_i(c, a0, a1, a2, a3, a4, a5, a6, a7);            \
		mn = imin(imin(imin(a0, a1), imin(a2, a3)),              \
		    imin(imin(a4, a5), imin(a6, a7)));                   \
		mx = imax(imax(imax(a0, a1), imax(a2, a3)),              \
		    imax(imax(a4, a5), imax(a6, a7)));                   \
	} while (0)

/* flo: v if finite, else +Inf (the min's identity); fhi: -Inf */
static inline float
flo(float v)
{
	return fabsf(v) <= FLT_MAX ? v : INFINITY;
}

static inline float
fhi(float v)
{
	return fabsf(v) <= FLT_MAX ? v : -INFINITY;
}

/* leaf_load: the 8 samples of the leaf whose lower and upper sample
 * planes are at layout offsets lo, hi, into c in vx_grid_cell's order,
 * and their range: integer types in *imn..*imx (all finite, exact in
 * float); f32 in *flop..*fhip over the finite ones (empty: +Inf, -Inf;
 * NaN and +-Inf left out) */
static inline void
leaf_load(const vx_grid *g, const int64_t lo[3], const int64_t hi[3],
    float c[8], int32_t *imn, int32_t *imx, float *flop, float *fhip)
{
	int64_t x0 = lo[0], x1 = hi[0];
	int64_t yz00 = lo[1] + lo[2], yz10 = hi[1] + lo[2];
	int64_t yz01 = lo[1] + hi[2], yz11 = hi[1] + hi[2];
	int32_t mn = 0, mx = 0;

	switch (g->type) {
	case VX_U8: LEAF_INT(uint8_t); break;
	case VX_U16: LEAF_INT(uint16_t); break;
	case VX_I16: LEAF_INT(int16_t); break;
	case VX_F32: {
		const float *d = (const float *)g->data;
		float a0 = d[x0 + yz00], a1 = d[x1 + yz00];
		float a2 = d[x0 + yz10], a3 = d[x1 + yz10];
		float a4 = d[x0 + yz01], a5 = d[x1 + yz01];
		float a6 = d[x0 + yz11], a7 = d[x1 + yz11];

		corners_f(c, a0, a1, a2, a3, a4, a5, a6, a7);
		*flop = min_first(min_first(min_first(flo(a0), flo(a1)),
		    min_first(flo(a2), flo(a3))), min_first(min_first(flo(a4),
		    flo(a5)), min_first(flo(a6), flo(a7))));
		*fhip = max_first(max_first(max_first(fhi(a0), fhi(a1)),
		    max_first(fhi(a2), fhi(a3))), max_first(max_first(fhi(a4),
		    fhi(a5)), max_first(fhi(a6), fhi(a7))));
		return;
	}
	default:
		corners_i(c, 0, 0, 0, 0, 0, 0, 0, 0);
		break;
	}
	*imn = mn;
	*imx = mx;
}

/* leaves: the level-0 part of the walk over volume leaves: from leaf c
 * (entered at *t through axis *e), visit and step leaf to leaf while the
 * next leaf stays in the sibling range (lim: the first index past it in
 * walking order) and the segment goes on.  Does exactly what the walk does
 * at level 0 for explicit leaves, leaf after leaf (the same tests, crossing
 * times and visits).  Returns the visitor's nonzero value, or 0 with *ax,
 * *texit the face and time through which the last leaf (c, entered at *t
 * through *e) is left: beyond tb, or into a leaf outside the range. */
static int
leaves(const ray *r, const vx_grid *g, int64_t c[3], const int64_t lim[3],
    double tn[3], double *tp, int *ep, double tb, const float *vals,
    int nvals, const uint64_t *bits, int64_t li, const int64_t dl[3],
    vx_visit_fn fn, void *ctx, vx_trav_stats *s, int *axp, double *texitp)
{
	const int64_t *off[3] = { g->lay.off[0], g->lay.off[1], g->lay.off[2] };
	const int *up = r->up;
	int64_t fl = 0, ce = 0, culled = 0;
	/* the leaf and its exit times in registers: a step picks its axis
	 * with selects, not a store and reload through an indexed array */
	int64_t c0 = c[0], c1 = c[1], c2 = c[2];
	double n0 = tn[0], n1 = tn[1], n2 = tn[2];
	/* the crossing after the next one per axis, computed a step ahead:
	 * a step then only selects it, and the next step's choice of axis
	 * does not wait for a conversion, a subtraction and a product (the
	 * same tcross of the same plane: the same bits) */
	double m0 = r->s[0] ? tcross(r, 0, c0 + r->s[0] + up[0]) : INFINITY;
	double m1 = r->s[1] ? tcross(r, 1, c1 + r->s[1] + up[1]) : INFINITY;
	double m2 = r->s[2] ? tcross(r, 2, c2 + r->s[2] + up[2]) : INFINITY;
	int isf = g->type == VX_F32, ithr = 0;
	vx_leaf_visit v;
	double t = *tp, texit;
	int ax, e = *ep, rc = 0;

	/* integer samples and one value v: (float)min <= v <= (float)max is
	 * min <= floor(v) and max >= ceil(v) (v clamped far beyond the 16-bit
	 * range first; NaN brackets nothing and takes the float test) */
	if (!isf && nvals == 1 && vals[0] == vals[0]) {
		double w = vals[0] < -0x1p40 ? -0x1p40 : vals[0] > 0x1p40 ?
		    0x1p40 : vals[0];

		ithr = 1;
		fl = (int64_t)floor(w);
		ce = (int64_t)ceil(w);
	}
	for (;;) {
		int64_t nc, p;
		double tv;

		ax = min_axis(n0, n1, n2, &texit);
		/* with a mask, a clear bit is this very test's answer: the
		 * samples are loaded only for a leaf to visit */
		if (bits != NULL && !(bits[li >> 6] >> (li & 63) & 1))
			culled++;
		else {
			float lo = 0, hi = 0;
			int32_t imn = 0, imx = 0;
			int64_t pl[3], ph[3];
			int in;

			pl[0] = off[0][c0];
			ph[0] = off[0][c0 + 1];
			pl[1] = off[1][c1];
			ph[1] = off[1][c1 + 1];
			pl[2] = off[2][c2];
			ph[2] = off[2][c2 + 1];
			leaf_load(g, pl, ph, v.c, &imn, &imx, &lo, &hi);
			if (ithr)
				in = imn <= fl && imx >= ce;
			else {
				if (!isf) {
					lo = (float)imn;
					hi = (float)imx;
				}
				in = brackets(lo, hi, vals, nvals);
			}
			if (in) {
				v.i[0] = c0;
				v.i[1] = c1;
				v.i[2] = c2;
				v.leaf = c0 + (r->n[0] * (c1 + r->n[1] * c2));
				v.t0 = t;
				v.t1 = texit < tb ? texit : tb;
				v.entry_axis = e;
				v.entry_side = e >= 0 && r->s[e] < 0;
				v.exit_axis = texit <= tb && r->s[ax] ? ax : -1;
				v.exit_side = v.exit_axis >= 0 && r->s[ax] > 0;
				v.lo = isf ? lo : (float)imn;
				v.hi = isf ? hi : (float)imx;
				s->leaves++;
				if ((rc = fn(ctx, &v)) != 0)
					break;
			} else
				culled++;
		}
		if (!(texit < tb))
			break;
		nc = AXIS(ax, c0, c1, c2) + r->s[ax];
		if (nc == lim[ax])
			break;
		/* the far plane of the next leaf, and its crossing time as
		 * t_exit_of gives it at level 0 (inside the grid: no clamp) */
		p = nc + r->s[ax] + up[ax];
		tv = AXIS(ax, m0, m1, m2);
		SET_AXIS(ax, c0, c1, c2, nc);
		SET_AXIS(ax, n0, n1, n2, tv);
		SET_AXIS(ax, m0, m1, m2, tcross(r, ax, p));
		li += dl[ax];
		t = texit;
		e = ax;
	}
	s->culled += (uint64_t)culled;
	c[0] = c0;
	c[1] = c1;
	c[2] = c2;
	tn[0] = n0;
	tn[1] = n1;
	tn[2] = n2;
	*tp = t;
	*ep = e;
	*axp = ax;
	*texitp = texit;
	return rc;
}

/* ray_axes: the ray's per-axis set-up over n leaves (direction signs,
 * crossing-time factors, the leaf kept along an axis the ray does not
 * move on).  Returns 0 when the ray is not finite or runs parallel to an
 * axis outside the grid (it visits nothing). */
static int
ray_axes(ray *r, const int64_t n[3], const double o[3], const double d[3])
{
	for (int a = 0; a < 3; a++) {
		double ad = fabs(d[a]);

		if (!isfinite(o[a]) || !isfinite(d[a]))
			return 0;
		r->o[a] = o[a];
		r->d[a] = d[a];
		r->s[a] = d[a] > 0 ? 1 : d[a] < 0 ? -1 : 0;
		r->up[a] = r->s[a] >= 0;
		r->div[a] = !(ad >= 0x1p-1000 && ad <= 0x1p1000);
		r->inv[a] = r->s[a] ? 1.0 / d[a] : 0.0;
		r->fixed[a] = 0;
		r->n[a] = n[a];
		if (r->s[a] == 0) {
			if (!(o[a] >= 0 && o[a] <= (double)n[a]))
				return 0;
			r->fixed[a] = (int64_t)floor(o[a]);
			if (r->fixed[a] > n[a] - 1)
				r->fixed[a] = n[a] - 1;
		}
	}
	return 1;
}

/* ray_clip: the set-up of ray r (ray_axes done, over n leaves) for a walk
 * from level top: the segment [*ta, *tb] clipped to the grid.  Returns 0
 * when nothing is to be walked (the ray misses, or the root range
 * brackets none of the values). */
static inline __attribute__((always_inline)) int
ray_clip(ray *r, const vx_macro *m, int top, const float *vals, int nvals,
    double *tap, double *tbp)
{
	const int64_t *n = r->n;
	double ta = *tap, tb = *tbp;
	int a;

	for (a = 0; a < 3; a++) {
		if (r->s[a] != 0) {
			double t0 = tcross(r, a, r->s[a] > 0 ? 0 : n[a]);
			double t1 = tcross(r, a, r->s[a] > 0 ? n[a] : 0);

			if (t0 > ta)
				ta = t0;
			if (t1 < tb)
				tb = t1;
		}
	}
	if (!(ta <= tb))
		return 0;
	if (top > 0 && nvals > 0 && !brackets(m->root[0], m->root[1], vals,
	    nvals))
		return 0;
	r->flip = (!r->up[0]) | (!r->up[1]) << 1 | (!r->up[2]) << 2;
	/* a hierarchy's level 0 is the leaf: width 1 */
	r->w = top > 0 ? (const int64_t (*)[3])m->width : unit_w;
	r->iw = top > 0 ? (const double (*)[3])m->iwidth : unit_iw;
	*tap = ta;
	*tbp = tb;
	return 1;
}

/* start_leaf: the leaf ray r is in just after ta (the segment's start)
 * and its entry axis *e (-1: ta is on no face of it) */
static inline void
start_leaf(const ray *r, double ta, int64_t leaf[3], int *e)
{
	*e = -1;
	for (int a = 0; a < 3; a++) {
		if (r->s[a] == 0) {
			leaf[a] = r->fixed[a];
			continue;
		}
		leaf[a] = find_cell(r, 0, a, 0, r->n[a], ta, 1);
		if (tcross(r, a, r->s[a] > 0 ? leaf[a] : leaf[a] + 1) == ta)
			*e = a;
	}
}

/* ray_finish: ray_clip, and the start leaf and its entry axis *e
 * (start_leaf) */
static inline __attribute__((always_inline)) int
ray_finish(ray *r, const vx_macro *m, int top, const float *vals,
    int nvals, double *tap, double *tbp, int64_t leaf[3], int *e)
{
	if (!ray_clip(r, m, top, vals, nvals, tap, tbp))
		return 0;
	start_leaf(r, *tap, leaf, e);
	return 1;
}

void
vx_macro_cell_box(const vx_macro *m, int l, int64_t b, int64_t lo[3],
    int64_t hi[3])
{
	int64_t c[3] = { b % m->dims[l][0], (b / m->dims[l][0]) % m->dims[l][1],
	    b / (m->dims[l][0] * m->dims[l][1]) };
	ray r;

	/* the walk's own planes: the last cell's upper one is the grid's */
	r.w = (const int64_t (*)[3])m->width;
	for (int a = 0; a < 3; a++) {
		r.n[a] = m->dims[0][a];
		lo[a] = plane_lo(&r, l, a, c[a]);
		hi[a] = plane_hi(&r, l, a, c[a]);
	}
}

int
vx_macro_cell_brackets(const vx_macro *m, int l, int64_t b,
    const float *vals, int nvals)
{
	return brackets(m->mm[l][2 * b], m->mm[l][2 * b + 1], vals, nvals);
}

/* box_times: ray r's entry time *tin into box bx, the axis *e of the
 * crossing that enters it, and its exit time *tout; 0 when the ray runs
 * beside it along an axis it does not move on */
static inline __attribute__((always_inline)) int
box_times(const ray *r, const vx_cellbox *bx, double *tin, double *tout,
    int *e)
{
	double ti = -INFINITY, to = INFINITY;
	int a, ea = -1;

	for (a = 0; a < 3; a++) {
		int64_t lo = bx->lo[a], hi = bx->hi[a];

		if (r->s[a] == 0) {
			if (r->fixed[a] < lo || r->fixed[a] >= hi)
				return 0;
		} else {
			double tn = tcross(r, a, r->up[a] ? lo : hi);
			double tf = tcross(r, a, r->up[a] ? hi : lo);

			if (tn >= ti) {
				ti = tn;
				ea = a;
			}
			if (tf < to)
				to = tf;
		}
	}
	*tin = ti;
	*tout = to;
	*e = ea;
	return 1;
}

/* fp_holds: 1 when box bx's footprint holds query point q (NULL: every
 * point) */
static inline int
fp_holds(const vx_cellbox *bx, const int32_t *q)
{
	return q == NULL || (q[0] >= bx->fp[0] && q[0] <= bx->fp[2] &&
	    q[1] >= bx->fp[1] && q[1] <= bx->fp[3]);
}

double
vx_macro_boxes_entry(const vx_macro *m, const vx_cellbox *box,
    const uint32_t *ix, size_t nbox, const double o[3], const double d[3],
    const int32_t q[2])
{
	double best = INFINITY, tin, tout;
	int e;
	ray r;

	/* set up by ray_axes as for the walk: the same crossing times */
	if (!ray_axes(&r, m->dims[0], o, d))
		return INFINITY;
	for (size_t k = 0; k < nbox; k++) {
		const vx_cellbox *bx = ix != NULL ? box + ix[k] : box + k;

		if (bx->lb > best)
			break;
		if (fp_holds(bx, q) && box_times(&r, bx, &tin, &tout, &e) &&
		    !(tin > tout) && tin < best)
			best = tin;
	}
	/* +0 for -0: the same time whatever the boxes' order */
	return best + 0.0;
}

/* ---- cell masks ----
 * A level-1 macrocell's samples are read once each, a row of samples along
 * x at a time, into two bit masks per value v: below (bit x set when sample
 * x is finite and <= v) and above (finite and >= v).  A leaf brackets v by
 * the walk's test (lo <= v <= hi, lo and hi the least and greatest finite
 * corner) exactly when one of its 8 corners is below and one above: integer
 * samples are exact in float, and the walk's integer test (min <= floor(v),
 * max >= ceil(v)) says the same; NaN v brackets nothing either way.  A
 * leaf row's corners are samples x and x + 1 of four sample rows (two in
 * each of two planes), so its bits are (B | B >> 1) OR-ed over the four
 * rows, the same for A, then B & A.  Rows of up to VX_CELLMASK_MAXROW
 * leaves (one word).
 *
 * Blocks are built lazily, by the first walk that enters one: its state
 * goes 0 (not built) -> 1 (being built, by the thread that won the
 * compare-and-swap) -> 2 (built, bits published with release order).  A
 * walk that finds a block being built by another thread tests samples
 * there instead: the same decisions, so the result never depends on which
 * thread built what. */

/* Where SSE2 is there (every x86-64), a block whose rows' x offsets let it
 * (a linear layout, bricks 16 bytes wide or more; u8 and u16/i16 bricks 4
 * samples wide: every type's default bricks) tests a row W samples at a
 * time (f32 8, the others 16), in chunks of W samples from the row's
 * start, each chunk a few loads (runs of 16, 8 or 4 bytes adjacent in
 * memory: the plan is made once per block, the x offsets being the same
 * for every row) and one compare per test and 16 bytes; one function per
 * type and runs reads the block's planes (block_for).  u8 (u16, i16) in
 * bricks 4 samples wide reads four (two) rows at once, 16 bytes holding a
 * run of each (tile_rows, tile16_rows).  Integer tests are exact in the
 * type's own width: u8 v <= fl as min(v, fl) == v and v >= ce as
 * max(v, ce) == v; u16 and i16 as not v > fl and not ce > v (u16 made
 * signed by flipping its top bit), fl and ce clamped into the type's range
 * (a value that no sample can be below, or none above, brackets nothing
 * and was skipped before).  Floats: the same finiteness test as one at a
 * time.  The row's last samples after the chunks are read as a chunk
 * where they are adjacent and 16 or 32 bytes from them lie within the
 * volume's samples (the bits past the row are never used), else one at a
 * time.  Other blocks test four samples adjacent in memory at once where
 * they are (integers widened to 32 bits, where v <= fl and v >= ce as
 * v > ce - 1 are exact), else one at a time (MASK_ROWS).  The bits are
 * the same every way. */

/* leaf_rows: a plane of leaves' bits into out, n rows of nx leaves from
 * bit p, step bits apart: a leaf row's corners are samples x and x + 1 of
 * rows y and y + 1 of two planes of samples, whose rows' bits, OR-ed over
 * the two planes, are ub (below) and ua (above).  Two rows at a time where
 * SSE2 is there (four put as one word where they are 16 bits apart from a
 * word's start); rows that never straddle two words (step divides 64) put
 * without the test. */
static void
leaf_rows(uint64_t *restrict out, const uint64_t *ub, const uint64_t *ua,
    int64_t n, int64_t p, int64_t step, int nx)
{
	const uint64_t keep = nx >= 64 ? ~(uint64_t)0 :
	    ((uint64_t)1 << nx) - 1;
	const int one = 64 % step == 0 && nx <= step;
	uint64_t v[2];
	int64_t y = 0;
	int i;

#ifdef MASK_SIMD
	const __m128i kp = _mm_set1_epi64x((long long)keep);

	/* rows 16 bits apart from a word's start (u8, u16, i16 macrocells 16
	 * leaves wide): four rows a word */
	if (step == 16 && nx <= 16 && (p & 63) == 0)
		for (; y + 4 <= n; y += 4, p += 64) {
			uint64_t w[4];

			for (i = 0; i < 4; i += 2) {
				__m128i bb = _mm_or_si128(_mm_loadu_si128(
				    (const __m128i *)(const void *)(ub + y + i)),
				    _mm_loadu_si128((const __m128i *)(const
				    void *)(ub + y + i + 1)));
				__m128i aa = _mm_or_si128(_mm_loadu_si128(
				    (const __m128i *)(const void *)(ua + y + i)),
				    _mm_loadu_si128((const __m128i *)(const
				    void *)(ua + y + i + 1)));

				bb = _mm_or_si128(bb, _mm_srli_epi64(bb, 1));
				aa = _mm_or_si128(aa, _mm_srli_epi64(aa, 1));
				_mm_storeu_si128((__m128i *)(void *)(w + i),
				    _mm_and_si128(_mm_and_si128(bb, aa), kp));
			}
			out[p >> 6] |= w[0] | w[1] << 16 | w[2] << 32 |
			    w[3] << 48;
		}
	for (; y + 2 <= n; y += 2) {
		__m128i bb = _mm_or_si128(_mm_loadu_si128((const __m128i *)
		    (const void *)(ub + y)), _mm_loadu_si128((const __m128i *)
		    (const void *)(ub + y + 1)));
		__m128i aa = _mm_or_si128(_mm_loadu_si128((const __m128i *)
		    (const void *)(ua + y)), _mm_loadu_si128((const __m128i *)
		    (const void *)(ua + y + 1)));

		bb = _mm_or_si128(bb, _mm_srli_epi64(bb, 1));
		aa = _mm_or_si128(aa, _mm_srli_epi64(aa, 1));
		_mm_storeu_si128((__m128i *)(void *)v, _mm_and_si128(
		    _mm_and_si128(bb, aa), kp));
		for (i = 0; i < 2; i++, p += step) {
			int sh = (int)(p & 63);

			out[p >> 6] |= v[i] << sh;
			if (!one && sh + nx > 64)
				out[(p >> 6) + 1] |= v[i] >> (64 - sh);
		}
	}
#endif
	for (; y < n; y++, p += step) {
		uint64_t bb = ub[y] | ub[y + 1];
		uint64_t aa = ua[y] | ua[y + 1];
		int sh = (int)(p & 63);

		v[0] = (bb | bb >> 1) & (aa | aa >> 1) & keep;
		out[p >> 6] |= v[0] << sh;
		if (sh + nx > 64)
			out[(p >> 6) + 1] |= v[0] >> (64 - sh);
	}
	(void)one;
	(void)i;
}

/* row_planes: row y's bits of plane z (bb below, aa above) OR-ed with
 * the previous plane's row into ub, ua (a leaf row's corners lie on both
 * planes), and kept in pb, pa for the next plane */
static inline void
row_planes(uint64_t *ub, uint64_t *ua, uint64_t *pb, uint64_t *pa, int64_t y,
    uint64_t bb, uint64_t aa)
{
	ub[y] = pb[y] | bb;
	ua[y] = pa[y] | aa;
	pb[y] = bb;
	pa[y] = aa;
}

#ifdef MASK_SIMD
typedef struct quad_k {
	__m128i fl, cm1;          /* integer thresholds: fl, ce - 1 */
	__m128 val, fmax, abs;    /* f32: the value, FLT_MAX, ~sign */
	__m128i f8, c8;           /* u8: fl, ce (each in 0..255) */
	__m128i f16, c16;         /* u16 (biased), i16: fl, ce in 16 bits */
} quad_k;

static inline void
quad_keys(quad_k *k, vx_type t, int64_t fl, int64_t ce, float val)
{
	/* integer samples lie within 16 bits: clamping far outside keeps
	 * every answer */
	int64_t f = fl < -0x40000000 ? -0x40000000 : fl > 0x40000000 ?
	    0x40000000 : fl;
	int64_t c = ce < -0x40000000 ? -0x40000000 : ce > 0x40000000 ?
	    0x40000000 : ce;
	/* the type's range (fl below it or ce above it: skipped), and the
	 * bias that makes u16 signed */
	int64_t tlo = t == VX_I16 ? -32768 : 0;
	int64_t thi = t == VX_U8 ? 255 : t == VX_I16 ? 32767 : 65535;
	int64_t bias = t == VX_U16 ? 32768 : 0;
	int64_t f1 = f > thi ? thi : f < tlo ? tlo : f;
	int64_t c1 = c < tlo ? tlo : c > thi ? thi : c;

	k->fl = _mm_set1_epi32((int)f);
	k->cm1 = _mm_set1_epi32((int)(c - 1));
	k->val = _mm_set1_ps(val);
	k->fmax = _mm_set1_ps(FLT_MAX);
	k->abs = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
	k->f8 = _mm_set1_epi8((char)(f1 & 255));
	k->c8 = _mm_set1_epi8((char)(c1 & 255));
	k->f16 = _mm_set1_epi16((short)(f1 - bias));
	k->c16 = _mm_set1_epi16((short)(c1 - bias));
}

static inline __m128i
load_u32(const char *p)
{
	uint32_t w;

	memcpy(&w, p, sizeof w);
	return _mm_cvtsi32_si128((int)w);
}

static inline __m128i
load_u64(const char *p)
{
	return _mm_loadl_epi64((const __m128i *)(const void *)p);
}

/* load16: 16 bytes in runs of run bytes (16, 8 or 4) at p + ro[0],
 * p + ro[1], ... */
static inline __m128i
load16(const char *p, const int64_t *ro, int run)
{
	if (run == 16)
		return _mm_loadu_si128((const __m128i *)(const void *)(p +
		    ro[0]));
	if (run == 8)
		return _mm_unpacklo_epi64(load_u64(p + ro[0]),
		    load_u64(p + ro[1]));
	return _mm_unpacklo_epi64(_mm_unpacklo_epi32(load_u32(p + ro[0]),
	    load_u32(p + ro[1])), _mm_unpacklo_epi32(load_u32(p + ro[2]),
	    load_u32(p + ro[3])));
}

/* test_u8: v's 16 samples' below bits (*b, v <= fl) and above bits
 * (*a, v >= ce) */
static inline void
test_u8(__m128i v, const quad_k *k, unsigned *b, unsigned *a)
{
	*b = (unsigned)_mm_movemask_epi8(_mm_cmpeq_epi8(_mm_min_epu8(v,
	    k->f8), v));
	*a = (unsigned)_mm_movemask_epi8(_mm_cmpeq_epi8(_mm_max_epu8(v,
	    k->c8), v));
}

/* chunk_*: the below bits (*b) and above bits (*a) of a chunk of W samples
 * at row p, in runs of run bytes at byte offsets ro */
static inline void
chunk_u8(const char *p, const int64_t *ro, int run, const quad_k *k,
    unsigned *b, unsigned *a)
{
	test_u8(load16(p, ro, run), k, b, a);
}

/* test_s16: the same for v0, v1 (16 signed samples): not above fl, not
 * below ce */
static inline void
test_s16(__m128i v0, __m128i v1, const quad_k *k, unsigned *b,
    unsigned *a)
{
	*b = (unsigned)_mm_movemask_epi8(_mm_packs_epi16(_mm_cmpgt_epi16(v0,
	    k->f16), _mm_cmpgt_epi16(v1, k->f16))) ^ 0xffffu;
	*a = (unsigned)_mm_movemask_epi8(_mm_packs_epi16(_mm_cmpgt_epi16(k->c16,
	    v0), _mm_cmpgt_epi16(k->c16, v1))) ^ 0xffffu;
}

/* test_s16_8: the same for 8 samples v */
static inline void
test_s16_8(__m128i v, const quad_k *k, unsigned *b, unsigned *a)
{
	unsigned m = (unsigned)_mm_movemask_epi8(_mm_packs_epi16(
	    _mm_cmpgt_epi16(v, k->f16), _mm_cmpgt_epi16(k->c16, v))) ^ 0xffffu;

	*b = m & 255u;
	*a = m >> 8;
}

/* load16s: load16 made signed: u16 (flip) with its top bit flipped, so
 * that signed compares order it as unsigned; i16 as it is */
static inline __m128i
load16s(const char *p, const int64_t *ro, int run, int flip)
{
	__m128i v = load16(p, ro, run);

	return flip ? _mm_xor_si128(v, _mm_set1_epi16(-0x8000)) : v;
}

static inline void
chunk_u16(const char *p, const int64_t *ro, int run, const quad_k *k,
    unsigned *b, unsigned *a)
{
	test_s16(load16s(p, ro, run, 1), load16s(p, ro + 16 / run, run, 1), k,
	    b, a);
}

static inline void
chunk_i16(const char *p, const int64_t *ro, int run, const quad_k *k,
    unsigned *b, unsigned *a)
{
	test_s16(load16s(p, ro, run, 0), load16s(p, ro + 16 / run, run, 0), k,
	    b, a);
}

/* tail_*: as chunk_* with runs of 16 bytes at ro[0], ro[1], only n samples
 * wanted: 16 bytes when they hold those */
static inline void
tail_u8(const char *p, const int64_t *ro, int n, const quad_k *k,
    unsigned *b, unsigned *a)
{
	(void)n;
	chunk_u8(p, ro, 16, k, b, a);
}

static inline void
tail_16(const char *p, const int64_t *ro, int n, const quad_k *k,
    unsigned *b, unsigned *a, int flip)
{
	if (n > 8)
		test_s16(load16s(p, ro, 16, flip), load16s(p, ro + 1, 16, flip),
		    k, b, a);
	else
		test_s16_8(load16s(p, ro, 16, flip), k, b, a);
}

static inline void
tail_u16(const char *p, const int64_t *ro, int n, const quad_k *k,
    unsigned *b, unsigned *a)
{
	tail_16(p, ro, n, k, b, a, 1);
}

static inline void
tail_i16(const char *p, const int64_t *ro, int n, const quad_k *k,
    unsigned *b, unsigned *a)
{
	tail_16(p, ro, n, k, b, a, 0);
}

static inline void
chunk_f32(const char *p, const int64_t *ro, int run, const quad_k *k,
    unsigned *b, unsigned *a)
{
	__m128 v0 = _mm_castsi128_ps(load16(p, ro, run));
	__m128 v1 = _mm_castsi128_ps(load16(p, ro + 16 / run, run));
	__m128 f0 = _mm_cmple_ps(_mm_and_ps(v0, k->abs), k->fmax);
	__m128 f1 = _mm_cmple_ps(_mm_and_ps(v1, k->abs), k->fmax);
	__m128i b01 = _mm_packs_epi32(
	    _mm_castps_si128(_mm_and_ps(_mm_cmple_ps(v0, k->val), f0)),
	    _mm_castps_si128(_mm_and_ps(_mm_cmple_ps(v1, k->val), f1)));
	__m128i a01 = _mm_packs_epi32(
	    _mm_castps_si128(_mm_and_ps(_mm_cmpge_ps(v0, k->val), f0)),
	    _mm_castps_si128(_mm_and_ps(_mm_cmpge_ps(v1, k->val), f1)));
	unsigned m = (unsigned)_mm_movemask_epi8(_mm_packs_epi16(b01, a01));

	*b = m & 255u;
	*a = m >> 8;
}

/* chunk_plan: whether a block's rows can be read in chunks of w samples of
 * sz bytes, the row's ns samples at x offsets o: the longest runs among
 * runs (a set of 16, 8 and 4 bytes, each at least one sample) that every
 * chunk's samples come in (runs of r bytes are runs of r / 2 too), and
 * their byte offsets from the row's start into ro; 0 when there is no
 * chunk or one has no such runs */
static int
chunk_plan(const int64_t *o, int64_t ns, int w, int sz, int runs,
    int64_t *ro)
{
	int n = (int)(ns / w), c, r, best = 16, i;

	for (c = 0; c < n; c++) {
		const int64_t *q = o + (int64_t)c * w;

		for (r = best; r >= 4 && r >= sz; r /= 2) {
			int step = r / sz;

			if (!(runs & r))
				continue;
			for (i = 0; i < w; i++)
				if (q[i] != q[i - i % step] + i % step)
					break;
			if (i == w)
				break;
		}
		if (r < 4 || r < sz)
			return 0;
		best = r;
	}
	if (n == 0)
		return 0;
	for (i = 0; i < n * w * sz / best; i++)
		ro[i] = o[i * best / sz] * sz;
	return best;
}

static inline void
quad_int(__m128i v, const quad_k *k, unsigned *b, unsigned *a)
{
	*b = ~(unsigned)_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(v,
	    k->fl))) & 15u;
	*a = (unsigned)_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(v,
	    k->cm1)));
}

static inline void
quad_u8(const uint8_t *p, const quad_k *k, unsigned *b, unsigned *a)
{
	uint32_t w;
	__m128i z = _mm_setzero_si128(), v;

	memcpy(&w, p, sizeof w);
	v = _mm_cvtsi32_si128((int)w);
	v = _mm_unpacklo_epi16(_mm_unpacklo_epi8(v, z), z);
	quad_int(v, k, b, a);
}

static inline void
quad_u16(const uint16_t *p, const quad_k *k, unsigned *b, unsigned *a)
{
	__m128i v = _mm_loadl_epi64((const __m128i *)(const void *)p);

	quad_int(_mm_unpacklo_epi16(v, _mm_setzero_si128()), k, b, a);
}

static inline void
quad_i16(const int16_t *p, const quad_k *k, unsigned *b, unsigned *a)
{
	__m128i v = _mm_loadl_epi64((const __m128i *)(const void *)p);

	quad_int(_mm_srai_epi32(_mm_unpacklo_epi16(v, v), 16), k, b, a);
}

static inline void
quad_f32(const float *p, const quad_k *k, unsigned *b, unsigned *a)
{
	__m128 v = _mm_loadu_ps(p);
	__m128 fin = _mm_cmple_ps(_mm_and_ps(v, k->abs), k->fmax);

	*b = (unsigned)_mm_movemask_ps(_mm_and_ps(_mm_cmple_ps(v, k->val), fin));
	*a = (unsigned)_mm_movemask_ps(_mm_and_ps(_mm_cmpge_ps(v, k->val), fin));
}

static inline void
tail_f32(const char *p, const int64_t *ro, int n, const quad_k *k,
    unsigned *b, unsigned *a)
{
	if (n > 4)
		chunk_f32(p, ro, 16, k, b, a);
	else
		quad_f32((const float *)(const void *)(p + ro[0]), k, b, a);
}

#define QUAD_RUN(T, QUAD)                                                \
	if (x + 4 <= ns[0] && o[x + 1] == o[x] + 1 &&                    \
	    o[x + 2] == o[x] + 2 && o[x + 3] == o[x] + 3) {              \
		unsigned b4, a4;                                         \
		QUAD((const T *)row + o[x], &qk, &b4, &a4);              \
		bb |= (uint64_t)b4 << x;                                 \
		aa |= (uint64_t)a4 << x;                                 \
		x += 4;                                                  \
		continue;                                                \
	}

/* a block's plan for reading its planes' rows in chunks, for one value */
typedef struct chunk_rows {
	const quad_k *k;
	int64_t fl, ce;           /* integer thresholds (the last samples) */
	float val;
	const char *base;         /* the samples */
	const int64_t *oz;        /* the planes' offsets, in samples */
	const int64_t *oy;        /* the rows' offsets, in samples */
	int64_t nz, ny;           /* planes, rows */
	int64_t ntile;            /* rows 0 to ntile - 1 read as tiles */
	const int64_t *ro;        /* the chunks' runs' byte offsets in a row */
	int nch;                  /* chunks in a row, >= 1 */
	int nt;                   /* samples after them, at byte offsets ot */
	const int64_t *ot;
	int tv;                   /* 1: those samples are one chunk's first,
	                             at ot[0], ot[1] in runs of 16 bytes
	                             (the rest read, in bounds, not used) */
	uint64_t *pb, *pa, *ub, *ua;   /* rows' bits: as MASK_ROWS */
	uint64_t *out;            /* the block's bits */
	int64_t step, pstep;      /* leaf rows', planes' bits apart */
	int nx;                   /* leaves in a row */
} chunk_rows;

/* CHUNK_PLANE: NAME(r, pl, y0, y1, pb, pa, ub, ua, nch) reads rows y0 to
 * y1 - 1 of the plane at pl as r plans, nch chunks of W samples of type T
 * in runs of R bytes, into below and above bits: a row's bits OR-ed with
 * the previous plane's row (pb, pa: in) into ub, ua, and its own into pb,
 * pa */
#define CHUNK_PLANE(NAME, T, CHUNK, TAIL, W, R, BELOW, ABOVE)            \
static inline __attribute__((always_inline)) void                        \
NAME(const chunk_rows *r, const char *pl, int64_t y0, int64_t y1,        \
    uint64_t *restrict pb, uint64_t *restrict pa, uint64_t *restrict ub, \
    uint64_t *restrict ua, const int nch)                                \
{                                                                        \
	const quad_k k = *r->k;                                          \
	const int64_t fl = r->fl, ce = r->ce;                            \
	const int64_t *oy = r->oy, *ro = r->ro, *ot = r->ot;             \
	const float val = r->val;                                        \
	const int nt = r->nt, tv = r->tv;                                \
	const int stride = (W) * (int)sizeof(T) / (R);                   \
	int64_t y;                                                       \
	int ch, t;                                                       \
									 \
	(void)fl;                                                        \
	(void)ce;                                                        \
	(void)val;                                                       \
	for (y = y0; y < y1; y++) {                                      \
		const char *row = pl + oy[y] * (int64_t)sizeof(T);       \
		uint64_t bb, aa;                                         \
		unsigned bw, aw;                                         \
									 \
		CHUNK(row, ro, R, &k, &bw, &aw);                         \
		bb = bw;                                                 \
		aa = aw;                                                 \
		for (ch = 1; ch < nch; ch++) {                           \
			CHUNK(row, ro + ch * stride, R, &k, &bw, &aw);   \
			bb |= (uint64_t)bw << (ch * (W));                \
			aa |= (uint64_t)aw << (ch * (W));                \
		}                                                        \
		if (tv) {                                                \
			TAIL(row, ot, nt, &k, &bw, &aw);                 \
			bb |= (uint64_t)bw << (nch * (W));               \
			aa |= (uint64_t)aw << (nch * (W));               \
		} else                                                   \
			for (t = 0; t < nt; t++) {                       \
				T v;                                     \
									 \
				memcpy(&v, row + ot[t], sizeof v);       \
				bb |= (uint64_t)(BELOW) << (nch * (W) + t); \
				aa |= (uint64_t)(ABOVE) << (nch * (W) + t); \
			}                                                \
		row_planes(ub, ua, pb, pa, y, bb, aa);                   \
	}                                                                \
}

CHUNK_PLANE(chunk_u8_16, uint8_t, chunk_u8, tail_u8, 16, 16, v <= fl,
    v >= ce)
CHUNK_PLANE(chunk_u8_4, uint8_t, chunk_u8, tail_u8, 16, 4, v <= fl, v >= ce)
CHUNK_PLANE(chunk_u16_16, uint16_t, chunk_u16, tail_u16, 16, 16, v <= fl,
    v >= ce)
CHUNK_PLANE(chunk_u16_8, uint16_t, chunk_u16, tail_u16, 16, 8, v <= fl,
    v >= ce)
CHUNK_PLANE(chunk_i16_16, int16_t, chunk_i16, tail_i16, 16, 16, v <= fl,
    v >= ce)
CHUNK_PLANE(chunk_i16_8, int16_t, chunk_i16, tail_i16, 16, 8, v <= fl,
    v >= ce)
CHUNK_PLANE(chunk_f32_16, float, chunk_f32, tail_f32, 8, 16,
    fabsf(v) <= FLT_MAX && v <= val, fabsf(v) <= FLT_MAX && v >= val)

/* load4: 16 bytes at each of row + q[0..3] */
static inline __attribute__((always_inline)) void
load4(const char *row, const int64_t *q, __m128i *v0, __m128i *v1,
    __m128i *v2, __m128i *v3)
{
	*v0 = _mm_loadu_si128((const __m128i *)(const void *)(row + q[0]));
	*v1 = _mm_loadu_si128((const __m128i *)(const void *)(row + q[1]));
	*v2 = _mm_loadu_si128((const __m128i *)(const void *)(row + q[2]));
	*v3 = _mm_loadu_si128((const __m128i *)(const void *)(row + q[3]));
}

/* tile_u8: as chunk_u8_4, rows y0 to y1 - 1 (y1 - y0 a multiple of 4) of
 * u8 samples in runs of 4 bytes, where each four rows from y0 on lie 4
 * bytes apart (a bricked layout's bricks 4 samples wide), so that 16 bytes
 * hold a run of each of the four: read as such tiles, turned into rows,
 * the last samples too (r->tv; nt <= 4; the bits past them, garbage, go
 * past the row's end, where no leaf reads them).  tile_rows: its body,
 * nch the chunks per row (a constant for one chunk, the usual) */
static inline __attribute__((always_inline)) void
tile_rows(const chunk_rows *r, const char *pl, int64_t y0, int64_t y1,
    uint64_t *restrict pb, uint64_t *restrict pa, uint64_t *restrict ub,
    uint64_t *restrict ua, const int nch)
{
	const quad_k k = *r->k;
	const int64_t *oy = r->oy, *ro = r->ro;
	const int sh = nch * 16, nt = r->nt;
	const int64_t t0 = r->ot[0];
	int64_t y;
	int ch, i;

	for (y = y0; y < y1; y += 4) {
		const char *row = pl + oy[y];
		uint64_t bb[4] = { 0, 0, 0, 0 }, aa[4] = { 0, 0, 0, 0 };
		unsigned bw, aw;

		for (ch = 0; ch < nch; ch++) {
			const int64_t *q = ro + ch * 4;
			__m128i v0, v1, v2, v3;

			load4(row, q, &v0, &v1, &v2, &v3);
			__m128i l01 = _mm_unpacklo_epi32(v0, v1);
			__m128i l23 = _mm_unpacklo_epi32(v2, v3);
			__m128i h01 = _mm_unpackhi_epi32(v0, v1);
			__m128i h23 = _mm_unpackhi_epi32(v2, v3);
			__m128i rw[4];

			rw[0] = _mm_unpacklo_epi64(l01, l23);
			rw[1] = _mm_unpackhi_epi64(l01, l23);
			rw[2] = _mm_unpacklo_epi64(h01, h23);
			rw[3] = _mm_unpackhi_epi64(h01, h23);
			for (i = 0; i < 4; i++) {
				test_u8(rw[i], &k, &bw, &aw);
				bb[i] |= (uint64_t)bw << (ch * 16);
				aa[i] |= (uint64_t)aw << (ch * 16);
			}
		}
		if (nt != 0) {
			test_u8(_mm_loadu_si128((const __m128i *)(const void *)
			    (row + t0)), &k, &bw, &aw);
			for (i = 0; i < 4; i++) {
				bb[i] |= (uint64_t)(bw >> 4 * i) << sh;
				aa[i] |= (uint64_t)(aw >> 4 * i) << sh;
			}
		}
		for (i = 0; i < 4; i++) {
			ub[y + i] = pb[y + i] | bb[i];
			ua[y + i] = pa[y + i] | aa[i];
			pb[y + i] = bb[i];
			pa[y + i] = aa[i];
		}
	}
}

/* tile_16: as tile_u8 for 16-bit samples (flip: u16) in runs of 8 bytes,
 * each two rows from y0 on 8 bytes apart (bricks 4 samples wide), so that
 * 16 bytes hold a run of each of the two; the last samples too (r->tv;
 * nt <= 4).  tile16_rows: its body */
static inline __attribute__((always_inline)) void
tile16_rows(const chunk_rows *r, const char *pl, int64_t y0, int64_t y1,
    uint64_t *restrict pb, uint64_t *restrict pa, uint64_t *restrict ub,
    uint64_t *restrict ua, const int nch, const int flip)
{
	const quad_k k = *r->k;
	const int64_t *oy = r->oy, *ro = r->ro;
	const int sh = nch * 16, nt = r->nt;
	const int64_t t0 = r->ot[0];
	const __m128i top = _mm_set1_epi16(flip ? -0x8000 : 0);
	int64_t y;
	int ch;

	for (y = y0; y < y1; y += 2) {
		const char *row = pl + oy[y] * 2;
		uint64_t b0 = 0, b1 = 0, a0 = 0, a1 = 0;
		unsigned bw, aw;

		for (ch = 0; ch < nch; ch++) {
			const int64_t *q = ro + ch * 4;
			__m128i v0, v1, v2, v3;

			load4(row, q, &v0, &v1, &v2, &v3);

			if (flip) {
				v0 = _mm_xor_si128(v0, top);
				v1 = _mm_xor_si128(v1, top);
				v2 = _mm_xor_si128(v2, top);
				v3 = _mm_xor_si128(v3, top);
			}
			test_s16(_mm_unpacklo_epi64(v0, v1),
			    _mm_unpacklo_epi64(v2, v3), &k, &bw, &aw);
			b0 |= (uint64_t)bw << (ch * 16);
			a0 |= (uint64_t)aw << (ch * 16);
			test_s16(_mm_unpackhi_epi64(v0, v1),
			    _mm_unpackhi_epi64(v2, v3), &k, &bw, &aw);
			b1 |= (uint64_t)bw << (ch * 16);
			a1 |= (uint64_t)aw << (ch * 16);
		}
		if (nt != 0) {
			__m128i v = _mm_loadu_si128((const __m128i *)(const
			    void *)(row + t0));

			test_s16_8(flip ? _mm_xor_si128(v, top) : v, &k, &bw,
			    &aw);
			b0 |= (uint64_t)bw << sh;
			a0 |= (uint64_t)aw << sh;
			b1 |= (uint64_t)(bw >> 4) << sh;
			a1 |= (uint64_t)(aw >> 4) << sh;
		}
		ub[y] = pb[y] | b0;
		ua[y] = pa[y] | a0;
		pb[y] = b0;
		pa[y] = a0;
		ub[y + 1] = pb[y + 1] | b1;
		ua[y + 1] = pa[y + 1] | a1;
		pb[y + 1] = b1;
		pa[y + 1] = a1;
	}
}

static inline __attribute__((always_inline)) void
tile_u16(const chunk_rows *r, const char *pl, int64_t y0, int64_t y1,
    uint64_t *restrict pb, uint64_t *restrict pa, uint64_t *restrict ub,
    uint64_t *restrict ua, const int nch)
{
	tile16_rows(r, pl, y0, y1, pb, pa, ub, ua, nch, 1);
}

static inline __attribute__((always_inline)) void
tile_i16(const chunk_rows *r, const char *pl, int64_t y0, int64_t y1,
    uint64_t *restrict pb, uint64_t *restrict pa, uint64_t *restrict ub,
    uint64_t *restrict ua, const int nch)
{
	tile16_rows(r, pl, y0, y1, pb, pa, ub, ua, nch, 0);
}

static inline __attribute__((always_inline)) void
tile_none(const chunk_rows *r, const char *pl, int64_t y0, int64_t y1,
    uint64_t *restrict pb, uint64_t *restrict pa, uint64_t *restrict ub,
    uint64_t *restrict ua, const int nch)
{
	(void)r, (void)pl, (void)y0, (void)y1, (void)pb, (void)pa, (void)ub;
	(void)ua, (void)nch;
}

/* BLOCK_FN: NAME(r) makes a block's bits for one value as r plans: each
 * plane's rows 0 to r->ntile - 1 read by TILE, the others by ROWS, then
 * its leaf rows (with the plane before); NAME_body with nch chunks a row,
 * a constant where it is 1 (the usual) */
#define BLOCK_FN(NAME, T, TILE, ROWS)                                    \
static inline __attribute__((always_inline)) void                        \
NAME##_body(const chunk_rows *r, const int nch)                          \
{                                                                        \
	const int64_t ny = r->ny, nty = r->ntile;                        \
	uint64_t *pb = r->pb, *pa = r->pa, *ub = r->ub, *ua = r->ua;     \
	int64_t z;                                                       \
									 \
	for (z = 0; z < r->nz; z++) {                                    \
		const char *pl = r->base + r->oz[z] * (int64_t)sizeof(T); \
									 \
		TILE(r, pl, 0, nty, pb, pa, ub, ua, nch);                \
		ROWS(r, pl, nty, ny, pb, pa, ub, ua, nch);               \
		if (z > 0)                                               \
			leaf_rows(r->out, ub, ua, ny - 1, r->pstep *     \
			    (z - 1), r->step, r->nx);                    \
	}                                                                \
}                                                                        \
									 \
static void                                                              \
NAME(const chunk_rows *r)                                                \
{                                                                        \
	if (r->nch == 1)                                                 \
		NAME##_body(r, 1);                                       \
	else                                                             \
		NAME##_body(r, r->nch);                                  \
}

/* the layouts that pay: linear and any bricks 16 bytes wide or more (runs
 * of 16), u8 bricks 4 wide (tiles, or rows where the block's rows do not
 * fall on the bricks' edges), u16 and i16 bricks 4 wide (the same): every
 * type's default bricks; others test samples four at a time (MASK_ROWS) */
BLOCK_FN(block_u8_16, uint8_t, tile_none, chunk_u8_16)
BLOCK_FN(block_u8_4, uint8_t, tile_rows, chunk_u8_4)
BLOCK_FN(block_u16_16, uint16_t, tile_none, chunk_u16_16)
BLOCK_FN(block_u16_8, uint16_t, tile_u16, chunk_u16_8)
BLOCK_FN(block_i16_16, int16_t, tile_none, chunk_i16_16)
BLOCK_FN(block_i16_8, int16_t, tile_i16, chunk_i16_8)
BLOCK_FN(block_f32_16, float, tile_none, chunk_f32_16)

typedef void block_fn(const chunk_rows *);

/* block_for: the block reader for type t and runs of run bytes; NULL:
 * none */
static block_fn *
block_for(vx_type t, int run)
{
	switch (t) {
	case VX_U8:
		return run == 16 ? block_u8_16 : run == 4 ? block_u8_4 : NULL;
	case VX_U16:
		return run == 16 ? block_u16_16 : run == 8 ? block_u16_8 : NULL;
	case VX_I16:
		return run == 16 ? block_i16_16 : run == 8 ? block_i16_8 : NULL;
	case VX_F32:
		return run == 16 ? block_f32_16 : NULL;
	default:
		return NULL;
	}
}
#else
#define QUAD_RUN(T, QUAD)
#endif

/* MASK_ROWS: plane z's rows' below and above bits, four samples at once
 * where they are adjacent, each row's OR-ed with the previous plane's row
 * (pb, pa: in) into ub, ua, and its own into pb, pa */
#define MASK_ROWS(T, QUAD, BELOW, ABOVE)                                 \
	do {                                                             \
		const T *dd = (const T *)g->data;                        \
		for (y = 0; y < ns[1]; y++) {                            \
			const T *row = dd + g->lay.off[1][lo[1] + y] +   \
			    g->lay.off[2][lo[2] + z];                    \
			const int64_t *o = ox + lo[0];                   \
			uint64_t bb = 0, aa = 0;                         \
			for (x = 0; x < ns[0];) {                        \
				QUAD_RUN(T, QUAD)                        \
				T v = row[o[x]];                         \
				bb |= (uint64_t)(BELOW) << x;            \
				aa |= (uint64_t)(ABOVE) << x;            \
				x++;                                     \
			}                                                \
			row_planes(ub, ua, pb, pa, y, bb, aa);           \
		}                                                        \
	} while (0)

/* mask_block: the bits of level-1 macrocell c (linear index) into out
 * (zeroed) */
static void
mask_block(const vx_macro *m, const vx_grid *g, int64_t c,
    const float *vals, int nvals, uint64_t *out)
{
	/* a plane's rows' bits, and those OR-ed with the previous plane's */
	uint64_t pb[VX_MACRO_MAXSIZE + 1], pa[VX_MACRO_MAXSIZE + 1];
	uint64_t ub[VX_MACRO_MAXSIZE + 1], ua[VX_MACRO_MAXSIZE + 1];
	const int64_t *ox = g->lay.off[0];
	const int64_t *w = m->width[1];
	int64_t b[3], lo[3], nl[3], ns[3], x, y, z;
	int a, j;
#ifdef MASK_SIMD
	/* the chunks' runs' byte offsets in a row (at most
	 * VX_CELLMASK_MAXROW + 1 samples in runs of 4 bytes or more), the
	 * last samples' */
	int64_t ro[VX_CELLMASK_MAXROW + 1], ot[16];
	block_fn *block = NULL;
	chunk_rows cr;
#endif

	b[0] = c % m->dims[1][0];
	b[1] = c / m->dims[1][0] % m->dims[1][1];
	b[2] = c / m->dims[1][0] / m->dims[1][1];
	for (a = 0; a < 3; a++) {
		lo[a] = b[a] * w[a];
		nl[a] = m->dims[0][a] - lo[a] < w[a] ? m->dims[0][a] - lo[a] :
		    w[a];
		ns[a] = nl[a] + 1;
	}
#ifdef MASK_SIMD
	if (ns[0] <= VX_CELLMASK_MAXROW + 1 && g->type >= VX_U8 &&
	    g->type <= VX_F32) {
		int cw = g->type == VX_F32 ? 8 : 16;
		int sz = (int)vx_type_size(g->type);
		/* the runs block_for has readers for */
		int run = chunk_plan(ox + lo[0], ns[0], cw, sz,
		    g->type == VX_U8 ? 16 | 4 : g->type == VX_F32 ? 16 :
		    16 | 8, ro);

		if (run != 0) {
			const int64_t *oy = g->lay.off[1] + lo[1];
			const int64_t *oz = g->lay.off[2] + lo[2];
			const int64_t *o = ox + lo[0];
			int64_t xt, top = 0, yt = 0, zt = 0;

			cr.base = (const char *)g->data;
			cr.oz = oz;
			cr.oy = oy;
			cr.nz = ns[2];
			cr.ny = ns[1];
			cr.ntile = 0;
			cr.ro = ro;
			cr.nch = (int)(ns[0] / cw);
			cr.nt = (int)(ns[0] % cw);
			cr.ot = ot;
			xt = (int64_t)cr.nch * cw;
			/* the last samples as a chunk: adjacent, and the
			 * chunk's bytes (32 for f32) within the samples from
			 * every row of the block */
			for (y = 0; y < ns[1]; y++)
				yt = oy[y] > yt ? oy[y] : yt;
			for (z = 0; z < ns[2]; z++)
				zt = oz[z] > zt ? oz[z] : zt;
			for (a = 1; a < cr.nt && o[xt + a] == o[xt] + a; a++)
				;
			if (cr.nt > 0)
				top = (yt + zt + o[xt]) * sz +
				    (cr.nt * sz > 16 ? 32 : 16);
			cr.tv = cr.nt > 0 && a == cr.nt && top > 0 &&
			    (uint64_t)top <= (uint64_t)g->nsample *
			    (uint64_t)sz;
			if (cr.tv) {
				ot[0] = o[xt] * sz;
				ot[1] = ot[0] + 16;
			} else
				for (a = 0; a < cr.nt; a++)
					ot[a] = o[xt + a] * sz;
			/* u8 in runs of 4 bytes, 16-bit in runs of 8: tiles of
			 * four (two) rows that many bytes apart (the last
			 * samples as a tile too) */
			if ((g->type == VX_U8 && run == 4) ||
			    ((g->type == VX_U16 || g->type == VX_I16) &&
			    run == 8)) {
				int gr = 16 / run, d = run / sz;

				if (cr.nt == 0 || (cr.tv && cr.nt <= d)) {
					for (y = 0; y + gr <= ns[1]; y += gr) {
						for (a = 1; a < gr && oy[y + a] ==
						    oy[y] + a * d; a++)
							;
						if (a < gr)
							break;
					}
					cr.ntile = y;
				}
			}
			block = block_for(g->type, run);
			cr.pb = pb;
			cr.pa = pa;
			cr.ub = ub;
			cr.ua = ua;
			cr.out = out;
			cr.step = w[0];
			cr.pstep = w[0] * w[1];
			cr.nx = (int)nl[0];
		}
	}
#endif
	for (j = 0; j < nvals; j++) {
		float val = vals[j];
		double cv;
		int64_t fl, ce;

		if (val != val)
			continue;    /* NaN brackets nothing */
		/* integers: v <= val is v <= floor(val), v >= val is
		 * v >= ceil(val) (val clamped far outside the 16-bit range) */
		cv = val < -0x1p40f ? -0x1p40 : val > 0x1p40f ? 0x1p40 :
		    (double)val;
		fl = (int64_t)floor(cv);
		ce = (int64_t)ceil(cv);
		/* no sample below, or none above: no leaf brackets */
		if ((g->type == VX_U8 && (fl < 0 || ce > 255)) ||
		    (g->type == VX_U16 && (fl < 0 || ce > 65535)) ||
		    (g->type == VX_I16 && (fl < -32768 || ce > 32767)))
			continue;
		for (y = 0; y < ns[1]; y++)
			pb[y] = pa[y] = 0;
#ifdef MASK_SIMD
		quad_k qk;

		quad_keys(&qk, g->type, fl, ce, val);
		cr.k = &qk;
		cr.fl = fl;
		cr.ce = ce;
		cr.val = val;
		if (block != NULL) {
			block(&cr);
			continue;
		}
#endif
		for (z = 0; z < ns[2]; z++) {
			switch (g->type) {
			case VX_U8:
				MASK_ROWS(uint8_t, quad_u8, v <= fl, v >= ce);
				break;
			case VX_U16:
				MASK_ROWS(uint16_t, quad_u16, v <= fl,
				    v >= ce);
				break;
			case VX_I16:
				MASK_ROWS(int16_t, quad_i16, v <= fl, v >= ce);
				break;
			case VX_F32:
				MASK_ROWS(float, quad_f32,
				    fabsf(v) <= FLT_MAX && v <= val,
				    fabsf(v) <= FLT_MAX && v >= val);
				break;
			default: return;
			}
			if (z == 0)
				continue;
			leaf_rows(out, ub, ua, nl[1], w[0] * w[1] * (z - 1),
			    w[0], (int)nl[0]);
		}
	}
}

/* mask_build: mask_get's answer where b's bits are not known built: build
 * them now if no one has (out of line: once per block) */
static __attribute__((noinline)) const uint64_t *
mask_build(vx_cellmask *k, const vx_macro *m, const vx_grid *g, int64_t b)
{
	unsigned char st, want = 0;

	st = atomic_load_explicit(&k->state[b], memory_order_acquire);
	if (st == 2)
		return k->bits + k->slot[b];
	if (st == 1 || !atomic_compare_exchange_strong_explicit(&k->state[b],
	    &want, 1, memory_order_acquire, memory_order_acquire))
		return want == 2 ? k->bits + k->slot[b] : NULL;
	mask_block(m, g, b, k->vals, k->nvals, k->bits + k->slot[b]);
	atomic_store_explicit(&k->state[b], 2, memory_order_release);
	atomic_fetch_add_explicit(&k->built, 1, memory_order_relaxed);
	return k->bits + k->slot[b];
}

/* mask_get: the bits of level-1 macrocell b, built now if no one has; NULL
 * when b has none (it does not bracket) or another thread is building them
 * (the test for built bits inline, for the walk) */
static inline const uint64_t *
mask_get(vx_cellmask *k, const vx_macro *m, const vx_grid *g, int64_t b)
{
	int64_t s = k->slot[b];

	if (s < 0)
		return NULL;
	if (atomic_load_explicit(&k->state[b], memory_order_acquire) == 2)
		return k->bits + s;
	return mask_build(k, m, g, b);
}

/* row_bits: n <= 64 bits of array v from bit position p */
static inline uint64_t
row_bits(const uint64_t *v, int64_t p, int n)
{
	int sh = (int)(p & 63);
	uint64_t r = v[p >> 6] >> sh;

	if (sh + n > 64)
		r |= v[(p >> 6) + 1] << (64 - sh);
	return n >= 64 ? r : r & (((uint64_t)1 << n) - 1);
}

size_t
vx_cellmask_boxes(vx_cellmask *k, int64_t b, int sub, vx_cellbox *out)
{
	const vx_macro *m = k->m;
	const uint64_t *bits;
	const int64_t *w;
	int64_t lo[3], hi[3], nl[3], jy, jz, j, y, z;
	uint64_t full, ry[VX_MACRO_MAXSIZE], rz[VX_MACRO_MAXSIZE];
	size_t n = 0;

	if (!k->ready || k->slot[b] < 0)
		return 0;
	vx_macro_cell_box(m, 1, b, lo, hi);
	if (sub < 1 || (bits = mask_get(k, m, k->g, b)) == NULL) {
		if (out != NULL) {
			memcpy(out[0].lo, lo, sizeof lo);
			memcpy(out[0].hi, hi, sizeof hi);
		}
		return 1;
	}
	w = m->width[1];
	for (int a = 0; a < 3; a++)
		nl[a] = hi[a] - lo[a];
	full = sub < 64 ? ((uint64_t)1 << sub) - 1 : ~(uint64_t)0;
	/* per row of blocks along x: the rows of leaf bits of its planes
	 * of leaves OR-ed per y (ry) and per z (rz), and all of them (rx):
	 * a block's leaves whose bits are set span, along x, its sub bits
	 * of rx and along y (z), the first to the last ry (rz) that has any
	 * of those bits (a row is at most 64 leaves, so at most 64 blocks) */
	for (jz = 0; jz < nl[2]; jz += sub)
		for (jy = 0; jy < nl[1]; jy += sub) {
			uint64_t rx = 0;
			int64_t ny = nl[1] - jy < sub ? nl[1] - jy : sub;
			int64_t nz = nl[2] - jz < sub ? nl[2] - jz : sub;

			for (z = 0; z < nz; z++) {
				uint64_t oz = 0;

				for (y = 0; y < ny; y++) {
					uint64_t r = row_bits(bits, w[0] * (jy + y +
					    w[1] * (jz + z)), (int)nl[0]);

					ry[y] = z > 0 ? ry[y] | r : r;
					oz |= r;
				}
				rz[z] = oz;
				rx |= oz;
			}
			for (uint64_t rr = rx; rr != 0;
			    rr &= ~(full << (j * sub))) {
				uint64_t bm, xm;
				int64_t y0 = 0, y1 = ny - 1, z0 = 0, z1 = nz - 1;

				j = __builtin_ctzll(rr) / sub;
				if (out == NULL) {
					n++;
					continue;
				}
				bm = full << (j * sub);
				xm = rx >> (j * sub) & full;
				while (!(ry[y0] & bm))
					y0++;
				while (!(ry[y1] & bm))
					y1--;
				while (!(rz[z0] & bm))
					z0++;
				while (!(rz[z1] & bm))
					z1--;
				/* the box of the block's set bits */
				out[n].lo[0] = lo[0] + j * sub + __builtin_ctzll(xm);
				out[n].hi[0] = lo[0] + j * sub + 64 -
				    __builtin_clzll(xm);
				out[n].lo[1] = lo[1] + jy + y0;
				out[n].hi[1] = lo[1] + jy + y1 + 1;
				out[n].lo[2] = lo[2] + jz + z0;
				out[n].hi[2] = lo[2] + jz + z1 + 1;
				n++;
			}
		}
	return n;
}

/* leaf_bits: the mask bits of level-1 cell c1 (NULL: none), the index li
 * of leaf c0 in them and the index steps dl per axis in walking order */
static inline const uint64_t *
leaf_bits(vx_cellmask *mk, const vx_macro *m, const vx_grid *g,
    const ray *r, const int64_t c1[3], const int64_t c0[3], int64_t *li,
    int64_t dl[3])
{
	const int64_t *w = m->width[1];
	int64_t b = c1[0] + m->dims[1][0] * (c1[1] + m->dims[1][1] * c1[2]);
	const uint64_t *bits = mask_get(mk, m, g, b);

	if (bits != NULL) {
		*li = (c0[0] - c1[0] * w[0]) + w[0] * ((c0[1] - c1[1] * w[1]) +
		    w[1] * (c0[2] - c1[2] * w[2]));
		dl[0] = r->s[0];
		dl[1] = r->s[1] * w[0];
		dl[2] = r->s[2] * w[0] * w[1];
	}
	return bits;
}

/* children: the children [*k0, *k1) along axis a of level-l cell cl
 * (l >= 1; n: leaf dims, for the last, partial cells of level 0) */
static inline void
children(const vx_macro *m, int l, int a, int64_t cl, const int64_t n[3],
    int64_t *k0, int64_t *k1)
{
	int64_t dk = l > 1 ? m->dims[l - 1][a] : n[a];
	int64_t lo = cl * m->size[l][a], hi = lo + m->size[l][a];

	if (hi > dk)
		hi = dk;
	*k0 = lo;
	*k1 = hi;
}

/* top_level: the walk's state at its start level top: the range of its
 * cell c[top] (lim, in walking order: the whole level) and the cell's exit
 * time per axis (tn) */
static void
top_level(const ray *r, const vx_macro *m, int top, const int64_t n[3],
    int64_t c[][3], int64_t lim[][3], double tn[][3])
{
	for (int a = 0; a < 3; a++) {
		lim[top][a] = r->up[a] ? (top ? m->dims[top][a] : n[a]) : -1;
		tn[top][a] = t_exit_of(r, top, a, c[top][a]);
	}
}

/* walk: the traversal behind the public entry points.  top is the level
 * whose DDA starts the walk (0: flat).  n: leaf dims.  g: the volume whose
 * cells are the leaves, or NULL; mm0: stored leaf ranges or NULL. */
static int
walk(const vx_macro *m, int top, const int64_t n[3], const vx_grid *g,
    const float *mm0, vx_cellmask *mk, const double o[3],
    const double d[3], double tmin, double tmax, const float *vals,
    int nvals, vx_visit_fn fn, void *ctx, vx_trav_stats *st)
{
	int64_t c[VX_MACRO_MAXLEV + 1][3];     /* current cell per level */
	int64_t lim[VX_MACRO_MAXLEV + 1][3];   /* first index past its
	                                          siblings, walking order */
	double tn[VX_MACRO_MAXLEV + 1][3];     /* next face crossing per axis */
	int64_t leaf[3];
	vx_trav_stats s;
	vx_leaf_visit v;
	double ta = tmin, tb = tmax, t, texit;
	int a, l, e, ax, start, cont = 0, rc = 0;
	ray r;

	memset(&s, 0, sizeof s);
	s.rays = 1;
	if (n[0] <= 0 || n[1] <= 0 || n[2] <= 0 || !(ta <= tb) ||
	    !ray_axes(&r, n, o, d))
		goto done;
	if (!ray_finish(&r, m, top, vals, nvals, &ta, &tb, leaf, &e))
		goto done;
	for (l = 0; l <= top; l++)
		for (a = 0; a < 3; a++)
			c[l][a] = leaf[a] / r.w[l][a];
	l = top;
	top_level(&r, m, top, n, c, lim, tn);
	t = ta;
	start = 1;

	for (;;) {
		if (l == 0 && g != NULL) {
			const uint64_t *bits = NULL;
			int64_t li = 0, dl[3] = { 0, 0, 0 };

			if (mk != NULL && top >= 1)
				bits = leaf_bits(mk, m, g, &r, c[1], c[0], &li, dl);
			if ((rc = leaves(&r, g, c[0], lim[0], tn[0], &t, &e, tb,
			    vals, nvals, bits, li, dl, fn, ctx, &s, &ax,
			    &texit)) != 0)
				goto done;
		} else if (l == 0) {
			float lo, hi;

			if (mm0 != NULL) {
				size_t k = 2 * (size_t)(c[0][0] + n[0] *
				    (c[0][1] + n[1] * c[0][2]));

				lo = mm0[k];
				hi = mm0[k + 1];
			} else {
				lo = -INFINITY;
				hi = INFINITY;
			}
			ax = min_axis(tn[0][0], tn[0][1], tn[0][2], &texit);
			if (brackets(lo, hi, vals, nvals)) {
				memcpy(v.i, c[0], sizeof v.i);
				v.leaf = c[0][0] + n[0] * (c[0][1] + n[1] *
				    c[0][2]);
				v.t0 = t;
				v.t1 = texit < tb ? texit : tb;
				v.entry_axis = e;
				v.entry_side = e >= 0 && r.s[e] < 0;
				v.exit_axis = texit <= tb && r.s[ax] ? ax : -1;
				v.exit_side = v.exit_axis >= 0 && r.s[ax] > 0;
				v.lo = lo;
				v.hi = hi;
				s.leaves++;
				if ((rc = fn(ctx, &v)) != 0)
					goto done;
			} else
				s.culled++;
		} else {
			/* a level-l macrocell (l >= 1).  Those that bracket
			 * nothing are stepped through here with the cell, its
			 * index into mm[l] and its exit times in registers:
			 * the same tests, steps and crossing times as the
			 * stepping below, which takes over when the ray
			 * leaves the parent or the segment ends */
			const float *mm = m->mm[l];
			const int64_t d0 = m->dims[l][0];
			const int64_t d01 = d0 * m->dims[l][1];
			int64_t x0 = c[l][0], x1 = c[l][1], x2 = c[l][2];
			int64_t q = x0 + d0 * x1 + d01 * x2, nc;
			int in;

			s.macro[l]++;
			in = brackets(mm[2 * q], mm[2 * q + 1], vals, nvals);
			if (!in) {
				const int64_t dq[3] = { r.s[0], r.s[1] * d0,
				    r.s[2] * d01 };
				double n0 = tn[l][0], n1 = tn[l][1], n2 = tn[l][2];
				double tv;

				for (;;) {
					ax = min_axis(n0, n1, n2, &texit);
					if (!(texit < tb))
						break;
					nc = AXIS(ax, x0, x1, x2) + r.s[ax];
					if (nc == lim[l][ax])
						break;
					tv = t_exit_of(&r, l, ax, nc);
					SET_AXIS(ax, x0, x1, x2, nc);
					SET_AXIS(ax, n0, n1, n2, tv);
					q += dq[ax];
					t = texit;
					e = ax;
					start = 0;
					cont = l;
					s.macro[l]++;
					if ((in = brackets(mm[2 * q], mm[2 * q + 1],
					    vals, nvals)) != 0)
						break;
				}
				c[l][0] = x0;
				c[l][1] = x1;
				c[l][2] = x2;
				tn[l][0] = n0;
				tn[l][1] = n1;
				tn[l][2] = n2;
			}
			if (in && !start && l - 1 >= cont) {
				/* the child the ray is in at t is where the last
				 * step left level l - 1: its index along e is the
				 * first in the new parent, the others and their
				 * crossing times those of the cell it left */
				int k = l - 1;
				int64_t k0, k1;

				children(m, l, e, c[l][e], n, &k0, &k1);
				lim[k][e] = r.up[e] ? k1 : k0 - 1;
				c[k][e] = r.up[e] ? k0 : k1 - 1;
				tn[k][e] = t_exit_of(&r, k, e, c[k][e]);
				l = k;
				continue;
			}
			if (in) {
				/* descend into the child the ray is in at t */
				int k = l - 1;

				cont = k;   /* what was below is left behind */
				for (a = 0; a < 3; a++) {
					int64_t k0, k1;

					children(m, l, a, c[l][a], n, &k0, &k1);
					lim[k][a] = r.up[a] ? k1 : k0 - 1;
					if (start)
						;  /* c[k] set from the start leaf */
					else if (r.s[a] == 0)
						c[k][a] = r.fixed[a] / r.w[k][a];
					else if (a == e)
						c[k][a] = r.up[a] ? k0 : k1 - 1;
					else
						/* tied axes before e were
						 * crossed first, after e not */
						c[k][a] = find_cell(&r, k, a, k0, k1,
						    t, a < e);
					tn[k][a] = t_exit_of(&r, k, a, c[k][a]);
				}
				l = k;
				continue;
			}
		}
		/* leave this cell through face ax at texit */
		if (!(texit < tb))
			break;
		start = 0;
		cont = l;   /* below l: left behind, unless l is 0; from l up
		               to where the step stops: left through face ax */
		for (;;) {
			c[l][ax] += r.s[ax];
			if (c[l][ax] != lim[l][ax])
				break;
			if (l == top)
				goto done;
			l++;   /* left the parent too, through the same face */
		}
		tn[l][ax] = t_exit_of(&r, l, ax, c[l][ax]);
		t = texit;
		e = ax;
	}
done:
	if (st != NULL) {
		for (l = 0; l <= VX_MACRO_MAXLEV; l++)
			st->macro[l] += s.macro[l];
		st->leaves += s.leaves;
		st->culled += s.culled;
		st->rays += s.rays;
	}
	return rc;
}

static int
fits(const vx_macro *m, const vx_grid *g)
{
	int64_t n[3];

	for (int a = 0; a < 3; a++)
		n[a] = g->dims[a] > 1 ? g->dims[a] - 1 : 0;
	if (n[0] == 0 || n[1] == 0 || n[2] == 0)
		n[0] = n[1] = n[2] = 0;
	return n[0] == m->dims[0][0] && n[1] == m->dims[0][1] &&
	    n[2] == m->dims[0][2];
}

int
vx_macro_traverse(const vx_macro *m, const vx_grid *g, const double o[3],
    const double d[3], double tmin, double tmax, const float *vals,
    int nvals, vx_visit_fn fn, void *ctx, vx_trav_stats *st)
{
	if (g != NULL && !fits(m, g))
		return -1;
	return walk(m, m->nlev, m->dims[0], g, g ? NULL : m->mm[0], NULL, o,
	    d, tmin, tmax, vals, nvals, fn, ctx, st);
}

int
vx_cellmask_matches(const vx_cellmask *k, const vx_macro *m,
    const float *vals, int nvals)
{
	int i;

	if (k == NULL || !k->ready || k->m != m || m->nlev < 1 ||
	    k->nvals != nvals)
		return 0;
	/* bit for bit, as memcmp would (a NaN value matches itself), without
	 * its call on every ray */
	for (i = 0; i < nvals; i++) {
		uint32_t a, b;

		memcpy(&a, &k->vals[i], sizeof a);
		memcpy(&b, &vals[i], sizeof b);
		if (a != b)
			return 0;
	}
	return 1;
}

/* mask_walk: -1 when volume g does not fit m; else 0, with *k NULL when
 * the mask is not for m and these values (the walk then tests samples) */
static int
mask_walk(const vx_macro *m, const vx_grid *g, vx_cellmask **k,
    const float *vals, int nvals)
{
	/* a mask built over this very m and g has checked that g fits m */
	if (g != NULL && vx_cellmask_matches(*k, m, vals, nvals) &&
	    (*k)->g == g)
		return 0;
	if (g == NULL || !fits(m, g))
		return -1;
	if (!vx_cellmask_matches(*k, m, vals, nvals))
		*k = NULL;
	return 0;
}

int
vx_macro_traverse_masked(const vx_macro *m, const vx_grid *g,
    vx_cellmask *k, const double o[3], const double d[3], double tmin,
    double tmax, const float *vals, int nvals, vx_visit_fn fn, void *ctx,
    vx_trav_stats *st)
{
	if (mask_walk(m, g, &k, vals, nvals) != 0)
		return -1;
	return walk(m, m->nlev, m->dims[0], g, NULL, k, o, d, tmin, tmax,
	    vals, nvals, fn, ctx, st);
}


/* The boxes' walk.  A ray is walked through the boxes of a list that it
 * enters, one after the other in order of entry, leaf by leaf inside each
 * box only: what lies between them holds no leaf to visit.  The boxes are
 * disjoint, so their spans along the ray are too (but for shared times
 * where the ray touches one at an edge or a corner), and the walk through
 * them visits exactly the leaves of the walk from 0 that lie in them, in
 * its order, with its data:
 * - a box's entry time is the largest crossing time of its near faces,
 *   and the crossing that enters it the one of the highest axis among
 *   those at that time (the walk crosses planes of equal time in axis
 *   order);
 * - the leaf it enters there is the walk's: along that axis the box's
 *   first, along the others the one whose entry face is crossed by then
 *   (on a lower axis at that very time too, on a higher one not:
 *   find_cell over the whole grid); where that leaf lies outside the box,
 *   the walk is never inside it (it passes an edge or a corner);
 * - a box entered at or before the segment's start holds the walk's start
 *   leaf or is not walked: it starts there, at the start, as the walk
 *   does;
 * - the entry is a crossing time of the walk's own planes, and from there
 *   on the steps are the walk's (leaves), up to the box's far faces;
 * - boxes are taken in order of (entry, axis of the crossing; a start box
 *   first): the walk's order, as one crossing enters one leaf.  The box's
 *   index breaks the remaining ties (boxes that will not be walked).
 * The boxes entered are kept in a list of at most PEND_MAX sorted by that
 * key, filled from the box list while its lower bounds (lb) do not pass
 * the earliest entry in it.  When it is full, the latest key is left out
 * and becomes a horizon: keys from it on wait, and when the list runs dry
 * the box list is read again from the start for them (the boxes walked
 * all lie before the horizon): exact whatever the number of boxes. */

#define PEND_MAX 64

typedef struct bkey {
	double t;     /* entry time (a start box: the segment's start) */
	int e;        /* axis of the entering crossing; -1: a start box */
	uint32_t j;   /* the box */
} bkey;

static inline int
key_lt(const bkey *a, const bkey *b)
{
	return a->t < b->t || (a->t == b->t && (a->e < b->e ||
	    (a->e == b->e && a->j < b->j)));
}

/* box_walk: the leaves of box bx that the walk visits, from the leaf it
 * enters at t through the face of axis e, or (e < 0) from the start leaf
 * sl at the segment's start t, entered through the face of axis se (tb:
 * the segment's end) */
static int
box_walk(const vx_macro *m, const vx_grid *g, vx_cellmask *mk, const ray *r,
    const vx_cellbox *bx, double t, int e, const int64_t sl[3], int se,
    double tb, const float *vals, int nvals, vx_visit_fn fn, void *ctx,
    vx_trav_stats *s)
{
	int64_t c[3], lim[3], c1[3], li = 0, dl[3] = { 0, 0, 0 };
	double tn[3], texit;
	const uint64_t *bits = NULL;
	int a, ax;

	for (a = 0; a < 3; a++) {
		lim[a] = r->up[a] ? bx->hi[a] : bx->lo[a] - 1;
		if (e < 0)
			c[a] = sl[a];
		else if (r->s[a] == 0)
			c[a] = r->fixed[a];
		else if (a == e)
			c[a] = r->up[a] ? bx->lo[a] : bx->hi[a] - 1;
		else
			c[a] = find_cell(r, 0, a, 0, r->n[a], t, a < e);
		if (c[a] < bx->lo[a] || c[a] >= bx->hi[a])
			return 0;   /* past an edge or a corner: not inside */
		tn[a] = r->s[a] ? tcross(r, a, c[a] + r->up[a]) : INFINITY;
	}
	if (e < 0)
		e = se;
	if (mk != NULL) {
		for (a = 0; a < 3; a++)
			c1[a] = c[a] / r->w[1][a];
		bits = leaf_bits(mk, m, g, r, c1, c, &li, dl);
	}
	return leaves(r, g, c, lim, tn, &t, &e, tb, vals, nvals, bits, li, dl,
	    fn, ctx, s, &ax, &texit);
}

/* boxes_walk: the boxes' walk of ray r (ray_axes done) through the boxes
 * the pick selects; the visitor's nonzero value, or 0 */
static int
boxes_walk(const vx_macro *m, const vx_grid *g, vx_cellmask *mk, ray *r,
    const vx_cellbox *box, const uint32_t *ix, size_t nbox,
    const vx_boxpick *pk, const float *vals, int nvals, vx_visit_fn fn,
    void *ctx, vx_trav_stats *s)
{
	const double *lbs = pk != NULL && pk->pix != NULL && ix != NULL ?
	    pk->lb : NULL;
	const int32_t *q = pk != NULL && lbs == NULL ? pk->q : NULL;
	bkey pend[PEND_MAX];   /* sorted, the earliest last */
	bkey hz = { INFINITY, 0, 0 }, fl = { -INFINITY, 0, 0 };
	double ta = 0, tb = INFINITY;
	int64_t sl[3] = { 0, 0, 0 };
	int np = 0, walked = 0, have_sl = 0, se = -1, rc = 0;
	size_t k = 0;
	/* with the query's entries as a mask: the entries not yet read */
	int use_em = lbs != NULL && pk->use_em;
	uint64_t rem = use_em ? pk->em : 0;

	if (!ray_clip(r, m, m->nlev, vals, nvals, &ta, &tb))
		return 0;
	for (;;) {
		for (; use_em ? rem != 0 : k < nbox; k++) {
			const vx_cellbox *bx;
			double tin, tout;
			uint32_t j;
			bkey y;
			int e, i;

			if (use_em)
				k = (size_t)__builtin_ctzll(rem);
			j = ix != NULL ? ix[k] : (uint32_t)k;
			bx = box + j;

			if ((lbs != NULL ? lbs[k] : bx->lb) > (np > 0 ?
			    pend[np - 1].t : hz.t))
				break;
			if (use_em)
				rem &= rem - 1;
			else if (lbs != NULL ? !(pk->pix[k] >> pk->bit & 1) :
			    !fp_holds(bx, q))
				continue;
			/* entered (a box entered after the start: before the
			 * end, where the walk still steps) */
			if (!box_times(r, bx, &tin, &tout, &e) || tin > tout ||
			    tout < ta || (tin > ta && !(tin < tb)))
				continue;
			y.t = tin > ta ? tin : ta;
			y.e = tin > ta ? e : -1;
			y.j = j;
			if (key_lt(&y, &fl) || !key_lt(&y, &hz))
				continue;   /* walked, or past the horizon */
			if (np == PEND_MAX) {
				/* full: the latest waits for the next pass */
				if (key_lt(&pend[0], &y)) {
					hz = y;
					continue;
				}
				hz = pend[0];
				memmove(pend, pend + 1, (size_t)(np - 1) *
				    sizeof *pend);
				np--;
			}
			for (i = np; i > 0 && key_lt(&pend[i - 1], &y); i--)
				pend[i] = pend[i - 1];
			pend[i] = y;
			np++;
		}
		if (np == 0) {
			if (hz.t == INFINITY)
				break;
			/* the boxes left at the horizon: a pass for them */
			fl = hz;
			hz.t = INFINITY;
			k = 0;
			rem = use_em ? pk->em : 0;
			continue;
		}
		np--;
		if (pend[np].e < 0 && !have_sl) {
			/* the start leaf, as the walk from the start has it */
			start_leaf(r, ta, sl, &se);
			have_sl = 1;
		}
		if (!walked) {
			walked = 1;
			s->rays++;
		}
		if ((rc = box_walk(m, g, mk, r, box + pend[np].j, pend[np].t,
		    pend[np].e, sl, se, tb, vals, nvals, fn, ctx, s)) != 0)
			break;
	}
	return rc;
}

int
vx_macro_traverse_boxes(const vx_macro *m, const vx_grid *g,
    vx_cellmask *k, const vx_cellbox *box, const uint32_t *ix, size_t nbox,
    const vx_boxpick *pk, const double o[3], const double d[3],
    const float *vals, int nvals, vx_visit_fn fn, void *ctx,
    vx_trav_stats *st)
{
	vx_trav_stats s;
	ray r;
	int rc;

	if (m->nlev < 1 || mask_walk(m, g, &k, vals, nvals) != 0)
		return -1;
	if (!ray_axes(&r, m->dims[0], o, d))
		return 0;
	memset(&s, 0, sizeof s);
	rc = boxes_walk(m, g, k, &r, box, ix, nbox, pk, vals, nvals, fn, ctx,
	    &s);
	if (st != NULL) {
		st->leaves += s.leaves;
		st->culled += s.culled;
		st->rays += s.rays;
	}
	return rc;
}

int
vx_macro_traverse_flat(const vx_macro *m, const vx_grid *g,
    const double o[3], const double d[3], double tmin, double tmax,
    const float *vals, int nvals, vx_visit_fn fn, void *ctx,
    vx_trav_stats *st)
{
	int64_t n[3];

	if (m == NULL) {
		if (g == NULL)
			return -1;
		for (int a = 0; a < 3; a++)
			n[a] = g->dims[a] > 1 ? g->dims[a] - 1 : 0;
		if (n[0] == 0 || n[1] == 0 || n[2] == 0)
			n[0] = n[1] = n[2] = 0;
		return walk(NULL, 0, n, g, NULL, NULL, o, d, tmin, tmax, vals,
		    nvals, fn, ctx, st);
	}
	if (g != NULL && !fits(m, g))
		return -1;
	return walk(m, 0, m->dims[0], g, g ? NULL : m->mm[0], NULL, o, d,
	    tmin, tmax, vals, nvals, fn, ctx, st);
}

/* ---- cell masks: building ---- */

void
vx_cellmask_init(vx_cellmask *k)
{
	memset(k, 0, sizeof *k);
}

void
vx_cellmask_free(vx_cellmask *k)
{
	if (k == NULL)
		return;
	free(k->slot);
	free((void *)k->state);
	free(k->bits);
	free(k->set);
	vx_cellmask_init(k);
}

size_t
vx_cellmask_bytes(const vx_cellmask *k)
{
	if (k == NULL || !k->ready)
		return 0;
	return (size_t)k->nblock * (sizeof *k->slot + 1) +
	    (size_t)k->nset * sizeof *k->set +
	    (size_t)(k->nset * k->words) * sizeof *k->bits;
}

int64_t
vx_cellmask_built(const vx_cellmask *k)
{
	if (k == NULL || !k->ready)
		return 0;
	return atomic_load_explicit(&k->built, memory_order_relaxed);
}

int
vx_cellmask_block_built(const vx_cellmask *k, int64_t b)
{
	if (k == NULL || !k->ready || b < 0 || b >= k->nblock)
		return 0;
	return atomic_load_explicit(&k->state[b], memory_order_acquire) == 2;
}

int
vx_cellmask_build(vx_cellmask *k, const vx_macro *m, const vx_grid *g,
    const float *vals, int nvals, int lazy, int nthreads, vx_err *e)
{
	int64_t nb, i, nset = 0, words;
	size_t bytes;

	vx_cellmask_init(k);
	if (m == NULL || g == NULL || m->nlev < 1 || m->explicit_leaves ||
	    nvals < 1 || nvals > VX_CELLMASK_MAXV || !fits(m, g) ||
	    g->data == NULL || m->width[1][0] > VX_CELLMASK_MAXROW ||
	    m->width[1][1] > VX_MACRO_MAXSIZE)
		return 0;
	nb = (int64_t)ncells(m, 1);
	words = (m->width[1][0] * m->width[1][1] * m->width[1][2] + 63) / 64;
	k->slot = malloc((size_t)(nb > 0 ? nb : 1) * sizeof *k->slot);
	k->state = calloc((size_t)(nb > 0 ? nb : 1), 1);
	if (k->slot == NULL || k->state == NULL) {
		vx_cellmask_free(k);
		return vx_err_set(e, VX_ENOMEM, "cell mask: out of memory");
	}
	for (i = 0; i < nb; i++)
		k->slot[i] = brackets(m->mm[1][2 * i], m->mm[1][2 * i + 1],
		    vals, nvals) ? nset++ * words : -1;
	if ((k->set = malloc((size_t)(nset > 0 ? nset : 1) *
	    sizeof *k->set)) == NULL) {
		vx_cellmask_free(k);
		return vx_err_set(e, VX_ENOMEM, "cell mask: out of memory");
	}
	for (nset = 0, i = 0; i < nb; i++)
		if (k->slot[i] >= 0)
			k->set[nset++] = i;
	/* calloc: pages of blocks never entered are never touched */
	if (vx_mul_size(&bytes, (size_t)(nset > 0 ? nset : 1) *
	    (size_t)words, sizeof *k->bits) != 0 ||
	    (k->bits = calloc(1, bytes)) == NULL) {
		vx_cellmask_free(k);
		return vx_err_set(e, VX_ENOMEM, "cell mask: out of memory "
		    "(%lld macrocells)", (long long)nset);
	}
	k->m = m;
	k->g = g;
	memcpy(k->vals, vals, (size_t)nvals * sizeof *vals);
	k->nvals = nvals;
	k->nblock = nb;
	k->nset = nset;
	k->words = words;
	k->ready = 1;
	if (!lazy) {
		int nt = threads(nthreads);

		(void)nt;
#ifdef _OPENMP
#pragma omp parallel for num_threads(nt) schedule(dynamic, 16)
#endif
		for (i = 0; i < nb; i++)
			if (k->slot[i] >= 0)
				(void)mask_get(k, m, g, i);
	}
	return 0;
}

/* ---- the MCEL chunk ---- */

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
	    vx_type_name(m->vtype))) ||
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

int
vx_macro_sizes_hdr_parse(const char *v, int nlev, int sizes[][3], vx_err *e)
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
vx_macro_from_chunk(vx_macro *m, const vx_chunk *c, vx_err *e)
{
	int sizes[VX_MACRO_MAXLEV][3];
	const unsigned char *body;
	size_t bodylen, nbytes, k;
	int64_t n[3], nl, dl[3];
	const char *v;
	unsigned char *tmp = NULL;
	int explicit_leaves, l, a, rc;
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
	if ((rc = vx_hdr_get_i64(&h, "levels", &nl, 1, e)) != 0)
		goto out;
	if (nl < 0 || nl > VX_MACRO_MAXLEV) {
		rc = vx_err_set(e, VX_EDATA, "levels %lld: expected 0..%d",
		    (long long)nl, VX_MACRO_MAXLEV);
		goto out;
	}
	if ((v = vx_hdr_get(&h, "sizes")) == NULL) {
		rc = vx_err_set(e, VX_EDATA, "missing sizes");
		goto out;
	}
	if ((rc = vx_macro_sizes_hdr_parse(v, (int)nl, sizes, e)) != 0 ||
	    (rc = vx_hdr_get_i64(&h, "leaf-dims", n, 3, e)) != 0)
		goto out;
	/* setup checks every size and dim before anything is allocated
	 * (its allocation is the body's size, checked below first) */
	for (a = 0; a < 3; a++)
		if (n[a] < 0 || n[a] > VX_GRID_MAX_DIM) {
			rc = vx_err_set(e, VX_EDATA, "leaf-dims: %lld out of "
			    "0..%lld", (long long)n[a],
			    (long long)VX_GRID_MAX_DIM);
			goto out;
		}
	for (l = 0; l < nl; l++)
		for (a = 0; a < 3; a++)
			if (sizes[l][a] < 1 || sizes[l][a] > VX_MACRO_MAXSIZE) {
				rc = vx_err_set(e, VX_EDATA, "sizes: edge %d out "
				    "of 1..%d", sizes[l][a], VX_MACRO_MAXSIZE);
				goto out;
			}
	{
		/* the body size, computed as setup will, checked first */
		vx_macro g;

		vx_macro_init(&g);
		nbytes = 0;
		for (a = 0; a < 3; a++)
			g.dims[0][a] = n[a];
		for (l = 1; l <= nl; l++)
			for (a = 0; a < 3; a++)
				g.dims[l][a] = (g.dims[l - 1][a] +
				    sizes[l - 1][a] - 1) / sizes[l - 1][a];
		for (l = explicit_leaves ? 0 : 1; l <= nl; l++) {
			if (vx_mul_size(&k, ncells(&g, l), 2 * sizeof(float)) ||
			    vx_add_size(&nbytes, nbytes, k)) {
				rc = vx_err_set(e, VX_EDATA, "too many cells");
				goto out;
			}
			if (l > 0) {
				char key[16];

				snprintf(key, sizeof key, "dims-%d", l);
				if ((rc = vx_hdr_get_i64(&h, key, dl, 3, e)) != 0)
					goto out;
				if (dl[0] != g.dims[l][0] ||
				    dl[1] != g.dims[l][1] ||
				    dl[2] != g.dims[l][2]) {
					rc = vx_err_set(e, VX_EDATA, "%s does not "
					    "follow from leaf-dims and sizes",
					    key);
					goto out;
				}
			}
		}
		if ((rc = vx_body_fits(&h, bodylen, nbytes, e)) != 0)
			goto out;
	}
	if ((rc = setup(m, n, (int)nl, sizes, explicit_leaves, e)) != 0)
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
		    (m->vtype = vx_type_parse(v)) == VX_TYPE_UNKNOWN) {
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
vx_macro_from_stream(vx_macro *m, const vx_stream *s, const vx_grid *g,
    long src, int *status, long *index, vx_err *e)
{
	long i = -1;
	int rc;

	vx_macro_init(m);
	*status = VX_MACRO_ABSENT;
	if (index != NULL)
		*index = -1;
	while ((i = vx_stream_find(s, VX_CHUNK_MACRO, (size_t)(i + 1))) >= 0) {
		const unsigned char *body;
		const char *v, *lv;
		size_t bodylen;
		vx_hdr h;
		int mine;

		vx_hdr_init(&h);
		if ((rc = vx_payload_parse(&s->chunk[i], &h, &body, &bodylen,
		    e)) != 0) {
			vx_hdr_free(&h);
			return vx_err_push(e, "macrocells");
		}
		v = vx_hdr_get(&h, "volume");
		mine = v != NULL && strcmp(v, g->name) == 0;
		lv = vx_hdr_get(&h, "leaves");
		if (v == NULL && (lv == NULL || strcmp(lv, "explicit") != 0)) {
			/* volume macrocells must name their volume */
			vx_hdr_free(&h);
			vx_err_set(e, VX_EDATA, "no 'volume' key");
			return vx_err_push(e, "macrocells");
		}
		vx_hdr_free(&h);
		if (!mine)
			continue;
		if (index != NULL)
			*index = i;
		if ((rc = vx_macro_from_chunk(m, &s->chunk[i], e)) != 0)
			return rc;
		/* the very bytes it was built from: their samples' CRC is the
		 * one recorded (the other checks still run) */
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
	return 0;
}
