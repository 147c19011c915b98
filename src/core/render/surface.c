/* surface.c: the isosurfaces of a scene for renderers and bakers: the
 * source (volume or mesh), the hit record, visibility, lights, shading
 * (vx_surface.h). */
#include "vx_surface.h"

#include <math.h>
#include <string.h>

#include "vx_cell.h"
#include "vx_tonemap.h"
#include "vx_vec.h"

void
vx_surfaces_init(vx_surfaces *sf)
{
	memset(sf, 0, sizeof *sf);
}

void
vx_surfaces_volume(vx_surfaces *sf, const vx_grid *g, const vx_macro *m,
    int solver, int flat, double offset)
{
	sf->g = g;
	sf->mesh = NULL;
	sf->lg = NULL;
	memset(&sf->tr, 0, sizeof sf->tr);
	sf->tr.g = g;
	sf->tr.m = m;
	sf->tr.flat = flat || m == NULL;
	sf->tr.solver = solver;
	sf->offset = offset;
}

void
vx_surfaces_mesh(vx_surfaces *sf, const vx_tetmesh *mesh,
    const vx_tetleaf *lg, double offset)
{
	double vol = 1, ext = 0, size;

	sf->g = NULL;
	memset(&sf->tr, 0, sizeof sf->tr);
	sf->mesh = mesh;
	sf->lg = lg;
	for (int a = 0; a < 3; a++) {
		double x = mesh->npoint ? mesh->bmax[a] - mesh->bmin[a] : 0;

		vol *= x;
		ext = x > ext ? x : ext;
	}
	size = vol > 0 && mesh->ntet > 0 ? cbrt(vol / (double)mesh->ntet) :
	    mesh->ntet > 0 ? ext / cbrt((double)mesh->ntet) : 1;
	sf->offset = offset * (size > 0 ? size : 1);
}

int
vx_surfaces_add(vx_surfaces *sf, double iso, int surface, double opacity,
    vx_err *e)
{
	int n = sf->niso;

	if (n >= VX_ISO_MAX) {
		vx_err_set(e, VX_EDATA, "surfaces: more than %d isovalues",
		    VX_ISO_MAX);
		return -1;
	}
	sf->isod[n] = iso;
	sf->iso[n] = (float)iso;
	sf->surf[n] = surface;
	sf->opacity[n] = opacity;
	sf->niso = n + 1;
	return n;
}

int
vx_surfaces_scene(vx_surfaces *sf, const vx_scene *s, const vx_plan *p,
    const vx_grid *const *tex, vx_err *e)
{
	sf->s = s;
	sf->p = p;
	sf->tex = tex;
	for (int k = 0; k < s->nsurface && sf->niso < VX_ISO_MAX; k++) {
		const vx_material *mt = &s->surface[k].m;

		if (!p->surface_on[k])
			continue;
		vx_surfaces_add(sf, s->surface[k].iso, k, p->composite ?
		    mt->opacity : 1.0, e);
		if (p->texture_on[k] && tex != NULL && tex[k] != NULL) {
			sf->tex_lo[k] = mt->has_window ? mt->window[0] :
			    tex[k]->vmin;
			sf->tex_hi[k] = mt->has_window ? mt->window[1] :
			    tex[k]->vmax;
		}
	}
	if (sf->niso == 0)
		return vx_err_set(e, VX_EDATA, "no surface to draw (give --iso "
		    "or a surface line in the scene)");
	return 0;
}

void
vx_surf_hit_volume(const vx_surfaces *sf, const vx_iso_hit *h,
    const double dw[3], vx_hit *out)
{
	out->t = h->t;
	out->iso = h->surface;
	out->entering = h->entering;
	vx_iso_normal(sf->g, h, dw, out->n);
	vx_index_to_world(sf->g, h->p, out->P);
	memcpy(out->pi, h->p, sizeof out->pi);
}

