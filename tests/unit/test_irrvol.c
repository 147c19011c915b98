/* test_irrvol.c: the irradiance volume: binary16 conversion, the lattice,
 * exact accumulators (any grouping, the same bits), interpolation modes,
 * merging, and the IRRV chunk with its malformed cases. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "vx_half.h"
#include "vx_irrvol.h"

/* room for one texel's accumulators of any size */
typedef union accbuf {
	vx_irr_acc a;
	int64_t w[3 + VX_IRR_MAX_COMP];
} accbuf;

/* binary16 by its definition (IEEE 754-2008 §3.6): the oracle is the exact
 * value of each bit pattern and round-to-nearest-even. */
static void
half_table(void **state)
{
	static const struct { float f; uint16_t h; } t[] = {
		{ 0.0f, 0x0000 }, { -0.0f, 0x8000 }, { 1.0f, 0x3c00 },
		{ -2.0f, 0xc000 }, { 65504.0f, 0x7bff },
		{ 65520.0f, 0x7c00 },               /* halfway to 2^16: even = inf */
		{ 65519.0f, 0x7bff }, { 1e9f, 0x7c00 },
		{ 5.9604644775390625e-8f, 0x0001 },  /* 2^-24, smallest subnormal */
		{ 2.98023223876953125e-8f, 0x0000 }, /* 2^-25: tie, to even 0 */
		{ 4.470348358154297e-8f, 0x0001 },   /* 1.5 * 2^-25: rounds up */
		{ 6.103515625e-5f, 0x0400 },         /* 2^-14, smallest normal */
		{ 1.00048828125f, 0x3c00 },          /* 1 + 2^-11: tie, to even */
		{ 1.00146484375f, 0x3c02 },          /* 1 + 3 * 2^-11: tie, up */
		{ 0.333333343f, 0x3555 },
	};

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof *t; i++) {
		assert_int_equal(vx_half_from_float(t[i].f), t[i].h);
		if ((t[i].h & 0x7c00) != 0x7c00 && t[i].h != 0)
			assert_true(fabsf(vx_half_to_float(t[i].h) - t[i].f) <=
			    fabsf(t[i].f) * 0x1p-11f + 0x1p-25f);
	}
	/* every finite half converts to float and back to itself */
	for (uint32_t h = 0; h < 0x10000; h++) {
		if ((h & 0x7c00) == 0x7c00)
			continue;
		assert_int_equal(vx_half_from_float(vx_half_to_float(
		    (uint16_t)h)), h);
	}
	assert_true(isinf(vx_half_to_float(0x7c00)));
	assert_true(isnan(vx_half_to_float(vx_half_from_float(NAN))));
}

/* lattice dims: round((V - 1) S) + 1, at least 2 where V > 1, 1 where
 * V = 1 (formats/irradiance.md) */
static void
lattice_table(void **state)
{
	static const struct { int64_t v[3]; double s; int64_t d[3]; } t[] = {
		{ { 181, 217, 181 }, 1, { 181, 217, 181 } },
		{ { 181, 217, 181 }, 0.5, { 91, 109, 91 } },
		{ { 181, 217, 181 }, 2, { 361, 433, 361 } },
		{ { 2, 2, 2 }, 0.1, { 2, 2, 2 } },
		{ { 1, 5, 9 }, 2, { 1, 9, 17 } },
		{ { 10, 10, 10 }, 0.25, { 3, 3, 3 } },    /* 9 * 0.25 = 2.25 */
	};
	vx_err e = { 0, "" };

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof *t; i++) {
		int64_t d[3];

		assert_int_equal(vx_irr_lattice(t[i].v, t[i].s, d, &e), 0);
		for (int a = 0; a < 3; a++)
			assert_int_equal(d[a], t[i].d[a]);
	}
	{
		int64_t v[3] = { 1 << 20, 1 << 20, 1 << 20 }, d[3];

		assert_int_equal(vx_irr_lattice(v, 1, d, &e), VX_EUSAGE);
		assert_int_equal(vx_irr_lattice(v, 0, d, &e), VX_EUSAGE);
		assert_int_equal(vx_irr_lattice(v, NAN, d, &e), VX_EUSAGE);
	}
}

