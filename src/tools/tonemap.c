/* tonemap.c: float image (stream IMAG chunk, PFM, Radiance HDR or
 * OpenEXR) to PNG or PFM, and image comparison metrics for studies.  See
 * tonemap(1). */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tool.h"
#include "vx_compare.h"
#include "vx_image.h"
#include "vx_imageio.h"
#include "vx_tonemap.h"
#include "vx_version.h"

static const char *usage =
    "tonemap [-o OUT.png|OUT.pfm] [--name NAME] [--bits 8|16] "
    "[--exposure STOPS] [--op clamp|reinhard|aces] [--white W] "
    "[--srgb|--gamma G|--linear] [--background R,G,B] [--dither] [--pfm] "
    "[--compare REF [--diff DIFF.png] [--diff-map abs|signed] "
    "[--diff-scale S] [--peak P] [--json]] [IN|-]";

/* Largest PFM or PNG file read: 2^28 RGB float pixels and a header. */
#define MAX_FILE (((size_t)1 << 28) * 12 + 4096)

typedef struct opts {
	const char *in, *out, *name, *ref, *diff;
	int bits, pfm, json, diff_map, dither;
	int png_only;           /* a PNG-only option was given */
	int has_white, has_bg;
	double peak, diff_scale;
	vx_tonemap_opts tm;
} opts;

/* An input image and what came with it. */
typedef struct input {
	vx_image img;
	int fmt;                /* VX_IMGFMT_* */
	int bits;               /* PNG bit depth */
	char *history;          /* stream history lines, or NULL */
} input;

