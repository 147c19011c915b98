/* json.c: the bounded JSON reader (vx_json.h). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vx_json.h"
#include "vx_scan.h"

typedef struct parser {
	const unsigned char *base, *p, *end;
	const unsigned char *lpos;    /* line counted up to here: */
	int lline;                    /*   the line of lpos */
	vx_json *j;
	int max_depth, max_nodes;
	vx_err *e;
} parser;

static int
fail(parser *ps, const unsigned char *at, const char *what)
{
	const unsigned char *q, *bol = ps->base;
	int line = 1;

	for (q = ps->base; q < at; q++)
		if (*q == '\n') {
			line++;
			bol = q + 1;
		}
	return vx_err_set(ps->e, VX_EDATA, "line %d, column %zu: %s", line,
	    (size_t)(at - bol) + 1, what);
}

/* line_of: the line of at, counted on from the last call (nodes start
 * in increasing order, so the text is scanned once). */
static int
line_of(parser *ps, const unsigned char *at)
{
	for (; ps->lpos < at; ps->lpos++)
		ps->lline += *ps->lpos == '\n';
	return ps->lline;
}

static void
blanks(parser *ps)
{
	while (ps->p < ps->end && (*ps->p == ' ' || *ps->p == '\t' ||
	    *ps->p == '\n' || *ps->p == '\r'))
		ps->p++;
}

/* new_node: append a node; its index, or -1 (error set). */
static int
new_node(parser *ps, vx_json_type t)
{
	vx_json *j = ps->j;
	vx_json_node *nd;

	if (j->n >= ps->max_nodes) {
		fail(ps, ps->p, "too many values");
		return -1;
	}
	if (j->n == j->cap) {
		int cap = j->cap ? 2 * j->cap : 64;

		if (cap > ps->max_nodes)
			cap = ps->max_nodes;
		nd = realloc(j->node, (size_t)cap * sizeof *nd);
		if (nd == NULL) {
			vx_err_set(ps->e, VX_ENOMEM, "out of memory");
			return -1;
		}
		j->node = nd;
		j->cap = cap;
	}
	nd = &j->node[j->n];
	memset(nd, 0, sizeof *nd);
	nd->type = t;
	nd->first = nd->next = -1;
	nd->line = line_of(ps, ps->p);
	return j->n++;
}

static int
hex4(const unsigned char *p, unsigned *v)
{
	*v = 0;
	for (int i = 0; i < 4; i++) {
		int c = p[i], d;

		if (c >= '0' && c <= '9')
			d = c - '0';
		else if (c >= 'a' && c <= 'f')
			d = c - 'a' + 10;
		else if (c >= 'A' && c <= 'F')
			d = c - 'A' + 10;
		else
			return -1;
		*v = *v << 4 | (unsigned)d;
	}
	return 0;
}

/* string: the string at ps->p (its opening quote) decoded into the pool;
 * *off gets its offset there. */