static void
make_grid(vx_grid *g, int64_t nx, int64_t ny, int64_t nz)
{
	int64_t d[3] = { nx, ny, nz };
	vx_err e = { 0, "" };

	vx_grid_init(g);
	assert_int_equal(vx_grid_alloc(g, d, VX_F32, NULL, &e), 0);
	snprintf(g->name, sizeof g->name, "density");
	for (int64_t z = 0; z < nz; z++)
		for (int64_t y = 0; y < ny; y++)
			for (int64_t x = 0; x < nx; x++)
				vx_grid_set(g, x, y, z, (double)(x + 2 * y + 3 * z));
	vx_grid_range(g);
}

/* Adding the same estimates in any grouping gives the same accumulators,
 * bit for bit (integer sums); saturation flags overflow. */
static void
accum_grouping(void **state)
{
	accbuf ub_one, ub_a, ub_b;
	vx_irr_acc *one = &ub_one.a, *a = &ub_a.a, *b = &ub_b.a;
	vx_irrvol iv;
	double est[257][3];
	uint64_t x = 88172645463325252u;

	(void)state;
	vx_irr_init(&iv);        /* irradiance: 3 components, 24 bits */
	for (int i = 0; i < 257; i++)
		for (int c = 0; c < 3; c++) {
			x ^= x << 13;
			x ^= x >> 7;
			x ^= x << 17;
			est[i][c] = (double)(x >> 11) * 0x1p-53 * 10 *
			    (c + 1) + (i % 7 == 0 ? 1e3 : 0);
		}
	memset(&ub_one, 0, sizeof ub_one);
	for (int i = 0; i < 257; i++)
		vx_irr_acc_add(&iv, one, est[i]);
	for (int split = 0; split <= 257; split += 37) {
		memset(&ub_a, 0, sizeof ub_a);
		memset(&ub_b, 0, sizeof ub_b);
		for (int i = 0; i < split; i++)
			vx_irr_acc_add(&iv, a, est[i]);
		for (int i = split; i < 257; i++)
			vx_irr_acc_add(&iv, b, est[i]);
		vx_irr_acc_merge(&iv, a, b);
		assert_memory_equal(a, one, vx_irr_acc_bytes(3));
	}
	/* the mean within rounding of the exact mean */
	{
		double m[3], ref[3] = { 0, 0, 0 };

		for (int i = 0; i < 257; i++)
			for (int c = 0; c < 3; c++)
				ref[c] += est[i][c] / 257;
		vx_irr_acc_mean(&iv, one, m);
		for (int c = 0; c < 3; c++)
			assert_true(fabs(m[c] - ref[c]) <= 1e-6 * ref[c]);
		assert_true(vx_irr_acc_relerr(&iv, one) > 0);
	}
	/* negative and NaN estimates count as 0; huge ones saturate */
	{
		double bad[3] = { -1, NAN, INFINITY };

		memset(&ub_a, 0, sizeof ub_a);
		vx_irr_acc_add(&iv, a, bad);
		assert_int_equal(a->count, 1);
		assert_int_equal(a->sum[0], 0);
		assert_int_equal(a->sum[1], 0);
		assert_true(a->flags & VX_TEXEL_OVERFLOW);
	}
}

static void
fill(vx_irrvol *v, int wanted_every)
{
	vx_err e = { 0, "" };
	size_t nb = (size_t)(v->bdims[0] * v->bdims[1] * v->bdims[2]);

	for (size_t b = 0; b < nb; b += (size_t)wanted_every)
		assert_int_equal(vx_irr_want_brick(v, b, &e), 0);
	for (int64_t k = 0; k < v->dims[2]; k++)
		for (int64_t j = 0; j < v->dims[1]; j++)
			for (int64_t i = 0; i < v->dims[0]; i++) {
				int64_t s = vx_irr_texel(v, i, j, k);
				double rgb[3] = { (double)i, (double)j + 0.5,
				    (double)k * 0.25 };

				if (s < 0)
					continue;
				for (int n = 0; n < 4; n++)
					vx_irr_acc_add(v, vx_irr_accp(v, s), rgb);
				vx_irr_accp(v, s)->flags |= VX_TEXEL_WANTED;
			}
	vx_irr_finish(v);
}