static void
parse(opts *o, int argc, char **argv)
{
	enum { O_NAME = 256, O_BITS, O_EXPO, O_OP, O_WHITE, O_SRGB, O_GAMMA,
	    O_LINEAR, O_BG, O_DITHER, O_PFM, O_CMP, O_DIFF, O_DMAP, O_DSCALE,
	    O_PEAK, O_JSON, O_HELP };
	static const struct option lo[] = {
		{ "name", required_argument, NULL, O_NAME },
		{ "bits", required_argument, NULL, O_BITS },
		{ "exposure", required_argument, NULL, O_EXPO },
		{ "op", required_argument, NULL, O_OP },
		{ "white", required_argument, NULL, O_WHITE },
		{ "srgb", no_argument, NULL, O_SRGB },
		{ "gamma", required_argument, NULL, O_GAMMA },
		{ "linear", no_argument, NULL, O_LINEAR },
		{ "background", required_argument, NULL, O_BG },
		{ "dither", no_argument, NULL, O_DITHER },
		{ "pfm", no_argument, NULL, O_PFM },
		{ "compare", required_argument, NULL, O_CMP },
		{ "diff", required_argument, NULL, O_DIFF },
		{ "diff-map", required_argument, NULL, O_DMAP },
		{ "diff-scale", required_argument, NULL, O_DSCALE },
		{ "peak", required_argument, NULL, O_PEAK },
		{ "json", no_argument, NULL, O_JSON },
		{ "help", no_argument, NULL, O_HELP },
		{ NULL, 0, NULL, 0 },
	};
	int c, ntf = 0;
	size_t len;

	memset(o, 0, sizeof *o);
	o->bits = 8;
	o->peak = 1;
	o->diff_map = VX_DIFF_ABS;
	vx_tonemap_defaults(&o->tm);
	while ((c = getopt_long(argc, argv, ":o:h", lo, NULL)) != -1) {
		switch (c) {
		case 'o': o->out = optarg; break;
		case O_NAME: o->name = optarg; break;
		case O_BITS:
			o->bits = tool_parse_bits(optarg);
			o->png_only = 1;
			break;
		case O_EXPO:
			o->tm.exposure = tool_parse_double("--exposure", optarg,
			    -100, 100);
			break;
		case O_OP:
			o->tm.op = tool_parse_enum("--op", &vx_tonemap_op_enum,
			    optarg);
			o->png_only = 1;
			break;
		case O_WHITE:
			o->tm.white = tool_parse_double("--white", optarg, 1e-30,
			    INFINITY);
			o->has_white = 1;
			break;
		case O_SRGB: o->tm.transfer = VX_TF_SRGB; ntf++; break;
		case O_LINEAR: o->tm.transfer = VX_TF_LINEAR; ntf++; break;
		case O_GAMMA:
			o->tm.transfer = VX_TF_GAMMA;
			o->tm.gamma = tool_parse_double("--gamma", optarg, 0.01,
			    100);
			ntf++;
			break;
		case O_BG:
			tool_parse_doubles("--background", optarg,
			    o->tm.background, 3);
			for (int k = 0; k < 3; k++)
				if (o->tm.background[k] < 0)
					tool_fail(VX_EUSAGE, "--background: values "
					    "must be >= 0");
			o->has_bg = 1;
			break;
		case O_DITHER: o->dither = 1; o->png_only = 1; break;
		case O_PFM: o->pfm = 1; break;
		case O_CMP: o->ref = optarg; break;
		case O_DIFF: o->diff = optarg; break;
		case O_DMAP:
			o->diff_map = tool_parse_enum("--diff-map", &vx_diff_map_enum,
			    optarg);
			break;
		case O_DSCALE:
			o->diff_scale = tool_parse_double("--diff-scale", optarg,
			    1e-30, 1e30);
			break;
		case O_PEAK:
			o->peak = tool_parse_double("--peak", optarg, 1e-30, 1e30);
			break;
		case O_JSON: o->json = 1; break;
		case O_HELP:
			tool_opt_other('h', usage, argv);
		default:
			tool_opt_other(c, usage, argv);
		}
	}
	o->in = tool_opt_input(argc, argv, usage);
	if (ntf > 1)
		tool_fail(VX_EUSAGE, "--srgb, --gamma and --linear exclude "
		    "each other");
	if (ntf > 0)
		o->png_only = 1;
	if (o->has_white && o->tm.op != VX_TM_REINHARD)
		tool_fail(VX_EUSAGE, "--white needs --op reinhard");
	if (o->out != NULL && (len = strlen(o->out)) >= 4 &&
	    strcasecmp(o->out + len - 4, ".pfm") == 0)
		o->pfm = 1;
	if (o->pfm && o->png_only)
		tool_fail(VX_EUSAGE, "--bits, --op, --srgb, --gamma, --linear "
		    "and --dither are for PNG output; PFM output stays linear");
	if (o->ref == NULL && (o->diff || o->json || o->diff_scale > 0))
		tool_fail(VX_EUSAGE, "--diff, --diff-scale and --json need "
		    "--compare");
	if (o->ref != NULL && o->out != NULL && strcmp(o->out, "-") == 0)
		tool_fail(VX_EUSAGE, "with --compare the metrics go to "
		    "standard output: give -o a file");
	if (o->ref != NULL && strcmp(o->ref, "-") == 0 &&
	    strcmp(o->in, "-") == 0)
		tool_fail(VX_EUSAGE, "IN and REF cannot both be standard "
		    "input");
	o->tm.flatten = o->has_bg;
	if (o->dither)
		o->tm.dither_bits = o->bits;
}

/* ---- reading inputs ---- */

struct peeked {
	FILE *f;
	unsigned char head[8];
	size_t nhead, pos;
};

static long
peeked_read(void *ctx, void *buf, size_t n)
{
	struct peeked *p = ctx;
	size_t k;

	if (p->pos < p->nhead) {
		k = p->nhead - p->pos < n ? p->nhead - p->pos : n;
		memcpy(buf, p->head + p->pos, k);
		p->pos += k;
		return (long)k;
	}
	k = fread(buf, 1, n, p->f);
	if (k == 0 && ferror(p->f))
		return -1;
	return (long)k;
}

/* load: read path ("-": stdin) as a stream (image `name`, or the first),
 * a PFM, Radiance HDR or OpenEXR file, or (when allow_png) a PNG; exits
 * on error. */
