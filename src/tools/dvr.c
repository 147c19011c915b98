/* dvr: direct volume rendering with volumetric light by half-angle slicing
 * (Kniss et al. 2003). */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tool.h"
#include "vx_camera.h"
#include "vx_dvr.h"
#include "vx_dvrref.h"
#include "vx_grid.h"
#include "vx_image.h"
#include "vx_macro.h"
#include "vx_plan.h"
#include "vx_scene.h"
#include "vx_tf.h"

static const char usage[] =
    "dvr [--scene FILE] [--size WxH] [--view NAME|AZ,EL] [--ortho]\n"
    "    [--fov DEG] [--light SPEC] [--lights none] [--effects WORDS]\n"
    "    [--background R,G,B] [--set LINE] [--name NAME] [--slices N]\n"
    "    [--light-size N] [--blur-angle DEG] [--blur-samples N] [--seed N]\n"
    "    [--no-skip] [--no-jitter] [--tf-table N] [--cutoff T] [-j N]\n"
    "    [--stats] [--explain] [-n] [--hdr] [-z LEVEL] [--pfm FILE]\n"
    "    [--bits 8|16] [--exposure STOPS] [-o OUT] [STREAM|-]\n"
    "    [--reference raymarch|pathtrace [--spp N] [--bounces N]\n"
    "    [--march-step S]]";

typedef struct opts {
	const char *in, *name;
	int ortho;
	tool_run_opts run;        /* -o, -j, --hdr, --stats, ... */
	vx_dvr_opts d;
	tool_scene_opts so;
	int ref;                  /* --reference given */
	int pt_opt, rm_opt;       /* --spp or --bounces, --march-step given */
	vx_dvrref_opts r;
} opts;

