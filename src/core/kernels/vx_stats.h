/* vx_stats.h: summary statistics of a volume's samples: counts of finite and
 * non-finite values, range, mean, histogram, and a layout-independent
 * checksum.  What vinfo prints, and what a tool can use to pick defaults
 * (isovalues, transfer function domains) without scanning twice. */
#ifndef VX_STATS_H
#define VX_STATS_H

#include <stddef.h>
#include <stdint.h>

#include "vx_err.h"
#include "vx_grid.h"

typedef struct vx_stats {
	uint64_t count;        /* real samples, dims[0]*dims[1]*dims[2] */
	uint64_t nfinite;      /* of which finite */
	uint64_t nnan, nposinf, nneginf;
	int has_range;         /* 1 when nfinite > 0 */
	double vmin, vmax;     /* over finite samples; 0 when none */
	double mean;           /* over finite samples; 0 when none */
	uint32_t crc;          /* CRC-32 (as the stream's) of the real samples
	                          in x-fastest order, little-endian: equal for
	                          equal samples whatever layout or encoding */
} vx_stats;

/* vx_grid_stats: fill st from g's real samples (padding is left out),
 * reading them through the layout tables.  Never fails. */
void vx_grid_stats(const vx_grid *g, vx_stats *st);

/* vx_grid_histogram: count g's finite samples in nbins equal bins over
 * [lo, hi]: bin floor((v - lo) / (hi - lo) * nbins), the top edge hi in the
 * last bin, values outside [lo, hi] not counted.  When lo == hi every sample
 * equal to lo goes in bin 0.  counts (nbins entries) is overwritten.
 * VX_EUSAGE for nbins 0, lo > hi or a non-finite bound. */
int vx_grid_histogram(const vx_grid *g, double lo, double hi, size_t nbins,
    uint64_t *counts, vx_err *e);

#endif
