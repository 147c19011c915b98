/* dvr.c: direct volume rendering by half-angle slicing (vx_dvr.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vx_dvr.h"
#include "vx_par.h"
#include "vx_perturb.h"
#include "vx_phase.h"
#include "vx_rng.h"
#include "vx_vec.h"


void
vx_dvr_opts_init(vx_dvr_opts *o)
{
	memset(o, 0, sizeof *o);
	o->light_size = 256;
	o->blur_angle = 20;
	o->blur_samples = 4;
	o->seed = 1;
	o->tf_table = 4096;
	o->cutoff = 1e-3;
	o->jitter = 1;
}

/* ---- the plan ---- */

static int
drives(vx_light_type t)
{
	return t == VX_LIGHT_POINT || t == VX_LIGHT_DIRECTIONAL ||
	    t == VX_LIGHT_HEADLIGHT;
}

void
vx_dvr_plan(const vx_scene *s, const vx_tf *tf, const vx_dvr_opts *o,
    vx_dvr_decide *d, vx_plan *p)
{
	int want_shadow = (s->effects & VX_FX_VOLUMETRIC_SHADOWS) != 0;
	int want_scatter = (s->effects & VX_FX_SCATTERING) != 0;
	char name[VX_PLAN_NAME];

	memset(d, 0, sizeof *d);
	vx_plan_init(p, "dvr half-angle slicing");
	d->driver = -1;
	for (int k = 0; k < s->nlight; k++)
		if (drives(s->light[k].type) && s->light[k].intensity > 0) {
			d->driver = k;
			break;
		}
	d->light_buffer = (want_shadow || want_scatter) && d->driver >= 0;
	d->scatter = want_scatter && d->light_buffer;
	d->gradient = vx_tf_needs_gradient(tf);
	d->surface = vx_tf_has_surface(tf);
	d->specular = d->surface && (s->effects & VX_FX_SPECULAR);
	d->g = s->has_medium && s->phase == VX_PHASE_HENYEY_GREENSTEIN ?
	    s->phase_g : 0;

	vx_plan_add(p, "eye rays", VX_PLAN_ON, 1, "one through each pixel "
	    "centre, sampled where it crosses each slice");
	if (d->light_buffer)
		vx_plan_add(p, "light buffer", VX_PLAN_ON, (double)o->light_size *
		    o->light_size / ((double)s->camera.w * s->camera.h),
		    "%dx%d texels (a light ray each), "
		    "driven by light %d (%s)", o->light_size, o->light_size,
		    d->driver + 1, vx_enum_str(&vx_light_type_enum,
		    s->light[d->driver].type));
	else
		vx_plan_add(p, "light buffer", VX_PLAN_OFF, 0, "%s",
		    !(want_shadow || want_scatter) ? "no volumetric-shadows or "
		    "scattering effect: lights reach every sample unattenuated" :
		    "no point, directional or headlight of nonzero intensity");
	vx_plan_add(p, "volumetric shadows", d->light_buffer ? VX_PLAN_ON :
	    VX_PLAN_OFF, 0, "%s", d->light_buffer ? (want_shadow ? "direct "
	    "attenuation through the light buffer" : "direct attenuation "
	    "through the light buffer (scattering needs it)") :
	    "no light buffer");
	if (d->scatter)
		vx_plan_add(p, "scattering", VX_PLAN_ON, 0, "indirect light "
		    "blurred within a %g degree cone (%d jittered samples), "
		    "attenuated by the transport colour%s, albedo %g %g %g",
		    o->blur_angle, o->blur_samples, tf->transport.n > 0 ? "" :
		    " (absent: 1 - opacity, grey)", s->albedo[0], s->albedo[1],
		    s->albedo[2]);
	else
		vx_plan_add(p, "scattering", VX_PLAN_OFF, 0, "%s",
		    want_scatter ? "no light buffer" : "no scattering effect");
	if (d->g != 0)
		vx_plan_add(p, "phase", VX_PLAN_ON, 0, "Henyey-Greenstein g %g "
		    "(the paper's 1D table, %d entries)", d->g,
		    VX_PHASE_TABLE_N);
	else
		vx_plan_add(p, "phase", VX_PLAN_OFF, 0, "isotropic");
	vx_plan_add(p, "gradient", d->gradient ? VX_PLAN_ON : VX_PLAN_OFF, 0,
	    "%s", d->gradient ? "central differences (6 more samples per "
	    "sample): the transfer function has a table, a gradient list or "
	    "a surface list or ramp" : "the transfer function needs none (no "
	    "table, gradient list or surface list or ramp)");
	vx_plan_add(p, "surface shading", d->surface ? VX_PLAN_ON :
	    VX_PLAN_OFF, 0, "%s", d->surface ? (d->specular ? "Blinn-Phong, "
	    "diffuse and specular, weighted by the surface list or ramp" :
	    "Blinn-Phong, diffuse only (no specular effect), weighted by the "
	    "surface list or ramp") : "no surface list or ramp: volume "
	    "shading only");
	vx_plan_add(p, "empty-space skipping", o->no_skip ? VX_PLAN_OFF :
	    VX_PLAN_ON, 0, "%s", o->no_skip ? "--no-skip: every sample "
	    "classified" : "samples in level-1 macrocells whose [min, max] "
	    "the transfer function maps to alpha 0 and transport 1 are "
	    "skipped");
	if (vx_tf_class_gradient(tf))
		vx_plan_add(p, "classification table", VX_PLAN_OFF, 0, "the "
		    "transfer function depends on the gradient magnitude: "
		    "evaluated at every sample");
	else if (o->tf_table > 0)
		vx_plan_add(p, "classification table", VX_PLAN_ON, 0, "%d "
		    "intervals over the volume's range (--tf-table)",
		    o->tf_table);
	else
		vx_plan_add(p, "classification table", VX_PLAN_OFF, 0,
		    "--tf-table 0: the transfer function evaluated at every "
		    "sample");
	vx_plan_add(p, "jitter", o->jitter ? VX_PLAN_ON : VX_PLAN_OFF, 0, "%s",
	    o->jitter ? "each eye ray's samples shifted along it by its "
	    "pixel's own fraction of a slice (--seed): fine noise instead of "
	    "the slices' rings" : "--no-jitter: every ray samples on the "
	    "slice planes");
	vx_plan_add(p, "early termination", o->cutoff > 0 ? VX_PLAN_ON :
	    VX_PLAN_OFF, 0, o->cutoff > 0 ? "front to back, a pixel stops "
	    "below transmittance %g (--cutoff)" : "--cutoff 0: every sample "
	    "taken", o->cutoff);
	for (int k = 0; k < s->nlight; k++) {
		const vx_light *l = &s->light[k];

		snprintf(name, sizeof name, "light %d %s", k + 1,
		    vx_enum_str(&vx_light_type_enum, l->type));
		if (k == d->driver) {
			vx_plan_add(p, name, VX_PLAN_ON, 0, "%s", d->light_buffer ?
			    "drives the light buffer" : "unshadowed (no light "
			    "buffer)");
		} else if (drives(l->type) && l->intensity > 0) {
			d->local[k] = 1;
			vx_plan_add(p, name, VX_PLAN_ON, 0, "unshadowed: only "
			    "the first point, directional or headlight drives "
			    "the light buffer");
		} else if (drives(l->type))
			vx_plan_add(p, name, VX_PLAN_OFF, 0, "intensity 0");
		else
			vx_plan_add(p, name, VX_PLAN_UNSUPPORTED, 0, "dvr does "
			    "not use environment or sky lights");
	}
	if (d->driver >= 0 && !d->light_buffer)
		d->local[d->driver] = 1;
	if (s->ambient_intensity > 0)
		vx_plan_add(p, "ambient", VX_PLAN_ON, 0, "E times ambient %g",
		    s->ambient_intensity);
	if (s->effects & VX_FX_INTERREFLECTION)
		vx_plan_add(p, "interreflection", VX_PLAN_UNSUPPORTED, 0,
		    "not computed by dvr");
	vx_perturb_plan(s, p);
}