/* trilinear lookup of an irradiance linear in position reproduces it
 * (oracle: the linear function), at scales 0.5, 1 and 2; nearest picks the
 * rounded texel; tricubic of a constant is the constant */
static void
lookup_modes(void **state)
{
	static const double scales[] = { 0.5, 1, 2 };
	vx_grid g;
	vx_err e = { 0, "" };

	(void)state;
	make_grid(&g, 13, 9, 11);
	for (size_t si = 0; si < 3; si++) {
		vx_irrvol v;
		double p[3] = { 5.3, 2.7, 7.9 }, rgb[3], u[3];

		vx_irr_init(&v);
		assert_int_equal(vx_irr_setup(&v, &g, 0, scales[si],
		    VX_IRR_ACCUM, &e), 0);
		/* texel points land on the volume's ends */
		{
			double q[3];

			vx_irr_texel_point(&v, v.dims[0] - 1, v.dims[1] - 1,
			    v.dims[2] - 1, q);
			assert_true(fabs(q[0] - 12) < 1e-12 &&
			    fabs(q[1] - 8) < 1e-12 && fabs(q[2] - 10) < 1e-12);
		}
		fill(&v, 1);
		for (int a = 0; a < 3; a++)
			u[a] = p[a] / v.step[a];
		assert_int_equal(vx_irr_lookup(&v, p, VX_INTERP_TRILINEAR, &g, 0,
		    rgb), 1);
		assert_true(fabs(rgb[0] - u[0]) < 1e-5);
		assert_true(fabs(rgb[1] - (u[1] + 0.5)) < 1e-5);
		assert_true(fabs(rgb[2] - u[2] * 0.25) < 1e-5);
		/* the unknown mode (a zeroed options record) reads as
		 * trilinear, bit for bit */
		{
			double t[3];

			assert_int_equal(vx_irr_lookup(&v, p, VX_INTERP_UNKNOWN,
			    &g, 0, t), 1);
			assert_memory_equal(t, rgb, sizeof t);
		}
		assert_int_equal(vx_irr_lookup(&v, p, VX_INTERP_NEAREST, &g, 0,
		    rgb), 1);
		assert_true(fabs(rgb[0] - floor(u[0] + 0.5)) < 1e-6);
		assert_true(fabs(rgb[2] - floor(u[2] + 0.5) * 0.25) < 1e-6);
		/* tricubic B-spline reproduces linear functions in the
		 * interior too (it is exact for degree 1) */
		assert_int_equal(vx_irr_lookup(&v, p, VX_INTERP_TRICUBIC, &g, 0,
		    rgb), 1);
		assert_true(fabs(rgb[0] - u[0]) < 1e-5);
		/* nearest-iso: the texel whose value is closest to iso; with
		 * f = x + 2y + 3z, iso at the value of corner (1,1,1) of the
		 * cell picks it */
		{
			int64_t b[3];
			double q[3];

			for (int a = 0; a < 3; a++)
				b[a] = (int64_t)floor(u[a]);
			vx_irr_texel_point(&v, b[0] + 1, b[1] + 1, b[2] + 1, q);
			assert_int_equal(vx_irr_lookup(&v, p, VX_INTERP_NEAREST_ISO,
			    &g, q[0] + 2 * q[1] + 3 * q[2], rgb), 1);
			assert_true(fabs(rgb[0] - (double)(b[0] + 1)) < 1e-6);
			assert_true(fabs(rgb[2] - (double)(b[2] + 1) * 0.25) <
			    1e-6);
		}
		vx_irr_free(&v);
	}
	/* unusable texels are skipped and the weights renormalized; none in
	 * reach: 0 */
	{
		vx_irrvol v;
		double p[3] = { 3.5, 3.5, 3.5 }, rgb[3];
		int64_t s;

		vx_irr_init(&v);
		assert_int_equal(vx_irr_setup(&v, &g, 0, 1, VX_IRR_ACCUM, &e), 0);
		fill(&v, 1);
		for (int q = 0; q < 8; q++) {
			s = vx_irr_texel(&v, 3 + (q & 1), 3 + (q >> 1 & 1),
			    3 + (q >> 2 & 1));
			if (q != 7)
				vx_irr_accp(&v, s)->flags |= q % 2 ? VX_TEXEL_FLAT :
				    VX_TEXEL_NAN;
		}
		vx_irr_finish(&v);
		assert_int_equal(vx_irr_lookup(&v, p, VX_INTERP_TRILINEAR, &g, 0,
		    rgb), 1);
		assert_true(fabs(rgb[0] - 4) < 1e-6);   /* texel (4,4,4) alone */
		s = vx_irr_texel(&v, 4, 4, 4);
		vx_irr_accp(&v, s)->flags |= VX_TEXEL_FLAT;
		vx_irr_finish(&v);
		assert_int_equal(vx_irr_lookup(&v, p, VX_INTERP_TRILINEAR, &g, 0,
		    rgb), 0);
		assert_true(rgb[0] == 0 && rgb[1] == 0 && rgb[2] == 0);
		vx_irr_free(&v);
	}
	vx_grid_free(&g);
}

