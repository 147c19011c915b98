/* test_tfimport.c: transfer-function imports (vx_tfimport.h): one
 * function written by hand in each format (ParaView JSON, Slicer .vp and
 * .vp.json, a miter txf) reads into the same lists; miter's 2-D txf into
 * the table (both axis orders, uchar unquantized as teem does); VTK's
 * midpoint and sharpness made piecewise linear (exact at sharpness 0 and
 * 1, within the stated tolerance between); format detection; and each
 * malformed file refused with its message. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include "helper_tmp.h"

#include "tf_priv.h"
#include "vx_tfimport.h"


/* put: a file in helper_tmpdir holding text; its path (static, 4 in
 * turn). */
static const char *
put(const char *name, const char *text, size_t n)
{
	static char s[4][256];
	static int k;
	FILE *f;

	k = (k + 1) % 4;
	snprintf(s[k], sizeof s[k], "%s/%s", helper_tmpdir, name);
	assert_non_null(f = fopen(s[k], "wb"));
	assert_int_equal(fwrite(text, 1, n, f), n);
	assert_int_equal(fclose(f), 0);
	return s[k];
}

static const char *
puts_(const char *name, const char *text)
{
	return put(name, text, strlen(text));
}

/* The oracle: colour red -> green -> blue-ish and opacity 0 -> 0.5 -> 1
 * at x = 0, 100, 200, every number exact in float (miter's samples). */
static const double ox[] = { 0, 100, 200 };
static const double ocolor[] = { 1, 0, 0.25, 0, 1, 0.5, 0.25, 0.5, 1 };
static const double oalpha[] = { 0, 0.5, 1 };
/* Slicer's gradient opacity in those files */
static const double gx[] = { 0, 255 }, gy[] = { 0.25, 1 };

static const char pv_json[] =
    "[\n  {\n    \"ColorSpace\" : \"RGB\",\n    \"Name\" : \"hand\",\n"
    "    \"NanColor\" : [1, 1, 0],\n"
    "    \"RGBPoints\" : [0, 1, 0, 0.25, 100, 0, 1, 0.5, 200, 0.25, 0.5, 1],\n"
    "    \"Points\" : [0, 0, 0.5, 0, 100, 0.5, 0.5, 0, 200, 1, 0.5, 0]\n"
    "  },\n  { \"Name\" : \"second\", \"RGBPoints\" : [0, 0, 0, 0] }\n]\n";
static const char slicer_vp[] =
    "1\n1\n0.7\n0.1\n0.2\n10\n"
    "6 0 0 100 0.5 200 1\n"
    "4 0 0.25 255 1\n"
    "12 0 1 0 0.25 100 0 1 0.5 200 0.25 0.5 1\n";
static const char slicer_json[] =
    "{\n\"@schema\": \"https://raw.githubusercontent.com/slicer/slicer/main/"
    "Modules/Loadable/VolumeRendering/Resources/Schema/volume-property-"
    "schema-v1.0.0.json#\",\n\"volumeProperties\": [ {\n"
    " \"effectiveRange\": [0.0, 200.0], \"isoSurfaceValues\": [],\n"
    " \"independentComponents\": true, \"interpolationType\": \"linear\",\n"
    " \"useClippedVoxelIntensity\": false, \"clippedVoxelIntensity\": 0.0,\n"
    " \"scatteringAnisotropy\": 0.0,\n \"components\": [ {\n"
    "  \"componentWeight\": 1.0, \"shade\": true,\n"
    "  \"lighting\": {\"diffuse\": 0.7, \"ambient\": 0.1, \"specular\": 0.2,"
    " \"specularPower\": 10.0},\n"
    "  \"disableGradientOpacity\": false,\n"
    "  \"scalarOpacityUnitDistance\": 0.5,\n"
    "  \"rgbTransferFunction\": {\"type\": \"colorTransferFunction\", "
    "\"points\": [\n"
    "   {\"x\": 0.0, \"color\": [1.0, 0.0, 0.25], \"midpoint\": 0.5, "
    "\"sharpness\": 0.0},\n"
    "   {\"x\": 100.0, \"color\": [0.0, 1.0, 0.5], \"midpoint\": 0.5, "
    "\"sharpness\": 0.0},\n"
    "   {\"x\": 200.0, \"color\": [0.25, 0.5, 1.0], \"midpoint\": 0.5, "
    "\"sharpness\": 0.0}]},\n"
    "  \"scalarOpacity\": {\"type\": \"piecewiseLinearFunction\", "
    "\"points\": [\n"
    "   {\"x\": 0.0, \"y\": 0.0, \"midpoint\": 0.5, \"sharpness\": 0.0},\n"
    "   {\"x\": 100.0, \"y\": 0.5, \"midpoint\": 0.5, \"sharpness\": 0.0},\n"
    "   {\"x\": 200.0, \"y\": 1.0, \"midpoint\": 0.5, \"sharpness\": 0.0}]},\n"
    "  \"gradientOpacity\": {\"type\": \"piecewiseLinearFunction\", "
    "\"points\": [\n"
    "   {\"x\": 0.0, \"y\": 0.25, \"midpoint\": 0.5, \"sharpness\": 0.0},\n"
    "   {\"x\": 255.0, \"y\": 1.0, \"midpoint\": 0.5, \"sharpness\": 0.0}]}\n"
    " } ]\n} ]\n}\n";
