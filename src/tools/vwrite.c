/* vwrite.c: export a volume of a voxlux stream to a NRRD file that Teem,
 * ParaView and 3D Slicer read. */
#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tool.h"
#include "vx_export.h"
#include "vx_grid.h"
#include "vx_stream.h"

static const char usage[] =
    "vwrite [-o FILE.nrrd] [--gzip] [--name NAME] [--chunk TYPE] [STREAM|-]";

typedef struct opts {
	const char *out;
	int gzip;
	const char *name;
	const char *chunk;
	const char *in;
} opts;

static void
parse_args(opts *o, int argc, char **argv)
{
	static const struct option lo[] = {
		{ "output", required_argument, NULL, 'o' },
		{ "gzip", no_argument, NULL, 'z' },
		{ "name", required_argument, NULL, 'n' },
		{ "chunk", required_argument, NULL, 'c' },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 },
	};
	int ch;

	memset(o, 0, sizeof *o);
	o->out = "-";
	o->chunk = VX_CHUNK_VOLUME;
	while ((ch = getopt_long(argc, argv, ":o:", lo, NULL)) != -1) {
		switch (ch) {
		case 'o':
			o->out = optarg;
			break;
		case 'z':
			o->gzip = 1;
			break;
		case 'n':
			o->name = optarg;
			break;
		case 'c':
			o->chunk = optarg;
			break;
		default:
			tool_opt_other(ch, usage, argv);
		}
	}
	o->in = tool_input(argc, argv, usage);
	/* Which chunk kinds can be exported.  The irradiance and SH volumes
	 * will be added here as their modules land. */
	if (strlen(o->chunk) != 4 || !vx_chunk_type_valid(o->chunk))
		tool_usage_fail(usage, "--chunk %s: not a chunk type", o->chunk);
	if (strcmp(o->chunk, VX_CHUNK_VOLUME) != 0)
		tool_fail(VX_EUSAGE, "--chunk %s: only %s chunks can be exported "
		    "so far", o->chunk, VX_CHUNK_VOLUME);
	if (strcmp(o->out, "-") == 0 && isatty(STDOUT_FILENO))
		tool_fail(VX_EUSAGE, "standard output is a terminal: give -o "
		    "FILE.nrrd or redirect it");
}

int
main(int argc, char **argv)
{
	vx_err e = { 0, "" };
	const char **lines = NULL;
	char *hist = NULL;
	vx_nrrd_opts no;
	vx_stream s;
	vx_grid g;
	vx_hdr vh, kv;
	tool_out out;
	size_t hn, n = 0, i;
	const char *h;
	opts o;
	long idx;

	tool_init("vwrite", argc, argv);
	parse_args(&o, argc, argv);
	vx_stream_init(&s);
	tool_read_stream(&s, o.in);
	if (vx_grid_view_stream(&g, &s, o.name, &idx, &e) != 0) {
		vx_err_push(&e, "%s", strcmp(o.in, "-") ? o.in : "<stdin>");
		tool_fail_err(&e);
	}
	/* the volume's header keys the VOLM writer does not make itself
	 * (units, notes: formats/stream.md 9.1) go along as key:=value */
	{
		const unsigned char *body;
		size_t bl;

		vx_hdr_init(&vh);
		vx_hdr_init(&kv);
		if (vx_payload_parse(&s.chunk[idx], &vh, &body, &bl, &e) != 0)
			tool_fail_err(&e);
		for (i = 0; i < vh.n; i++)
			if (!vx_grid_key_known(vh.key[i]) &&
			    vx_hdr_set_str(&kv, vh.key[i], vh.val[i], &e) != 0)
				tool_fail_err(&e);
	}
	/* comments: the stream's history and this run, one line each */
	h = vx_stream_history(&s, &hn);
	if ((hist = malloc(hn + 1)) == NULL ||
	    (lines = calloc(hn + 2, sizeof *lines)) == NULL)
		tool_fail(VX_ENOMEM, "out of memory");
	if (hn > 0)
		memcpy(hist, h, hn);
	hist[hn] = '\0';
	for (i = 0; i < hn; i++)
		if (i == 0 || hist[i - 1] == '\0') {
			lines[n++] = hist + i;
			if ((h = memchr(hist + i, '\n', hn - i)) != NULL)
				hist[h - hist] = '\0';
		}
	lines[n++] = tool_history_line();
	memset(&no, 0, sizeof no);
	no.gzip = o.gzip;
	no.comments = lines;
	no.ncomments = n;
	no.keys = &kv;
	tool_out_open(&out, o.out);
	if (vx_export_nrrd_opts(&g, out.f, &no, &e) != 0) {
		tool_out_abort(&out);
		vx_err_push(&e, "%s", out.path);
		tool_fail_err(&e);
	}
	tool_out_close(&out);
	free(lines);
	free(hist);
	vx_hdr_free(&kv);
	vx_hdr_free(&vh);
	vx_grid_free(&g);
	vx_stream_free(&s);
	return tool_finish();
}
