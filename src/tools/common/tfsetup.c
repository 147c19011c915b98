/* tfsetup.c: a scene's transfer function, its file imported (tool.h). */
#include "tool.h"
#include "vx_scene.h"
#include "vx_tf.h"
#include "vx_tfimport.h"

void
tool_scene_tf(vx_tf *tf, const vx_scene *s)
{
	vx_err e = { 0, "" };

	vx_tf_init(tf);
	if (s->tf_file[0] != '\0') {
		vx_tf_format f = s->tf_file_format != VX_TF_FORMAT_UNKNOWN ?
		    s->tf_file_format : VX_TF_FORMAT_AUTO;

		if (vx_tf_import(s->tf_file, f, tf, &e) != 0) {
			vx_err_push(&e, "transfer file %s", s->tf_file);
			tool_fail_err(&e);
		}
	}
	if (vx_tf_apply_scene(tf, s, &e) != 0 || vx_tf_check(tf, &e) != 0) {
		vx_err_push(&e, "transfer");
		tool_fail_err(&e);
	}
}
