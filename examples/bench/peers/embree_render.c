/* embree_render.c: benchmark peer: Lambert+headlight rendering of an extracted
 * isosurface mesh with Embree 3 (BVH build time, frame time), voxlux's camera. */
#define _GNU_SOURCE
#include <embree3/rtcore.h>
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* The mesh file (written by extract.py; see README.md):
 *   "VXMESH01" | u32 nverts | u32 ntris | f32 xyz[nverts][3] | u32 tri[ntris][3]
 *   | f32 normal[nverts][3], all little-endian. */
#define MESH_MAGIC "VXMESH01"
#define MAX_FRAMES 1000
#define MAX_IMAGE 16384

static const char *usage =
	"usage: embree_render -m MESH -o OUT.pfm --eye X Y Z --look X Y Z [--up X Y Z]\n"
	"                     (--fov DEG | --ortho WIDTH) [--size W H] [-j THREADS]\n"
	"                     [-n FRAMES] [-b BUILDS] [-q low|medium|high]";

typedef struct {
	uint32_t nv, nt;
	float *pos;		/* nv*3 */
	uint32_t *tri;		/* nt*3 */
	float *nrm;		/* nv*3 */
} mesh;

typedef struct {
	double eye[3], f[3], u[3], v[3];
	double fov, ortho;	/* fov > 0: perspective; else ortho = view width */
	int w, h;
} camera;

_Noreturn static void die(int code, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

static void
die(int code, const char *fmt, ...)
{
	va_list ap;

	fputs("embree_render: ", stderr);
	va_start(ap, fmt);
	vfprintf(stderr, fmt, ap);
	va_end(ap);
	fputc('\n', stderr);
	exit(code);
}

static double
parse_num(const char *opt, const char *s)
{
	char *end;
	double x;

	errno = 0;
	x = strtod(s, &end);
	if (errno || end == s || *end || !isfinite(x))
		die(64, "%s: not a number: '%s'", opt, s);
	return x;
}

/* parse_vec3: the option's argument and the two following argv words. */
static void
parse_vec3(const char *opt, int argc, char **argv, double out[3])
{
	if (optind + 2 > argc)
		die(64, "%s needs three numbers\n%s", opt, usage);
	out[0] = parse_num(opt, optarg);
	out[1] = parse_num(opt, argv[optind++]);
	out[2] = parse_num(opt, argv[optind++]);
}

static uint32_t
le32(const unsigned char *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
	    (uint32_t)p[3] << 24;
}

/* read_mesh: load and validate the mesh file; exits on error.  The counts are
 * checked against the file size before anything is allocated. */
static void
read_mesh(const char *path, mesh *m)
{
	FILE *f = fopen(path, "rb");
	unsigned char hdr[16];
	long size;
	uint64_t need;
	size_t i;

	if (!f)
		die(66, "%s: %s", path, strerror(errno));
	if (fread(hdr, 1, 16, f) != 16 || memcmp(hdr, MESH_MAGIC, 8) != 0)
		die(65, "%s: not a VXMESH01 mesh", path);
	m->nv = le32(hdr + 8);
	m->nt = le32(hdr + 12);
	if (fseek(f, 0, SEEK_END) != 0 || (size = ftell(f)) < 0)
		die(74, "%s: cannot seek", path);
	need = 16 + (uint64_t)m->nv * 24 + (uint64_t)m->nt * 12;
	if ((uint64_t)size != need)
		die(65, "%s: %ld bytes, the counts (%u vertices, %u triangles) need %llu",
		    path, size, m->nv, m->nt, (unsigned long long)need);
	if (m->nv == 0 || m->nt == 0)
		die(65, "%s: empty mesh", path);
	fseek(f, 16, SEEK_SET);
	m->pos = malloc((size_t)m->nv * 12);
	m->tri = malloc((size_t)m->nt * 12);
	m->nrm = malloc((size_t)m->nv * 12);
	if (!m->pos || !m->tri || !m->nrm)
		die(71, "%s: out of memory", path);
	if (fread(m->pos, 12, m->nv, f) != m->nv ||
	    fread(m->tri, 12, m->nt, f) != m->nt ||
	    fread(m->nrm, 12, m->nv, f) != m->nv)
		die(74, "%s: short read", path);
	fclose(f);
	/* The file is little-endian; so is every machine Embree runs on here. */
	for (i = 0; i < (size_t)m->nt * 3; i++)
		if (m->tri[i] >= m->nv)
			die(65, "%s: triangle %zu refers to vertex %u of %u", path,
			    i / 3, m->tri[i], m->nv);
}

static void
normalize(double a[3])
{
	double l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);

	a[0] /= l;
	a[1] /= l;
	a[2] /= l;
}

static void
cross(const double a[3], const double b[3], double out[3])
{
	out[0] = a[1] * b[2] - a[2] * b[1];
	out[1] = a[2] * b[0] - a[0] * b[2];
	out[2] = a[0] * b[1] - a[1] * b[0];
}

/* camera_setup: the frame f (forward), u (right), v (up) from eye, look, up,
 * as voxlux's vx_camera_resolve does it: (u, v, -f) is right-handed, and an up
 * (nearly) parallel to f is replaced by z, or y when |f.z| >= 0.9. */
