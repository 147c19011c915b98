/* embree_common.c: what the Embree peers share (embree_common.h). */
#define _GNU_SOURCE
#include <errno.h>
#include <getopt.h>
#include <omp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "embree_common.h"

void
die(int code, const char *fmt, ...)
{
	va_list ap;

	fprintf(stderr, "%s: ", peer_name);
	va_start(ap, fmt);
	vfprintf(stderr, fmt, ap);
	va_end(ap);
	fputc('\n', stderr);
	exit(code);
}

double
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

void
parse_vecn(const char *opt, int argc, char **argv, double *out, int n)
{
	if (optind + n - 1 > argc)
		die(64, "%s needs %d numbers\n%s", opt, n, peer_usage);
	out[0] = parse_num(opt, optarg);
	for (int i = 1; i < n; i++)
		out[i] = parse_num(opt, argv[optind++]);
}

static uint32_t
le32(const unsigned char *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
	    (uint32_t)p[3] << 24;
}

void
read_mesh(const char *path, mesh *m)
{
	FILE *f = fopen(path, "rb");
	unsigned char hdr[16];
	long size;
	uint64_t need;

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
		die(65, "%s: %ld bytes, the counts (%u vertices, %u triangles) "
		    "need %llu", path, size, m->nv, m->nt,
		    (unsigned long long)need);
	if (m->nv == 0 || m->nt == 0)
		die(65, "%s: empty mesh", path);
	if (fseek(f, 16, SEEK_SET) != 0)
		die(74, "%s: cannot seek", path);
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
	for (size_t i = 0; i < (size_t)m->nt * 3; i++)
		if (m->tri[i] >= m->nv)
			die(65, "%s: triangle %zu refers to vertex %u of %u",
			    path, i / 3, m->tri[i], m->nv);
}

void
free_mesh(mesh *m)
{
	free(m->pos);
	free(m->tri);
	free(m->nrm);
}

void
camera_setup(camera *c, const double look[3], const double up_in[3])
{
	double up[3] = {up_in[0], up_in[1], up_in[2]};

	for (int i = 0; i < 3; i++)
		c->f[i] = look[i] - c->eye[i];
	if (!unit(c->f))
		die(64, "eye and look coincide");
	if (!unit(up))
		die(64, "--up must be a nonzero vector");
	cross(c->f, up, c->u);
	if (!(sqrt(dot(c->u, c->u)) > 1e-9)) {
		double z[3] = {0, 0, 1}, y[3] = {0, 1, 0};

		cross(c->f, fabs(c->f[2]) < 0.9 ? z : y, c->u);
	}
	unit(c->u);
	cross(c->u, c->f, c->v);
	unit(c->v);
}

void
camera_dir(const camera *c, int px, int py, double d[3])
{
	double sx = 2.0 * (px + 0.5) / c->w - 1.0;
	double sy = 1.0 - 2.0 * (py + 0.5) / c->h;
	double aspect = (double)c->w / c->h, t = tan(c->fov * M_PI / 360.0);

	for (int i = 0; i < 3; i++)
		d[i] = c->f[i] + sx * t * aspect * c->u[i] + sy * t * c->v[i];
	unit(d);
}

static void
on_embree_error(void *user, enum RTCError code, const char *str)
{
	die(70, "embree error %d: %s", (int)code, str ? str : "");
}

RTCDevice
peer_device(int *threads)
{
	char config[64] = "";
	RTCDevice dev;

	if (*threads > 0) {
		omp_set_num_threads(*threads);
		snprintf(config, sizeof config, "threads=%d", *threads);
	} else
		*threads = omp_get_max_threads();
	if (!(dev = rtcNewDevice(config[0] ? config : NULL)))
		die(70, "rtcNewDevice failed (%d)", (int)rtcGetDeviceError(NULL));
	rtcSetDeviceErrorFunction(dev, on_embree_error, NULL);
	return dev;
}

RTCGeometry
peer_geometry(RTCDevice dev, const mesh *m, enum RTCBuildQuality q)
{
	RTCGeometry geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);

	memcpy(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
	    RTC_FORMAT_FLOAT3, 12, m->nv), m->pos, (size_t)m->nv * 12);
	memcpy(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
	    RTC_FORMAT_UINT3, 12, m->nt), m->tri, (size_t)m->nt * 12);
	rtcSetGeometryBuildQuality(geom, q);
	rtcCommitGeometry(geom);
	return geom;
}

double
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

double
median(double *v, int n)
{
	qsort(v, n, sizeof *v, cmp_double);
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void
write_pfm(const char *path, const float *img, int w, int h, int nc)
{
	char tmp[4096];
	FILE *f;

	if (snprintf(tmp, sizeof tmp, "%s.tmp%ld", path, (long)getpid()) >=
	    (int)sizeof tmp)
		die(73, "%s: path too long", path);
	if (!(f = fopen(tmp, "wb")))
		die(73, "%s: %s", tmp, strerror(errno));
	fprintf(f, "%s\n%d %d\n-1.0\n", nc == 3 ? "PF" : "Pf", w, h);
	for (int y = h - 1; y >= 0; y--)
		fwrite(img + (size_t)nc * y * w, sizeof(float),
		    (size_t)nc * w, f);
	if (fflush(f) != 0 || ferror(f) || fclose(f) != 0) {
		remove(tmp);
		die(74, "%s: write failed", path);
	}
	if (rename(tmp, path) != 0) {
		remove(tmp);
		die(73, "%s: %s", path, strerror(errno));
	}
}
