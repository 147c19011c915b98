/* raycast: ray-traced isosurfaces of a volume (Parker et al. 1999 §4.1) or
 * of a tetrahedral mesh (§4.2). */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tool.h"
#include "vx_camera.h"
#include "vx_grid.h"
#include "vx_image.h"
#include "vx_imageio.h"
#include "vx_bake.h"
#include "vx_gi.h"
#include "vx_irrvol.h"
#include "vx_macro.h"
#include "vx_macroio.h"
#include "vx_plan.h"
#include "vx_raycast.h"
#include "vx_scene.h"
#include "vx_sh.h"
#include "vx_shlight.h"
#include "vx_env.h"
#include "vx_tetimport.h"
#include "vx_tetleaf.h"
#include "vx_tonemap.h"

static const char usage[] =
    "raycast [--scene FILE] [--iso V[,V...]] [--size WxH] [--view NAME|AZ,EL]\n"
    "        [--ortho] [--fov DEG] [--light SPEC] [--lights none]\n"
    "        [--effects WORDS] [--background R,G,B] [--set LINE]\n"
    "        [--name NAME] [--solver exact|neubauer|linear] [--flat]\n"
    "        [--no-cellmask] [--no-binning] [--bin-block N] [--aa N] [-j N]\n"
    "        [--stats] [--explain] [-n] [--hdr] [-z LEVEL] [--bits 8|16]\n"
    "        [--exposure STOPS] [--depth FILE.pfm] [--normals FILE.pfm]\n"
    "        [--lazy] [--lazy-save STREAM] [--spp N] [-o OUT] [STREAM|-]";

typedef struct opts {
	const char *in;
	int flat, aa, solver, nomask, nobin, binblock, lazy, spp;
	const char *lazy_save;
	int ortho;
	tool_run_opts run;         /* -o, -j, --hdr, --stats, ... */
	tool_scene_opts so;       /* --scene and the scene options */
} opts;

static void
parse(opts *o, int argc, char **argv)
{
	enum { O_ORTHO = 256, O_SOLVER, O_FLAT, O_AA, O_NOMASK,
	    O_NOBIN, O_BINBLOCK, O_LAZY, O_LAZYSAVE, O_SPP };
	static const struct option lo[] = {
		TOOL_SCENE_LONG, { "ortho", 0, 0, O_ORTHO },
		{ "name", 1, 0, TOOL_O_NAME },
		{ "solver", 1, 0, O_SOLVER }, { "flat", 0, 0, O_FLAT },
		{ "no-cellmask", 0, 0, O_NOMASK },
		{ "no-binning", 0, 0, O_NOBIN },
		{ "bin-block", 1, 0, O_BINBLOCK },
		{ "lazy", 0, 0, O_LAZY }, { "lazy-save", 1, 0, O_LAZYSAVE },
		{ "spp", 1, 0, O_SPP }, { "aa", 1, 0, O_AA },
		{ "exposure", 1, 0, TOOL_O_EXPOSURE },
		{ "depth", 1, 0, TOOL_O_DEPTH },
		{ "normals", 1, 0, TOOL_O_NORMALS },
		TOOL_RUN_LONG, TOOL_RENDER_LONG, { 0, 0, 0, 0 }
	};
	int c;

	memset(o, 0, sizeof *o);
	tool_run_opts_init(&o->run);
	o->aa = 1;
	o->solver = VX_CELL_EXACT;
	while ((c = getopt_long(argc, argv, TOOL_RUN_SHORT, lo, NULL)) != -1) {
		switch (c) {
		case O_ORTHO: o->ortho = 1; break;
		case O_SOLVER:
			o->solver = tool_parse_enum("--solver",
			    &vx_cell_solver_enum, optarg);
			break;
		case O_FLAT: o->flat = 1; break;
		case O_NOMASK: o->nomask = 1; break;
		case O_NOBIN: o->nobin = 1; break;
		case O_LAZY: o->lazy = 1; break;
		case O_SPP:
			o->spp = (int)tool_parse_long("--spp", optarg, 1, 1000000);
			break;
		case O_LAZYSAVE: o->lazy = 1; o->lazy_save = optarg; break;
		case O_BINBLOCK:
			o->binblock = (int)tool_parse_long("--bin-block", optarg, 1,
			    VX_RAYCAST_BLOCK_MAX);
			break;
		case O_AA: o->aa = (int)tool_parse_long("--aa", optarg, 1, 16); break;
		default:
			if (!tool_run_opt(&o->run, c, optarg) &&
			    !tool_scene_opt(&o->so, c, optarg, usage))
				tool_opt_other(c, usage, argv);
		}
	}
	o->in = tool_opt_input(argc, argv, usage);
}

