/* tf_scene.c: a scene's transfer lines into a transfer function
 * (vx_tf.h, vx_tf_apply_scene). */
#include <stdlib.h>
#include <string.h>

#include "vx_scene.h"
#include "vx_tf.h"

/* set_list: list l from n points of the scene's rows of per numbers (the
 * abscissa, then dim values). */
static int
set_list(vx_tf_list *l, const double *rows, int n, int per, const char *name,
    vx_err *e)
{
	double x[VX_SCENE_MAX_TF], y[3 * VX_SCENE_MAX_TF];
	int dim = per - 1, rc;

	for (int i = 0; i < n; i++) {
		x[i] = rows[i * per];
		for (int c = 0; c < dim; c++)
			y[i * dim + c] = rows[i * per + 1 + c];
	}
	if ((rc = vx_tf_list_set(l, n, dim, x, y, e)) != 0)
		vx_err_push(e, "transfer %s", name);
	return rc;
}

int
vx_tf_apply_scene(vx_tf *tf, const vx_scene *s, vx_err *e)
{
	int rc = 0;

	if ((s->ntf_color > 0 || s->ntf_opacity > 0) && tf->has_table) {
		free(tf->rgba);          /* colour and opacity together */
		tf->rgba = NULL;
		tf->has_table = 0;
		memset(tf->size, 0, sizeof tf->size);
	}
	if (s->ntf_opacity > 0)
		rc = set_list(&tf->opacity, &s->tf_opacity[0][0],
		    s->ntf_opacity, 2, "opacity", e);
	if (rc == 0 && s->ntf_color > 0)
		rc = set_list(&tf->color, &s->tf_color[0][0], s->ntf_color, 4,
		    "color", e);
	if (rc == 0 && s->ntf_transport > 0)
		rc = set_list(&tf->transport, &s->tf_transport[0][0],
		    s->ntf_transport, 4, "transport", e);
	if (rc == 0 && s->ntf_surface > 0)
		rc = set_list(&tf->surface, &s->tf_surface[0][0],
		    s->ntf_surface, 2, "surface", e);
	if (rc == 0 && s->ntf_gradient > 0)
		rc = set_list(&tf->gradient, &s->tf_gradient[0][0],
		    s->ntf_gradient, 2, "gradient", e);
	if (rc == 0 && s->has_tf_surface_ramp) {
		tf->has_surface_ramp = 1;
		tf->surface_ramp[0] = s->tf_surface_ramp[0];
		tf->surface_ramp[1] = s->tf_surface_ramp[1];
	}
	if (rc == 0 && s->has_tf_step)
		tf->ref_step = s->tf_step;
	return rc;
}
