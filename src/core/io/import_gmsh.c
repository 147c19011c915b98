/* import_gmsh.c: gmsh .msh files (ASCII, versions 2.x and 4.1) as tet
 * meshes: $Nodes, $Elements (type 4, the 4-node tetrahedron) and a
 * $NodeData view for the scalar. */
#include "vx_tetimport.h"
#include "import_priv.h"
#include "vx_scan.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TOK 256              /* a section name's bytes, with the NUL */

/* gmsh element types: dimension and node count (gmsh reference manual,
 * "MSH file format"); types not listed are refused. */
static int
elem_info(int64_t type, int *dim, int *nnode)
{
	static const struct { int type, dim, n; } tab[] = {
		{ 1, 1, 2 }, { 2, 2, 3 }, { 3, 2, 4 }, { 4, 3, 4 }, { 5, 3, 8 },
		{ 6, 3, 6 }, { 7, 3, 5 }, { 8, 1, 3 }, { 9, 2, 6 }, { 10, 2, 9 },
		{ 11, 3, 10 }, { 12, 3, 27 }, { 13, 3, 18 }, { 14, 3, 14 },
		{ 15, 0, 1 }, { 16, 2, 8 }, { 17, 3, 20 }, { 18, 3, 15 },
		{ 19, 3, 13 }, { 20, 2, 9 }, { 21, 2, 10 }, { 22, 2, 12 },
		{ 23, 2, 15 }, { 24, 2, 15 }, { 25, 2, 21 }, { 26, 1, 4 },
		{ 27, 1, 5 }, { 28, 1, 6 }, { 29, 3, 20 }, { 30, 3, 35 },
		{ 31, 3, 56 }, { 92, 3, 64 }, { 93, 3, 125 },
	};
	for (size_t i = 0; i < sizeof tab / sizeof tab[0]; i++)
		if (tab[i].type == type) {
			*dim = tab[i].dim;
			*nnode = tab[i].n;
			return 1;
		}
	return 0;
}

static const char *
elem_name(int64_t type)
{
	switch (type) {
	case 5: return "8-node hexahedron";
	case 6: return "6-node prism";
	case 7: return "5-node pyramid";
	case 11: return "10-node second-order tetrahedron";
	default: return "volume element";
	}
}

/* node tag -> index map: sorted (tag, index) pairs, or a direct offset when
 * the tags are consecutive */
typedef struct nodemap {
	int64_t *tag;          /* sorted tags */
	uint32_t *idx;         /* their point indices */
	size_t n;
	int dense;             /* tag[i] == tag[0] + i */
} nodemap;

typedef struct gmsh {
	vx_scan s;
	vx_err *e;
	const vx_tetimport_opt *opt;
	vx_tetimport_info *info;
	int v4;
	size_t npoint;
	int have_nodes, have_elems;
	double *pts;
	int64_t *ntag;         /* tag of point i, file order */
	nodemap map;
	uint32_t *tet;
	size_t ntet;
	double *val;           /* chosen node data, NaN where absent */
	unsigned char *has;    /* 1 where val was given */
	char valname[VX_TETMESH_NAME];
} gmsh;

static int
gfail(gmsh *g, const char *fmt, const char *a)
{
	char msg[400];
	snprintf(msg, sizeof msg, fmt, a ? a : "");
	return vx_err_set(g->e, VX_EDATA, "gmsh: line %zu: %s",
	    vx_scan_lineno(&g->s), msg);
}

static int
gi64(gmsh *g, int64_t *v, const char *what)
{
	const char *w;
	size_t n = vx_scan_word(&g->s, &w);

	if (n == 0)
		return gfail(g, "truncated in %s", what);
	if (vx_num_i64(w, n, -VX_IMP_INT_MAX, VX_IMP_INT_MAX, v) != 0)
		return gfail(g, "%s: expected an integer", what);
	return 0;
}

static int
gf64(gmsh *g, double *v, const char *what)
{
	const char *w;
	size_t n = vx_scan_word(&g->s, &w);

	if (n == 0)
		return gfail(g, "truncated in %s", what);
	if (vx_num_f64(w, n, VX_NUM_NONFINITE, v) != 0)
		return gfail(g, "%s: expected a number", what);
	return 0;
}

