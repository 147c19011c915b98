/* vwrite.c: export a volume of a voxlux stream, or an irradiance volume
 * (--chunk IRRV), to a NRRD file that Teem, ParaView and 3D Slicer read. */
#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tool.h"
#include "vx_export.h"
#include "vx_grid.h"
#include "vx_irrvol.h"
#include "vx_stream.h"

static const char usage[] =
    "vwrite [-o FILE.nrrd] [--gzip] [--name NAME] [--chunk VOLM|IRRV]\n"
    "    [--flags FILE.nrrd] [--flags-type u8|u32] [STREAM|-]";

typedef struct opts {
	const char *out;
	int gzip;
	const char *name;
	const char *chunk;
	const char *in;
	const char *flags;      /* IRRV: the texels' flags to this file */
	int flag_bytes;         /* 1 or 4 */
} opts;

static void
parse_args(opts *o, int argc, char **argv)
{
	static const struct option lo[] = {
		{ "output", required_argument, NULL, 'o' },
		{ "gzip", no_argument, NULL, 'z' },
		{ "name", required_argument, NULL, 'n' },
		{ "chunk", required_argument, NULL, 'c' },
		{ "flags", required_argument, NULL, 'f' },
		{ "flags-type", required_argument, NULL, 't' },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 },
	};
	int ch;

	memset(o, 0, sizeof *o);
	o->out = "-";
	o->chunk = VX_CHUNK_VOLUME;
	o->flag_bytes = 1;
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
		case 'f':
			o->flags = optarg;
			break;
		case 't':
			if (strcmp(optarg, "u8") == 0)
				o->flag_bytes = 1;
			else if (strcmp(optarg, "u32") == 0)
				o->flag_bytes = 4;
			else
				tool_usage_fail(usage, "--flags-type: u8 or u32, "
				    "not '%s'", optarg);
			break;
		default:
			tool_opt_other(ch, usage, argv);
		}
	}
	o->in = tool_opt_input(argc, argv, usage);
	/* which chunk kinds can be exported: volumes and irradiance
	 * volumes */
	if (strlen(o->chunk) != 4 || !vx_chunk_type_valid(o->chunk))
		tool_usage_fail(usage, "--chunk %s: not a chunk type", o->chunk);
	if (strcmp(o->chunk, VX_CHUNK_VOLUME) != 0 &&
	    strcmp(o->chunk, VX_CHUNK_IRRAD) != 0 &&
	    strcmp(o->chunk, VX_CHUNK_SHXFER) != 0)
		tool_fail(VX_EUSAGE, "--chunk %s: only %s, %s and %s chunks can "
		    "be exported", o->chunk, VX_CHUNK_VOLUME, VX_CHUNK_IRRAD,
		    VX_CHUNK_SHXFER);
	if (o->flags != NULL && strcmp(o->chunk, VX_CHUNK_IRRAD) != 0 &&
	    strcmp(o->chunk, VX_CHUNK_SHXFER) != 0)
		tool_usage_fail(usage, "--flags: only with --chunk %s or %s",
		    VX_CHUNK_IRRAD, VX_CHUNK_SHXFER);
	if (o->flags != NULL && (strcmp(o->flags, "-") == 0 ||
	    strcmp(o->flags, o->out) == 0))
		tool_usage_fail(usage, "--flags %s: a file of its own",
		    o->flags);
	if (strcmp(o->out, "-") == 0 && isatty(STDOUT_FILENO))
		tool_fail(VX_EUSAGE, "standard output is a terminal: give -o "
		    "FILE.nrrd or redirect it");
}

static const char *
inname(const opts *o)
{
	return strcmp(o->in, "-") ? o->in : "<stdin>";
}

/* irr_key_kept: an IRRV header key that tells how the texels were baked
 * (the body's layout keys are the NRRD's own business) */
static int
irr_key_kept(const char *k)
{
	static const char *const drop[] = { "lattice-dims", "brick", "bricks",
	    "encoding", "pad" };

	for (size_t i = 0; i < sizeof drop / sizeof *drop; i++)
		if (strcmp(k, drop[i]) == 0)
			return 0;
	return 1;
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
	vx_irrvol iv;
	tool_out out, fout;
	size_t hn, n = 0, i;
	const char *h;
	opts o;
	long idx;
	int irr;

	tool_init("vwrite", argc, argv);
	parse_args(&o, argc, argv);
	irr = strcmp(o.chunk, VX_CHUNK_IRRAD) == 0 ? 1 :
	    strcmp(o.chunk, VX_CHUNK_SHXFER) == 0 ? 2 : 0;
	vx_stream_init(&s);
	vx_irr_init(&iv);
	tool_read_stream(&s, o.in);
	if (irr) {
		/* the irradiance volume of volume --name (or the first); its
		 * volume gives the lattice's place in the world */
		if ((irr == 2 ? vx_irr_sh_from_stream : vx_irr_from_stream)(&iv,
		    &s, o.name, &idx, &e) != 0) {
			vx_err_push(&e, "%s", inname(&o));
			tool_fail_err(&e);
		}
		if (idx < 0)
			tool_fail(VX_EDATA, "%s: no %s%s%s%s", inname(&o),
			    irr == 2 ? "SH transfer volume" :
			    "irradiance volume", o.name ? " of '" : "",
			    o.name ? o.name : "", o.name ? "'" : "");
		if (vx_grid_view_stream(&g, &s, iv.volume, NULL, &e) != 0) {
			vx_err_push(&e, "%s: the volume of the irradiance "
			    "volume (its world frame)", inname(&o));
			tool_fail_err(&e);
		}
	} else if (vx_grid_view_stream(&g, &s, o.name, &idx, &e) != 0) {
		vx_err_push(&e, "%s", inname(&o));
		tool_fail_err(&e);
	}
	/* the chunk's header keys the NRRD header does not say itself go
	 * along as key:=value: a volume's units and notes (formats/stream.md
	 * 9.1); an irradiance volume's bake (store, samples, key, settings) */
	{
		const unsigned char *body;
		size_t bl;

		vx_hdr_init(&vh);
		vx_hdr_init(&kv);
		if (vx_payload_parse(&s.chunk[idx], &vh, &body, &bl, &e) != 0)
			tool_fail_err(&e);
		for (i = 0; i < vh.n; i++)
			if ((irr ? irr_key_kept(vh.key[i]) :
			    !vx_grid_key_known(vh.key[i])) &&
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
	if ((irr ? vx_export_nrrd_irr(&iv, &g, out.f, &no, &e) :
	    vx_export_nrrd_opts(&g, out.f, &no, &e)) != 0) {
		tool_out_abort(&out);
		vx_err_push(&e, "%s", out.path);
		tool_fail_err(&e);
	}
	if (o.flags != NULL) {
		tool_out_open(&fout, o.flags);
		if (vx_export_nrrd_irr_flags(&iv, &g, o.flag_bytes, fout.f, &no,
		    &e) != 0) {
			tool_out_abort(&fout);
			tool_out_abort(&out);
			vx_err_push(&e, "%s", fout.path);
			tool_fail_err(&e);
		}
		tool_out_close(&fout);
	}
	tool_out_close(&out);
	free(lines);
	free(hist);
	vx_hdr_free(&kv);
	vx_hdr_free(&vh);
	vx_irr_free(&iv);
	vx_grid_free(&g);
	vx_stream_free(&s);
	return tool_finish();
}
