/* env.c: environment lights (vx_env.h): the lat-long and angular mappings,
 * exact pixel solid angles, lookups, the pixel iterator, importance sampling
 * by marginal and conditional CDFs, the content hash, the sky, and loading
 * a scene's environment lights. */
#include "vx_env.h"
#include "vx_imageio.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Rec. 709 luminance: the sampling weight of a pixel's radiance */
static const double lum_w[3] = { 0.2126, 0.7152, 0.0722 };

/* 8-point Gauss-Legendre nodes and weights on [-1, 1] (4 of each sign) */
static const double gl_x[4] = {
	0.1834346424956498049, 0.5255324099163289858,
	0.7966664774136267396, 0.9602898564975362317
};
static const double gl_w[4] = {
	0.3626837833783619830, 0.3137066458778872873,
	0.2223810344533744706, 0.1012285362903762592
};

/* ---- the mapping ---- */

int
vx_env_image_to_dir(vx_env_layout layout, int w, int h, double x, double y,
    double dir[3])
{
	if (layout == VX_ENV_ANGULAR) {
		double a = 2 * x / w - 1, b = 1 - 2 * y / h;
		double r = sqrt(a * a + b * b), s;

		if (r > 1) {
			dir[0] = -1;
			dir[1] = dir[2] = 0;
			return -1;
		}
		if (r == 0) {
			dir[0] = 1;
			dir[1] = dir[2] = 0;
			return 0;
		}
		s = sin(M_PI * r) / r;
		dir[0] = cos(M_PI * r);
		dir[1] = -a * s;
		dir[2] = b * s;
		return 0;
	} else {
		double theta = M_PI * y / h, phi = M_PI - 2 * M_PI * x / w;
		double st = sin(theta);

		dir[0] = st * cos(phi);
		dir[1] = st * sin(phi);
		dir[2] = cos(theta);
		return 0;
	}
}

void
vx_env_dir_to_image(vx_env_layout layout, int w, int h, const double dir[3],
    double *x, double *y)
{
	double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
	double dx = dir[0] / len, dy = dir[1] / len, dz = dir[2] / len;

	if (layout == VX_ENV_ANGULAR) {
		/* r = angle from +x / pi, along (a, b) ~ (-y, z) */
		double q = sqrt(dy * dy + dz * dz);
		double r = atan2(q, dx) / M_PI, a, b;

		if (q > 0) {
			a = -dy / q * r;
			b = dz / q * r;
		} else {
			a = r;     /* +x: the centre; -x: the rim, taken at b = 0 */
			b = 0;
		}
		*x = (a + 1) * w / 2;
		*y = (1 - b) * h / 2;
	} else {
		double s = (M_PI - atan2(dy, dx)) / (2 * M_PI);
		double t = acos(dz < -1 ? -1 : dz > 1 ? 1 : dz) / M_PI;

		if (!(s < 1))   /* atan2 = -pi exactly (the -x meridian) */
			s = 0;
		*x = s * w;
		*y = t * h;
	}
}

/* ---- solid angles ---- */

/* latlong_row_omega: a pixel's solid angle in row j of h, w columns:
 * (2 pi / w)(cos t0 - cos t1), written without the cancellation. */
static double
latlong_row_omega(int j, int w, int h)
{
	return 4 * M_PI / w * sin(M_PI * (j + 0.5) / h) * sin(M_PI / (2 * h));
}

/* seg_flux: over the part of the segment p -> q inside the unit disc, the
 * integral of (1 - cos(pi r)) / r^2 (x dy - y dx): the angular map's
 * solid-angle density pi sin(pi r) / r, as the flux of h(r) r_hat with
 * h = (1 - cos pi r) / r through the segment (divergence theorem). */
