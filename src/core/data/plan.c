/* plan.c: render plans: what a renderer computes for a scene and why, with
 * a predicted cost; the plan of the ray-cast isosurface renderer. */
#include "vx_plan.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static const vx_enum_name state_names[] = {
	{ "on", VX_PLAN_ON }, { "off", VX_PLAN_OFF },
	{ "unsupported", VX_PLAN_UNSUPPORTED }, { NULL, VX_PLAN_UNKNOWN }
};
const vx_enum vx_plan_state_enum = { "plan state", state_names, "?", 0 };

void
vx_plan_init(vx_plan *p, const char *renderer)
{
	memset(p, 0, sizeof *p);
	snprintf(p->renderer, sizeof p->renderer, "%s", renderer);
}

void
vx_plan_add(vx_plan *p, const char *name, vx_plan_state state, double rays,
    const char *fmt, ...)
{
	vx_plan_item *it;
	va_list ap;

	p->rays_per_pixel += rays;
	if (state == VX_PLAN_UNSUPPORTED)
		p->nunsupported++;
	if (p->n == VX_PLAN_MAX_ITEMS) {
		p->dropped++;
		return;
	}
	it = &p->item[p->n++];
	snprintf(it->name, sizeof it->name, "%s", name);
	it->state = state;
	it->rays = rays;
	va_start(ap, fmt);
	vsnprintf(it->reason, sizeof it->reason, fmt, ap);
	va_end(ap);
}

/* out: snprintf into buf at *k, counting what would be needed. */
static void
out(char *buf, size_t n, size_t *k, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));

static void
out(char *buf, size_t n, size_t *k, const char *fmt, ...)
{
	va_list ap;
	int m;

	va_start(ap, fmt);
	m = vsnprintf(*k < n ? buf + *k : NULL, *k < n ? n - *k : 0, fmt, ap);
	va_end(ap);
	if (m > 0)
		*k += (size_t)m;
}

size_t
vx_plan_format(const vx_plan *p, char *buf, size_t n)
{
	size_t k = 0;
	int i;

	if (n > 0)
		buf[0] = '\0';
	out(buf, n, &k, "plan: %s\n", p->renderer);
	for (i = 0; i < p->n; i++) {
		const vx_plan_item *it = &p->item[i];
		char rays[32] = "";

		if (it->rays > 0)
			snprintf(rays, sizeof rays, "%.2f", it->rays);
		out(buf, n, &k, "  %-11s %-24s %6s  %s\n",
		    vx_enum_str(&vx_plan_state_enum, it->state), it->name,
		    rays, it->reason);
	}
	if (p->dropped > 0)
		out(buf, n, &k, "  (%d more items not listed)\n", p->dropped);
	out(buf, n, &k, "predicted: about %.1f rays per pixel where the "
	    "surfaces cover it", p->rays_per_pixel);
	if (p->nunsupported > 0)
		out(buf, n, &k, "; %d asked-for item%s not supported yet",
		    p->nunsupported, p->nunsupported > 1 ? "s" : "");
	out(buf, n, &k, "\n");
	return k;
}

/* ---- the ray-cast isosurface renderer ---- */

static void
camera_text(const vx_camera *c, char *b, size_t n)
{
	char proj[48];

	if (c->projection == VX_PERSPECTIVE)
		snprintf(proj, sizeof proj, "perspective fov %g", c->fov);
	else if (c->is_auto)
		snprintf(proj, sizeof proj, "orthographic");
	else
		snprintf(proj, sizeof proj, "orthographic width %g",
		    c->view_width);
	if (c->is_auto && c->view == VX_VIEW_ANGLES)
		snprintf(b, n, "auto, azimuth %g elevation %g, %s, %dx%d, "
		    "framed at render time", c->azimuth, c->elevation, proj,
		    c->w, c->h);
	else if (c->is_auto)
		snprintf(b, n, "auto, %s view, %s, %dx%d, framed at render time",
		    vx_enum_str(&vx_view_enum, c->view), proj, c->w, c->h);
	else
		snprintf(b, n, "eye %g %g %g, look %g %g %g, %s, %dx%d",
		    c->eye[0], c->eye[1], c->eye[2], c->look[0], c->look[1],
		    c->look[2], proj, c->w, c->h);
}

static int
light_black(const vx_light *l)
{
	return l->intensity == 0 ||
	    (l->color[0] == 0 && l->color[1] == 0 && l->color[2] == 0);
}

