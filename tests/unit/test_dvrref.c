/* test_dvrref.c: the references of direct volume rendering (vx_dvrref.h).
 *
 * Oracles (sigma = -ln(1 - alpha) / ref, q = 1 - alpha' for a step h):
 *  - a homogeneous slab seen straight on and 30 degrees off its normal:
 *    ray march coverage 1 - exp(-sigma d) exactly (its segments add up to
 *    the path d at any step), path tracer coverage within 4 standard
 *    deviations of the binomial fraction of paths with a vertex;
 *  - the shadow of one slab on another, light along the view: pixel(both)
 *    = pixel(occluder) + q^(n_e + n_s) pixel(receiver), n_e the eye
 *    samples and n_s the shadow segments in the occluder (each the
 *    occluder's thickness rounded to the step), and pixel(receiver) =
 *    alpha' (1 - q^(2 n)) / (1 - q^2) for its n samples;
 *  - single scattering in a thin homogeneous slab of depth d lit head-on:
 *    backscatter (light from the eye's side) Ll P (1 - exp(-2 sigma d))
 *    / 2, forward (light from behind) Ll P sigma d exp(-sigma d), with
 *    P = 4 pi p_HG(cos): the path tracer within its Monte Carlo bound;
 *    the ray march exactly times sech(sigma h / 2) and
 *    sinh(sigma h / 2) / (sigma h / 2) (the sums over its midpoints);
 *  - multiple scattering in a deep, wide homogeneous medium of albedo w
 *    lit and seen along the normal: Chandrasekhar's semi-infinite
 *    isotropic reflection, (w / 2) Ll H(1)^2 with H his H-function
 *    (solved here by iteration), within the Monte Carlo bound; one vertex
 *    gives w / 2 (H = 1);
 *  - half-angle slicing against the ray march on a smooth blob: relative
 *    RMSE below the first-order bound exp(sigma_max h_l / 2) - 1 (h_l the
 *    light ray's spacing between slices: the light buffer at a slice
 *    holds the attenuation up to half a spacing before it, the march from
 *    the point itself), the slicer brighter on the whole (that term's
 *    sign), and the error falls as the slices double;
 *  - 1 thread = 3 threads bit for bit; spp 8 = the mean of paths 0-3 and
 *    4-7 (additivity); more bounces only add light. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "helper_dvr.h"
#include "vx_dvrref.h"
#include "vx_phase.h"

/* render g as text says, by the reference o (NULL: the slicer with dvr
 * options dv) */
static void
render(const char *text, const vx_grid *g, const vx_dvrref_opts *o,
    const vx_dvr_opts *dv, vx_image *img)
{
	vx_scene s;
	vx_tf tf;
	vx_plan p;
	vx_dvr_decide d;
	vx_dvr_opts dd;
	vx_err e = { 0, "" };

	vx_dvr_opts_init(&dd);
	dvr_prepare(text, g, dv ? dv : &dd, &s, &tf, &d, &p);
	vx_image_init(img);
	if (o != NULL) {
		vx_dvrref_plan(&s, &tf, &d, o, &p);
		if (vx_dvrref_render(&s, &d, &tf, g, o, img, NULL, &e) != 0)
			fail_msg("%s", e.msg);
	} else if (vx_dvr_render(&s, &d, &tf, g, NULL, dv, img, NULL, &e) != 0)
		fail_msg("%s", e.msg);
	vx_tf_free(&tf);
}

static vx_dvrref_opts
ref(int method, double step, int spp, int bounces)
{
	vx_dvrref_opts o;

	vx_dvrref_opts_init(&o);
	o.method = method;
	o.step = step;
	o.spp = spp;
	o.bounces = bounces;
	o.nthreads = 2;
	return o;
}

/* mean of channel c over the image */
static double
mean(const vx_image *img, int c)
{
	double s = 0;
	size_t n = (size_t)img->w * (size_t)img->h;

	for (size_t i = 0; i < n; i++)
		s += img->px[4 * i + c];
	return s / (double)n;
}

