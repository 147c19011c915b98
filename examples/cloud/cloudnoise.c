/* cloudnoise.c: a coarse volume made a cloud by noise (Kniss et al. 2003,
 * section 5 and Figs. 11-13): each sample of a finer grid reads the
 * coarse volume (trilinear) at its position displaced by an fBm vector
 * field, so the coarse shape keeps its outline at large scale and gains
 * wisps at small scale; then its density is modulated by turbulence.
 * A filter: a voxlux stream with a volume in, the fine volume out.
 *
 *   cloudnoise [UP [AMPLITUDE [OCTAVES [SEED]]]] < coarse.vx > cloud.vx
 *
 * UP: fine samples per coarse cell per axis (default 6); AMPLITUDE: the
 * displacement in coarse cells (default 1.5); OCTAVES of fBm (default 5,
 * frequency 1/4 per coarse cell, lacunarity 2, gain 1/2); SEED (0).
 * The field is vx_noise's: the same cloud at any thread count. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "vx_grid.h"
#include "vx_noise.h"
#include "vx_stream.h"

static void
die(const vx_err *e)
{
	fprintf(stderr, "cloudnoise: %s\n", e->msg);
	exit(e->code ? e->code : 70);
}

int
main(int argc, char **argv)
{
	int up = argc > 1 ? atoi(argv[1]) : 6;
	double amp = argc > 2 ? atof(argv[2]) : 1.5;
	vx_noise_fbm f;
	vx_stream s;
	vx_grid g, c;
	vx_chunk ch;
	int64_t dims[3];
	long i;
	vx_err e;

	vx_noise_fbm_init(&f);
	f.octaves = argc > 3 ? atoi(argv[3]) : 5;
	f.seed = argc > 4 ? strtoull(argv[4], NULL, 10) : 0;
	f.frequency = 0.25;
	vx_err_clear(&e);
	if (up < 1 || up > 16 || !(amp >= 0) || vx_noise_fbm_check(&f, &e))
		fprintf(stderr, "usage: cloudnoise [UP [AMPLITUDE [OCTAVES "
		    "[SEED]]]] < coarse.vx > cloud.vx\n"), exit(64);
	vx_stream_init(&s);
	if (vx_stream_read(&s, stdin, &e) != 0)
		die(&e);
	if ((i = vx_stream_find(&s, "VOLM", 0)) < 0) {
		fprintf(stderr, "cloudnoise: no volume in the stream\n");
		return 65;
	}
	if (vx_grid_from_chunk(&c, &s.chunk[i], &e) != 0)
		die(&e);
	for (int a = 0; a < 3; a++)
		dims[a] = c.dims[a] > 1 ? (c.dims[a] - 1) * up + 1 : 1;
	if (vx_grid_alloc(&g, dims, VX_F32, NULL, &e) != 0)
		die(&e);
	for (int64_t z = 0; z < dims[2]; z++)
		for (int64_t y = 0; y < dims[1]; y++)
			for (int64_t x = 0; x < dims[0]; x++) {
				double p[3] = { (double)x / up, (double)y / up,
				    (double)z / up }, q[3], d[3];

				/* three decorrelated fBm fields displace the
				 * lookup (coarse index units) */
				for (int a = 0; a < 3; a++) {
					vx_noise_fbm fa = f;

					fa.seed = f.seed * 3 + (uint64_t)a + 1;
					d[a] = vx_noise_fbm_eval(&fa, p, NULL);
				}
				for (int a = 0; a < 3; a++)
					q[a] = p[a] + amp * d[a];
				vx_grid_set(&g, x, y, z, vx_grid_trilinear(&c, q) *
				    (0.6 + 0.8 * vx_noise_turbulence(&f, p)));
			}
	for (int a = 0; a < 3; a++) {
		g.spacing[a] = c.spacing[a] / up;
		g.origin[a] = c.origin[a];
	}
	vx_grid_range(&g);
	if (vx_grid_to_chunk(&g, 6, &ch, &e) != 0)
		die(&e);
	vx_stream_replace(&s, (size_t)i, &ch);
	{
		char line[128];

		snprintf(line, sizeof line, "cloudnoise %d %g %d %llu", up, amp,
		    f.octaves, (unsigned long long)f.seed);
		if (vx_stream_history_add(&s, line, &e) != 0)
			die(&e);
	}
	if (vx_stream_write(&s, stdout, &e) != 0)
		die(&e);
	vx_grid_free(&g);
	vx_grid_free(&c);
	vx_stream_free(&s);
	return 0;
}
