/* stats.c: summary statistics of a volume's samples (see vx_stats.h). */
#include "vx_stats.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

/* put_le: sample i of g as little-endian bytes at p; returns the width. */
static size_t
put_le(const vx_grid *g, size_t i, unsigned char *p)
{
	uint32_t u;
	float f;

	switch (g->type) {
	case VX_U8:
		p[0] = ((const uint8_t *)g->data)[i];
		return 1;
	case VX_U16:
		u = ((const uint16_t *)g->data)[i];
		break;
	case VX_I16:
		u = (uint16_t)((const int16_t *)g->data)[i];
		break;
	case VX_F32:
		f = ((const float *)g->data)[i];
		memcpy(&u, &f, 4);
		vx_put_le32(p, u);
		return 4;
	default:
		return 0;
	}
	p[0] = (unsigned char)(u & 0xff);
	p[1] = (unsigned char)(u >> 8);
	return 2;
}

void
vx_grid_stats(const vx_grid *g, vx_stats *st)
{
	unsigned char row[4096];
	double sum = 0;
	int64_t x, y, z;
	uLong crc = crc32(0L, Z_NULL, 0);

	memset(st, 0, sizeof *st);
	st->vmin = INFINITY;
	st->vmax = -INFINITY;
	for (z = 0; z < g->dims[2]; z++)
		for (y = 0; y < g->dims[1]; y++) {
			size_t base = (size_t)(g->lay.off[1][y] + g->lay.off[2][z]);
			double rsum = 0;   /* per-row partial sums: less rounding */
			size_t k = 0;

			for (x = 0; x < g->dims[0]; x++) {
				size_t i = base + (size_t)g->lay.off[0][x];
				double v = vx_grid_get_index(g, i);

				if (k + 4 > sizeof row) {
					crc = crc32(crc, row, (uInt)k);
					k = 0;
				}
				k += put_le(g, i, row + k);
				st->count++;
				if (isnan(v)) {
					st->nnan++;
					continue;
				}
				if (isinf(v)) {
					if (v > 0)
						st->nposinf++;
					else
						st->nneginf++;
					continue;
				}
				st->nfinite++;
				rsum += v;
				if (v < st->vmin)
					st->vmin = v;
				if (v > st->vmax)
					st->vmax = v;
			}
			crc = crc32(crc, row, (uInt)k);
			sum += rsum;
		}
	st->crc = (uint32_t)crc;
	st->has_range = st->nfinite > 0;
	if (!st->has_range) {
		st->vmin = st->vmax = 0;
		return;
	}
	st->mean = sum / (double)st->nfinite;
	/* rounding can push the mean of near-equal values past the range */
	if (st->mean < st->vmin)
		st->mean = st->vmin;
	if (st->mean > st->vmax)
		st->mean = st->vmax;
}

int
vx_grid_histogram(const vx_grid *g, double lo, double hi, size_t nbins,
    uint64_t *counts, vx_err *e)
{
	int64_t x, y, z;
	double span, scale, nb = (double)nbins;
	int fast;

	if (nbins == 0 || !isfinite(lo) || !isfinite(hi) || lo > hi)
		return vx_err_set(e, VX_EUSAGE, "histogram: %zu bins over "
		    "[%g, %g]", nbins, lo, hi);
	memset(counts, 0, nbins * sizeof *counts);
	/* a product a sample where the scale is a double; a quotient where
	 * the width is subnormal (its scale overflows), a quotient of
	 * halves where the width itself overflows */
	span = hi - lo;
	scale = nb / span;
	fast = span > 0 && isfinite(span) && isfinite(scale);
	for (z = 0; z < g->dims[2]; z++)
		for (y = 0; y < g->dims[1]; y++) {
			size_t base = (size_t)(g->lay.off[1][y] + g->lay.off[2][z]);

			for (x = 0; x < g->dims[0]; x++) {
				double v = vx_grid_get_index(g,
				    base + (size_t)g->lay.off[0][x]);
				double q;
				size_t b;

				if (!(v >= lo && v <= hi))   /* also NaN */
					continue;
				q = fast ? (v - lo) * scale : isfinite(span) ?
				    (v - lo) / span * nb : (0.5 * v - 0.5 * lo) /
				    (0.5 * hi - 0.5 * lo) * nb;
				/* NaN (lo == hi: 0 / 0) is bin 0 */
				b = q >= nb ? nbins - 1 : q >= 1 ? (size_t)q : 0;
				counts[b]++;
			}
		}
	return 0;
}