/* 1. Beer-Lambert through a homogeneous slab */
static void
slab_transmittance(void **state)
{
	static const double steps[] = { 0, 0.7, 3.1, 39 };
	const double alpha = 0.05, sigma = -log(1 - alpha);
	const char *head = "camera orthographic eye 3.5 3.5 100 look 3.5 3.5 0 "
	    "up 0 1 0 width 7\nimage width 8 height 8\nlight none\n"
	    "ambient intensity 1\neffects none\ntransfer opacity 0 0.05\n";
	double want = 1 - exp(-sigma * 39);
	vx_grid g;
	vx_image img;

	(void)state;
	zgrid(&g, 8, 8, 40, z_one);
	for (size_t i = 0; i < sizeof steps / sizeof steps[0]; i++) {
		vx_dvrref_opts o = ref(VX_DVRREF_RAYMARCH, steps[i], 1, 1);

		render(head, &g, &o, NULL, &img);
		for (int p = 0; p < 64; p++) {
			assert_true(fabs(img.px[4 * p + 3] - want) < 2e-6);
			assert_true(fabs(img.px[4 * p] - want) < 2e-6);
		}
		vx_image_free(&img);
	}
	/* the path tracer: the fraction of 64 x 256 paths with a vertex;
	 * colour = coverage path by path (emission 1) */
	{
		vx_dvrref_opts o = ref(VX_DVRREF_PATHTRACE, 0, 256, 1);
		double n = 64 * 256, sd = sqrt(want * (1 - want) / n);

		render(head, &g, &o, NULL, &img);
		assert_true(fabs(mean(&img, 3) - want) < 4 * sd);
		for (int p = 0; p < 64; p++)
			assert_true(img.px[4 * p] == img.px[4 * p + 3]);
		vx_image_free(&img);
	}
	vx_grid_free(&g);
	/* oblique, 30 degrees off the normal of a slab that fills the view:
	 * the path is 39 / cos 30 at any step */
	{
		double c = cos(30 * M_PI / 180);
		char text[512];
		vx_dvrref_opts o = ref(VX_DVRREF_RAYMARCH, 0.9, 1, 1);

		wide_slab(&g);
		wide_slab_scene(text, sizeof text, alpha);
		render(text, &g, &o, NULL, &img);
		want = 1 - exp(-sigma * 39 / c);
		for (int i = 0; i < 16; i++)
			assert_true(fabs(img.px[4 * i + 3] - want) < 2e-6);
		vx_image_free(&img);
		vx_grid_free(&g);
	}
}

/* 2. the shadow of one slab on another.  Values 1 in z [6, 13] (the
 * receiver) and [24, 29] (the occluder), 0 elsewhere; opacity steps up at
 * 0.25, so the material is z in [5.25, 13.75] and [23.25, 29.75] (the
 * trilinear value crosses 0.25 a quarter voxel outside).  Eye samples at
 * z = 38.5, 37.5, ...: 9 in the receiver, 7 in the occluder; shadow
 * segments from a receiver sample upward have midpoints at the integers:
 * 6 in the occluder (its thickness 6.5 rounded by the step). */
static void
slab_shadow(void **state)
{
	const double alpha = 0.2, q = 1 - alpha;
	double (*fs[3])(int) = { z_slabs, z_receiver, z_occluder };
	double pix[3];
	char text[512];
	vx_dvrref_opts o = ref(VX_DVRREF_RAYMARCH, 0, 1, 1);

	(void)state;
	snprintf(text, sizeof text, "camera orthographic eye 3.5 3.5 100 "
	    "look 3.5 3.5 0 up 0 1 0 width 7\nimage width 8 height 8\n"
	    "light directional direction 0 0 -1\neffects volumetric-shadows\n"
	    "ambient intensity 0\n"
	    "transfer opacity 0 0 0.25 0 0.25 %.17g\n", alpha);
	for (int i = 0; i < 3; i++) {
		vx_grid g;
		vx_image img;

		zgrid(&g, 8, 8, 40, fs[i]);
		render(text, &g, &o, NULL, &img);
		pix[i] = img.px[4 * (3 * 8 + 4)];
		vx_image_free(&img);
		vx_grid_free(&g);
	}
	/* the receiver alone: sample j from the top sees q^j through the
	 * receiver above it, and the light q^j */
	assert_true(fabs(pix[1] - alpha * (1 - pow(q, 18)) / (1 - q * q)) <
	    1e-6);
	assert_true(fabs(pix[2] - alpha * (1 - pow(q, 14)) / (1 - q * q)) <
	    1e-6);
	assert_true(fabs(pix[0] - (pix[2] + pow(q, 7 + 6) * pix[1])) < 1e-6);
}

