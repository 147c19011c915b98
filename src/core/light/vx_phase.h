/* vx_phase.h: phase functions of participating media (Kniss et al. 2003,
 * §3.2): Henyey-Greenstein with asymmetry g, the isotropic one, and the
 * paper's approximation, a 1D table indexed by the scaled cosine.
 *
 * Conventions.  cos_theta = dot(w_in, w_out), with w_in the direction the
 * light travels before the scattering event and w_out the direction it
 * travels after (toward the eye): cos_theta = 1 is straight on, so g > 0
 * scatters forward.  vx_phase_hg and vx_phase_iso are normalized over the
 * sphere (integral of p over all w_out = 1), in 1/steradian.  The table
 * holds 4 pi p, the phase relative to isotropic scattering (1 for the
 * isotropic phase), as the paper's unnormalized lookup does: a renderer
 * multiplies the direct light by it. */
#ifndef VX_PHASE_H
#define VX_PHASE_H

/* vx_phase_iso: 1 / (4 pi). */
double vx_phase_iso(void);

/* vx_phase_hg: (1 - g^2) / (4 pi (1 + g^2 - 2 g cos_theta)^(3/2)), for g in
 * (-1, 1) and cos_theta in [-1, 1] (clamped); g 0 is vx_phase_iso. */
double vx_phase_hg(double g, double cos_theta);

/* vx_phase_hg_sample: a direction w_out for unit w_in, distributed as
 * vx_phase_hg(g, dot(w_in, w_out)), from two uniform numbers u1, u2 in
 * [0,1) (vx_rng.h: pure functions of the sample, never a shared
 * generator): cos_theta by inverting the CDF (1 - 2 u1 for |g| < 1e-3),
 * the azimuth 2 pi u2 about w_in.  Returns the pdf of w_out (per
 * steradian), equal to vx_phase_hg_pdf. */
double vx_phase_hg_sample(double g, const double w_in[3], double u1,
    double u2, double w_out[3]);

/* vx_phase_hg_pdf: the density of vx_phase_hg_sample's w_out for unit
 * w_in, w_out: vx_phase_hg(g, dot(w_in, w_out)). */
double vx_phase_hg_pdf(double g, const double w_in[3], const double w_out[3]);

/* The paper's approximation: VX_PHASE_TABLE_N samples of 4 pi p over the
 * scaled cosine t = (cos_theta + 1) / 2 at t = i / (N - 1), linearly
 * interpolated between them. */
#define VX_PHASE_TABLE_N 256

typedef struct vx_phase_table {
	float v[VX_PHASE_TABLE_N];
} vx_phase_table;

/* vx_phase_table_hg: the table of Henyey-Greenstein with g (g 0: every
 * entry 1, the isotropic phase). */
void vx_phase_table_hg(vx_phase_table *t, double g);

/* vx_phase_table_eval: the table at cos_theta (clamped to [-1, 1]; NaN
 * gives the entry at -1).  Inline: renderers call it per sample. */
static inline double
vx_phase_table_eval(const vx_phase_table *t, double c)
{
	double x = (c + 1) * 0.5 * (VX_PHASE_TABLE_N - 1);
	int i;

	if (!(x > 0))
		return t->v[0];
	if (x >= VX_PHASE_TABLE_N - 1)
		return t->v[VX_PHASE_TABLE_N - 1];
	i = (int)x;
	return t->v[i] + (x - i) * (t->v[i + 1] - t->v[i]);
}

#endif