/* load_scene: the stream's scene, replaced by --scene, then the options. */
static void
load_scene(vx_scene *s, const opts *o, const vx_stream *st)
{
	tool_scene_opts_load(s, &o->so, st);
	if (o->ortho)
		s->camera.projection = VX_ORTHOGRAPHIC;
}

static void
print_stats(const vx_raycast_stats *st, const vx_macro *m, int w, int h,
    int nthr)
{
	double rays = (double)(st->primary + st->shadow) + 1e-300;
	double px = (double)w * h;
	int l;

	fprintf(stderr, "raycast: %dx%d, %d thread%s, %.3f s (%.1f Mrays/s)\n",
	    w, h, nthr, nthr == 1 ? "" : "s", st->seconds,
	    (double)(st->primary + st->shadow) / st->seconds * 1e-6);
	fprintf(stderr, "raycast: rays: %llu primary, %llu shadow; "
	    "covered pixels %.1f%%\n", (unsigned long long)st->primary,
	    (unsigned long long)st->shadow,
	    100.0 * (double)st->covered / (px > 0 ? px : 1));
	if (st->mesh)
		fprintf(stderr, "raycast: leaves searched %llu (%.1f per ray), "
		    "list entries %llu (%.1f per ray), tets tested %llu (%.1f "
		    "per ray), crossings %llu, shaded %llu\n",
		    (unsigned long long)st->leaves, (double)st->leaves / rays,
		    (unsigned long long)st->entries, (double)st->entries / rays,
		    (unsigned long long)st->cells,
		    (double)st->cells / rays, (unsigned long long)st->hits,
		    (unsigned long long)st->shaded);
	else
		fprintf(stderr, "raycast: cells visited %llu (%.1f per ray), "
		    "roots solved %llu (%llu ruled out by the cubic's sign "
		    "bound, %llu of them without the face values), %llu signs "
		    "decided exactly, hits %llu, shaded %llu, non-finite "
		    "cells %llu\n",
		    (unsigned long long)st->cells, (double)st->cells / rays,
		    (unsigned long long)st->roots,
		    (unsigned long long)st->bounded,
		    (unsigned long long)st->certified,
		    (unsigned long long)st->exact,
		    (unsigned long long)st->hits, (unsigned long long)st->shaded,
		    (unsigned long long)st->nonfinite);
	if (st->paths > 0)
		fprintf(stderr, "raycast: pathtrace: %llu paths, %llu rays "
		    "(bounce and shadow), %.0f paths/s\n",
		    (unsigned long long)st->paths,
		    (unsigned long long)st->gi_rays,
		    (double)st->paths / (st->seconds > 0 ? st->seconds : 1e-9));
	if (st->irr_missing > 0)
		fprintf(stderr, "raycast: irradiance: %llu of %llu shaded points "
		    "found no baked texel (drawn black: outside the bake's "
		    "isovalue band)\n", (unsigned long long)st->irr_missing,
		    (unsigned long long)st->shaded);
	if (!st->mesh && st->mask_bytes > 0)
		fprintf(stderr, "raycast: cell mask: %llu of %llu level-1 "
		    "macrocells bracket, %llu of them masked (bits built); "
		    "%.1f KiB\n", (unsigned long long)st->mask_set,
		    (unsigned long long)st->mask_blocks,
		    (unsigned long long)st->mask_built,
		    (double)st->mask_bytes / 1024);
	if (!st->mesh && st->bins && st->bin_block)
		fprintf(stderr, "raycast: binning: %llu boxes (of the "
		    "bracketing leaves of each block of %dx%dx%d, and %llu "
		    "bracketing level-1 macrocells whole, %.1f ms); %llu of "
		    "%llu primary rays enter none (not walked)\n",
		    (unsigned long long)st->bin_boxes, st->bin_block,
		    st->bin_block, st->bin_block,
		    (unsigned long long)st->bin_whole, 1e3 * st->bin_seconds,
		    (unsigned long long)st->binned,
		    (unsigned long long)st->primary);
	else if (!st->mesh && st->bins)
		fprintf(stderr, "raycast: binning: %llu boxes (bracketing "
		    "level-1 macrocells, %.1f ms); %llu of %llu primary rays "
		    "enter none (not walked)\n", (unsigned long long)st->bin_boxes,
		    1e3 * st->bin_seconds,
		    (unsigned long long)st->binned,
		    (unsigned long long)st->primary);
	if (m != NULL) {
		fprintf(stderr, "raycast: macrocells examined:");
		for (l = m->nlev; l >= 1; l--)
			fprintf(stderr, " level %d: %llu", l,
			    (unsigned long long)st->macro[l]);
		fprintf(stderr, "; leaves stepped through without a visit: "
		    "%llu\n", (unsigned long long)st->culled);
	}
	fprintf(stderr, "raycast: time: traversal %.0f%%, %s %.0f%%, "
	    "shading %.0f%%\n", 100 * st->share_traverse,
	    st->mesh ? "tet tests" : "intersection", 100 * st->share_isect,
	    100 * st->share_shade);
	fprintf(stderr, "raycast: tiles: %.1f ms on %d thread%s, %.1f ms of "
	    "the threads' time (balance %.0f%%); outside them %.1f ms (set-up, "
	    "bins, the centre pixels' pass)\n", 1e3 * st->tile_seconds,
	    st->threads, st->threads == 1 ? "" : "s", 1e3 * st->thread_seconds,
	    st->tile_seconds > 0 && st->threads > 0 ? 100 * st->thread_seconds /
	    (st->threads * st->tile_seconds) : 0.0, 1e3 * (st->seconds -
	    st->tile_seconds));
}

