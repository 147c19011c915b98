/* gi.c: the irradiance estimator on isosurfaces (vx_gi.h). */
#include "vx_gi.h"
#include "vx_rng.h"
#include "vx_vec.h"
#include "vx_warp.h"

#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846

int
vx_gi_setup(vx_gi *gi, const vx_scene *s, const vx_grid *g,
    const vx_macro *m, vx_err *e)
{
	int k, n;

	memset(gi, 0, sizeof *gi);
	gi->g = g;
	gi->tr.g = g;
	gi->tr.m = m;
	gi->tr.flat = m == NULL;
	gi->tr.solver = VX_CELL_EXACT;
	gi->eps = 1e-3;
	for (k = 0; k < s->nlight; k++) {
		const vx_light *l = &s->light[k];
		vx_gi_light *q;
		double sc = PI * l->intensity;

		switch (l->type) {
		case VX_LIGHT_POINT:
		case VX_LIGHT_DIRECTIONAL:
			q = &gi->light[gi->nlight++];
			q->point = l->type == VX_LIGHT_POINT;
			memcpy(q->pos, l->position, sizeof q->pos);
			for (int a = 0; a < 3; a++) {
				q->dir[a] = -l->direction[a];
				q->rgb[a] = l->color[a] * sc;
			}
			if (!q->point) {
				vx_unit3(q->dir);
				if (!vx_finite3(q->dir) || vx_dot3(q->dir,
				    q->dir) == 0)
					return vx_err_set(e, VX_EUSAGE, "light %d: "
					    "no direction", k + 1);
			}
			q->inverse_square = l->falloff ==
			    VX_FALLOFF_INVERSE_SQUARE;
			q->shadows = l->shadows &&
			    (s->effects & VX_FX_SHADOWS) != 0;
			break;
		case VX_LIGHT_SKY:
			gi->has_sky = 1;
			for (int a = 0; a < 3; a++)
				gi->sky[a] += l->color[a] * l->intensity;
			break;
		case VX_LIGHT_HEADLIGHT:
			gi->skipped_headlights++;
			break;
		default:                  /* environment: vx_gi_set_env */
			break;
		}
	}
	n = s->nsurface;
	if (n == 0) {
		gi->nalbedo = 1;
		gi->albedo_v[0] = 0;
		for (int a = 0; a < 3; a++)
			gi->albedo_c[0][a] = 0.8;
	} else {
		/* insertion sort by value, stable */
		for (k = 0; k < n; k++) {
			int j = gi->nalbedo++;

			while (j > 0 && gi->albedo_v[j - 1] > s->surface[k].iso) {
				gi->albedo_v[j] = gi->albedo_v[j - 1];
				memcpy(gi->albedo_c[j], gi->albedo_c[j - 1],
				    sizeof gi->albedo_c[j]);
				j--;
			}
			gi->albedo_v[j] = s->surface[k].iso;
			for (int a = 0; a < 3; a++)
				gi->albedo_c[j][a] = s->surface[k].m.color[a] *
				    s->surface[k].m.kd;
		}
	}
	if (s->has_interreflection && (s->effects & VX_FX_INTERREFLECTION))
		gi->bounces = s->bounces;
	gi->vicinity = INFINITY;
	if (s->has_occlusion) {
		/* the special case: a white sky of radiance 1 and nothing
		 * else, no bounces; rays longer than the distance are open */
		gi->occlusion = 1;
		gi->nlight = 0;
		gi->has_sky = 1;
		gi->sky[0] = gi->sky[1] = gi->sky[2] = 1;
		gi->bounces = 0;
		if (s->occlusion_distance > 0)
			gi->vicinity = s->occlusion_distance;
	}
	return 0;
}

void
vx_gi_set_env(vx_gi *gi, const vx_gi_env *env, int importance)
{
	gi->has_env = env != NULL;
	if (env != NULL)
		gi->env = *env;
	gi->env_mis = env != NULL && importance && env->sample != NULL &&
	    env->pdf != NULL;
}

void
vx_gi_albedo(const vx_gi *gi, double v, double rgb[3])
{
	int n = gi->nalbedo, k;

	if (n == 1 || !(v > gi->albedo_v[0])) {          /* NaN too */
		memcpy(rgb, gi->albedo_c[0], 3 * sizeof *rgb);
		return;
	}
	if (v >= gi->albedo_v[n - 1]) {
		memcpy(rgb, gi->albedo_c[n - 1], 3 * sizeof *rgb);
		return;
	}
	for (k = 1; k < n && v > gi->albedo_v[k]; k++)
		;
	{
		double v0 = gi->albedo_v[k - 1], v1 = gi->albedo_v[k];
		double t = v1 > v0 ? (v - v0) / (v1 - v0) : 1;

		for (int a = 0; a < 3; a++)
			rgb[a] = gi->albedo_c[k - 1][a] + t *
			    (gi->albedo_c[k][a] - gi->albedo_c[k - 1][a]);
	}
}