static double
seg_flux(double px, double py, double qx, double qy)
{
	double dx = qx - px, dy = qy - py;
	double cross = px * dy - py * dx;      /* x dy - y dx per unit t */
	double a = dx * dx + dy * dy, b = px * dx + py * dy;
	double disc, sq, t0, t1, sum = 0;
	int pieces;

	/* the line's distance to the origin is |cross| / |d|: the chord's
	 * half-length (in t) is sqrt(a - cross^2) / a (Lagrange's identity
	 * b^2 - a (|p|^2 - 1) = a - cross^2, exact at tangency) */
	if (cross == 0 || a == 0)
		return 0;
	disc = a - cross * cross;
	if (disc <= 0)
		return 0;
	sq = sqrt(disc);
	t0 = (-b - sq) / a;
	t1 = (-b + sq) / a;
	t0 = t0 > 0 ? t0 : 0;
	t1 = t1 < 1 ? t1 : 1;
	if (!(t1 > t0))
		return 0;
	/* pieces of at most 1/16 in length keep the rule at rounding level */
	pieces = (int)ceil((t1 - t0) * sqrt(a) * 16);
	pieces = pieces < 1 ? 1 : pieces;
	for (int k = 0; k < pieces; k++) {
		double lo = t0 + (t1 - t0) * k / pieces;
		double hi = t0 + (t1 - t0) * (k + 1) / pieces;
		double mid = (lo + hi) / 2, half = (hi - lo) / 2, part = 0;

		for (int g = 0; g < 8; g++) {
			double t = mid + (g < 4 ? -gl_x[g] : gl_x[g - 4]) * half;
			double x = px + t * dx, y = py + t * dy;
			double r2 = x * x + y * y, sh = sin(M_PI / 2 * sqrt(r2));

			part += gl_w[g & 3] * 2 * sh * sh / r2;
		}
		sum += part * half;
	}
	return cross * sum;
}

static int
cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

/* arc_in_box: the angle of the unit circle inside [u0,u1] x [v0,v1]. */
static double
arc_in_box(double u0, double u1, double v0, double v1)
{
	double ang[9], lim[4] = { u0, u1, v0, v1 }, total = 0;
	int n = 0;

	for (int k = 0; k < 4; k++) {
		double c = lim[k], s;

		if (!(fabs(c) < 1))
			continue;
		s = sqrt((1 - c) * (1 + c));
		for (int sg = -1; sg <= 1; sg += 2) {
			double o = sg * s;

			if (k < 2 && o >= v0 && o <= v1)
				ang[n++] = atan2(o, c);
			else if (k >= 2 && o >= u0 && o <= u1)
				ang[n++] = atan2(c, o);
		}
	}
	if (n == 0)
		return u0 <= 1 && 1 <= u1 && v0 <= 0 && 0 <= v1 ? 2 * M_PI : 0;
	qsort(ang, (size_t)n, sizeof *ang, cmp_double);
	ang[n] = ang[0] + 2 * M_PI;
	for (int k = 0; k < n; k++) {
		double mid = (ang[k] + ang[k + 1]) / 2;
		double cx = cos(mid), cy = sin(mid);

		if (cx >= u0 && cx <= u1 && cy >= v0 && cy <= v1)
			total += ang[k + 1] - ang[k];
	}
	return total;
}

/* angular_omega: every pixel's solid angle (w * h, top row first), from the
 * edges' fluxes (each edge once, shared by its two pixels) and the rim. */
static int
angular_omega(double *om, int w, int h, vx_err *e)
{
	double *top = vx_malloc(sizeof *top * (size_t)w * 2, e), *bot;
	double *vert = vx_malloc(sizeof *vert * ((size_t)w + 1), e);

	if (top == NULL || vert == NULL) {
		free(top);
		free(vert);
		return VX_ENOMEM;
	}
	bot = top + w;
	/* H(v, i): flux along +a across [a_i, a_i+1] at height v */
	for (int i = 0; i < w; i++)
		top[i] = seg_flux(2.0 * i / w - 1, 1, 2.0 * (i + 1) / w - 1, 1);
	for (int j = 0; j < h; j++) {
		double v1 = 1 - 2.0 * j / h, v0 = 1 - 2.0 * (j + 1) / h;

		for (int i = 0; i < w; i++)
			bot[i] = seg_flux(2.0 * i / w - 1, v0, 2.0 * (i + 1) / w -
			    1, v0);
		/* V(a, j): flux along +b across [v0, v1] at a */
		for (int i = 0; i <= w; i++) {
			double a = 2.0 * i / w - 1;

			vert[i] = seg_flux(a, v0, a, v1);
		}
		for (int i = 0; i < w; i++) {
			double u0 = 2.0 * i / w - 1, u1 = 2.0 * (i + 1) / w - 1;
			double nx = u0 > 0 ? u0 : u1 < 0 ? u1 : 0;
			double ny = v0 > 0 ? v0 : v1 < 0 ? v1 : 0;
			double fx = fabs(u0) > fabs(u1) ? u0 : u1;
			double fy = fabs(v0) > fabs(v1) ? v0 : v1;
			double o;

			if (nx * nx + ny * ny >= 1) {   /* wholly outside */
				om[(size_t)j * w + i] = 0;
				continue;
			}
			/* ccw: bottom +a, right +b, top -a, left -b */
			o = bot[i] + vert[i + 1] - top[i] - vert[i];
			if (fx * fx + fy * fy > 1)      /* the rim crosses it */
				o += 2 * arc_in_box(u0, u1, v0, v1);
			om[(size_t)j * w + i] = o > 0 ? o : 0;
		}
		memcpy(top, bot, sizeof *top * (size_t)w);
	}
	free(top);
	free(vert);
	return 0;
}

