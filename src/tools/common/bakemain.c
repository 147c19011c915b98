/* bakemain.c: the bakers bake-irr and bake-sh (Wyman et al. 2006), one
 * program with two faces: for every wanted texel of a lattice over the
 * volume, path-traced irradiance (bake-irr, the IRRV chunk) or the SH
 * projection of the radiance transfer (bake-sh, SHTV) on the isosurface
 * through the texel's own value (vx_bake.h).  A stream that already holds
 * this volume's bake gets more samples (resume); --merge adds another
 * bake's samples. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "tool.h"
#include "bakemain.h"
#include "vx_bake.h"
#include "vx_gi.h"
#include "vx_grid.h"
#include "vx_irrvol.h"
#include "vx_macro.h"
#include "vx_par.h"
#include "vx_scene.h"

/* the options both take, after each one's own */
#define USAGE_COMMON \
    "    [--samples N] [--target-error E] [--round N] [--min-samples N]\n" \
    "    [--bounces N] [--offset VOXELS] [--seed N] [--first-sample N]\n" \
    "    [--iso-range A,B] [--margin M] [--all] [--side low|high]\n" \
    "    [--merge STREAM] [--fresh] [--lazy] [--half|--final] [--fixed BITS]\n" \
    "    [--max-memory GB] [-z LEVEL] [-j N] [--stats] [--explain] [-n]\n" \
    "    [-o OUT] [IN|-]"
static const char usage_irr[] =
    "bake-irr [--scene FILE] [--set LINE] [--light SPEC] [--lights none]\n"
    "    [--effects WORDS] [--iso V[,V...]] [--name VOLUME] [--scale S]\n"
    USAGE_COMMON;
static const char usage_sh[] =
    "bake-sh [--scene FILE] [--set LINE] [--effects WORDS] [--iso V[,V...]]\n"
    "    [--name VOLUME] [--order N] [--channels 1|3] [--scale S]\n"
    USAGE_COMMON;
static const char *usage;
static const char *me;         /* the tool's name */
static int sh;                 /* 1: bake-sh */

/* --side: which side of the isosurface is lit (opts.high) */
static const vx_enum_name side_names[] = {
	{ "low", 0 }, { "high", 1 }, { NULL, -1 }
};
static const vx_enum sides = { "side", side_names, "?", 0 };

typedef struct opts {
	const char *in, *merge;
	int fresh, all, fixed, lazy;
	int has_bounces, bounces, has_range, has_first, has_samples, high;
	int order, channels;
	double max_gb;
	vx_irr_store store;
	double range[2], margin;
	uint64_t seed;
	uint32_t first;
	tool_run_opts run;       /* -o, -j, -z, -n, --stats, --explain */
	vx_bake_opts b;
	tool_scene_opts so;      /* --scene and the scene options */
} opts;

