/* sh-rotate.c: project an environment light onto spherical harmonics,
 * rotate the coefficients, and write them into the stream as an SHLC chunk
 * (formats/shlight.md) or print them. */
#include <getopt.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tool.h"
#include "vx_env.h"
#include "vx_image.h"
#include "vx_imageio.h"
#include "vx_par.h"
#include "vx_scene.h"
#include "vx_sh.h"
#include "vx_shlight.h"
#include "vx_stream.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static const char usage[] =
    "sh-rotate [--env FILE [--layout latlong|angular]] [--scene FILE]\n"
    "    [--order N] [--euler A,B,G | --axis X,Y,Z,DEG | --matrix M9]\n"
    "    [--print | --json | --irradiance] [--reconstruct OUT.pfm\n"
    "    [--width W] [--height H] [--window none|hanning|lanczos]]\n"
    "    [--irradiance-error] [--stats] [--explain] [-o OUT] [STREAM|-]";

enum { WIN_NONE, WIN_HANNING, WIN_LANCZOS };

typedef struct opts {
	const char *env, *scene, *out, *in, *recon;
	vx_env_layout layout;
	int order, order_set;
	int nrot;               /* rotation options given */
	double r[3][3];         /* the rotation asked for */
	int print, json, irr, irrerr, stats, explain, out_set;
	int width, height, window;
} opts;

enum { O_ENV = 256, O_LAYOUT, O_SCENE, O_ORDER, O_EULER, O_AXIS, O_MATRIX,
	O_PRINT, O_JSON, O_IRR, O_RECON, O_WIDTH, O_HEIGHT, O_WINDOW,
	O_STATS, O_EXPLAIN, O_IRRERR };

/* is_rotation: m m^T = I and det m = 1, to 1e-6 */
static int
is_rotation(const double m[3][3])
{
	double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
	    m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
	    m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);

	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++) {
			double d = 0;

			for (int k = 0; k < 3; k++)
				d += m[i][k] * m[j][k];
			if (!(fabs(d - (i == j)) <= 1e-6))
				return 0;
		}
	return fabs(det - 1) <= 1e-6;
}