static double
pixel_omega(const vx_env *env, int i, int j)
{
	return env->layout == VX_ENV_ANGULAR ?
	    env->omega[(size_t)j * env->w + i] : env->omega[j];
}

/* ---- making and freeing ---- */

uint64_t
vx_env_hash(const float *px, int w, int h)
{
	uint64_t x = 0xcbf29ce484222325ULL;
	size_t n = (size_t)w * (size_t)h * 3;
	unsigned char b[4];

#define FNV(byte) (x = (x ^ (byte)) * 0x100000001b3ULL)
	for (int k = 0; k < 4; k++)
		FNV((uint32_t)w >> (8 * k) & 0xff);
	for (int k = 0; k < 4; k++)
		FNV((uint32_t)h >> (8 * k) & 0xff);
	for (size_t i = 0; i < n; i++) {
		uint32_t u;

		memcpy(&u, &px[i], 4);
		for (int k = 0; k < 4; k++)
			b[k] = (unsigned char)(u >> (8 * k));
		for (int k = 0; k < 4; k++)
			FNV(b[k]);
	}
#undef FNV
	return x;
}

void
vx_env_free(vx_env *env)
{
	if (env == NULL)
		return;
	free(env->px);
	free(env->omega);
	free(env->cdf_row);
	free(env->cdf_col);
	memset(env, 0, sizeof *env);
}

/* rotation: R = Rz(c) Ry(b) Rx(a), degrees. */
static void
rotation(double R[3][3], const double deg[3])
{
	double a = deg[0] * M_PI / 180, b = deg[1] * M_PI / 180;
	double c = deg[2] * M_PI / 180;
	double ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b);
	double cc = cos(c), sc = sin(c);

	R[0][0] = cc * cb;
	R[0][1] = cc * sb * sa - sc * ca;
	R[0][2] = cc * sb * ca + sc * sa;
	R[1][0] = sc * cb;
	R[1][1] = sc * sb * sa + cc * ca;
	R[1][2] = sc * sb * ca - cc * sa;
	R[2][0] = -sb;
	R[2][1] = cb * sa;
	R[2][2] = cb * ca;
}

/* weight: pixel (i, j)'s sampling weight. */
static double
weight(const vx_env *env, int i, int j)
{
	const float *p = env->px + 3 * ((size_t)j * env->w + i);
	double om = pixel_omega(env, i, j), y = 0;

	if (env->uniform)
		return om;
	for (int c = 0; c < 3; c++)
		y += lum_w[c] * env->scale[c] * p[c];
	return y * om;
}

/* tables: the marginal and conditional CDFs. */
static int
tables(vx_env *env, vx_err *e)
{
	int w = env->w, h = env->h;
	double total = 0;

	env->cdf_row = vx_malloc(sizeof(double) * ((size_t)h + 1), e);
	env->cdf_col = vx_malloc(sizeof(double) * ((size_t)w + 1) * (size_t)h,
	    e);
	if (env->cdf_row == NULL || env->cdf_col == NULL)
		return VX_ENOMEM;
	for (int pass = 0; pass < 2; pass++) {
		env->uniform = pass == 1;
		total = 0;
		env->cdf_row[0] = 0;
		for (int j = 0; j < h; j++) {
			double *cc = env->cdf_col + (size_t)j * (w + 1), row = 0;

			cc[0] = 0;
			for (int i = 0; i < w; i++) {
				row += weight(env, i, j);
				cc[i + 1] = row;
			}
			for (int i = 1; i <= w; i++)   /* a black row: uniform */
				cc[i] = row > 0 ? cc[i] / row : (double)i / w;
			cc[w] = 1;
			total += row;
			env->cdf_row[j + 1] = total;
		}
		if (total > 0 && isfinite(total))
			break;
	}
	for (int j = 1; j <= h; j++)
		env->cdf_row[j] /= total;
	env->cdf_row[h] = 1;
	env->total = total;
	return 0;
}

