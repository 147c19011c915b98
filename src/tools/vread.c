/* vread.c: import a volume (raw, NRRD, NIfTI-1, VTK legacy) or a tet mesh
 * (VTK legacy unstructured grid, gmsh), or make a synthetic volume, and
 * write it as a voxlux stream with one VOLM or TETM chunk (a volume split
 * into tets with --split). */
#include <getopt.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tool.h"
#include "vx_grid.h"
#include "vx_import.h"
#include "vx_scan.h"
#include "vx_stream.h"
#include "vx_tetimport.h"
#include "vx_tetleaf.h"

static const char usage[] =
    "vread [-o out] [--format F] [--raw NX,NY,NZ --type T "
    "[--endian little|big] [--skip BYTES]] [--spacing SX,SY,SZ] "
    "[--origin X,Y,Z] [--name NAME] [--scalar NAME] [--skip-cells] "
    "[--split 5|6] [--add STREAM] [-z LEVEL] [FILE|-]\n"
    "       vread --synth NAME [--size N[,NY,NZ]] [--spacing SX,SY,SZ] "
    "[--origin X,Y,Z] [--name NAME] [--split 5|6] [--add STREAM] [-o out] "
    "[-z LEVEL]";

typedef struct opts {
	const char *out, *in, *name, *add;
	vx_import_opts imp;
	int raw, have_type, have_endian, have_skip;
	int have_spacing, have_origin;
	double spacing[3], origin[3];
	vx_synth_kind synth;
	int have_size;
	int64_t size[3];
	int zlevel;
	int split;                 /* 5 or 6: the volume as a tet mesh */
	vx_tetimport_opt mesh;     /* --scalar, --skip-cells */
} opts;

enum { O_FORMAT = 256, O_RAW, O_TYPE, O_ENDIAN, O_SKIP, O_SPACING, O_ORIGIN,
	O_NAME, O_SYNTH, O_SIZE, O_ADD, O_SPLIT, O_SCALAR, O_SKIPCELLS };

/* parse_dims: "N,NY,NZ" (or just "N" when one_ok, meaning N,N,N). */
static void
parse_dims(const char *opt, const char *s, int64_t out[3], int one_ok)
{
	double v[3];
	int a;

	if (one_ok && strchr(s, ',') == NULL) {
		if (vx_num_f64(s, strlen(s), 0, &v[0]) != 0)
			tool_fail(VX_EUSAGE, "%s: '%s' is not a size", opt, s);
		v[1] = v[2] = v[0];
	} else
		tool_parse_doubles(opt, s, v, 3);
	for (a = 0; a < 3; a++) {
		if (v[a] != floor(v[a]) || v[a] < 1 ||
		    v[a] > (double)VX_GRID_MAX_DIM)
			tool_fail(VX_EUSAGE, "%s: '%s': sizes must be integers in "
			    "1..%lld", opt, s, (long long)VX_GRID_MAX_DIM);
		out[a] = (int64_t)v[a];
	}
}

static void
parse_name(const char *s)
{
	size_t i, n = strlen(s);

	if (n == 0 || n >= 64)
		tool_fail(VX_EUSAGE, "--name: '%s': 1 to 63 characters", s);
	for (i = 0; i < n; i++)
		if (!((s[i] >= 'a' && s[i] <= 'z') || (s[i] >= 'A' &&
		    s[i] <= 'Z') || (s[i] >= '0' && s[i] <= '9') ||
		    strchr("_.+-", s[i]) != NULL))
			tool_fail(VX_EUSAGE, "--name: '%s': use letters, digits "
			    "and _ . + -", s);
}

