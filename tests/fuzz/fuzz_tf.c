/* fuzz_tf.c: libFuzzer target for the transfer-function imports
 * (vx_tf_import_mem: ParaView JSON, Slicer .vp and .vp.json, miter txf)
 * and the JSON reader under them.  The first byte picks the format (auto,
 * paraview, slicer, miter); the rest is the file.  An import that
 * succeeds must pass vx_tf_check and keep its promises: every list's
 * abscissae finite and non-decreasing, every value in [0,1], evaluation
 * inside the values' range, table cells in [0,1]. */
#include "fuzz.h"
#include "vx_json.h"
#include "vx_tfimport.h"

static double
touch_list(const vx_tf_list *l, int dim)
{
	double sum = 0, out[3];

	if (l->n == 0)
		return 0;
	if (l->n > VX_TF_MAX_POINTS || l->dim != dim)
		fuzz_fail("tf: list size or dim");
	for (int i = 0; i < l->n; i++) {
		if (!isfinite(l->x[i]) || (i > 0 && l->x[i] < l->x[i - 1]))
			fuzz_fail("tf: abscissa not finite or decreasing");
		for (int c = 0; c < dim; c++)
			if (!(l->y[dim * i + c] >= 0 && l->y[dim * i + c] <= 1))
				fuzz_fail("tf: value outside [0,1]");
	}
	for (int k = -1; k <= 16; k++) {
		double t = l->x[0] + (l->x[l->n - 1] - l->x[0]) * k / 15.0;

		vx_tf_list_eval(l, t, out);
		for (int c = 0; c < dim; c++) {
			if (!(out[c] >= 0 && out[c] <= 1))
				fuzz_fail("tf: evaluation outside [0,1]");
			sum += out[c];
		}
	}
	return sum;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static const vx_tf_format fmts[4] = { VX_TF_FORMAT_AUTO,
	    VX_TF_FORMAT_PARAVIEW, VX_TF_FORMAT_SLICER, VX_TF_FORMAT_MITER };
	volatile double sink = 0;
	vx_json j;
	vx_err e;
	vx_tf tf;
	int rc;

	if (size < 1)
		return 0;
	vx_err_clear(&e);
	rc = vx_tf_import_mem(data + 1, size - 1, fmts[data[0] & 3], NULL, &tf,
	    &e);
	fuzz_err_check(rc, &e);
	if (rc == 0) {
		if (vx_tf_check(&tf, &e) != 0)
			fuzz_fail("tf: an import fails vx_tf_check");
		sink += touch_list(&tf.color, 3) + touch_list(&tf.opacity, 1) +
		    touch_list(&tf.transport, 3) + touch_list(&tf.surface, 1) +
		    touch_list(&tf.gradient, 1);
		if (tf.has_table)
			for (size_t i = 0; i < 4 * (size_t)tf.size[0] *
			    (size_t)tf.size[1]; i++) {
				if (!(tf.rgba[i] >= 0 && tf.rgba[i] <= 1))
					fuzz_fail("tf: table cell outside [0,1]");
				sink += tf.rgba[i];
			}
		vx_tf_free(&tf);
	}
	/* the JSON reader alone, with tight bounds */
	vx_err_clear(&e);
	rc = vx_json_parse(&j, data + 1, size - 1, 8, 4096, &e);
	fuzz_err_check(rc, &e);
	if (rc == 0) {
		for (int i = 0; i < j.n; i++) {
			const vx_json_node *nd = &j.node[i];

			if (nd->type == VX_JSON_STRING && strlen(nd->str) != nd->len)
				fuzz_fail("json: string length");
			if (nd->type == VX_JSON_NUMBER && !isfinite(nd->num))
				fuzz_fail("json: number not finite");
			if (nd->first >= j.n || nd->next >= j.n)
				fuzz_fail("json: child index");
			if (nd->key != NULL)
				sink += (double)strlen(nd->key);
		}
		vx_json_free(&j);
	}
	(void)sink;
	return 0;
}
