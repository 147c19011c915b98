/* hdr.c: Radiance RGBE images (.hdr, .pic): the reader (the header, the
 * resolution line in any of its 8 orientations, new run-length, flat and old
 * run-length scanlines) and a writer (new run-length or flat scanlines).
 * The format is Greg Ward's (Radiance's "Real Pixels", Graphics Gems II);
 * vx_imageio.h states what this reader makes of it. */
#include "vx_imageio.h"
#include "vx_scan.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define RLE_MIN  8           /* new run-length scanlines: 8 .. 0x7fff wide */
#define RLE_MAX  0x7fff
#define MINRUN   4           /* the writer's shortest run */

/* The geometry the resolution line gives. */
typedef struct geom {
	int w, h;                /* the image */
	int nscan, len;          /* scanlines in the file, pixels in each */
	int x_first;             /* 1: scanlines are columns */
	int xright, ydown;       /* pixels run to the right, scanlines down */
} geom;

/* ---- the header ---- */

/* line_is: the line [s, s + len) starts with key (which ends in '='). */
static int
line_is(const unsigned char *s, size_t len, const char *key)
{
	size_t k = strlen(key);

	return len >= k && memcmp(s, key, k) == 0;
}

/* numbers: the positive numbers (vx_scan.h's grammar) of the value
 * [s, s + len), blank-separated; returns how many, or -1 for a word that is
 * not one or for more than want of them. */
static int
numbers(const unsigned char *s, size_t len, double *out, int want)
{
	size_t i = 0;
	int got = 0;

	for (;;) {
		size_t b;

		while (i < len && (s[i] == ' ' || s[i] == '\t'))
			i++;
		if (i == len)
			return got;
		b = i;
		while (i < len && s[i] != ' ' && s[i] != '\t')
			i++;
		if (got == want || vx_num_f64((const char *)s + b, i - b, 0,
		    &out[got]) != 0 || !(out[got] > 0))
			return -1;
		got++;
	}
}

/* header: the lines from "#?" up to the empty line; *pos gets the offset of
 * the resolution line. */
static int
header(const unsigned char *p, size_t n, size_t *pos, vx_hdr_info *in,
    vx_err *e)
{
	size_t i = 0;
	long line = 0;

	if (n < 2 || p[0] != '#' || p[1] != '?')
		return vx_err_set(e, VX_EDATA, "not a Radiance file (no '#?' "
		    "line)");
	for (;;) {
		const unsigned char *s = p + i, *nl;
		size_t len;

		nl = memchr(s, '\n', n - i);
		line++;
		if (nl == NULL)
			return vx_err_set(e, VX_EDATA, "header: ends at line %ld "
			    "without the empty line before the resolution", line);
		len = (size_t)(nl - s);
		i += len + 1;
		if (len > 0 && s[len - 1] == '\r')
			len--;
		if (line == 1)
			continue;
		if (len == 0)
			break;
		if (line_is(s, len, "FORMAT=")) {
			const unsigned char *v = s + 7;
			size_t vl = len - 7;

			while (vl > 0 && (v[vl - 1] == ' ' || v[vl - 1] == '\t'))
				vl--;
			while (vl > 0 && (*v == ' ' || *v == '\t')) {
				v++;
				vl--;
			}
			if (vl == 15 && memcmp(v, "32-bit_rle_rgbe", 15) == 0)
				continue;
			return vx_err_set(e, VX_EDATA, "header line %ld: FORMAT="
			    "%.*s: only 32-bit_rle_rgbe is read%s", line,
			    (int)(vl < 40 ? vl : 40), (const char *)v,
			    vl == 15 && memcmp(v, "32-bit_rle_xyze", 15) == 0 ?
			    " (XYZE is not RGB)" : "");
		}
		if (line_is(s, len, "EXPOSURE=")) {
			double x;

			if (numbers(s + 9, len - 9, &x, 1) != 1)
				return vx_err_set(e, VX_EDATA, "header line %ld: "
				    "EXPOSURE: expected one positive number",
				    line);
			in->exposure *= x;
			continue;
		}
		if (line_is(s, len, "COLORCORR=")) {
			double x[3];

			if (numbers(s + 10, len - 10, x, 3) != 3)
				return vx_err_set(e, VX_EDATA, "header line %ld: "
				    "COLORCORR: expected three positive numbers",
				    line);
			for (int c = 0; c < 3; c++)
				in->colorcorr[c] *= x[c];
			continue;
		}
		/* comments, SOFTWARE=, VIEW=, PRIMARIES=, PIXASPECT=, ...:
		 * nothing this reader uses */
	}
	if (!(in->exposure > 0) || !isfinite(in->exposure) ||
	    !(in->colorcorr[0] > 0 && in->colorcorr[1] > 0 &&
	    in->colorcorr[2] > 0) || !isfinite(in->colorcorr[0] *
	    in->colorcorr[1] * in->colorcorr[2]))
		return vx_err_set(e, VX_EDATA, "header: the product of the "
		    "EXPOSURE or COLORCORR values is 0 or infinite");
	*pos = i;
	return 0;
}

