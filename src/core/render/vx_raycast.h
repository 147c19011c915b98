/* vx_raycast.h: the ray-cast isosurface renderer (Parker et al. 1999 §4.1):
 * one primary ray per pixel sample through the macrocell hierarchy, the
 * analytic cell intersection, Lambert and Blinn-Phong shading from point,
 * directional and head lights, hard shadows through the same traversal,
 * transparent layers composited front to back in one traversal, and a second
 * volume mapped as color onto a surface.  What is computed is what the plan
 * (vx_plan.h, from the scene) says, no more.
 *
 * Output: linear RGBA radiance, premultiplied by alpha = coverage
 * (formats/image.md; the background is not in it: composite with
 * vx_image_flatten or tonemap --background), and on request the depth of the first hit
 * (distance along the unit camera ray, +Inf where nothing was hit) and its
 * world-space unit normal.  Bit-identical for any thread count. */
#ifndef VX_RAYCAST_H
#define VX_RAYCAST_H

#include <stdint.h>

#include "vx_grid.h"
#include "vx_image.h"
#include "vx_irrvol.h"
#include "vx_iso.h"
#include "vx_cellmask.h"
#include "vx_macro.h"
#include "vx_plan.h"
#include "vx_scene.h"
#include "vx_tetleaf.h"

typedef struct vx_raycast_opts {
	int nthreads;            /* <= 0: OpenMP's default (vx_par_threads) */
	int solver;              /* vx_cell_solver */
	int flat;                /* 1: no hierarchy (benchmarks) */
	int aa;                  /* samples per pixel edge (aa x aa grid), >= 1 */
	int tile;                /* tile edge in pixels (default 16) */
	double shadow_offset;    /* shadow-ray start offset along the normal,
	                            in voxels (meshes: in units of the mean tet
	                            size, (box volume / tets)^(1/3); default
	                            1e-3) */
	int timing;              /* 1: measure the share of time per phase */
	int no_binning;          /* 1: every primary ray walks from its start
	                            (same picture, for measuring the bins:
	                            each ray otherwise walks only the binned
	                            boxes it enters, and a ray that enters
	                            none is not walked) */
	int bin_block;           /* edge of the blocks of leaves binned (1 to
	                            VX_RAYCAST_BLOCK_MAX; <= 0: the default,
	                            VX_RAYCAST_BLOCK): each block's box of
	                            bracketing leaves is binned, and a ray
	                            walks the boxes it enters, leaf by leaf
	                            inside each (same picture whatever the
	                            edge: for measuring it) */
	int no_cellmask;         /* 1: no cell mask (vx_cellmask.h): the walk
	                            reads every stepped leaf's samples (same
	                            picture, for measuring the mask) */
	vx_cellmask *mask_keep;  /* NULL (a mask per render), or a mask the
	                            caller keeps between renders (made with
	                            vx_cellmask_init, freed with
	                            vx_cellmask_free): reused, with the bits
	                            already built, while the hierarchy and the
	                            isovalues stay the same; rebuilt when they
	                            change.  A kept mask with bits built skips
	                            the first pass over the bins' centres
	                            (first_pass 0): a camera that turns to new
	                            macrocells walks them whole in that frame,
	                            building their bits (the same picture) */
	const vx_irrvol *irr;    /* the plan's irradiance volume (volumes
	                            only; required when plan.irradiance) */
	vx_interp irr_interp;   /* how it is read */
	const double *shl;       /* the plan's SH lighting when plan.sh
	                            (vx_surface.h) */
	vx_irr_need_fn irr_need; /* non-NULL: a collecting pass for lazy
	                            illumination: instead of reading irr,
	                            each shaded point reports the texels its
	                            lookup will read (vx_irr_reach; called
	                            from every thread: it must be safe so)
	                            and is drawn black */
	void *irr_need_ctx;
	const struct vx_gi *gi;  /* the plan's path tracer (pathtrace) */
} vx_raycast_opts;

/* Primary rays are binned with the boxes of the bracketing leaves of each
 * block of VX_RAYCAST_BLOCK^3 leaves by default (with a cell mask; else
 * whole level-1 macrocells); bin_block sets the edge, up to
 * VX_RAYCAST_BLOCK_MAX (a row of blocks' leaf bits is one word). */
#define VX_RAYCAST_BLOCK 8
#define VX_RAYCAST_BLOCK_MAX 64