int
vx_env_init(vx_env *env, const vx_image *img, vx_env_layout layout,
    const double scale[3], const double rotation_deg[3], vx_err *e)
{
	int w = img->w, h = img->h, rc;
	size_t n;

	memset(env, 0, sizeof *env);
	if (layout != VX_ENV_LATLONG && layout != VX_ENV_ANGULAR)
		return vx_err_set(e, VX_EUSAGE, "environment: unknown layout");
	if (img->nc != 1 && img->nc != 3)
		return vx_err_set(e, VX_EDATA, "environment: %d channels (1 or "
		    "3)", img->nc);
	if (layout == VX_ENV_ANGULAR && w != h)
		return vx_err_set(e, VX_EDATA, "environment: an angular map must "
		    "be square (this one is %d x %d)", w, h);
	for (int c = 0; c < 3; c++)
		if (scale != NULL && !(scale[c] >= 0 && isfinite(scale[c])))
			return vx_err_set(e, VX_EUSAGE, "environment: scale "
			    "must be finite and >= 0");
	n = (size_t)w * (size_t)h;
	env->layout = layout;
	env->w = w;
	env->h = h;
	if ((env->px = vx_malloc(n * 3 * sizeof(float), e)) == NULL)
		goto fail;
	for (size_t i = 0; i < n; i++)
		for (int c = 0; c < 3; c++) {
			float v = img->px[i * (size_t)img->nc +
			    (img->nc == 3 ? (size_t)c : 0)];

			if (!isfinite(v)) {
				vx_err_set(e, VX_EDATA, "environment: pixel (%zu, "
				    "%zu) is %s", i % (size_t)w, i / (size_t)w,
				    isnan(v) ? "NaN" : "infinite");
				goto fail;
			}
			if (v < 0)
				env->nclamped++;
			env->px[3 * i + c] = v > 0 ? v : 0;   /* -0 too */
		}
	env->hash = vx_env_hash(env->px, w, h);
	for (int c = 0; c < 3; c++)
		env->scale[c] = scale != NULL ? scale[c] : 1;
	rotation(env->rot, rotation_deg != NULL ? rotation_deg :
	    (const double[3]){ 0, 0, 0 });
	if (layout == VX_ENV_ANGULAR) {
		if ((env->omega = vx_malloc(n * sizeof(double), e)) == NULL ||
		    angular_omega(env->omega, w, h, e) != 0)
			goto fail;
	} else {
		if ((env->omega = vx_malloc((size_t)h * sizeof(double), e)) ==
		    NULL)
			goto fail;
		for (int j = 0; j < h; j++)
			env->omega[j] = latlong_row_omega(j, w, h);
	}
	if (tables(env, e) != 0)
		goto fail;
	return 0;
fail:
	rc = e->code;
	vx_env_free(env);
	return rc;
}

int
vx_env_sky(vx_env *env, const double rgb[3], vx_err *e)
{
	static float one[3] = { 1, 1, 1 };
	vx_image img;

	vx_image_init(&img);
	img.w = img.h = 1;
	img.nc = 3;
	img.px = one;
	return vx_env_init(env, &img, VX_ENV_LATLONG, rgb, NULL, e);
}