void
vx_surf_hit_mesh(const vx_tethit *h, const double ow[3], const double dw[3],
    vx_hit *out)
{
	int a;

	out->t = h->t;
	out->iso = h->iso;
	out->entering = h->enter;
	memcpy(out->n, h->n, sizeof out->n);
	if (vx_dot3(out->n, dw) > 0)
		for (a = 0; a < 3; a++)
			out->n[a] = -out->n[a];
	for (a = 0; a < 3; a++)
		out->P[a] = ow[a] + h->t * dw[a];
	out->pi[0] = out->pi[1] = out->pi[2] = NAN;
}

/* trace_ctx: vx_surf_trace's adapter from the sources' hits to records */
typedef struct trace_ctx {
	const vx_surfaces *sf;
	const double *ow, *dw;
	vx_hit_fn fn;
	void *ctx;
} trace_ctx;

static int
trace_volume_hit(void *ctx, const vx_iso_hit *h)
{
	const trace_ctx *x = ctx;
	vx_hit r;

	vx_surf_hit_volume(x->sf, h, x->dw, &r);
	return x->fn(x->ctx, &r);
}

static int
trace_mesh_hit(void *ctx, const vx_tethit *h)
{
	const trace_ctx *x = ctx;
	vx_hit r;

	vx_surf_hit_mesh(h, x->ow, x->dw, &r);
	return x->fn(x->ctx, &r);
}

int
vx_surf_trace(const vx_surfaces *sf, const double ow[3], const double dw[3],
    double tmax, vx_hit_fn fn, void *ctx, vx_surf_stats *st)
{
	trace_ctx x = { sf, ow, dw, fn, ctx };
	double oi[3], di[3];

	if (sf->mesh != NULL)
		return vx_tetleaf_trace(sf->lg, sf->mesh, ow, dw, sf->isod,
		    sf->niso, 0, tmax, trace_mesh_hit, &x, &st->tet);
	vx_world_to_index(sf->g, ow, oi);
	vx_world_to_index_dir(sf->g, dw, di);
	return vx_iso_trace(&sf->tr, oi, di, 0, tmax, sf->isod, sf->niso,
	    trace_volume_hit, &x, &st->iso);
}

/* normalize3: a made unit by its length (not rescaled first, as vx_unit3
 * is: the shading's own rounding) */
static inline void
normalize3(double a[3])
{
	double l = sqrt(vx_dot3(a, a));

	if (l > 0 && isfinite(l)) {
		a[0] /= l;
		a[1] /= l;
		a[2] /= l;
	}
}

/* sample: the trilinear value of g at world point w, clamped to the box;
 * NaN where a corner is not finite. */
static inline double
sample(const vx_grid *g, const double w[3])
{
	double p[3];

	vx_world_to_index(g, w, p);
	return vx_grid_trilinear(g, p);
}

typedef struct shadow_ctx {
	const vx_surfaces *sf;
	double T;                 /* transmission so far */
	int self_surface;         /* the surface the shadow ray starts on */
	int self_entering;        /* how the eye ray crossed it */
	int first;                /* no crossing seen yet */
} shadow_ctx;

static int
shadow_absorb(shadow_ctx *x, int iso, int entering)
{
	double a = x->sf->opacity[iso];
	int first = x->first;

	x->first = 0;
	/* The shadow ray leaves the surface on the eye's side, where an
	 * occluder of the same surface is crossed the way the eye ray crossed
	 * it.  A first crossing of that surface the other way means the start
	 * point was a little inside (the root is only as exact as the solver):
	 * the ray is just leaving its own surface, not shadowed by it. */
	if (first && iso == x->self_surface && entering != x->self_entering)
		return 0;
	x->T *= 1.0 - a;
	return x->T <= 1e-4;      /* opaque enough: stop */
}

static int
shadow_hit(void *ctx, const vx_iso_hit *h)
{
	return shadow_absorb(ctx, h->surface, h->entering);
}

static int
shadow_tet_hit(void *ctx, const vx_tethit *h)
{
	return shadow_absorb(ctx, h->iso, h->enter);
}

/* visibility, light_at: vx_surf_visibility and vx_surf_light, inline in
 * vx_surf_shade */
