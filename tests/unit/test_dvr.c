/* test_dvr.c: direct volume rendering by half-angle slicing (vx_dvr.h).
 *
 * Oracles:
 *  - a homogeneous slab seen straight on, no light: coverage
 *    1 - exp(-sigma d) with sigma = -ln(1 - alpha) / ref and d the depth
 *    (the Beer-Lambert law), the same at every slice count (opacity
 *    correction), and along an oblique orthographic view through a slab
 *    that fills the image, d / cos;
 *  - two slabs lit along the view by a directional light: slice j of the
 *    material (counted from the light and the eye, which meet it in the
 *    same order) sends alpha' q^j of light (q = 1 - alpha') through q^j to
 *    the eye, so the pixel is the sum of alpha' q^(2j) over the material
 *    slices; without volumetric shadows, the sum of alpha' q^j; the shadow
 *    the occluder casts multiplies the receiver by q^(2 n_o);
 *  - a lit, scattering sphere at 1x, 2x and 4x the slices: the pictures
 *    converge (relative RMS between successive ones below a bound, and
 *    falling);
 *  - the light turned through 90 degrees from the view in steps: the
 *    change at the switch of compositing order (front to back <-> back to
 *    front) is no larger than a step's change elsewhere allows;
 *  - skipping empty macrocells changes no bit, and does skip; 1 thread and
 *    3 threads give the same bits;
 *  - the plan's decisions for a table of scenes, by vx_dvr.h's rules. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "helper_dvr.h"
#include "vx_import.h"

/* render g as text says; returns the image (RGBA) and fills st */
static void
render(const char *text, const vx_grid *g, const vx_macro *m,
    const vx_dvr_opts *o, vx_image *img, vx_dvr_stats *st)
{
	vx_scene s;
	vx_tf tf;
	vx_plan p;
	vx_dvr_decide d;
	vx_err e = { 0, "" };

	dvr_prepare(text, g, o, &s, &tf, &d, &p);
	vx_image_init(img);
	if (vx_dvr_render(&s, &d, &tf, g, m, o, img, st, &e) != 0)
		fail_msg("%s", e.msg);
	vx_tf_free(&tf);
}

/* 1. Beer-Lambert through a homogeneous slab, any slice count */
static void
slab_transmittance(void **state)
{
	static const int slices[] = { 0, 13, 39, 78, 250 };
	const double alpha = 0.05, ref = 1;
	const double sigma = -log(1 - alpha) / ref;
	vx_grid g;
	vx_dvr_opts o;
	char text[512];

	(void)state;
	zgrid(&g, 8, 8, 40, z_one);   /* depth 39 along z */
	for (size_t i = 0; i < sizeof slices / sizeof slices[0]; i++) {
		vx_image img;
		vx_dvr_stats st;

		vx_dvr_opts_init(&o);
		o.slices = slices[i];
		snprintf(text, sizeof text, "camera orthographic eye 3.5 3.5 100 "
		    "look 3.5 3.5 0 up 0 1 0 width 7\nimage width 8 height 8\n"
		    "light none\nambient intensity 1\neffects none\n"
		    "transfer opacity 0 %.17g\n", alpha);
		render(text, &g, NULL, &o, &img, &st);
		assert_int_equal(st.nslices, slices[i] ? slices[i] : 39);
		/* emission 1 (white, ambient 1): colour = coverage */
		double want = 1 - exp(-sigma * 39);
		float *px = &img.px[4 * (4 * 8 + 4)];

		assert_true(fabs(px[3] - want) < 2e-6);
		assert_true(fabs(px[0] - want) < 2e-6);
		vx_image_free(&img);
	}
	/* oblique: a slab 39 deep that fills the view, seen 30 degrees off
	 * its normal: the path is 39 / cos 30 */
	{
		vx_grid w;
		vx_image img;
		double c = cos(30 * M_PI / 180);

		wide_slab(&w);
		vx_dvr_opts_init(&o);
		wide_slab_scene(text, sizeof text, alpha);
		render(text, &w, NULL, &o, &img, NULL);
		double want = 1 - exp(-sigma * 39 / c);

		/* the slices cut the path into whole steps: within one
		 * step's share of the exponent */
		for (int i = 0; i < 16; i++)
			assert_true(fabs(img.px[4 * i + 3] - want) <
			    sigma / c * exp(-sigma * 39 / c) + 1e-6);
		vx_image_free(&img);
		vx_grid_free(&w);
	}
	vx_grid_free(&g);
}

/* the oracle: the sum over material slices j (from the top) of
 * alpha q^(power j); the slice points are at z = 38.5 - k (39 slices over
 * the depth 39, from the light's side), material where the interpolated
 * value is >= 0.5 (the transfer function's step) */