/* res_axis: "[-+][XY]" at *i. */
static int
res_axis(const unsigned char *p, size_t n, size_t *i, int *sign, int *axis)
{
	if (*i + 2 > n || (p[*i] != '-' && p[*i] != '+') ||
	    (p[*i + 1] != 'X' && p[*i + 1] != 'Y'))
		return -1;
	*sign = p[*i] == '+' ? 1 : -1;
	*axis = p[*i + 1];
	*i += 2;
	return 0;
}

/* res_count: blanks, then a decimal count (vx_scan.h's integers). */
static int
res_count(const unsigned char *p, size_t n, size_t *i, long *out)
{
	size_t b;
	int64_t v;

	if (*i >= n || (p[*i] != ' ' && p[*i] != '\t'))
		return -1;
	while (*i < n && (p[*i] == ' ' || p[*i] == '\t'))
		(*i)++;
	b = *i;
	while (*i < n && p[*i] != ' ' && p[*i] != '\t' && p[*i] != '\r' &&
	    p[*i] != '\n')
		(*i)++;
	if (vx_num_i64((const char *)p + b, *i - b, 0, INT32_MAX, &v) != 0)
		return -1;
	*out = (long)v;
	return 0;
}

/* resolution: "-Y H +X W" (or another orientation) and its newline. */
static int
resolution(const unsigned char *p, size_t n, size_t *pos, geom *g,
    vx_hdr_info *in, vx_err *e)
{
	size_t i = *pos;
	int s1, a1, s2, a2;
	long n1, n2;

	if (res_axis(p, n, &i, &s1, &a1) != 0 || res_count(p, n, &i, &n1) != 0 ||
	    i >= n || (p[i] != ' ' && p[i] != '\t'))
		goto bad;
	while (i < n && (p[i] == ' ' || p[i] == '\t'))
		i++;
	if (res_axis(p, n, &i, &s2, &a2) != 0 || res_count(p, n, &i, &n2) != 0)
		goto bad;
	while (i < n && (p[i] == ' ' || p[i] == '\t' || p[i] == '\r'))
		i++;
	if (i >= n || p[i] != '\n' || a1 == a2)
		goto bad;
	*pos = i + 1;
	if (n1 < 1 || n2 < 1 || n1 > VX_IMAGE_MAX_DIM || n2 > VX_IMAGE_MAX_DIM ||
	    (size_t)n1 * (size_t)n2 > VX_IMAGE_MAX_PIXELS)
		return vx_err_set(e, VX_EDATA, "resolution %c%c %ld %c%c %ld: "
		    "size beyond the limits (1 to %d a side, at most %zu "
		    "pixels)", s1 > 0 ? '+' : '-', a1, n1, s2 > 0 ? '+' : '-', a2,
		    n2, VX_IMAGE_MAX_DIM, VX_IMAGE_MAX_PIXELS);
	g->nscan = (int)n1;
	g->len = (int)n2;
	g->x_first = a1 == 'X';
	if (g->x_first) {
		g->w = (int)n1;
		g->h = (int)n2;
		g->xright = s1 > 0;
		g->ydown = s2 < 0;
	} else {
		g->h = (int)n1;
		g->w = (int)n2;
		g->ydown = s1 < 0;
		g->xright = s2 > 0;
	}
	snprintf(in->orient, sizeof in->orient, "%c%c%c%c", s1 > 0 ? '+' : '-',
	    a1, s2 > 0 ? '+' : '-', a2);
	return 0;
bad:
	return vx_err_set(e, VX_EDATA, "resolution line: expected \"-Y H +X W\" "
	    "or another orientation (two of [-+]Y N, [-+]X N)");
}

