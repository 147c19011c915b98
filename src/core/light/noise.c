/* noise.c: counter-based gradient noise and its fractal sums
 * (vx_noise.h). */
#include <math.h>
#include <string.h>

#include "vx_noise.h"
#include "vx_rng.h"

#define DOMAIN 0x6e6f6973652d3344ull     /* "noise-3D": apart from other
                                            users of the seed */
#define TWO32 4294967296.0

/* the twelve edge directions; g[i ^ 1] = -g[i] */
static const signed char grads[12][3] = {
	{ 1, 1, 0 }, { -1, -1, 0 }, { 1, -1, 0 }, { -1, 1, 0 },
	{ 1, 0, 1 }, { -1, 0, -1 }, { 1, 0, -1 }, { -1, 0, 1 },
	{ 0, 1, 1 }, { 0, -1, -1 }, { 0, 1, -1 }, { 0, -1, 1 },
};

static const signed char *
grad_at(uint64_t seed, uint32_t i, uint32_t j, uint32_t k)
{
	uint64_t h = vx_rng_hash(seed ^ DOMAIN, i, j, k);

	return grads[((h >> 32) * 12) >> 32];
}

static double
fade(double t)
{
	return t * t * t * (t * (t * 6 - 15) + 10);
}

static double
dfade(double t)
{
	return 30 * t * t * (t * (t - 2) + 1);
}

/* cell: the lattice cell of x (its low corner, 32-bit, the lattice
 * repeating every 2^32) and the offset in it. */
static uint32_t
cell(double x, double *t)
{
	double f;

	if (!(fabs(x) < TWO32 / 2))
		x -= TWO32 * floor(x / TWO32);    /* [0, 2^32) */
	f = floor(x);
	*t = x - f;
	return (uint32_t)(int64_t)f;
}

double
vx_noise3_grad(uint64_t seed, const double p[3], double grad[3])
{
	double t[3], w[3][2], dw[3][2], v = 0, gd[3] = { 0, 0, 0 };
	uint32_t c[3];

	for (int a = 0; a < 3; a++) {
		double f;

		if (!isfinite(p[a])) {
			if (grad != NULL)
				grad[0] = grad[1] = grad[2] = 0;
			return 0;
		}
		c[a] = cell(p[a], &t[a]);
		f = fade(t[a]);
		w[a][0] = 1 - f;
		w[a][1] = f;
		dw[a][1] = dfade(t[a]);
		dw[a][0] = -dw[a][1];
	}
	for (int k = 0; k < 2; k++)
		for (int j = 0; j < 2; j++)
			for (int i = 0; i < 2; i++) {
				const signed char *g = grad_at(seed, c[0] + (uint32_t)i,
				    c[1] + (uint32_t)j, c[2] + (uint32_t)k);
				double d[3] = { t[0] - i, t[1] - j, t[2] - k };
				double dot = g[0] * d[0] + g[1] * d[1] + g[2] * d[2];
				double wt = w[0][i] * w[1][j] * w[2][k];

				v += wt * dot;
				if (grad == NULL)
					continue;
				gd[0] += dw[0][i] * w[1][j] * w[2][k] * dot + wt * g[0];
				gd[1] += w[0][i] * dw[1][j] * w[2][k] * dot + wt * g[1];
				gd[2] += w[0][i] * w[1][j] * dw[2][k] * dot + wt * g[2];
			}
	if (grad != NULL)
		for (int a = 0; a < 3; a++)
			grad[a] = gd[a] * (2.0 / 3);
	return v * (2.0 / 3);
}

double
vx_noise3(uint64_t seed, const double p[3])
{
	return vx_noise3_grad(seed, p, NULL);
}

void
vx_noise_fbm_init(vx_noise_fbm *f)
{
	memset(f, 0, sizeof *f);
	f->octaves = 4;
	f->frequency = 1;
	f->lacunarity = 2;
	f->gain = 0.5;
}

int
vx_noise_fbm_check(const vx_noise_fbm *f, vx_err *e)
{
	if (f->octaves < 1 || f->octaves > VX_NOISE_MAX_OCTAVES)
		return vx_err_set(e, VX_EUSAGE, "noise octaves %d: 1 to %d",
		    f->octaves, VX_NOISE_MAX_OCTAVES);
	if (!(f->frequency > 0) || !isfinite(f->frequency))
		return vx_err_set(e, VX_EUSAGE, "noise frequency %g: a positive "
		    "number", f->frequency);
	if (!(f->lacunarity > 0 && f->lacunarity <= 1000))
		return vx_err_set(e, VX_EUSAGE, "noise lacunarity %g: in (0, "
		    "1000]", f->lacunarity);
	if (!(f->gain > 0 && f->gain <= 1000))
		return vx_err_set(e, VX_EUSAGE, "noise gain %g: in (0, 1000]",
		    f->gain);
	return 0;
}

/* octave: octave o's seed and offset (lattice units in [0, 256)) */
static uint64_t
octave(uint64_t seed, int o, double off[3])
{
	for (int a = 0; a < 3; a++)
		off[a] = 256 * vx_rng_uniform(seed ^ DOMAIN, 0x6f6374, (uint64_t)o,
		    (uint32_t)a);
	return vx_rng_hash(seed ^ DOMAIN, 0x6f6374, (uint64_t)o, 3);
}

/* sum: the fractal sum, of |noise| when absolute. */
static double
sum(const vx_noise_fbm *f, const double p[3], double grad[3], int absolute)
{
	double amp = 1, freq = f->frequency, total = 0, wsum = 0;
	double gsum[3] = { 0, 0, 0 };

	for (int o = 0; o < f->octaves; o++) {
		double offd[3], q[3], g[3], v;
		const double *off = offd;
		uint64_t s;

		if (f->prepared == f->seed + 1 && o < VX_NOISE_MAX_OCTAVES) {
			s = f->oseed_[o];
			off = f->off_[o];
		} else
			s = octave(f->seed, o, offd);

		for (int a = 0; a < 3; a++)
			q[a] = p[a] * freq + off[a];
		v = vx_noise3_grad(s, q, grad ? g : NULL);
		if (absolute && v < 0) {
			v = -v;
			for (int a = 0; a < 3 && grad != NULL; a++)
				g[a] = -g[a];
		}
		total += amp * v;
		if (grad != NULL)
			for (int a = 0; a < 3; a++)
				gsum[a] += amp * freq * g[a];
		wsum += amp;
		amp *= f->gain;
		freq *= f->lacunarity;
	}
	if (grad != NULL)
		for (int a = 0; a < 3; a++)
			grad[a] = gsum[a] / wsum;
	return total / wsum;
}

void
vx_noise_fbm_prepare(vx_noise_fbm *f)
{
	/* every octave: a later change of the octave count stays right */
	for (int o = 0; o < VX_NOISE_MAX_OCTAVES; o++)
		f->oseed_[o] = octave(f->seed, o, f->off_[o]);
	f->prepared = f->seed + 1;
}

double
vx_noise_fbm_eval(const vx_noise_fbm *f, const double p[3], double grad[3])
{
	return sum(f, p, grad, 0);
}

double
vx_noise_turbulence(const vx_noise_fbm *f, const double p[3])
{
	return sum(f, p, NULL, 1);
}

double
vx_noise_turbulence_grad(const vx_noise_fbm *f, const double p[3],
    double grad[3])
{
	return sum(f, p, grad, 1);
}