static void
parse_args(opts *o, int argc, char **argv)
{
	static const struct option lo[] = {
		{ "env", 1, 0, O_ENV }, { "layout", 1, 0, O_LAYOUT },
		{ "scene", 1, 0, O_SCENE }, { "order", 1, 0, O_ORDER },
		{ "euler", 1, 0, O_EULER }, { "axis", 1, 0, O_AXIS },
		{ "matrix", 1, 0, O_MATRIX }, { "print", 0, 0, O_PRINT },
		{ "json", 0, 0, O_JSON }, { "irradiance", 0, 0, O_IRR },
		{ "reconstruct", 1, 0, O_RECON }, { "width", 1, 0, O_WIDTH },
		{ "height", 1, 0, O_HEIGHT }, { "window", 1, 0, O_WINDOW },
		{ "irradiance-error", 0, 0, O_IRRERR },
		{ "stats", 0, 0, O_STATS }, { "explain", 0, 0, O_EXPLAIN },
		{ "output", 1, 0, 'o' }, { "help", 0, 0, 'h' },
		{ NULL, 0, 0, 0 },
	};
	double v[9];
	int ch, nout;

	memset(o, 0, sizeof *o);
	o->out = "-";
	o->layout = VX_ENV_LATLONG;
	o->order = 5;
	o->width = 256;
	o->height = 128;
	for (int i = 0; i < 3; i++)
		o->r[i][i] = 1;
	while ((ch = getopt_long(argc, argv, ":o:h", lo, NULL)) != -1) {
		switch (ch) {
		case O_ENV: o->env = optarg; break;
		case O_LAYOUT:
			o->layout = tool_parse_enum("--layout",
			    &vx_env_layout_enum, optarg);
			break;
		case O_SCENE: o->scene = optarg; break;
		case O_ORDER:
			o->order = (int)tool_parse_long("--order", optarg, 1,
			    VX_SHLIGHT_MAX_ORDER);
			o->order_set = 1;
			break;
		case O_EULER:
			tool_parse_doubles("--euler", optarg, v, 3);
			vx_rot3_zyz(v[0] * M_PI / 180, v[1] * M_PI / 180,
			    v[2] * M_PI / 180, o->r);
			o->nrot++;
			break;
		case O_AXIS:
			tool_parse_doubles("--axis", optarg, v, 4);
			if (v[0] == 0 && v[1] == 0 && v[2] == 0)
				tool_usage_fail(usage, "--axis %s: the axis is "
				    "zero", optarg);
			vx_rot3_axis(v, v[3] * M_PI / 180, o->r);
			o->nrot++;
			break;
		case O_MATRIX:
			tool_parse_doubles("--matrix", optarg, v, 9);
			for (int i = 0; i < 9; i++)
				o->r[i / 3][i % 3] = v[i];
			if (!is_rotation(o->r))
				tool_usage_fail(usage, "--matrix: not a rotation "
				    "(orthogonal, determinant 1, to 1e-6)");
			o->nrot++;
			break;
		case O_PRINT: o->print = 1; break;
		case O_JSON: o->json = 1; break;
		case O_IRR: o->irr = 1; break;
		case O_RECON: o->recon = optarg; break;
		case O_WIDTH:
			o->width = (int)tool_parse_long("--width", optarg, 1,
			    65536);
			break;
		case O_HEIGHT:
			o->height = (int)tool_parse_long("--height", optarg, 1,
			    32768);
			break;
		case O_WINDOW:
			if (strcmp(optarg, "none") == 0)
				o->window = WIN_NONE;
			else if (strcmp(optarg, "hanning") == 0)
				o->window = WIN_HANNING;
			else if (strcmp(optarg, "lanczos") == 0)
				o->window = WIN_LANCZOS;
			else
				tool_usage_fail(usage, "--window: none, hanning "
				    "or lanczos, not '%s'", optarg);
			break;
		case O_IRRERR: o->irrerr = 1; break;
		case O_STATS: o->stats = 1; break;
		case O_EXPLAIN: o->explain = 1; break;
		case 'o': o->out = optarg; o->out_set = 1; break;
		default:
			tool_opt_other(ch, usage, argv);
		}
	}
	/* with --env and no operand nothing is read: the output stream holds
	 * the SH lighting alone */
	o->in = optind < argc || o->env == NULL ?
	    tool_opt_input(argc, argv, usage) : NULL;
	if (o->nrot > 1)
		tool_usage_fail(usage, "one of --euler, --axis, --matrix");
	nout = o->print + o->json + o->irr + o->irrerr;
	if (nout > 1)
		tool_usage_fail(usage, "one of --print, --json, --irradiance, "
		    "--irradiance-error");
	if (o->irrerr && o->env == NULL)
		tool_usage_fail(usage, "--irradiance-error: needs --env");
	if (nout && o->out_set)
		tool_usage_fail(usage, "-o: the stream is not written with "
		    "--print, --json or --irradiance");
	if (o->irr && o->order < 3)
		tool_usage_fail(usage, "--irradiance: needs --order 3 or more");
	if ((long)o->width * o->height > 1L << 26)
		tool_usage_fail(usage, "--width x --height: at most 2^26 "
		    "pixels");
}

/* project: the SH lighting of order --order into sl: the projection of
 * --env's file (kept in env, for --irradiance-error), or else the sum of the
 * scene's environment and sky lights (vx_shlight_from_scene); returns how
 * many maps were projected (0: none, sl untouched), *npix their pixels
 * and *sec the time the projection took */
