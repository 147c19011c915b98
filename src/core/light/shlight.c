/* shlight.c: the SHLC chunk (formats/shlight.md). */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vx_shlight.h"

void
vx_shlight_init(vx_shlight *l)
{
	memset(l, 0, sizeof *l);
	l->order = 1;
	l->phase = VX_SHLIGHT_PHASE_CS;
	for (int i = 0; i < 3; i++)
		l->rot[i][i] = 1;
}

static const char *const phase_name[] = { "condon-shortley", "none" };

int
vx_shlight_to_chunk(const vx_shlight *l, vx_chunk *c, vx_err *e)
{
	size_t n, nc;
	unsigned char *body;
	vx_hdr h;
	int rc;

	if (l->order < 1 || l->order > VX_SHLIGHT_MAX_ORDER)
		return vx_err_set(e, VX_EINTERNAL, "SH lighting: order %d "
		    "outside 1 .. %d", l->order, VX_SHLIGHT_MAX_ORDER);
	nc = (size_t)l->order * (size_t)l->order * 3;
	for (size_t i = 0; i < nc; i++)
		if (!isfinite(l->c[i]))
			return vx_err_set(e, VX_EINTERNAL, "SH lighting: "
			    "coefficient %zu is not finite", i);
	for (int i = 0; i < 9; i++)
		if (!isfinite(l->rot[i / 3][i % 3]))
			return vx_err_set(e, VX_EINTERNAL, "SH lighting: "
			    "rotation is not finite");
	n = nc * 8;
	if ((body = malloc(n)) == NULL)
		return vx_err_set(e, VX_ENOMEM, "out of memory");
	for (size_t i = 0; i < nc; i++) {
		uint64_t u;

		memcpy(&u, &l->c[i], 8);
		vx_put_le64(body + 8 * i, u);
	}
	vx_hdr_init(&h);
	if ((rc = vx_hdr_set(&h, "order", e, "%d", l->order)) ||
	    (rc = vx_hdr_set(&h, "channels", e, "3")) ||
	    (rc = vx_hdr_set(&h, "phase", e, "%s", phase_name[l->phase])) ||
	    (rc = l->has_hash ? vx_hdr_set(&h, "source-hash", e, "%016" PRIx64,
	    l->env_hash) : vx_hdr_set(&h, "source-hash", e, "none")) ||
	    (rc = vx_hdr_set(&h, "rotation", e,
	    "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g",
	    l->rot[0][0], l->rot[0][1], l->rot[0][2], l->rot[1][0],
	    l->rot[1][1], l->rot[1][2], l->rot[2][0], l->rot[2][1],
	    l->rot[2][2]))) {
		free(body);
		vx_hdr_free(&h);
		return rc;
	}
	rc = vx_payload_wrap(c, VX_CHUNK_SHLIGHT, &h, body, n, e);
	vx_hdr_free(&h);
	return rc;
}

/* rot_ok: r r^T = I and det r = 1, to 1e-6 */
static int
rot_ok(const double r[3][3])
{
	double det;

	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++) {
			double d = 0;

			for (int k = 0; k < 3; k++)
				d += r[i][k] * r[j][k];
			if (fabs(d - (i == j)) > 1e-6)
				return 0;
		}
	det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
	    r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
	    r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
	return fabs(det - 1) <= 1e-6;
}

static int
parse_hash(const char *s, uint64_t *out)
{
	uint64_t v = 0;

	if (s == NULL || strlen(s) != 16)
		return -1;
	for (int i = 0; i < 16; i++) {
		int d;

		if (s[i] >= '0' && s[i] <= '9')
			d = s[i] - '0';
		else if (s[i] >= 'a' && s[i] <= 'f')
			d = s[i] - 'a' + 10;
		else
			return -1;
		v = v << 4 | (uint64_t)d;
	}
	*out = v;
	return 0;
}