static void
parse(opts *o, int argc, char **argv)
{
	enum { O_ORTHO = 256, O_NAME, O_SLICES, O_LSIZE, O_BANGLE, O_BSAMP,
	    O_SEED, O_NOSKIP, O_REF, O_SPP, O_BOUNCES, O_MSTEP, O_TFTABLE,
	    O_CUTOFF, O_NOJITTER };
	static const struct option lo[] = {
		{ "scene", 1, 0, TOOL_O_SCENE },
		{ "size", 1, 0, TOOL_O_SIZE }, { "view", 1, 0, TOOL_O_VIEW },
		{ "ortho", 0, 0, O_ORTHO }, { "fov", 1, 0, TOOL_O_FOV },
		{ "light", 1, 0, TOOL_O_LIGHT }, { "lights", 1, 0, TOOL_O_LIGHTS },
		{ "effects", 1, 0, TOOL_O_EFFECTS },
		{ "background", 1, 0, TOOL_O_BG },
		{ "set", 1, 0, TOOL_O_SET }, { "name", 1, 0, O_NAME },
		{ "slices", 1, 0, O_SLICES }, { "light-size", 1, 0, O_LSIZE },
		{ "blur-angle", 1, 0, O_BANGLE },
		{ "blur-samples", 1, 0, O_BSAMP }, { "seed", 1, 0, O_SEED },
		{ "no-skip", 0, 0, O_NOSKIP },
		{ "tf-table", 1, 0, O_TFTABLE }, { "cutoff", 1, 0, O_CUTOFF },
		{ "no-jitter", 0, 0, O_NOJITTER },
		{ "exposure", 1, 0, TOOL_O_EXPOSURE },
		{ "pfm", 1, 0, TOOL_O_PFM },
		{ "reference", 1, 0, O_REF }, { "spp", 1, 0, O_SPP },
		{ "bounces", 1, 0, O_BOUNCES }, { "march-step", 1, 0, O_MSTEP },
		TOOL_RUN_LONG, TOOL_RENDER_LONG, { 0, 0, 0, 0 }
	};
	int c;

	memset(o, 0, sizeof *o);
	tool_run_opts_init(&o->run);
	vx_dvr_opts_init(&o->d);
	vx_dvrref_opts_init(&o->r);
	while ((c = getopt_long(argc, argv, TOOL_RUN_SHORT, lo, NULL)) != -1) {
		switch (c) {
		case O_ORTHO: o->ortho = 1; break;
		case O_NAME: o->name = optarg; break;
		case O_SLICES:
			o->d.slices = (int)tool_parse_long("--slices", optarg, 1,
			    VX_DVR_MAX_SLICES);
			break;
		case O_LSIZE:
			o->d.light_size = (int)tool_parse_long("--light-size",
			    optarg, 1, VX_DVR_MAX_LIGHT_SIZE);
			break;
		case O_BANGLE:
			o->d.blur_angle = tool_parse_double("--blur-angle", optarg,
			    0, 89.9);
			break;
		case O_BSAMP:
			o->d.blur_samples = (int)tool_parse_long("--blur-samples",
			    optarg, 1, VX_DVR_MAX_BLUR);
			break;
		case O_SEED:
			o->d.seed = (uint64_t)tool_parse_long("--seed", optarg, 0,
			    0x7fffffffffffffffL);
			break;
		case O_NOSKIP: o->d.no_skip = 1; break;
		case O_NOJITTER: o->d.jitter = 0; break;
		case O_TFTABLE:
			o->d.tf_table = (int)tool_parse_long("--tf-table", optarg,
			    0, VX_TF_MAX_LUT);
			break;
		case O_CUTOFF:
			o->d.cutoff = tool_parse_double("--cutoff", optarg, 0, 1);
			break;
		/* the references (vx_dvrref.h) */
		case O_REF:
			o->ref = 1;
			if (strcmp(optarg, "raymarch") == 0)
				o->r.method = VX_DVRREF_RAYMARCH;
			else if (strcmp(optarg, "pathtrace") == 0)
				o->r.method = VX_DVRREF_PATHTRACE;
			else
				tool_usage_fail(usage, "--reference: raymarch or "
				    "pathtrace");
			break;
		case O_SPP:
			o->pt_opt = 1;
			o->r.spp = (int)tool_parse_long("--spp", optarg, 1,
			    VX_DVRREF_MAX_SPP);
			break;
		case O_BOUNCES:
			o->pt_opt = 1;
			o->r.bounces = (int)tool_parse_long("--bounces", optarg, 1,
			    VX_DVRREF_MAX_BOUNCES);
			break;
		case O_MSTEP:
			o->rm_opt = 1;
			o->r.step = tool_parse_double("--march-step", optarg,
			    1e-9, 1e9);
			break;
		default:
			if (!tool_run_opt(&o->run, c, optarg) &&
			    !tool_scene_opt(&o->so, c, optarg, usage))
				tool_opt_other(c, usage, argv);
		}
	}
	o->in = tool_opt_input(argc, argv, usage);
	o->r.seed = o->d.seed;
	if (o->pt_opt && !(o->ref && o->r.method == VX_DVRREF_PATHTRACE))
		tool_usage_fail(usage, "--spp, --bounces: only with --reference "
		    "pathtrace");
	if (o->rm_opt && !(o->ref && o->r.method == VX_DVRREF_RAYMARCH))
		tool_usage_fail(usage, "--march-step: only with --reference "
		    "raymarch");
}

static void
explain_geometry(const vx_scene *s, const vx_dvr_decide *d,
    const vx_dvr_geom *geo, const vx_grid *g, int nthr)
{
	const double *a = geo->axis;

	fprintf(stderr, "dvr: %dx%d pixels (%s camera), volume '%s' %lldx%lldx"
	    "%lld; %d thread%s\n", s->camera.w, s->camera.h,
	    vx_enum_str(&vx_projection_enum, s->camera.projection), g->name,
	    (long long)g->dims[0], (long long)g->dims[1],
	    (long long)g->dims[2], nthr, nthr == 1 ? "" : "s");
	if (d->light_buffer)
		fprintf(stderr, "dvr: slicing axis %.4g %.4g %.4g, halfway "
		    "between the light's direction %.4g %.4g %.4g and the %s "
		    "%.4g %.4g %.4g (angle between light and view %.1f "
		    "degrees): the eye composites %s\n", a[0], a[1], a[2],
		    geo->light_dir[0], geo->light_dir[1], geo->light_dir[2],
		    geo->back_to_front ? "inverted view" : "view",
		    geo->back_to_front ? -geo->view_dir[0] : geo->view_dir[0],
		    geo->back_to_front ? -geo->view_dir[1] : geo->view_dir[1],
		    geo->back_to_front ? -geo->view_dir[2] : geo->view_dir[2],
		    acos(fmax(-1, fmin(1, geo->light_dir[0] *
		    geo->view_dir[0] + geo->light_dir[1] * geo->view_dir[1] +
		    geo->light_dir[2] * geo->view_dir[2]))) * 180 / M_PI,
		    geo->back_to_front ? "back to front (the light faces the "
		    "viewer)" : "front to back");
	else
		fprintf(stderr, "dvr: slicing axis %.4g %.4g %.4g, the view "
		    "direction (no light buffer): the eye composites front to "
		    "back\n", a[0], a[1], a[2]);
	fprintf(stderr, "dvr: %d slices %.4g apart (world units along the "
	    "axis); opacity given for a reference step of %.4g, corrected "
	    "along each eye and light ray's own path between slices\n",
	    geo->nslices, geo->dt, geo->ref_step);
	fprintf(stderr, "dvr: buffers: eye %dx%d RGBA%s\n", s->camera.w,
	    s->camera.h, d->light_buffer ? (geo->light.projection ==
	    VX_PERSPECTIVE ? ", light (perspective from the point light) "
	    "D + RGB, two for ping-pong" : ", light (orthographic along the "
	    "light) D + RGB, two for ping-pong") : "");
}