typedef struct vx_raycast_stats {
	uint64_t primary, shadow;        /* rays */
	uint64_t cells, roots, hits;     /* cell kernel work, all rays (meshes:
	                                    cells = tets tested (segment
	                                    computed), hits = crossings,
	                                    roots 0) */
	uint64_t bounded, certified;     /* roots: misses settled by the
	                                    cubic's sign bound, and of them
	                                    those settled without the face
	                                    values (vx_iso_stats) */
	uint64_t exact;                  /* signs the cell kernel's filter
	                                    left undecided, evaluated exactly
	                                    (vx_iso_stats) */
	uint64_t leaves, entries;        /* meshes: leaf lists searched, and
	                                    their entries scanned */
	int mesh;                        /* 1: the source was a mesh */
	uint64_t macro[VX_MACRO_MAXLEV + 1];
	uint64_t culled;                 /* volumes: leaves stepped through
	                                    without a visit (not bracketing) */
	uint64_t nonfinite;              /* cells skipped for NaN/Inf corners */
	uint64_t shaded;                 /* surface points shaded */
	uint64_t paths, gi_rays;         /* pathtrace: paths, and rays they
	                                    traced (bounce and shadow) */
	uint64_t irr_missing;            /* of them, irradiance lookups that
	                                    found no usable texel (drawn
	                                    black) */
	uint64_t covered;                /* pixels with a hit */
	double seconds;                  /* wall time of the render (the
	                                    cell mask's build included) */
	uint64_t mask_bytes;             /* its memory, 0: none */
	int bins;                /* 1: primary rays were binned */
	int bin_block;           /* the binned boxes: those of the bracketing
	                            leaves of each block of bin_block^3
	                            leaves, or 0: whole level-1 macrocells */
	uint64_t bin_boxes;      /* boxes binned (the bins' entries are
	                            more: a box is in each bin it covers) */
	uint64_t bin_whole;      /* of them whole level-1 macrocells (with
	                            bin_block: those whose bits no ray had
	                            built) */
	uint64_t binned;         /* primary rays that entered no binned box:
	                            not walked */
	double bin_seconds;      /* wall time of making the bins (the bits
	                            of the cell mask they needed included) */
	uint64_t first_pass;     /* pixels drawn before the main pass, to
	                            build the bits of the macrocells in sight
	                            (the bins' centres; only with a mask no
	                            ray had entered: one made for the frame) */
	uint64_t mask_blocks, mask_set, mask_built;   /* level-1 macrocells,
	                                    those bracketing (masked), and
	                                    those whose bits rays needed */
	double share_traverse, share_isect, share_shade;   /* when timing */
	int threads;             /* threads the frame ran on */
	double tile_seconds;     /* wall time of the frame's tiles (the
	                            main pass over the pixels) */
	double thread_seconds;   /* the threads' time in those tiles, summed:
	                            at 1 thread tile_seconds; at N, the same
	                            work spread over N, plus what running side
	                            by side costs each thread; thread_seconds
	                            / (N tile_seconds) is the tiles' balance */
} vx_raycast_stats;

void vx_raycast_opts_init(vx_raycast_opts *o);

/* vx_raycast_render: render scene s (its camera must be resolved) as planned
 * by p over volume g with hierarchy m (NULL: flat).  tex[k] is surface k's
 * texture volume (NULL when p->texture_on[k] is 0).  color is allocated as
 * w x h x 4; depth (w x h x 1) and normal (w x h x 3) when non-NULL.
 * st may be NULL.  Errors: VX_ENOMEM, VX_EDATA (no surface to draw). */
int vx_raycast_render(const vx_scene *s, const vx_plan *p, const vx_grid *g,
    const vx_macro *m, const vx_grid *const *tex,
    const vx_raycast_opts *o, vx_image *color, vx_image *depth,
    vx_image *normal, vx_raycast_stats *st, vx_err *e);

/* vx_raycast_render_mesh: the same picture of tet mesh `mesh` through its
 * leaf grid lg (vx_tetleaf_build or vx_tetleaf_from_stream): every
 * crossing of the primary ray in order (vx_tetleaf_trace), shaded with the
 * tet's constant gradient as normal (facing the viewer), composited,
 * shadowed and counted exactly as for a volume; the camera is resolved
 * over the mesh's box by the caller.  o->solver and o->flat do not apply.
 * Same outputs and errors as vx_raycast_render. */
int vx_raycast_render_mesh(const vx_scene *s, const vx_plan *p,
    const vx_tetmesh *mesh, const vx_tetleaf *lg, const vx_grid *const *tex,
    const vx_raycast_opts *o, vx_image *color, vx_image *depth,
    vx_image *normal, vx_raycast_stats *st, vx_err *e);

#endif
