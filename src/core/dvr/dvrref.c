/* dvrref.c: the ray-marched and path-traced references of direct volume
 * rendering (vx_dvrref.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vx_dvrref.h"
#include "vx_par.h"
#include "vx_perturb.h"
#include "vx_phase.h"
#include "vx_rng.h"
#include "vx_vec.h"


void
vx_dvrref_opts_init(vx_dvrref_opts *o)
{
	memset(o, 0, sizeof *o);
	o->method = VX_DVRREF_RAYMARCH;
	o->spp = 16;
	o->bounces = 1;
	o->seed = 1;
}

void
vx_dvrref_plan(const vx_scene *s, const vx_tf *tf, const vx_dvr_decide *d,
    const vx_dvrref_opts *o, vx_plan *p)
{
	int pt = o->method == VX_DVRREF_PATHTRACE;
	int shadow = pt ? d->driver >= 0 : d->light_buffer;

	(void)tf;
	vx_plan_init(p, pt ? "dvr reference: volumetric path tracer" :
	    "dvr reference: ray march, exact shadow rays");
	if (pt) {
		vx_plan_add(p, "paths", VX_PLAN_ON, o->spp, "%d per pixel "
		    "(numbers %llu..%llu, seed %llu) from the pixel centre, "
		    "vertices by delta tracking against the largest extinction",
		    o->spp, (unsigned long long)o->first,
		    (unsigned long long)(o->first + (uint64_t)o->spp - 1),
		    (unsigned long long)o->seed);
		vx_plan_add(p, "scattering", VX_PLAN_ON, o->bounces, "%s: up to "
		    "%d vertices a path, directions sampled from the phase "
		    "function, throughput x colour x albedo %g %g %g",
		    o->bounces == 1 ? "single" : "multiple", o->bounces,
		    s->albedo[0], s->albedo[1], s->albedo[2]);
	} else
		vx_plan_add(p, "eye rays", VX_PLAN_ON, 1, "one through each "
		    "pixel centre, a sample at the middle of each step%s",
		    o->step > 0 ? " (--march-step)" : " (the reference step)");
	if (shadow)
		vx_plan_add(p, "shadow rays", VX_PLAN_ON, 0, "%s toward light "
		    "%d (%s), every vertex or sample with opacity: O(n) per "
		    "sample, O(n^2) per pixel", pt ? "ratio tracking" :
		    "a march at the same step", d->driver + 1,
		    vx_enum_str(&vx_light_type_enum, s->light[d->driver].type));
	else
		vx_plan_add(p, "shadow rays", VX_PLAN_OFF, 0, "%s", d->driver < 0 ?
		    "no point, directional or headlight of nonzero intensity" :
		    "no volumetric-shadows or scattering effect: the light "
		    "reaches every sample unattenuated");
	if (d->g != 0)
		vx_plan_add(p, "phase", VX_PLAN_ON, 0, "Henyey-Greenstein g %g, "
		    "exact", d->g);
	else
		vx_plan_add(p, "phase", VX_PLAN_OFF, 0, "isotropic");
	vx_plan_add(p, "surface shading", d->surface ? VX_PLAN_ON :
	    VX_PLAN_OFF, 0, "%s", d->surface ? (pt ? "Blinn-Phong at the "
	    "first vertex, weighted by the surface list or ramp" :
	    "Blinn-Phong, weighted by the surface list or ramp") : "no "
	    "surface list or ramp");
	for (int k = 0; k < s->nlight; k++)
		if (d->local[k] && k != d->driver) {
			char name[VX_PLAN_NAME];

			snprintf(name, sizeof name, "light %d %s", k + 1,
			    vx_enum_str(&vx_light_type_enum, s->light[k].type));
			vx_plan_add(p, name, VX_PLAN_ON, 0, "unshadowed%s",
			    pt ? ", at the first vertex" : "");
		}
	if (!pt && d->scatter)
		vx_plan_add(p, "indirect light", VX_PLAN_UNSUPPORTED, 0, "the "
		    "ray march has no scattering term (the path tracer is the "
		    "reference for it)");
	vx_plan_add(p, "empty-space skipping", VX_PLAN_OFF, 0, "every sample "
	    "classified");
	vx_perturb_plan(s, p);
}

/* ---- the frame ---- */

typedef struct ctx {
	const vx_scene *s;
	const vx_dvr_decide *d;
	const vx_tf *tf;
	const vx_grid *g;
	const vx_dvrref_opts *o;
	double lo[3], hi[3];
	double ref, h;            /* reference step, march step */
	double smax;              /* majorant (path tracer) */
	int class_g;              /* classification needs the gradient */
	vx_perturb pt;            /* the scene's perturbation (or none) */
	int shadow;               /* transmittance toward the driver */
	float *px;                /* output RGBA */
} ctx;