static int
project(const opts *o, vx_env *env, const vx_stream *st, vx_shlight *sl,
    size_t *npix, double *sec)
{
	static vx_scene s;
	static vx_shlight p;
	vx_err e = { 0, "" };
	double t0;
	int found = 1;

	if (o->env != NULL) {
		vx_image img;

		if (vx_image_read_linear_file(&img, o->env, NULL, &e) != 0)
			tool_fail_err(&e);
		if (vx_env_init(env, &img, o->layout, NULL, NULL, &e) != 0) {
			vx_err_push(&e, "%s", o->env);
			tool_fail_err(&e);
		}
		vx_image_free(&img);
		vx_shlight_init(&p);
		p.order = o->order;
		p.has_hash = 1;
		p.env_hash = env->hash;
		*npix = vx_env_npixel(env);
		t0 = vx_par_seconds();
		vx_shlight_project(env, o->order, p.c);
		*sec = vx_par_seconds() - t0;
	} else {
		vx_scene_init(&s);
		tool_scene_load(&s, o->scene, st, 0, NULL, NULL);
		t0 = vx_par_seconds();
		if (vx_shlight_from_scene(&p, &s, o->order, &found, npix,
		    &e) != 0)
			tool_fail_err(&e);
		*sec = vx_par_seconds() - t0;
	}
	if (found > 0)
		*sl = p;
	return found;
}

static double
window(int kind, int l, int order)
{
	double x = (double)l / order;

	if (kind == WIN_HANNING)
		return 0.5 * (1 + cos(M_PI * x));
	if (kind == WIN_LANCZOS)
		return l == 0 ? 1 : sin(M_PI * x) / (M_PI * x);
	return 1;
}

/* reconstruct: the lat-long map (width x height, formats/scene.md's
 * mapping, world frame) of the expansion, each band scaled by the window */
static void
reconstruct(const opts *o, const vx_shlight *sl)
{
	vx_err e = { 0, "" };
	int n = sl->order, nn = n * n;
	double c[3 * VX_SHLIGHT_MAX_COEF];
	vx_image img;

	for (int k = 0; k < 3; k++)
		for (int l = 0; l < n; l++)
			for (int m = -l; m <= l; m++) {
				int i = vx_sh_index(l, m);

				c[k * nn + i] = sl->c[k * nn + i] *
				    window(o->window, l, n);
			}
	if (vx_image_alloc(&img, o->width, o->height, 3, &e) != 0)
		tool_fail_err(&e);
	for (int y = 0; y < o->height; y++)
		for (int x = 0; x < o->width; x++) {
			double d[3];

			vx_env_image_to_dir(VX_ENV_LATLONG, o->width,
			    o->height, x + 0.5, y + 0.5, d);
			for (int k = 0; k < 3; k++)
				vx_image_set(&img, x, y, k, (float)
				    vx_sh_eval_sum(n, c + k * nn, d));
		}
	tool_write_pfm(o->recon, &img);
	vx_image_free(&img);
}

static void
print_hash(const vx_shlight *sl, char *buf, size_t n)
{
	if (sl->has_hash)
		snprintf(buf, n, "%016" PRIx64, sl->env_hash);
	else
		snprintf(buf, n, "none");
}

static void
print_text(const vx_shlight *sl)
{
	int n = sl->order, nn = n * n;
	char h[24];

	print_hash(sl, h, sizeof h);
	printf("# sh-rotate: order %d, phase %s, source %s\n", n,
	    sl->phase == VX_SHLIGHT_PHASE_CS ? "condon-shortley" : "none", h);
	printf("# rotation");
	for (int i = 0; i < 9; i++)
		printf(" %.17g", sl->rot[i / 3][i % 3]);
	printf("\n# l m r g b\n");
	for (int l = 0; l < n; l++)
		for (int m = -l; m <= l; m++) {
			int i = vx_sh_index(l, m);

			printf("%d %d %.17g %.17g %.17g\n", l, m, sl->c[i],
			    sl->c[nn + i], sl->c[2 * nn + i]);
		}
}

static void
print_json(const vx_shlight *sl)
{
	int n = sl->order, nn = n * n;
	char h[24];

	print_hash(sl, h, sizeof h);
	printf("{\"order\": %d, \"channels\": 3, \"phase\": \"%s\", "
	    "\"source_hash\": \"%s\",\n \"rotation\": [", n,
	    sl->phase == VX_SHLIGHT_PHASE_CS ? "condon-shortley" : "none", h);
	for (int i = 0; i < 9; i++)
		printf("%s%.17g", i ? ", " : "", sl->rot[i / 3][i % 3]);
	printf("],\n \"coefficients\": [");
	for (int i = 0; i < nn; i++)
		printf("%s\n  [%.17g, %.17g, %.17g]", i ? "," : "", sl->c[i],
		    sl->c[nn + i], sl->c[2 * nn + i]);
	printf("]}\n");
}