/* The trilinear lookup, whether its 8 texels lie in one brick or straddle
 * bricks, is the documented sum bit for bit: texels k = x + 2y + 4z of the
 * lattice cell holding the point, the usable ones weighted by the products
 * of their fractions, the sum divided by the weights' sum when that is not
 * 1 (oracle: that formula evaluated here in the same order); for random
 * values, sparse bricks, unusable texels and points (inside, on brick
 * faces, clamped outside), at scales 0.5, 1 and 2, every store. */
static void
trilinear_matches_formula(void **state)
{
	static const double scales[] = { 0.5, 1, 2 };
	static const vx_irr_store st[] = { VX_IRR_ACCUM, VX_IRR_F32,
	    VX_IRR_F16 };
	uint64_t r = 99;
	vx_grid g;
	vx_err e = { 0, "" };
	int in = 0, across = 0;

	(void)state;
	make_grid(&g, 23, 18, 20);
	for (int it = 0; it < 9; it++) {
		vx_irrvol v;
		size_t nb;

		vx_irr_init(&v);
		assert_int_equal(vx_irr_setup(&v, &g, 0, scales[it % 3],
		    VX_IRR_ACCUM, &e), 0);
		nb = (size_t)(v.bdims[0] * v.bdims[1] * v.bdims[2]);
		for (size_t b = 0; b < nb; b++)
			if ((b + (size_t)it) % 4 != 0)
				assert_int_equal(vx_irr_want_brick(&v, b, &e), 0);
		for (int64_t k = 0; k < v.dims[2]; k++)
		for (int64_t j = 0; j < v.dims[1]; j++)
		for (int64_t i = 0; i < v.dims[0]; i++) {
			int64_t s = vx_irr_texel(&v, i, j, k);
			double rgb[3];

			if (s < 0)
				continue;
			for (int c = 0; c < 3; c++) {
				r = r * 6364136223846793005u + 1442695040888963407u;
				rgb[c] = (double)(r >> 40) / (1 << 20);
			}
			r = r * 6364136223846793005u + 1442695040888963407u;
			if ((r >> 60) != 0) {   /* 1 in 16 left unsampled */
				vx_irr_acc_add(&v, vx_irr_accp(&v, s), rgb);
				vx_irr_accp(&v, s)->flags |= VX_TEXEL_WANTED;
			}
			if ((r >> 56 & 15) == 3)
				vx_irr_accp(&v, s)->flags |= VX_TEXEL_FLAT;
		}
		vx_irr_finish(&v);
		if (st[it / 3] != VX_IRR_ACCUM)
			assert_int_equal(vx_irr_finalize(&v, st[it / 3], &e), 0);
		for (int q = 0; q < 3000; q++) {
			double p[3], u[3], f[3], want[3] = { 0, 0, 0 };
			double got[3], ws = 0;
			int64_t b[3];
			int ok;

			for (int a = 0; a < 3; a++) {
				r = r * 6364136223846793005u + 1442695040888963407u;
				p[a] = (double)(r >> 40) / (1 << 24) *
				    (double)(g.dims[a] + 2) - 1;
				if (q % 5 == 0)   /* on lattice planes */
					p[a] = floor(p[a] / v.step[a]) * v.step[a];
			}
			for (int a = 0; a < 3; a++) {
				double hi = (double)(v.dims[a] - 1);

				u[a] = p[a] / v.step[a];
				if (!(u[a] > 0))
					u[a] = 0;
				if (u[a] > hi)
					u[a] = hi;
				b[a] = (int64_t)floor(u[a]);
				if (b[a] > v.dims[a] - 2)
					b[a] = v.dims[a] - 2;
				f[a] = u[a] - (double)b[a];
				if (f[a] > 1)
					f[a] = 1;
			}
			for (int k = 0; k < 8; k++) {
				int64_t s = vx_irr_texel(&v, b[0] + (k & 1),
				    b[1] + (k >> 1 & 1), b[2] + (k >> 2 & 1));
				double wt = ((k & 1) ? f[0] : 1 - f[0]) *
				    ((k >> 1 & 1) ? f[1] : 1 - f[1]) *
				    ((k >> 2 & 1) ? f[2] : 1 - f[2]);

				if (s < 0 || !vx_irr_usable(&v, s))
					continue;
				ws += wt;
				for (int c = 0; c < 3; c++)
					want[c] += wt * v.mean[3 * s + c];
			}
			if (ws > 0 && ws != 1)
				for (int c = 0; c < 3; c++)
					want[c] /= ws;
			if (!(ws > 0))
				want[0] = want[1] = want[2] = 0;
			ok = vx_irr_lookup(&v, p, VX_INTERP_TRILINEAR, &g, 0, got);
			assert_int_equal(ok, ws > 0);
			assert_memory_equal(got, want, sizeof got);
			if ((b[0] % 8 == 7) || (b[1] % 8 == 7) || (b[2] % 8 == 7))
				across++;
			else
				in++;
		}
		vx_irr_free(&v);
	}
	assert_true(in > 10000 && across > 3000);
	vx_grid_free(&g);
}