/* 3. single scattering in a thin homogeneous slab, depth 4, lit head-on
 * from the eye's side (backscatter) and from behind (forward) */
static void
single_scatter(void **state)
{
	const double alpha = 0.1, sigma = -log(1 - alpha), d = 4, g = 0.3;
	vx_grid gr;

	(void)state;
	zgrid(&gr, 16, 16, 5, z_one);
	for (int side = 0; side < 2; side++) {
		double cosv = side == 0 ? -1 : 1;
		double P = 4 * M_PI * vx_phase_hg(g, cosv), want;
		char text[512];
		vx_image img;

		want = side == 0 ? P * (1 - exp(-2 * sigma * d)) / 2 :
		    P * sigma * d * exp(-sigma * d);
		snprintf(text, sizeof text, "camera orthographic eye 7.5 7.5 100 "
		    "look 7.5 7.5 0 up 0 1 0 width 8\nimage width 8 height 8\n"
		    "light directional direction 0 0 %d\n"
		    "effects volumetric-shadows\nambient intensity 0\n"
		    "medium phase henyey-greenstein g %.17g\n"
		    "transfer opacity 0 %.17g\n", side == 0 ? -1 : 1, g, alpha);
		/* path tracer: a path's contribution X is in [0, P], so its
		 * variance is at most P E[X] */
		vx_dvrref_opts o = ref(VX_DVRREF_PATHTRACE, 0, 512, 1);
		double n = 64.0 * 512, bound = 4 * sqrt(P * want / n);

		render(text, &gr, &o, NULL, &img);
		assert_true(fabs(mean(&img, 0) - want) < bound);
		assert_true(fabs(mean(&img, 2) - want) < bound);
		vx_image_free(&img);
		/* ray march at steps 1 and 1/4: the midpoint sums in closed
		 * form */
		for (int k = 0; k < 2; k++) {
			double h = k ? 0.25 : 1, x = sigma * h / 2;
			double wm = side == 0 ? want / cosh(x) : want * sinh(x) / x;

			o = ref(VX_DVRREF_RAYMARCH, h, 1, 1);
			render(text, &gr, &o, NULL, &img);
			for (int p = 0; p < 64; p++)
				assert_true(fabs(img.px[4 * p + 1] - wm) <
				    2e-6 * wm);
			vx_image_free(&img);
		}
	}
	vx_grid_free(&gr);
}

/* Chandrasekhar's H(1) for isotropic scattering of albedo w, by iterating
 * H(mu) = 1 / (1 - (w / 2) mu int_0^1 H(mu') / (mu + mu') dmu') on a
 * midpoint rule of N nodes; *m0 gets the zeroth moment int_0^1 H */
static double
chandrasekhar_h1(double w, double *m0)
{
	enum { N = 800 };
	static double h[N], hn[N];
	double s;

	for (int i = 0; i < N; i++)
		h[i] = 1;
	for (int it = 0; it < 200; it++) {
		double dmax = 0;

		for (int i = 0; i < N; i++) {
			double mu = (i + 0.5) / N;

			s = 0;
			for (int j = 0; j < N; j++)
				s += h[j] / (mu + (j + 0.5) / N);
			hn[i] = 1 / (1 - 0.5 * w * mu * s / N);
			dmax = fmax(dmax, fabs(hn[i] - h[i]));
		}
		memcpy(h, hn, sizeof h);
		if (dmax < 1e-12)
			break;
	}
	s = *m0 = 0;
	for (int j = 0; j < N; j++) {
		s += h[j] / (1 + (j + 0.5) / N);
		*m0 += h[j] / N;
	}
	return 1 / (1 - 0.5 * w * s / N);
}