/* print_irr: Ramamoorthi and Hanrahan's nine L_lm (their basis, without
 * the Condon-Shortley phase), then the irradiance at the six axis
 * directions by vx_sh_irradiance */
static void
print_irr(const vx_shlight *sl)
{
	static const char *const name[9] = { "L00", "L1-1", "L10", "L11",
	    "L2-2", "L2-1", "L20", "L21", "L22" };
	static const double axis[6][3] = { { 1, 0, 0 }, { -1, 0, 0 },
	    { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
	static const char *const aname[6] = { "+x", "-x", "+y", "-y", "+z",
	    "-z" };
	int nn = sl->order * sl->order;
	double c[27], nph[27];

	for (int k = 0; k < 3; k++)
		for (int i = 0; i < 9; i++)
			c[9 * k + i] = sl->c[k * nn + i];
	memcpy(nph, c, sizeof c);
	if (sl->phase == VX_SHLIGHT_PHASE_CS)
		vx_sh_flip_phase(3, 3, nph);
	else
		vx_sh_flip_phase(3, 3, c);
	printf("# sh-rotate: Ramamoorthi-Hanrahan L_lm (basis without the "
	    "Condon-Shortley phase), r g b\n");
	for (int i = 0; i < 9; i++)
		printf("%s %.9g %.9g %.9g\n", name[i], nph[i], nph[9 + i],
		    nph[18 + i]);
	printf("# irradiance E(n) of the order-3 lighting, r g b\n");
	for (int a = 0; a < 6; a++) {
		double e[3];

		vx_sh_irradiance(3, 3, c, axis[a], e);
		printf("E %s %.9g %.9g %.9g\n", aname[a], e[0], e[1], e[2]);
	}
}

/* irr_error: the irradiance of the order-n lighting (vx_sh_irradiance)
 * against the exact quadrature of the map's pixels, sum of radiance x solid
 * angle x max(n.w, 0), at NERR normals of a Fibonacci sphere; prints the
 * relative RMS error sqrt(sum dE^2 / sum E^2) and the largest |dE| over the
 * mean E, all channels */
#define NERR 256
static void
irr_error(const vx_env *env, const vx_shlight *sl)
{
	size_t np = vx_env_npixel(env);
	double se = 0, s2 = 0, sum = 0, mx = 0;

	for (int k = 0; k < NERR; k++) {
		double z = 1 - (2 * k + 1.0) / NERR, r = sqrt(1 - z * z);
		double ph = k * M_PI * (3 - sqrt(5.0));
		double n[3] = { r * cos(ph), r * sin(ph), z }, ex[3] = { 0 };
		double esh[3];

		for (size_t i = 0; i < np; i++) {
			double d[3], om, rgb[3], c;

			vx_env_pixel(env, i, d, &om, rgb);
			c = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
			if (c > 0 && om > 0)
				for (int j = 0; j < 3; j++)
					ex[j] += rgb[j] * om * c;
		}
		vx_sh_irradiance(sl->order, 3, sl->c, n, esh);
		for (int j = 0; j < 3; j++) {
			double d = esh[j] - ex[j];

			se += d * d;
			s2 += ex[j] * ex[j];
			sum += ex[j];
			mx = fmax(mx, fabs(d));
		}
	}
	printf("order %d rms %.6g max %.6g normals %d\n", sl->order,
	    s2 > 0 ? sqrt(se / s2) : 0, sum > 0 ? mx / (sum / (3 * NERR)) :
	    0, NERR);
}

int
main(int argc, char **argv)
{
	vx_err e = { 0, "" };
	static double rot[5500];        /* vx_sh_rot_size(16) = 5456 */
	vx_shlight sl;
	vx_stream st;
	vx_env env;
	vx_chunk c;
	double t0, tproj = 0, trot = 0, r0[3][3];
	long idx = -1;
	int have_env, nout;
	size_t npix = 0;
	opts o;

	tool_init("sh-rotate", argc, argv);
	parse_args(&o, argc, argv);
	nout = o.print + o.json + o.irr + o.irrerr;
	vx_stream_init(&st);
	memset(&env, 0, sizeof env);
	if (o.in != NULL)
		tool_read_stream(&st, o.in);
	if (vx_shlight_from_stream(&sl, &st, &idx, &e) != 0)
		tool_fail_err(&e);
	have_env = project(&o, &env, &st, &sl, &npix, &tproj);
	if (!have_env && idx >= 0) {
		/* no light in the scene: the stream's SH lighting is turned
		 * further (truncated to --order when that is smaller) */
		int n0 = sl.order, n = o.order_set ? o.order : n0;
		double tmp[3 * VX_SHLIGHT_MAX_COEF];

		if (n > n0)
			tool_fail(VX_EUSAGE, "--order %d: the stream's SH "
			    "lighting has order %d", n, n0);
		for (int k = 0; k < 3; k++)
			memcpy(tmp + k * n * n, sl.c + k * n0 * n0,
			    sizeof(double) * n * n);
		memcpy(sl.c, tmp, sizeof(double) * 3 * n * n);
		sl.order = n;
		if (sl.phase == VX_SHLIGHT_PHASE_NONE) {
			vx_sh_flip_phase(n, 3, sl.c);
			sl.phase = VX_SHLIGHT_PHASE_CS;
		}
	} else if (!have_env)
		tool_fail(VX_EUSAGE, "no environment: the scene has no "
		    "environment or sky light and the stream no SH lighting "
		    "(give --env FILE)");
	/* rotate: the new rotation after the one already applied */
	memcpy(r0, sl.rot, sizeof r0);
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			sl.rot[i][j] = o.r[i][0] * r0[0][j] +
			    o.r[i][1] * r0[1][j] + o.r[i][2] * r0[2][j];
	if (o.nrot) {
		t0 = vx_par_seconds();
		vx_sh_rot_from_matrix(sl.order, o.r, rot);
		vx_sh_rot_apply(sl.order, rot, 3, sl.c, sl.c);
		trot = vx_par_seconds() - t0;
	}
	if (o.explain) {
		fprintf(stderr, "sh-rotate: source %s%s (%zu pixels), order %d "
		    "(%d coefficients x 3), rotation %s; output %s%s%s\n",
		    have_env ? (o.env ? o.env : "the scene's light") :
		    "the stream's SH lighting", have_env > 1 ? "s, summed" : "",
		    npix, sl.order,
		    sl.order * sl.order, o.nrot ? "given" : "none",
		    o.print ? "text" : o.json ? "JSON" : o.irr ?
		    "irradiance coefficients" : "SHLC chunk",
		    o.recon ? ", reconstruction " : "", o.recon ? o.recon : "");
	}
	if (o.recon != NULL)
		reconstruct(&o, &sl);
	if (o.print)
		print_text(&sl);
	else if (o.json)
		print_json(&sl);
	else if (o.irr)
		print_irr(&sl);
	else if (o.irrerr)
		irr_error(&env, &sl);
	if (!nout && (o.recon == NULL || o.out_set)) {
		memset(&c, 0, sizeof c);
		if (vx_shlight_to_chunk(&sl, &c, &e) != 0)
			tool_fail_err(&e);
		if (idx >= 0)
			vx_stream_replace(&st, (size_t)idx, &c);
		else if (vx_stream_append(&st, &c, &e) != 0)
			tool_fail_err(&e);
		tool_write_stream(&st, o.out);
	}
	if (o.stats)
		fprintf(stderr, "sh-rotate: order %d: projection %.6f s (%zu "
		    "pixels), rotation %.6f s\n", sl.order, tproj, npix, trot);
	vx_env_free(&env);
	vx_stream_free(&st);
	return tool_finish();
}
