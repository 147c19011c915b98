/* embree_render.c: benchmark peer: Lambert+headlight rendering of an extracted
 * isosurface mesh with Embree 3 (BVH build time, frame time), voxlux's camera. */
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

const char *peer_name = "embree_render";
const char *peer_usage =
	"usage: embree_render -m MESH -o OUT.pfm --eye X Y Z --look X Y Z [--up X Y Z]\n"
	"                     (--fov DEG | --ortho WIDTH) [--size W H] [-j THREADS]\n"
	"                     [-n FRAMES] [-b BUILDS] [-q low|medium|high]";

/* camera_ray: the ray through the centre of pixel (px, py), (0,0) top-left. */
static void
camera_ray(const camera *c, int px, int py, float org[3], float dir[3])
{
	int i;

	if (c->fov > 0) {
		double d[3];

		camera_dir(c, px, py, d);
		for (i = 0; i < 3; i++) {
			org[i] = (float)c->eye[i];
			dir[i] = (float)d[i];
		}
	} else {
		double sx = 2.0 * (px + 0.5) / c->w - 1.0;
		double sy = 1.0 - 2.0 * (py + 0.5) / c->h;
		double hw = c->ortho / 2, hh = hw / ((double)c->w / c->h);

		for (i = 0; i < 3; i++) {
			org[i] = (float)(c->eye[i] + sx * hw * c->u[i] + sy * hh * c->v[i]);
			dir[i] = (float)c->f[i];
		}
	}
}

/* render: one frame into img (row 0 at the top).  Rows are spread over the
 * OpenMP threads (dynamic schedule), one rtcIntersect1 per pixel. */
static void
render(RTCScene scene, const mesh *m, const camera *c, float *img)
{
	int py;

#pragma omp parallel for schedule(dynamic, 1)
	for (py = 0; py < c->h; py++) {
		struct RTCIntersectContext ctx;
		int px;

		rtcInitIntersectContext(&ctx);
		for (px = 0; px < c->w; px++) {
			struct RTCRayHit rh;
			float org[3], dir[3], shade = 0;

			camera_ray(c, px, py, org, dir);
			memset(&rh, 0, sizeof rh);
			rh.ray.org_x = org[0];
			rh.ray.org_y = org[1];
			rh.ray.org_z = org[2];
			rh.ray.dir_x = dir[0];
			rh.ray.dir_y = dir[1];
			rh.ray.dir_z = dir[2];
			rh.ray.tnear = 0;
			rh.ray.tfar = INFINITY;
			rh.ray.mask = UINT32_MAX;
			rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
			rtcIntersect1(scene, &ctx, &rh);
			if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
				const uint32_t *t = m->tri + 3 * (size_t)rh.hit.primID;
				float b0 = 1 - rh.hit.u - rh.hit.v, n[3], l;
				int i;

				for (i = 0; i < 3; i++)
					n[i] = b0 * m->nrm[3 * t[0] + i] +
					    rh.hit.u * m->nrm[3 * t[1] + i] +
					    rh.hit.v * m->nrm[3 * t[2] + i];
				l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
				if (!(l > 0)) {
					n[0] = rh.hit.Ng_x;
					n[1] = rh.hit.Ng_y;
					n[2] = rh.hit.Ng_z;
					l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
				}
				/* headlight: the light is at the eye, so L = -dir;
				 * the normal is flipped to face the ray */
				shade = fabsf(n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2]) / l;
			}
			img[(size_t)py * c->w + px] = shade;
		}
	}
}