/* ---- scanlines ---- */

static int
truncated(vx_err *e, int j, int nscan)
{
	return vx_err_set(e, VX_EDATA, "scanline %d of %d: the data ends early "
	    "(truncated file)", j + 1, nscan);
}

/* scan_rle: the four planes of a new run-length scanline (after its
 * 4-byte start) into sl. */
static int
scan_rle(const unsigned char *p, size_t n, size_t *pos, unsigned char *sl,
    int len, int j, int nscan, vx_err *e)
{
	size_t i = *pos;

	for (int c = 0; c < 4; c++) {
		int k = 0;

		while (k < len) {
			int code, cnt;

			if (i >= n)
				return truncated(e, j, nscan);
			code = p[i++];
			cnt = code > 128 ? code - 128 : code;
			if (cnt == 0)
				return vx_err_set(e, VX_EDATA, "scanline %d: a "
				    "run-length count of 0", j + 1);
			if (cnt > len - k)
				return vx_err_set(e, VX_EDATA, "scanline %d: a run "
				    "of %d passes the scanline's end (%d of %d "
				    "filled in component %d)", j + 1, cnt, k, len,
				    c);
			if (code > 128) {
				if (i >= n)
					return truncated(e, j, nscan);
				for (int t = 0; t < cnt; t++)
					sl[4 * (k + t) + c] = p[i];
				i++;
			} else {
				if ((size_t)cnt > n - i)
					return truncated(e, j, nscan);
				for (int t = 0; t < cnt; t++)
					sl[4 * (k + t) + c] = p[i + (size_t)t];
				i += (size_t)cnt;
			}
			k += cnt;
		}
	}
	*pos = i;
	return 0;
}

/* scan_old: pixels k.. of a flat or old run-length scanline into sl. */
static int
scan_old(const unsigned char *p, size_t n, size_t *pos, unsigned char *sl,
    int k, int len, int j, int nscan, vx_err *e)
{
	size_t i = *pos;
	int shift = 0;

	while (k < len) {
		const unsigned char *q;

		if (n - i < 4)
			return truncated(e, j, nscan);
		q = p + i;
		i += 4;
		if (q[0] == 1 && q[1] == 1 && q[2] == 1) {
			size_t cnt;

			if (k == 0)
				return vx_err_set(e, VX_EDATA, "scanline %d: an "
				    "old run-length code with no pixel before "
				    "it", j + 1);
			if (shift > 16)
				return vx_err_set(e, VX_EDATA, "scanline %d: more "
				    "than three old run-length codes in a row",
				    j + 1);
			cnt = (size_t)q[3] << shift;
			if (cnt > (size_t)(len - k))
				return vx_err_set(e, VX_EDATA, "scanline %d: a run "
				    "of %zu passes the scanline's end (%d of %d "
				    "filled)", j + 1, cnt, k, len);
			for (size_t t = 0; t < cnt; t++)
				memcpy(sl + 4 * (k + (int)t),
				    sl + 4 * (k - 1), 4);
			k += (int)cnt;
			shift += 8;
		} else {
			memcpy(sl + 4 * k, q, 4);
			k++;
			shift = 0;
		}
	}
	*pos = i;
	return 0;
}

/* scan: one scanline of g->len pixels at *pos into sl (4 bytes a pixel);
 * *rle gets 1 for the new encoding. */
static int
scan(const unsigned char *p, size_t n, size_t *pos, unsigned char *sl,
    const geom *g, int j, int *rle, vx_err *e)
{
	int len = g->len;
	const unsigned char *q = p + *pos;

	*rle = 0;
	if (len < RLE_MIN || len > RLE_MAX)
		return scan_old(p, n, pos, sl, 0, len, j, g->nscan, e);
	if (n - *pos < 4)
		return truncated(e, j, g->nscan);
	if (q[0] != 2 || q[1] != 2 || (q[2] & 0x80) != 0) {
		/* not the new encoding: q is the first pixel (Radiance's rule) */
		if (q[0] == 1 && q[1] == 1 && q[2] == 1)
			return vx_err_set(e, VX_EDATA, "scanline %d: an old "
			    "run-length code with no pixel before it", j + 1);
		memcpy(sl, q, 4);
		*pos += 4;
		return scan_old(p, n, pos, sl, 1, len, j, g->nscan, e);
	}
	if ((q[2] << 8 | q[3]) != len)
		return vx_err_set(e, VX_EDATA, "scanline %d: its run-length start "
		    "gives %d pixels, the resolution line %d", j + 1,
		    q[2] << 8 | q[3], len);
	*pos += 4;
	*rle = 1;
	return scan_rle(p, n, pos, sl, len, j, g->nscan, e);
}

