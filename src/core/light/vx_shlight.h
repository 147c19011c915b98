/* vx_shlight.h: SH lighting, the SHLC chunk (formats/shlight.md): the
 * radiance of a distant environment projected onto real spherical harmonics
 * of order n (vx_sh.h), three channels (r, g, b), with the content hash of
 * the environment it came from and the rotation applied to it. */
#ifndef VX_SHLIGHT_H
#define VX_SHLIGHT_H

#include <stdint.h>

#include "vx_env.h"
#include "vx_err.h"
#include "vx_sh.h"
#include "vx_stream.h"

/* Orders 1 .. 16 (bands 0 .. 15): 256 coefficients per channel at most. */
#define VX_SHLIGHT_MAX_ORDER 16
#define VX_SHLIGHT_MAX_COEF (VX_SHLIGHT_MAX_ORDER * VX_SHLIGHT_MAX_ORDER)

/* The basis's phase: vx_sh.h's (with the Condon-Shortley phase), or
 * Ramamoorthi and Hanrahan's (without; coefficient (l, m) times (-1)^m). */
typedef enum vx_shlight_phase {
	VX_SHLIGHT_PHASE_CS = 0,
	VX_SHLIGHT_PHASE_NONE
} vx_shlight_phase;

typedef struct vx_shlight {
	int order;                /* 1 .. VX_SHLIGHT_MAX_ORDER */
	vx_shlight_phase phase;
	int has_hash;             /* 1: env_hash names the source map */
	uint64_t env_hash;        /* vx_env.h's content hash of the source */
	double rot[3][3];         /* the rotation applied (identity: none),
	                             row-major, proper and orthogonal */
	double c[3 * VX_SHLIGHT_MAX_COEF]; /* channel k's coefficient i at
	                             c[k * order^2 + i] */
} vx_shlight;

/* vx_shlight_init: order 1, phase CS, no hash, identity, zeros. */
void vx_shlight_init(vx_shlight *l);

/* vx_shlight_to_chunk: l as an SHLC chunk (raw body) in c.  Errors:
 * VX_EINTERNAL for an order outside 1 .. 16 or a value that is not finite
 * (checked before anything is made), VX_ENOMEM. */
int vx_shlight_to_chunk(const vx_shlight *l, vx_chunk *c, vx_err *e);

/* vx_shlight_from_chunk: decode chunk c (an SHLC chunk) into l.  Errors
 * (VX_EDATA): another chunk type, a missing or malformed key, order outside
 * 1 .. 16, channels other than 3, an unknown phase, a rotation that is not
 * orthogonal with determinant +1 (to 1e-6), a body whose decoded size is
 * not order^2 x 3 doubles, a coefficient that is NaN or infinite.  On error
 * l is left initialized (vx_shlight_init). */
int vx_shlight_from_chunk(vx_shlight *l, const vx_chunk *c, vx_err *e);

/* vx_shlight_from_stream: the first SHLC chunk of s into l; *idx gets its
 * index, or -1 (and l is initialized, 0 returned) when there is none.
 * Errors as vx_shlight_from_chunk, with the chunk's offset. */
int vx_shlight_from_stream(vx_shlight *l, const vx_stream *s, long *idx,
    vx_err *e);

/* vx_shlight_project: add to c (3 channels of order^2, r's first) the
 * projection of env's radiance by quadrature over the map's pixels: each
 * pixel's radiance times its exact solid angle times Y at its centre
 * (vx_sh.h's basis, with the Condon-Shortley phase); a constant sky (a
 * 1 x 1 lat-long map, vx_env_sky) exactly: its constant term only.  The
 * quadrature's error grows with the order for coarse maps. */
void vx_shlight_project(const vx_env *env, int order, double *c);

/* vx_shlight_from_scene: l (initialized here) of order `order` (1 .. 16)
 * from scene s: the sum of the projections (vx_shlight_project) of every
 * environment and sky light of s, each read by vx_env_load_light (its
 * file's hash checked when the light carries one).  The lights add, as
 * light does: two lights light a surface as their sum.  The source hash is
 * the light's map's when there is exactly one, else none.  *nlight gets
 * how many lights were projected (0: l's coefficients are 0) and *npixel
 * their maps' pixels, all together (either may be NULL).  Errors: as
 * vx_env_load_light's, with "light N: " before; VX_EINTERNAL for an order
 * out of range. */
int vx_shlight_from_scene(vx_shlight *l, const vx_scene *s, int order,
    int *nlight, size_t *npixel, vx_err *e);

#endif