/* the chunk round-trips every store, sparse bricks included; malformed
 * chunks are refused with VX_EDATA */
static void
chunk_roundtrip(void **state)
{
	static const vx_irr_store st[] = { VX_IRR_ACCUM, VX_IRR_F32, VX_IRR_F16 };
	vx_grid g;
	vx_err e = { 0, "" };

	(void)state;
	make_grid(&g, 20, 9, 17);
	for (size_t si = 0; si < 3; si++) {
		vx_irrvol v, w;
		vx_chunk c;

		vx_irr_init(&v);
		assert_int_equal(vx_irr_setup(&v, &g, 0xdeadbeef, 1,
		    VX_IRR_ACCUM, &e), 0);
		snprintf(v.key, sizeof v.key, "0123456789abcdef");
		fill(&v, 3);
		if (st[si] != VX_IRR_ACCUM)
			assert_int_equal(vx_irr_finalize(&v, st[si], &e), 0);
		memset(&c, 0, sizeof c);
		assert_int_equal(vx_irr_to_chunk(&v, si == 1 ? 6 : 0, &c, &e), 0);
		assert_int_equal(vx_irr_from_chunk(&w, &c, &e), 0);
		assert_int_equal(w.store, st[si]);
		assert_int_equal(w.nslot, v.nslot);
		assert_int_equal(w.vcrc, 0xdeadbeef);
		for (int64_t k = 0; k < v.dims[2]; k++)
			for (int64_t j = 0; j < v.dims[1]; j++)
				for (int64_t i = 0; i < v.dims[0]; i++) {
					int64_t a = vx_irr_texel(&v, i, j, k),
					    b = vx_irr_texel(&w, i, j, k);

					assert_true((a < 0) == (b < 0));
					if (a < 0)
						continue;
					assert_memory_equal(&v.mean[3 * a],
					    &w.mean[3 * b], 3 * sizeof(float));
					if (st[si] == VX_IRR_ACCUM)
						assert_memory_equal(vx_irr_accp(&v, a),
						    vx_irr_accp(&w, b),
						    vx_irr_acc_bytes(v.ncomp));
				}
		vx_irr_free(&w);
		/* malformed: a flipped map bit past the bricks, a count that
		 * disagrees, a negative sum (raw bodies only) */
		if (si == 0) {
			vx_chunk bad;
			size_t hdr = c.len - (v.nslot * VX_IRR_BRICK3 * 48 +
			    ((size_t)(v.bdims[0] * v.bdims[1] * v.bdims[2]) + 7) / 8);
			size_t nb = (size_t)(v.bdims[0] * v.bdims[1] * v.bdims[2]);

			bad = c;
			bad.data = malloc(c.len);
			memcpy(bad.data, c.data, c.len);
			if (nb % 8 != 0) {
				bad.data[hdr + nb / 8] |= (unsigned char)(0x80);
				assert_int_equal(vx_irr_from_chunk(&w, &bad, &e),
				    VX_EDATA);
				memcpy(bad.data, c.data, c.len);
			}
			bad.data[hdr] ^= 2;     /* brick 1: count mismatch */
			assert_int_equal(vx_irr_from_chunk(&w, &bad, &e),
			    VX_EDATA);
			memcpy(bad.data, c.data, c.len);
			bad.data[hdr + (nb + 7) / 8 + 8 + 7] = 0x80; /* sum < 0 */
			assert_int_equal(vx_irr_from_chunk(&w, &bad, &e),
			    VX_EDATA);
			/* the in-memory SAMPLED bit in a stored record with no
			 * samples: ignored, the texel is not usable (fuzz_stream
			 * found it drawn as irradiance 0) */
			memcpy(bad.data, c.data, c.len);
			memset(bad.data + hdr + (nb + 7) / 8, 0, 4);  /* count 0 */
			bad.data[hdr + (nb + 7) / 8 + 7] |= 0x80;     /* bit 31 */
			assert_int_equal(vx_irr_from_chunk(&w, &bad, &e), 0);
			assert_int_equal(vx_irr_accp(&w, 0)->count, 0);
			assert_false(vx_irr_usable(&w, 0));
			assert_false(vx_irr_accp(&w, 0)->flags &
			    VX_TEXEL_SAMPLED);
			vx_irr_free(&w);
			free(bad.data);
		}
		vx_chunk_free(&c);
		vx_irr_free(&v);
	}
	vx_grid_free(&g);
}

