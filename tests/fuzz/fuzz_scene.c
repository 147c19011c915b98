/* fuzz_scene.c: libFuzzer target for the scene text.  Any input either
 * fails cleanly or parses to a scene whose canonical text reads back to
 * an equal scene and the same text; the plan and camera never crash.  A
 * failure leaves a one-line message.
 * Build: make fuzz-build; run: build/fuzz/fuzz_scene -max_total_time=30 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "vx_plan.h"

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static const double lo[3] = { -1, -2, -3 }, hi[3] = { 4, 5, 6 };
	vx_scene s, back;
	vx_err e = { 0, "" };
	vx_plan p;
	char *t1, *t2, buf[256];
	size_t n1, n2;

	if (vx_scene_parse(&s, (const char *)data, size, &e) != 0) {
		/* one line, a sysexits code (fuzz.h) */
		fuzz_err_check(e.code, &e);
		return 0;
	}
	if (vx_scene_format(&s, &t1, &n1, &e) != 0)
		abort();
	if (vx_scene_parse(&back, t1, n1, &e) != 0 || !vx_scene_equal(&s, &back))
		abort();
	if (vx_scene_format(&back, &t2, &n2, &e) != 0 || n1 != n2 ||
	    memcmp(t1, t2, n1) != 0)
		abort();
	vx_scene_plan_isosurface(&s, &p);
	vx_plan_format(&p, buf, sizeof buf);
	if (vx_camera_resolve(&s.camera, lo, hi, &e) == 0) {
		double o[3], d[3];

		vx_camera_ray(&s.camera, 0.5, 0.5, o, d);
	}
	free(t1);
	free(t2);
	return 0;
}
