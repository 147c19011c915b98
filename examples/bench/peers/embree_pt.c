/* embree_pt.c: benchmark peer: a path tracer of an extracted isosurface mesh
 * with Embree 3, the scene of voxlux's `raycast --set "illumination
 * pathtrace"` (src/core/render/vx_gi.h): a sky, one directional light with
 * shadows, Lambertian albedo, N bounces, voxlux's camera.  Prints the frame
 * time and the time per path (per sample of a covered pixel), writes an RGB
 * PFM.  See README.md, "Path tracing".
 *
 * What a pixel computes (the same estimator as vx_gi_sample):
 *   first hit x0 of the camera ray, shading normal n0 (the interpolated
 *   vertex normal, turned toward the eye), D0 = the directional light's
 *   irradiance pi I cos (a shadow ray), once per pixel;
 *   per sample: a cosine-weighted direction about n0; the ray escapes: pi L_sky;
 *   it hits x1 while bounces remain: albedo (D(x1) + the same step at x1);
 *   pixel = albedo E / pi, E = D0 + the mean over the samples.
 * The last segment of a path only asks whether it escapes (an occlusion
 * ray), as do the shadow rays.  Rays start 'eps' world units off the
 * surface along its geometric normal, on the side they leave by.
 *
 * Random numbers: each (pixel, depth) gets a rotation (a hash), sample i of
 * it is the i-th point of the R2 sequence (Roberts' generalized golden
 * ratio) shifted by it, modulo 1 (Cranley-Patterson): stratified like a
 * low-discrepancy set, and a pure function of (seed, pixel, depth, i), so
 * the picture is the same at any thread count. */
#define _GNU_SOURCE
#include <embree3/rtcore.h>
#include <getopt.h>
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "embree_common.h"

#define MAX_SPP 65536
#define MAX_BOUNCES 64
#define PI 3.14159265358979323846

const char *peer_name = "embree_pt";
const char *peer_usage =
	"usage: embree_pt -m MESH -o OUT.pfm --eye X Y Z --look X Y Z [--up X Y Z]\n"
	"                 --fov DEG [--size W H] [--spp N] [--bounces B]\n"
	"                 [--sky R G B] [--sun DX DY DZ R G B] [--albedo R G B]\n"
	"                 [--eps E] [--seed S] [--packets] [-j THREADS] [-n FRAMES]\n"
	"                 [-w WARMUPS]";

typedef struct {
	int spp, bounces, packets;
	double sky[3];		/* radiance */
	int has_sun;
	double sun_dir[3];	/* unit, toward the light */
	double sun_rgb[3];	/* pi C I */
	double albedo[3];	/* colour times kd */
	double eps;		/* ray start offset, world units */
	uint64_t seed;
} scene;

typedef struct {
	uint64_t covered, paths, primary, shadow, bounce;
} counts;

/* ---- random numbers ---- */

static uint64_t
mix64(uint64_t z)
{
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
	return z ^ (z >> 31);
}

/* rot: the Cranley-Patterson rotation of (pixel, depth), two numbers in
 * [0, 1). */
static void
rot(uint64_t seed, uint64_t pixel, int depth, double r[2])
{
	uint64_t h = mix64(seed ^ mix64(pixel * 64 + (uint64_t)depth + 1));

	r[0] = (h >> 11) * 0x1.0p-53;
	r[1] = (mix64(h) >> 11) * 0x1.0p-53;
}

/* r2: point i of the R2 sequence rotated by r, in [0, 1)^2. */
static void
r2(const double r[2], int i, double u[2])
{
	static const double a1 = 0.7548776662466927, a2 = 0.5698402909980532;
	double x = r[0] + a1 * i, y = r[1] + a2 * i;

	u[0] = x - floor(x);
	u[1] = y - floor(y);
	if (u[0] >= 1)
		u[0] = 0;
	if (u[1] >= 1)
		u[1] = 0;
}