/* A count that must fit in the rest of the input at `per` bytes each. */
static int
gcount(gmsh *g, int64_t *v, size_t per, const char *what)
{
	int rc = gi64(g, v, what);

	if (rc == 0 && (*v < 0 || (uint64_t)*v > vx_scan_left(&g->s) / per + 1))
		return gfail(g, "%s: count out of range for the data present",
		    what);
	return rc;
}

/* Expect "$End<name>" as the next token. */
static int
gend(gmsh *g, const char *name)
{
	char want[64];
	const char *w;
	size_t n;

	snprintf(want, sizeof want, "$End%s", name);
	n = vx_scan_word(&g->s, &w);
	if (!vx_word_eq(w, n, want, 0))
		return gfail(g, "expected %s", want);
	return 0;
}

/* Skip a section up to and including its $End line. */
static int
gskip(gmsh *g, const char *name)
{
	char want[TOK + 8];
	const char *w;
	size_t n;

	snprintf(want, sizeof want, "$End%s", name + 1);
	while ((n = vx_scan_word(&g->s, &w)) != 0)
		if (vx_word_eq(w, n, want, 0))
			return 0;
	return gfail(g, "section %s has no end", name);
}

static int
pair_cmp(const void *a, const void *b)
{
	const int64_t *x = a, *y = b;
	return (x[0] > y[0]) - (x[0] < y[0]);
}

static int
map_build(gmsh *g)
{
	nodemap *m = &g->map;
	size_t i, n = g->npoint;
	int64_t *pr;

	m->n = n;
	m->tag = vx_malloc((n ? n : 1) * sizeof *m->tag, g->e);
	m->idx = vx_malloc((n ? n : 1) * sizeof *m->idx, g->e);
	pr = vx_malloc((n ? n : 1) * 2 * sizeof *pr, g->e);
	if (m->tag == NULL || m->idx == NULL || pr == NULL) {
		free(pr);
		return VX_ENOMEM;
	}
	for (i = 0; i < n; i++) {
		pr[2 * i] = g->ntag[i];
		pr[2 * i + 1] = (int64_t)i;
	}
	qsort(pr, n, 2 * sizeof *pr, pair_cmp);
	m->dense = 1;
	for (i = 0; i < n; i++) {
		m->tag[i] = pr[2 * i];
		m->idx[i] = (uint32_t)pr[2 * i + 1];
		if (i > 0 && m->tag[i] == m->tag[i - 1]) {
			int64_t t = m->tag[i];
			free(pr);
			return vx_err_set(g->e, VX_EDATA, "gmsh: node %lld is "
			    "defined twice", (long long)t);
		}
		if (m->tag[i] != m->tag[0] + (int64_t)i)
			m->dense = 0;
	}
	free(pr);
	return 0;
}

/* Point index of node tag t, or -1. */
static int64_t
map_find(const nodemap *m, int64_t t)
{
	size_t lo = 0, hi = m->n;

	if (m->n == 0)
		return -1;
	if (m->dense) {
		if (t < m->tag[0] || t - m->tag[0] >= (int64_t)m->n)
			return -1;
		return m->idx[t - m->tag[0]];
	}
	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;
		if (m->tag[mid] < t)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo < m->n && m->tag[lo] == t ? (int64_t)m->idx[lo] : -1;
}

static int
alloc_nodes(gmsh *g, int64_t n)
{
	if ((uint64_t)n > VX_TETMESH_MAX_POINTS)
		return gfail(g, "too many nodes", NULL);
	g->npoint = (size_t)n;
	g->pts = vx_malloc(((size_t)n ? (size_t)n : 1) * 3 * sizeof *g->pts,
	    g->e);
	g->ntag = vx_malloc(((size_t)n ? (size_t)n : 1) * sizeof *g->ntag, g->e);
	return g->pts && g->ntag ? 0 : VX_ENOMEM;
}