/* ---- geometry ---- */

static void
box_centre(const vx_grid *g, double c[3], double *radius)
{
	double lo[3], hi[3], r2 = 0;

	vx_grid_box(g, lo, hi);
	for (int a = 0; a < 3; a++) {
		c[a] = 0.5 * (lo[a] + hi[a]);
		r2 += 0.25 * (hi[a] - lo[a]) * (hi[a] - lo[a]);
	}
	*radius = sqrt(r2);
}

static double
min_spacing(const vx_grid *g)
{
	return fmin(g->spacing[0], fmin(g->spacing[1], g->spacing[2]));
}

/* light_frame: where the driving light is (point: pos, *is_point) and its
 * direction of travel at the box centre. */
static void
light_frame(const vx_scene *s, const vx_dvr_decide *d, const double c[3],
    double L[3], double pos[3], int *is_point)
{
	const vx_light *l = &s->light[d->driver];
	const vx_camera *cam = &s->camera;

	*is_point = 0;
	if (l->type == VX_LIGHT_DIRECTIONAL) {
		memcpy(L, l->direction, 3 * sizeof *L);
	} else if (l->type == VX_LIGHT_HEADLIGHT &&
	    cam->projection == VX_ORTHOGRAPHIC) {
		memcpy(L, cam->fwd, 3 * sizeof *L);
	} else {
		*is_point = 1;
		memcpy(pos, l->type == VX_LIGHT_HEADLIGHT ? cam->o : l->position,
		    3 * sizeof *pos);
		for (int a = 0; a < 3; a++)
			L[a] = c[a] - pos[a];
		if (vx_dot3(L, L) == 0)
			memcpy(L, cam->fwd, 3 * sizeof *L);
	}
	vx_unit3(L);
}

int
vx_dvr_geometry(const vx_scene *s, const vx_dvr_decide *d, const vx_tf *tf,
    const vx_grid *g, const vx_dvr_opts *o, vx_dvr_geom *geo, vx_err *e)
{
	double c[3], R, lo[3], hi[3], tmax, pos[3] = { 0, 0, 0 };
	int is_point;

	memset(geo, 0, sizeof *geo);
	if (!s->camera.ready)
		return vx_err_set(e, VX_EINTERNAL, "dvr: camera not resolved");
	box_centre(g, c, &R);
	if (!(R > 0))
		R = min_spacing(g);
	memcpy(geo->view_dir, s->camera.fwd, sizeof geo->view_dir);
	if (d->light_buffer) {
		vx_camera *lc = &geo->light;
		double L[3];

		light_frame(s, d, c, L, pos, &is_point);
		memcpy(geo->light_dir, L, sizeof L);
		vx_camera_init(lc);
		lc->is_auto = 0;
		lc->w = lc->h = o->light_size;
		lc->up[0] = lc->up[1] = 0;
		lc->up[2] = 1;
		if (is_point) {
			double dist = sqrt((c[0] - pos[0]) * (c[0] - pos[0]) +
			    (c[1] - pos[1]) * (c[1] - pos[1]) +
			    (c[2] - pos[2]) * (c[2] - pos[2]));

			lc->projection = VX_PERSPECTIVE;
			memcpy(lc->eye, pos, sizeof pos);
			for (int a = 0; a < 3; a++)
				lc->look[a] = pos[a] + L[a];
			/* the bounding sphere with a margin; from inside it,
			 * 170 degrees (outside those, light is unattenuated) */
			lc->fov = dist > R * 1.0001 ? fmin(170, 2 * asin(R /
			    dist) * 180 / M_PI * 1.05) : 170;
		} else {
			lc->projection = VX_ORTHOGRAPHIC;
			for (int a = 0; a < 3; a++) {
				lc->eye[a] = c[a] - 2 * R * L[a];
				lc->look[a] = c[a];
			}
			lc->view_width = 2 * R * 1.05;
		}
		if (vx_camera_resolve(lc, NULL, NULL, e) != 0)
			return vx_err_push(e, "dvr: light camera");
		if (vx_dot3(L, geo->view_dir) >= 0) {
			for (int a = 0; a < 3; a++)
				geo->axis[a] = L[a] + geo->view_dir[a];
		} else {
			geo->back_to_front = 1;
			for (int a = 0; a < 3; a++)
				geo->axis[a] = L[a] - geo->view_dir[a];
		}
		vx_unit3(geo->axis);
	} else
		memcpy(geo->axis, geo->view_dir, sizeof geo->axis);
	/* the slab of planes that cut the box */
	vx_grid_box(g, lo, hi);
	geo->tmin = HUGE_VAL;
	tmax = -HUGE_VAL;
	for (int k = 0; k < 8; k++) {
		double p[3] = { k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1],
		    k & 4 ? hi[2] : lo[2] };
		double t = vx_dot3(geo->axis, p);

		geo->tmin = fmin(geo->tmin, t);
		tmax = fmax(tmax, t);
	}
	if (o->slices > 0)
		geo->nslices = o->slices;
	else {
		double n = ceil((tmax - geo->tmin) / min_spacing(g));

		if (!(n <= VX_DVR_MAX_SLICES))
			return vx_err_set(e, VX_EDATA, "dvr: %.0f slices one voxel "
			    "apart (at most %d: give fewer)", n,
			    VX_DVR_MAX_SLICES);
		geo->nslices = n < 1 ? 1 : (int)n;
	}
	geo->dt = (tmax - geo->tmin) / geo->nslices;
	if (!(geo->dt > 0))
		geo->dt = min_spacing(g);
	geo->ref_step = tf->ref_step > 0 ? tf->ref_step : min_spacing(g);
	return 0;
}

