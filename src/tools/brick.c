/* brick.c: rewrite a volume's samples into Parker's two-level bricked order
 * (cache-line bricks inside page bricks), or back to linear order; every
 * other chunk passes through unchanged and in order, and so do the volume's
 * header keys that this version does not know. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tool.h"
#include "vx_grid.h"
#include "vx_par.h"
#include "vx_stream.h"

static const char usage[] =
    "brick [--bricks AxBxC[,DxExF...] | --linear] [--name NAME] [--stats] "
    "[-v] [-o OUT] [IN|-]";

typedef struct opts {
	const char *in, *bricks;
	int linear;
	tool_run_opts run;       /* -o, --name, --stats */
} opts;

static void
parse_args(opts *o, int argc, char **argv)
{
	static const struct option lo[] = {
		{ "bricks", required_argument, NULL, 'b' },
		{ "linear", no_argument, NULL, 'l' },
		{ "name", required_argument, NULL, TOOL_O_NAME },
		{ "stats", no_argument, NULL, TOOL_O_STATS },
		{ "verbose", no_argument, NULL, TOOL_O_STATS },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 },
	};
	int ch;

	memset(o, 0, sizeof *o);
	tool_run_opts_init(&o->run);
	while ((ch = getopt_long(argc, argv, ":vo:", lo, NULL)) != -1) {
		if (ch == 'b')
			o->bricks = optarg;
		else if (ch == 'l')
			o->linear = 1;
		else if (ch == 'v')
			o->run.stats = 1;
		else if (!tool_run_opt(&o->run, ch, optarg))
			tool_opt_other(ch, usage, argv);
	}
	if (o->linear && o->bricks)
		tool_usage_fail(usage, "--bricks and --linear exclude each "
		    "other");
	o->in = tool_opt_input(argc, argv, usage);
}

/* bricks_spec: "--bricks AxBxC,DxExF" as the layout string "bricked AxBxC
 * DxExF"; exits with a usage error unless each edge is a power of two in
 * 1..1024 and there are 1..VX_LAYOUT_MAXLEV levels. */
static void
bricks_spec(const char *arg, char *spec, size_t n)
{
	const char *p = arg;
	size_t k = (size_t)snprintf(spec, n, "bricked");
	int lev = 0;

	for (;;) {
		int b[3], used;

		if (lev == VX_LAYOUT_MAXLEV || *p < '0' || *p > '9' ||
		    sscanf(p, "%5dx%5dx%5d%n", &b[0], &b[1], &b[2], &used) != 3)
			tool_fail(VX_EUSAGE, "--bricks: '%s': expected 1 to %d "
			    "sizes AxBxC separated by commas", arg,
			    VX_LAYOUT_MAXLEV);
		for (int a = 0; a < 3; a++)
			if (b[a] < 1 || b[a] > 1024 || (b[a] & (b[a] - 1)))
				tool_fail(VX_EUSAGE, "--bricks: '%s': %d is not a "
				    "power of two in 1..1024", arg, b[a]);
		k += (size_t)snprintf(spec + k, n - k, " %dx%dx%d", b[0], b[1],
		    b[2]);
		p += used;
		lev++;
		if (*p == '\0')
			return;
		if (*p++ != ',')
			tool_fail(VX_EUSAGE, "--bricks: '%s': expected 1 to %d "
			    "sizes AxBxC separated by commas", arg,
			    VX_LAYOUT_MAXLEV);
	}
}

/* input_zlevel: keep the input's encoding: zlib stays zlib (level 6). */
static int
input_zlevel(const vx_hdr *h)
{
	const char *enc = vx_hdr_get(h, "encoding");

	return enc != NULL && strcmp(enc, "zlib") == 0 ? 6 : 0;
}

int
main(int argc, char **argv)
{
	char spec[128], was[128];
	vx_stream s;
	vx_grid g, b;
	vx_chunk c;
	vx_hdr h;
	const unsigned char *body;
	size_t bodylen;
	vx_err e = { 0, "" };
	long idx;
	opts o;
	double t0;

	tool_init("brick", argc, argv);
	parse_args(&o, argc, argv);
	vx_stream_init(&s);
	tool_read_stream(&s, o.in);
	if (vx_grid_view_stream(&g, &s, o.run.name, &idx, &e) != 0)
		tool_fail_err(&e);
	if (o.linear)
		snprintf(spec, sizeof spec, "linear");
	else if (o.bricks)
		bricks_spec(o.bricks, spec, sizeof spec);
	else {
		int br[2][3];

		vx_layout_default_bricks(g.type, br);
		snprintf(spec, sizeof spec, "bricked %dx%dx%d %dx%dx%d",
		    br[0][0], br[0][1], br[0][2], br[1][0], br[1][1], br[1][2]);
	}
	t0 = vx_par_seconds();
	if (vx_grid_relayout(&b, &g, spec, &e) != 0) {
		vx_err_push(&e, "%s", g.name);
		tool_fail_err(&e);
	}
	if (o.run.stats) {
		double real = (double)g.dims[0] * (double)g.dims[1] *
		    (double)g.dims[2];

		vx_layout_string(&g.lay, was, sizeof was);
		fprintf(stderr, "%s: %s: %lldx%lldx%lld %s: %s -> %s: "
		    "%lldx%lldx%lld padded, %zu samples for %.0f (padding "
		    "%.2f %%), %.3f s\n", tool_name, g.name,
		    (long long)g.dims[0], (long long)g.dims[1],
		    (long long)g.dims[2], vx_enum_str(&vx_type_enum, g.type),
		    was, spec,
		    (long long)b.lay.pdims[0], (long long)b.lay.pdims[1],
		    (long long)b.lay.pdims[2], b.nsample, real,
		    100.0 * ((double)b.nsample - real) / real, vx_par_seconds() - t0);
	}
	/* the volume is the same, only its layout changes: keys this version
	 * does not know pass through (formats/stream.md 9.1) */
	vx_hdr_init(&h);
	if (vx_payload_parse(&s.chunk[idx], &h, &body, &bodylen, &e) != 0)
		tool_fail_err(&e);
	memset(&c, 0, sizeof c);
	vx_grid_free(&g);   /* a view: nothing freed, done with it */
	/* the new layout's memory becomes the chunk (b is freed) */
	if (vx_grid_to_chunk_take(&b, input_zlevel(&h), &h, &c, &e) != 0)
		tool_fail_err(&e);
	vx_hdr_free(&h);
	vx_stream_replace(&s, (size_t)idx, &c);
	tool_write_stream(&s, o.run.out);
	vx_stream_free(&s);
	return tool_finish();
}