static inline double
visibility(const vx_surfaces *S, const vx_hit *h, const double Ld[3],
    double dist, vx_surf_stats *st)
{
	shadow_ctx x = { S, 1.0, h->iso, h->entering, 1 };
	int a;

	st->shadow++;
	if (S->mesh != NULL) {
		double o[3];

		/* start a small step off the surface, on the lit side */
		for (a = 0; a < 3; a++)
			o[a] = h->P[a] + S->offset * h->n[a];
		vx_tetleaf_trace(S->lg, S->mesh, o, Ld, S->isod, S->niso, 0,
		    dist, shadow_tet_hit, &x, &st->tet);
	} else {
		double oi[3], di[3], ni[3];

		/* start a small step off the surface, on the lit side */
		vx_world_to_index_dir(S->g, h->n, ni);
		normalize3(ni);
		for (a = 0; a < 3; a++)
			oi[a] = h->pi[a] + S->offset * ni[a];
		vx_world_to_index_dir(S->g, Ld, di);
		vx_iso_trace(&S->tr, oi, di, 0, dist, S->isod, S->niso,
		    shadow_hit, &x, &st->iso);
	}
	return x.T;
}

static inline void
light_at(const vx_scene *s, int k, const double P[3], double L[3],
    double *dist, double rad[3])
{
	const vx_light *lt = &s->light[k];
	const vx_camera *cam = &s->camera;
	double scale = lt->intensity;
	int a, point = 0;

	switch (lt->type) {
	case VX_LIGHT_POINT:
		for (a = 0; a < 3; a++)
			L[a] = lt->position[a] - P[a];
		point = 1;
		break;
	case VX_LIGHT_DIRECTIONAL:
		for (a = 0; a < 3; a++)
			L[a] = -lt->direction[a];
		break;
	case VX_LIGHT_HEADLIGHT:
	default:
		if (cam->projection == VX_ORTHOGRAPHIC) {
			for (a = 0; a < 3; a++)
				L[a] = -cam->fwd[a];
		} else {
			for (a = 0; a < 3; a++)
				L[a] = cam->o[a] - P[a];
			point = 1;
		}
		break;
	}
	/* normalize3(L), with the length it would compute taken from dist
	 * (the same expression: the same bits) */
	{
		double l = sqrt(vx_dot3(L, L));

		*dist = point ? l : INFINITY;
		if (l > 0 && isfinite(l))
			for (a = 0; a < 3; a++)
				L[a] /= l;
	}
	if (point && lt->falloff == VX_FALLOFF_INVERSE_SQUARE && *dist > 0)
		scale /= *dist * *dist;
	for (a = 0; a < 3; a++)
		rad[a] = lt->color[a] * scale;
}

double
vx_surf_visibility(const vx_surfaces *sf, const vx_hit *h, const double Ld[3],
    double dist, vx_surf_stats *st)
{
	return visibility(sf, h, Ld, dist, st);
}

void
vx_surf_light(const vx_scene *s, int k, const double P[3], double L[3],
    double *dist, double rad[3])
{
	light_at(s, k, P, L, dist, rad);
}

/* albedo: the diffuse color at world point P of scene surface k */
static inline void
albedo(const vx_surfaces *S, int k, const double P[3], double alb[3])
{
	const vx_material *m = &S->s->surface[k].m;

	if (S->p->texture_on[k] && S->tex != NULL && S->tex[k] != NULL) {
		double v = sample(S->tex[k], P);
		double t = (v - S->tex_lo[k]) / (S->tex_hi[k] - S->tex_lo[k]);

		if (!isfinite(t))
			t = 0;
		vx_colormap_eval(m->colormap, t, alb);
	} else
		memcpy(alb, m->color, 3 * sizeof *alb);
}

void
vx_surf_albedo(const vx_surfaces *sf, const vx_hit *h, double alb[3])
{
	albedo(sf, sf->surf[h->iso], h->P, alb);
}

/* lambert_irr: kd albedo E / pi, vx_surf_shade_irradiance's rule */
static inline void
lambert_irr(const vx_material *m, const double alb[3], const double E[3],
    double col[3])
{
	for (int a = 0; a < 3; a++)
		col[a] = m->kd * alb[a] * E[a] * (1 / 3.14159265358979323846);
}

