/* gisetup.c: the global-illumination estimator from a scene, shared by
 * bake-irr and raycast's --lazy and pathtrace (one place decides what a
 * scene's lights mean to global illumination). */
#include <stdio.h>

#include "tool.h"
#include "vx_env.h"
#include "vx_gi.h"
#include "vx_scene.h"

/* the scene's environment map, for the run */
static vx_env env;

static void
env_eval(void *ctx, const double w[3], double rgb[3])
{
	/* the pixel's radiance: the piecewise-constant function that
	 * vx_env_sample samples */
	vx_env_lookup(ctx, w, 0, rgb);
}

static double
env_sample(void *ctx, const double u[2], double w[3], double rgb[3])
{
	return vx_env_sample(ctx, u, w, rgb);
}

static double
env_pdf(void *ctx, const double w[3])
{
	return vx_env_pdf(ctx, w);
}

void
tool_gi_setup(vx_gi *gi, vx_scene *s, const vx_grid *g, const vx_macro *m)
{
	vx_err e = { 0, "" };
	int nenv = 0;

	if (vx_env_scene_resolve(s, &e) != 0)
		tool_fail_err(&e);
	if (vx_gi_setup(gi, s, g, m, &e) != 0)
		tool_fail_err(&e);
	for (int k = 0; k < s->nlight; k++) {
		const vx_light *l = &s->light[k];

		if (l->type != VX_LIGHT_ENVIRONMENT || gi->occlusion)
			continue;    /* occlusion: a white sky, nothing else */
		if (nenv++ > 0)
			tool_fail(VX_EUSAGE, "light %d: one environment light at "
			    "most (merge the maps)", k + 1);
		if (vx_env_load_light(&env, l, &e) != 0) {
			vx_err_push(&e, "light %d", k + 1);
			tool_fail_err(&e);
		}
		{
			vx_gi_env ge = { &env, env_eval, env_sample, env_pdf };

			vx_gi_set_env(gi, &ge, 1);
		}
		snprintf(gi->env_id, sizeof gi->env_id, "%016llx",
		    (unsigned long long)env.hash);
	}
	if (gi->nlight == 0 && !gi->has_sky && !gi->has_env)
		tool_fail(VX_EUSAGE, "no light to bake: the scene has %s; add "
		    "a sky, environment, point or directional light (--light "
		    "\"sky\")", gi->skipped_headlights ? "only a headlight, "
		    "which moves with the camera" : "no light");
}