/* 4. multiple scattering: a medium 27 optical depths deep (sigma 0.69 a
 * voxel, depth 39) reaching 27 voxels (19 optical depths) beyond the
 * pixels seen on every side, albedo 0.8, isotropic, lit and seen along
 * its normal */
static void
multiple_scatter(void **state)
{
	const double w = 0.8;
	double m0, H1 = chandrasekhar_h1(w, &m0);
	vx_grid g;
	vx_image i1, in;
	const char *text = "camera orthographic eye 31.5 31.5 100 "
	    "look 31.5 31.5 0 up 0 1 0 width 8\nimage width 8 height 8\n"
	    "light directional direction 0 0 -1\n"
	    "effects volumetric-shadows\nambient intensity 0\n"
	    "transfer opacity 0 0.5\n"
	    "transfer color 0 0.8 0.8 0.8\n";
	vx_dvrref_opts o1 = ref(VX_DVRREF_PATHTRACE, 0, 512, 1);
	vx_dvrref_opts on = ref(VX_DVRREF_PATHTRACE, 0, 512, 80);

	(void)state;
	/* the solution checked by an exact identity of H: its zeroth moment
	 * is (2 / w) (1 - sqrt(1 - w)) */
	assert_true(fabs(m0 - 2 / w * (1 - sqrt(1 - w))) < 1e-4);
	zgrid(&g, 64, 64, 40, z_one);
	render(text, &g, &o1, NULL, &i1);
	render(text, &g, &on, NULL, &in);
	/* one vertex: w / 2; a path's X in [0, 1] */
	double n = 64.0 * 512, want1 = w / 2, wantn = w / 2 * H1 * H1;

	assert_true(fabs(mean(&i1, 1) - want1) < 4 * sqrt(want1 / n));
	/* all orders: a path's X in [0, 1 / (1 - w)] (w^(k-1) at vertex
	 * k); 0.8^80 of the light is left out */
	assert_true(fabs(mean(&in, 1) - wantn) < 4 * sqrt(wantn / (1 - w) /
	    n) + pow(w, 80) / (1 - w));
	/* more bounces only add light: the first vertex's numbers are the
	 * same */
	for (int p = 0; p < 64; p++)
		for (int c = 0; c < 4; c++)
			assert_true(in.px[4 * p + c] >= i1.px[4 * p + c]);
	vx_image_free(&i1);
	vx_image_free(&in);
	vx_grid_free(&g);
}

/* a smooth blob: exp(-r^2 / (2 s^2)) over an n^3 grid */
static void
blob(vx_grid *g, int n)
{
	int64_t dims[3] = { n, n, n };
	vx_err e = { 0, "" };
	double c = (n - 1) / 2.0, s = n / 6.0;

	vx_grid_init(g);
	assert_int_equal(vx_grid_alloc(g, dims, VX_F32, NULL, &e), 0);
	for (int z = 0; z < n; z++)
		for (int y = 0; y < n; y++)
			for (int x = 0; x < n; x++) {
				double r2 = (x - c) * (x - c) + (y - c) * (y - c) +
				    (z - c) * (z - c);

				vx_grid_set(g, x, y, z, exp(-r2 / (2 * s * s)));
			}
	vx_grid_range(g);
}

/* relative RMSE of b's colour against a's over pixels either covers */
static double
relrmse(const vx_image *a, const vx_image *b)
{
	double se = 0, sm = 0;
	size_t n = (size_t)a->w * (size_t)a->h, k = 0;

	for (size_t i = 0; i < n; i++)
		if (a->px[4 * i + 3] > 0 || b->px[4 * i + 3] > 0)
			for (int c = 0; c < 3; c++) {
				double d = b->px[4 * i + c] - a->px[4 * i + c];

				se += d * d;
				sm += a->px[4 * i + c];
				k++;
			}
	return sqrt(se / (double)k) / (sm / (double)k);
}

/* 5. slicing against the ray march on the blob, the light 60 degrees
 * from the view: opacity up to 0.3 a voxel */