/* path_traced: Lambert under the mean of pt_samples estimates of the
 * irradiance at h (vx_gi), lit from the eye's side */
static inline void
path_traced(const vx_surfaces *S, const vx_hit *h, const vx_material *m,
    const double alb[3], double col[3], vx_surf_stats *st)
{
	const vx_scene *s = S->s;
	const vx_gi *gi = S->gi;
	vx_gi_stats gs;
	double E[3] = { 0, 0, 0 }, D[3], isov = S->isod[h->iso];
	int high = !h->entering;     /* the eye's side is lit */
	uint64_t stream = 0xcbf29ce484222325u, bits;
	int a, l;

	/* a stream per hit point: the same for any thread count */
	for (a = 0; a < 3; a++) {
		memcpy(&bits, &h->pi[a], sizeof bits);
		stream = (stream ^ bits) * 0x100000001b3u;
	}
	memset(&gs, 0, sizeof gs);
	vx_gi_direct(gi, h->P, h->pi, h->n, isov, high, D, &gs);
	for (l = 0; l < s->pt_samples; l++) {
		double r[3];

		vx_gi_sample(gi, h->pi, h->n, isov, high, D, stream,
		    (uint64_t)l, r, &gs);
		for (a = 0; a < 3; a++)
			E[a] += r[a];
	}
	for (a = 0; a < 3; a++)
		col[a] = m->kd * alb[a] * E[a] / s->pt_samples *
		    (1 / 3.14159265358979323846);
	st->paths += gs.samples;
	st->gi_rays += gs.rays + gs.shadow_rays;
}

/* sh_texel: texel s's E under the SH lighting (Wyman et al. eq. 9: its
 * transfer vector dotted with the lighting, per channel), computed once a
 * frame: the first lookup to read it stores it (threads that race store
 * the same bits) */
static void
sh_texel(const vx_surfaces *S, int64_t s, float E[3])
{
	const vx_irrvol *v = S->irr;
	uint32_t *e = (uint32_t *)(void *)(S->sh_e + 3 * s);

	if (__atomic_load_n(&S->sh_done[s], __ATOMIC_ACQUIRE)) {
		for (int c = 0; c < 3; c++) {
			uint32_t u = __atomic_load_n(&e[c], __ATOMIC_RELAXED);

			memcpy(&E[c], &u, 4);
		}
		return;
	}
	{
		int nn = v->sh_order * v->sh_order;
		const float *t = v->mean + (size_t)v->ncomp * (size_t)s;

		for (int c = 0; c < 3; c++) {
			const float *tc = t + (v->channels == 3 ? c * nn : 0);
			const double *lc = S->shl + c * nn;
			double sum = 0;
			uint32_t u;

			for (int i = 0; i < nn; i++)
				sum += lc[i] * tc[i];
			E[c] = (float)sum;
			memcpy(&u, &E[c], 4);
			__atomic_store_n(&e[c], u, __ATOMIC_RELAXED);
		}
	}
	__atomic_store_n(&S->sh_done[s], 1, __ATOMIC_RELEASE);
}

/* sh_irradiance: E at h from the SH transfer volume and the lighting: the
 * texels' E (sh_texel) interpolated as irradiance is; a negative result
 * (ringing of truncated lighting) is clamped to 0 */
static void
sh_irradiance(const vx_surfaces *S, const vx_hit *h, double E[3],
    vx_surf_stats *st)
{
	int64_t idx[64];
	double w[64];
	int n = vx_irr_weights(S->irr, h->pi, S->irr_interp, S->g,
	    S->isod[h->iso], idx, w);

	E[0] = E[1] = E[2] = 0;
	if (n == 0) {
		st->irr_missing++;
		return;
	}
	for (int k = 0; k < n; k++) {
		float et[3];

		sh_texel(S, idx[k], et);
		for (int c = 0; c < 3; c++)
			E[c] += w[k] * et[c];
	}
	for (int c = 0; c < 3; c++)
		if (!(E[c] > 0))
			E[c] = 0;
}