static int
decode(vx_shlight *l, const vx_chunk *c, vx_err *e)
{
	const unsigned char *body;
	const char *s;
	double rot[9];
	int64_t order, nch;
	size_t bl, nc;
	unsigned char *buf;
	vx_hdr h;
	int rc;

	if (strcmp(c->type, VX_CHUNK_SHLIGHT) != 0)
		return vx_err_set(e, VX_EDATA, "%s chunk is not %s", c->type,
		    VX_CHUNK_SHLIGHT);
	vx_hdr_init(&h);
	if ((rc = vx_payload_parse(c, &h, &body, &bl, e)) != 0 ||
	    (rc = vx_hdr_get_i64(&h, "order", &order, 1, e)) != 0 ||
	    (rc = vx_hdr_get_i64(&h, "channels", &nch, 1, e)) != 0 ||
	    (rc = vx_hdr_get_f64(&h, "rotation", rot, 9, e)) != 0)
		goto out;
	rc = VX_EDATA;
	if (order < 1 || order > VX_SHLIGHT_MAX_ORDER) {
		vx_err_set(e, rc, "order %" PRId64 " outside 1 .. %d", order,
		    VX_SHLIGHT_MAX_ORDER);
		goto out;
	}
	if (nch != 3) {
		vx_err_set(e, rc, "channels %" PRId64 ": must be 3", nch);
		goto out;
	}
	l->order = (int)order;
	s = vx_hdr_get(&h, "phase");
	if (s != NULL && strcmp(s, phase_name[0]) == 0)
		l->phase = VX_SHLIGHT_PHASE_CS;
	else if (s != NULL && strcmp(s, phase_name[1]) == 0)
		l->phase = VX_SHLIGHT_PHASE_NONE;
	else {
		vx_err_set(e, rc, "phase '%s': condon-shortley or none",
		    s ? s : "(missing)");
		goto out;
	}
	s = vx_hdr_get(&h, "source-hash");
	if (s != NULL && strcmp(s, "none") == 0)
		l->has_hash = 0;
	else if (parse_hash(s, &l->env_hash) == 0)
		l->has_hash = 1;
	else {
		vx_err_set(e, rc, "source-hash '%s': 16 lower-case hex digits "
		    "or none", s ? s : "(missing)");
		goto out;
	}
	for (int i = 0; i < 9; i++)
		l->rot[i / 3][i % 3] = rot[i];
	if (!rot_ok(l->rot)) {
		vx_err_set(e, rc, "rotation is not a rotation matrix");
		goto out;
	}
	nc = (size_t)order * (size_t)order * 3;
	if ((rc = vx_body_fits(&h, bl, nc * 8, e)) != 0)
		goto out;
	if ((buf = malloc(nc * 8)) == NULL) {
		rc = vx_err_set(e, VX_ENOMEM, "out of memory");
		goto out;
	}
	if ((rc = vx_body_decode(&h, body, bl, buf, nc * 8, e)) != 0) {
		free(buf);
		goto out;
	}
	for (size_t i = 0; i < nc; i++) {
		uint64_t u = vx_le64(buf + 8 * i);

		memcpy(&l->c[i], &u, 8);
		if (!isfinite(l->c[i])) {
			free(buf);
			rc = vx_err_set(e, VX_EDATA, "coefficient %zu is not "
			    "finite", i);
			goto out;
		}
	}
	free(buf);
	rc = 0;
out:
	vx_hdr_free(&h);
	return rc;
}

int
vx_shlight_from_chunk(vx_shlight *l, const vx_chunk *c, vx_err *e)
{
	int rc;

	vx_shlight_init(l);
	if ((rc = decode(l, c, e)) != 0) {
		vx_shlight_init(l);
		vx_err_push(e, "SH lighting");
	}
	return rc;
}

int
vx_shlight_from_stream(vx_shlight *l, const vx_stream *s, long *idx,
    vx_err *e)
{
	long i = vx_stream_find(s, VX_CHUNK_SHLIGHT, 0);
	int rc;

	*idx = i;
	vx_shlight_init(l);
	if (i < 0)
		return 0;
	if ((rc = vx_shlight_from_chunk(l, &s->chunk[i], e)) != 0)
		vx_err_push(e, "%s chunk at offset %llu", VX_CHUNK_SHLIGHT,
		    (unsigned long long)s->chunk[i].offset);
	return rc;
}

void
vx_shlight_project(const vx_env *env, int order, double *c)
{
	size_t n = vx_env_npixel(env);

	if (env->layout == VX_ENV_LATLONG && env->w == 1 && env->h == 1) {
		/* a constant sky: Y_0^0 = 1 / (2 sqrt(pi)) is the only band
		 * with a nonzero integral, 2 sqrt(pi) (one pixel's centre
		 * would stand for the whole sphere) */
		for (int k = 0; k < 3; k++)
			c[k * order * order] += 2 * sqrt(3.14159265358979323846) *
			    env->scale[k] * env->px[k];
		return;
	}
	for (size_t i = 0; i < n; i++) {
		double dir[3], om, rgb[3];

		vx_env_pixel(env, i, dir, &om, rgb);
		if (om > 0)
			vx_sh_accumulate(order, dir, om, rgb, 3, c);
	}
}

int
vx_shlight_from_scene(vx_shlight *l, const vx_scene *s, int order,
    int *nlight, size_t *npixel, vx_err *e)
{
	int n = 0;
	size_t np = 0;

	vx_shlight_init(l);
	if (order < 1 || order > VX_SHLIGHT_MAX_ORDER)
		return vx_err_set(e, VX_EINTERNAL, "SH lighting: order %d "
		    "outside 1 .. %d", order, VX_SHLIGHT_MAX_ORDER);
	l->order = order;
	for (int k = 0; k < s->nlight; k++) {
		const vx_light *lt = &s->light[k];
		vx_env env;

		if (lt->type != VX_LIGHT_ENVIRONMENT && lt->type != VX_LIGHT_SKY)
			continue;
		if (vx_env_load_light(&env, lt, e) != 0)
			return vx_err_push(e, "light %d", k + 1);
		vx_shlight_project(&env, order, l->c);
		l->env_hash = env.hash;
		np += vx_env_npixel(&env);
		vx_env_free(&env);
		n++;
	}
	l->has_hash = n == 1;
	if (n != 1)
		l->env_hash = 0;
	if (nlight != NULL)
		*nlight = n;
	if (npixel != NULL)
		*npixel = np;
	return 0;
}