static void
load(input *in, const char *path, const char *name, int allow_png)
{
	const char *shown = strcmp(path, "-") ? path : "<stdin>";
	struct peeked p;
	vx_err e = { 0, "" };
	int rc = 0, linear;

	memset(in, 0, sizeof *in);
	memset(&p, 0, sizeof p);
	vx_image_init(&in->img);
	if (strcmp(path, "-") == 0) {
		if (isatty(STDIN_FILENO))
			tool_fail(VX_EUSAGE, "standard input is a terminal: pipe "
			    "a voxlux stream or an image file in");
		p.f = stdin;
	} else if ((p.f = fopen(path, "rb")) == NULL)
		tool_fail(VX_ENOINPUT, "%s: %s", path, strerror(errno));
	p.nhead = fread(p.head, 1, sizeof p.head, p.f);
	if (ferror(p.f))
		tool_fail(VX_EIO, "%s: read error: %s", shown, strerror(errno));
	if (p.nhead == 0)
		tool_fail(VX_ENOINPUT, "%s: empty input", shown);
	in->fmt = vx_image_sniff(p.head, p.nhead);
	linear = in->fmt == VX_IMGFMT_PFM || in->fmt == VX_IMGFMT_HDR ||
	    in->fmt == VX_IMGFMT_EXR;
	if (in->fmt == VX_IMGFMT_STREAM) {
		vx_stream s;
		const char *h;
		size_t hl;

		vx_stream_init(&s);
		if ((rc = vx_stream_read_fn(&s, peeked_read, &p, &e)) == 0)
			rc = vx_image_from_stream(&in->img, &s, name, NULL, &e);
		if (rc == 0 && (h = vx_stream_history(&s, &hl)) != NULL) {
			if ((in->history = malloc(hl + 1)) == NULL)
				tool_fail(VX_ENOMEM, "out of memory");
			memcpy(in->history, h, hl);
			in->history[hl] = '\0';
		}
		vx_stream_free(&s);
	} else if (linear || (allow_png && in->fmt == VX_IMGFMT_PNG)) {
		unsigned char *buf, *all;
		size_t n;

		if (name != NULL && linear && !allow_png)
			tool_fail(VX_EUSAGE, "%s: --name: a %s file holds one "
			    "unnamed image", shown, vx_image_format_name(in->fmt));
		if ((rc = vx_file_read_all(p.f, MAX_FILE, &buf, &n, &e)) == 0) {
			if ((all = malloc(n + p.nhead)) == NULL)
				tool_fail(VX_ENOMEM, "out of memory");
			memcpy(all, p.head, p.nhead);
			if (n > 0)
				memcpy(all + p.nhead, buf, n);
			free(buf);
			n += p.nhead;
			if (linear)
				rc = vx_image_read_linear_mem(&in->img, all, n,
				    NULL, &e);
			else
				rc = vx_image_png_read_mem(&in->img, all, n,
				    &in->bits, &e);
			free(all);
		}
	} else if (in->fmt == VX_IMGFMT_PNG)
		tool_fail(VX_EDATA, "%s: a PNG holds display values; tonemap "
		    "reads linear images (voxlux stream, PFM, Radiance HDR or "
		    "OpenEXR)", shown);
	else
		tool_fail(VX_EDATA, "%s: not a voxlux stream, PFM, Radiance HDR%s "
		    "file", shown, allow_png ? ", OpenEXR or PNG" : " or OpenEXR");
	if (p.f != stdin)
		fclose(p.f);
	if (rc != 0) {
		vx_err_push(&e, "%s", shown);
		tool_fail_err(&e);
	}
}

/* ---- outputs ---- */

/* refuse_tty: a picture is not written to a terminal. */
static void
refuse_tty(const char *path)
{
	if (strcmp(path, "-") == 0 && isatty(STDOUT_FILENO))
		tool_fail(VX_EUSAGE, "standard output is a terminal: give -o "
		    "FILE or redirect");
}

static double
png_gamma(const vx_tonemap_opts *tm)
{
	return tm->transfer == VX_TF_SRGB ? 0 : tm->transfer == VX_TF_GAMMA ?
	    tm->gamma : 1;
}

/* display: the PNG-bound picture of src with the options, alpha flattened
 * when `flatten` (over --background, black by default). */