/* merging: disjoint sample ranges that join give the single run's bits;
 * ranges that do not join, other keys and final stores are refused */
static void
merge_rules(void **state)
{
	vx_grid g;
	vx_err e = { 0, "" };
	vx_irrvol one, a, b;
	double est[3] = { 0.25, 0.5, 1.75 };

	(void)state;
	make_grid(&g, 10, 10, 10);
	vx_irr_init(&one);
	vx_irr_init(&a);
	vx_irr_init(&b);
	assert_int_equal(vx_irr_setup(&one, &g, 7, 1, VX_IRR_ACCUM, &e), 0);
	assert_int_equal(vx_irr_setup(&a, &g, 7, 1, VX_IRR_ACCUM, &e), 0);
	assert_int_equal(vx_irr_setup(&b, &g, 7, 1, VX_IRR_ACCUM, &e), 0);
	b.first = 3;
	assert_int_equal(vx_irr_want_brick(&one, 0, &e), 0);
	assert_int_equal(vx_irr_want_brick(&a, 0, &e), 0);
	assert_int_equal(vx_irr_want_brick(&b, 0, &e), 0);
	assert_int_equal(vx_irr_want_brick(&b, 7, &e), 0);
	for (int n = 0; n < 5; n++) {
		est[0] += 0.125;
		vx_irr_acc_add(&one, vx_irr_accp(&one, 9), est);
		vx_irr_acc_add(&a, vx_irr_accp(n < 3 ? &a : &b, 9), est);
	}
	assert_int_equal(vx_irr_merge(&a, &b, &e), 0);
	assert_memory_equal(vx_irr_accp(&a, 9), vx_irr_accp(&one, 9),
	    vx_irr_acc_bytes(3));
	assert_int_equal(a.nslot, 2);   /* b's brick 7 joined */
	/* a texel of 5 samples cannot take samples that start at 3 */
	assert_int_equal(vx_irr_merge(&a, &b, &e), VX_EDATA);
	snprintf(b.key, sizeof b.key, "ffffffffffffffff");
	assert_int_equal(vx_irr_merge(&one, &b, &e), VX_EDATA);
	b.key[0] = 0;
	assert_int_equal(vx_irr_finalize(&b, VX_IRR_F16, &e), 0);
	assert_int_equal(vx_irr_merge(&one, &b, &e), VX_EDATA);
	vx_irr_free(&one);
	vx_irr_free(&a);
	vx_irr_free(&b);
	vx_grid_free(&g);
}