static double
oracle(double (*f)(int), double alpha, int power)
{
	double sum = 0, q = 1 - alpha;
	int j = 0;

	for (int k = 0; k < 39; k++) {
		double z = 38.5 - k;
		int z0 = (int)floor(z);
		double v = 0.5 * (f(z0) + f(z0 + 1));

		if (v >= 0.5) {
			sum += alpha * pow(q, power * j);
			j++;
		}
	}
	return sum;
}

static void
slab_shadow(void **state)
{
	const double alpha = 0.2;
	double (*fs[3])(int) = { z_slabs, z_receiver, z_occluder };
	double lit[3], unlit[3];
	vx_dvr_opts o;
	char text[512];

	(void)state;
	vx_dvr_opts_init(&o);
	o.light_size = 16;
	o.jitter = 0;      /* the oracle counts samples on the voxel planes */
	for (int i = 0; i < 3; i++)
		for (int sh = 0; sh < 2; sh++) {
			vx_grid g;
			vx_image img;
			double want = oracle(fs[i], alpha, sh ? 2 : 1);

			zgrid(&g, 8, 8, 40, fs[i]);
			snprintf(text, sizeof text, "camera orthographic eye 3.5 "
			    "3.5 100 look 3.5 3.5 0 up 0 1 0 width 7\n"
			    "image width 8 height 8\n"
			    "light directional direction 0 0 -1\n"
			    "ambient intensity 0\neffects %s\n"
			    "transfer opacity 0.5 0 0.5 %.17g\n",
			    sh ? "volumetric-shadows" : "none", alpha);
			render(text, &g, NULL, &o, &img, NULL);
			double got = img.px[4 * (4 * 8 + 4)];

			assert_true(fabs(got - want) < 1e-5);
			(sh ? lit : unlit)[i] = got;
			vx_image_free(&img);
			vx_grid_free(&g);
		}
	/* the occluder (6 slabs' worth of samples: n_o material slices)
	 * dims the receiver by q^(2 n_o) with shadows, q^(n_o) without */
	double q = 1 - alpha;
	int no = 0;

	for (int k = 0; k < 39; k++) {
		double z = 38.5 - k;
		int z0 = (int)floor(z);

		no += 0.5 * (z_occluder(z0) + z_occluder(z0 + 1)) >= 0.5;
	}
	assert_true(fabs((lit[0] - lit[2]) - pow(q, 2 * no) * lit[1]) < 1e-5);
	assert_true(fabs((unlit[0] - unlit[2]) - pow(q, no) * unlit[1]) < 1e-5);
	assert_true(lit[0] < unlit[0]);
}

/* relative RMS difference of the colour of a and b over pixels b covers */
static double
relrms(const vx_image *a, const vx_image *b)
{
	double s = 0, m = 0;
	size_t n = (size_t)a->w * a->h;

	for (size_t i = 0; i < n; i++)
		for (int c = 0; c < 3; c++) {
			double d = a->px[4 * i + c] - b->px[4 * i + c];

			s += d * d;
			m += b->px[4 * i + c];
		}
	return sqrt(s / (3.0 * n)) / (m / (3.0 * n));
}

static const char sphere_tf[] =
    "transfer opacity 0 0.1 0.6 0.1 0.7 0.02 0.8 0\n"
    "transfer color 0 1 0.8 0.6 0.7 0.9 0.9 1\n"
    "transfer transport 0 0.95 0.8 0.6 0.7 0.95 0.8 0.6 0.8 1 1 1\n"
    "medium phase henyey-greenstein g 0.3\n"
    "effects volumetric-shadows scattering\nambient intensity 0.05\n";

static void
synth_sphere(vx_grid *g, int n)
{
	int64_t dims[3] = { n, n, n };
	vx_err e = { 0, "" };

	vx_grid_init(g);
	assert_int_equal(vx_synth_make(g, VX_SYNTH_SPHERE, dims, &e), 0);
}

/* 3. slice count: converging pictures */
static void
slice_count(void **state)
{
	vx_grid g;
	vx_image img[3];
	vx_dvr_opts o;
	char text[1024];
	double d01, d12;

	(void)state;
	synth_sphere(&g, 32);
	snprintf(text, sizeof text, "%simage width 48 height 48\n"
	    "light directional direction 1 -1 -1\n", sphere_tf);
	for (int i = 0; i < 3; i++) {
		vx_dvr_opts_init(&o);
		o.light_size = 48;
		o.slices = 40 << i;
		render(text, &g, NULL, &o, &img[i], NULL);
	}
	d01 = relrms(&img[0], &img[1]);
	d12 = relrms(&img[1], &img[2]);
	/* first order: each doubling about halves the difference (0.057,
	 * then 0.028 when this was written) */
	assert_true(d01 < 0.08);
	assert_true(d12 < 0.04);
	assert_true(d12 < 0.6 * d01);
	for (int i = 0; i < 3; i++)
		vx_image_free(&img[i]);
	vx_grid_free(&g);
}