static void
print_stats(const vx_dvr_stats *st)
{
	double es = (double)st->eye_samples, ls = (double)st->light_samples;

	fprintf(stderr, "dvr: %d slices, %d thread%s, %.3f s\n", st->nslices,
	    st->threads, st->threads == 1 ? "" : "s", st->seconds);
	fprintf(stderr, "dvr: eye samples %llu (%.1f%% skipped as empty, "
	    "%.1f%% behind the cutoff), light samples %llu (%.1f%% skipped), "
	    "light buffer %dx%d\n", (unsigned long long)st->eye_samples,
	    es > 0 ? 100 * (double)st->eye_skipped / es : 0.0,
	    es > 0 ? 100 * (double)st->eye_done / es : 0.0,
	    (unsigned long long)st->light_samples,
	    ls > 0 ? 100 * (double)st->light_skipped / ls : 0.0,
	    st->light_size, st->light_size);
	fprintf(stderr, "dvr: time: set-up %.3f s, eye passes %.3f s, light "
	    "passes %.3f s\n", st->setup_s, st->eye_s, st->light_s);
}

/* ---- the references (--reference, vx_dvrref.h) ---- */

static void
explain_reference(const opts *o, const vx_scene *s, const vx_tf *tf,
    const vx_dvr_decide *d, const vx_grid *g, int nthr)
{
	vx_plan p;
	double ms = fmin(g->spacing[0], fmin(g->spacing[1], g->spacing[2]));
	double ref = tf->ref_step > 0 ? tf->ref_step : ms;

	vx_dvrref_plan(s, tf, d, &o->r, &p);
	tool_plan_print(&p);
	fprintf(stderr, "dvr: %dx%d pixels (%s camera), volume '%s' %lldx%lldx"
	    "%lld; %d thread%s\n", s->camera.w, s->camera.h,
	    vx_enum_str(&vx_projection_enum, s->camera.projection), g->name,
	    (long long)g->dims[0], (long long)g->dims[1],
	    (long long)g->dims[2], nthr, nthr == 1 ? "" : "s");
	if (o->r.method == VX_DVRREF_RAYMARCH)
		fprintf(stderr, "dvr: reference ray march at a step of %.4g "
		    "(opacity given for %.4g), a shadow ray at the same step "
		    "from every sample with opacity: cost about (samples per "
		    "ray)^2 per pixel, slow\n", o->r.step > 0 ? o->r.step : ref,
		    ref);
	else
		fprintf(stderr, "dvr: reference path tracer, %d path%s per "
		    "pixel, up to %d vertex%s each (%s scattering), delta "
		    "tracking and ratio-tracked shadow rays: cost about spp x "
		    "vertices x (tentative collisions per ray) per pixel, "
		    "noisy as 1/sqrt(spp)\n", o->r.spp, o->r.spp == 1 ? "" : "s",
		    o->r.bounces, o->r.bounces == 1 ? "" : "es",
		    o->r.bounces == 1 ? "single" : "multiple");
}