typedef struct local_st {
	uint64_t samples, shadow, vertices, tentative;
} local_st;

/* clip: the part [*t0, *t1] of ray o + t d (t >= 0) inside the box;
 * 0 when it misses. */
static int
clip(const ctx *c, const double o[3], const double d[3], double *t0,
    double *t1)
{
	double a0 = 0, a1 = HUGE_VAL;

	for (int a = 0; a < 3; a++) {
		if (d[a] == 0) {
			if (o[a] < c->lo[a] || o[a] > c->hi[a])
				return 0;
			continue;
		}
		double u = (c->lo[a] - o[a]) / d[a];
		double v = (c->hi[a] - o[a]) / d[a];

		a0 = fmax(a0, fmin(u, v));
		a1 = fmin(a1, fmax(u, v));
	}
	*t0 = a0;
	*t1 = a1;
	return a0 < a1;
}

/* classify: the transfer function at world point w; grad gets the world
 * gradient (central differences one voxel either side) when want_grad or
 * classification needs it. */
static void
classify(const ctx *c, const double w[3], int want_grad, vx_tf_sample *smp,
    double grad[3])
{
	const vx_grid *g = c->g;
	double p[3];

	for (int a = 0; a < 3; a++)
		p[a] = (w[a] - g->origin[a]) / g->spacing[a];
	vx_perturb_classify(&c->pt, c->tf, g, p, want_grad || c->class_g, smp,
	    grad);
}

/* light_dir: for light k at world point w: the unit direction the light
 * travels (L), the distance to it along -L (HUGE_VAL: directional) and
 * its radiance (colour x intensity, over r^2 for an inverse-square point
 * light). */
static void
light_dir(const ctx *c, int k, const double w[3], double L[3], double *dist,
    double rad[3])
{
	const vx_scene *s = c->s;
	const vx_light *l = &s->light[k];
	double I = l->intensity;

	*dist = HUGE_VAL;
	if (l->type == VX_LIGHT_DIRECTIONAL || (l->type == VX_LIGHT_HEADLIGHT &&
	    s->camera.projection == VX_ORTHOGRAPHIC)) {
		memcpy(L, l->type == VX_LIGHT_DIRECTIONAL ? l->direction :
		    s->camera.fwd, 3 * sizeof *L);
		vx_unit3(L);
	} else {
		const double *pos = l->type == VX_LIGHT_HEADLIGHT ? s->camera.o :
		    l->position;
		double r2;

		for (int a = 0; a < 3; a++)
			L[a] = w[a] - pos[a];
		r2 = vx_dot3(L, L);
		*dist = sqrt(r2);
		vx_unit3(L);
		if (l->falloff == VX_FALLOFF_INVERSE_SQUARE)
			I /= r2 > 0 ? r2 : HUGE_VAL;
	}
	for (int a = 0; a < 3; a++)
		rad[a] = I * l->color[a];
}

/* march_shadow: the transmittance from w toward the light (unit u, to
 * distance dist) by segments of h, each attenuating by its midpoint's
 * corrected opacity. */
static double
march_shadow(const ctx *c, const double w[3], const double u[3], double dist,
    local_st *ls)
{
	double t0, t1, D = 1, grad[3];
	vx_tf_sample smp;

	if (!clip(c, w, u, &t0, &t1))
		return 1;
	t1 = fmin(t1, dist);
	if (!(t1 > 0))
		return 1;
	double n = ceil(t1 / c->h);

	for (double i = 0; i < n && D > 0; i++) {
		double a = i * c->h, b = fmin(t1, a + c->h), m = 0.5 * (a + b);
		double x[3] = { w[0] + m * u[0], w[1] + m * u[1], w[2] + m * u[2] };

		if (!(b > a))
			break;
		classify(c, x, 0, &smp, grad);
		ls->shadow++;
		if (smp.alpha > 0)
			D *= 1 - vx_tf_correct(smp.alpha, (b - a) / c->ref);
	}
	return D;
}

static double
sigma_t(const ctx *c, double alpha)
{
	return -log1p(-fmin(alpha, VX_DVRREF_ALPHA_CAP)) / c->ref;
}

/* ratio_track: the transmittance estimate from w toward the light (unit u,
 * to dist) by ratio tracking; *dim counts the numbers drawn. */
