/* gisetup.c: the global-illumination estimator from a scene, shared by
 * bake-irr and raycast --lazy (one place decides what a scene's lights
 * mean to a bake). */
#include "tool.h"
#include "vx_gi.h"
#include "vx_scene.h"

void
tool_gi_setup(vx_gi *gi, const vx_scene *s, const vx_grid *g,
    const vx_macro *m)
{
	vx_err e = { 0, "" };

	if (vx_gi_setup(gi, s, g, m, &e) != 0)
		tool_fail_err(&e);
	for (int k = 0; k < s->nlight; k++)
		if (s->light[k].type == VX_LIGHT_ENVIRONMENT)
			tool_fail(VX_EUSAGE, "light %d: environment lights are "
			    "not baked yet", k + 1);
	if (gi->nlight == 0 && !gi->has_sky && !gi->has_env)
		tool_fail(VX_EUSAGE, "no light to bake: the scene has %s; add "
		    "a sky, point or directional light (--light \"sky\")",
		    gi->skipped_headlights ? "only a headlight, which moves with "
		    "the camera" : "no light");
}
