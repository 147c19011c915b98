/* test_shlight.c: the SHLC chunk (vx_shlight.h, formats/shlight.md): a
 * round trip keeps every bit, and a table of malformed chunks (each made by
 * editing a good one's header or body) is refused with VX_EDATA; a scene's
 * environment and sky lights project as their sum. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "vx_scene.h"
#include "vx_shlight.h"

/* sample: order n, coefficients that are distinct, non-trivial doubles,
 * a hash, a rotation about z by 30 degrees */
static void
sample(vx_shlight *l, int n)
{
	vx_shlight_init(l);
	l->order = n;
	l->has_hash = 1;
	l->env_hash = 0x0123456789abcdefULL;
	vx_rot3_zyz(0.5235987755982988, 0, 0, l->rot);
	for (int i = 0; i < 3 * n * n; i++)
		l->c[i] = sin(1.0 + i) / 3.0 * (i % 5 == 0 ? 1e-300 : 1);
}

/* round trip, orders 1, 3, 16 and both phases: bit for bit (oracle: the
 * body holds the doubles' bits, the header %.17g, which round-trips) */
static void
round_trip(void **state)
{
	static const int orders[] = { 1, 3, 16 };
	vx_err e = { 0, "" };

	(void)state;
	for (size_t k = 0; k < 3; k++)
		for (int ph = 0; ph < 2; ph++) {
			vx_shlight a, b;
			vx_chunk c;

			sample(&a, orders[k]);
			a.phase = ph ? VX_SHLIGHT_PHASE_NONE :
			    VX_SHLIGHT_PHASE_CS;
			a.has_hash = ph;
			memset(&c, 0, sizeof c);
			assert_int_equal(vx_shlight_to_chunk(&a, &c, &e), 0);
			assert_string_equal(c.type, "SHLC");
			assert_int_equal(vx_shlight_from_chunk(&b, &c, &e), 0);
			assert_int_equal(b.order, a.order);
			assert_int_equal(b.phase, a.phase);
			assert_int_equal(b.has_hash, a.has_hash);
			if (a.has_hash)
				assert_true(b.env_hash == a.env_hash);
			assert_memory_equal(b.rot, a.rot, sizeof a.rot);
			assert_memory_equal(b.c, a.c,
			    sizeof(double) * 3 * a.order * a.order);
			vx_chunk_free(&c);
		}
}

/* the writer refuses what it could not write faithfully */
static void
writer_refuses(void **state)
{
	vx_err e = { 0, "" };
	vx_shlight a;
	vx_chunk c;

	(void)state;
	memset(&c, 0, sizeof c);
	sample(&a, 0 + 1);
	a.order = 0;
	assert_int_equal(vx_shlight_to_chunk(&a, &c, &e), VX_EINTERNAL);
	a.order = 17;
	assert_int_equal(vx_shlight_to_chunk(&a, &c, &e), VX_EINTERNAL);
	a.order = 2;
	a.c[5] = NAN;
	assert_int_equal(vx_shlight_to_chunk(&a, &c, &e), VX_EINTERNAL);
}

/* remake: a chunk with header text hdr (the "key: value" lines, without
 * the empty line) and body bytes body (n), encoding raw */
static void
remake(vx_chunk *c, const char *hdr, const void *body, size_t n)
{
	size_t hl = strlen(hdr);

	memset(c, 0, sizeof *c);
	strcpy(c->type, "SHLC");
	c->len = hl + 1 + n;
	c->data = malloc(c->len ? c->len : 1);
	assert_non_null(c->data);
	memcpy(c->data, hdr, hl);
	c->data[hl] = '\n';
	if (n)
		memcpy(c->data + hl + 1, body, n);
}

#define GOOD_ROT "rotation: 1 0 0 0 1 0 0 0 1\n"
#define HDR(order, rest) "order: " order "\nchannels: 3\nphase: " \
	"condon-shortley\nsource-hash: none\n" rest "encoding: raw\n"