static double
ratio_track(const ctx *c, const double w[3], const double u[3], double dist,
    uint64_t stream, uint64_t index, uint32_t *dim, local_st *ls)
{
	double t0, t1, t = 0, T = 1, grad[3];
	vx_tf_sample smp;

	if (c->smax <= 0 || !clip(c, w, u, &t0, &t1))
		return 1;
	t1 = fmin(t1, dist);
	for (;;) {
		double r = vx_rng_uniform(c->o->seed, stream, index, (*dim)++);

		t -= log1p(-r) / c->smax;
		if (!(t < t1))
			break;
		double x[3] = { w[0] + t * u[0], w[1] + t * u[1], w[2] + t * u[2] };

		classify(c, x, 0, &smp, grad);
		ls->shadow++;
		T *= 1 - sigma_t(c, smp.alpha) / c->smax;
		if (T <= 0)
			return 0;
	}
	return T;
}

/* surface_w: the surface term's factor (1 - S) + S f for light travelling
 * L, seen from v (unit, toward the eye), gradient grad; 1 without a
 * usable normal. */
static double
surface_w(const ctx *c, const vx_tf_sample *smp, const double grad[3],
    const double L[3], const double v[3])
{
	double n[3], l[3] = { -L[0], -L[1], -L[2] };

	if (!(c->d->surface && smp->surface > 0) || !vx_dvr_normal(grad, v, n))
		return 1;
	return (1 - smp->surface) + smp->surface *
	    vx_dvr_blinn_phong(n, l, v, c->d->specular);
}

/* shade: the radiance of a sample at w seen from v (toward the eye), the
 * driving light's transmittance D (1 when not shadowed); vx_dvrref.h's
 * colour model. */
static void
shade(const ctx *c, const double w[3], const double v[3],
    const vx_tf_sample *smp, const double grad[3], double D, double out[3])
{
	const vx_scene *s = c->s;

	for (int a = 0; a < 3; a++)
		out[a] = smp->color[a] * s->ambient[a] * s->ambient_intensity;
	for (int k = 0; k < s->nlight; k++) {
		double L[3], dist, rad[3], P, sw;

		if (!(k == c->d->driver || c->d->local[k]))
			continue;
		light_dir(c, k, w, L, &dist, rad);
		P = 4 * M_PI * vx_phase_hg(c->d->g, vx_dot3(L, v));
		sw = surface_w(c, smp, grad, L, v);
		if (k == c->d->driver)
			P *= D;
		for (int a = 0; a < 3; a++)
			out[a] += smp->color[a] * sw * rad[a] * P;
	}
}

/* ---- ray march ---- */

static void
march_pixel(const ctx *c, int x, int y, local_st *ls, float out[4])
{
	double o[3], d[3], t0, t1, T = 1, acc[3] = { 0, 0, 0 }, v[3];
	const vx_dvr_decide *dd = c->d;

	vx_camera_ray(&c->s->camera, x + 0.5, y + 0.5, o, d);
	v[0] = -d[0];
	v[1] = -d[1];
	v[2] = -d[2];
	if (clip(c, o, d, &t0, &t1)) {
		double n = ceil((t1 - t0) / c->h);

		for (double i = 0; i < n && T > 0; i++) {
			double a = t0 + i * c->h, b = fmin(t1, a + c->h);
			double m = 0.5 * (a + b), w[3], grad[3], rad[3], D = 1, al;
			vx_tf_sample smp;

			if (!(b > a))
				break;
			for (int q = 0; q < 3; q++)
				w[q] = o[q] + m * d[q];
			classify(c, w, dd->surface, &smp, grad);
			ls->samples++;
			if (!(smp.alpha > 0))
				continue;
			al = vx_tf_correct(smp.alpha, (b - a) / c->ref);
			if (c->shadow) {
				double L[3], dist, lr[3], u[3];

				light_dir(c, dd->driver, w, L, &dist, lr);
				u[0] = -L[0];
				u[1] = -L[1];
				u[2] = -L[2];
				D = march_shadow(c, w, u, dist, ls);
			}
			shade(c, w, v, &smp, grad, D, rad);
			for (int q = 0; q < 3; q++)
				acc[q] += T * al * rad[q];
			T *= 1 - al;
		}
	}
	for (int q = 0; q < 3; q++)
		out[q] = (float)acc[q];
	out[3] = (float)(1 - T);
}

/* ---- path tracer ---- */

/* track: delta tracking from o along unit d inside the box; 1 and the
 * vertex w, its classification (and its gradient when want_grad) at a
 * real collision, 0 when the path leaves. */
