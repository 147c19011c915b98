/* perturb.c: volume perturbation by noise (vx_perturb.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vx_perturb.h"
#include "vx_rng.h"
#include "vx_vec.h"

#define DOMAIN 0x7065727475726221ull     /* "perturb!" */

void
vx_perturb_none(vx_perturb *pt)
{
	memset(pt, 0, sizeof *pt);
}

/* fbm_of: the fractal sum of line q for target t's component c. */
static void
fbm_of(vx_noise_fbm *f, const vx_scene_perturb *q, int t, int c)
{
	vx_noise_fbm_init(f);
	f->seed = vx_rng_hash((uint64_t)q->seed ^ DOMAIN, (uint64_t)t,
	    (uint64_t)c, 0);
	f->octaves = q->octaves;
	f->frequency = 1 / q->scale;
	f->lacunarity = q->lacunarity;
	f->gain = q->gain;
	vx_noise_fbm_prepare(f);
}

int
vx_perturb_init(vx_perturb *pt, const vx_scene *s, vx_err *e)
{
	int rc;

	vx_perturb_none(pt);
	for (int i = 0; i < VX_PERTURB_N; i++) {
		const vx_scene_perturb *q = &s->perturb[i];
		vx_noise_fbm *f = i == VX_PERTURB_COORDINATES - 1 ? pt->coord :
		    i == VX_PERTURB_VALUE - 1 ? &pt->value : &pt->density;
		int nc = i == VX_PERTURB_COORDINATES - 1 ? 3 : 1;

		if (!q->on || q->amplitude == 0)
			continue;
		if (!(q->amplitude > 0) || !isfinite(q->amplitude) ||
		    !(q->scale > 0) || !isfinite(q->scale)) {
			vx_perturb_none(pt);
			return vx_err_set(e, VX_EDATA, "perturb %s: scale %g, "
			    "amplitude %g: need positive finite numbers",
			    vx_enum_str(&vx_perturb_target_enum, i + 1),
			    q->scale, q->amplitude);
		}
		for (int c = 0; c < nc; c++) {
			fbm_of(&f[c], q, i + 1, c);
			if ((rc = vx_noise_fbm_check(&f[c], e)) != 0) {
				vx_perturb_none(pt);
				return vx_err_push(e, "perturb %s",
				    vx_enum_str(&vx_perturb_target_enum, i + 1));
			}
		}
		pt->on[i] = 1;
		pt->amp[i] = q->amplitude;
		pt->turb[i] = q->turbulence;
		pt->any = 1;
	}
	return 0;
}

void
vx_perturb_plan(const vx_scene *s, vx_plan *p)
{
	static const char *what[VX_PERTURB_N] = {
		"the data coordinates displaced by A x a vector",
		"the value offset by A x",
		"the extinction multiplied by max(0, 1 + A x",
	};
	char name[VX_PLAN_NAME];
	vx_perturb pb, *pt = &pb;
	vx_err e;

	if (vx_perturb_init(pt, s, &e) != 0)
		vx_perturb_none(pt);
	if (!pt->any) {
		int given = 0;

		for (int i = 0; i < VX_PERTURB_N; i++)
			given |= s->perturb[i].on;
		vx_plan_add(p, "perturbation", VX_PLAN_OFF, 0, "%s", given ?
		    "amplitude 0: nothing perturbed, no noise evaluated" :
		    "no perturb line: the volume as it is");
		return;
	}
	for (int i = 0; i < VX_PERTURB_N; i++) {
		const vx_scene_perturb *q = &s->perturb[i];

		snprintf(name, sizeof name, "perturb %s",
		    vx_enum_str(&vx_perturb_target_enum, i + 1));
		if (!pt->on[i])
			continue;
		vx_plan_add(p, name, VX_PLAN_ON, 0, "%s %s(x / %g)%s: A %g, "
		    "%d octaves, lacunarity %g, gain %g, seed %ld", what[i],
		    pt->turb[i] ? "turbulence" : "fBm", q->scale,
		    i == VX_PERTURB_DENSITY - 1 ? ")" : "", q->amplitude,
		    q->octaves, q->lacunarity, q->gain, q->seed);
	}
}

/* noise: target i's sum f at world point w (gradient in grad, or NULL). */
static double
noise(const vx_perturb *pt, int i, const vx_noise_fbm *f, const double w[3],
    double grad[3])
{
	return pt->turb[i] ? vx_noise_turbulence_grad(f, w, grad) :
	    vx_noise_fbm_eval(f, w, grad);
}

/* central: the world gradient at index point p by central differences of
 * the interpolated value one voxel either side (dvr's, exactly). */
static void
central(const vx_grid *g, const double p[3], double grad[3])
{
	for (int a = 0; a < 3; a++) {
		double q[3] = { p[0], p[1], p[2] }, v1, v0;

		q[a] = p[a] + 1;
		v1 = vx_grid_trilinear(g, q);
		q[a] = p[a] - 1;
		v0 = vx_grid_trilinear(g, q);
		grad[a] = (v1 - v0) / (2 * g->spacing[a]);
	}
}