/* ---- rendering ---- */

/* A ray and the slices it crosses inside the box, [k0, k1). */
typedef struct ray {
	double o[3], d[3];
	double so, sd;            /* s . o, s . d */
	double ratio;             /* spacing / ref_step */
	int k0, k1;
} ray;

/* An eye ray in slice steps: it crosses slice k at index-space point
 * p + k dp (p extrapolated to slice 0), along unit world direction d. */
typedef struct eray {
	double p[3], dp[3];
	float d[3];
	float ratio;              /* spacing / ref_step */
} eray;

/* A light as the samples use it (those that shine: the driver and the
 * local ones). */
typedef struct flight {
	int point;                /* 1: from pos; 0: along L */
	int inv_square;
	int driver;
	double L[3];              /* unit direction of travel (not point) */
	double pos[3];
	double rad[3];            /* colour x intensity */
} flight;

typedef struct frame {
	const vx_scene *s;
	const vx_dvr_decide *d;
	const vx_tf *tf;
	const vx_grid *g;
	const vx_macro *m;
	const vx_dvr_opts *o;
	const vx_dvr_geom *geo;
	const uint8_t *clear;     /* per level-1 macrocell, or NULL */
	vx_tf_lut lut;            /* the classification table, or absent */
	int flat;                 /* an axis of one sample */
	double vhi[3];            /* dims - 1 per axis */
	int64_t cmax[3];          /* dims - 2: the last cell */
	double amb[3];            /* ambient colour x intensity */
	float cutoff;             /* front to back: a pixel whose
	                             transmittance is below it is done */
	size_t *mcoff[3];         /* data cell -> its macrocell's linear
	                             index share, per axis */
	double dir[256][2];       /* the blur's directions: cos, sin */
	vx_phase_table phase;
	vx_perturb pt;            /* the scene's perturbation (or none) */
	int class_g;              /* classification needs the gradient */
	int W, H;                 /* eye image */
	int LW;                   /* light buffer edge */
	eray *eye;
	ray *lray;
	int32_t *ek, *lk;         /* k0, k1 of each eye and light ray,
	                             compact: every slice reads them all; an
	                             eye ray's k0 moves on past clear
	                             macrocells and to k1 at the cutoff */
	int *span;                /* per eye row: the pixels [x0, x1) whose
	                             rays cross the box */
	float *acc;               /* eye: r g b, and T (front to back) or A */
	float *cur, *next;        /* light: D, Ir, Ig, Ib per texel */
	int k;                    /* the slice being drawn */
	flight light[VX_SCENE_MAX_LIGHTS];
	int nlight;
	double lpos[3];           /* point light position */
	int lpoint;
	double lrad[3];           /* driving light radiance (colour x I) */
	int inv_square;
	double blur_tan;          /* tan(angle / 2) */
	double texel;             /* ortho light: world units per texel;
	                             perspective: per unit distance */
} frame;

typedef struct local_st {
	uint64_t eye, eye_skip, eye_done, light, light_skip;
} local_st;

/* ray_setup: the slices ray r crosses inside the box, and its ratio. */
static void
ray_setup(ray *r, const vx_dvr_geom *geo, const double lo[3],
    const double hi[3])
{
	double t0 = 0, t1 = HUGE_VAL, ta, tb;

	r->so = vx_dot3(geo->axis, r->o);
	r->sd = vx_dot3(geo->axis, r->d);
	r->k0 = r->k1 = 0;
	r->ratio = geo->dt / fabs(r->sd) / geo->ref_step;
	if (fabs(r->sd) < 1e-9)
		return;                  /* along the planes: crosses none */
	for (int a = 0; a < 3; a++) {
		if (r->d[a] == 0) {
			if (r->o[a] < lo[a] || r->o[a] > hi[a])
				return;
			continue;
		}
		double u = (lo[a] - r->o[a]) / r->d[a];
		double v = (hi[a] - r->o[a]) / r->d[a];

		t0 = fmax(t0, fmin(u, v));
		t1 = fmin(t1, fmax(u, v));
	}
	if (!(t0 <= t1))
		return;
	ta = r->so + t0 * r->sd;
	tb = r->so + t1 * r->sd;
	if (ta > tb) {
		double t = ta;

		ta = tb;
		tb = t;
	}
	double k0 = ceil((ta - geo->tmin) / geo->dt - 0.5);
	double k1 = floor((tb - geo->tmin) / geo->dt - 0.5) + 1;

	r->k0 = (int)fmax(0, fmin(k0, geo->nslices));
	r->k1 = (int)fmax(0, fmin(k1, geo->nslices));
	if (r->k1 < r->k0)
		r->k1 = r->k0;
}