/* 4. the view-light flip: the light turned from 75 to 105 degrees off the
 * view (front view: V = -y) in steps of 6 degrees, through 90 where the
 * compositing order switches: the step across the switch changes the
 * picture by no more than 1.5 times the largest other step (they were
 * 0.10 to 0.11 in relative RMS, the switch's 0.10, when this was
 * written) */
static void
flip(void **state)
{
	vx_grid g;
	vx_image img[6];
	vx_dvr_opts o;
	char text[1024];
	double step[6], worst_else = 0, at_switch = 0;
	int n = 0;

	(void)state;
	synth_sphere(&g, 32);
	vx_dvr_opts_init(&o);
	o.light_size = 48;
	o.slices = 96;
	for (int deg = 75; deg <= 105; deg += 6, n++) {
		double th = deg * M_PI / 180;

		/* V = (0,-1,0); L at angle th from V in the x-y plane */
		snprintf(text, sizeof text, "%simage width 48 height 48\n"
		    "light directional direction %.17g %.17g 0\n", sphere_tf,
		    sin(th), -cos(th));
		render(text, &g, NULL, &o, &img[n], NULL);
	}
	for (int i = 0; i + 1 < n; i++) {
		int d0 = 75 + 6 * i;

		step[i] = relrms(&img[i], &img[i + 1]);
		print_message("%d -> %d: %g\n", d0, d0 + 6, step[i]);
		if (d0 == 87)
			at_switch = step[i];
		else if (step[i] > worst_else)
			worst_else = step[i];
	}
	/* 87 -> 93 crosses the switch */
	assert_true(at_switch > 0 && at_switch < 1.5 * worst_else);
	for (int i = 0; i < n; i++)
		vx_image_free(&img[i]);
	vx_grid_free(&g);
}

/* 5. skipping changes no bit; threads change no bit */
static void
skip_and_threads(void **state)
{
	vx_grid g;
	vx_macro m;
	vx_image a, b, c;
	vx_dvr_stats sa, sb, sc;
	vx_dvr_opts o;
	vx_err e = { 0, "" };
	int sizes[2][3];
	char text[1024];

	(void)state;
	synth_sphere(&g, 40);
	vx_macro_default_sizes(g.type, 2, sizes);
	assert_int_equal(vx_macro_build(&m, &g, 2, sizes, 1, &e), 0);
	snprintf(text, sizeof text, "%simage width 40 height 40\n"
	    "light point position 0.5 3 2\n"
	    "transfer surface 0 0 0.5 1\neffects +specular\n", sphere_tf);
	vx_dvr_opts_init(&o);
	o.light_size = 40;
	o.nthreads = 1;
	render(text, &g, &m, &o, &a, &sa);
	o.nthreads = 3;
	render(text, &g, &m, &o, &b, &sb);
	render(text, &g, NULL, &o, &c, &sc);
	assert_true(sa.eye_skipped > 0 && sa.light_skipped > 0);
	assert_int_equal(sc.eye_skipped, 0);
	assert_true(sa.eye_samples == sc.eye_samples);
	assert_int_equal(memcmp(a.px, b.px, 4 * sizeof(float) * 40 * 40), 0);
	assert_int_equal(memcmp(a.px, c.px, 4 * sizeof(float) * 40 * 40), 0);
	vx_image_free(&a);
	vx_image_free(&b);
	vx_image_free(&c);
	vx_macro_free(&m);
	vx_grid_free(&g);
}

/* 5b. the approximations' knobs (vx_dvr_opts): emission only (ambient
 * 1, white, no lights), so every sample's radiance is 1 and a pixel's
 * colour moves by at most the sum of its samples' alpha errors (each
 * partial derivative of the compositing is a transmittance times a
 * radiance difference, within [-1, 1]).  The cutoff stops a ray whose
 * transmittance fell below it: what it leaves out is at most that
 * transmittance.  The table errs per sample by at most the opacity's
 * slope times its node spacing (test_tf's lut), the correction's
 * derivative being <= 1 at ratio 1 (orthographic, one voxel apart).
 * Oracle: the exact renderer (tf_table 0, cutoff 0). */
