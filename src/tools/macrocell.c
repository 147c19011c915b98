/* macrocell.c: build the multilevel min/max hierarchy over a volume's cells
 * and store it in the stream as an MCEL chunk (added after the volume, or
 * replacing the one already there for that volume); for a tet mesh, build
 * its leaf grid of tet lists with the levels above it, stored as a TLEF
 * chunk the same way. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tool.h"
#include "vx_grid.h"
#include "vx_macro.h"
#include "vx_macroio.h"
#include "vx_par.h"
#include "vx_stream.h"
#include "vx_tetimport.h"
#include "vx_tetleaf.h"

static const char usage[] =
    "macrocell [--levels N] [--sizes AxBxC[,DxExF...]] [--name NAME] "
    "[--density D] [--bbox] [-j N] [--stats] [-o OUT] [IN|-]";

typedef struct opts {
	const char *in, *sizes;
	long levels;     /* -1: not given */
	long jobs;
	double density;  /* meshes: leaves per tet (0: not given) */
	int bbox;        /* meshes: bounding-box lists */
	tool_run_opts run;       /* -o, --name, --stats */
} opts;

static void
parse_args(opts *o, int argc, char **argv)
{
	static const struct option lo[] = {
		{ "levels", required_argument, NULL, 'L' },
		{ "sizes", required_argument, NULL, 'S' },
		{ "name", required_argument, NULL, TOOL_O_NAME },
		{ "stats", no_argument, NULL, TOOL_O_STATS },
		{ "density", required_argument, NULL, 'D' },
		{ "bbox", no_argument, NULL, 'B' },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 },
	};
	int ch;

	memset(o, 0, sizeof *o);
	tool_run_opts_init(&o->run);
	o->levels = -1;
	while ((ch = getopt_long(argc, argv, ":j:o:", lo, NULL)) != -1) {
		switch (ch) {
		case 'L':
			o->levels = tool_parse_long("--levels", optarg, 0,
			    VX_MACRO_MAXLEV);
			break;
		case 'S':
			o->sizes = optarg;
			break;
		case 'D':
			o->density = tool_parse_double("--density", optarg,
			    1e-3, 64);
			break;
		case 'B':
			o->bbox = 1;
			break;
		case 'j':
			o->jobs = tool_parse_long("-j", optarg, 1, 1024);
			break;
		default:
			if (!tool_run_opt(&o->run, ch, optarg))
				tool_opt_other(ch, usage, argv);
		}
	}
	o->in = tool_opt_input(argc, argv, usage);
}

/* find_owned: the index of the MCEL (TLEF) chunk of volume (mesh) `name`,
 * or -1; a chunk of the type that nobody can place is bad input: one line
 * and exit 65 (keeping it would leave a stream the renderers refuse;
 * dropping it would lose data). */
static long
find_owned(const vx_stream *s, const char *type, const char *name)
{
	vx_err e = { 0, "" };
	long i;

	if (vx_macro_find_owned(s, type, name, &i, &e) != 0)
		tool_fail_err(&e);
	return i;
}

static void
print_stats(const vx_macro *m, const vx_grid *g, double tbuild, int nt)
{
	double data = (double)g->dims[0] * (double)g->dims[1] *
	    (double)g->dims[2] * (double)vx_type_size(g->type);
	size_t bytes = vx_macro_bytes(m);
	int l;

	fprintf(stderr, "%s: %s: %lldx%lldx%lld %s, %lldx%lldx%lld cells, "
	    "%d levels", tool_name, g->name, (long long)g->dims[0],
	    (long long)g->dims[1], (long long)g->dims[2],
	    vx_enum_str(&vx_type_enum, g->type), (long long)m->dims[0][0],
	    (long long)m->dims[0][1], (long long)m->dims[0][2], m->nlev);
	for (l = 1; l <= m->nlev; l++)
		fprintf(stderr, "%s %dx%dx%d", l == 1 ? ":" : ",", m->size[l][0],
		    m->size[l][1], m->size[l][2]);
	fprintf(stderr, "\n");
	for (l = 1; l <= m->nlev; l++) {
		double n = (double)m->dims[l][0] * (double)m->dims[l][1] *
		    (double)m->dims[l][2];

		fprintf(stderr, "%s:   level %d: %lldx%lldx%lld macrocells of "
		    "%lldx%lldx%lld cells, %.0f bytes (%.4f %% of the data)\n",
		    tool_name, l, (long long)m->dims[l][0],
		    (long long)m->dims[l][1], (long long)m->dims[l][2],
		    (long long)(m->width[l][0] < m->dims[0][0] ?
		    m->width[l][0] : m->dims[0][0]),
		    (long long)(m->width[l][1] < m->dims[0][1] ?
		    m->width[l][1] : m->dims[0][1]),
		    (long long)(m->width[l][2] < m->dims[0][2] ?
		    m->width[l][2] : m->dims[0][2]), 8 * n,
		    data > 0 ? 800 * n / data : 0.0);
	}
	if (m->root[0] <= m->root[1])
		fprintf(stderr, "%s:   root: [%.9g, %.9g]\n", tool_name,
		    (double)m->root[0], (double)m->root[1]);
	else
		fprintf(stderr, "%s:   root: empty (no finite sample)\n",
		    tool_name);
	fprintf(stderr, "%s: memory %zu bytes = %.3f %% of the data (%.0f "
	    "bytes); build %.3f s with %d threads\n", tool_name, bytes,
	    data > 0 ? 100.0 * (double)bytes / data : 0.0, data, tbuild, nt);
}