/* three cells over [-50, 250]: their centres are 0, 100, 200 */
static const char miter_txf[] =
    "NRRD0004\n# a miter txf\ntype: float\ndimension: 2\nsizes: 4 3\n"
    "kinds: ??? domain\ncenters: ??? cell\n"
    "axis mins: nan -50\naxis maxs: nan 250\n"
    "labels: \"RGBA\" \"gage(scalar:v)\"\nencoding: ascii\n\n"
    "1 0 0.25 0\n0 1 0.5 0.5\n0.25 0.5 1 1\n";

static void
same_list(const vx_tf_list *l, int n, int dim, const double *x,
    const double *y)
{
	assert_int_equal(l->n, n);
	assert_int_equal(l->dim, dim);
	for (int i = 0; i < n; i++) {
		assert_true(l->x[i] == x[i]);
		for (int c = 0; c < dim; c++)
			assert_true(l->y[dim * i + c] == y[dim * i + c]);
	}
}

/* The same function in each format, read with the format named and by
 * detection: the oracle's lists, bit for bit. */
static void
same_in_each(void **state)
{
	static const struct {
		const char *name, *text;
		vx_tf_format fmt;
		int gradient;       /* Slicer's files carry gy */
		double ref_step;
	} t[] = {
		{ "pv.json", pv_json, VX_TF_FORMAT_PARAVIEW, 0, 0 },
		{ "hand.vp", slicer_vp, VX_TF_FORMAT_SLICER, 1, 0 },
		{ "hand.vp.json", slicer_json, VX_TF_FORMAT_SLICER, 1, 0.5 },
		{ "hand.txf", miter_txf, VX_TF_FORMAT_MITER, 0, 0 },
	};
	vx_err e;

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++)
		for (int detect = 0; detect < 2; detect++) {
			const char *p = puts_(t[i].name, t[i].text);
			vx_tf tf;

			if (vx_tf_import(p, detect ? VX_TF_FORMAT_AUTO : t[i].fmt,
			    &tf, &e) != 0)
				fail_msg("%s: %s", t[i].name, e.msg);
			same_list(&tf.color, 3, 3, ox, ocolor);
			same_list(&tf.opacity, 3, 1, ox, oalpha);
			if (t[i].gradient)
				same_list(&tf.gradient, 2, 1, gx, gy);
			else
				assert_int_equal(tf.gradient.n, 0);
			assert_int_equal(tf.has_table, 0);
			assert_true(tf.ref_step == t[i].ref_step);
			assert_int_equal(vx_tf_check(&tf, &e), 0);
			vx_tf_free(&tf);
		}
}

/* A 2-D txf (value x gradient magnitude) becomes the table; written with
 * the axes the other way round it gives the same table; uchar samples
 * are (v + 0.5) / 256 as teem's nrrdUnquantize has them. */