/* ---- lazy illumination ---- */

/* the baked volume the plan reads, for messages */
static const char *
what(const vx_plan *plan)
{
	return plan->sh ? "SH transfer volume" : "irradiance volume";
}

typedef struct lazy_map {
	const vx_irrvol *v;
	uint8_t *need;            /* a byte a texel, i + n0 (j + n1 k) */
} lazy_map;

static void
lazy_mark(void *ctx, int64_t i, int64_t j, int64_t k)
{
	lazy_map *x = ctx;
	size_t t = (size_t)i + (size_t)x->v->dims[0] * ((size_t)j +
	    (size_t)x->v->dims[1] * (size_t)k);

	/* several threads may store 1 to the same byte */
	__atomic_store_n(&x->need[t], 1, __ATOMIC_RELAXED);
}

/* lazy_bake: make irr hold every texel that the lookups of this view
 * read, baked exactly as bake-irr would (the stream's bake is extended
 * when its settings are the scene's; else a new one at bake-irr's
 * defaults): a collecting pass over the view, then the missing texels
 * baked.  Prints what it spent with --stats. */
static void
lazy_bake(vx_irrvol *irr, int have, vx_scene *s, const vx_grid *g,
    const vx_macro *m, const vx_plan *plan, const vx_grid *const *tex,
    vx_raycast_opts *ro, int nthr, int stats)
{
	vx_gi gi;
	vx_bake_opts bo;
	vx_bake_stats bs;
	vx_raycast_stats rs;
	vx_image c;
	vx_err e = { 0, "" };
	lazy_map x;
	char settings[2048], key[17];
	size_t nt;
	uint64_t before = 0, after = 0;

	if (!plan->sh)
		tool_gi_setup(&gi, s, g, m);
	else if (vx_gi_setup(&gi, s, g, m, &e) != 0)
		tool_fail_err(&e);    /* a transfer needs no light */
	vx_bake_opts_init(&bo);
	if (have) {
		gi.seed = irr->seed;
		gi.high = irr->high;
		bo.offset = irr->offset;
		bo.scale = irr->scale;
		bo.samples = irr->samples;
	} else {
		uint32_t crc = vx_macro_grid_crc(g);

		gi.seed = 1;
		bo.samples = s->has_interreflection ? (uint32_t)s->samples : 64;
		if (vx_irr_setup_sh(irr, g, crc, 1, VX_IRR_ACCUM,
		    plan->sh ? s->sh_order : 0, plan->sh ?
		    vx_gi_sh_channels(&gi) : 3, &e) != 0)
			tool_fail_err(&e);
		vx_bake_sign(irr, &gi, &bo);
	}
	if (irr->store != VX_IRR_ACCUM)
		tool_fail(VX_EDATA, "--lazy: the stream's %s is final (%s): it "
		    "cannot take more texels", what(plan),
		    vx_enum_str(&vx_irr_store_enum, irr->store));
	vx_bake_settings(irr, &gi, &bo, settings, sizeof settings);
	vx_bake_key(settings, key);
	if (strcmp(key, irr->key) != 0)
		tool_fail(VX_EDATA, "--lazy: the stream's %s was baked with "
		    "other settings than this scene's (key %s, the scene gives "
		    "%s): bake anew with %s --fresh", what(plan), irr->key, key,
		    plan->sh ? "bake-sh" : "bake-irr");
	if (bo.samples == 0)
		bo.samples = 64;
	nt = (size_t)irr->dims[0] * (size_t)irr->dims[1] *
	    (size_t)irr->dims[2];
	x.v = irr;
	if ((x.need = calloc(nt, 1)) == NULL)
		tool_fail(VX_ENOMEM, "--lazy: out of memory for %zu texels", nt);
	/* the collecting pass: which texels this view reads */
	ro->irr = irr;
	ro->irr_need = lazy_mark;
	ro->irr_need_ctx = &x;
	vx_image_init(&c);
	if (vx_raycast_render(s, plan, g, m, tex, ro, &c, NULL, NULL, &rs,
	    &e) != 0)
		tool_fail_err(&e);
	vx_image_free(&c);
	ro->irr_need = NULL;
	ro->irr_need_ctx = NULL;
	/* want them, then bake those without samples */
	for (int64_t k = 0; k < irr->dims[2]; k++)
		for (int64_t j = 0; j < irr->dims[1]; j++)
			for (int64_t i = 0; i < irr->dims[0]; i++) {
				size_t t = (size_t)i + (size_t)irr->dims[0] *
				    ((size_t)j + (size_t)irr->dims[1] * (size_t)k);
				int64_t q;

				if (!x.need[t])
					continue;
				if ((q = vx_irr_want_texel(irr, i, j, k, &e)) < 0)
					tool_fail_err(&e);
				if (vx_irr_accp(irr, q)->count > 0 ||
				    (vx_irr_accp(irr, q)->flags &
				    (VX_TEXEL_FLAT | VX_TEXEL_NAN))) {
					x.need[t] = 0;    /* baked already */
					before++;
				} else
					after++;
			}
	memset(&bs, 0, sizeof bs);
	bo.topup = 1;
	bo.only = x.need;
	bo.threads = nthr;
	if (vx_bake_run(irr, &gi, g, &bo, &bs, &e) != 0)
		tool_fail_err(&e);
	free(x.need);
	if (stats)
		fprintf(stderr, "raycast: lazy: the view reads %llu texels: %llu "
		    "baked now (%llu paths, %.3f s), %llu there already\n",
		    (unsigned long long)(before + after),
		    (unsigned long long)after, (unsigned long long)bs.samples,
		    bs.bake_s, (unsigned long long)before);
}

