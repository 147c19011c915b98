/* synth.c: synthetic test fields on [-1,1]^3 (formulas in vx_import.h). */
#include "vx_import.h"

#include <math.h>
#include <string.h>

static const vx_enum_name synth_names[] = {
	{ "sphere", VX_SYNTH_SPHERE }, { "torus", VX_SYNTH_TORUS },
	{ "linear", VX_SYNTH_LINEAR }, { "ml", VX_SYNTH_ML },
	{ "saddle", VX_SYNTH_SADDLE }, { NULL, VX_SYNTH_UNKNOWN }
};
const vx_enum vx_synth_enum = { "field", synth_names, "unknown", 0 };

double
vx_synth_coord(int64_t i, int64_t n)
{
	if (n < 2)
		return 0;
	/* (2i - (n-1)) / (n-1): exact at both ends and at the centre */
	return (2.0 * (double)i - (double)(n - 1)) / (double)(n - 1);
}

double
vx_synth_eval(vx_synth_kind k, double x, double y, double z)
{
	switch (k) {
	case VX_SYNTH_SPHERE:
		return sqrt(x * x + y * y + z * z);
	case VX_SYNTH_TORUS: {
		double r = sqrt(x * x + y * y) - 0.5;

		return sqrt(r * r + z * z);
	}
	case VX_SYNTH_LINEAR:
		return x + 2 * y + 3 * z + 0.5;
	case VX_SYNTH_ML: {
		/* Marschner and Lobb 1994, f_M = 6, alpha = 0.25 */
		const double fm = 6, alpha = 0.25;
		double r = sqrt(x * x + y * y);
		double rho = cos(2 * M_PI * fm * cos(M_PI * r / 2));

		return (1 - sin(M_PI * z / 2) + alpha * (1 + rho)) /
		    (2 * (1 + alpha));
	}
	case VX_SYNTH_SADDLE:
		return x * y * z + (x * y + y * z + z * x) / 2;
	default:
		return NAN;
	}
}

int
vx_synth_make(vx_grid *g, vx_synth_kind k, const int64_t dims[3],
    vx_err *e)
{
	int64_t i, j, l;
	float *d;
	int a, rc;

	vx_grid_init(g);
	if (k <= VX_SYNTH_UNKNOWN || k >= VX_SYNTH_LAST)
		return vx_err_set(e, VX_EUSAGE, "synth: unknown field");
	if ((rc = vx_grid_alloc(g, dims, VX_F32, NULL, e)) != 0)
		return rc;
	for (a = 0; a < 3; a++) {
		g->origin[a] = dims[a] < 2 ? 0 : -1;
		g->spacing[a] = dims[a] < 2 ? 1 : 2.0 / (double)(dims[a] - 1);
	}
	d = g->data;
	for (l = 0; l < dims[2]; l++) {
		double z = vx_synth_coord(l, dims[2]);

		for (j = 0; j < dims[1]; j++) {
			double y = vx_synth_coord(j, dims[1]);
			float *row = d + vx_grid_index(g, 0, j, l);

			for (i = 0; i < dims[0]; i++)
				row[i] = (float)vx_synth_eval(k,
				    vx_synth_coord(i, dims[0]), y, z);
		}
	}
	vx_grid_range(g);
	return 0;
}