static void
miter_table(void **state)
{
	static const char vg[] =
	    "NRRD0005\ntype: double\ndimension: 3\nsizes: 4 3 2\n"
	    "axis mins: nan 0 0\naxis maxs: nan 30 2\n"
	    "labels: \"RGBA\" \"gage(v)\" \"gage(gm)\"\nencoding: ascii\n\n"
	    "0 0 0 0  0.25 0 0 0.125  0.5 0 0 0.25\n"
	    "0 1 0 0.5  0.25 1 0 0.625  0.5 1 0 0.75\n";
	/* the same with gm along axis 1: sample (c, g, v) */
	static const char gv[] =
	    "NRRD0005\ntype: double\ndimension: 3\nsizes: 4 2 3\n"
	    "axis mins: nan 0 0\naxis maxs: nan 2 30\n"
	    "labels: \"RGBA\" \"gage(gm)\" \"gage(v)\"\nencoding: ascii\n\n"
	    "0 0 0 0  0 1 0 0.5\n0.25 0 0 0.125  0.25 1 0 0.625\n"
	    "0.5 0 0 0.25  0.5 1 0 0.75\n";
	static const float want[] = {
		0, 0, 0, 0, 0.25f, 0, 0, 0.125f, 0.5f, 0, 0, 0.25f,
		0, 1, 0, 0.5f, 0.25f, 1, 0, 0.625f, 0.5f, 1, 0, 0.75f,
	};
	static const char u8[] =
	    "NRRD0004\ntype: uchar\ndimension: 2\nsizes: 1 2\n"
	    "centers: ??? node\naxis mins: nan 10\naxis maxs: nan 20\n"
	    "labels: \"A\" \"gage(value)\"\nencoding: ascii\n\n0 255\n";
	static const double u8x[] = { 10, 20 };
	static const double u8y[] = { 0.5 / 256, 255.5 / 256 };
	const char *text[2] = { vg, gv };
	vx_err e;
	vx_tf tf;

	(void)state;
	for (int k = 0; k < 2; k++) {
		if (vx_tf_import(puts_("t.nrrd", text[k]), VX_TF_FORMAT_AUTO, &tf,
		    &e) != 0)
			fail_msg("%d: %s", k, e.msg);
		assert_int_equal(tf.has_table, 1);
		assert_int_equal(tf.size[0], 3);
		assert_int_equal(tf.size[1], 2);
		assert_true(tf.vrange[0] == 0 && tf.vrange[1] == 30);
		assert_true(tf.grange[0] == 0 && tf.grange[1] == 2);
		assert_memory_equal(tf.rgba, want, sizeof want);
		assert_int_equal(tf.color.n + tf.opacity.n, 0);
		vx_tf_free(&tf);
	}
	if (vx_tf_import(puts_("u8.nrrd", u8), VX_TF_FORMAT_MITER, &tf,
	    &e) != 0)
		fail_msg("%s", e.msg);
	same_list(&tf.opacity, 2, 1, u8x, u8y);   /* node centred */
	assert_int_equal(tf.color.n, 0);
	vx_tf_free(&tf);
}

/* VTK's segments: midpoint with sharpness 0 inserts one point and is
 * exact; sharpness 1 is a step at the midpoint (exact); between, the
 * linear form stays within the tolerance of VTK's curve (the oracle is
 * vx_tfi_vtk_eval, VTK's formula) checked at 2000 points per segment. */
static void
sharpness(void **state)
{
	static const double mids[] = { 0.5, 0.25, 0.8, 0, 1 };
	static const double sharps[] = { 0, 0.005, 0.2, 0.5, 0.9, 0.995, 1 };
	const double x[] = { 10, 20, 20, 40 }, y[] = { 0, 1, 0.25, 0.75 };
	vx_err e;

	(void)state;
	for (size_t a = 0; a < sizeof mids / sizeof mids[0]; a++)
		for (size_t b = 0; b < sizeof sharps / sizeof sharps[0]; b++) {
			double mid[4], sh[4], worst = 0;
			vx_tfi_pts p;
			vx_tf_list l = { 0 };

			for (int i = 0; i < 4; i++) {
				mid[i] = mids[a];
				sh[i] = sharps[b];
			}
			vx_tfi_pts_init(&p, 1);
			assert_int_equal(vx_tfi_vtk(&p, 4, 1, x, y, mid, sh, &e), 0);
			assert_int_equal(vx_tfi_set(&l, &p, &e), 0);
			for (int s = 0; s < 3; s++) {
				if (x[s + 1] == x[s])
					continue;
				/* the segment's end is the next node (a step's
				 * left value there is not the list's) */
				for (int k = 0; k < 2000; k++) {
					double u = k / 2000.0, got, want;

					vx_tf_list_eval(&l, x[s] + u * (x[s + 1] - x[s]),
					    &got);
					want = vx_tfi_vtk_eval(y[s], y[s + 1], mid[s],
					    sh[s], u);
					worst = fmax(worst, fabs(got - want));
				}
			}
			if (sharps[b] < 0.01 || sharps[b] > 0.99) {
				/* exact but for rounding, and the step's point
				 * when the midpoint falls between samples */
				assert_true(worst <= 1e-12 || (sharps[b] > 0.99 &&
				    worst == 0));
				assert_true(p.n <= 4 + 3 * 2);
			} else
				assert_true(worst <= 2 * VX_TFI_SHARP_TOL);
			vx_tfi_pts_free(&p);
			vx_tf_list_free(&l);
		}
}

/* ParaView presets in HSV, Lab and Diverging space: the colour list
 * against VTK 9.1's own vtkColorTransferFunction::GetColor (python3-vtk9,
 * SetColorSpace 1, 2, 3, the same four nodes; the oracle values below
 * were printed by it), within twice the tolerance: the interpolation in
 * each space, the white Moreland's diverging maps put between two
 * saturated ends, VTK's gamut clipping. */