int
vx_gi_sh_channels(const vx_gi *gi)
{
	if (gi->bounces == 0)
		return 1;
	for (int i = 0; i < gi->nalbedo; i++)
		if (gi->albedo_c[i][0] != gi->albedo_c[i][1] ||
		    gi->albedo_c[i][1] != gi->albedo_c[i][2])
			return 3;
	return 1;
}

/* ---- tracing ---- */

typedef struct first_ctx {
	vx_iso_hit hit;
	int found;
	int high;
} first_ctx;

/* a crossing from the lit side into the other (or a touch) blocks; a
 * crossing the other way is the ray leaving its own surface from a start
 * just behind it */
static int
first_fn(void *ctx, const vx_iso_hit *h)
{
	first_ctx *x = ctx;

	if (h->kind != VX_CELL_TOUCH && h->entering == x->high)
		return 0;
	x->hit = *h;
	x->found = 1;
	return 1;
}

/* trace: the first blocking crossing of the isosurface iso along index ray
 * o + t d, t in [0, tmax]; 1 when found */
static int
trace(const vx_gi *gi, const double o[3], const double d[3], double tmax,
    double iso, int high, first_ctx *x, vx_gi_stats *st)
{
	x->found = 0;
	x->high = high;
	vx_iso_trace(&gi->tr, o, d, 0, tmax, &iso, 1, first_fn, x,
	    st ? &st->iso : NULL);
	return x->found;
}

/* offset: index point pi moved eps index units along world normal n */
static void
offset(const vx_gi *gi, const double pi[3], const double n[3], double eps,
    double o[3])
{
	double ni[3];

	vx_world_to_index_dir(gi->g, n, ni);
	vx_unit3(ni);
	for (int a = 0; a < 3; a++)
		o[a] = pi[a] + eps * ni[a];
}

/* visible: nothing blocks world direction w up to dist from o (a surface
 * point already moved off its surface by offset) */
static int
visible(const vx_gi *gi, const double o[3], const double w[3], double dist,
    double iso, int high, vx_gi_stats *st)
{
	double d[3];
	first_ctx x;

	vx_world_to_index_dir(gi->g, w, d);
	if (st)
		st->shadow_rays++;
	return !trace(gi, o, d, dist, iso, high, &x, st);
}

/* direct: vx_gi_direct with the shadow rays' start o (pi offset) */
static void
direct(const vx_gi *gi, const double pw[3], const double o[3],
    const double n[3], double iso, int high, double rgb[3], vx_gi_stats *st)
{
	rgb[0] = rgb[1] = rgb[2] = 0;
	for (int k = 0; k < gi->nlight; k++) {
		const vx_gi_light *l = &gi->light[k];
		double L[3], dist = INFINITY, cs, sc = 1;

		if (l->point) {
			double len;

			for (int a = 0; a < 3; a++)
				L[a] = l->pos[a] - pw[a];
			len = sqrt(vx_dot3(L, L));
			if (!(len > 0))
				continue;
			for (int a = 0; a < 3; a++)
				L[a] /= len;
			dist = len;
			if (l->inverse_square)
				sc = 1 / (len * len);
		} else {
			memcpy(L, l->dir, sizeof L);
		}
		cs = vx_dot3(n, L);
		if (!(cs > 0))
			continue;
		if (l->shadows && !visible(gi, o, L, dist, iso, high, st))
			continue;
		for (int a = 0; a < 3; a++)
			rgb[a] += l->rgb[a] * sc * cs;
	}
}

void
vx_gi_direct(const vx_gi *gi, const double pw[3], const double pi[3],
    const double n[3], double iso, int high, double rgb[3], vx_gi_stats *st)
{
	double o[3];

	offset(gi, pi, n, gi->eps, o);
	direct(gi, pw, o, n, iso, high, rgb, st);
}

static double
power(double a, double b)
{
	double a2 = a * a, b2 = b * b;

	return a2 + b2 > 0 ? a2 / (a2 + b2) : 0;
}