static int
nodes(gmsh *g)
{
	int64_t n, nb, i, k;
	int rc;

	if (g->have_nodes)
		return gfail(g, "$Nodes given twice", NULL);
	g->have_nodes = 1;
	if (!g->v4) {
		/* n, then n lines "tag x y z" (at least 8 bytes each) */
		if ((rc = gcount(g, &n, 8, "$Nodes")) || (rc = alloc_nodes(g, n)))
			return rc;
		for (i = 0; i < n; i++) {
			if ((rc = gi64(g, &g->ntag[i], "$Nodes")))
				return rc;
			for (k = 0; k < 3; k++)
				if ((rc = gf64(g, &g->pts[3 * i + k], "$Nodes")))
					return rc;
		}
		return gend(g, "Nodes");
	}
	/* 4.1: numEntityBlocks numNodes minNodeTag maxNodeTag, then blocks
	 * "entityDim entityTag parametric numNodesInBlock", the block's tags,
	 * then its coordinates (x y z, plus entityDim parameters if
	 * parametric) */
	int64_t mn, mx;
	if ((rc = gcount(g, &nb, 8, "$Nodes")) ||
	    (rc = gcount(g, &n, 8, "$Nodes")) ||
	    (rc = gi64(g, &mn, "$Nodes")) || (rc = gi64(g, &mx, "$Nodes")) ||
	    (rc = alloc_nodes(g, n)))
		return rc;
	size_t at = 0;
	for (int64_t b = 0; b < nb; b++) {
		int64_t dim, etag, par, cnt;
		if ((rc = gi64(g, &dim, "$Nodes block")) ||
		    (rc = gi64(g, &etag, "$Nodes block")) ||
		    (rc = gi64(g, &par, "$Nodes block")) ||
		    (rc = gi64(g, &cnt, "$Nodes block")))
			return rc;
		if (dim < 0 || dim > 3 || (par != 0 && par != 1) || cnt < 0 ||
		    (uint64_t)cnt > g->npoint - at)
			return gfail(g, "$Nodes: bad block header (or more nodes "
			    "than announced)", NULL);
		for (i = 0; i < cnt; i++)
			if ((rc = gi64(g, &g->ntag[at + (size_t)i], "$Nodes")))
				return rc;
		for (i = 0; i < cnt; i++) {
			double u;
			for (k = 0; k < 3; k++)
				if ((rc = gf64(g, &g->pts[3 * (at + (size_t)i) +
				    (size_t)k], "$Nodes")))
					return rc;
			for (k = 0; par && k < dim; k++)
				if ((rc = gf64(g, &u, "$Nodes")))
					return rc;
		}
		at += (size_t)cnt;
	}
	if (at != g->npoint)
		return gfail(g, "$Nodes: the blocks hold fewer nodes than "
		    "announced", NULL);
	return gend(g, "Nodes");
}

/* One element's nodes (already known to be a tet) into the tet list. */
static int
add_tet(gmsh *g, const int64_t q[4], int64_t etag)
{
	uint32_t *t = g->tet + 4 * g->ntet;

	for (int k = 0; k < 4; k++) {
		int64_t p = map_find(&g->map, q[k]);
		if (p < 0)
			return vx_err_set(g->e, VX_EDATA, "gmsh: line %zu: element "
			    "%lld refers to undefined node %lld",
			    vx_scan_lineno(&g->s), (long long)etag,
			    (long long)q[k]);
		t[k] = (uint32_t)p;
	}
	g->ntet++;
	return 0;
}

/* Classify one element of type `type`: 1 keep (tet), 0 skip, or an error. */
static int
classify(gmsh *g, int64_t type, int *nnode, int *keep)
{
	int dim;

	if (!elem_info(type, &dim, nnode))
		return vx_err_set(g->e, VX_EDATA, "gmsh: line %zu: unknown "
		    "element type %lld", vx_scan_lineno(&g->s),
		    (long long)type);
	*keep = type == 4;
	if (*keep)
		return 0;
	if (dim < 3) {
		g->info->nskip_lower++;
		return 0;
	}
	if (g->opt && g->opt->skip_volume_cells) {
		g->info->nskip_volume++;
		return 0;
	}
	return vx_err_set(g->e, VX_EDATA, "gmsh: line %zu: element type %lld "
	    "(%s) is not supported: only 4-node tetrahedra (type 4)",
	    vx_scan_lineno(&g->s), (long long)type, elem_name(type));
}