static void
knobs(void **state)
{
	/* moves: the knob changes some pixel (at 4096 nodes the table's
	 * second-order error in sigma falls below single precision here) */
	static const struct { int table; double cutoff; int moves; } t[] = {
		{ 0, 1e-3, 1 }, { 0, 0.05, 1 }, { 4096, 0, 0 }, { 16, 0, 1 },
		{ 4096, 1e-3, 1 },
	};
	vx_grid g;
	vx_image ex, img;
	vx_dvr_stats st;
	vx_dvr_opts o;
	const char *text = "camera orthographic eye 15.5 15.5 100 "
	    "look 15.5 15.5 0 up 0 1 0 width 31\nimage width 32 height 32\n"
	    "light none\nambient intensity 1\neffects none\n"
	    "transfer opacity 0 0 1 0.4\n";
	double lo = 0, hi = 0;

	(void)state;
	synth_sphere(&g, 32);
	lo = g.vmin;
	hi = g.vmax;
	vx_dvr_opts_init(&o);
	o.tf_table = 0;
	o.cutoff = 0;
	render(text, &g, NULL, &o, &ex, &st);
	assert_int_equal(st.eye_done, 0);
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		double bound = t[i].cutoff + (t[i].table > 0 ? st.nslices *
		    0.4 * (hi - lo) / t[i].table : 0) + 1e-6, worst = 0;
		vx_dvr_stats s2;

		vx_dvr_opts_init(&o);
		o.tf_table = t[i].table;
		o.cutoff = t[i].cutoff;
		render(text, &g, NULL, &o, &img, &s2);
		for (int k = 0; k < 4 * 32 * 32; k++)
			worst = fmax(worst, fabs(img.px[k] - ex.px[k]));
		assert_true(worst <= bound);
		assert_true((worst > 0) == t[i].moves);
		assert_true((s2.eye_done > 0) == (t[i].cutoff > 0));
		vx_image_free(&img);
	}
	vx_image_free(&ex);
	vx_grid_free(&g);
}

/* 6. the plan: only what the scene asks for (vx_dvr.h, "Only what the
 * scene asks for" and "Lights") */
static void
plan_table(void **state)
{
	static const struct {
		const char *text;
		int driver, light_buffer, scatter, gradient, surface, specular;
		int local0, local1;
	} t[] = {
		/* the default headlight, no effects asked: unattenuated */
		{ "", 0, 0, 0, 0, 0, 0, 1, 0 },
		{ "effects volumetric-shadows", 0, 1, 0, 0, 0, 0, 0, 0 },
		/* scattering implies the light buffer */
		{ "effects scattering", 0, 1, 1, 0, 0, 0, 0, 0 },
		/* the first point/directional light drives; the next is local */
		{ "light sky\nlight directional direction 0 0 -1\n"
		  "light point position 0 0 5\neffects volumetric-shadows",
		  1, 1, 0, 0, 0, 0, 0, 0 },
		/* a light of intensity 0 drives nothing */
		{ "light point position 0 0 5 intensity 0\n"
		  "light directional direction 0 0 -1\neffects scattering",
		  1, 1, 1, 0, 0, 0, 0, 0 },
		/* no light that can drive the buffer: none, even if asked */
		{ "light sky\neffects volumetric-shadows scattering",
		  -1, 0, 0, 0, 0, 0, 0, 0 },
		/* the gradient for a surface list or a gradient list */
		{ "transfer surface 0 1\neffects specular", 0, 0, 0, 1, 1, 1, 1,
		  0 },
		{ "transfer gradient 0 1\neffects none", 0, 0, 0, 1, 0, 0, 1, 0 },
	};
	vx_dvr_opts o;

	(void)state;
	vx_dvr_opts_init(&o);
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		char text[512];
		vx_scene s;
		vx_tf tf;
		vx_plan p;
		vx_dvr_decide d;

		snprintf(text, sizeof text, "transfer opacity 0 0.5\n%s\n",
		    t[i].text);
		dvr_prepare(text, NULL, &o, &s, &tf, &d, &p);
		if (d.driver != t[i].driver || d.light_buffer != t[i].light_buffer ||
		    d.scatter != t[i].scatter || d.gradient != t[i].gradient ||
		    d.surface != t[i].surface || d.specular != t[i].specular ||
		    d.local[0] != t[i].local0 || d.local[1] != t[i].local1)
			fail_msg("case %zu (%s): driver %d buffer %d scatter %d "
			    "gradient %d surface %d specular %d local %d %d", i,
			    t[i].text, d.driver, d.light_buffer, d.scatter,
			    d.gradient, d.surface, d.specular, d.local[0],
			    d.local[1]);
		vx_tf_free(&tf);
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(slab_transmittance),
		cmocka_unit_test(slab_shadow),
		cmocka_unit_test(slice_count),
		cmocka_unit_test(flip),
		cmocka_unit_test(skip_and_threads),
		cmocka_unit_test(knobs),
		cmocka_unit_test(plan_table),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