/* at: where ray r crosses slice k (world) and in index space. */
static void
at(const frame *f, const ray *r, int k, double w[3], double p[3])
{
	double t = f->geo->tmin + (k + 0.5) * f->geo->dt;
	double lam = (t - r->so) / r->sd;

	for (int a = 0; a < 3; a++) {
		w[a] = r->o[a] + lam * r->d[a];
		p[a] = (w[a] - f->g->origin[a]) / f->g->spacing[a];
	}
}

/* skip: 1 when index point p lies in a clear level-1 macrocell (the
 * data cell holding p, clamped into the volume, looked up per axis in
 * mcoff: the macrocell's share of its linear index). */
static int
skip(const frame *f, const double p[3])
{
	size_t c = 0;

	if (f->clear == NULL)
		return 0;
	for (int a = 0; a < 3; a++) {
		int64_t n = f->g->dims[a] - 1, i;

		if (!(p[a] >= 0))
			i = 0;
		else if (p[a] >= (double)n)
			i = n - 1;
		else
			i = (int64_t)p[a];
		c += f->mcoff[a][i];
	}
	return f->clear[c];
}

/* clear_run: 0 when index point p lies in a macrocell that is not clear
 * (or there is no hierarchy); else how many slices from this one on the
 * ray of per-slice step dp stays inside that clear macrocell (>= 1): its
 * samples there are all clear, so the caller moves past them at once. */
static int
clear_run(const frame *f, const double p[3], const double dp[3])
{
	int64_t i[3];
	size_t c = 0;
	double t = HUGE_VAL, j;

	if (f->clear == NULL)
		return 0;
	for (int a = 0; a < 3; a++) {
		int64_t n = f->g->dims[a] - 1;

		if (!(p[a] >= 0))
			i[a] = 0;
		else if (p[a] >= (double)n)
			i[a] = n - 1;
		else
			i[a] = (int64_t)p[a];
		c += f->mcoff[a][i[a]];
	}
	if (!f->clear[c])
		return 0;
	for (int a = 0; a < 3; a++) {
		int64_t w = f->m->width[1][a];
		double lo = (double)(i[a] / w * w), hi = lo + (double)w;

		if (dp[a] > 0)
			t = fmin(t, (hi - p[a]) / dp[a]);
		else if (dp[a] < 0)
			t = fmin(t, (lo - p[a]) / dp[a]);
	}
	/* slices k + j, 0 <= j <= t, lie in the macrocell's closed box, whose
	 * corner values bound its range; a margin against rounding */
	j = floor(t - 1e-6);
	return !(j >= 0) ? 1 : j >= 1 << 30 ? 1 << 30 : (int)j + 1;
}

/* value: the trilinear value at index point p clamped into the volume:
 * vx_grid_trilinear's cell and weights, its lerps in single precision
 * (the samples' own precision); a volume with an axis of one sample goes
 * through vx_grid_trilinear. */
static inline __attribute__((always_inline)) double
value(const frame *f, const double p[3])
{
	const vx_grid *g = f->g;
	int64_t i[3];
	float l[3], c[8], e0, e1, e2, e3;

	if (f->flat)
		return vx_grid_trilinear_inline(g, p);
	for (int a = 0; a < 3; a++) {
		double q = p[a] > 0 ? p[a] : 0;
		int64_t j;

		q = q < f->vhi[a] ? q : f->vhi[a];
		j = (int64_t)q;
		j = j < f->cmax[a] ? j : f->cmax[a];
		i[a] = j;
		l[a] = (float)(q - (double)j);
	}
	vx_grid_cell_inline(g, i[0], i[1], i[2], c);
	e0 = c[0] + (c[1] - c[0]) * l[0];
	e1 = c[2] + (c[3] - c[2]) * l[0];
	e2 = c[4] + (c[5] - c[4]) * l[0];
	e3 = c[6] + (c[7] - c[6]) * l[0];
	e0 += (e1 - e0) * l[1];
	e2 += (e3 - e2) * l[1];
	return e0 + (e2 - e0) * l[2];
}

/* gradient: the world gradient at index point p (central differences of
 * the interpolated value, one voxel either side). */
static void
gradient(const frame *f, const double p[3], double grad[3])
{
	for (int a = 0; a < 3; a++) {
		double q[3] = { p[0], p[1], p[2] }, v1, v0;

		q[a] = p[a] + 1;
		v1 = value(f, q);
		q[a] = p[a] - 1;
		v0 = value(f, q);
		grad[a] = (v1 - v0) / (2 * f->g->spacing[a]);
	}
}

/* classify_exact: the transfer function at value v and gradient magnitude
 * gm, evaluated (no table), as the table's quads. */
static void
classify_exact(const frame *f, double v, double gm, vx_f4 q[2])
{
	vx_tf_sample cs;
	vx_tf_optic c;

	vx_tf_classify(f->tf, v, gm, &cs);
	vx_tf_optic_of(&cs, &c);
	q[0] = (vx_f4){ (float)c.sigma, (float)c.color[0], (float)c.color[1],
	    (float)c.color[2] };
	q[1] = (vx_f4){ (float)c.ltr[0], (float)c.ltr[1], (float)c.ltr[2],
	    (float)c.surface };
}

/* perturbed: sample() of a perturbed volume (vx_perturb.h): the value
 * (and the gradient) of the perturbed field, the extinction (sigma and
 * ltr) times the density factor. */