static void
color_spaces(void **state)
{
	static const char fmt[] = "[{\"ColorSpace\": \"%s\", \"RGBPoints\": "
	    "[0, 0.231373, 0.298039, 0.752941, 1, 0.705882, 0.0156863, 0.14902,"
	    " 2, 0.9, 0.9, 0.2, 3, 0.1, 0.8, 0.9]}]";
	static const double xs[9] = { 0, 0.25, 0.5, 0.75, 1, 1.3, 1.5, 2.5, 3 };
	static const struct {
		const char *space;
		double rgb[9][3];
	} t[] = {
		{ "HSV", {
		    { 0.231373000, 0.298039000, 0.752941000 },
		    { 0.376427247, 0.174935991, 0.741176250 },
		    { 0.631628914, 0.120175872, 0.729411500 },
		    { 0.717646750, 0.067092641, 0.507414626 },
		    { 0.705882000, 0.015686300, 0.149020000 },
		    { 0.764117400, 0.178380600, 0.062827456 },
		    { 0.802941000, 0.382461267, 0.098137252 },
		    { 0.150000000, 0.900000000, 0.196875000 },
		    { 0.100000000, 0.800000000, 0.900000000 } } },
		{ "Lab", {
		    { 0.231373000, 0.298039000, 0.752941000 },
		    { 0.466813343, 0.253075163, 0.595160089 },
		    { 0.580662530, 0.202498456, 0.443042772 },
		    { 0.653883510, 0.138599115, 0.296020041 },
		    { 0.705879693, 0.015812728, 0.149021126 },
		    { 0.784719293, 0.380435274, 0.172776605 },
		    { 0.827912260, 0.534596168, 0.184849346 },
		    { 0.682182506, 0.847309663, 0.593722474 },
		    { 0.100116914, 0.800010803, 0.900005052 } } },
		{ "Diverging", {
		    { 0.231373000, 0.298039000, 0.752941000 },
		    { 0.553318141, 0.688634521, 0.995187915 },
		    { 0.865395197, 0.865410210, 0.865395561 },
		    { 0.958417217, 0.603116240, 0.481685120 },
		    { 0.705879693, 0.015812728, 0.149021126 },
		    { 1.000000000, 0.805209337, 0.552883485 },
		    { 0.999982963, 1.000000000, 0.999983376 },
		    { 0.999982963, 1.000000000, 0.999983376 },
		    { 0.100116914, 0.800010803, 0.900005052 } } },
	};
	char text[512];
	vx_err e;

	(void)state;
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		vx_tf tf;

		snprintf(text, sizeof text, fmt, t[i].space);
		if (vx_tf_import(puts_("cs.json", text), VX_TF_FORMAT_AUTO, &tf,
		    &e) != 0)
			fail_msg("%s: %s", t[i].space, e.msg);
		assert_true(tf.color.n > 4);     /* points were inserted */
		for (int k = 0; k < 9; k++) {
			double c[3];

			vx_tf_list_eval(&tf.color, xs[k], c);
			for (int a = 0; a < 3; a++)
				if (fabs(c[a] - t[i].rgb[k][a]) > 2 * VX_TFI_SHARP_TOL)
					fail_msg("%s at %g: channel %d is %.9f, VTK "
					    "%.9f", t[i].space, xs[k], a, c[a],
					    t[i].rgb[k][a]);
		}
		vx_tf_free(&tf);
	}
}

/* VTK's midpoint and sharpness on an opacity function, against VTK 9.1's
 * vtkPiecewiseFunction::GetValue (python3-vtk9; nodes (10, 0, 0.25, 0.6),
 * (20, 1, 0.5, 0), (40, 0.25, 0.8, 0.995), (50, 0.75)): the formula to
 * rounding, the list within twice the tolerance. */
static void
vtk_piecewise(void **state)
{
	static const double x[] = { 10, 20, 40, 50 }, y[] = { 0, 1, 0.25, 0.75 };
	static const double mid[] = { 0.25, 0.5, 0.8, 0.5 };
	static const double sh[] = { 0.6, 0, 0.995, 0 };
	static const double t[][2] = {
		{ 10, 0.0 }, { 11, 0.00032888729984502347 }, { 12.5, 0.5 },
		{ 13, 0.7405457208130601 }, { 15, 0.9867830708469435 },
		{ 19.9, 0.9999999999999848 }, { 20, 1.0 }, { 25, 0.8125 },
		{ 30, 0.625 }, { 35, 0.4375 }, { 36, 0.39999999999999997 },
		{ 39, 0.28750000000000003 }, { 42, 0.25 }, { 47.5, 0.25 },
		{ 50, 0.75 },
	};
	vx_tf_list l = { 0 };
	vx_tfi_pts p;
	vx_err e;

	(void)state;
	vx_tfi_pts_init(&p, 1);
	assert_int_equal(vx_tfi_vtk(&p, 4, 1, x, y, mid, sh, &e), 0);
	assert_int_equal(vx_tfi_set(&l, &p, &e), 0);
	for (size_t k = 0; k < sizeof t / sizeof t[0]; k++) {
		int s = t[k][0] >= 40 ? 2 : t[k][0] >= 20 ? 1 : 0;
		double u = (t[k][0] - x[s]) / (x[s + 1] - x[s]), got;

		assert_true(fabs(vx_tfi_vtk_eval(y[s], y[s + 1], mid[s], sh[s],
		    u) - t[k][1]) < 1e-12);
		vx_tf_list_eval(&l, t[k][0], &got);
		assert_true(fabs(got - t[k][1]) <= 2 * VX_TFI_SHARP_TOL);
	}
	vx_tfi_pts_free(&p);
	vx_tf_list_free(&l);
}