void
vx_scene_plan_isosurface(const vx_scene *s, vx_plan *p)
{
	unsigned fx = s->effects;
	int ntransp = 0, ntransp_asked = 0, nopaque = 0, nspec = 0, ntex = 0, nshadow_asked = 0;
	int k, nl = s->nlight, ns = s->nsurface;
	double layers, segments;
	char name[VX_PLAN_NAME], text[VX_PLAN_REASON];
	const char *baked;

	if (nl > VX_SCENE_MAX_LIGHTS)
		nl = VX_SCENE_MAX_LIGHTS;
	if (ns > VX_SCENE_MAX_SURFACES)
		ns = VX_SCENE_MAX_SURFACES;
	vx_plan_init(p, "raycast isosurface");
	camera_text(&s->camera, text, sizeof text);
	vx_plan_add(p, "primary rays", VX_PLAN_ON, 1, "%s", text);

	/* Surfaces: which are drawn, and as what. */
	for (k = 0; k < ns; k++) {
		const vx_surface *sf = &s->surface[k];
		int transp = (fx & VX_FX_TRANSPARENCY) && sf->m.opacity < 1;

		snprintf(name, sizeof name, "surface iso %g", sf->iso);
		if (transp && sf->m.opacity == 0) {
			vx_plan_add(p, name, VX_PLAN_OFF, 0, "opacity 0: "
			    "invisible, not traced");
			continue;
		}
		p->surface_on[k] = 1;
		p->nsurface_on++;
		if (sf->m.opacity < 1)
			ntransp_asked++;
		if (transp)
			ntransp++;
		else
			nopaque++;
		if (sf->m.ks > 0)
			nspec++;
		if (sf->m.texture[0] != '\0' && (fx & VX_FX_TEXTURE)) {
			p->texture_on[k] = 1;
			ntex++;
		}
		vx_plan_add(p, name, VX_PLAN_ON, 0, "%s, color %g %g %g, kd %g, "
		    "ks %g", transp ? "transparent layer" :
		    sf->m.opacity < 1 ? "opaque (transparency not in effects)" :
		    "opaque", sf->m.color[0], sf->m.color[1], sf->m.color[2],
		    sf->m.kd, sf->m.ks);
	}
	p->composite = ntransp > 0;
	p->irradiance = s->has_illumination &&
	    (s->illumination == VX_ILLUM_IRRADIANCE ||
	    s->illumination == VX_ILLUM_SH);
	p->sh = s->has_illumination && s->illumination == VX_ILLUM_SH;
	baked = p->sh ? "illumination sh: in the SH transfer volume and "
	    "lighting" : "illumination irradiance: baked into the irradiance "
	    "volume";
	p->pathtrace = s->has_illumination &&
	    s->illumination == VX_ILLUM_PATHTRACE;
	p->specular = (fx & VX_FX_SPECULAR) && nspec > 0 && !p->irradiance &&
	    !p->pathtrace;
	/* Shaded hits per covered pixel: a closed transparent surface is met
	 * twice, then the first opaque one ends the ray. */
	layers = p->nsurface_on == 0 ? 0 :
	    p->composite ? 2.0 * ntransp + (nopaque > 0) : 1;
	segments = 1 + (p->composite ? 2.0 * ntransp : 0);
	p->layers = layers;
	if (p->nsurface_on == 0)
		vx_plan_add(p, "surfaces", VX_PLAN_OFF, 0, "%s",
		    ns == 0 ? "the scene has no surface: only the background "
		    "(add a surface line or --iso)" :
		    "every surface is invisible");

	/* Lights: which shade, which cast shadow rays. */
	for (k = 0; k < nl; k++) {
		const vx_light *l = &s->light[k];

		snprintf(name, sizeof name, "light %d %s", k + 1,
		    vx_enum_str(&vx_light_type_enum, l->type));
		if (p->pathtrace) {
			vx_plan_add(p, name, l->type == VX_LIGHT_HEADLIGHT ?
			    VX_PLAN_OFF : VX_PLAN_ON, 0, "%s",
			    l->type == VX_LIGHT_HEADLIGHT ? "illumination "
			    "pathtrace: a headlight is not part of global "
			    "illumination" : l->type == VX_LIGHT_ENVIRONMENT ?
			    "illumination pathtrace: importance-sampled at every "
			    "path vertex (MIS with the cosine lobe)" :
			    "illumination pathtrace: sampled at every path vertex");
			continue;
		}
		if (p->irradiance) {
			vx_plan_add(p, name, VX_PLAN_OFF, 0, "%s",
			    l->type == VX_LIGHT_HEADLIGHT ? "a headlight is not "
			    "part of the baked light" : p->sh ?
			    "illumination sh: the SH lighting (SHLC, or the "
			    "scene's environment or sky) lights the transfer "
			    "volume; point and directional lights are not part "
			    "of it" : baked);
			continue;
		}
		if (l->type == VX_LIGHT_ENVIRONMENT) {
			char hash[24];

			if (l->has_hash)
				snprintf(hash, sizeof hash, "hash %016llx",
				    (unsigned long long)l->hash);
			else
				snprintf(hash, sizeof hash, "no hash yet");
			vx_plan_add(p, name, VX_PLAN_UNSUPPORTED, 0, "%.60s (%s, "
			    "%s): not shaded by raycast yet, skipped", l->file,
			    vx_enum_str(&vx_env_layout_enum, l->layout), hash);
			continue;
		}
		if (l->type == VX_LIGHT_SKY) {
			vx_plan_add(p, name, VX_PLAN_UNSUPPORTED, 0, "radiance %g "
			    "%g %g: not in local shading (illumination "
			    "irradiance or pathtrace use it), skipped",
			    l->color[0] * l->intensity, l->color[1] * l->intensity,
			    l->color[2] * l->intensity);
			continue;
		}
		if (light_black(l)) {
			vx_plan_add(p, name, VX_PLAN_OFF, 0, "intensity or color "
			    "0: contributes nothing");
			continue;
		}
		if (p->nsurface_on == 0) {
			vx_plan_add(p, name, VX_PLAN_OFF, 0, "nothing to light");
			continue;
		}
		p->light_on[k] = 1;
		if (l->shadows)
			nshadow_asked++;
		if (!l->shadows) {
			vx_plan_add(p, name, VX_PLAN_ON, 0, "shading; no shadows "
			    "(light's shadows off)");
		} else if (!(fx & VX_FX_SHADOWS)) {
			vx_plan_add(p, name, VX_PLAN_ON, 0, "shading; no shadows "
			    "(shadows not in effects)");
		} else if (l->type == VX_LIGHT_HEADLIGHT && !p->composite) {
			vx_plan_add(p, name, VX_PLAN_ON, 0, "shading; shadows "
			    "skipped: a light at the eye casts them only behind "
			    "opaque surfaces");
		} else {
			p->shadow_on[k] = 1;
			p->nshadow++;
			vx_plan_add(p, name, VX_PLAN_ON, layers, "shading and "
			    "shadow rays (%.0f per covered pixel)", layers);
		}
	}
	if (nl == 0 && !p->irradiance && !p->pathtrace)
		vx_plan_add(p, "lights", VX_PLAN_OFF, 0, "no lights: ambient "
		    "term only");

	/* Effects, on or off, with the reason. */
	if (p->irradiance)
		vx_plan_add(p, "shadows", VX_PLAN_OFF, 0, "%s", baked);
	else if (p->pathtrace)
		vx_plan_add(p, "shadows", (fx & VX_FX_SHADOWS) ? VX_PLAN_ON :
		    VX_PLAN_OFF, 0, "illumination pathtrace: %s",
		    (fx & VX_FX_SHADOWS) ? "shadow rays at every path vertex" :
		    "not in effects");
	else if (p->nshadow > 0)
		vx_plan_add(p, "shadows", VX_PLAN_ON, 0, "shadow rays to %d "
		    "light%s", p->nshadow, p->nshadow > 1 ? "s" : "");
	else if (!(fx & VX_FX_SHADOWS))
		vx_plan_add(p, "shadows", VX_PLAN_OFF, 0, "not in effects%s",
		    nshadow_asked ? " (a light asks for them)" : "");
	else
		vx_plan_add(p, "shadows", VX_PLAN_OFF, 0, "%s",
		    nshadow_asked ? "only a headlight asks, and its shadows "
		    "cannot be seen" : "no light casts shadows");
	if (p->composite)
		vx_plan_add(p, "transparency", VX_PLAN_ON, segments - 1,
		    "%d transparent surface%s: layers composited front to "
		    "back, up to %.0f continuation rays", ntransp,
		    ntransp > 1 ? "s" : "", segments - 1);
	else if (!(fx & VX_FX_TRANSPARENCY) && ntransp_asked > 0)
		vx_plan_add(p, "transparency", VX_PLAN_OFF, 0, "not in effects: "
		    "every surface drawn opaque, first hit only");
	else
		vx_plan_add(p, "transparency", VX_PLAN_OFF, 0, "every drawn "
		    "surface is opaque: first hit only, no compositing");
	if (p->irradiance || p->pathtrace)
		vx_plan_add(p, "specular", VX_PLAN_OFF, 0, "illumination %s: "
		    "diffuse only", p->sh ? "sh" : p->irradiance ? "irradiance" :
		    "pathtrace");
	else if (p->specular)
		vx_plan_add(p, "specular", VX_PLAN_ON, 0, "Blinn-Phong on %d "
		    "surface%s with ks > 0", nspec, nspec > 1 ? "s" : "");
	else
		vx_plan_add(p, "specular", VX_PLAN_OFF, 0, "%s",
		    !(fx & VX_FX_SPECULAR) ? "not in effects" :
		    "no drawn surface has ks > 0");
	if (ntex > 0) {
		for (k = 0; k < ns; k++)
			if (p->texture_on[k]) {
				snprintf(name, sizeof name, "texture iso %g",
				    s->surface[k].iso);
				vx_plan_add(p, name, VX_PLAN_ON, 0, "volume '%s' "
				    "through %s", s->surface[k].m.texture,
				    vx_enum_str(&vx_colormap_enum,
				    s->surface[k].m.colormap));
			}
	} else {
		int asked = 0;

		for (k = 0; k < ns; k++)
			asked |= s->surface[k].m.texture[0] != '\0';
		vx_plan_add(p, "texture", VX_PLAN_OFF, 0, "%s",
		    asked ? "not in effects" : "no surface names a texture");
	}

	/* Reserved: asked for, but not computed by this renderer yet. */
	if (p->irradiance && (fx & VX_FX_INTERREFLECTION)) {
		vx_plan_add(p, "interreflection", VX_PLAN_OFF, 0, "%s", baked);
	} else if (p->pathtrace) {
		int nb = (fx & VX_FX_INTERREFLECTION) && s->has_interreflection ?
		    s->bounces : 0;

		vx_plan_add(p, "interreflection", nb > 0 ? VX_PLAN_ON :
		    VX_PLAN_OFF, 0, "illumination pathtrace: %d bounce%s", nb,
		    nb == 1 ? "" : "s");
	} else if (fx & VX_FX_INTERREFLECTION) {
		if (s->has_interreflection && s->bounces > 0)
			vx_plan_add(p, "interreflection", VX_PLAN_UNSUPPORTED, 0,
			    "%d bounce%s, %d samples: not supported by raycast "
			    "yet", s->bounces, s->bounces > 1 ? "s" : "",
			    s->samples);
		else
			vx_plan_add(p, "interreflection", VX_PLAN_OFF, 0, "in "
			    "effects, but no bounces asked");
	} else if (s->has_interreflection && s->bounces > 0) {
		vx_plan_add(p, "interreflection", VX_PLAN_OFF, 0, "not in "
		    "effects");
	}
	if (fx & VX_FX_VOLUMETRIC_SHADOWS)
		vx_plan_add(p, "volumetric-shadows", VX_PLAN_UNSUPPORTED, 0,
		    "not supported by raycast yet");
	if (fx & VX_FX_SCATTERING)
		vx_plan_add(p, "scattering", VX_PLAN_UNSUPPORTED, 0,
		    "not supported by raycast yet");
	if (p->pathtrace)
		vx_plan_add(p, "illumination", VX_PLAN_ON, 2.0 * s->pt_samples *
		    layers, "pathtrace: albedo E / pi, E from %d paths per pixel "
		    "sample (cosine-weighted, counter-based), the reference",
		    s->pt_samples);
	else if (p->sh)
		vx_plan_add(p, "illumination", VX_PLAN_ON, 0, "sh: albedo E / "
		    "pi, E the dot product of the SH lighting with the "
		    "transfer vector interpolated (%s) from the SH transfer "
		    "volume; no rays beyond the primary ones",
		    vx_enum_str(&vx_interp_enum, s->interp));
	else if (p->irradiance)
		vx_plan_add(p, "illumination", VX_PLAN_ON, 0, "irradiance: "
		    "albedo E / pi, E interpolated (%s) from the irradiance "
		    "volume; no rays beyond the primary ones",
		    vx_enum_str(&vx_interp_enum, s->interp));
	if (s->has_occlusion) {
		char dist[48] = "unlimited rays";

		if (s->occlusion_distance > 0)
			snprintf(dist, sizeof dist, "rays open past %g",
			    s->occlusion_distance);
		if ((p->irradiance && !p->sh) || p->pathtrace)
			vx_plan_add(p, "occlusion", VX_PLAN_ON, 0, "ambient "
			    "occlusion (%s): a white sky of radiance 1 in place "
			    "of the lights, no bounces", dist);
		else if (p->sh)
			vx_plan_add(p, "occlusion", VX_PLAN_ON, 0, "%s, no "
			    "bounces, in the transfer (bake-sh); the lighting is "
			    "the SH lighting's", dist);
		else
			vx_plan_add(p, "occlusion", VX_PLAN_UNSUPPORTED, 0,
			    "ambient occlusion (%s) is computed by illumination "
			    "irradiance or pathtrace, not by local shading", dist);
	}
	if (s->ntf_opacity > 0 || s->ntf_color > 0 || s->ntf_transport > 0 ||
	    s->ntf_surface > 0 || s->ntf_gradient > 0 || s->tf_file[0] != '\0')
		vx_plan_add(p, "transfer function", VX_PLAN_OFF, 0, "for direct "
		    "volume rendering (dvr): not used by raycast");
	if (s->has_medium)
		vx_plan_add(p, "medium", VX_PLAN_OFF, 0, "for direct volume "
		    "rendering: not used by raycast");
}
