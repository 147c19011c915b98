/* heightfield.c: a height field from a 2D map, as a volume dvr can render
 * (Kniss et al. 2003, section 5, Fig. 13): the density at (x, y, z) is a
 * soft step at the map's height h(x, y): 1 below, 0 above, a linear ramp
 * of the edge width centred on h (or, with --thickness, a layer of that
 * thickness below h with the same ramp at its bottom).  The map is a PGM
 * (binary, 8 or 16 bits), a PNG (any type, 8 or 16 bits) or a PFM. */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tool.h"
#include "vx_file.h"
#include "vx_grid.h"
#include "vx_imageio.h"
#include "vx_stream.h"

#define MAX_NZ   4096
#define MAX_FILE ((size_t)1 << 31)   /* a 16-bit PNG or a PFM of the largest
                                        voxlux image, and room for headers */

static const char usage[] =
    "heightfield [--nz N] [--range LO,HI] [--edge W] [--thickness T] "
    "[--spacing SX,SY,SZ] [--name NAME] [-z LEVEL] [-o OUT] [MAP|-]";

typedef struct opts {
	const char *in, *name;
	int nz;
	double range[2], edge, thickness, spacing[3];
	tool_run_opts run;       /* -o, -z, --name */
} opts;

static void
parse_args(opts *o, int argc, char **argv)
{
	static const struct option lo[] = {
		{ "nz", required_argument, NULL, 'n' },
		{ "range", required_argument, NULL, 'r' },
		{ "edge", required_argument, NULL, 'e' },
		{ "thickness", required_argument, NULL, 't' },
		{ "spacing", required_argument, NULL, 's' },
		{ "name", required_argument, NULL, TOOL_O_NAME },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 },
	};
	int ch;

	memset(o, 0, sizeof *o);
	tool_run_opts_init(&o->run);
	o->run.zlevel = 0;       /* raw samples unless -z, as vread */
	o->nz = 64;
	o->range[1] = 1;
	o->edge = 2;
	o->thickness = HUGE_VAL;
	o->spacing[0] = o->spacing[1] = o->spacing[2] = 1;
	while ((ch = getopt_long(argc, argv, ":o:z:", lo, NULL)) != -1) {
		switch (ch) {
		case 'n':
			o->nz = (int)tool_parse_long("--nz", optarg, 2, MAX_NZ);
			break;
		case 'r':
			tool_parse_doubles("--range", optarg, o->range, 2);
			if (!isfinite(o->range[0]) || !isfinite(o->range[1]) ||
			    !(o->range[1] != o->range[0]))
				tool_fail(VX_EUSAGE, "--range: '%s': two different "
				    "finite numbers", optarg);
			break;
		case 'e':
			o->edge = tool_parse_double("--edge", optarg, 0, 1e6);
			break;
		case 't':
			o->thickness = tool_parse_double("--thickness", optarg,
			    0, 1e6);
			if (!(o->thickness > 0))
				tool_fail(VX_EUSAGE, "--thickness: '%s': a positive "
				    "number of voxels", optarg);
			break;
		case 's':
			tool_parse_doubles("--spacing", optarg, o->spacing, 3);
			for (int a = 0; a < 3; a++)
				if (!(o->spacing[a] > 0) || !isfinite(o->spacing[a]))
					tool_fail(VX_EUSAGE, "--spacing: '%s': three "
					    "positive numbers", optarg);
			break;
		default:
			if (!tool_run_opt(&o->run, ch, optarg))
				tool_opt_other(ch, usage, argv);
		}
	}
	o->name = o->run.name != NULL ? o->run.name : "height";
	if (o->name[0] == '\0' || strlen(o->name) >= 64)
		tool_fail(VX_EUSAGE, "--name: 1 to 63 bytes");
	o->in = tool_opt_input(argc, argv, usage);
}

/* read_map: the map at path ("-": standard input) into img; exits on
 * error. */