static void
print_mesh_stats(const vx_tetleaf *lg, const vx_tetmesh *m, double density,
    int bbox, double tbuild, int nt)
{
	const vx_macro *mc = &lg->mc;
	double ntet = m->ntet > 0 ? (double)m->ntet : 1;
	size_t nidx = lg->off[lg->nleaf], bytes = vx_tetleaf_bytes(lg);
	size_t mbytes = m->npoint * (3 * sizeof(double) + sizeof(float)) +
	    m->ntet * 4 * sizeof(uint32_t);
	int l;

	fprintf(stderr, "%s: %s: %zu tets, %zu points; leaf grid %lldx%lldx%lld"
	    " = %zu leaves (%.2f per tet, density %g), %s lists\n", tool_name,
	    m->name, m->ntet, m->npoint, (long long)lg->dims[0],
	    (long long)lg->dims[1], (long long)lg->dims[2], lg->nleaf,
	    (double)lg->nleaf / ntet, density, bbox ? "bounding-box" : "exact");
	fprintf(stderr, "%s:   lists: %zu entries (%.2f per tet, %.2f per "
	    "leaf)\n", tool_name, nidx, (double)nidx / ntet,
	    lg->nleaf ? (double)nidx / (double)lg->nleaf : 0.0);
	for (l = 1; l <= mc->nlev; l++)
		fprintf(stderr, "%s:   level %d: %lldx%lldx%lld macrocells of "
		    "%dx%dx%d below\n", tool_name, l, (long long)mc->dims[l][0],
		    (long long)mc->dims[l][1], (long long)mc->dims[l][2],
		    mc->size[l][0], mc->size[l][1], mc->size[l][2]);
	if (mc->root[0] <= mc->root[1])
		fprintf(stderr, "%s:   root: [%.9g, %.9g]\n", tool_name,
		    (double)mc->root[0], (double)mc->root[1]);
	fprintf(stderr, "%s: memory %zu bytes = %.1f B/tet (offsets %.1f, "
	    "lists %.1f, min/max %.1f; the mesh itself %.1f B/tet); build "
	    "%.3f s = %.2f us/tet with %d thread%s\n", tool_name, bytes,
	    (double)bytes / ntet, 4.0 * (double)(lg->nleaf + 1) / ntet,
	    4.0 * (double)nidx / ntet, (double)vx_macro_bytes(mc) / ntet,
	    (double)mbytes / ntet, tbuild, 1e6 * tbuild / ntet, nt,
	    nt == 1 ? "" : "s");
}