/* cosine_dir: a cosine-weighted unit direction about unit n from u. */
static void
cosine_dir(const double n[3], const double u[2], double w[3])
{
	double t[3], b[3], r = sqrt(u[0]), phi = 2 * PI * u[1];
	double x = r * cos(phi), y = r * sin(phi), z = sqrt(fmax(0, 1 - u[0]));
	double s = n[2] >= 0 ? 1 : -1, a = -1 / (s + n[2]), c = n[0] * n[1] * a;

	/* Duff et al.'s branchless orthonormal basis */
	t[0] = 1 + s * n[0] * n[0] * a;
	t[1] = s * c;
	t[2] = -s * n[0];
	b[0] = c;
	b[1] = s + n[1] * n[1] * a;
	b[2] = -n[1];
	for (int i = 0; i < 3; i++)
		w[i] = x * t[i] + y * b[i] + z * n[i];
	unit(w);
}

/* ---- tracing ---- */

typedef struct {
	RTCScene scene;
	const mesh *m;
	const scene *s;
} tracer;

/* surf: a hit: point, shading normal n and geometric normal ng, both unit
 * and turned toward the side the ray came from (-dir). */
typedef struct {
	double p[3], n[3], ng[3];
} surf;

static void
set_ray(struct RTCRay *r, const double o[3], const double d[3], float tfar)
{
	r->org_x = (float)o[0];
	r->org_y = (float)o[1];
	r->org_z = (float)o[2];
	r->dir_x = (float)d[0];
	r->dir_y = (float)d[1];
	r->dir_z = (float)d[2];
	r->tnear = 0;
	r->tfar = tfar;
	r->time = 0;
	r->mask = UINT32_MAX;
	r->id = 0;
	r->flags = 0;
}

/* hit_surf: the surface at hit (primID, u, v) seen along dir. */
static void
hit_surf(const tracer *T, unsigned prim, float hu, float hv, const double d[3],
    surf *h)
{
	const mesh *m = T->m;
	const uint32_t *t = m->tri + 3 * (size_t)prim;
	const float *a = m->pos + 3 * (size_t)t[0], *b = m->pos + 3 * (size_t)t[1],
	    *c = m->pos + 3 * (size_t)t[2];
	double b0 = 1.0 - hu - hv, e1[3], e2[3];

	for (int i = 0; i < 3; i++) {
		h->p[i] = b0 * a[i] + hu * b[i] + hv * c[i];
		h->n[i] = b0 * m->nrm[3 * t[0] + i] + hu * m->nrm[3 * t[1] + i] +
		    hv * m->nrm[3 * t[2] + i];
		e1[i] = b[i] - a[i];
		e2[i] = c[i] - a[i];
	}
	cross(e1, e2, h->ng);
	unit(h->ng);
	if (!unit(h->n))
		memcpy(h->n, h->ng, sizeof h->n);
	if (dot(h->ng, d) > 0)
		for (int i = 0; i < 3; i++)
			h->ng[i] = -h->ng[i];
	if (dot(h->n, d) > 0)
		for (int i = 0; i < 3; i++)
			h->n[i] = -h->n[i];
}

/* origin: a ray's start off surface h, on the side of ng. */
static void
origin(const tracer *T, const surf *h, double o[3])
{
	for (int i = 0; i < 3; i++)
		o[i] = h->p[i] + T->s->eps * h->ng[i];
}

/* escapes: 1 when the ray from h along w meets no triangle. */
static int
escapes(const tracer *T, const surf *h, const double w[3])
{
	struct RTCIntersectContext ctx;
	struct RTCRay r;
	double o[3];

	rtcInitIntersectContext(&ctx);
	origin(T, h, o);
	set_ray(&r, o, w, INFINITY);
	rtcOccluded1(T->scene, &ctx, &r);
	return r.tfar >= 0;
}