/* element: the node tags of element tag, of type type (the rest of its
 * line), into the tet list when it is a tet. */
static int
element(gmsh *g, int64_t tag, int64_t type)
{
	int64_t q[4], v;
	int rc, k, nnode = 0, keep = 0;

	if ((rc = classify(g, type, &nnode, &keep)) != 0)
		return rc;
	for (k = 0; k < nnode; k++) {
		if ((rc = gi64(g, &v, "$Elements")))
			return rc;
		if (keep)
			q[k] = v;
	}
	return keep ? add_tet(g, q, tag) : 0;
}

/* alloc_elems: room for n tets (every element might be one). */
static int
alloc_elems(gmsh *g, int64_t n)
{
	g->info->ncell = (size_t)n;
	g->tet = vx_malloc(((size_t)n ? (size_t)n : 1) * 4 * sizeof *g->tet,
	    g->e);
	return g->tet != NULL ? 0 : VX_ENOMEM;
}

static int
elements(gmsh *g)
{
	int64_t n, nb, i, k, tag, type;
	int rc;

	if (!g->have_nodes)
		return gfail(g, "$Elements before $Nodes", NULL);
	if (g->have_elems)
		return gfail(g, "$Elements given twice", NULL);
	g->have_elems = 1;
	if (g->map.tag == NULL && (rc = map_build(g)) != 0)
		return rc;
	if (!g->v4) {
		/* n, then lines "tag type ntags tags... nodes..." (>= 10 bytes) */
		if ((rc = gcount(g, &n, 10, "$Elements")) ||
		    (rc = alloc_elems(g, n)))
			return rc;
		for (i = 0; i < n; i++) {
			int64_t ntags, dummy;
			if ((rc = gi64(g, &tag, "$Elements")) ||
			    (rc = gi64(g, &type, "$Elements")) ||
			    (rc = gi64(g, &ntags, "$Elements")))
				return rc;
			if (ntags < 0 || ntags > 1000)
				return gfail(g, "$Elements: bad tag count", NULL);
			for (k = 0; k < ntags; k++)
				if ((rc = gi64(g, &dummy, "$Elements")))
					return rc;
			if ((rc = element(g, tag, type)) != 0)
				return rc;
		}
		return gend(g, "Elements");
	}
	/* 4.1: numEntityBlocks numElements minTag maxTag; blocks "entityDim
	 * entityTag elementType numElementsInBlock" then "tag nodes..." */
	int64_t mn, mx;
	if ((rc = gcount(g, &nb, 8, "$Elements")) ||
	    (rc = gcount(g, &n, 4, "$Elements")) ||
	    (rc = gi64(g, &mn, "$Elements")) ||
	    (rc = gi64(g, &mx, "$Elements")) || (rc = alloc_elems(g, n)))
		return rc;
	size_t seen = 0;
	for (int64_t b = 0; b < nb; b++) {
		int64_t dim, etag, cnt;
		if ((rc = gi64(g, &dim, "$Elements block")) ||
		    (rc = gi64(g, &etag, "$Elements block")) ||
		    (rc = gi64(g, &type, "$Elements block")) ||
		    (rc = gi64(g, &cnt, "$Elements block")))
			return rc;
		if (cnt < 0 || (uint64_t)cnt > (uint64_t)n - seen)
			return gfail(g, "$Elements: more elements than announced",
			    NULL);
		for (i = 0; i < cnt; i++)
			if ((rc = gi64(g, &tag, "$Elements")) ||
			    (rc = element(g, tag, type)))
				return rc;
		seen += (size_t)cnt;
	}
	if (seen != (size_t)n)
		return gfail(g, "$Elements: the blocks hold fewer elements than "
		    "announced", NULL);
	return gend(g, "Elements");
}