/* baked: Lambert under the irradiance volume's value at h; with irr_need,
 * the texels the lookup reads reported, and black */
static inline void
baked(const vx_surfaces *S, const vx_hit *h, const vx_material *m,
    const double alb[3], double col[3], vx_surf_stats *st)
{
	double E[3];

	if (S->irr_need != NULL) {
		vx_irr_reach(S->irr, h->pi, S->irr_interp, S->irr_need,
		    S->irr_need_ctx);
		col[0] = col[1] = col[2] = 0;
		return;
	}
	if (S->irr->sh_order > 0) {
		sh_irradiance(S, h, E, st);
	} else if (!vx_irr_lookup(S->irr, h->pi, S->irr_interp, S->g,
	    S->isod[h->iso], E))
		st->irr_missing++;
	lambert_irr(m, alb, E, col);
}

/* irradiance_shade: vx_surf_shade under an irradiance, path-traced or
 * baked, as the plan says (out of line: the local lights' path keeps its
 * registers) */
static __attribute__((noinline)) void
irradiance_shade(const vx_surfaces *S, const vx_hit *h, double col[3],
    vx_surf_stats *st)
{
	int k = S->surf[h->iso];
	const vx_material *m = &S->s->surface[k].m;
	double alb[3];

	albedo(S, k, h->P, alb);
	if (S->p->pathtrace)
		path_traced(S, h, m, alb, col, st);
	else
		baked(S, h, m, alb, col, st);
	st->shaded++;
}

void
vx_surf_shade(const vx_surfaces *S, const vx_hit *h, const double dw[3],
    double col[3], vx_surf_stats *st)
{
	const vx_scene *s = S->s;
	const vx_plan *p = S->p;
	int k = S->surf[h->iso], a, l;
	const vx_material *m = &s->surface[k].m;
	const double *n = h->n, *P = h->P;
	double V[3] = { 0, 0, 0 }, alb[3], amb[3];

	if (p->pathtrace || p->irradiance) {
		irradiance_shade(S, h, col, st);
		return;
	}
	/* the view direction only for a highlight (its square root and
	 * divisions are in each hit's chain of dependent operations) */
	if (p->specular && m->ks > 0) {
		for (a = 0; a < 3; a++)
			V[a] = -dw[a];
		normalize3(V);
	}
	albedo(S, k, P, alb);
	for (a = 0; a < 3; a++) {
		amb[a] = s->ambient[a] * s->ambient_intensity;
		col[a] = amb[a] * alb[a];
	}
	for (l = 0; l < s->nlight; l++) {
		double Ld[3], rad[3], dist, ndl, vis = 1, spec = 0;

		if (!p->light_on[l])
			continue;
		light_at(s, l, P, Ld, &dist, rad);
		ndl = vx_dot3(n, Ld);
		if (!(ndl > 0))
			continue;
		if (p->shadow_on[l]) {
			uint64_t c0 = S->timing ? vx_cycles() : 0;

			vis = visibility(S, h, Ld, dist, st);
			if (S->timing)
				st->cyc_shadow += vx_cycles() - c0;
			if (vis <= 1e-4)
				continue;
		}
		if (p->specular && m->ks > 0) {
			double H[3];

			for (a = 0; a < 3; a++)
				H[a] = Ld[a] + V[a];
			normalize3(H);
			double ndh = vx_dot3(n, H);
			if (ndh > 0)
				spec = m->ks * pow(ndh, m->shininess);
		}
		for (a = 0; a < 3; a++)
			col[a] += vis * rad[a] * (m->kd * alb[a] * ndl + spec);
	}
	st->shaded++;
}

void
vx_surf_shade_irradiance(const vx_surfaces *S, const vx_hit *h,
    const double E[3], double col[3])
{
	int k = S->surf[h->iso];
	double alb[3];

	albedo(S, k, h->P, alb);
	lambert_irr(&S->s->surface[k].m, alb, E, col);
}

