/* macrocell.c: build the multilevel min/max hierarchy over a volume's cells
 * and store it in the stream as an MCEL chunk (added after the volume, or
 * replacing the one already there for that volume). */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tool.h"
#include "vx_grid.h"
#include "vx_macro.h"
#include "vx_stream.h"

static const char usage[] =
    "macrocell [--levels N] [--sizes AxBxC[,DxExF...]] [--name NAME] "
    "[-j N] [--stats] [-o OUT] [IN|-]";

typedef struct opts {
	const char *in, *out, *name, *sizes;
	long levels;     /* -1: not given */
	long jobs;
	int stats;
} opts;

static void
parse_args(opts *o, int argc, char **argv)
{
	static const struct option lo[] = {
		{ "levels", required_argument, NULL, 'L' },
		{ "sizes", required_argument, NULL, 'S' },
		{ "name", required_argument, NULL, 'n' },
		{ "stats", no_argument, NULL, 's' },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 },
	};
	int ch;

	memset(o, 0, sizeof *o);
	o->in = "-";
	o->out = "-";
	o->levels = -1;
	opterr = 0;
	while ((ch = getopt_long(argc, argv, ":j:o:", lo, NULL)) != -1) {
		switch (ch) {
		case 'L':
			o->levels = tool_parse_long("--levels", optarg, 0,
			    VX_MACRO_MAXLEV);
			break;
		case 'S':
			o->sizes = optarg;
			break;
		case 'n':
			o->name = optarg;
			break;
		case 's':
			o->stats = 1;
			break;
		case 'j':
			o->jobs = tool_parse_long("-j", optarg, 1, 1024);
			break;
		case 'o':
			o->out = optarg;
			break;
		case 'h':
			printf("usage: %s\n", usage);
			exit(tool_finish());
		case ':':
			tool_usage_fail(usage, "%s needs a value", argv[optind - 1]);
		default:
			tool_usage_fail(usage, "unknown option '%s'",
			    argv[optind - 1]);
		}
	}
	if (argc - optind > 1)
		tool_usage_fail(usage, "at most one input");
	if (argc - optind == 1)
		o->in = argv[optind];
}

/* find_mcel: index of the MCEL chunk that belongs to volume `name`, or -1
 * (a chunk whose header cannot be read belongs to nobody). */
static long
find_mcel(const vx_stream *s, const char *name)
{
	long i = -1;

	while ((i = vx_stream_find(s, VX_CHUNK_MACRO, (size_t)(i + 1))) >= 0) {
		const unsigned char *body;
		const char *v;
		size_t n;
		vx_hdr h;
		int mine;

		vx_hdr_init(&h);
		mine = vx_payload_parse(&s->chunk[i], &h, &body, &n, NULL) == 0 &&
		    (v = vx_hdr_get(&h, "volume")) != NULL && strcmp(v, name) == 0;
		vx_hdr_free(&h);
		if (mine)
			return i;
	}
	return -1;
}

static double
now(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
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
	    vx_type_name(g->type), (long long)m->dims[0][0],
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
	if (vx_grid_from_stream(&g, &s, o.name, &idx, &e) != 0)
		tool_fail_err(&e);
	if (o.sizes == NULL && nlev > 0)
		vx_macro_default_sizes(g.type, nlev, sizes);
	nt = tool_threads(o.jobs);
	t0 = now();
	if (vx_macro_build(&m, &g, nlev, (const int (*)[3])sizes, nt, &e) != 0) {
		vx_err_push(&e, "%s", g.name);
		tool_fail_err(&e);
	}
	if (o.stats)
		print_stats(&m, &g, now() - t0, nt);
	memset(&c, 0, sizeof c);
	if (vx_macro_to_chunk(&m, 0, &c, &e) != 0)
		tool_fail_err(&e);
	if ((old = find_mcel(&s, g.name)) >= 0)
		vx_stream_replace(&s, (size_t)old, &c);
	else if (vx_stream_insert(&s, (size_t)idx + 1, &c, &e) != 0)
		tool_fail_err(&e);
	vx_macro_free(&m);
	vx_grid_free(&g);
	tool_write_stream(&s, o.out);
	vx_stream_free(&s);
	return tool_finish();
}