/* closest: the first surface along the ray from o along w; 0 when none. */
static int
closest(const tracer *T, const double o[3], const double w[3], surf *h)
{
	struct RTCIntersectContext ctx;
	struct RTCRayHit rh;

	rtcInitIntersectContext(&ctx);
	set_ray(&rh.ray, o, w, INFINITY);
	rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
	rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
	rtcIntersect1(T->scene, &ctx, &rh);
	if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
		return 0;
	hit_surf(T, rh.hit.primID, rh.hit.u, rh.hit.v, w, h);
	return 1;
}

/* direct: the directional light's irradiance at h (a shadow ray). */
static void
direct(const tracer *T, const surf *h, double E[3], counts *k)
{
	const scene *s = T->s;
	double cs;

	E[0] = E[1] = E[2] = 0;
	if (!s->has_sun || !((cs = dot(h->n, s->sun_dir)) > 0))
		return;
	k->shadow++;
	if (!escapes(T, h, s->sun_dir))
		return;
	for (int i = 0; i < 3; i++)
		E[i] = s->sun_rgb[i] * cs;
}

/* indirect: one sample's estimate of E - D at h (the part through the
 * cosine-weighted direction of depth d), given that direction w. */
static void
indirect(const tracer *T, const surf *h, const double w[3], uint64_t pixel,
    int sample, int d, double E[3], counts *k)
{
	const scene *s = T->s;
	double thr[3] = {1, 1, 1}, ww[3], o[3];
	surf x = *h, y;

	E[0] = E[1] = E[2] = 0;
	memcpy(ww, w, sizeof ww);
	for (;; d++) {
		double D[3], r[2], u[2];

		k->bounce++;
		if (d == s->bounces) {
			/* the last segment: only its escape matters */
			if (escapes(T, &x, ww))
				for (int i = 0; i < 3; i++)
					E[i] += thr[i] * PI * s->sky[i];
			return;
		}
		origin(T, &x, o);
		if (!closest(T, o, ww, &y)) {
			for (int i = 0; i < 3; i++)
				E[i] += thr[i] * PI * s->sky[i];
			return;
		}
		for (int i = 0; i < 3; i++)
			thr[i] *= s->albedo[i];
		direct(T, &y, D, k);
		for (int i = 0; i < 3; i++)
			E[i] += thr[i] * D[i];
		x = y;
		rot(s->seed, pixel, d + 1, r);
		r2(r, sample, u);
		cosine_dir(x.n, u, ww);
	}
}

/* pixel_packet: the indirect estimates of a pixel's samples with the
 * first bounce rays traced 16 at a time (rtcIntersect16: a common origin);
 * the rest of each path as in indirect(). */