/* An opacity step at sharpness 1 and an inserted midpoint, read through
 * the ParaView reader: the points themselves. */
static void
paraview_points(void **state)
{
	static const char text[] =
	    "{\"RGBPoints\": [0, 0, 0, 0, 1, 1, 1, 1],\n"
	    " \"Points\": [0, 0, 0.25, 0, 10, 1, 0.5, 1, 20, 0, 0.5, 0]}";
	static const double x[] = { 0, 2.5, 10, 15, 15, 20 };
	static const double y[] = { 0, 0.5, 1, 1, 0, 0 };
	static const char ramp[] = "[{\"RGBPoints\": [5, 0, 0, 0, 7, 1, 1, 1]}]";
	static const double rx[] = { 5, 7 }, ry[] = { 0, 1 };
	vx_err e;
	vx_tf tf;

	(void)state;
	assert_int_equal(vx_tf_import(puts_("p.json", text),
	    VX_TF_FORMAT_PARAVIEW, &tf, &e), 0);
	same_list(&tf.opacity, 6, 1, x, y);
	vx_tf_free(&tf);
	/* no Points: ParaView's default ramp over the colours' range */
	assert_int_equal(vx_tf_import(puts_("r.json", ramp), VX_TF_FORMAT_AUTO,
	    &tf, &e), 0);
	same_list(&tf.opacity, 2, 1, rx, ry);
	vx_tf_free(&tf);
}

/* Malformed files: the code and a part of the one-line message, which
 * starts with the file's path. */