int
vx_env_load_light(vx_env *env, const vx_light *l, vx_err *e)
{
	double rgb[3];
	vx_image img;
	int rc;

	memset(env, 0, sizeof *env);
	for (int c = 0; c < 3; c++)
		rgb[c] = l->color[c] * l->intensity;
	if (l->type == VX_LIGHT_SKY)
		return vx_env_sky(env, rgb, e);
	if (l->type != VX_LIGHT_ENVIRONMENT)
		return vx_err_set(e, VX_EUSAGE, "a %s light is no environment",
		    vx_enum_str(&vx_light_type_enum, l->type));
	if ((rc = vx_image_read_linear_file(&img, l->file, NULL, e)) != 0)
		return rc;
	rc = vx_env_init(env, &img, l->layout, rgb, l->rotation, e);
	vx_image_free(&img);
	if (rc != 0)
		return vx_err_push(e, "%s", l->file);
	if (l->has_hash && l->hash != env->hash) {
		vx_err_set(e, VX_EDATA, "%s: content hash %016llx differs from "
		    "the scene's %016llx (the file changed)", l->file,
		    (unsigned long long)env->hash,
		    (unsigned long long)l->hash);
		vx_env_free(env);
		return VX_EDATA;
	}
	return 0;
}

int
vx_env_scene_resolve(vx_scene *s, vx_err *e)
{
	for (int k = 0; k < s->nlight; k++) {
		vx_light *l = &s->light[k];
		vx_env env;

		if (l->type != VX_LIGHT_ENVIRONMENT)
			continue;
		if (vx_env_load_light(&env, l, e) != 0)
			return vx_err_push(e, "light %d", k + 1);
		l->hash = env.hash;
		l->has_hash = 1;
		vx_env_free(&env);
	}
	return 0;
}

/* ---- the light ---- */

/* to_map: the map-frame direction of world direction d (R^T d). */
static void
to_map(const vx_env *env, const double d[3], double m[3])
{
	for (int a = 0; a < 3; a++)
		m[a] = env->rot[0][a] * d[0] + env->rot[1][a] * d[1] +
		    env->rot[2][a] * d[2];
}

static void
to_world(const vx_env *env, const double m[3], double d[3])
{
	for (int a = 0; a < 3; a++)
		d[a] = env->rot[a][0] * m[0] + env->rot[a][1] * m[1] +
		    env->rot[a][2] * m[2];
}

static int
clampi(int v, int lo, int hi)
{
	return v < lo ? lo : v > hi ? hi : v;
}

/* pixel_at: the pixel holding image point (x, y). */
static void
pixel_at(const vx_env *env, double x, double y, int *i, int *j)
{
	*i = clampi((int)floor(x), 0, env->w - 1);
	*j = clampi((int)floor(y), 0, env->h - 1);
}

void
vx_env_lookup(const vx_env *env, const double dir[3], int bilinear,
    double rgb[3])
{
	double m[3], x, y, acc[3] = { 0, 0, 0 };
	int w = env->w, h = env->h;

	to_map(env, dir, m);
	vx_env_dir_to_image(env->layout, w, h, m, &x, &y);
	if (!bilinear) {
		int i, j;
		const float *p;

		pixel_at(env, x, y, &i, &j);
		p = env->px + 3 * ((size_t)j * w + i);
		for (int c = 0; c < 3; c++)
			rgb[c] = env->scale[c] * p[c];
		return;
	}
	x -= 0.5;
	y -= 0.5;
	{
		double fx = floor(x), fy = floor(y), tx = x - fx, ty = y - fy;
		int x0 = (int)fx, y0 = (int)fy;

		for (int k = 0; k < 4; k++) {
			int xi = x0 + (k & 1), yi = clampi(y0 + (k >> 1), 0, h - 1);
			double wk = ((k & 1) ? tx : 1 - tx) *
			    ((k >> 1) ? ty : 1 - ty);
			const float *p;

			if (env->layout == VX_ENV_LATLONG)
				xi = ((xi % w) + w) % w;
			else
				xi = clampi(xi, 0, w - 1);
			p = env->px + 3 * ((size_t)yi * w + xi);
			for (int c = 0; c < 3; c++)
				acc[c] += wk * p[c];
		}
	}
	for (int c = 0; c < 3; c++)
		rgb[c] = env->scale[c] * acc[c];
}

size_t
vx_env_npixel(const vx_env *env)
{
	return (size_t)env->w * (size_t)env->h;
}

void
vx_env_pixel(const vx_env *env, size_t idx, double dir[3], double *omega,
    double rgb[3])
{
	int i = (int)(idx % (size_t)env->w), j = (int)(idx / (size_t)env->w);
	const float *p = env->px + 3 * idx;
	double m[3];

	(void)vx_env_image_to_dir(env->layout, env->w, env->h, i + 0.5, j + 0.5,
	    m);
	to_world(env, m, dir);
	*omega = pixel_omega(env, i, j);
	for (int c = 0; c < 3; c++)
		rgb[c] = env->scale[c] * p[c];
}