/* mesh_main: the leaf grid of the mesh in chunk idx, into the stream. */
static void
mesh_main(vx_stream *s, long idx, const opts *o, int nlev,
    int sizes[][3])
{
	vx_tetmesh m;
	vx_tetleaf lg;
	vx_chunk c;
	vx_err e = { 0, "" };
	double t0, density = o->density > 0 ? o->density : 1;
	long old;
	int nt = tool_threads(o->jobs);

	if (vx_tetmesh_from_chunk(&m, &s->chunk[idx], &e) != 0)
		tool_fail_err(&e);
	if (o->sizes == NULL && nlev > 0)
		vx_macro_default_sizes(VX_F32, nlev, sizes);
	t0 = vx_par_seconds();
	if (vx_tetleaf_build_levels(&lg, &m, density, o->bbox ?
	    VX_TETLEAF_BBOX : 0, nlev, (const int (*)[3])sizes, nt, &e) != 0) {
		vx_err_push(&e, "%s", m.name);
		tool_fail_err(&e);
	}
	if (o->run.stats)
		print_mesh_stats(&lg, &m, density, o->bbox, vx_par_seconds() - t0, nt);
	memset(&c, 0, sizeof c);
	if (vx_tetleaf_to_chunk(&lg, &m, 0, &c, &e) != 0)
		tool_fail_err(&e);
	if ((old = find_owned(s, VX_CHUNK_TETLEAF, m.name)) >= 0)
		vx_stream_replace(s, (size_t)old, &c);
	else if (vx_stream_insert(s, (size_t)idx + 1, &c, &e) != 0)
		tool_fail_err(&e);
	vx_tetleaf_free(&lg);
	vx_tetmesh_free(&m);
}

int
main(int argc, char **argv)
{
	int sizes[VX_MACRO_MAXLEV][3], nlev, nt;
	vx_stream s;
	vx_grid g;
	vx_macro m;
	vx_chunk c;
	vx_err e = { 0, "" };
	long idx, old;
	double t0;
	opts o;

	tool_init("macrocell", argc, argv);
	parse_args(&o, argc, argv);
	if (o.sizes != NULL) {
		if ((nlev = vx_macro_parse_sizes(o.sizes, sizes, &e)) < 0)
			tool_usage_fail(usage, "--sizes: %s", e.msg);
		if (o.levels >= 0 && o.levels != nlev)
			tool_usage_fail(usage, "--levels %ld but --sizes gives %d "
			    "levels", o.levels, nlev);
	} else
		nlev = o.levels >= 0 ? (int)o.levels : VX_MACRO_DEFAULT_LEVELS;
	vx_stream_init(&s);
	tool_read_stream(&s, o.in);
	{
		int is_mesh = 0;
		long src = vx_tetmesh_find_source(&s, o.run.name, &is_mesh);

		if (src >= 0 && is_mesh) {
			mesh_main(&s, src, &o, nlev, sizes);
			tool_write_stream(&s, o.run.out);
			vx_stream_free(&s);
			return tool_finish();
		}
		if (src < 0 && o.run.name != NULL)
			tool_fail(VX_EDATA, "no volume or mesh named '%s' in the "
			    "stream", o.run.name);
	}
	if (o.density > 0 || o.bbox)
		tool_usage_fail(usage, "--density and --bbox apply to tet "
		    "meshes");
	if (vx_grid_view_stream(&g, &s, o.run.name, &idx, &e) != 0)
		tool_fail_err(&e);
	if (o.sizes == NULL && nlev > 0)
		vx_macro_default_sizes(g.type, nlev, sizes);
	nt = tool_threads(o.jobs);
	t0 = vx_par_seconds();
	if (vx_macro_build(&m, &g, nlev, (const int (*)[3])sizes, nt, &e) != 0) {
		vx_err_push(&e, "%s", g.name);
		tool_fail_err(&e);
	}
	if (o.run.stats)
		print_stats(&m, &g, vx_par_seconds() - t0, nt);
	/* the volume's chunk goes out as it came in: its CRC lets a renderer
	 * skip the pass over the samples that proves the cells match */
	m.vchunk_crc = vx_chunk_crc_of(&s.chunk[idx]);
	m.has_vchunk_crc = 1;
	memset(&c, 0, sizeof c);
	if (vx_macro_to_chunk(&m, 0, &c, &e) != 0)
		tool_fail_err(&e);
	if ((old = find_owned(&s, VX_CHUNK_MACRO, g.name)) >= 0)
		vx_stream_replace(&s, (size_t)old, &c);
	else if (vx_stream_insert(&s, (size_t)idx + 1, &c, &e) != 0)
		tool_fail_err(&e);
	vx_macro_free(&m);
	vx_grid_free(&g);
	tool_write_stream(&s, o.run.out);
	vx_stream_free(&s);
	return tool_finish();
}
