/* embree_common.h: what the Embree peers (embree_render.c, embree_pt.c)
 * share: errors, number options, the VXMESH01 mesh, voxlux's camera frame,
 * the device and the mesh's geometry, timing and PFM output
 * (embree_common.c). */
#ifndef EMBREE_COMMON_H
#define EMBREE_COMMON_H

#include <embree3/rtcore.h>
#include <math.h>
#include <stdint.h>

/* The mesh file (written by extract.py; see README.md):
 *   "VXMESH01" | u32 nverts | u32 ntris | f32 xyz[nverts][3] | u32 tri[ntris][3]
 *   | f32 normal[nverts][3], all little-endian. */
#define MESH_MAGIC "VXMESH01"
#define MAX_FRAMES 1000
#define MAX_IMAGE 16384

/* the program's name and usage, for die() and the option parsers */
extern const char *peer_name, *peer_usage;

_Noreturn void die(int code, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

/* parse_num: a finite number, else exit 64 naming opt. */
double parse_num(const char *opt, const char *s);
/* parse_vecn: the option's argument (optarg) and the n - 1 following argv
 * words, as numbers. */
void parse_vecn(const char *opt, int argc, char **argv, double *out, int n);

typedef struct {
	uint32_t nv, nt;
	float *pos;		/* nv*3 */
	uint32_t *tri;		/* nt*3 */
	float *nrm;		/* nv*3 */
} mesh;

/* read_mesh: load and validate the mesh file; exits on error.  The counts
 * are checked against the file size before anything is allocated. */
void read_mesh(const char *path, mesh *m);
void free_mesh(mesh *m);

static inline double
dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void
cross(const double a[3], const double b[3], double out[3])
{
	out[0] = a[1] * b[2] - a[2] * b[1];
	out[1] = a[2] * b[0] - a[0] * b[2];
	out[2] = a[0] * b[1] - a[1] * b[0];
}

/* unit: a / |a|; 0 (a unchanged) when a is zero or not finite. */
static inline int
unit(double a[3])
{
	double l = sqrt(dot(a, a));

	if (!(l > 0) || !isfinite(l))
		return 0;
	a[0] /= l;
	a[1] /= l;
	a[2] /= l;
	return 1;
}

typedef struct {
	double eye[3], f[3], u[3], v[3];
	double fov, ortho;	/* fov > 0: perspective; else ortho = view width */
	int w, h;
} camera;

/* camera_setup: the frame f (forward), u (right), v (up) from eye, look,
 * up, as voxlux's vx_camera_resolve does it (README.md, "Camera"): (u, v,
 * -f) is right-handed, and an up (nearly) parallel to f is replaced by z,
 * or y when |f.z| >= 0.9.  Exits 64 when eye and look coincide or up is
 * zero. */
void camera_setup(camera *c, const double look[3], const double up_in[3]);

/* camera_dir: the unit direction of the perspective ray through the
 * centre of pixel (px, py), (0,0) top-left; the ray starts at the eye. */
void camera_dir(const camera *c, int px, int py, double d[3]);

/* peer_device: the Embree device, with `threads` threads (0: OpenMP's
 * default, returned) made OpenMP's too; errors exit 70. */
RTCDevice peer_device(int *threads);

/* peer_geometry: the mesh's committed triangle geometry (vertices and
 * indices copied into Embree's buffers) at build quality q. */
RTCGeometry peer_geometry(RTCDevice dev, const mesh *m,
    enum RTCBuildQuality q);

/* cpu_seconds: CPU time of the whole process (all threads, Embree's and
 * OpenMP's), to read beside wall time on a shared machine. */
double cpu_seconds(void);
/* median: of v[0..n-1] (sorted in place). */
double median(double *v, int n);

/* write_pfm: nc (1 or 3) channels of w x h floats, row 0 at the top, as a
 * little-endian PFM (rows bottom to top); atomically. */
void write_pfm(const char *path, const float *img, int w, int h, int nc);

#endif