static void
perturbed(const frame *f, const double p[3], vx_f4 q[2], double grad[3],
    int *has_grad)
{
	double m, v = vx_perturb_field(&f->pt, f->g, p, f->class_g ? grad :
	    NULL, &m), gm = 0;

	*has_grad = f->class_g;
	if (f->lut.n > 0)
		vx_tf_lut_at(&f->lut, v, q);
	else {
		if (f->class_g)
			gm = sqrt(vx_dot3(grad, grad));
		classify_exact(f, v, gm, q);
	}
	q[0][0] *= (float)m;
	q[1] *= (vx_f4){ (float)m, (float)m, (float)m, 1 };
}

/* sample: classification of the sample at index point p, as the table's
 * quads (vx_tf_lut_at: q[0] sigma, color; q[1] ltr, surface); *grad gets
 * the gradient when classification looks at its magnitude (a table or a
 * gradient list: *has_grad 1); else the caller computes it if it needs
 * the normal. */
static inline void
sample(const frame *f, const double p[3], vx_f4 q[2], double grad[3],
    int *has_grad)
{
	double v, gm = 0;

	if (f->pt.any) {
		perturbed(f, p, q, grad, has_grad);
		return;
	}
	v = value(f, p);
	*has_grad = 0;
	if (f->lut.n > 0) {
		vx_tf_lut_at(&f->lut, v, q);
		return;
	}
	if (f->class_g) {
		gradient(f, p, grad);
		gm = sqrt(vx_dot3(grad, grad));
		*has_grad = 1;
	}
	classify_exact(f, v, gm, q);
}

/* light_at: bilinear D, I from buffer b at light image point (px, py),
 * in single precision (the buffer's); outside the buffer, unattenuated. */
static inline vx_f4
light_at(const frame *f, const float *b, double px, double py)
{
	double x = px - 0.5, y = py - 0.5;
	int n = f->LW, x0, y0, x1, y1;
	vx_f4 a, bb, cc, dd, fx, fy;

	if (!(px >= 0 && px <= n && py >= 0 && py <= n))
		return (vx_f4){ 1, 1, 1, 1 };
	x = x < n - 1 ? x : n - 1;
	x = x > 0 ? x : 0;
	y = y < n - 1 ? y : n - 1;
	y = y > 0 ? y : 0;
	x0 = (int)x;
	y0 = (int)y;
	x1 = x0 + 1 < n ? x0 + 1 : x0;
	y1 = y0 + 1 < n ? y0 + 1 : y0;
	memcpy(&a, b + 4 * ((size_t)y0 * n + x0), sizeof a);
	memcpy(&bb, b + 4 * ((size_t)y0 * n + x1), sizeof bb);
	memcpy(&cc, b + 4 * ((size_t)y1 * n + x0), sizeof cc);
	memcpy(&dd, b + 4 * ((size_t)y1 * n + x1), sizeof dd);
	fx = (vx_f4){ 1, 1, 1, 1 } * (float)(x - x0);
	fy = (vx_f4){ 1, 1, 1, 1 } * (float)(y - y0);
	a += fx * (bb - a);
	cc += fx * (dd - cc);
	return a + fy * (cc - a);
}

/* radiance of one eye sample at world point w, seen along unit d. */
static void
radiance(const frame *f, const double w[3], const double d[3],
    const vx_f4 q[2], const double grad[3], double out[3])
{
	const vx_scene *s = f->s;
	double v[3] = { -d[0], -d[1], -d[2] }, n[3] = { 0, 0, 0 };
	double color[3] = { q[0][1], q[0][2], q[0][3] }, surface = q[1][3];
	int has_n = 0;

	for (int a = 0; a < 3; a++)
		out[a] = color[a] * f->amb[a];
	if (f->d->surface && surface > 0)
		has_n = vx_dvr_normal(grad, v, n);
	for (int k = 0; k < f->nlight; k++) {
		const flight *l = &f->light[k];
		double L[3], tl[3], Ll = 1, pc, sw, lt[3];

		if (l->point) {
			double r2;

			for (int a = 0; a < 3; a++)
				L[a] = w[a] - l->pos[a];
			r2 = vx_dot3(L, L);
			vx_unit3(L);
			if (l->inv_square)
				Ll /= r2 > 0 ? r2 : HUGE_VAL;
		} else
			memcpy(L, l->L, sizeof L);
		pc = vx_phase_table_eval(&f->phase, vx_dot3(L, v));
		sw = 1;
		if (has_n) {
			tl[0] = -L[0];
			tl[1] = -L[1];
			tl[2] = -L[2];
			sw = (1 - surface) + surface * vx_dvr_blinn_phong(n,
			    tl, v, f->d->specular);
		}
		if (l->driver && f->d->light_buffer) {
			double px, py, dep;
			vx_f4 b = { 1, 1, 1, 1 };

			if (vx_camera_project(&f->geo->light, w, &px, &py, &dep))
				b = light_at(f, f->cur, px, py);
			for (int a = 0; a < 3; a++) {
				lt[a] = b[0] * pc;
				if (f->d->scatter)
					lt[a] += s->albedo[a] * (b[1 + a] > b[0] ?
					    b[1 + a] - b[0] : 0);
			}
		} else
			lt[0] = lt[1] = lt[2] = pc;
		for (int a = 0; a < 3; a++)
			out[a] += color[a] * sw * Ll * l->rad[a] * lt[a];
	}
}