/* malformed catalog: each case and why it is wrong */
static void
malformed(void **state)
{
	static const struct {
		const char *why, *hdr;
		size_t nbody;      /* body bytes; order 2 wants 96 */
		int nan_at;        /* coefficient made NaN, or -1 */
	} tab[] = {
		{ "good (control)", HDR("2", GOOD_ROT), 96, -1 },
		{ "body one double short", HDR("2", GOOD_ROT), 88, -1 },
		{ "body one double long", HDR("2", GOOD_ROT), 104, -1 },
		{ "empty body", HDR("2", GOOD_ROT), 0, -1 },
		{ "order 0", HDR("0", GOOD_ROT), 0, -1 },
		{ "order 17", HDR("17", GOOD_ROT), 17 * 17 * 24, -1 },
		{ "order -1", HDR("-1", GOOD_ROT), 96, -1 },
		{ "huge order (no allocation on its word)",
		  HDR("4000000000", GOOD_ROT), 96, -1 },
		{ "NaN coefficient", HDR("2", GOOD_ROT), 96, 7 },
		{ "NaN in the rotation", HDR("2", "rotation: 1 0 0 0 nan 0 0 "
		  "0 1\n"), 96, -1 },
		{ "rotation not orthogonal", HDR("2", "rotation: 2 0 0 0 1 0 "
		  "0 0 1\n"), 96, -1 },
		{ "reflection (det -1)", HDR("2", "rotation: -1 0 0 0 1 0 0 0 "
		  "1\n"), 96, -1 },
		{ "eight rotation numbers", HDR("2", "rotation: 1 0 0 0 1 0 0 "
		  "0\n"), 96, -1 },
		{ "no rotation", HDR("2", ""), 96, -1 },
		{ "channels 1", "order: 2\nchannels: 1\nphase: none\n"
		  "source-hash: none\n" GOOD_ROT "encoding: raw\n", 32, -1 },
		{ "unknown phase", "order: 2\nchannels: 3\nphase: schmidt\n"
		  "source-hash: none\n" GOOD_ROT "encoding: raw\n", 96, -1 },
		{ "bad hash", "order: 2\nchannels: 3\nphase: none\n"
		  "source-hash: 12345\n" GOOD_ROT "encoding: raw\n", 96, -1 },
		{ "no empty line after the header", NULL, 0, -1 },
	};
	unsigned char body[17 * 17 * 24];

	(void)state;
	for (size_t i = 0; i < sizeof body / 8; i++) {
		double v = 0.25 * (double)i;
		uint64_t u;

		memcpy(&u, &v, 8);
		vx_put_le64(body + 8 * i, u);
	}
	for (size_t k = 0; k < sizeof tab / sizeof *tab; k++) {
		vx_err e = { 0, "" };
		unsigned char b[sizeof body];
		vx_shlight l;
		vx_chunk c;
		int rc;

		memcpy(b, body, sizeof b);
		if (tab[k].nan_at >= 0) {
			double v = NAN;
			uint64_t u;

			memcpy(&u, &v, 8);
			vx_put_le64(b + 8 * tab[k].nan_at, u);
		}
		if (tab[k].hdr == NULL) {
			remake(&c, "order: 2", NULL, 0);
			c.len--;          /* drop the empty line */
		} else
			remake(&c, tab[k].hdr, b, tab[k].nbody);
		rc = vx_shlight_from_chunk(&l, &c, &e);
		if (k == 0) {
			assert_int_equal(rc, 0);
			assert_int_equal(l.order, 2);
			assert_true(l.c[11] == 2.75);
		} else {
			if (rc != VX_EDATA)
				fail_msg("%s: rc %d (%s)", tab[k].why, rc,
				    e.msg);
			assert_int_equal(l.order, 1);   /* left initialized */
			assert_non_null(strstr(e.msg, "SH lighting"));
		}
		vx_chunk_free(&c);
	}
}

/* a stream without the chunk: idx -1, no error; with it: found */
static void
from_stream(void **state)
{
	vx_err e = { 0, "" };
	vx_shlight a, b;
	vx_stream s;
	vx_chunk c;
	long idx;

	(void)state;
	vx_stream_init(&s);
	assert_int_equal(vx_shlight_from_stream(&b, &s, &idx, &e), 0);
	assert_int_equal(idx, -1);
	sample(&a, 5);
	memset(&c, 0, sizeof c);
	assert_int_equal(vx_shlight_to_chunk(&a, &c, &e), 0);
	assert_int_equal(vx_stream_append(&s, &c, &e), 0);
	assert_int_equal(vx_shlight_from_stream(&b, &s, &idx, &e), 0);
	assert_int_equal(idx, 0);
	assert_int_equal(b.order, 5);
	assert_true(b.c[74] == a.c[74]);
	vx_stream_free(&s);
}

/* a scene's lights: none, one sky, two skies, a sky beside a point light
 * (not projected).  Oracle: a constant radiance L over the sphere has the
 * constant term L * 4 pi * Y00 = 2 sqrt(pi) L and no other; lights add. */
static void
from_scene(void **state)
{
	static const struct {
		const char *light[3];   /* --light specs after "lights none" */
		double k;               /* the summed intensity */
		int n;                  /* lights projected */
	} t[] = {
		{ { "point position 0 0 5", NULL, NULL }, 0, 0 },
		{ { "sky color 1 0.5 0.25 intensity 2", NULL, NULL }, 2, 1 },
		{ { "sky color 1 0.5 0.25 intensity 2",
		    "sky color 1 0.5 0.25 intensity 3", NULL }, 5, 2 },
		{ { "sky color 1 0.5 0.25 intensity 3", "point position 0 0 5",
		    NULL }, 3, 1 },
	};
	static const double col[3] = { 1, 0.5, 0.25 };
	const double y = 2 * sqrt(3.14159265358979323846);
	vx_err e = { 0, "" };

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_scene s;
		vx_shlight l;
		int n = -1;
		size_t np = 0;

		vx_scene_init(&s);
		assert_int_equal(vx_scene_option(&s, "lights", "none", &e), 0);
		for (int k = 0; k < 3 && t[i].light[k] != NULL; k++)
			assert_int_equal(vx_scene_option(&s, "light",
			    t[i].light[k], &e), 0);
		assert_int_equal(vx_shlight_from_scene(&l, &s, 3, &n, &np, &e),
		    0);
		assert_int_equal(n, t[i].n);
		assert_int_equal(np, (size_t)t[i].n);  /* a sky: one pixel */
		assert_int_equal(l.order, 3);
		assert_int_equal(l.has_hash, t[i].n == 1);
		for (int c = 0; c < 3; c++)
			for (int j = 0; j < 9; j++)
				assert_true(fabs(l.c[c * 9 + j] - (j == 0 ?
				    y * t[i].k * col[c] : 0)) < 1e-12);
	}
	{
		vx_scene s;
		vx_shlight l;

		vx_scene_init(&s);
		assert_int_equal(vx_shlight_from_scene(&l, &s, 17, NULL, NULL,
		    &e), VX_EINTERNAL);
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(round_trip),
		cmocka_unit_test(writer_refuses),
		cmocka_unit_test(malformed),
		cmocka_unit_test(from_stream),
		cmocka_unit_test(from_scene),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