static void
parse_args(opts *o, int argc, char **argv)
{
	static const struct option lo[] = {
		{ "output", required_argument, NULL, 'o' },
		{ "format", required_argument, NULL, O_FORMAT },
		{ "raw", required_argument, NULL, O_RAW },
		{ "type", required_argument, NULL, O_TYPE },
		{ "endian", required_argument, NULL, O_ENDIAN },
		{ "skip", required_argument, NULL, O_SKIP },
		{ "spacing", required_argument, NULL, O_SPACING },
		{ "origin", required_argument, NULL, O_ORIGIN },
		{ "name", required_argument, NULL, O_NAME },
		{ "synth", required_argument, NULL, O_SYNTH },
		{ "size", required_argument, NULL, O_SIZE },
		{ "add", required_argument, NULL, O_ADD },
		{ "split", required_argument, NULL, O_SPLIT },
		{ "scalar", required_argument, NULL, O_SCALAR },
		{ "skip-cells", no_argument, NULL, O_SKIPCELLS },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	vx_raw_info *r = &o->imp.raw;
	int c, a;

	memset(o, 0, sizeof *o);
	o->out = "-";
	vx_import_opts_init(&o->imp);
	while ((c = getopt_long(argc, argv, ":o:z:h", lo, NULL)) != -1) {
		switch (c) {
		case 'o':
			o->out = optarg;
			break;
		case 'z':
			o->zlevel = (int)tool_parse_long("-z", optarg, 0, 9);
			break;
		case O_ADD:
			o->add = optarg;
			break;
		case O_SPLIT:
			o->split = (int)tool_parse_long("--split", optarg, 5, 6);
			break;
		case O_SCALAR:
			o->mesh.scalar = optarg;
			break;
		case O_SKIPCELLS:
			o->mesh.skip_volume_cells = 1;
			break;
		case O_FORMAT:
			o->imp.format = (vx_format)tool_parse_enum("--format",
			    &vx_format_enum, optarg);
			break;
		case O_RAW:
			parse_dims("--raw", optarg, r->dims, 0);
			o->raw = 1;
			break;
		case O_TYPE:
			r->type = (vx_scalar)tool_parse_enum("--type",
			    &vx_scalar_enum, optarg);
			o->have_type = 1;
			break;
		case O_ENDIAN:
			r->big_endian = tool_parse_enum("--endian",
			    &vx_endian_enum, optarg);
			o->have_endian = 1;
			break;
		case O_SKIP:
			r->skip = (uint64_t)tool_parse_long("--skip", optarg, 0,
			    LONG_MAX);
			o->have_skip = 1;
			break;
		case O_SPACING:
			tool_parse_doubles("--spacing", optarg, o->spacing, 3);
			for (a = 0; a < 3; a++)
				if (!(o->spacing[a] > 0))
					tool_fail(VX_EUSAGE, "--spacing: '%s': each "
					    "must be positive", optarg);
			o->have_spacing = 1;
			break;
		case O_ORIGIN:
			tool_parse_doubles("--origin", optarg, o->origin, 3);
			o->have_origin = 1;
			break;
		case O_NAME:
			parse_name(optarg);
			o->name = optarg;
			break;
		case O_SYNTH:
			o->synth = (vx_synth_kind)tool_parse_enum("--synth",
			    &vx_synth_enum, optarg);
			break;
		case O_SIZE:
			parse_dims("--size", optarg, o->size, 1);
			o->have_size = 1;
			break;
		default:
			tool_opt_other(c, usage, argv);
		}
	}
	if (optind < argc)
		o->in = tool_opt_input(argc, argv, usage);
	if ((o->have_type || o->have_endian || o->have_skip) && !o->raw)
		tool_fail(VX_EUSAGE, "--type, --endian and --skip go with "
		    "--raw");
	if (o->raw && !o->have_type)
		tool_fail(VX_EUSAGE, "--raw needs --type");
	if (o->raw && o->imp.format != VX_FORMAT_UNKNOWN &&
	    o->imp.format != VX_FORMAT_RAW)
		tool_fail(VX_EUSAGE, "--raw contradicts --format %s",
		    vx_enum_str(&vx_format_enum, o->imp.format));
	if (o->imp.format == VX_FORMAT_RAW && !o->raw)
		tool_fail(VX_EUSAGE, "--format raw needs --raw NX,NY,NZ and "
		    "--type T");
	if (o->raw)
		o->imp.format = VX_FORMAT_RAW;
	if ((o->mesh.scalar != NULL || o->mesh.skip_volume_cells) &&
	    (o->split || o->synth != VX_SYNTH_UNKNOWN || o->raw))
		tool_fail(VX_EUSAGE, "--scalar and --skip-cells apply to tet "
		    "mesh files, not to volumes");
	if (o->have_size && o->synth == VX_SYNTH_UNKNOWN)
		tool_fail(VX_EUSAGE, "--size goes with --synth");
	if (o->synth != VX_SYNTH_UNKNOWN) {
		if (o->in != NULL || o->raw || o->imp.format != VX_FORMAT_UNKNOWN)
			tool_fail(VX_EUSAGE, "--synth reads no input");
		if (!o->have_size)
			o->size[0] = o->size[1] = o->size[2] = 64;
	}
	if (o->in == NULL)
		o->in = "-";
}

/* name_taken: 1 if stream s already holds a volume or a mesh named name. */
static int
name_taken(const vx_stream *s, const char *name)
{
	static const char *const kinds[] = { VX_CHUNK_VOLUME, VX_CHUNK_TETMESH };
	vx_err e = { 0, "" };

	for (int k = 0; k < 2; k++)
		for (long i = -1; (i = vx_stream_find(s, kinds[k],
		    (size_t)(i + 1))) >= 0;) {
			vx_hdr h;
			const unsigned char *b;
			size_t bl;
			const char *nm;
			int same;

			vx_hdr_init(&h);
			if (vx_payload_parse(&s->chunk[i], &h, &b, &bl, &e) != 0)
				tool_fail_err(&e);
			nm = vx_hdr_get(&h, "name");
			if (nm == NULL)
				nm = k == 0 ? "density" : "mesh";
			same = strcmp(nm, name) == 0;
			vx_hdr_free(&h);
			if (same)
				return 1;
		}
	return 0;
}

int
main(int argc, char **argv)
{
	vx_err e = { 0, "" };
	vx_stream s;
	vx_chunk c;
	vx_grid g;
	vx_tetmesh m;
	vx_tetimport_info info;
	opts o;
	int a, is_mesh = 0;

	tool_init("vread", argc, argv);
	if (argc == 1 && isatty(STDIN_FILENO))
		tool_usage_fail(usage, "no input");
	parse_args(&o, argc, argv);
	memset(&info, 0, sizeof info);
	vx_tetmesh_init(&m);
	if (o.synth != VX_SYNTH_UNKNOWN) {
		if (vx_synth_make(&g, o.synth, o.size, &e) != 0)
			tool_fail_err(&e);
	} else {
		if (strcmp(o.in, "-") == 0 && isatty(STDIN_FILENO))
			tool_fail(VX_EUSAGE, "standard input is a terminal: give "
			    "a file or pipe the data in");
		if (vx_import_volume_or_mesh(&g, &m, &is_mesh, o.in, &o.imp,
		    &o.mesh, &info, &e) != 0)
			tool_fail_err(&e);
	}
	if (is_mesh) {
		if (o.split)
			tool_fail(VX_EUSAGE, "--split: %s is a tet mesh already",
			    o.in);
		if (o.have_spacing || o.have_origin)
			tool_fail(VX_EUSAGE, "--spacing and --origin apply to "
			    "volumes; %s is a tet mesh", o.in);
		if (info.nskip_volume > 0)
			tool_note("%s: skipped %zu volume cells that are not "
			    "linear tetrahedra", o.in, info.nskip_volume);
		if (o.name != NULL)
			vx_tetmesh_set_name(&m, o.name);
	} else {
		if (o.mesh.scalar != NULL || o.mesh.skip_volume_cells)
			tool_fail(VX_EUSAGE, "--scalar and --skip-cells apply to "
			    "tet mesh files; %s is a volume", o.in);
		if (o.name != NULL)
			snprintf(g.name, sizeof g.name, "%s", o.name);
		for (a = 0; a < 3; a++) {
			if (o.have_spacing)
				g.spacing[a] = o.spacing[a];
			if (o.have_origin)
				g.origin[a] = o.origin[a];
		}
		if (vx_grid_check_box(&g, &e) != 0)
			tool_fail_err(&e);
		if (o.split) {
			/* the volume's tet split: vertices at the samples */
			if (vx_tetsynth_from_grid(&m, &g, o.split, &e) != 0) {
				vx_err_push(&e, "--split");
				tool_fail_err(&e);
			}
			vx_tetmesh_set_name(&m, g.name);
			vx_grid_free(&g);
			is_mesh = 1;
		}
	}
	if (strcmp(o.out, "-") == 0 && isatty(STDOUT_FILENO))
		tool_fail(VX_EUSAGE, "standard output is a terminal: redirect it "
		    "or give -o FILE");
	vx_stream_init(&s);
	if (o.add != NULL) {
		/* append to an existing stream, e.g. a texture volume */
		tool_read_stream(&s, o.add);
		if (name_taken(&s, is_mesh ? m.name : g.name))
			tool_fail(VX_EUSAGE, "--add: the stream already has a "
			    "volume or mesh named '%s': give --name",
			    is_mesh ? m.name : g.name);
	}
	if (is_mesh) {
		if (vx_tetmesh_to_chunk(&m, o.zlevel, &c, &e) != 0 ||
		    vx_stream_append(&s, &c, &e) != 0)
			tool_fail_err(&e);
		vx_tetmesh_free(&m);
	} else {
		/* the samples' own memory becomes the chunk (g is freed) */
		if (vx_grid_to_chunk_take(&g, o.zlevel, NULL, &c, &e) != 0 ||
		    vx_stream_append(&s, &c, &e) != 0)
			tool_fail_err(&e);
	}
	tool_write_stream(&s, o.out);
	vx_stream_free(&s);
	return tool_finish();
}