/* The rest of the current line as a string tag (quotes removed). */
static void
string_tag(gmsh *g, char *out, size_t cap)
{
	vx_scan *s = &g->s;
	size_t k = 0;

	vx_scan_skip_blank(s);
	int quoted = s->p < s->end && *s->p == '"';
	if (quoted)
		s->p++;
	while (s->p < s->end && *s->p != '\n' && !(quoted && *s->p == '"')) {
		if (k + 1 < cap && *s->p != '\r')
			out[k++] = (char)*s->p;
		s->p++;
	}
	out[k] = '\0';
	vx_scan_next_line(s);
}

static int
node_data(gmsh *g)
{
	int64_t ns, nr, ni, i, tags[4] = { 0, 1, 0, -1 };
	char name[256] = "";
	double x;
	int rc, want;

	if ((rc = gi64(g, &ns, "$NodeData")))
		return rc;
	if (ns < 0 || ns > 100)
		return gfail(g, "$NodeData: bad string tag count", NULL);
	vx_scan_next_line(&g->s);
	for (i = 0; i < ns; i++) {
		char t[256];
		string_tag(g, t, sizeof t);
		if (i == 0)
			memcpy(name, t, sizeof name);
	}
	if ((rc = gi64(g, &nr, "$NodeData")))
		return rc;
	if (nr < 0 || nr > 100)
		return gfail(g, "$NodeData: bad real tag count", NULL);
	for (i = 0; i < nr; i++)
		if ((rc = gf64(g, &x, "$NodeData")))
			return rc;
	if ((rc = gi64(g, &ni, "$NodeData")))
		return rc;
	if (ni < 3 || ni > 100)
		return gfail(g, "$NodeData: need at least 3 integer tags (time "
		    "step, components, entries)", NULL);
	for (i = 0; i < ni; i++) {
		int64_t v;
		if ((rc = gi64(g, &v, "$NodeData")))
			return rc;
		if (i < 4)
			tags[i] = v;
	}
	int64_t ncomp = tags[1], nent = tags[2];
	if (ncomp < 1 || ncomp > 9 || nent < 0 ||
	    (uint64_t)nent > vx_scan_left(&g->s) / 4 + 1)
		return gfail(g, "$NodeData: bad component or entry count", NULL);
	g->info->narray += ncomp == 1;
	const char *sel = g->opt ? g->opt->scalar : NULL;
	want = g->val == NULL && (sel == NULL ? ncomp == 1 :
	    strcmp(sel, name) == 0);
	if (want && ncomp != 1)
		return gfail(g, "$NodeData '%.60s' has several components (need "
		    "one)", name);
	if (want) {
		if (!g->have_nodes)
			return gfail(g, "$NodeData before $Nodes", NULL);
		if (g->map.tag == NULL && (rc = map_build(g)) != 0)
			return rc;
		g->val = vx_malloc((g->npoint ? g->npoint : 1) * sizeof *g->val,
		    g->e);
		g->has = vx_calloc(g->npoint ? g->npoint : 1, 1, g->e);
		if (g->val == NULL || g->has == NULL)
			return VX_ENOMEM;
		for (size_t p = 0; p < g->npoint; p++)
			g->val[p] = NAN;
		snprintf(g->valname, sizeof g->valname, "%.*s",
		    (int)sizeof g->valname - 1, name);
	}
	for (i = 0; i < nent; i++) {
		int64_t tag, p;
		if ((rc = gi64(g, &tag, "$NodeData")))
			return rc;
		for (int64_t c = 0; c < ncomp; c++)
			if ((rc = gf64(g, &x, "$NodeData")))
				return rc;
		if (!want)
			continue;
		if ((p = map_find(&g->map, tag)) < 0)
			return vx_err_set(g->e, VX_EDATA, "gmsh: line %zu: "
			    "$NodeData refers to undefined node %lld",
			    vx_scan_lineno(&g->s), (long long)tag);
		g->val[p] = x;
		g->has[p] = 1;
	}
	return gend(g, "NodeData");
}

