/* fuzz_env.h: what the HDR image targets (fuzz_hdr, fuzz_exr) check on a
 * decoded image: it becomes an environment map (lat-long; angular too when
 * square) or is refused with a clean error, and a map keeps its promises:
 * finite non-negative pixels, solid angles that sum to 4 pi, samples whose
 * pdf is finite and non-negative and agrees with vx_env_pdf. */
#ifndef VX_FUZZ_ENV_H
#define VX_FUZZ_ENV_H

#include "fuzz.h"
#include "vx_env.h"

static inline void
fuzz_env_check(const vx_image *img)
{
	vx_env_layout lay[2] = { VX_ENV_LATLONG, VX_ENV_ANGULAR };

	/* small maps only: the targets must stay fast */
	if ((size_t)img->w * (size_t)img->h > 65536)
		return;
	for (int k = 0; k < 2; k++) {
		vx_env env;
		vx_err e;
		double sum = 0;
		int rc;

		if (lay[k] == VX_ENV_ANGULAR && img->w != img->h)
			continue;
		vx_err_clear(&e);
		rc = vx_env_init(&env, img, lay[k], (const double[3]){ 1, 2, 3 },
		    (const double[3]){ 10, 20, 30 }, &e);
		fuzz_err_check(rc, &e);
		if (rc != 0)
			continue;
		for (size_t i = 0; i < 3 * vx_env_npixel(&env); i++)
			if (!(env.px[i] >= 0) || !isfinite(env.px[i]))
				fuzz_fail("env: a pixel is negative or not finite");
		for (size_t i = 0; i < vx_env_npixel(&env); i++) {
			double d[3], om, c[3];

			vx_env_pixel(&env, i, d, &om, c);
			if (!(om >= 0))
				fuzz_fail("env: a negative solid angle");
			sum += om;
		}
		if (fabs(sum - 4 * M_PI) > 1e-9)
			fuzz_fail("env: the solid angles do not sum to 4 pi");
		for (int s = 0; s < 16; s++) {
			double u[2] = { (s + 0.5) / 16, (s * 7 % 16 + 0.25) / 16 };
			double d[3], c[3], pdf, q;

			pdf = vx_env_sample(&env, u, d, c);
			if (!(pdf >= 0) || !isfinite(pdf))
				fuzz_fail("env: a sample's pdf is negative or not "
				    "finite");
			if (pdf == 0)
				continue;
			q = vx_env_pdf(&env, d);
			if (!(q >= 0) || !isfinite(q))
				fuzz_fail("env: vx_env_pdf is negative or not finite");
			vx_env_lookup(&env, d, 1, c);
		}
		vx_env_free(&env);
	}
}

#endif