static void
display(vx_image *dst, const vx_image *src, const opts *o, int flatten,
    vx_tonemap_stats *st)
{
	vx_tonemap_opts tm = o->tm;
	vx_err e = { 0, "" };

	tm.flatten = flatten;
	if (vx_tonemap_image(dst, src, &tm, st, &e) != 0)
		tool_fail_err(&e);
}

/* scene: the PFM-bound picture: exposure, alpha flattened. */
static void
scene(vx_image *dst, const vx_image *src, const opts *o)
{
	vx_err e = { 0, "" };

	if (vx_image_flatten(dst, src, exp2(o->tm.exposure), o->tm.background,
	    &e) != 0)
		tool_fail_err(&e);
}

/* add_alpha: dst gets src with an opaque alpha channel appended. */
static void
add_alpha(vx_image *dst, const vx_image *src)
{
	vx_err e = { 0, "" };
	size_t p, np = (size_t)src->w * (size_t)src->h;

	if (vx_image_alloc(dst, src->w, src->h, src->nc + 1, &e) != 0)
		tool_fail_err(&e);
	for (p = 0; p < np; p++) {
		memcpy(dst->px + p * (size_t)dst->nc, src->px + p *
		    (size_t)src->nc, (size_t)src->nc * sizeof(float));
		dst->px[p * (size_t)dst->nc + (size_t)src->nc] = 1;
	}
}

static void
warn_repairs(const vx_tonemap_stats *st)
{
	if (st->nan > 0)
		fprintf(stderr, "%s: warning: %zu NaN values shown as 0\n",
		    tool_name, st->nan);
}

/* ---- comparison ---- */

static void
put_num(int json, const char *key, double v, int *first)
{
	if (json) {
		printf("%s\"%s\": ", *first ? "" : ", ", key);
		if (isfinite(v))
			printf("%.10g", v);
		else
			printf("null");
	} else if (isinf(v))
		printf("%s %s\n", key, v > 0 ? "inf" : "-inf");
	else
		printf("%s %.10g\n", key, v);
	*first = 0;
}

/* What a comparison found, printed after the outputs are written. */
typedef struct result {
	vx_compare r;
	int w, h, nc, png_ref;
	size_t nan_shown;
	double dscale;
} result;

/* compare: load REF, put the image in its form, compute the metrics and
 * write the difference picture; exits on error. */
static void
compare(result *res, const opts *o, const input *in)
{
	input ref;
	vx_image a, b;
	vx_tonemap_stats st = { 0, 0, 0 };
	vx_err e = { 0, "" };
	int ra, ia;

	load(&ref, o->ref, o->name, 1);
	vx_image_init(&a);
	vx_image_init(&b);
	ia = vx_image_has_alpha(&in->img);
	ra = vx_image_has_alpha(&ref.img);
	if (vx_image_ncolor(&in->img) != vx_image_ncolor(&ref.img))
		tool_fail(VX_EDATA, "compare: image has %d channels, reference "
		    "%s has %d", in->img.nc, o->ref, ref.img.nc);
	/* the image is put in the reference's form: tone mapped and quantized
	 * like it for a PNG, scaled by the exposure for a float one; an alpha
	 * the reference lacks is flattened away, one it has and the image
	 * lacks is taken as opaque */
	if (ref.fmt == VX_IMGFMT_PNG) {
		display(&b, &in->img, o, ia && !ra, &st);
		vx_image_quantize(&b, ref.bits);
	} else if (ia && !ra)
		scene(&b, &in->img, o);
	else {
		size_t i, n = vx_image_nvalue(&in->img);
		int nc = in->img.nc, ncol = vx_image_ncolor(&in->img);
		double s = exp2(o->tm.exposure);

		if (vx_image_copy(&b, &in->img, &e) != 0)
			tool_fail_err(&e);
		for (i = 0; i < n; i++)
			if ((int)(i % (size_t)nc) < ncol)
				b.px[i] = (float)(b.px[i] * s);
	}
	if (!ia && ra) {
		add_alpha(&a, &b);
		vx_image_free(&b);
	} else {
		a = b;
		vx_image_init(&b);
	}
	memset(res, 0, sizeof *res);
	res->dscale = o->diff_scale;
	if (vx_image_compare(&res->r, &a, &ref.img, o->peak, &e) != 0)
		tool_fail_err(&e);
	if (o->diff != NULL) {
		vx_image d;
		char sc[64];
		vx_text text[2] = {
			{ "voxlux-diff-map", o->diff_map == VX_DIFF_ABS ?
			    "abs: mean |a - b| over channels, viridis from 0 to "
			    "voxlux-diff-scale; magenta: NaN or unequal infinity" :
			    "signed: mean (a - b) over channels, blue (a < b) - "
			    "white (0) - red (a > b), +-voxlux-diff-scale; "
			    "magenta: NaN or unequal infinity" },
			{ "voxlux-diff-scale", sc },
		};

		if (vx_image_diff(&d, &a, &ref.img, o->diff_map, &res->dscale,
		    &e))
			tool_fail_err(&e);
		snprintf(sc, sizeof sc, "%.10g", res->dscale);
		tool_write_png(o->diff, &d, 8, 0, in->history, in->history ?
		    strlen(in->history) : 0, text, 2);
		vx_image_free(&d);
	}
	res->w = a.w;
	res->h = a.h;
	res->nc = a.nc;
	res->png_ref = ref.fmt == VX_IMGFMT_PNG;
	res->nan_shown = st.nan;
	vx_image_free(&a);
	vx_image_free(&ref.img);
	free(ref.history);
}