static int
string(parser *ps, size_t *off)
{
	vx_json *j = ps->j;
	const unsigned char *start = ps->p;
	char *out = j->pool + j->pool_len;
	size_t k = 0;

	ps->p++;
	for (;;) {
		unsigned c, u, lo;

		if (ps->p >= ps->end)
			return fail(ps, start, "string without its closing quote");
		c = *ps->p++;
		if (c == '"')
			break;
		if (k >= VX_JSON_STR_MAX)
			return fail(ps, start, "string longer than the limit");
		if (c < 0x20)
			return fail(ps, ps->p - 1, "control character in a string");
		if (c != '\\') {
			out[k++] = (char)c;
			continue;
		}
		if (ps->p >= ps->end)
			return fail(ps, start, "string without its closing quote");
		c = *ps->p++;
		switch (c) {
		case '"': case '\\': case '/':
			out[k++] = (char)c;
			continue;
		case 'b': out[k++] = '\b'; continue;
		case 'f': out[k++] = '\f'; continue;
		case 'n': out[k++] = '\n'; continue;
		case 'r': out[k++] = '\r'; continue;
		case 't': out[k++] = '\t'; continue;
		case 'u': break;
		default:
			return fail(ps, ps->p - 2, "unknown escape in a string");
		}
		if (ps->end - ps->p < 4 || hex4(ps->p, &u) != 0)
			return fail(ps, ps->p - 2, "\\u needs four hex digits");
		ps->p += 4;
		if (u >= 0xdc00 && u <= 0xdfff)
			return fail(ps, ps->p - 6, "lone low surrogate");
		if (u >= 0xd800 && u <= 0xdbff) {
			if (ps->end - ps->p < 6 || ps->p[0] != '\\' ||
			    ps->p[1] != 'u' || hex4(ps->p + 2, &lo) != 0 ||
			    lo < 0xdc00 || lo > 0xdfff)
				return fail(ps, ps->p - 6, "high surrogate without "
				    "its low surrogate");
			ps->p += 6;
			u = 0x10000 + ((u - 0xd800) << 10) + (lo - 0xdc00);
		}
		if (u == 0)
			return fail(ps, ps->p - 6, "\\u0000 in a string");
		/* the decoded bytes never outnumber the escape's */
		if (u < 0x80)
			out[k++] = (char)u;
		else if (u < 0x800) {
			out[k++] = (char)(0xc0 | u >> 6);
			out[k++] = (char)(0x80 | (u & 0x3f));
		} else if (u < 0x10000) {
			out[k++] = (char)(0xe0 | u >> 12);
			out[k++] = (char)(0x80 | (u >> 6 & 0x3f));
			out[k++] = (char)(0x80 | (u & 0x3f));
		} else {
			out[k++] = (char)(0xf0 | u >> 18);
			out[k++] = (char)(0x80 | (u >> 12 & 0x3f));
			out[k++] = (char)(0x80 | (u >> 6 & 0x3f));
			out[k++] = (char)(0x80 | (u & 0x3f));
		}
	}
	out[k] = '\0';
	*off = j->pool_len;
	j->pool_len += k + 1;
	return 0;
}

static int
digit(int c)
{
	return c >= '0' && c <= '9';
}

static int
number(parser *ps, double *v)
{
	const unsigned char *s = ps->p, *q = ps->p;

	if (q < ps->end && *q == '-')
		q++;
	if (q < ps->end && *q == '0')
		q++;
	else if (q < ps->end && digit(*q))
		while (q < ps->end && digit(*q))
			q++;
	else
		return fail(ps, s, "not a JSON value");
	if (q < ps->end && *q == '.') {
		q++;
		if (q >= ps->end || !digit(*q))
			return fail(ps, s, "a number needs digits after '.'");
		while (q < ps->end && digit(*q))
			q++;
	}
	if (q < ps->end && (*q == 'e' || *q == 'E')) {
		q++;
		if (q < ps->end && (*q == '+' || *q == '-'))
			q++;
		if (q >= ps->end || !digit(*q))
			return fail(ps, s, "a number needs digits in its exponent");
		while (q < ps->end && digit(*q))
			q++;
	}
	if (vx_num_f64((const char *)s, (size_t)(q - s), 0, v) != 0)
		return fail(ps, s, "number beyond the double range (or longer "
		    "than the limit)");
	ps->p = q;
	return 0;
}

static int
word(parser *ps, const char *w)
{
	size_t n = strlen(w);

	if ((size_t)(ps->end - ps->p) < n || memcmp(ps->p, w, n) != 0)
		return fail(ps, ps->p, "not a JSON value");
	ps->p += n;
	return 0;
}

