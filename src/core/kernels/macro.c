/* macro.c: the multilevel min/max grid: its geometry, its build over a
 * volume's cells or over explicit leaves, and the volume's identity (the
 * samples' CRC).  See vx_macro.h. */
#include "vx_macro.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "macro_priv.h"

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

size_t
vx_macro_bytes(const vx_macro *m)
{
	size_t n = 0;
	int l;

	for (l = m->explicit_leaves ? 0 : 1; l <= m->nlev; l++)
		n += 2 * sizeof(float) * ncells(m, l);
	return n;
}

/* vx_macro_setup: see macro_priv.h */
int
vx_macro_setup(vx_macro *m, const int64_t n[3], int nlev,
    const int sizes[][3], int leaf0, vx_err *e)
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
	int a, l, rc, nt = vx_par_threads(nthreads);

	leaf_dims(g, n);
	if ((rc = vx_macro_setup(m, n, nlev, sizes, 0, e)) != 0)
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
	int l, rc, nt = vx_par_threads(nthreads);

	if ((rc = vx_macro_setup(m, n, nlev, sizes, 1, e)) != 0)
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