/* print_result: one "key value" line each, or one JSON object. */
static void
print_result(const result *res, const opts *o)
{
	int first = 1;

	if (o->json)
		printf("{");
	put_num(o->json, "width", res->w, &first);
	put_num(o->json, "height", res->h, &first);
	put_num(o->json, "channels", res->nc, &first);
	put_num(o->json, "compared", (double)res->r.n, &first);
	put_num(o->json, "mse", res->r.mse, &first);
	put_num(o->json, "rmse", res->r.rmse, &first);
	put_num(o->json, "relmse", res->r.relmse, &first);
	put_num(o->json, "psnr", res->r.psnr, &first);
	put_num(o->json, "peak", res->r.peak, &first);
	put_num(o->json, "max_abs", res->r.max_abs, &first);
	put_num(o->json, "max_x", res->r.max_x, &first);
	put_num(o->json, "max_y", res->r.max_y, &first);
	put_num(o->json, "max_c", res->r.max_c, &first);
	put_num(o->json, "nan_a", (double)res->r.nan_a, &first);
	put_num(o->json, "nan_b", (double)res->r.nan_b, &first);
	put_num(o->json, "inf_mismatch", (double)res->r.inf_mismatch, &first);
	if (res->png_ref)
		put_num(o->json, "nan_shown_as_0", (double)res->nan_shown, &first);
	if (o->diff != NULL)
		put_num(o->json, "diff_scale", res->dscale, &first);
	if (o->json)
		printf("}\n");
}

int
main(int argc, char **argv)
{
	opts o;
	input in;
	vx_image out;
	vx_tonemap_stats st = { 0, 0, 0 };
	result res;

	tool_init("tonemap", argc, argv);
	parse(&o, argc, argv);
	(void)tool_threads(0);   /* the parallel loops' threads, made safely */
	load(&in, o.in, o.name, 0);
	if (o.ref != NULL)
		compare(&res, &o, &in);
	if (o.ref == NULL || o.out != NULL) {
		const char *path = o.out ? o.out : "-";

		if (o.pfm) {
			scene(&out, &in.img, &o);
			refuse_tty(path);
			tool_write_pfm(path, &out);
		} else {
			display(&out, &in.img, &o, o.tm.flatten, &st);
			tool_write_png(path, &out, o.bits, png_gamma(&o.tm),
			    in.history, in.history ? strlen(in.history) : 0,
			    NULL, 0);
			warn_repairs(&st);
		}
		vx_image_free(&out);
	}
	if (o.ref != NULL)
		print_result(&res, &o);
	vx_image_free(&in.img);
	free(in.history);
	return tool_finish();
}