static int
eye_rows(void *ctx, void *local, const vx_par_block *b)
{
	const frame *f = ctx;
	local_st *ls = local;
	const vx_grid *g = f->g;
	int k = f->k, btf = f->geo->back_to_front;

	for (int64_t y = b->lo[1]; y < b->hi[1]; y++)
		for (int x = f->span[2 * y]; x < f->span[2 * y + 1]; x++) {
			size_t i = (size_t)y * (size_t)f->W + (size_t)x;
			const eray *r = &f->eye[i];
			int32_t *ek = f->ek + 2 * i;
			float *acc = f->acc + 4 * i;
			double w[3], p[3], d[3], grad[3] = { 0, 0, 0 }, rad[3], a;
			vx_f4 c[2];
			int hg, run;

			if (k < ek[0] || k >= ek[1])
				continue;
			for (int q = 0; q < 3; q++)
				p[q] = r->p[q] + k * r->dp[q];
			if ((run = clear_run(f, p, r->dp)) > 0) {
				int to = run < ek[1] - k ? k + run : ek[1];

				ls->eye_skip += (uint64_t)(to - k);
				ek[0] = to;
				continue;
			}
			sample(f, p, c, grad, &hg);
			if (c[0][0] <= 0)
				continue;
			if (!hg && f->d->surface && c[1][3] > 0)
				f->pt.any ? (void)vx_perturb_field(&f->pt, g, p,
				    grad, NULL) : gradient(f, p, grad);
			a = -expm1(-c[0][0] * (double)r->ratio);
			for (int q = 0; q < 3; q++) {
				w[q] = g->origin[q] + p[q] * g->spacing[q];
				d[q] = r->d[q];
			}
			radiance(f, w, d, c, grad, rad);
			if (btf) {
				for (int q = 0; q < 3; q++)
					acc[q] = (float)(acc[q] * (1 - a) + a *
					    rad[q]);
				acc[3] = (float)(acc[3] * (1 - a) + a);
			} else {
				for (int q = 0; q < 3; q++)
					acc[q] = (float)(acc[q] + acc[3] * a *
					    rad[q]);
				acc[3] = (float)(acc[3] * (1 - a));
				if (acc[3] < f->cutoff) {
					ls->eye_done += (uint64_t)(ek[1] - k - 1);
					ek[0] = ek[1];
				}
			}
		}
	return 0;
}

/* blur: the mean of I over blur_samples points jittered in a disk of
 * radius rad texels about texel (x, y), bilinear in the current buffer. */
static void
blur(const frame *f, int x, int y, double rad, double out[3])
{
	int ns = f->o->blur_samples;
	uint64_t stream = (uint64_t)y * (uint64_t)f->LW + (uint64_t)x;

	vx_f4 sum = { 0, 0, 0, 0 };
	uint64_t h = 0;

	for (int j = 0; j < ns; j++) {
		double u1, r;
		const double *d;

		/* one hash gives two points: four 16-bit numbers, ample for a
		 * jitter within a few texels */
		if (j % 2 == 0)
			h = vx_rng_hash(f->o->seed, stream, (uint64_t)f->k,
			    (uint32_t)(j / 2));
		u1 = ((double)(h & 0xffff) + 0.5) / 65536;
		d = f->dir[(h >> 16) & 0xff];     /* one of 256 directions */
		h >>= 32;
		r = rad * sqrt(u1);

		sum += light_at(f, f->cur, x + 0.5 + r * d[0], y + 0.5 + r * d[1]);
	}
	out[0] = (double)sum[1] / ns;
	out[1] = (double)sum[2] / ns;
	out[2] = (double)sum[3] / ns;
}

static int
light_rows(void *ctx, void *local, const vx_par_block *b)
{
	const frame *f = ctx;
	local_st *ls = local;
	int k = f->k, n = f->LW;

	for (int64_t y = b->lo[1]; y < b->hi[1]; y++)
		for (int x = 0; x < n; x++) {
			size_t i = (size_t)y * (size_t)n + (size_t)x;
			const ray *r = &f->lray[i];
			const float *in = f->cur + 4 * i;
			float *o = f->next + 4 * i;
			double w[3], p[3], grad[3] = { 0, 0, 0 }, a, tr[3], bl[3];
			vx_f4 c[2];
			int hg;

			/* outside its slices a texel's value stays: both
			 * buffers hold it once copied at k1 (never in place) */
			if (k < f->lk[2 * i] || k > f->lk[2 * i + 1])
				continue;
			if (o != in)
				memcpy(o, in, 4 * sizeof *o);
			if (k == f->lk[2 * i + 1])
				continue;
			ls->light++;
			at(f, r, k, w, p);
			if (skip(f, p)) {
				ls->light_skip++;
				continue;
			}
			sample(f, p, c, grad, &hg);
			if (c[0][0] <= 0 && c[1][0] >= 0 && c[1][1] >= 0 &&
			    c[1][2] >= 0)
				continue;
			a = -expm1(-c[0][0] * r->ratio);
			o[0] = (float)(in[0] * (1 - a));
			if (!f->d->scatter)
				continue;
			for (int q = 0; q < 3; q++)
				tr[q] = c[1][q] >= 0 ? 1 : exp(c[1][q] * r->ratio);
			if (a > 0 && f->blur_tan > 0) {
				double dist = r->ratio * f->geo->ref_step;
				double tex = f->texel;

				if (f->lpoint) {
					double dd[3] = { w[0] - f->lpos[0],
					    w[1] - f->lpos[1], w[2] - f->lpos[2] };

					tex *= sqrt(vx_dot3(dd, dd));
				}
				blur(f, x, (int)y, dist * f->blur_tan / tex, bl);
			} else
				bl[0] = bl[1] = bl[2] = 0;
			for (int q = 0; q < 3; q++)
				o[1 + q] = (float)(tr[q] * ((1 - a) * in[1 + q] +
				    a * bl[q]));
		}
	return 0;
}

static int
merge(void *ctx, void *local, int t)
{
	local_st *sum = ctx, *l = local;

	(void)t;
	sum->eye_skip += l->eye_skip;
	sum->eye_done += l->eye_done;
	sum->light += l->light;
	sum->light_skip += l->light_skip;
	return 0;
}

/* clear_cells: a byte per level-1 macrocell, 1 when its range is clear. */
static uint8_t *
clear_cells(const vx_macro *m, const vx_tf *tf, vx_err *e)
{
	size_t n = (size_t)m->dims[1][0] * (size_t)m->dims[1][1] *
	    (size_t)m->dims[1][2];
	uint8_t *c = vx_malloc(n ? n : 1, e);

	if (c == NULL)
		return NULL;
	for (size_t i = 0; i < n; i++)
		c[i] = (uint8_t)vx_tf_range_clear(tf, m->mm[1][2 * i],
		    m->mm[1][2 * i + 1]);
	return c;
}