static int
track(const ctx *c, const double o[3], const double d[3], int want_grad,
    uint64_t stream, uint64_t index, uint32_t *dim, local_st *ls,
    double w[3], vx_tf_sample *smp, double grad[3])
{
	double t0, t1, t;

	if (c->smax <= 0 || !clip(c, o, d, &t0, &t1))
		return 0;
	t = t0;
	for (;;) {
		double r = vx_rng_uniform(c->o->seed, stream, index, (*dim)++);

		t -= log1p(-r) / c->smax;
		if (!(t < t1))
			return 0;
		for (int a = 0; a < 3; a++)
			w[a] = o[a] + t * d[a];
		classify(c, w, 0, smp, grad);
		ls->tentative++;
		r = vx_rng_uniform(c->o->seed, stream, index, (*dim)++);
		if (r * c->smax < sigma_t(c, smp->alpha)) {
			if (want_grad && !c->class_g)
				classify(c, w, 1, smp, grad);
			return 1;
		}
	}
}

static void
trace_pixel(const ctx *c, int x, int y, local_st *ls, float out[4])
{
	const vx_dvrref_opts *op = c->o;
	const vx_dvr_decide *dd = c->d;
	uint64_t stream = (uint64_t)y * (uint64_t)c->s->camera.w + (uint64_t)x;
	double sum[3] = { 0, 0, 0 }, cover = 0, eo[3], ed[3];

	vx_camera_ray(&c->s->camera, x + 0.5, y + 0.5, eo, ed);
	for (int sp = 0; sp < op->spp; sp++) {
		uint64_t index = op->first + (uint64_t)sp;
		uint32_t dim = 0;
		double o[3], d[3], beta[3] = { 1, 1, 1 };

		memcpy(o, eo, sizeof o);
		memcpy(d, ed, sizeof d);
		ls->samples++;
		for (int k = 1; k <= op->bounces; k++) {
			double w[3], grad[3], v[3] = { -d[0], -d[1], -d[2] };
			double rad[3], D = 1, L[3], dist, lr[3], u[3];
			vx_tf_sample smp;

			if (!track(c, o, d, k == 1 && dd->surface, stream, index,
			    &dim, ls, w, &smp, grad))
				break;
			ls->vertices++;
			if (k == 1)
				cover += 1;
			if (dd->driver >= 0) {
				light_dir(c, dd->driver, w, L, &dist, lr);
				u[0] = -L[0];
				u[1] = -L[1];
				u[2] = -L[2];
				D = ratio_track(c, w, u, dist, stream, index, &dim,
				    ls);
			}
			if (k == 1)
				shade(c, w, v, &smp, grad, D, rad);
			else if (dd->driver >= 0) {
				double P = 4 * M_PI * vx_phase_hg(dd->g,
				    vx_dot3(L, v)) * D;

				for (int a = 0; a < 3; a++)
					rad[a] = smp.color[a] * lr[a] * P;
			} else
				rad[0] = rad[1] = rad[2] = 0;
			for (int a = 0; a < 3; a++)
				sum[a] += beta[a] * rad[a];
			if (k == op->bounces)
				break;
			for (int a = 0; a < 3; a++)
				beta[a] *= smp.color[a] * c->s->albedo[a];
			if (beta[0] <= 0 && beta[1] <= 0 && beta[2] <= 0)
				break;
			/* the light arrives travelling w_in and leaves along
			 * v: w_in ~ p(w_in . v); the path goes on along -w_in */
			double u1 = vx_rng_uniform(op->seed, stream, index, dim++);
			double u2 = vx_rng_uniform(op->seed, stream, index, dim++);
			double win[3];

			vx_phase_hg_sample(dd->g, v, u1, u2, win);
			memcpy(o, w, sizeof o);
			for (int a = 0; a < 3; a++)
				d[a] = -win[a];
		}
	}
	for (int a = 0; a < 3; a++)
		out[a] = (float)(sum[a] / op->spp);
	out[3] = (float)(cover / op->spp);
}

/* ---- the loop ---- */

static int
tiles(void *vc, void *local, const vx_par_block *b)
{
	const ctx *c = vc;
	int W = c->s->camera.w;

	for (int64_t y = b->lo[1]; y < b->hi[1]; y++)
		for (int64_t x = b->lo[0]; x < b->hi[0]; x++) {
			float *o = c->px + 4 * ((size_t)y * (size_t)W + (size_t)x);

			if (c->o->method == VX_DVRREF_PATHTRACE)
				trace_pixel(c, (int)x, (int)y, local, o);
			else
				march_pixel(c, (int)x, (int)y, local, o);
		}
	return 0;
}

static int
merge(void *vc, void *local, int t)
{
	local_st *sum = vc, *l = local;

	(void)t;
	sum->samples += l->samples;
	sum->shadow += l->shadow;
	sum->vertices += l->vertices;
	sum->tentative += l->tentative;
	return 0;
}