/* decode: every scanline from pos; with img NULL only checks (and counts)
 * them, else also writes the pixels, scaled by f[3], in img. */
static int
decode(const unsigned char *p, size_t n, size_t pos, const geom *g,
    unsigned char *sl, const double f[3], vx_image *img, vx_hdr_info *in,
    vx_err *e)
{
	int rc, rle;

	in->nrle = in->nflat = 0;
	for (int j = 0; j < g->nscan; j++) {
		if ((rc = scan(p, n, &pos, sl, g, j, &rle, e)) != 0)
			return rc;
		if (rle)
			in->nrle++;
		else
			in->nflat++;
		if (img == NULL)
			continue;
		for (int k = 0; k < g->len; k++) {
			const unsigned char *q = sl + 4 * k;
			int x, y;
			float *o;

			if (g->x_first) {
				x = g->xright ? j : g->w - 1 - j;
				y = g->ydown ? k : g->h - 1 - k;
			} else {
				y = g->ydown ? j : g->h - 1 - j;
				x = g->xright ? k : g->w - 1 - k;
			}
			o = vx_image_pixel(img, x, y);
			if (q[3] == 0) {
				o[0] = o[1] = o[2] = 0;
				continue;
			}
			for (int c = 0; c < 3; c++)
				o[c] = (float)(ldexp((double)q[c], q[3] - 136) /
				    f[c]);
		}
	}
	in->trailing = n - pos;
	return 0;
}

int
vx_hdr_read_mem(vx_image *img, const void *buf, size_t n, vx_hdr_info *info,
    vx_err *e)
{
	const unsigned char *p = buf;
	vx_hdr_info in;
	unsigned char *sl;
	size_t pos = 0;
	double f[3];
	geom g;
	int rc;

	vx_image_init(img);
	memset(&in, 0, sizeof in);
	in.exposure = 1;
	in.colorcorr[0] = in.colorcorr[1] = in.colorcorr[2] = 1;
	if ((rc = header(p, n, &pos, &in, e)) != 0 ||
	    (rc = resolution(p, n, &pos, &g, &in, e)) != 0)
		return rc;
	for (int c = 0; c < 3; c++)
		f[c] = in.exposure * in.colorcorr[c];
	if ((sl = vx_malloc((size_t)g.len * 4, e)) == NULL)
		return e->code;
	/* first the scanlines' structure (no image yet), then the pixels */
	if ((rc = decode(p, n, pos, &g, sl, f, NULL, &in, e)) == 0 &&
	    (rc = vx_image_alloc_uninit(img, g.w, g.h, 3, e)) == 0)
		rc = decode(p, n, pos, &g, sl, f, img, &in, e);
	free(sl);
	if (rc != 0) {
		vx_image_free(img);
		return rc;
	}
	if (info != NULL)
		*info = in;
	return 0;
}

/* ---- the writer ---- */

/* rgbe: the nearest RGBE pixel to (r, g, b), each finite and >= 0. */
static void
rgbe(const double v[3], unsigned char out[4])
{
	double m = v[0] > v[1] ? v[0] : v[1];
	int ex, mant[3], top = 0;

	m = m > v[2] ? m : v[2];
	memset(out, 0, 4);
	if (!(m > 0))
		return;
	(void)frexp(m, &ex);      /* m = f 2^ex, f in [0.5, 1) */
	for (;;) {
		if (ex > 127)
			ex = 127;     /* the largest exponent byte, 255 */
		if (ex < -127)
			ex = -127;    /* the smallest nonzero one, 1 */
		top = 0;
		for (int c = 0; c < 3; c++) {
			double q = floor(ldexp(v[c], 8 - ex) + 0.5);

			mant[c] = q > 255 ? 256 : (int)q;
			top = mant[c] > top ? mant[c] : top;
		}
		if (top < 256)
			break;
		if (ex == 127) {  /* beyond 255 * 2^119: the largest value */
			for (int c = 0; c < 3; c++)
				mant[c] = mant[c] > 255 ? 255 : mant[c];
			top = 255;
			break;
		}
		ex++;             /* rounding carried into the next power */
	}
	if (top == 0)
		return;
	for (int c = 0; c < 3; c++)
		out[c] = (unsigned char)mant[c];
	out[3] = (unsigned char)(ex + 128);
}