static void
stats_reference(const opts *o, const vx_dvrref_stats *st)
{
	if (o->r.method == VX_DVRREF_RAYMARCH)
		fprintf(stderr, "dvr: reference raymarch, step %.4g, %d "
		    "thread%s, %.3f s\ndvr: eye samples %llu, shadow steps %llu "
		    "(%.1f a sample)\n", st->step, st->threads,
		    st->threads == 1 ? "" : "s", st->seconds,
		    (unsigned long long)st->samples,
		    (unsigned long long)st->shadow_steps, st->samples ?
		    (double)st->shadow_steps / (double)st->samples : 0.0);
	else
		fprintf(stderr, "dvr: reference pathtrace, %d spp, %d bounce%s, "
		    "%d thread%s, %.3f s\ndvr: paths %llu, vertices %llu, "
		    "tentative collisions %llu (majorant %.4g per unit), "
		    "shadow steps %llu\n", o->r.spp, o->r.bounces,
		    o->r.bounces == 1 ? "" : "s", st->threads,
		    st->threads == 1 ? "" : "s", st->seconds,
		    (unsigned long long)st->samples,
		    (unsigned long long)st->vertices,
		    (unsigned long long)st->tentative, st->sigma_max,
		    (unsigned long long)st->shadow_steps);
}

int
main(int argc, char **argv)
{
	opts o;
	vx_stream st;
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_tf tf;
	vx_plan plan;
	vx_dvr_decide d;
	vx_dvr_geom geo;
	vx_dvr_stats ds;
	vx_image color;
	vx_err e = { 0, "" };
	double lo[3], hi[3];
	long gi;
	int nthr;
	const char *want;

	tool_init("dvr", argc, argv);
	parse(&o, argc, argv);
	vx_stream_init(&st);
	tool_read_stream(&st, o.in);
	vx_scene_init(&s);
	tool_scene_opts_load(&s, &o.so, &st);
	if (o.ortho)
		s.camera.projection = VX_ORTHOGRAPHIC;
	want = o.name ? o.name : (s.volume[0] ? s.volume : NULL);
	vx_grid_init(&g);
	if (vx_grid_view_stream(&g, &st, want, &gi, &e) != 0)
		tool_fail_err(&e);
	if (vx_grid_check_box(&g, &e) != 0)
		tool_fail_err(&e);
	tool_scene_tf(&tf, &s);
	nthr = tool_threads(o.run.threads);
	o.d.nthreads = nthr;
	vx_dvr_plan(&s, &tf, &o.d, &d, &plan);
	vx_grid_box(&g, lo, hi);
	if (vx_camera_resolve(&s.camera, lo, hi, &e) != 0)
		tool_fail_err(&e);
	if (vx_dvr_geometry(&s, &d, &tf, &g, &o.d, &geo, &e) != 0)
		tool_fail_err(&e);
	o.r.nthreads = nthr;
	if (o.run.explain && o.ref)
		explain_reference(&o, &s, &tf, &d, &g, nthr);
	if (o.run.explain && !o.ref) {
		tool_plan_print(&plan);
		explain_geometry(&s, &d, &geo, &g, nthr);
	}
	vx_macro_init(&m);
	if (!o.d.no_skip && !o.ref)
		tool_macro_load(&m, &st, &g, gi, nthr, o.run.dry);
	if (o.run.dry) {
		vx_macro_free(&m);
		vx_tf_free(&tf);
		vx_grid_free(&g);
		vx_stream_free(&st);
		return tool_finish();
	}
	vx_image_init(&color);
	if (o.ref) {
		vx_dvrref_stats rs;

		if (vx_dvrref_render(&s, &d, &tf, &g, &o.r, &color, &rs,
		    &e) != 0)
			tool_fail_err(&e);
		if (o.run.stats)
			stats_reference(&o, &rs);
	} else {
		if (vx_dvr_render(&s, &d, &tf, &g, o.d.no_skip ? NULL : &m,
		    &o.d, &color, &ds, &e) != 0)
			tool_fail_err(&e);
		if (o.run.stats)
			print_stats(&ds);
	}
	{
		/* the volume and its hierarchy are consumed */
		static const char *const drawn[] = { VX_CHUNK_VOLUME,
		    VX_CHUNK_MACRO, NULL };
		const vx_image *img[3] = { &color, NULL, NULL };

		tool_render_write(&o.run, &st, drawn, &s, img, NULL);
	}
	vx_image_free(&color);
	vx_macro_free(&m);
	vx_tf_free(&tf);
	vx_grid_free(&g);
	vx_stream_free(&st);
	return tool_finish();
}