static void
malformed(void **state)
{
	static char deep[200];
	static const struct {
		const char *name, *text;
		vx_tf_format fmt;
		int code;
		const char *msg;
	} t[] = {
		/* JSON, ParaView */
		{ "cut.json", "[{\"RGBPoints\": [0, 1, 0, 0", VX_TF_FORMAT_AUTO,
		    VX_EDATA, "line 1, column 27: the text ends inside" },
		{ "deep.json", deep, VX_TF_FORMAT_AUTO, VX_EDATA,
		    "nested too deep" },
		{ "nan.json", "[{\"RGBPoints\": [0, 1, 0, NaN]}]",
		    VX_TF_FORMAT_PARAVIEW, VX_EDATA, "column 26: not a JSON value" },
		{ "inf.json", "[{\"RGBPoints\": [0, 1, 0, 1e999]}]",
		    VX_TF_FORMAT_PARAVIEW, VX_EDATA, "beyond the double range" },
		{ "count.json", "[{\"RGBPoints\": [0, 1, 0, 0, 1, 1]}]",
		    VX_TF_FORMAT_PARAVIEW, VX_EDATA,
		    "key \"RGBPoints\": 6 numbers, not a positive multiple of 4" },
		{ "range.json", "[{\"RGBPoints\": [0, 1, 0, 0,\n 1, 1, 1.5, 1]}]",
		    VX_TF_FORMAT_PARAVIEW, VX_EDATA,
		    "line 1: key \"RGBPoints\" element 6: 1.5 is outside [0, 1]" },
		{ "down.json", "[{\"RGBPoints\": [0, 1, 0, 0, -1, 1, 1, 1]}]",
		    VX_TF_FORMAT_PARAVIEW, VX_EDATA, "key \"RGBPoints\" element 4: "
		    "x -1 is less than the one before it (0)" },
		{ "mid.json", "[{\"Points\": [0, 0, 1.5, 0, 1, 1, 0.5, 0]}]",
		    VX_TF_FORMAT_PARAVIEW, VX_EDATA, "element 2: 1.5 is outside" },
		{ "word.json", "[{\"Points\": [0, 0, 0.5, \"0\"]}]",
		    VX_TF_FORMAT_PARAVIEW, VX_EDATA,
		    "key \"Points\" element 3: a string, not a number" },
		{ "space.json", "[{\"ColorSpace\": \"Step\", \"RGBPoints\": "
		    "[0, 1, 0, 0]}]", VX_TF_FORMAT_PARAVIEW, VX_EDATA,
		    "\"Step\" is not supported" },
		/* found by fuzz_tf: a decoded newline reached the message */
		{ "csnl.json", "[{\"ColorSpace\": \"a\\nb\\u001b\", \"Points\": "
		    "[0, 0, 0.5, 0]}]", VX_TF_FORMAT_PARAVIEW, VX_EDATA,
		    "\"a?b?\" is not supported" },
		{ "empty.json", "[]", VX_TF_FORMAT_PARAVIEW, VX_EDATA,
		    "an empty array" },
		{ "none.json", "[{\"Name\": \"x\"}]", VX_TF_FORMAT_PARAVIEW,
		    VX_EDATA, "neither \"RGBPoints\" nor \"Points\"" },
		{ "dup.json", "[{\"Points\": [0,0,0.5,0], \"Points\": [0,1,0.5,0]}]",
		    VX_TF_FORMAT_PARAVIEW, VX_EDATA, "given twice" },
		{ "after.json", "[{\"Points\": [0,0,0.5,0]}] x",
		    VX_TF_FORMAT_PARAVIEW, VX_EDATA, "text after the value" },
		{ "ctl.json", "[{\"Na\tme\": 1}]", VX_TF_FORMAT_PARAVIEW, VX_EDATA,
		    "control character" },
		{ "lead0.json", "[{\"Points\": [00, 0, 0.5, 0]}]",
		    VX_TF_FORMAT_PARAVIEW, VX_EDATA, "expected ',' or ']'" },
		/* Slicer .vp */
		{ "short.vp", "1\n1\n0.7\n0.1\n0.2\n10\n8 0 0 100 1 200 1\n",
		    VX_TF_FORMAT_SLICER, VX_EDATA, "line 7 (scalar opacity): the "
		    "count is 8 but 6 numbers follow it" },
		{ "huge.vp", "1\n1\n0.7\n0.1\n0.2\n10\n99999999998 0 0\n",
		    VX_TF_FORMAT_SLICER, VX_EDATA, "points (at most 65536)" },
		{ "longcount.vp", "1\n1\n0.7\n0.1\n0.2\n10\n20 0 0 1 1\n",
		    VX_TF_FORMAT_AUTO, VX_EDATA, "more than the line holds" },
		{ "nan.vp", "1\n1\n0.7\n0.1\n0.2\n10\n4 0 nan 1 1\n",
		    VX_TF_FORMAT_SLICER, VX_EDATA,
		    "line 7 (scalar opacity): number 2 'nan' is not a finite" },
		{ "inf.vp", "1\n1\n0.7\n0.1\n0.2\n10\n4 0 0 1 1\n4 0 1 1e400 1\n",
		    VX_TF_FORMAT_SLICER, VX_EDATA,
		    "line 8 (gradient opacity): number 3 '1e400'" },
		{ "down.vp", "1\n1\n0.7\n0.1\n0.2\n10\n4 5 0 1 1\n",
		    VX_TF_FORMAT_SLICER, VX_EDATA,
		    "number 3: x 1 is less than the one before it (5)" },
		{ "range.vp", "1\n1\n0.7\n0.1\n0.2\n10\n4 0 0 1 1\n\n"
		    "6 0 1 0 0 1 1\n", VX_TF_FORMAT_SLICER, VX_EDATA,
		    "line 9 (color transfer function): the count 6 is not a "
		    "multiple of 4" },
		{ "over.vp", "1\n1\n0.7\n0.1\n0.2\n10\n4 0 0 1 1.5\n",
		    VX_TF_FORMAT_SLICER, VX_EDATA, "number 4: 1.5 is outside" },
		{ "more.vp", "1\n1\n0.7\n0.1\n0.2\n10\n4 0 0 1 1 2\n",
		    VX_TF_FORMAT_SLICER, VX_EDATA, "more numbers than the count" },
		{ "interp.vp", "7\n1\n0.7\n0.1\n0.2\n10\n4 0 0 1 1\n",
		    VX_TF_FORMAT_SLICER, VX_EDATA, "line 1 (interpolation type)" },
		{ "noopacity.vp", "1\n1\n0.7\n0.1\n0.2\n10\n",
		    VX_TF_FORMAT_SLICER, VX_EDATA, "no scalar opacity" },
		{ "extra.vp", "1\n1\n0.7\n0.1\n0.2\n10\n2 0 1\n\n\nmore\n",
		    VX_TF_FORMAT_SLICER, VX_EDATA, "line 10: text after" },
		/* Slicer .vp.json */
		{ "novp.vp.json", "{\"components\": []}", VX_TF_FORMAT_SLICER,
		    VX_EDATA, "no key \"volumeProperties\"" },
		{ "color2.vp.json", "{\"volumeProperties\": [{\"components\": [{"
		    "\"scalarOpacity\": {\"points\": [{\"x\": 0, \"y\": 1}]},\n"
		    "\"rgbTransferFunction\": {\"points\": [{\"x\": 0, \"color\": "
		    "[1, 0]}]}}]}]}", VX_TF_FORMAT_AUTO, VX_EDATA,
		    "line 2: key \"rgbTransferFunction\" point 0: \"color\" has 2 "
		    "numbers, not 3" },
		{ "y.vp.json", "{\"volumeProperties\": [{\"components\": [{"
		    "\"scalarOpacity\": {\"points\": [{\"x\": 0, \"y\": 2}]}}]}]}",
		    VX_TF_FORMAT_SLICER, VX_EDATA, "point 0: y 2 is outside" },
		{ "nox.vp.json", "{\"volumeProperties\": [{\"components\": [{"
		    "\"scalarOpacity\": {\"points\": [{\"y\": 1}]}}]}]}",
		    VX_TF_FORMAT_SLICER, VX_EDATA, "point 0: line 1: no key \"x\"" },
		{ "noop.vp.json", "{\"volumeProperties\": [{\"components\": "
		    "[{}]}]}", VX_TF_FORMAT_SLICER, VX_EDATA, "no scalar opacity" },
		/* miter txf */
		{ "axis0.nrrd", "NRRD0004\ntype: float\ndimension: 2\n"
		    "sizes: 4 2\naxis mins: nan 0\naxis maxs: nan 1\n"
		    "labels: \"RGBX\" \"gage(v)\"\nencoding: ascii\n\n"
		    "0 0 0 0 1 1 1 1\n", VX_TF_FORMAT_AUTO, VX_EDATA,
		    "axis 0: label \"RGBX\" with size 4" },
		{ "axis0size.nrrd", "NRRD0004\ntype: float\ndimension: 2\n"
		    "sizes: 4 2\naxis mins: nan 0\naxis maxs: nan 1\n"
		    "labels: \"RGB\" \"gage(v)\"\nencoding: ascii\n\n"
		    "0 0 0 0 1 1 1 1\n", VX_TF_FORMAT_MITER, VX_EDATA,
		    "label \"RGB\" with size 4" },
		{ "noalpha.nrrd", "NRRD0004\ntype: float\ndimension: 2\n"
		    "sizes: 3 2\naxis mins: nan 0\naxis maxs: nan 1\n"
		    "labels: \"RGB\" \"gage(v)\"\nencoding: ascii\n\n"
		    "0 0 0 1 1 1\n", VX_TF_FORMAT_MITER, VX_EDATA, "has no A" },
		{ "var.nrrd", "NRRD0004\ntype: float\ndimension: 2\n"
		    "sizes: 1 2\naxis mins: nan 0\naxis maxs: nan 1\n"
		    "labels: \"A\" \"mite(ndotv)\"\nencoding: ascii\n\n0 1\n",
		    VX_TF_FORMAT_MITER, VX_EDATA, "label \"mite(ndotv)\"" },
		{ "mins.nrrd", "NRRD0004\ntype: float\ndimension: 2\n"
		    "sizes: 1 2\naxis mins: nan nan\naxis maxs: nan 1\n"
		    "labels: \"A\" \"gage(v)\"\nencoding: ascii\n\n0 1\n",
		    VX_TF_FORMAT_MITER, VX_EDATA, "axis 1: [axis min, axis max]" },
		{ "type.nrrd", "NRRD0004\ntype: short\ndimension: 2\n"
		    "sizes: 1 2\naxis mins: nan 0\naxis maxs: nan 1\n"
		    "labels: \"A\" \"gage(v)\"\nencoding: ascii\n\n0 1\n",
		    VX_TF_FORMAT_MITER, VX_EDATA, "float, double or uchar" },
		{ "dim.nrrd", "NRRD0004\ntype: float\ndimension: 1\nsizes: 4\n"
		    "encoding: ascii\n\n0 0 0 0\n", VX_TF_FORMAT_MITER, VX_EDATA,
		    "field 'dimension'" },
		{ "value.nrrd", "NRRD0004\ntype: float\ndimension: 2\n"
		    "sizes: 1 2\naxis mins: nan 0\naxis maxs: nan 1\n"
		    "labels: \"A\" \"gage(v)\"\nencoding: ascii\n\n0 1.5\n",
		    VX_TF_FORMAT_MITER, VX_EDATA, "A = 1.5 is outside [0, 1]" },
		{ "cut.nrrd", "NRRD0004\ntype: float\ndimension: 2\n"
		    "sizes: 1 2\naxis mins: nan 0\naxis maxs: nan 1\n"
		    "labels: \"A\" \"gage(v)\"\nencoding: raw\nendian: little\n\n"
		    "\0\0\0", VX_TF_FORMAT_MITER, VX_EDATA, "truncated" },
		/* anything else */
		{ "text.txt", "hello\n", VX_TF_FORMAT_AUTO, VX_EDATA,
		    "not a transfer function" },
		{ "empty.vp", "", VX_TF_FORMAT_AUTO, VX_ENOINPUT, "empty file" },
	};
	vx_err e;
	vx_tf tf;

	(void)state;
	for (int i = 0; i < 40; i++) {
		deep[2 * i] = '[';
		deep[2 * i + 1] = ' ';
	}
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		/* the one file holding NUL bytes is sized by hand */
		size_t n = strcmp(t[i].name, "cut.nrrd") == 0 ?
		    strlen(t[i].text) + 3 : strlen(t[i].text);
		const char *p = put(t[i].name, t[i].text, n);
		int rc = vx_tf_import(p, t[i].fmt, &tf, &e);

		if (rc != t[i].code || strstr(e.msg, t[i].msg) == NULL ||
		    strncmp(e.msg, p, strlen(p)) != 0 || strchr(e.msg, '\n'))
			fail_msg("%s: rc %d, message '%s', want '%s'", t[i].name,
			    rc, e.msg, t[i].msg);
		assert_int_equal(tf.color.n + tf.opacity.n + tf.gradient.n, 0);
		assert_null(tf.rgba);
	}
	assert_int_equal(vx_tf_import("/nonexistent/x.vp", VX_TF_FORMAT_AUTO,
	    &tf, &e), VX_ENOINPUT);
	assert_int_equal(vx_tf_import(helper_tmpdir, VX_TF_FORMAT_AUTO, &tf,
	    &e), VX_ENOINPUT);
	assert_non_null(strstr(e.msg, "is a directory"));
}