static int
parse(gmsh *g)
{
	vx_scan *s = &g->s;
	char t[TOK];
	double ver;
	int64_t ft, ds;
	int rc, k;

	if (vx_scan_token(s, t, sizeof t) <= 0 || strcmp(t, "$MeshFormat") != 0)
		return vx_err_set(g->e, VX_EDATA, "gmsh: not a gmsh file (no "
		    "$MeshFormat)");
	if ((rc = gf64(g, &ver, "$MeshFormat")) ||
	    (rc = gi64(g, &ft, "$MeshFormat")) ||
	    (rc = gi64(g, &ds, "$MeshFormat")))
		return rc;
	if (ft != 0)
		return gfail(g, "binary .msh files are not supported (save as "
		    "ASCII)", NULL);
	if (ver >= 2 && ver < 3)
		g->v4 = 0;
	else if (ver == 4.1)
		g->v4 = 1;
	else {
		char vs[32];
		snprintf(vs, sizeof vs, "%g", ver);
		return gfail(g, "version %s is not supported (2.x or 4.1)", vs);
	}
	g->info->format = g->v4 ? VX_TETFMT_GMSH4 : VX_TETFMT_GMSH2;
	if ((rc = gend(g, "MeshFormat")))
		return rc;
	while ((k = vx_scan_token(s, t, sizeof t)) != 0) {
		if (k < 0 || t[0] != '$')
			return gfail(g, "expected a section ($Name)", NULL);
		if (strcmp(t, "$Nodes") == 0)
			rc = nodes(g);
		else if (strcmp(t, "$Elements") == 0)
			rc = elements(g);
		else if (strcmp(t, "$NodeData") == 0)
			rc = node_data(g);
		else
			rc = gskip(g, t);
		if (rc)
			return rc;
	}
	if (!g->have_nodes || !g->have_elems)
		return vx_err_set(g->e, VX_EDATA, "gmsh: no %s section",
		    g->have_nodes ? "$Elements" : "$Nodes");
	if (g->val == NULL) {
		if (g->opt && g->opt->scalar)
			return vx_err_set(g->e, VX_EDATA, "gmsh: no $NodeData "
			    "named '%.60s'", g->opt->scalar);
		return vx_err_set(g->e, VX_EDATA, "gmsh: no one-component "
		    "$NodeData (the mesh needs one value per node)");
	}
	for (size_t i = 0; i < 4 * g->ntet; i++)
		if (!g->has[g->tet[i]])
			return vx_err_set(g->e, VX_EDATA, "gmsh: node %lld of "
			    "tetrahedron %zu has no value in $NodeData "
			    "'%.60s'", (long long)g->ntag[g->tet[i]], i / 4,
			    g->valname);
	return 0;
}

int
vx_tetmesh_import_gmsh(vx_tetmesh *m, const void *buf, size_t n,
    const vx_tetimport_opt *opt, vx_tetimport_info *info, vx_err *e)
{
	vx_tetimport_info dummy;
	gmsh g;
	int rc;

	vx_tetmesh_init(m);
	if (info == NULL)
		info = &dummy;
	memset(info, 0, sizeof *info);
	memset(&g, 0, sizeof g);
	vx_scan_init(&g.s, buf, n);
	g.e = e;
	g.opt = opt;
	g.info = info;
	rc = parse(&g);
	if (rc == 0 && (uint64_t)g.ntet > VX_TETMESH_MAX_TETS)
		rc = vx_err_set(e, VX_EDATA, "gmsh: too many tetrahedra");
	if (rc == 0) {
		size_t bad;

		m->npoint = g.npoint;
		m->pts = g.pts;
		g.pts = NULL;
		m->ntet = g.ntet;
		m->tet = g.tet;
		g.tet = NULL;
		if ((rc = vx_imp_mesh_values(m, g.val, &bad, e)) == VX_EDATA)
			vx_err_set(e, rc, "gmsh: value %g of node %lld is "
			    "beyond the float range", g.val[bad],
			    (long long)g.ntag[bad]);
		vx_tetmesh_set_scalar(m, g.valname);
	}
	if (rc == 0)
		rc = vx_tetmesh_validate(m, e);
	free(g.pts);
	free(g.ntag);
	free(g.map.tag);
	free(g.map.idx);
	free(g.tet);
	free(g.val);
	free(g.has);
	if (rc != 0)
		vx_tetmesh_free(m);
	return rc;
}