static void
parse(opts *o, int argc, char **argv)
{
	enum { O_SCALE = 256, O_SAMPLES, O_TARGET, O_ROUND, O_MIN, O_BOUNCES,
	    O_OFFSET, O_SEED, O_FIRST, O_RANGE, O_MARGIN, O_ALL, O_MERGE,
	    O_FRESH, O_HALF, O_FINAL, O_FIXED, O_SIDE,
	    O_LAZY, O_ORDER, O_CHANNELS, O_MAXMEM };
	static const struct option lo[] = {
		{ "scene", 1, 0, TOOL_O_SCENE }, { "iso", 1, 0, TOOL_O_ISO },
		TOOL_SCENE_LONG_LIGHTS,
		{ "name", 1, 0, TOOL_O_NAME }, { "scale", 1, 0, O_SCALE },
		{ "samples", 1, 0, O_SAMPLES },
		{ "target-error", 1, 0, O_TARGET }, { "round", 1, 0, O_ROUND },
		{ "min-samples", 1, 0, O_MIN }, { "bounces", 1, 0, O_BOUNCES },
		{ "offset", 1, 0, O_OFFSET }, { "seed", 1, 0, O_SEED },
		{ "first-sample", 1, 0, O_FIRST },
		{ "iso-range", 1, 0, O_RANGE }, { "margin", 1, 0, O_MARGIN },
		{ "all", 0, 0, O_ALL }, { "merge", 1, 0, O_MERGE },
		{ "fresh", 0, 0, O_FRESH }, { "half", 0, 0, O_HALF },
		{ "final", 0, 0, O_FINAL }, { "fixed", 1, 0, O_FIXED },
		{ "side", 1, 0, O_SIDE }, { "lazy", 0, 0, O_LAZY },
		{ "order", 1, 0, O_ORDER }, { "channels", 1, 0, O_CHANNELS },
		{ "max-memory", 1, 0, O_MAXMEM }, TOOL_RUN_LONG, { 0, 0, 0, 0 }
	};
	int ch;

	memset(o, 0, sizeof *o);
	tool_run_opts_init(&o->run);
	o->run.zlevel = 0;
	o->fixed = VX_IRR_FIXED;
	o->seed = 1;
	o->store = VX_IRR_ACCUM;
	o->order = 5;
	vx_bake_opts_init(&o->b);
	while ((ch = getopt_long(argc, argv, TOOL_RUN_SHORT, lo, NULL)) != -1) {
		switch (ch) {
		case O_SCALE:
			o->b.scale = tool_parse_double("--scale", optarg, 1e-3,
			    64);
			break;
		case O_SAMPLES:
			o->b.samples = (uint32_t)tool_parse_long("--samples",
			    optarg, 0, 1L << 30);
			o->has_samples = 1;
			break;
		case O_TARGET:
			o->b.target = tool_parse_double("--target-error", optarg,
			    1e-6, 1);
			break;
		case O_ROUND:
			o->b.round = (uint32_t)tool_parse_long("--round", optarg,
			    1, 1L << 20);
			break;
		case O_MIN:
			o->b.min_samples = (uint32_t)tool_parse_long(
			    "--min-samples", optarg, 2, 1L << 30);
			break;
		case O_BOUNCES:
			o->bounces = (int)tool_parse_long("--bounces", optarg, 0,
			    VX_GI_MAX_BOUNCES);
			o->has_bounces = 1;
			break;
		case O_OFFSET:
			o->b.offset = tool_parse_double("--offset", optarg, 0, 8);
			break;
		case O_SEED:
			o->seed = (uint64_t)tool_parse_long("--seed", optarg, 0,
			    2147483647L);
			break;
		case O_FIRST:
			o->first = (uint32_t)tool_parse_long("--first-sample",
			    optarg, 0, 1L << 30);
			o->has_first = 1;
			break;
		case O_RANGE:
			tool_parse_doubles("--iso-range", optarg, o->range, 2);
			if (!(o->range[0] <= o->range[1]))
				tool_usage_fail(usage, "--iso-range: A must be "
				    "<= B");
			o->has_range = 1;
			break;
		case O_MARGIN:
			o->margin = tool_parse_double("--margin", optarg, 0,
			    1e300);
			break;
		case O_ALL: o->all = 1; break;
		case O_SIDE:
			o->high = tool_parse_enum("--side", &sides, optarg);
			break;
		case O_MERGE: o->merge = optarg; break;
		case O_FRESH: o->fresh = 1; break;
		case O_LAZY: o->lazy = 1; break;
		case O_HALF: o->store = VX_IRR_F16; break;
		case O_FINAL: o->store = VX_IRR_F32; break;
		case O_FIXED:
			o->fixed = (int)tool_parse_long("--fixed", optarg, 0, 40);
			break;
		case O_ORDER:
			if (!sh)
				tool_usage_fail(usage, "--order: bake-sh only");
			o->order = (int)tool_parse_long("--order", optarg, 1, 16);
			break;
		case O_CHANNELS:
			if (!sh)
				tool_usage_fail(usage, "--channels: bake-sh only");
			o->channels = (int)tool_parse_long("--channels", optarg,
			    1, 3);
			if (o->channels == 2)
				tool_usage_fail(usage, "--channels: 1 or 3");
			break;
		case O_MAXMEM:
			o->max_gb = tool_parse_double("--max-memory", optarg,
			    1e-6, 1e9);
			break;
		default:
			if (!tool_run_opt(&o->run, ch, optarg) &&
			    !tool_scene_opt(&o->so, ch, optarg, usage))
				tool_opt_other(ch, usage, argv);
		}
	}
	o->in = tool_opt_input(argc, argv, usage);
	if (o->all && o->has_range)
		tool_usage_fail(usage, "--all and --iso-range exclude each other");
}