static void
pixel_packet(const tracer *T, const surf *h, uint64_t pixel, double E[3],
    counts *k)
{
	const scene *s = T->s;
	double r[2], o[3];
	int spp = s->spp;

	rot(s->seed, pixel, 0, r);
	origin(T, h, o);
	for (int i0 = 0; i0 < spp; i0 += 16) {
		struct RTCIntersectContext ctx;
		struct RTCRayHit16 rh __attribute__((aligned(64)));
		int valid[16] __attribute__((aligned(64)));
		double w[16][3];
		int n = spp - i0 < 16 ? spp - i0 : 16;

		for (int j = 0; j < 16; j++) {
			double u[2];

			/* an inactive lane holds a well-formed ray too (the
			 * normal's): Debian's Embree asserts on the lanes */
			valid[j] = j < n ? -1 : 0;
			if (j < n) {
				r2(r, i0 + j, u);
				cosine_dir(h->n, u, w[j]);
			} else
				memcpy(w[j], h->n, sizeof w[j]);
			rh.ray.org_x[j] = (float)o[0];
			rh.ray.org_y[j] = (float)o[1];
			rh.ray.org_z[j] = (float)o[2];
			rh.ray.dir_x[j] = (float)w[j][0];
			rh.ray.dir_y[j] = (float)w[j][1];
			rh.ray.dir_z[j] = (float)w[j][2];
			rh.ray.tnear[j] = 0;
			rh.ray.tfar[j] = INFINITY;
			rh.ray.time[j] = 0;
			rh.ray.mask[j] = UINT32_MAX;
			rh.ray.id[j] = 0;
			rh.ray.flags[j] = 0;
			rh.hit.geomID[j] = RTC_INVALID_GEOMETRY_ID;
			rh.hit.instID[0][j] = RTC_INVALID_GEOMETRY_ID;
		}
		rtcInitIntersectContext(&ctx);
		if (s->bounces == 0)
			rtcOccluded16(valid, T->scene, &ctx, &rh.ray);
		else
			rtcIntersect16(valid, T->scene, &ctx, &rh);
		for (int j = 0; j < n; j++) {
			double thr[3], D[3], u[2], ww[3], Ei[3];
			surf y;

			k->bounce++;
			if (s->bounces == 0) {
				if (rh.ray.tfar[j] >= 0)
					for (int i = 0; i < 3; i++)
						E[i] += PI * s->sky[i];
				continue;
			}
			if (rh.hit.geomID[j] == RTC_INVALID_GEOMETRY_ID) {
				for (int i = 0; i < 3; i++)
					E[i] += PI * s->sky[i];
				continue;
			}
			hit_surf(T, rh.hit.primID[j], rh.hit.u[j], rh.hit.v[j],
			    w[j], &y);
			for (int i = 0; i < 3; i++)
				thr[i] = s->albedo[i];
			direct(T, &y, D, k);
			{
				double rr[2];

				rot(s->seed, pixel, 1, rr);
				r2(rr, i0 + j, u);
			}
			cosine_dir(y.n, u, ww);
			indirect(T, &y, ww, pixel, i0 + j, 1, Ei, k);
			for (int i = 0; i < 3; i++)
				E[i] += thr[i] * (D[i] + Ei[i]);
		}
	}
}

/* render_pixel: pixel (px, py) into img. */
static void
render_pixel(const tracer *T, const camera *c, int px, int py, float *img,
    counts *k)
{
	const scene *s = T->s;
	uint64_t pixel = (uint64_t)py * c->w + px;
	double d[3], E[3] = {0, 0, 0}, D[3], r[2];
	float *out = img + 3 * pixel;
	surf h;

	camera_dir(c, px, py, d);
	k->primary++;
	if (!closest(T, c->eye, d, &h)) {
		out[0] = out[1] = out[2] = 0;
		return;
	}
	k->covered++;
	direct(T, &h, D, k);
	if (s->packets) {
		pixel_packet(T, &h, pixel, E, k);
	} else {
		rot(s->seed, pixel, 0, r);
		for (int i = 0; i < s->spp; i++) {
			double u[2], w[3], Ei[3];

			r2(r, i, u);
			cosine_dir(h.n, u, w);
			indirect(T, &h, w, pixel, i, 0, Ei, k);
			for (int a = 0; a < 3; a++)
				E[a] += Ei[a];
		}
	}
	k->paths += s->spp;
	for (int a = 0; a < 3; a++)
		out[a] = (float)(s->albedo[a] * (D[a] + E[a] / s->spp) / PI);
}

/* render: one frame into img (RGB, row 0 at the top).  Rows are spread
 * over the OpenMP threads (dynamic schedule). */
static void
render(const tracer *T, const camera *c, float *img, counts *total)
{
	memset(total, 0, sizeof *total);
#pragma omp parallel
	{
		counts k = {0, 0, 0, 0, 0};

#pragma omp for schedule(dynamic, 1)
		for (int py = 0; py < c->h; py++)
			for (int px = 0; px < c->w; px++)
				render_pixel(T, c, px, py, img, &k);
#pragma omp critical
		{
			total->covered += k.covered;
			total->paths += k.paths;
			total->primary += k.primary;
			total->shadow += k.shadow;
			total->bounce += k.bounce;
		}
	}
}