/* one vertex's estimate of E at (pw, pi, n), depth d */
static void
vertex(const vx_gi *gi, const double pw[3], const double pi[3],
    const double n[3], double iso, int high, const double *D,
    uint64_t stream, uint64_t index, int depth, double albedo[3],
    double E[3], vx_gi_stats *st)
{
	double u[2], lw[3], w[3], t[3], b[3], cs, o[3], di[3];
	first_ctx x;

	/* every ray of this vertex starts from the same point off its
	 * surface */
	offset(gi, pi, n, gi->eps, o);
	if (D != NULL)
		memcpy(E, D, 3 * sizeof *E);
	else
		direct(gi, pw, o, n, iso, high, E, st);
	vx_onb(n, t, b);
	/* the environment, importance-sampled, MIS against the cosine */
	if (gi->has_env && gi->env_mis) {
		double rgb[3], pdf;

		vx_rng_ld2(gi->seed, stream, index, 3u * (unsigned)depth + 1, u);
		pdf = gi->env.sample(gi->env.ctx, u, w, rgb);
		cs = vx_dot3(n, w);
		if (pdf > 0 && cs > 0 && (rgb[0] > 0 || rgb[1] > 0 ||
		    rgb[2] > 0) && visible(gi, o, w, INFINITY, iso, high, st)) {
			double wt = power(pdf, cs / PI) * cs / pdf;

			for (int a = 0; a < 3; a++)
				E[a] += rgb[a] * wt;
		}
	}
	/* a cosine-weighted direction: the sky, the environment, or a
	 * surface */
	vx_rng_ld2(gi->seed, stream, index, 3u * (unsigned)depth, u);
	vx_warp_cosine_hemisphere(u, lw);
	vx_onb_to_world(n, t, b, lw, w);
	vx_unit3(w);
	cs = vx_dot3(n, w);
	vx_world_to_index_dir(gi->g, w, di);
	if (st)
		st->rays++;
	if (!trace(gi, o, di, gi->vicinity, iso, high, &x, st)) {
		double rgb[3] = { 0, 0, 0 };

		if (gi->has_env) {
			double wt = PI;

			gi->env.eval(gi->env.ctx, w, rgb);
			if (gi->env_mis)
				wt *= power(cs / PI, gi->env.pdf(gi->env.ctx, w));
			for (int a = 0; a < 3; a++)
				rgb[a] *= wt;
		}
		if (gi->has_sky)
			for (int a = 0; a < 3; a++)
				rgb[a] += PI * gi->sky[a];
		for (int a = 0; a < 3; a++)
			E[a] += rgb[a];
		return;
	}
	if (st)
		st->hits++;
	if (depth < gi->bounces && (albedo[0] > 0 || albedo[1] > 0 ||
	    albedo[2] > 0)) {
		double ny[3], yw[3], Ey[3];

		vx_iso_normal(gi->g, &x.hit, w, ny);
		vx_index_to_world(gi->g, x.hit.p, yw);
		vertex(gi, yw, x.hit.p, ny, iso, high, NULL, stream, index,
		    depth + 1, albedo, Ey, st);
		for (int a = 0; a < 3; a++)
			E[a] += albedo[a] * Ey[a];
	}
}

void
vx_gi_sample(const vx_gi *gi, const double pi[3], const double n[3],
    double iso, int high, const double D[3], uint64_t stream,
    uint64_t index, double rgb[3], vx_gi_stats *st)
{
	double pw[3], albedo[3];

	vx_index_to_world(gi->g, pi, pw);
	vx_gi_albedo(gi, iso, albedo);
	vertex(gi, pw, pi, n, iso, high, D, stream, index, 0, albedo, rgb, st);
	if (st)
		st->samples++;
}

int
vx_gi_transfer(const vx_gi *gi, const double pi[3], const double n[3],
    double iso, int high, uint64_t stream, uint64_t index, double w[3],
    double thru[3], vx_gi_stats *st)
{
	double p[3], nn[3], albedo[3];

	memcpy(p, pi, sizeof p);
	memcpy(nn, n, sizeof nn);
	vx_gi_albedo(gi, iso, albedo);
	thru[0] = thru[1] = thru[2] = 1;
	if (st)
		st->samples++;
	for (int depth = 0; ; depth++) {
		double u[2], lw[3], t[3], b[3], o[3], di[3];
		first_ctx x;

		offset(gi, p, nn, gi->eps, o);
		vx_onb(nn, t, b);
		vx_rng_ld2(gi->seed, stream, index, 3u * (unsigned)depth, u);
		vx_warp_cosine_hemisphere(u, lw);
		vx_onb_to_world(nn, t, b, lw, w);
		vx_unit3(w);
		vx_world_to_index_dir(gi->g, w, di);
		if (st)
			st->rays++;
		if (!trace(gi, o, di, gi->vicinity, iso, high, &x, st))
			return 1;
		if (st)
			st->hits++;
		if (depth >= gi->bounces || !(albedo[0] > 0 || albedo[1] > 0 ||
		    albedo[2] > 0))
			return 0;
		for (int a = 0; a < 3; a++)
			thru[a] *= albedo[a];
		vx_iso_normal(gi->g, &x.hit, w, nn);
		memcpy(p, x.hit.p, sizeof p);
	}
}

void
vx_gi_stats_add(vx_gi_stats *a, const vx_gi_stats *b)
{
	a->samples += b->samples;
	a->rays += b->rays;
	a->shadow_rays += b->shadow_rays;
	a->hits += b->hits;
	a->iso.rays += b->iso.rays;
	a->iso.cells += b->iso.cells;
	a->iso.roots += b->iso.roots;
	a->iso.hits += b->iso.hits;
}