/* a final f16 store keeps a mean beyond binary16's range as 65504 with
 * the overflow flag, by vx_irr_finalize and by vx_irr_settle alike, and the
 * chunk reads back (an infinity would be refused: bake-irr --half under a
 * bright sky wrote volumes no reader took) */
static void
half_saturates(void **state)
{
	double big[3] = { 1e6, 0.5, 70000 };
	vx_grid g;
	vx_err e = { 0, "" };
	vx_irrvol v, w;
	vx_chunk c;
	vx_irr_acc *a;
	int64_t s;

	(void)state;
	make_grid(&g, 4, 4, 4);
	vx_irr_init(&v);
	assert_int_equal(vx_irr_setup(&v, &g, 0, 1, VX_IRR_ACCUM, &e), 0);
	s = vx_irr_want_texel(&v, 1, 2, 3, &e);
	assert_true(s >= 0);
	vx_irr_accp(&v, s)->flags |= VX_TEXEL_WANTED;
	vx_irr_acc_add(&v, vx_irr_accp(&v, s), big);
	assert_false(vx_irr_accp(&v, s)->flags & VX_TEXEL_OVERFLOW);
	assert_int_equal(vx_irr_finalize(&v, VX_IRR_F16, &e), 0);
	assert_true(v.mean[3 * s] == 65504.0f);
	assert_true(v.mean[3 * s + 1] == 0.5f);
	assert_true(v.mean[3 * s + 2] == 65504.0f);
	assert_true(v.flags[s] & VX_TEXEL_OVERFLOW);
	assert_true(vx_irr_usable(&v, s));
	memset(&c, 0, sizeof c);
	assert_int_equal(vx_irr_to_chunk(&v, 0, &c, &e), 0);
	assert_int_equal(vx_irr_from_chunk(&w, &c, &e), 0);
	assert_memory_equal(w.mean, v.mean, 3 * VX_IRR_BRICK3 * sizeof(float));
	assert_memory_equal(w.flags, v.flags, VX_IRR_BRICK3 * sizeof(uint32_t));
	vx_chunk_free(&c);
	vx_irr_free(&w);
	/* settle: the same from accumulators kept aside */
	a = calloc(1, vx_irr_acc_bytes(3));
	assert_non_null(a);
	a->flags = VX_TEXEL_WANTED;
	vx_irr_acc_add(&v, a, big);
	v.mean[3 * s] = 0;
	v.flags[s] = 0;
	vx_irr_settle(&v, s, a);
	assert_true(v.mean[3 * s] == 65504.0f && v.mean[3 * s + 1] == 0.5f);
	assert_true(v.flags[s] & VX_TEXEL_OVERFLOW);
	free(a);
	vx_irr_free(&v);
	vx_grid_free(&g);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(half_table),
		cmocka_unit_test(lattice_table),
		cmocka_unit_test(accum_grouping),
		cmocka_unit_test(lookup_modes),
		cmocka_unit_test(trilinear_matches_formula),
		cmocka_unit_test(chunk_roundtrip),
		cmocka_unit_test(merge_rules),
		cmocka_unit_test(half_saturates),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