/* The JSON reader alone: escapes, surrogates, nesting at the limit,
 * the value bound, lines in messages. */
static void
json(void **state)
{
	static const char text[] = "\xef\xbb\xbf {\"a\\u00e9\\ud83d\\ude00\": "
	    "[1, -0.5e1, true, false, null, \"\\\"\\\\\\/\\b\\f\\n\\r\\t\"],"
	    "\n \"b\": {}}";
	const vx_json_node *a, *c;
	vx_json j;
	vx_err e;
	int dup;

	(void)state;
	assert_int_equal(vx_json_parse(&j, text, sizeof text - 1, 4, 100, &e),
	    0);
	a = vx_json_get(&j, vx_json_at(&j, 0), "a\xc3\xa9\xf0\x9f\x98\x80",
	    &dup);
	assert_non_null(a);
	assert_int_equal(dup, 0);
	assert_int_equal(a->n, 6);
	c = vx_json_at(&j, a->first);
	assert_true(c->num == 1);
	c = vx_json_at(&j, c->next);
	assert_true(c->num == -5);
	c = vx_json_at(&j, vx_json_at(&j, vx_json_at(&j, c->next)->next)->next);
	assert_int_equal(c->type, VX_JSON_NULL);
	c = vx_json_at(&j, c->next);
	assert_string_equal(c->str, "\"\\/\b\f\n\r\t");
	assert_int_equal(vx_json_get(&j, vx_json_at(&j, 0), "b", NULL)->line, 2);
	vx_json_free(&j);
	/* bounds: depth 2 holds [[1]], not [[[1]]]; 3 values not 4 */
	assert_int_equal(vx_json_parse(&j, "[[1]]", 5, 2, 100, &e), 0);
	vx_json_free(&j);
	assert_int_equal(vx_json_parse(&j, "[[[1]]]", 7, 2, 100, &e), VX_EDATA);
	assert_int_equal(vx_json_parse(&j, "[1,2]", 5, 2, 3, &e), 0);
	vx_json_free(&j);
	assert_int_equal(vx_json_parse(&j, "[1,2,3]", 7, 2, 3, &e), VX_EDATA);
	assert_non_null(strstr(e.msg, "too many values"));
	assert_int_equal(vx_json_parse(&j, "\"\\ud800\"", 8, 2, 3, &e),
	    VX_EDATA);
	assert_int_equal(vx_json_parse(&j, "\"\\u0000\"", 8, 2, 3, &e),
	    VX_EDATA);
	assert_int_equal(vx_json_parse(&j, "[1,]", 4, 2, 9, &e), VX_EDATA);
	assert_int_equal(vx_json_parse(&j, "{\"a\" 1}", 7, 2, 9, &e), VX_EDATA);
	assert_int_equal(vx_json_parse(&j, "  ", 2, 2, 9, &e), VX_EDATA);
	assert_int_equal(vx_json_parse(&j, "1.", 2, 2, 9, &e), VX_EDATA);
	assert_int_equal(vx_json_parse(&j, "-", 1, 2, 9, &e), VX_EDATA);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(same_in_each),
		cmocka_unit_test(miter_table),
		cmocka_unit_test(sharpness),
		cmocka_unit_test(paraview_points),
		cmocka_unit_test(color_spaces),
		cmocka_unit_test(vtk_piecewise),
		cmocka_unit_test(malformed),
		cmocka_unit_test(json),
	};

	return cmocka_run_group_tests(tests, helper_tmp_setup,
	    helper_tmp_teardown);
}
