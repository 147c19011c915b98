/* helper_dvr.h: the slab scenes the direct-volume-rendering tests share
 * (test_dvr.c, test_dvrref.c; helper_dvr.c). */
#ifndef HELPER_DVR_H
#define HELPER_DVR_H

#include "vx_dvr.h"

/* dvr_prepare: scene s from text (which must parse), its transfer function
 * tf (initialized here; vx_tf_apply_scene, vx_tf_check must pass), the
 * slicer's decisions d and plan p under options o, and when g is not NULL
 * the camera resolved over g's box.  A failure fails the test. */
void dvr_prepare(const char *text, const vx_grid *g, const vx_dvr_opts *o,
    vx_scene *s, vx_tf *tf, vx_dvr_decide *d, vx_plan *p);

/* zgrid: g (initialized here) of nx x ny x nz f32 samples, value f(z
 * index) on every sample of layer z. */
void zgrid(vx_grid *g, int nx, int ny, int nz, double (*f)(int));

/* Layer values along z for zgrid: z_one 1 everywhere; two slabs of one
 * material, the receiver z in [6, 13] and the occluder z in [24, 29]
 * (1 there, else 0): z_slabs both, z_receiver and z_occluder each alone. */
double z_one(int z);
double z_slabs(int z);
double z_receiver(int z);
double z_occluder(int z);

/* wide_slab: g (initialized here) of 400 x 400 x 40 u8 samples, all 1: a
 * slab 39 deep that fills an oblique view.  wide_slab_scene: the scene
 * text (into buf of size n) that looks at it orthographically from 30
 * degrees off its normal in the x-z plane (the path through it 39 / cos 30),
 * 4 x 4 pixels, no light, ambient 1, constant opacity alpha. */
void wide_slab(vx_grid *g);
void wide_slab_scene(char *buf, size_t n, double alpha);

#endif