/* find: the k in [0, n) with cdf[k] <= u < cdf[k + 1] (cdf[0] = 0,
 * cdf[n] = 1, u in [0, 1)): pieces of zero width are never chosen. */
static int
find(const double *cdf, int n, double u)
{
	int lo = 0, hi = n;       /* cdf[lo] <= u < cdf[hi] */

	while (hi - lo > 1) {
		int mid = lo + (hi - lo) / 2;

		if (cdf[mid] <= u)
			lo = mid;
		else
			hi = mid;
	}
	return lo;
}

/* remainder: where u falls in [lo, hi), in [0, 1). */
static double
remainder01(double u, double lo, double hi)
{
	double f = (u - lo) / (hi - lo);

	return f < 0 ? 0 : f < 1 ? f : 0x1.fffffffffffffp-1;
}

/* jacobian: dw / (da db) of the angular map at radius r: pi sin(pi r)/r. */
static double
jacobian(double r)
{
	return r > 0 ? M_PI * sin(M_PI * r) / r : M_PI * M_PI;
}

/* pixel_pdf: the probability of pixel (i, j). */
static double
pixel_prob(const vx_env *env, int i, int j)
{
	return weight(env, i, j) / env->total;
}

double
vx_env_sample(const vx_env *env, const double u[2], double dir[3],
    double rgb[3])
{
	int w = env->w, h = env->h, i, j;
	double a, b, m[3], pdf, prob;
	const double *cc;
	const float *p;

	j = find(env->cdf_row, h, u[0]);
	a = remainder01(u[0], env->cdf_row[j], env->cdf_row[j + 1]);
	cc = env->cdf_col + (size_t)j * (w + 1);
	i = find(cc, w, u[1]);
	b = remainder01(u[1], cc[i], cc[i + 1]);
	prob = pixel_prob(env, i, j);
	if (env->layout == VX_ENV_LATLONG) {
		double z0 = cos(M_PI * j / h), dz, z, rr, phi;

		/* uniform in cos theta over the row, in phi over the pixel */
		dz = 2 * sin(M_PI * (j + 0.5) / h) * sin(M_PI / (2 * h));
		z = z0 - a * dz;
		z = z < -1 ? -1 : z > 1 ? 1 : z;
		rr = sqrt(1 - z * z);
		phi = M_PI - 2 * M_PI * (i + b) / w;
		m[0] = rr * cos(phi);
		m[1] = rr * sin(phi);
		m[2] = z;
		pdf = prob / env->omega[j];
	} else {
		/* uniform in the pixel's square: a down, b right */
		double x = i + b, y = j + a;
		double aa = 2 * x / w - 1, bb = 1 - 2 * y / h;
		double r = sqrt(aa * aa + bb * bb);

		if (!(r < 1) || vx_env_image_to_dir(env->layout, w, h, x, y,
		    m) != 0 || !(jacobian(r) > 0)) {
			memset(dir, 0, 3 * sizeof *dir);
			memset(rgb, 0, 3 * sizeof *rgb);
			return 0;
		}
		pdf = prob / ((2.0 / w) * (2.0 / h) * jacobian(r));
	}
	to_world(env, m, dir);
	p = env->px + 3 * ((size_t)j * w + i);
	for (int c = 0; c < 3; c++)
		rgb[c] = env->scale[c] * p[c];
	return pdf;
}

double
vx_env_pdf(const vx_env *env, const double dir[3])
{
	double m[3], x, y;
	int i, j;

	to_map(env, dir, m);
	vx_env_dir_to_image(env->layout, env->w, env->h, m, &x, &y);
	pixel_at(env, x, y, &i, &j);
	if (env->layout == VX_ENV_LATLONG)
		return pixel_prob(env, i, j) / env->omega[j];
	{
		double aa = 2 * x / env->w - 1, bb = 1 - 2 * y / env->h;
		double r = sqrt(aa * aa + bb * bb), jac = jacobian(r);

		if (!(r < 1) || !(jac > 0))
			return 0;
		return pixel_prob(env, i, j) / ((2.0 / env->w) *
		    (2.0 / env->h) * jac);
	}
}