static void
camera_setup(camera *c, const double look[3], const double up_in[3])
{
	double up[3] = {up_in[0], up_in[1], up_in[2]};
	int i;

	for (i = 0; i < 3; i++)
		c->f[i] = look[i] - c->eye[i];
	if (c->f[0] == 0 && c->f[1] == 0 && c->f[2] == 0)
		die(64, "eye and look coincide");
	if (up[0] == 0 && up[1] == 0 && up[2] == 0)
		die(64, "--up must be a nonzero vector");
	normalize(c->f);
	normalize(up);
	cross(c->f, up, c->u);
	if (!(sqrt(c->u[0] * c->u[0] + c->u[1] * c->u[1] + c->u[2] * c->u[2]) > 1e-9)) {
		double z[3] = {0, 0, 1}, y[3] = {0, 1, 0};

		cross(c->f, fabs(c->f[2]) < 0.9 ? z : y, c->u);
	}
	normalize(c->u);
	cross(c->u, c->f, c->v);
	normalize(c->v);
}

/* camera_ray: the ray through the centre of pixel (px, py), (0,0) top-left. */
static void
camera_ray(const camera *c, int px, int py, float org[3], float dir[3])
{
	double sx = 2.0 * (px + 0.5) / c->w - 1.0;
	double sy = 1.0 - 2.0 * (py + 0.5) / c->h;
	double aspect = (double)c->w / c->h, d[3];
	int i;

	if (c->fov > 0) {
		double t = tan(c->fov * M_PI / 360.0);

		for (i = 0; i < 3; i++)
			d[i] = c->f[i] + sx * t * aspect * c->u[i] + sy * t * c->v[i];
		normalize(d);
		for (i = 0; i < 3; i++) {
			org[i] = (float)c->eye[i];
			dir[i] = (float)d[i];
		}
	} else {
		double hw = c->ortho / 2, hh = hw / aspect;

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

/* cpu_seconds: CPU time of the whole process (all threads, Embree's and
 * OpenMP's), to read beside wall time on a shared machine. */
static double
cpu_seconds(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static int
cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

static double
median(double *v, int n)
{
	qsort(v, n, sizeof *v, cmp_double);
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* write_pfm: gray PFM, little-endian, rows bottom to top; atomically. */
static void
write_pfm(const char *path, const float *img, int w, int h)
{
	char tmp[4096];
	FILE *f;
	int y;

	if (snprintf(tmp, sizeof tmp, "%s.tmp%ld", path, (long)getpid()) >= (int)sizeof tmp)
		die(73, "%s: path too long", path);
	if (!(f = fopen(tmp, "wb")))
		die(73, "%s: %s", tmp, strerror(errno));
	fprintf(f, "Pf\n%d %d\n-1.0\n", w, h);
	for (y = h - 1; y >= 0; y--)
		fwrite(img + (size_t)y * w, sizeof(float), w, f);
	if (fflush(f) != 0 || ferror(f) || fclose(f) != 0) {
		remove(tmp);
		die(74, "%s: write failed", path);
	}
	if (rename(tmp, path) != 0) {
		remove(tmp);
		die(73, "%s: %s", path, strerror(errno));
	}
}

static void
on_embree_error(void *user, enum RTCError code, const char *str)
{
	die(70, "embree error %d: %s", (int)code, str ? str : "");
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
	char config[64] = "";
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
		case 'E': parse_vec3("--eye", argc, argv, cam.eye); have_eye = 1; break;
		case 'L': parse_vec3("--look", argc, argv, look); have_look = 1; break;
		case 'U': parse_vec3("--up", argc, argv, up); break;
		case 'F': cam.fov = parse_num("--fov", optarg); break;
		case 'O': cam.ortho = parse_num("--ortho", optarg); break;
		case 'S':
			if (optind + 1 > argc)
				die(64, "--size needs two numbers\n%s", usage);
			cam.w = (int)parse_num("--size", optarg);
			cam.h = (int)parse_num("--size", argv[optind++]);
			break;
		case 'h': puts(usage); return 0;
		default: die(64, "%s", usage);
		}
	}
	if (optind != argc || !meshpath || !out || !have_eye || !have_look)
		die(64, "%s", usage);
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
	if (threads > 0) {
		omp_set_num_threads(threads);
		snprintf(config, sizeof config, "threads=%d", threads);
	} else
		threads = omp_get_max_threads();

	read_mesh(meshpath, &m);
	if (!(dev = rtcNewDevice(config[0] ? config : NULL)))
		die(70, "rtcNewDevice failed (%d)", (int)rtcGetDeviceError(NULL));
	rtcSetDeviceErrorFunction(dev, on_embree_error, NULL);

	/* BVH build: the geometry is set up once (a copy into Embree's buffers,
	 * not timed); each build is a fresh scene committed from it. */
	geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
	memcpy(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
	    RTC_FORMAT_FLOAT3, 12, m.nv), m.pos, (size_t)m.nv * 12);
	memcpy(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
	    RTC_FORMAT_UINT3, 12, m.nt), m.tri, (size_t)m.nt * 12);
	rtcSetGeometryBuildQuality(geom, quality);
	rtcCommitGeometry(geom);
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
	write_pfm(out, img, cam.w, cam.h);

	rtcReleaseScene(scene);
	rtcReleaseGeometry(geom);
	rtcReleaseDevice(dev);
	free(img);
	free(times);
	free(cpu);
	free(m.pos);
	free(m.tri);
	free(m.nrm);
	return 0;
}