/* alpha_max: the largest opacity tf gives over the grid's values widened
 * by below and above (the value perturbation's margin; the list's maximum
 * over [vmin - below, vmax + above] is at an end or a control point
 * inside; a table: its largest alpha). */
static double
alpha_max(const vx_tf *tf, const vx_grid *g, double below, double above)
{
	double m = 0, y, lo = g->vmin - below, hi = g->vmax + above;

	if (tf->has_table) {
		size_t n = (size_t)tf->size[0] * (size_t)tf->size[1];

		for (size_t i = 0; i < n; i++)
			m = fmax(m, tf->rgba[4 * i + 3]);
		return m;
	}
	if (tf->opacity.n < 1)
		return 0;
	if (!g->has_range) {
		for (int i = 0; i < tf->opacity.n; i++)
			m = fmax(m, tf->opacity.y[i]);
		return m;
	}
	vx_tf_list_eval(&tf->opacity, lo, &y);
	m = y;
	vx_tf_list_eval(&tf->opacity, hi, &y);
	m = fmax(m, y);
	for (int i = 0; i < tf->opacity.n; i++)
		if (tf->opacity.x[i] >= lo && tf->opacity.x[i] <= hi)
			m = fmax(m, tf->opacity.y[i]);
	return m;
}

int
vx_dvrref_render(const vx_scene *s, const vx_dvr_decide *d, const vx_tf *tf,
    const vx_grid *g, const vx_dvrref_opts *o, vx_image *out,
    vx_dvrref_stats *st, vx_err *e)
{
	ctx c;
	vx_par team;
	local_st sum = { 0 };
	vx_dvrref_stats dummy;
	double t0 = vx_par_seconds(), ms;
	int rc;

	if (st == NULL)
		st = &dummy;
	memset(st, 0, sizeof *st);
	if ((o->method != VX_DVRREF_RAYMARCH &&
	    o->method != VX_DVRREF_PATHTRACE) || !(o->step >= 0) ||
	    o->spp < 1 || o->spp > VX_DVRREF_MAX_SPP || o->bounces < 1 ||
	    o->bounces > VX_DVRREF_MAX_BOUNCES)
		return vx_err_set(e, VX_EINTERNAL, "dvr: reference options out "
		    "of range");
	if (!s->camera.ready)
		return vx_err_set(e, VX_EINTERNAL, "dvr: camera not resolved");
	if ((rc = vx_grid_check_box(g, e)) != 0)
		return rc;
	memset(&c, 0, sizeof c);
	c.s = s;
	c.d = d;
	c.tf = tf;
	c.g = g;
	c.o = o;
	vx_grid_box(g, c.lo, c.hi);
	ms = fmin(g->spacing[0], fmin(g->spacing[1], g->spacing[2]));
	c.ref = tf->ref_step > 0 ? tf->ref_step : ms;
	c.h = o->step > 0 ? o->step : c.ref;
	c.class_g = vx_tf_class_gradient(tf);
	if ((rc = vx_perturb_init(&c.pt, s, e)) != 0)
		return rc;
	if (o->method == VX_DVRREF_PATHTRACE) {
		double below, above;

		/* the perturbed extinction is at most the density factor's
		 * maximum times the largest over the widened values */
		vx_perturb_value_margin(&c.pt, &below, &above);
		c.smax = vx_perturb_density_max(&c.pt) * sigma_t(&c,
		    alpha_max(tf, g, below, above));
		c.shadow = d->driver >= 0;
	} else
		c.shadow = d->light_buffer;
	if ((rc = vx_image_alloc(out, s->camera.w, s->camera.h, 4, e)) != 0)
		return rc;
	snprintf(out->name, sizeof out->name, "color");
	c.px = out->px;
	if ((rc = vx_par_init(&team, o->nthreads, sizeof(local_st), e)) != 0) {
		vx_image_free(out);
		return rc;
	}
	vx_par_loop lp = VX_PAR_TILES(s->camera.w, s->camera.h, 8);

	rc = vx_par_run(&team, &lp, tiles, &c, NULL);
	st->threads = team.nthreads;
	vx_par_each(&team, merge, &sum);
	vx_par_free(&team);
	if (rc != 0) {
		vx_image_free(out);
		return rc;
	}
	st->step = c.h;
	st->sigma_max = c.smax;
	st->samples = sum.samples;
	st->shadow_steps = sum.shadow;
	st->vertices = sum.vertices;
	st->tentative = sum.tentative;
	st->seconds = vx_par_seconds() - t0;
	return 0;
}