int
vx_dvr_render(const vx_scene *s, const vx_dvr_decide *d, const vx_tf *tf,
    const vx_grid *g, const vx_macro *m, const vx_dvr_opts *o,
    vx_image *out, vx_dvr_stats *st, vx_err *e)
{
	vx_dvr_geom geo;
	frame f;
	vx_par team;
	vx_par_time tm;
	local_st sum = { 0 };
	vx_dvr_stats dummy;
	double t0 = vx_par_seconds(), lo[3], hi[3];
	size_t np;
	int rc;

	if (st == NULL)
		st = &dummy;
	memset(st, 0, sizeof *st);
	if (o->light_size < 1 || o->light_size > VX_DVR_MAX_LIGHT_SIZE ||
	    o->blur_samples < 1 || o->blur_samples > VX_DVR_MAX_BLUR ||
	    !(o->blur_angle >= 0 && o->blur_angle < 90) ||
	    o->slices < 0 || o->slices > VX_DVR_MAX_SLICES)
		return vx_err_set(e, VX_EINTERNAL, "dvr: options out of range");
	if ((rc = vx_grid_check_box(g, e)) != 0)
		return rc;
	if ((rc = vx_dvr_geometry(s, d, tf, g, o, &geo, e)) != 0)
		return rc;
	memset(&f, 0, sizeof f);
	f.s = s;
	f.d = d;
	f.tf = tf;
	f.g = g;
	f.o = o;
	f.geo = &geo;
	f.W = s->camera.w;
	f.H = s->camera.h;
	f.LW = d->light_buffer ? o->light_size : 0;
	f.blur_tan = tan(o->blur_angle * M_PI / 360);
	for (int i = 0; i < 256; i++) {
		f.dir[i][0] = cos(2 * M_PI * (i + 0.5) / 256);
		f.dir[i][1] = sin(2 * M_PI * (i + 0.5) / 256);
	}
	f.class_g = d->gradient && vx_tf_class_gradient(tf);
	if ((rc = vx_perturb_init(&f.pt, s, e)) != 0)
		return rc;
	vx_phase_table_hg(&f.phase, d->g);
	if (m != NULL && !o->no_skip && m->nlev >= 1 && !m->explicit_leaves &&
	    g->dims[0] > 1 && g->dims[1] > 1 && g->dims[2] > 1) {
		f.m = m;
		if ((f.clear = clear_cells(m, tf, e)) == NULL)
			return VX_ENOMEM;
		if ((rc = vx_perturb_clear(&f.pt, tf, g, m, (uint8_t *)f.clear,
		    e)) != 0)
			goto done;
		for (int a = 0; a < 3; a++) {
			size_t sd = a == 0 ? 1 : a == 1 ? (size_t)m->dims[1][0] :
			    (size_t)m->dims[1][0] * (size_t)m->dims[1][1];
			int64_t n = g->dims[a] - 1;

			if ((f.mcoff[a] = vx_malloc((size_t)n *
			    sizeof *f.mcoff[a], e)) == NULL) {
				rc = VX_ENOMEM;
				goto done;
			}
			for (int64_t i = 0; i < n; i++)
				f.mcoff[a][i] = (size_t)(i / m->width[1][a]) * sd;
		}
	}
	if (o->tf_table > 0 && !f.class_g) {
		double vlo = g->vmin, vhi = g->vmax, below, above;

		if (!g->has_range)
			vlo = vhi = 0;
		vx_perturb_value_margin(&f.pt, &below, &above);
		vlo -= below;     /* where a perturbed value can go */
		vhi += above;
		if ((rc = vx_tf_lut_build(&f.lut, tf, vlo, vhi, o->tf_table,
		    e)) != 0)
			goto done;
	}
	f.cutoff = (float)o->cutoff;
	for (int a = 0; a < 3; a++) {
		f.flat |= g->dims[a] < 2;
		f.vhi[a] = (double)(g->dims[a] - 1);
		f.cmax[a] = g->dims[a] - 2;
		f.amb[a] = s->ambient[a] * s->ambient_intensity;
	}
	for (int k = 0; k < s->nlight; k++) {
		const vx_light *l = &s->light[k];
		flight *fl = &f.light[f.nlight];

		if (!(k == d->driver || d->local[k]))
			continue;
		memset(fl, 0, sizeof *fl);
		fl->driver = k == d->driver;
		if (l->type == VX_LIGHT_DIRECTIONAL ||
		    (l->type == VX_LIGHT_HEADLIGHT &&
		    s->camera.projection == VX_ORTHOGRAPHIC)) {
			memcpy(fl->L, l->type == VX_LIGHT_DIRECTIONAL ?
			    l->direction : s->camera.fwd, sizeof fl->L);
			vx_unit3(fl->L);
		} else {
			fl->point = 1;
			memcpy(fl->pos, l->type == VX_LIGHT_HEADLIGHT ?
			    s->camera.o : l->position, sizeof fl->pos);
			fl->inv_square = l->falloff == VX_FALLOFF_INVERSE_SQUARE;
		}
		for (int a = 0; a < 3; a++)
			fl->rad[a] = l->intensity * l->color[a];
		f.nlight++;
	}
	if ((rc = vx_image_alloc(out, f.W, f.H, 4, e)) != 0)
		goto done;
	snprintf(out->name, sizeof out->name, "color");
	np = (size_t)f.W * (size_t)f.H;
	f.eye = vx_malloc(np * sizeof *f.eye, e);
	f.ek = vx_malloc(np * 2 * sizeof *f.ek, e);
	f.acc = vx_malloc(np * 4 * sizeof *f.acc, e);
	f.span = vx_malloc((size_t)f.H * 2 * sizeof *f.span, e);
	if (f.eye == NULL || f.ek == NULL || f.acc == NULL || f.span == NULL) {
		rc = VX_ENOMEM;
		goto done;
	}
	vx_grid_box(g, lo, hi);
	for (int y = 0; y < f.H; y++) {
		f.span[2 * y] = f.W;
		f.span[2 * y + 1] = 0;
		for (int x = 0; x < f.W; x++) {
			size_t i = (size_t)y * (size_t)f.W + (size_t)x;
			eray *er = &f.eye[i];
			ray r;
			double lam0, dlam;

			vx_camera_ray(&s->camera, x + 0.5, y + 0.5, r.o, r.d);
			ray_setup(&r, &geo, lo, hi);
			f.ek[2 * i] = r.k0;
			f.ek[2 * i + 1] = r.k1;
			f.acc[4 * i] = f.acc[4 * i + 1] = f.acc[4 * i + 2] = 0;
			f.acc[4 * i + 3] = geo.back_to_front ? 0 : 1;
			memset(er, 0, sizeof *er);
			if (r.k1 <= r.k0)
				continue;
			sum.eye += (uint64_t)(r.k1 - r.k0);
			if (x < f.span[2 * y])
				f.span[2 * y] = x;
			f.span[2 * y + 1] = x + 1;
			/* jitter: the ray's samples shifted along it by one
			 * offset in [-1/2, 1/2) of a slice, a pure function of
			 * (seed, pixel): slices' rings become fine noise */
			lam0 = (geo.tmin + 0.5 * geo.dt - r.so) / r.sd;
			if (o->jitter)
				lam0 += (vx_rng_uniform(o->seed, (uint64_t)i,
				    0, 1) - 0.5) * geo.dt / r.sd;
			dlam = geo.dt / r.sd;
			for (int a = 0; a < 3; a++) {
				er->p[a] = (r.o[a] + lam0 * r.d[a] - g->origin[a]) /
				    g->spacing[a];
				er->dp[a] = dlam * r.d[a] / g->spacing[a];
				er->d[a] = (float)r.d[a];
			}
			er->ratio = (float)r.ratio;
		}
	}
	if (d->light_buffer) {
		size_t nl = (size_t)f.LW * (size_t)f.LW;
		const vx_light *l = &s->light[d->driver];

		f.lray = vx_malloc(nl * sizeof *f.lray, e);
		f.lk = vx_malloc(nl * 2 * sizeof *f.lk, e);
		f.cur = vx_malloc(nl * 4 * sizeof *f.cur, e);
		/* the blur reads neighbours: two buffers (ping-pong); the
		 * direct attenuation alone updates in place */
		f.next = d->scatter ? vx_malloc(nl * 4 * sizeof *f.next, e) :
		    f.cur;
		if (f.lray == NULL || f.lk == NULL || f.cur == NULL ||
		    f.next == NULL) {
			rc = VX_ENOMEM;
			goto done;
		}
		for (int y = 0; y < f.LW; y++)
			for (int x = 0; x < f.LW; x++) {
				size_t i = (size_t)y * (size_t)f.LW + (size_t)x;

				vx_camera_ray(&geo.light, x + 0.5, y + 0.5,
				    f.lray[i].o, f.lray[i].d);
				ray_setup(&f.lray[i], &geo, lo, hi);
				f.lk[2 * i] = f.lray[i].k0;
				f.lk[2 * i + 1] = f.lray[i].k1;
				for (int c = 0; c < 4; c++) {
					f.cur[4 * i + c] = 1;
					f.next[4 * i + c] = 1;
				}
			}
		f.lpoint = geo.light.projection == VX_PERSPECTIVE;
		if (f.lpoint)
			memcpy(f.lpos, geo.light.o, sizeof f.lpos);
		f.texel = f.lpoint ? 2 * geo.light.half_h / f.LW :
		    2 * geo.light.half_w / f.LW;
		(void)l;
	}
	if ((rc = vx_par_init(&team, o->nthreads, sizeof(local_st), e)) != 0)
		goto done;
	st->setup_s = vx_par_seconds() - t0;
	for (int k = 0; k < geo.nslices; k++) {
		vx_par_loop le = { { f.W, f.H, 1 }, { f.W, 4, 1 }, 1 };

		f.k = k;
		if ((rc = vx_par_run(&team, &le, eye_rows, &f, &tm)) != 0)
			break;
		st->eye_s += tm.seconds;
		if (d->light_buffer && k + 1 < geo.nslices) {
			vx_par_loop ll = { { f.LW, f.LW, 1 }, { f.LW, 4, 1 },
			    1 };
			float *t;

			if ((rc = vx_par_run(&team, &ll, light_rows, &f,
			    &tm)) != 0)
				break;
			st->light_s += tm.seconds;
			t = f.cur;
			f.cur = f.next;
			f.next = t;
		}
	}
	st->threads = team.nthreads;
	vx_par_each(&team, merge, &sum);
	vx_par_free(&team);
	if (rc != 0)
		goto done;
	for (size_t i = 0; i < np; i++) {
		float *px = out->px + 4 * i;

		px[0] = f.acc[4 * i];
		px[1] = f.acc[4 * i + 1];
		px[2] = f.acc[4 * i + 2];
		px[3] = geo.back_to_front ? f.acc[4 * i + 3] :
		    1 - f.acc[4 * i + 3];
	}
	st->nslices = geo.nslices;
	st->light_size = f.LW;
	st->eye_samples = sum.eye;
	st->eye_skipped = sum.eye_skip;
	st->eye_done = sum.eye_done;
	st->light_samples = sum.light;
	st->light_skipped = sum.light_skip;
done:
	if (rc != 0)
		vx_image_free(out);
	free(f.eye);
	free(f.span);
	free(f.acc);
	free(f.lray);
	if (f.next != f.cur)
		free(f.next);
	free(f.cur);
	free(f.ek);
	free(f.lk);
	free((void *)f.clear);
	vx_tf_lut_free(&f.lut);
	for (int a = 0; a < 3; a++)
		free(f.mcoff[a]);
	st->seconds = vx_par_seconds() - t0;
	return rc;
}