/* sh_lighting: the SH lighting of order n into c (3 channels of n^2, vx_sh.h's
 * basis): the stream's SHLC chunk (from sh-rotate), else the sum of the
 * projections of the scene's environment and sky lights
 * (vx_shlight_from_scene); bands the lighting lacks are 0, bands beyond n
 * dropped */
static void
sh_lighting(vx_scene *s, const vx_stream *st, int n, double *c, int say)
{
	static vx_shlight sl;
	vx_err e = { 0, "" };
	long idx;
	int nn = n * n, found = 0;

	memset(c, 0, sizeof(double) * 3 * (size_t)nn);
	if (vx_shlight_from_stream(&sl, st, &idx, &e) != 0)
		tool_fail_err(&e);
	if (idx >= 0) {
		int m = sl.order < n ? sl.order : n, mm = sl.order * sl.order;

		if (sl.phase == VX_SHLIGHT_PHASE_NONE)
			vx_sh_flip_phase(sl.order, 3, sl.c);
		for (int k = 0; k < 3; k++)
			memcpy(c + k * nn, sl.c + k * mm, sizeof(double) *
			    (size_t)(m * m));
		if (say)
			fprintf(stderr, "raycast: SH lighting: the stream's (order "
			    "%d%s) for a transfer of order %d\n", sl.order,
			    sl.order < n ? ", higher bands 0" : "", n);
		return;
	}
	if (vx_env_scene_resolve(s, &e) != 0 ||
	    vx_shlight_from_scene(&sl, s, n, &found, NULL, &e) != 0)
		tool_fail_err(&e);
	if (found == 0)
		tool_fail(VX_EUSAGE, "illumination sh: no SH lighting: the "
		    "stream has no SHLC chunk (sh-rotate makes one) and the "
		    "scene no environment or sky light");
	memcpy(c, sl.c, sizeof(double) * 3 * (size_t)nn);
	if (say)
		fprintf(stderr, "raycast: SH lighting: %d environment or sky "
		    "light%s of the scene projected to order %d\n", found,
		    found == 1 ? "" : "s", n);
}