/* value: the value at ps->p (after blanks); *out gets its node. */
static int
value(parser *ps, int depth, int *out)
{
	int i, rc, last = -1;
	size_t off;
	unsigned char c;

	blanks(ps);
	if (ps->p >= ps->end)
		return fail(ps, ps->p, "the text ends where a value should be");
	c = *ps->p;
	switch (c) {
	case '{':
	case '[':
		if (depth >= ps->max_depth)
			return fail(ps, ps->p, "arrays and objects nested too "
			    "deep");
		if ((i = new_node(ps, c == '{' ? VX_JSON_OBJECT :
		    VX_JSON_ARRAY)) < 0)
			return ps->e->code;
		ps->p++;
		blanks(ps);
		if (ps->p < ps->end && *ps->p == (c == '{' ? '}' : ']')) {
			ps->p++;
			break;
		}
		for (;;) {
			int child;

			blanks(ps);
			if (c == '{') {
				if (ps->p >= ps->end || *ps->p != '"')
					return fail(ps, ps->p, "expected a key "
					    "string");
				if ((rc = string(ps, &off)) != 0)
					return rc;
				blanks(ps);
				if (ps->p >= ps->end || *ps->p != ':')
					return fail(ps, ps->p, "expected ':' after "
					    "a key");
				ps->p++;
			}
			if ((rc = value(ps, depth + 1, &child)) != 0)
				return rc;
			if (c == '{')   /* the pool never moves */
				ps->j->node[child].key = ps->j->pool + off;
			if (last < 0)
				ps->j->node[i].first = child;
			else
				ps->j->node[last].next = child;
			last = child;
			ps->j->node[i].n++;
			blanks(ps);
			if (ps->p < ps->end && *ps->p == ',') {
				ps->p++;
				continue;
			}
			if (ps->p < ps->end && *ps->p == (c == '{' ? '}' :
			    ']')) {
				ps->p++;
				break;
			}
			return fail(ps, ps->p, ps->p >= ps->end ? "the text "
			    "ends inside an array or object" : c == '{' ?
			    "expected ',' or '}'" : "expected ',' or ']'");
		}
		break;
	case '"':
		if ((i = new_node(ps, VX_JSON_STRING)) < 0)
			return ps->e->code;
		if ((rc = string(ps, &off)) != 0)
			return rc;
		ps->j->node[i].str = ps->j->pool + off;
		ps->j->node[i].len = strlen(ps->j->pool + off);
		break;
	case 't':
	case 'f':
	case 'n':
		if ((i = new_node(ps, c == 't' ? VX_JSON_TRUE : c == 'f' ?
		    VX_JSON_FALSE : VX_JSON_NULL)) < 0)
			return ps->e->code;
		if ((rc = word(ps, c == 't' ? "true" : c == 'f' ? "false" :
		    "null")) != 0)
			return rc;
		break;
	default:
		if ((i = new_node(ps, VX_JSON_NUMBER)) < 0)
			return ps->e->code;
		if ((rc = number(ps, &ps->j->node[i].num)) != 0)
			return rc;
		break;
	}
	*out = i;
	return 0;
}

int
vx_json_parse(vx_json *j, const void *buf, size_t n, int max_depth,
    int max_nodes, vx_err *e)
{
	parser ps;
	int top, rc;

	memset(j, 0, sizeof *j);
	ps.base = ps.p = ps.lpos = buf;
	ps.lline = 1;
	ps.end = ps.base + n;
	ps.j = j;
	ps.max_depth = max_depth;
	ps.max_nodes = max_nodes > 0 ? max_nodes : 1;
	ps.e = e;
	if (n >= 3 && memcmp(ps.p, "\xef\xbb\xbf", 3) == 0)
		ps.p += 3;
	/* decoded strings with their NULs never outgrow the text, so the
	 * pool is allocated once and never moves */
	if ((j->pool = vx_malloc(n + 1, e)) == NULL)
		return VX_ENOMEM;
	j->pool_cap = n + 1;
	if ((rc = value(&ps, 0, &top)) != 0)
		goto bad;
	blanks(&ps);
	if (ps.p != ps.end) {
		rc = fail(&ps, ps.p, "text after the value");
		goto bad;
	}
	return 0;
bad:
	vx_json_free(j);
	return rc;
}

void
vx_json_free(vx_json *j)
{
	free(j->node);
	free(j->pool);
	memset(j, 0, sizeof *j);
}

const vx_json_node *
vx_json_at(const vx_json *j, int i)
{
	return i >= 0 && i < j->n ? &j->node[i] : NULL;
}

const vx_json_node *
vx_json_get(const vx_json *j, const vx_json_node *obj, const char *key,
    int *dup)
{
	const vx_json_node *found = NULL, *c;

	if (dup != NULL)
		*dup = 0;
	if (obj == NULL || obj->type != VX_JSON_OBJECT)
		return NULL;
	for (c = vx_json_at(j, obj->first); c != NULL; c = vx_json_at(j,
	    c->next))
		if (strcmp(c->key, key) == 0) {
			if (found == NULL)
				found = c;
			else if (dup != NULL)
				*dup = 1;
		}
	return found;
}

const char *
vx_json_type_name(vx_json_type t)
{
	static const char *names[] = { "null", "false", "true", "number",
	    "string", "array", "object" };

	return (unsigned)t < sizeof names / sizeof names[0] ? names[t] : "?";
}