/* ---- progress on a terminal ---- */

typedef struct progress {
	double t0;
	int shown;
} progress;

static double
now(void)
{
	return vx_par_seconds();
}

static void
show_progress(void *ctx, uint64_t done, uint64_t total)
{
	progress *p = ctx;
	double el = now() - p->t0, left;

	if (total == 0)
		return;
	left = done > 0 ? el * (double)(total - done) / (double)done : 0;
	fprintf(stderr, "\r%s: %5.1f%% of %llu texels, %.0f s elapsed, "
	    "about %.0f s left   ", me, 100.0 * (double)done / (double)total,
	    (unsigned long long)total, el, left);
	if (done == total)
		fputc('\n', stderr);
	fflush(stderr);
	p->shown = 1;
}

/* what a texel holds, for messages */
static const char *
contents(const vx_irrvol *v)
{
	static char buf[64];

	if (v->sh_order == 0)
		return " RGB irradiance";
	snprintf(buf, sizeof buf, " SH order %d (%d coefficient%s x %d "
	    "channel%s)", v->sh_order, v->sh_order * v->sh_order,
	    v->sh_order == 1 ? "" : "s", v->channels,
	    v->channels == 1 ? "" : "s");
	return buf;
}

/* the chunk's name, for messages */
static const char *
what(void)
{
	return sh ? "SH transfer volume" : "irradiance volume";
}

/* the process's CPU seconds so far (all threads) */
static double
cpu_now(void)
{
	struct timespec ts;

	if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0)
		return 0;
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* cpu_s: CPU seconds of the planning and baking (every thread) */
static void
print_stats(const vx_bake_stats *bs, const vx_irrvol *v, int nthr,
    double cpu_s)
{
	double t = bs->bake_s > 0 ? bs->bake_s : 1e-9;
	uint64_t rays = bs->gi.rays + bs->gi.shadow_rays;

	fprintf(stderr, "%s: lattice %lld x %lld x %lld (%llu texels), "
	    "%llu wanted, %llu baked, %llu flat, %llu with NaN, %llu at the "
	    "border\n", me, (long long)v->dims[0], (long long)v->dims[1],
	    (long long)v->dims[2], (unsigned long long)bs->lattice,
	    (unsigned long long)bs->wanted, (unsigned long long)bs->baked,
	    (unsigned long long)bs->flat, (unsigned long long)bs->nan,
	    (unsigned long long)bs->border);
	fprintf(stderr, "%s: %llu samples (paths), %llu bounce rays, "
	    "%llu shadow rays, %llu hits; %.0f paths/s, %.0f rays/s on %d "
	    "thread%s; %.0f paths per core-second (%.2f CPU s, plan and "
	    "bake)\n", me,
	    (unsigned long long)bs->samples, (unsigned long long)bs->gi.rays,
	    (unsigned long long)bs->gi.shadow_rays,
	    (unsigned long long)bs->gi.hits, (double)bs->samples / t,
	    (double)rays / t, nthr, nthr == 1 ? "" : "s",
	    cpu_s > 0 ? (double)bs->samples / cpu_s : 0.0, cpu_s);
	fprintf(stderr, "%s: time: plan %.3f s, bake %.3f s; storage "
	    "%s%s, %zu bytes per texel in the stream (%zu in memory), %zu "
	    "bricks of %d^3, %.1f MB in memory\n", me, bs->plan_s, bs->bake_s,
	    vx_enum_str(&vx_irr_store_enum, v->store), contents(v),
	    vx_irr_texel_bytes(v->store, v->ncomp),
	    vx_irr_texel_memory(v->store, v->ncomp), v->nslot, VX_IRR_BRICK,
	    (double)vx_irr_bytes(v) / 1e6);
}