int
main(int argc, char **argv)
{
	static double shl[3 * VX_SHLIGHT_MAX_COEF];
	opts o;
	vx_stream st;
	vx_grid g;
	vx_macro m;
	vx_scene s;
	vx_plan plan;
	vx_raycast_opts ro;
	vx_raycast_stats rs;
	vx_irrvol irr;
	vx_gi pgi;
	vx_image color, depth, normal;
	const vx_grid *tex[VX_SCENE_MAX_SURFACES];
	vx_grid texg[VX_SCENE_MAX_SURFACES];
	vx_err e = { 0, "" };
	double lo[3], hi[3];
	long gi;
	int k, nthr, is_mesh = 0;
	vx_tetmesh mesh;
	vx_tetleaf lg;
	const char *want;

	tool_init("raycast", argc, argv);
	parse(&o, argc, argv);
	vx_stream_init(&st);
	tool_read_stream(&st, o.in);
	vx_scene_init(&s);
	load_scene(&s, &o, &st);
	if (o.spp > 0)
		s.pt_samples = o.spp;
	/* what to draw: the named (or first) volume or mesh */
	want = o.run.name ? o.run.name : (s.volume[0] ? s.volume : NULL);
	vx_grid_init(&g);
	vx_tetmesh_init(&mesh);
	vx_tetleaf_init(&lg);
	gi = vx_tetmesh_find_source(&st, want, &is_mesh);
	if (gi < 0 && want != NULL)
		tool_fail(VX_EDATA, "no volume or mesh named '%s' in the stream",
		    want);
	if (gi < 0)
		tool_fail(VX_EDATA, "no volume or mesh in the stream");
	if (is_mesh) {
		if (vx_tetmesh_from_chunk(&mesh, &st.chunk[gi], &e) != 0)
			tool_fail_err(&e);
		if (mesh.ntet == 0)
			tool_fail(VX_EDATA, "mesh '%s' has no tets", mesh.name);
	} else if (vx_grid_view_stream(&g, &st, want, &gi, &e) != 0)
		tool_fail_err(&e);
	vx_scene_plan_isosurface(&s, &plan);
	nthr = tool_threads(o.run.threads);
	if (o.run.explain) {
		tool_plan_print(&plan);
		if (is_mesh)
			fprintf(stderr, "raycast: %dx%d pixels, %d sample%s per "
			    "pixel, about %.0f rays; mesh '%s' (%zu tets): leaf "
			    "grid of tet lists, %s, linear field per tet, %d "
			    "thread%s\n", s.camera.w, s.camera.h, o.aa * o.aa,
			    o.aa > 1 ? "s" : "", plan.rays_per_pixel *
			    s.camera.w * s.camera.h * o.aa * o.aa, mesh.name,
			    mesh.ntet, o.flat ? "no macrocell levels" :
			    "hierarchical", nthr, nthr == 1 ? "" : "s");
		else
			fprintf(stderr, "raycast: %dx%d pixels, %d sample%s per "
			    "pixel, about %.0f rays; solver %s, %s, %d "
			    "thread%s\n", s.camera.w, s.camera.h, o.aa * o.aa,
			    o.aa > 1 ? "s" : "", plan.rays_per_pixel *
			    s.camera.w * s.camera.h * o.aa * o.aa,
			    vx_enum_str(&vx_cell_solver_enum, o.solver),
			    o.flat ?
			    "flat traversal" : o.nomask ?
			    "hierarchical traversal (no cell mask)" :
			    "hierarchical traversal with a cell mask (a bit "
			    "per cell of the macrocells bracketing the "
			    "isovalues, built as rays first enter them)", nthr,
			    nthr == 1 ? "" : "s");
		if (!is_mesh && !o.flat) {
			int bb = o.binblock > 0 ? o.binblock : VX_RAYCAST_BLOCK;

			if (o.nobin)
				fprintf(stderr, "raycast: primary rays walk from "
				    "the eye (--no-binning)\n");
			else if (o.nomask)
				fprintf(stderr, "raycast: primary rays walk the "
				    "level-1 macrocells bracketing an isovalue "
				    "that they enter (binned per 8x8 pixels), one "
				    "after the other, and nothing between them; a "
				    "ray that enters none is not walked\n");
			else
				fprintf(stderr, "raycast: primary rays walk the "
				    "boxes they enter (binned per 8x8 pixels) of "
				    "the leaves bracketing an isovalue in each "
				    "block of %dx%dx%d leaves, in the macrocells "
				    "whose cell mask bits are built (the centre "
				    "pixel of each 8x8 bin is drawn first, to "
				    "build those in sight; the other bracketing "
				    "macrocells whole), one after the other, and "
				    "nothing between them; a ray that enters none "
				    "is not walked\n", bb, bb, bb);
		}
	}
	if (plan.nsurface_on == 0)
		tool_fail(VX_EUSAGE, "no surface to draw: give --iso V or a "
		    "surface line in the scene");
	/* the hierarchy: from the stream, else built here; for a mesh, its
	 * leaf grid (--flat: the leaves alone, no levels above) */
	vx_macro_init(&m);
	if (is_mesh)
		tool_tetleaf_load(&lg, &st, &mesh, o.flat ? 0 :
		    VX_MACRO_DEFAULT_LEVELS, nthr, o.run.dry, o.run.dry);
	else if (!o.flat)
		tool_macro_load(&m, &st, &g, gi, nthr, o.run.dry);
	if (o.run.dry) {
		vx_tetleaf_free(&lg);
		vx_tetmesh_free(&mesh);
		vx_macro_free(&m);
		vx_grid_free(&g);
		vx_stream_free(&st);
		return tool_finish();
	}
	/* texture volumes named by the surfaces */
	for (k = 0; k < VX_SCENE_MAX_SURFACES; k++) {
		tex[k] = NULL;
		vx_grid_init(&texg[k]);
	}
	for (k = 0; k < s.nsurface; k++)
		if (plan.texture_on[k]) {
			if (vx_grid_view_stream(&texg[k], &st,
			    s.surface[k].m.texture, NULL, &e) != 0) {
				vx_err_push(&e, "surface %d texture", k + 1);
				tool_fail_err(&e);
			}
			tex[k] = &texg[k];
		}
	if (is_mesh)
		for (int a = 0; a < 3; a++) {
			lo[a] = mesh.bmin[a];
			hi[a] = mesh.bmax[a];
		}
	else
		vx_grid_box(&g, lo, hi);
	if (vx_camera_resolve(&s.camera, lo, hi, &e) != 0)
		tool_fail_err(&e);
	vx_raycast_opts_init(&ro);
	ro.nthreads = nthr;
	ro.solver = o.solver;
	ro.flat = o.flat;
	ro.aa = o.aa;
	ro.timing = o.run.stats;
	ro.no_cellmask = o.nomask;
	ro.no_binning = o.nobin;
	ro.bin_block = o.binblock;
	vx_irr_init(&irr);
	if (plan.irradiance) {
		const char *il = plan.sh ? "illumination sh" :
		    "illumination irradiance";
		long ii;

		if (is_mesh)
			tool_fail(VX_EUSAGE, "%s: %ss are baked for volumes, not "
			    "meshes", il, what(&plan));
		if ((plan.sh ? vx_irr_sh_from_stream : vx_irr_from_stream)(&irr,
		    &st, g.name, &ii, &e) != 0)
			tool_fail_err(&e);
		if (ii < 0 && !o.lazy)
			tool_fail(VX_EDATA, "%s: no %s of '%s' in the stream (bake "
			    "one with %s, or give --lazy)", il, what(&plan),
			    g.name, plan.sh ? "bake-sh" : "bake-irr");
		for (int a = 0; a < 3 && ii >= 0; a++)
			if (irr.vdims[a] != g.dims[a])
				tool_fail(VX_EDATA, "%s: the %s was baked for dims "
				    "%lld %lld %lld, not these", il, what(&plan),
				    (long long)irr.vdims[0],
				    (long long)irr.vdims[1],
				    (long long)irr.vdims[2]);
		ro.irr = &irr;
		ro.irr_interp = s.interp;
		if (o.lazy) {
			lazy_bake(&irr, ii >= 0, &s, &g, o.flat ? NULL : &m, &plan,
			    tex, &ro, nthr, o.run.stats);
			if (o.lazy_save != NULL) {
				vx_chunk c;

				memset(&c, 0, sizeof c);
				if (vx_irr_to_chunk(&irr, 0, &c, &e) != 0)
					tool_fail_err(&e);
				if (ii >= 0)
					vx_stream_replace(&st, (size_t)ii, &c);
				else if (vx_stream_append(&st, &c, &e) != 0)
					tool_fail_err(&e);
				tool_write_stream(&st, o.lazy_save);
			}
		}
		if (plan.sh) {
			sh_lighting(&s, &st, irr.sh_order, shl, o.run.stats ||
			    o.run.explain);
			ro.shl = shl;
		}
	} else if (o.lazy) {
		tool_fail(VX_EUSAGE, "--lazy: the scene's illumination is not "
		    "irradiance or sh (add --set \"illumination irradiance\")");
	}
	if (plan.pathtrace) {
		if (is_mesh)
			tool_fail(VX_EUSAGE, "illumination pathtrace: volumes "
			    "only, not meshes");
		tool_gi_setup(&pgi, &s, &g, o.flat ? NULL : &m);
		ro.gi = &pgi;
	}
	vx_image_init(&color);
	vx_image_init(&depth);
	vx_image_init(&normal);
	if (is_mesh) {
		if (vx_raycast_render_mesh(&s, &plan, &mesh, &lg, tex, &ro,
		    &color, (o.run.depth || o.run.hdr) ? &depth : NULL,
		    (o.run.normals || o.run.hdr) ? &normal : NULL, &rs,
		    &e) != 0)
			tool_fail_err(&e);
	} else if (vx_raycast_render(&s, &plan, &g, o.flat ? NULL : &m, tex,
	    &ro, &color, (o.run.depth || o.run.hdr) ? &depth : NULL,
	    (o.run.normals || o.run.hdr) ? &normal : NULL, &rs, &e) != 0)
		tool_fail_err(&e);
	if (o.run.stats)
		print_stats(&rs, is_mesh ? &lg.mc : o.flat ? NULL : &m,
		    s.camera.w, s.camera.h, nthr);
	{
		/* volumes, meshes and their hierarchies are consumed */
		static const char *const drawn[] = { VX_CHUNK_VOLUME,
		    VX_CHUNK_MACRO, VX_CHUNK_TETMESH, VX_CHUNK_TETLEAF, NULL };
		const vx_image *img[3] = { &color, &depth, &normal };

		tool_render_write(&o.run, &st, drawn, &s, img, NULL);
	}
	for (k = 0; k < VX_SCENE_MAX_SURFACES; k++)
		vx_grid_free(&texg[k]);
	vx_image_free(&color);
	vx_image_free(&depth);
	vx_image_free(&normal);
	vx_tetleaf_free(&lg);
	vx_tetmesh_free(&mesh);
	vx_irr_free(&irr);
	vx_macro_free(&m);
	vx_grid_free(&g);
	vx_stream_free(&st);
	return tool_finish();
}