double
vx_perturb_field(const vx_perturb *pt, const vx_grid *g, const double p[3],
    double grad[3], double *density)
{
	const int C = VX_PERTURB_COORDINATES - 1, V = VX_PERTURB_VALUE - 1;
	const int D = VX_PERTURB_DENSITY - 1;
	double w[3], q[3], J[3][3], gq[3], v;

	if (density != NULL)
		*density = 1;
	if (!pt->any) {
		if (grad != NULL)
			central(g, p, grad);
		return vx_grid_trilinear(g, p);
	}
	for (int a = 0; a < 3; a++) {
		w[a] = g->origin[a] + p[a] * g->spacing[a];
		q[a] = p[a];
	}
	if (pt->on[C])
		for (int a = 0; a < 3; a++)
			q[a] = p[a] + pt->amp[C] * noise(pt, C, &pt->coord[a], w,
			    grad != NULL ? J[a] : NULL) / g->spacing[a];
	v = vx_grid_trilinear(g, q);
	if (grad != NULL) {
		central(g, q, gq);
		for (int b = 0; b < 3; b++) {
			grad[b] = gq[b];
			if (pt->on[C])
				for (int a = 0; a < 3; a++)
					grad[b] += pt->amp[C] * J[a][b] * gq[a];
		}
	}
	if (pt->on[V]) {
		double gv[3];

		v += pt->amp[V] * noise(pt, V, &pt->value, w, grad != NULL ? gv :
		    NULL);
		if (grad != NULL)
			for (int a = 0; a < 3; a++)
				grad[a] += pt->amp[V] * gv[a];
	}
	if (density != NULL && pt->on[D])
		*density = fmax(0, 1 + pt->amp[D] * noise(pt, D, &pt->density, w,
		    NULL));
	return v;
}

void
vx_perturb_optics(vx_tf_sample *c, double m)
{
	if (m == 1)
		return;
	c->alpha = vx_tf_correct(c->alpha, m);
	for (int a = 0; a < 3; a++)
		if (c->transport[a] < 1)
			c->transport[a] = pow(c->transport[a], m);
}

void
vx_perturb_classify(const vx_perturb *pt, const vx_tf *tf, const vx_grid *g,
    const double p[3], int want_grad, vx_tf_sample *c, double grad[3])
{
	double v, m, gm = 0;

	grad[0] = grad[1] = grad[2] = 0;
	v = vx_perturb_field(pt, g, p, want_grad ? grad : NULL, &m);
	if (want_grad)
		gm = sqrt(vx_dot3(grad, grad));
	vx_tf_classify(tf, v, gm, c);
	vx_perturb_optics(c, m);
}

void
vx_perturb_value_margin(const vx_perturb *pt, double *below, double *above)
{
	const int V = VX_PERTURB_VALUE - 1;

	*below = *above = 0;
	if (!pt->on[V])
		return;
	*above = pt->amp[V];
	*below = pt->turb[V] ? 0 : pt->amp[V];
}

double
vx_perturb_density_max(const vx_perturb *pt)
{
	const int D = VX_PERTURB_DENSITY - 1;

	return pt->on[D] ? 1 + pt->amp[D] : 1;
}

/* erode: along axis a, clear[c] = the AND of clear over the r cells
 * either side (clamped to the grid), using tmp (n bytes). */
static void
erode(uint8_t *clear, uint8_t *tmp, const int64_t dims[3], int a, int64_t r)
{
	size_t n = (size_t)dims[0] * (size_t)dims[1] * (size_t)dims[2];
	size_t stride = a == 0 ? 1 : a == 1 ? (size_t)dims[0] :
	    (size_t)dims[0] * (size_t)dims[1];

	memcpy(tmp, clear, n);
	for (size_t i = 0; i < n; i++) {
		int64_t k = (int64_t)(i / stride % (size_t)dims[a]);
		int64_t lo = k - r < 0 ? 0 : k - r;
		int64_t hi = k + r >= dims[a] ? dims[a] - 1 : k + r;
		uint8_t c = 1;

		for (int64_t j = lo; j <= hi && c; j++)
			c = tmp[i + (size_t)(j - k) * stride];
		clear[i] = c;
	}
}

int
vx_perturb_clear(const vx_perturb *pt, const vx_tf *tf, const vx_grid *g,
    const vx_macro *m, uint8_t *clear, vx_err *e)
{
	const int C = VX_PERTURB_COORDINATES - 1;
	size_t n = (size_t)m->dims[1][0] * (size_t)m->dims[1][1] *
	    (size_t)m->dims[1][2];
	double below, above;
	uint8_t *tmp;

	vx_perturb_value_margin(pt, &below, &above);
	if (!pt->on[C] && below == 0 && above == 0)
		return 0;
	if ((tmp = vx_malloc(n ? n : 1, e)) == NULL)
		return VX_ENOMEM;
	if (below != 0 || above != 0)
		for (size_t i = 0; i < n; i++)
			clear[i] = (uint8_t)vx_tf_range_clear(tf,
			    m->mm[1][2 * i] - below, m->mm[1][2 * i + 1] + above);
	if (pt->on[C])
		for (int a = 0; a < 3; a++) {
			/* |displacement| <= A along each axis: A / spacing
			 * data cells, ceil(that / width) macrocells */
			double r = ceil(pt->amp[C] / g->spacing[a] /
			    (double)m->width[1][a]);

			erode(clear, tmp, m->dims[1], a, r < (double)m->dims[1][a] ?
			    (int64_t)r : m->dims[1][a]);
		}
	free(tmp);
	return 0;
}