/* physical memory in bytes (0: unknown) */
static uint64_t
physical(void)
{
	long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);

	return pages > 0 && size > 0 ? (uint64_t)pages * (uint64_t)size : 0;
}

int
tool_bake_main(int argc, char **argv, int want_sh)
{
	opts o;
	vx_stream st;
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_gi gi;
	vx_irrvol v, old;
	vx_bake_stats bs;
	vx_err e = { 0, "" };
	long gidx, iidx = -1;
	int nthr, resumed = 0;
	double cpu0;
	char settings[2048], key[17];
	progress pr;

	sh = want_sh;
	me = sh ? "bake-sh" : "bake-irr";
	usage = sh ? usage_sh : usage_irr;
	tool_init(me, argc, argv);
	parse(&o, argc, argv);
	vx_stream_init(&st);
	tool_read_stream(&st, o.in);
	vx_scene_init(&s);
	tool_scene_opts_load(&s, &o.so, &st);
	vx_grid_init(&g);
	if (vx_grid_view_stream(&g, &st, o.run.name ? o.run.name : (s.volume[0] ?
	    s.volume : NULL), &gidx, &e) != 0)
		tool_fail_err(&e);
	nthr = tool_threads(o.run.threads);
	if (!sh) {
		tool_gi_setup(&gi, &s, &g, NULL);
	} else if (vx_gi_setup(&gi, &s, &g, NULL, &e) != 0) {
		tool_fail_err(&e);   /* transfer needs no light */
	}
	if (o.has_bounces)
		gi.bounces = o.bounces;
	gi.seed = o.seed;
	gi.high = o.high;
	/* which texels */
	o.b.all = o.all || (!o.has_range && s.nsurface == 0);
	if (o.has_range) {
		o.b.nband = 1;
		o.b.band[0][0] = o.range[0] - o.margin;
		o.b.band[0][1] = o.range[1] + o.margin;
	} else if (!o.b.all) {
		for (int k = 0; k < s.nsurface && k < VX_BAKE_MAX_BANDS; k++) {
			o.b.band[k][0] = s.surface[k].iso - o.margin;
			o.b.band[k][1] = s.surface[k].iso + o.margin;
		}
		o.b.nband = s.nsurface < VX_BAKE_MAX_BANDS ? s.nsurface :
		    VX_BAKE_MAX_BANDS;
	}
	o.b.threads = nthr;
	if (sh && o.channels == 0)   /* colour only where bounces colour it */
		o.channels = vx_gi_sh_channels(&gi);
	if (!sh) {
		o.order = 0;
		o.channels = 3;
	}
	o.b.max_bytes = o.max_gb > 0 ? (uint64_t)(o.max_gb * 1e9) :
	    physical() / 10 * 9;
	if (!o.has_samples)
		o.b.samples = s.has_interreflection ? (uint32_t)s.samples : 64;
	{
		vx_irrvol tmp;

		vx_irr_init(&tmp);
		tmp.scale = o.b.scale;
		tmp.fixed = o.fixed;
		tmp.sh_order = o.order;
		tmp.channels = o.channels;
		vx_bake_settings(&tmp, &gi, &o.b, settings, sizeof settings);
		vx_bake_key(settings, key);
	}
	/* the stream's bake of this volume: resumed unless --fresh */
	vx_irr_init(&v);
	if ((sh ? vx_irr_sh_from_stream : vx_irr_from_stream)(&old, &st, g.name,
	    &iidx, &e) != 0)
		tool_fail_err(&e);
	vx_macro_init(&m);
	(void)m;
	memset(&bs, 0, sizeof bs);
	{
		uint32_t crc = vx_macro_grid_crc(&g);

		if (iidx >= 0 && !o.fresh) {
			if (old.vcrc != crc)
				tool_fail(VX_EDATA, "the stream's %s "
				    "was baked from other samples of '%s' (use "
				    "--fresh to bake anew)", what(), g.name);
			if (strcmp(old.key, key) != 0)
				tool_fail(VX_EDATA, "the stream's %s "
				    "was baked with other settings (key %s, these "
				    "give %s; use --fresh to bake anew)", what(),
				    old.key, key);
			if (old.store != VX_IRR_ACCUM)
				tool_fail(VX_EDATA, "the stream's %s "
				    "is final (%s): it cannot take more samples "
				    "(use --fresh to bake anew)", what(),
				    vx_enum_str(&vx_irr_store_enum, old.store));
			if (o.has_first && o.first != old.first)
				tool_fail(VX_EUSAGE, "--first-sample %u: the "
				    "stream's bake starts at %u", o.first,
				    old.first);
			v = old;
			resumed = 1;
		} else {
			vx_irr_free(&old);
			/* a final store without --merge and --lazy is baked
			 * straight into it (no accumulators kept) */
			if (vx_irr_setup_sh(&v, &g, crc, o.b.scale,
			    o.merge || o.lazy ? VX_IRR_ACCUM : o.store,
			    o.order, o.channels, &e) != 0)
				tool_fail_err(&e);
			v.fixed = o.fixed;
			v.first = o.first;
			vx_bake_sign(&v, &gi, &o.b);
		}
		if (resumed && o.b.scale != v.scale)
			tool_fail(VX_EUSAGE, "--scale %g: the stream's bake has "
			    "scale %g", o.b.scale, v.scale);
	}
	for (size_t i = 0; i < st.n; i++)
		o.b.held_bytes += st.chunk[i].len;
	/* a lazy bake records its settings and plans nothing: raycast
	 * --lazy wants the texels its views read */
	if (!o.lazy && vx_bake_plan(&v, &g, &o.b, &bs, &e) != 0) {
		if (e.code == VX_ENOMEM && o.b.max_bytes > 0 &&
		    bs.need_bytes > o.b.max_bytes)
			tool_fail(VX_ENOMEM, "%s: %s (--max-memory); it fits "
			    "with %s", g.name, e.msg, sh ? "a lower --order, "
			    "--half or --channels 1, a narrower --iso-range, or "
			    "a smaller --scale" : "--half or --final, a narrower "
			    "--iso-range, or a smaller --scale");
		tool_fail_err(&e);
	}
	if (o.merge != NULL) {
		vx_stream ms;
		vx_irrvol mv;
		long mi;

		vx_stream_init(&ms);
		tool_read_stream(&ms, o.merge);
		if ((sh ? vx_irr_sh_from_stream : vx_irr_from_stream)(&mv, &ms,
		    g.name, &mi, &e) != 0) {
			vx_err_push(&e, "%s", o.merge);
			tool_fail_err(&e);
		}
		if (mi < 0)
			tool_fail(VX_EDATA, "%s: no %s of '%s'", o.merge, what(),
			    g.name);
		if (vx_irr_merge(&v, &mv, &e) != 0) {
			vx_err_push(&e, "--merge %s", o.merge);
			tool_fail_err(&e);
		}
		vx_irr_free(&mv);
		vx_stream_free(&ms);
		if (!o.has_samples)
			o.b.samples = 0;
	}
	if (o.run.explain) {
		double paths = (double)bs.wanted * o.b.samples;

		fprintf(stderr, "%s: plan: %s %lld x %lld x %lld texels at "
		    "scale %g (%s), %llu wanted (%s)\n", me,
		    resumed ? "resume the stream's bake:" : "lattice of",
		    (long long)v.dims[0], (long long)v.dims[1],
		    (long long)v.dims[2], v.scale, v.scale == 1 ?
		    "one texel a sample" : "its own resolution",
		    (unsigned long long)bs.wanted, o.lazy ? "lazy: none now, "
		    "raycast --lazy bakes the texels its views read" :
		    o.b.all ? "every texel" :
		    "cells whose values meet the isovalue band");
		fprintf(stderr, "%s: plan: storage %s%s: %zu bytes a texel in "
		    "memory (%zu in the stream), %llu bricks of %d^3: %.1f MB "
		    "of memory at the peak, with the input and the chunk "
		    "written (limit %.1f MB, --max-memory)\n", me,
		    vx_enum_str(&vx_irr_store_enum, o.store), contents(&v),
		    vx_irr_texel_memory(v.store, v.ncomp),
		    vx_irr_texel_bytes(o.store, v.ncomp),
		    (unsigned long long)bs.bricks, VX_IRR_BRICK,
		    (double)bs.need_bytes / 1e6, (double)o.b.max_bytes / 1e6);
		if (sh)
			fprintf(stderr, "%s: plan: the transfer of distant light "
			    "(no light of the scene is used: SH lighting is "
			    "applied when rendering); %d bounce%s%s; normals "
			    "from the B-spline-smoothed gradient, start %g "
			    "voxels along them\n", me, gi.bounces,
			    gi.bounces == 1 ? "" : "s", v.channels == 3 ?
			    ", coloured by the albedo (3 channels)" :
			    ", one channel", o.b.offset);
		else
			fprintf(stderr, "%s: plan: %d delta light%s (shadow rays "
			    "%s), %s, %s; %d bounce%s; normals from the "
			    "B-spline-smoothed gradient, start %g voxels along "
			    "them\n", me, gi.nlight, gi.nlight == 1 ? "" : "s",
			    (s.effects & VX_FX_SHADOWS) ? "on" : "off",
			    gi.has_sky ? "a sky" : "no sky",
			    gi.has_env ? "an environment (importance-sampled, "
			    "MIS)" : "no environment", gi.bounces,
			    gi.bounces == 1 ? "" : "s", o.b.offset);
		if (!sh && gi.skipped_headlights)
			fprintf(stderr, "%s: plan: %d headlight%s left out "
			    "(it moves with the camera)\n", me,
			    gi.skipped_headlights,
			    gi.skipped_headlights == 1 ? "" : "s");
		if (o.b.target > 0)
			fprintf(stderr, "%s: plan: samples in rounds of %u "
			    "until the relative standard error is %g (at least "
			    "%u, at most %u a texel)\n", me, o.b.round,
			    o.b.target, o.b.min_samples, o.b.samples);
		fprintf(stderr, "%s: plan: %s%u samples a texel: about "
		    "%.3g paths, %.3g rays (%d thread%s)\n", me,
		    o.b.target > 0 ? "at most " : "", o.b.samples, paths,
		    sh ? paths * (1 + gi.bounces) :
		    paths * (1 + gi.bounces) * (1 + gi.nlight +
		    (gi.has_env ? 1 : 0)), nthr, nthr == 1 ? "" : "s");
	}
	if (o.run.dry) {
		vx_irr_free(&v);
		vx_grid_free(&g);
		vx_stream_free(&st);
		return tool_finish();
	}
	/* the hierarchy for the traversal */
	tool_macro_load(&m, &st, &g, gidx, nthr, 0);
	gi.tr.m = &m;
	gi.tr.flat = 0;
	memset(&pr, 0, sizeof pr);
	pr.t0 = now();
	if (isatty(2)) {
		o.b.progress = show_progress;
		o.b.progress_ctx = &pr;
	}
	cpu0 = cpu_now();
	if (!o.lazy && o.b.samples > 0 &&
	    vx_bake_run(&v, &gi, &g, &o.b, &bs, &e) != 0)
		tool_fail_err(&e);
	cpu0 = cpu_now() - cpu0;
	v.samples += o.b.samples;
	if (o.store != VX_IRR_ACCUM && vx_irr_finalize(&v, o.store, &e) != 0)
		tool_fail_err(&e);
	if (o.run.stats)
		print_stats(&bs, &v, nthr, cpu0);
	{
		vx_chunk c;

		memset(&c, 0, sizeof c);
		if (vx_irr_to_chunk(&v, o.run.zlevel, &c, &e) != 0)
			tool_fail_err(&e);
		if (iidx >= 0)
			vx_stream_replace(&st, (size_t)iidx, &c);
		else if (vx_stream_append(&st, &c, &e) != 0)
			tool_fail_err(&e);
	}
	tool_write_stream(&st, o.run.out);
	vx_irr_free(&v);
	vx_macro_free(&m);
	vx_grid_free(&g);
	vx_stream_free(&st);
	return tool_finish();
}