int
main(int argc, char **argv)
{
	static const struct option lopts[] = {
		{"eye", required_argument, 0, 'E'}, {"look", required_argument, 0, 'L'},
		{"up", required_argument, 0, 'U'}, {"fov", required_argument, 0, 'F'},
		{"ortho", required_argument, 0, 'O'}, {"size", required_argument, 0, 'S'},
		{0, 0, 0, 0}};
	const char *meshpath = NULL, *out = NULL;
	double look[3] = {0, 0, 0}, up[3] = {0, 0, 1}, t0, c0, *times, *cpu;
	int threads = 0, frames = 5, builds = 1, have_eye = 0, have_look = 0, opt, i;
	enum RTCBuildQuality quality = RTC_BUILD_QUALITY_MEDIUM;
	const char *qname = "medium";
	camera cam = {.fov = 0, .ortho = 0, .w = 512, .h = 512};
	RTCDevice dev;
	RTCScene scene = NULL;
	RTCGeometry geom;
	mesh m;
	float *img;

	while ((opt = getopt_long(argc, argv, "m:o:j:n:b:q:h", lopts, NULL)) != -1) {
		switch (opt) {
		case 'm': meshpath = optarg; break;
		case 'o': out = optarg; break;
		case 'j': threads = (int)parse_num("-j", optarg); break;
		case 'n': frames = (int)parse_num("-n", optarg); break;
		case 'b': builds = (int)parse_num("-b", optarg); break;
		case 'q':
			qname = optarg;
			if (!strcmp(optarg, "low"))
				quality = RTC_BUILD_QUALITY_LOW;
			else if (!strcmp(optarg, "medium"))
				quality = RTC_BUILD_QUALITY_MEDIUM;
			else if (!strcmp(optarg, "high"))
				quality = RTC_BUILD_QUALITY_HIGH;
			else
				die(64, "-q: low, medium or high, not '%s'", optarg);
			break;
		case 'E': parse_vecn("--eye", argc, argv, cam.eye, 3); have_eye = 1; break;
		case 'L': parse_vecn("--look", argc, argv, look, 3); have_look = 1; break;
		case 'U': parse_vecn("--up", argc, argv, up, 3); break;
		case 'F': cam.fov = parse_num("--fov", optarg); break;
		case 'O': cam.ortho = parse_num("--ortho", optarg); break;
		case 'S': {
			double wh[2];

			parse_vecn("--size", argc, argv, wh, 2);
			if (!(wh[0] >= 1 && wh[0] <= MAX_IMAGE && wh[1] >= 1 &&
			    wh[1] <= MAX_IMAGE))
				die(64, "--size: 1..%d", MAX_IMAGE);
			cam.w = (int)wh[0];
			cam.h = (int)wh[1];
			break;
		}
		case 'h': puts(peer_usage); return 0;
		default: die(64, "%s", peer_usage);
		}
	}
	if (optind != argc || !meshpath || !out || !have_eye || !have_look)
		die(64, "%s", peer_usage);
	if ((cam.fov > 0) == (cam.ortho > 0))
		die(64, "give exactly one of --fov DEG (0..180) or --ortho WIDTH (> 0)");
	if (cam.fov >= 180)
		die(64, "--fov: %g is not below 180", cam.fov);
	if (cam.w < 1 || cam.h < 1 || cam.w > MAX_IMAGE || cam.h > MAX_IMAGE)
		die(64, "--size: 1..%d", MAX_IMAGE);
	if (frames < 1 || frames > MAX_FRAMES || builds < 1 || builds > MAX_FRAMES)
		die(64, "-n and -b: 1..%d", MAX_FRAMES);
	if (threads < 0)
		die(64, "-j: not negative");
	camera_setup(&cam, look, up);
	read_mesh(meshpath, &m);
	dev = peer_device(&threads);

	/* BVH build: the geometry is set up once (a copy into Embree's buffers,
	 * not timed); each build is a fresh scene committed from it. */
	geom = peer_geometry(dev, &m, quality);
	times = malloc(sizeof *times * (frames > builds ? frames : builds));
	cpu = malloc(sizeof *cpu * (frames > builds ? frames : builds));
	if (!times || !cpu)
		die(71, "out of memory");
	for (i = 0; i < builds; i++) {
		if (scene)
			rtcReleaseScene(scene);
		scene = rtcNewScene(dev);
		rtcSetSceneBuildQuality(scene, quality);
		rtcAttachGeometry(scene, geom);
		c0 = cpu_seconds();
		t0 = omp_get_wtime();
		rtcCommitScene(scene);
		times[i] = omp_get_wtime() - t0;
		cpu[i] = cpu_seconds() - c0;
	}
	printf("mesh %s vertices %u triangles %u\n", meshpath, m.nv, m.nt);
	printf("build_ms %.3f (median of %d, quality %s, embree %s, threads %d)\n",
	    1e3 * median(times, builds), builds, qname, RTC_VERSION_STRING, threads);
	printf("build_cpu_ms %.3f (process CPU time, median of %d)\n",
	    1e3 * median(cpu, builds), builds);

	if (!(img = malloc(sizeof *img * (size_t)cam.w * cam.h)))
		die(71, "out of memory");
	render(scene, &m, &cam, img);	/* warm-up frame */
	for (i = 0; i < frames; i++) {
		c0 = cpu_seconds();
		t0 = omp_get_wtime();
		render(scene, &m, &cam, img);
		times[i] = omp_get_wtime() - t0;
		cpu[i] = cpu_seconds() - c0;
	}
	printf("render_ms %.3f (median of %d frames after 1 warm-up, %dx%d, %s, "
	    "threads %d, rtcIntersect1 per pixel, OpenMP dynamic over rows)\n",
	    1e3 * median(times, frames), frames, cam.w, cam.h,
	    cam.fov > 0 ? "perspective" : "orthographic", threads);
	printf("render_cpu_ms %.3f (process CPU time, median of %d frames)\n",
	    1e3 * median(cpu, frames), frames);
	write_pfm(out, img, cam.w, cam.h, 1);

	rtcReleaseScene(scene);
	rtcReleaseGeometry(geom);
	rtcReleaseDevice(dev);
	free(img);
	free(times);
	free(cpu);
	free_mesh(&m);
	return 0;
}