int
main(int argc, char **argv)
{
	enum { O_EYE = 256, O_LOOK, O_UP, O_FOV, O_SIZE, O_SPP, O_BOUNCES,
	    O_SKY, O_SUN, O_ALBEDO, O_EPS, O_SEED, O_PACKETS };
	static const struct option lopts[] = {
		{"eye", required_argument, 0, O_EYE},
		{"look", required_argument, 0, O_LOOK},
		{"up", required_argument, 0, O_UP},
		{"fov", required_argument, 0, O_FOV},
		{"size", required_argument, 0, O_SIZE},
		{"spp", required_argument, 0, O_SPP},
		{"bounces", required_argument, 0, O_BOUNCES},
		{"sky", required_argument, 0, O_SKY},
		{"sun", required_argument, 0, O_SUN},
		{"albedo", required_argument, 0, O_ALBEDO},
		{"eps", required_argument, 0, O_EPS},
		{"seed", required_argument, 0, O_SEED},
		{"packets", no_argument, 0, O_PACKETS},
		{0, 0, 0, 0}};
	const char *meshpath = NULL, *out = NULL;
	double look[3] = {0, 0, 0}, up[3] = {0, 0, 1}, sun[6], t0, c0, b0;
	double *times, *cpu, build_s, build_cpu_s;
	int threads = 0, frames = 1, warmups = 1, have_eye = 0, have_look = 0;
	int opt, i;
	camera cam = {.fov = 0, .ortho = 0, .w = 512, .h = 512};
	scene s = {.spp = 16, .bounces = 1, .sky = {1, 1, 1},
	    .albedo = {0.8, 0.8, 0.8}, .eps = 1e-3, .seed = 0};
	counts k;
	RTCDevice dev;
	RTCScene rs;
	RTCGeometry geom;
	tracer T;
	mesh m;
	float *img;

	while ((opt = getopt_long(argc, argv, "m:o:j:n:w:h", lopts, NULL)) != -1) {
		switch (opt) {
		case 'm': meshpath = optarg; break;
		case 'o': out = optarg; break;
		case 'j': threads = (int)parse_num("-j", optarg); break;
		case 'n': frames = (int)parse_num("-n", optarg); break;
		case 'w': warmups = (int)parse_num("-w", optarg); break;
		case O_EYE: parse_vecn("--eye", argc, argv, cam.eye, 3);
			have_eye = 1; break;
		case O_LOOK: parse_vecn("--look", argc, argv, look, 3);
			have_look = 1; break;
		case O_UP: parse_vecn("--up", argc, argv, up, 3); break;
		case O_FOV: cam.fov = parse_num("--fov", optarg); break;
		case O_SIZE: {
			double wh[2];

			parse_vecn("--size", argc, argv, wh, 2);
			if (!(wh[0] >= 1 && wh[0] <= MAX_IMAGE && wh[1] >= 1 &&
			    wh[1] <= MAX_IMAGE))
				die(64, "--size: 1..%d", MAX_IMAGE);
			cam.w = (int)wh[0];
			cam.h = (int)wh[1];
			break;
		}
		case O_SPP: s.spp = (int)parse_num("--spp", optarg); break;
		case O_BOUNCES:
			s.bounces = (int)parse_num("--bounces", optarg);
			break;
		case O_SKY: parse_vecn("--sky", argc, argv, s.sky, 3); break;
		case O_SUN:
			parse_vecn("--sun", argc, argv, sun, 6);
			s.has_sun = 1;
			break;
		case O_ALBEDO:
			parse_vecn("--albedo", argc, argv, s.albedo, 3);
			break;
		case O_EPS: s.eps = parse_num("--eps", optarg); break;
		case O_SEED: s.seed = (uint64_t)parse_num("--seed", optarg); break;
		case O_PACKETS: s.packets = 1; break;
		case 'h': puts(peer_usage); return 0;
		default: die(64, "%s", peer_usage);
		}
	}
	if (optind != argc || !meshpath || !out || !have_eye || !have_look)
		die(64, "%s", peer_usage);
	if (!(cam.fov > 0 && cam.fov < 180))
		die(64, "--fov: 0 < DEG < 180");
	if (frames < 1 || frames > MAX_FRAMES || warmups < 0 ||
	    warmups > MAX_FRAMES)
		die(64, "-n: 1..%d, -w: 0..%d", MAX_FRAMES, MAX_FRAMES);
	if (s.spp < 1 || s.spp > MAX_SPP)
		die(64, "--spp: 1..%d", MAX_SPP);
	if (s.bounces < 0 || s.bounces > MAX_BOUNCES)
		die(64, "--bounces: 0..%d", MAX_BOUNCES);
	if (!(s.eps >= 0))
		die(64, "--eps: not negative");
	if (threads < 0)
		die(64, "-j: not negative");
	if (s.has_sun) {
		/* the scene's direction is the light's travel; E = pi C I cos */
		for (i = 0; i < 3; i++) {
			s.sun_dir[i] = -sun[i];
			s.sun_rgb[i] = PI * sun[3 + i];
		}
		if (!unit(s.sun_dir))
			die(64, "--sun: no direction");
	}
	camera_setup(&cam, look, up);
	read_mesh(meshpath, &m);
	dev = peer_device(&threads);
	geom = peer_geometry(dev, &m, RTC_BUILD_QUALITY_MEDIUM);
	rs = rtcNewScene(dev);
	rtcAttachGeometry(rs, geom);
	b0 = cpu_seconds();
	t0 = omp_get_wtime();
	rtcCommitScene(rs);
	build_s = omp_get_wtime() - t0;
	build_cpu_s = cpu_seconds() - b0;
	T.scene = rs;
	T.m = &m;
	T.s = &s;

	times = malloc(sizeof *times * frames);
	cpu = malloc(sizeof *cpu * frames);
	img = malloc(sizeof *img * 3 * (size_t)cam.w * cam.h);
	if (!times || !cpu || !img)
		die(71, "out of memory");
	for (i = 0; i < warmups; i++)
		render(&T, &cam, img, &k);
	for (i = 0; i < frames; i++) {
		c0 = cpu_seconds();
		t0 = omp_get_wtime();
		render(&T, &cam, img, &k);
		times[i] = omp_get_wtime() - t0;
		cpu[i] = cpu_seconds() - c0;
	}
	printf("mesh %s vertices %u triangles %u\n", meshpath, m.nv, m.nt);
	printf("build_ms %.3f (embree %s, quality medium, threads %d; "
	    "process CPU %.3f ms)\n", 1e3 * build_s, RTC_VERSION_STRING, threads,
	    1e3 * build_cpu_s);
	{
		double tm = median(times, frames), cm = median(cpu, frames);
		double np = k.paths ? (double)k.paths : 1;

		printf("render_ms %.3f (median of %d frames after %d warm-up, "
		    "%dx%d, spp %d, bounces %d, threads %d, %s)\n", 1e3 * tm,
		    frames, warmups, cam.w, cam.h, s.spp, s.bounces, threads,
		    s.packets ? "rtcIntersect16 for the first bounce" :
		    "rtcIntersect1/rtcOccluded1 per ray");
		printf("render_cpu_ms %.3f (process CPU time, median of %d "
		    "frames)\n", 1e3 * cm, frames);
		printf("paths %llu covered %llu rays: primary %llu shadow %llu "
		    "bounce %llu\n", (unsigned long long)k.paths,
		    (unsigned long long)k.covered,
		    (unsigned long long)k.primary,
		    (unsigned long long)k.shadow,
		    (unsigned long long)k.bounce);
		printf("ns_per_path %.2f (frame time / paths) ns_per_path_cpu "
		    "%.2f\n", 1e9 * tm / np, 1e9 * cm / np);
	}
	write_pfm(out, img, cam.w, cam.h, 3);

	rtcReleaseScene(rs);
	rtcReleaseGeometry(geom);
	rtcReleaseDevice(dev);
	free(img);
	free(times);
	free(cpu);
	free_mesh(&m);
	return 0;
}