static void
read_map(vx_image *img, const char *path)
{
	const char *shown = strcmp(path, "-") ? path : "<stdin>";
	unsigned char *buf = NULL;
	size_t n = 0;
	FILE *f = stdin;
	vx_err e = { 0, "" };
	int rc, fmt;

	if (strcmp(path, "-") != 0) {
		if ((f = fopen(path, "rb")) == NULL)
			tool_fail(VX_ENOINPUT, "%s: %s", path, strerror(errno));
	} else if (isatty(STDIN_FILENO))
		tool_fail(VX_EUSAGE, "standard input is a terminal: give a map "
		    "(PGM, PNG or PFM)");
	rc = vx_file_read_all(f, MAX_FILE, &buf, &n, &e);
	if (f != stdin)
		fclose(f);
	if (rc != 0) {
		vx_err_push(&e, "%s", shown);
		tool_fail_err(&e);
	}
	if (n == 0)
		tool_fail(VX_ENOINPUT, "%s: empty input", shown);
	fmt = vx_image_sniff(buf, n);
	if (fmt == VX_IMGFMT_PGM)
		rc = vx_pgm_read_mem(img, buf, n, NULL, &e);
	else if (fmt == VX_IMGFMT_PNG)
		rc = vx_image_png_read_mem(img, buf, n, NULL, &e);
	else if (fmt == VX_IMGFMT_PFM)
		rc = vx_pfm_read_mem(img, buf, n, &e);
	else
		rc = vx_err_set(&e, VX_EDATA, "not a PGM (P5), PNG or PFM file "
		    "(%s)", fmt == VX_IMGFMT_UNKNOWN ? "unknown format" :
		    vx_image_format_name(fmt));
	free(buf);
	if (rc != 0) {
		vx_err_push(&e, "%s", shown);
		tool_fail_err(&e);
	}
}

/* height: the map's value at pixel (x, y): the grey value, or the mean of
 * R, G and B (alpha ignored). */
static double
height(const vx_image *img, int x, int y)
{
	const float *p = vx_image_pixel(img, x, y);

	return img->nc >= 3 ? ((double)p[0] + p[1] + p[2]) / 3 : p[0];
}

static double
clamp01(double v)
{
	return v < 0 ? 0 : v > 1 ? 1 : v;
}

int
main(int argc, char **argv)
{
	vx_image img;
	vx_grid g;
	vx_stream s;
	vx_chunk c;
	vx_err e = { 0, "" };
	int64_t dims[3];
	opts o;

	tool_init("heightfield", argc, argv);
	parse_args(&o, argc, argv);
	if (strcmp(o.run.out, "-") == 0 && isatty(STDOUT_FILENO))
		tool_fail(VX_EUSAGE, "standard output is a terminal: redirect it "
		    "or give -o FILE");
	read_map(&img, o.in);
	/* every value finite before anything more is allocated */
	for (int y = 0; y < img.h; y++)
		for (int x = 0; x < img.w; x++)
			if (!isfinite(height(&img, x, y)))
				tool_fail(VX_EDATA, "%s: pixel (%d, %d): height is "
				    "not finite", strcmp(o.in, "-") ? o.in :
				    "<stdin>", x, y);
	dims[0] = img.w;
	dims[1] = img.h;
	dims[2] = o.nz;
	vx_grid_init(&g);
	if (vx_grid_alloc(&g, dims, VX_F32, NULL, &e) != 0) {
		vx_err_push(&e, "%dx%dx%d volume", img.w, img.h, o.nz);
		tool_fail_err(&e);
	}
	snprintf(g.name, sizeof g.name, "%s", o.name);
	memcpy(g.spacing, o.spacing, sizeof g.spacing);
	for (int y = 0; y < img.h; y++)
		for (int x = 0; x < img.w; x++) {
			/* the map's top row is the volume's far edge (y up) */
			double v = height(&img, x, img.h - 1 - y);
			double hz = (v - o.range[0]) / (o.range[1] - o.range[0]) *
			    (o.nz - 1);

			for (int z = 0; z < o.nz; z++) {
				double d = z - hz, top, bot;

				if (o.edge > 0) {
					top = clamp01(0.5 - d / o.edge);
					bot = clamp01(0.5 + (d + o.thickness) / o.edge);
				} else {
					top = d < 0 ? 1 : d > 0 ? 0 : 0.5;
					bot = d + o.thickness > 0 ? 1 :
					    d + o.thickness < 0 ? 0 : 0.5;
				}
				vx_grid_set(&g, x, y, z, fmin(top, bot));
			}
		}
	vx_image_free(&img);
	vx_grid_range(&g);
	vx_stream_init(&s);
	if (vx_grid_to_chunk_take(&g, o.run.zlevel, NULL, &c, &e) != 0 ||
	    vx_stream_append(&s, &c, &e) != 0)
		tool_fail_err(&e);
	tool_write_stream(&s, o.run.out);
	vx_stream_free(&s);
	return tool_finish();
}