static void
slicing_bound(void **state)
{
	const char *text = "image width 64 height 64\n"
	    "camera auto projection orthographic view front\n"
	    "ambient intensity 0\n"
	    "light directional direction 0.8660254 0.5 0\n"
	    "effects volumetric-shadows\n"
	    "transfer opacity 0 0 0.1 0 1 0.3\n";
	const double smax = -log(1 - 0.3);
	vx_grid g;
	vx_image rm, sl[2];
	double err[2];
	vx_dvrref_opts o = ref(VX_DVRREF_RAYMARCH, 0.25, 1, 1);

	(void)state;
	blob(&g, 32);
	render(text, &g, &o, NULL, &rm);
	for (int i = 0; i < 2; i++) {
		vx_dvr_opts dv;
		vx_scene s;
		vx_dvr_decide d;
		vx_dvr_geom geo;
		vx_plan p;
		vx_tf tf;
		vx_err e = { 0, "" };
		double hl, bound;

		vx_dvr_opts_init(&dv);
		dv.slices = 40 << i;
		dv.light_size = 256;
		dv.nthreads = 2;
		render(text, &g, NULL, &dv, &sl[i]);
		err[i] = relrmse(&rm, &sl[i]);
		/* the light ray's spacing: dt / |s . L| */
		dvr_prepare(text, &g, &dv, &s, &tf, &d, &p);
		assert_int_equal(vx_dvr_geometry(&s, &d, &tf, &g, &dv, &geo, &e),
		    0);
		hl = geo.dt / fabs(geo.axis[0] * geo.light_dir[0] +
		    geo.axis[1] * geo.light_dir[1] +
		    geo.axis[2] * geo.light_dir[2]);
		bound = exp(smax * hl / geo.ref_step / 2) - 1;
		print_message("slices %d: relative RMSE %.4g, bound %.4g\n",
		    dv.slices, err[i], bound);
		assert_true(err[i] < bound);
		assert_true(mean(&sl[i], 0) > mean(&rm, 0));
		vx_tf_free(&tf);
		vx_image_free(&sl[i]);
	}
	assert_true(err[1] < 0.7 * err[0]);
	vx_image_free(&rm);
	vx_grid_free(&g);
}

/* 6. threads, determinism, additivity */
static void
threads_spp(void **state)
{
	const char *text = "image width 24 height 20\n"
	    "light directional direction 1 -1 -1\n"
	    "light point position 40 -40 40 intensity 0.3\n"
	    "effects volumetric-shadows\nmedium phase henyey-greenstein g 0.4\n"
	    "transfer opacity 0 0 0.2 0 1 0.4\ntransfer surface 0 0 1 0.5\n"
	    "ambient intensity 0.1\n";
	vx_grid g;
	vx_image a, b, c;
	size_t n = 24 * 20 * 4;

	(void)state;
	blob(&g, 16);
	for (int m = 0; m < 2; m++) {
		vx_dvrref_opts o = ref(m ? VX_DVRREF_PATHTRACE :
		    VX_DVRREF_RAYMARCH, 0, 8, 3);

		o.nthreads = 1;
		render(text, &g, &o, NULL, &a);
		o.nthreads = 3;
		render(text, &g, &o, NULL, &b);
		assert_memory_equal(a.px, b.px, n * sizeof *a.px);
		assert_true(mean(&a, 0) > 0.01);
		vx_image_free(&b);
		if (m == 1) {
			/* paths 0-3 and 4-7 average to paths 0-7 */
			o.spp = 4;
			render(text, &g, &o, NULL, &b);
			o.first = 4;
			render(text, &g, &o, NULL, &c);
			for (size_t i = 0; i < n; i++)
				assert_true(fabs(a.px[i] - 0.5 * (b.px[i] +
				    c.px[i])) <= 1e-6 * (1 + fabs(a.px[i])));
			assert_memory_not_equal(b.px, c.px, n * sizeof *b.px);
			vx_image_free(&b);
			vx_image_free(&c);
		}
		vx_image_free(&a);
	}
	vx_grid_free(&g);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(slab_transmittance),
		cmocka_unit_test(slab_shadow),
		cmocka_unit_test(single_scatter),
		cmocka_unit_test(multiple_scatter),
		cmocka_unit_test(slicing_bound),
		cmocka_unit_test(threads_spp),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