/* rle_plane: component c of len pixels (4 bytes each) in Radiance's new
 * run-length code, appended at o; returns the new end. */
static unsigned char *
rle_plane(const unsigned char *px, int len, int c, unsigned char *o)
{
	int i = 0;

	while (i < len) {
		int beg, cnt = 0;

		/* the next run of MINRUN or more equal bytes, from i */
		for (beg = i; beg < len; beg += cnt) {
			for (cnt = 1; cnt < 127 && beg + cnt < len &&
			    px[4 * (beg + cnt) + c] == px[4 * beg + c]; cnt++)
				;
			if (cnt >= MINRUN)
				break;
		}
		while (i < beg) {         /* literals before it */
			int k = beg - i < 128 ? beg - i : 128;

			*o++ = (unsigned char)k;
			for (int t = 0; t < k; t++)
				*o++ = px[4 * (i + t) + c];
			i += k;
		}
		if (beg < len) {          /* the run */
			*o++ = (unsigned char)(128 + cnt);
			*o++ = px[4 * beg + c];
			i = beg + cnt;
		}
	}
	return o;
}

int
vx_hdr_write(const vx_image *img, FILE *f, int rle, vx_err *e)
{
	unsigned char *px, *buf;
	int w = img->w, h = img->h, nc = img->nc, rc = 0;

	if (nc != 1 && nc != 3)
		return vx_err_set(e, VX_EUSAGE, "hdr: %d channels (1 or 3 are "
		    "written)", nc);
	for (size_t i = 0; i < vx_image_nvalue(img); i++)
		if (!isfinite(img->px[i]))
			return vx_err_set(e, VX_EDATA, "hdr: pixel (%zu, %zu) is "
			    "%s", i / (size_t)nc % (size_t)w,
			    i / (size_t)nc / (size_t)w,
			    isnan(img->px[i]) ? "NaN" : "infinite");
	rle = rle && w >= RLE_MIN && w <= RLE_MAX;
	px = vx_malloc((size_t)w * 4, e);
	buf = vx_malloc(4 + 4 * ((size_t)w + (size_t)w / 128 + 2), e);
	if (px == NULL || buf == NULL) {
		free(px);
		free(buf);
		return VX_ENOMEM;
	}
	fprintf(f, "#?RADIANCE\n# written by voxlux\nFORMAT=32-bit_rle_rgbe\n"
	    "\n-Y %d +X %d\n", h, w);
	for (int y = 0; y < h && rc == 0; y++) {
		unsigned char *o = buf;

		for (int x = 0; x < w; x++) {
			const float *s = vx_image_pixel(img, x, y);
			double v[3];

			for (int c = 0; c < 3; c++) {
				v[c] = s[nc == 3 ? c : 0];
				v[c] = v[c] > 0 ? v[c] : 0;
			}
			rgbe(v, px + 4 * x);
		}
		if (rle) {
			*o++ = 2;
			*o++ = 2;
			*o++ = (unsigned char)(w >> 8);
			*o++ = (unsigned char)(w & 0xff);
			for (int c = 0; c < 4; c++)
				o = rle_plane(px, w, c, o);
		} else {
			memcpy(o, px, (size_t)w * 4);
			o += (size_t)w * 4;
		}
		if (fwrite(buf, 1, (size_t)(o - buf), f) != (size_t)(o - buf))
			rc = VX_EIO;
	}
	free(px);
	free(buf);
	if (rc != 0 || fflush(f) != 0 || ferror(f))
		return vx_err_set(e, VX_EIO, "hdr: write error: %s",
		    strerror(errno));
	return 0;
}
