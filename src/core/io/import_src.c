/* import_src.c: byte sources for the importers (memory, bounded gunzip)
 * and loading whole files into memory. */
#include "import_priv.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#define GZ_CHUNK ((size_t)1 << 16)

int
vx_imp_is_gzip(const void *p, size_t n)
{
	const unsigned char *b = p;

	return n >= 3 && b[0] == 0x1f && b[1] == 0x8b && b[2] == 8;
}

void
vx_imp_src_mem(vx_imp_src *s, const void *p, size_t n)
{
	static const unsigned char none[1];

	memset(s, 0, sizeof *s);
	s->mem = p != NULL ? p : none;
	s->n = n;
	s->fd = -1;
}

void
vx_imp_src_fd(vx_imp_src *s, int fd)
{
	memset(s, 0, sizeof *s);
	s->gz = 2;
	s->fd = fd;
}

/* fd_read: up to n bytes of the descriptor into p (short only at its
 * end); *got the count */
static int
fd_read(vx_imp_src *s, unsigned char *p, size_t n, size_t *got, vx_err *e)
{
	*got = 0;
	while (*got < n && !s->eof) {
		ssize_t r = read(s->fd, p + *got, n - *got);

		if (r < 0) {
			if (errno == EINTR)
				continue;
			return vx_err_set(e, VX_EIO, "read: %s", strerror(errno));
		}
		if (r == 0)
			s->eof = 1;
		*got += (size_t)r;
	}
	return 0;
}

int
vx_imp_src_gzip(vx_imp_src *s, vx_imp_src *under, vx_err *e)
{
	memset(s, 0, sizeof *s);
	s->gz = 1;
	s->fd = -1;
	s->under = under;
	/* 15 + 16: a gzip wrapper, not zlib's */
	if (inflateInit2(&s->zs, 15 + 16) != Z_OK)
		return vx_err_set(e, VX_ENOMEM, "gzip: cannot start inflate");
	s->zinit = 1;
	return 0;
}

int
vx_imp_src_auto(vx_imp_src *s, const void *p, size_t n, vx_err *e)
{
	vx_imp_src *m;
	int rc;

	if (!vx_imp_is_gzip(p, n)) {
		vx_imp_src_mem(s, p, n);
		return 0;
	}
	if ((m = vx_malloc(sizeof *m, e)) == NULL)
		return VX_ENOMEM;
	vx_imp_src_mem(m, p, n);
	if ((rc = vx_imp_src_gzip(s, m, e)) != 0) {
		free(m);
		return rc;
	}
	s->own = m;
	return 0;
}

void
vx_imp_src_close(vx_imp_src *s)
{
	if (s->zinit)
		inflateEnd(&s->zs);
	free(s->buf);
	if (s->own != NULL) {
		vx_imp_src_close(s->own);
		free(s->own);
	}
	memset(s, 0, sizeof *s);
}

/* gz_inflate: inflate into out[0..outn) until it is full or the stream
 * ends (all members); *produced gets the count. */
static int
gz_inflate(vx_imp_src *s, unsigned char *out, size_t outn, size_t *produced,
    vx_err *e)
{
	const unsigned char *in;
	size_t avail, used;
	int rc, src;

	*produced = 0;
	while (*produced < outn) {
		if (s->zend) {
			/* another gzip member may follow; other bytes after
			 * a member are ignored, as gzip(1) does */
			if ((rc = vx_imp_peek(s->under, 3, &in, &avail, e)) != 0)
				return rc;
			if (!vx_imp_is_gzip(in, avail))
				return 0;
			inflateReset(&s->zs);
			s->zend = 0;
		}
		if ((rc = vx_imp_peek(s->under, GZ_CHUNK, &in, &avail, e)) != 0)
			return rc;
		size_t room = outn - *produced;

		if (room > UINT_MAX)
			room = UINT_MAX;
		s->zs.next_in = (unsigned char *)in;
		s->zs.avail_in = (uInt)avail;
		s->zs.next_out = out + *produced;
		s->zs.avail_out = (uInt)room;
		rc = inflate(&s->zs, Z_NO_FLUSH);
		used = avail - s->zs.avail_in;
		*produced += room - s->zs.avail_out;
		if (used > 0 && (src = vx_imp_skip(s->under, used, e)) != 0)
			return src;
		if (rc == Z_STREAM_END) {
			s->zend = 1;
			continue;
		}
		if (rc == Z_BUF_ERROR && avail == 0)
			return vx_err_set(e, VX_EDATA, "gzip: compressed data ends "
			    "early (truncated file?)");
		if (rc == Z_MEM_ERROR)
			return vx_err_set(e, VX_ENOMEM, "gzip: out of memory");
		if (rc != Z_OK && rc != Z_BUF_ERROR)
			return vx_err_set(e, VX_EDATA, "gzip: corrupt data (%s)",
			    s->zs.msg ? s->zs.msg : "inflate failed");
	}
	return 0;
}

int
vx_imp_peek(vx_imp_src *s, size_t want, const unsigned char **p, size_t *avail,
    vx_err *e)
{
	size_t have, got;
	int rc;

	if (s->gz == 0) {
		have = s->n - s->pos;
		*p = s->mem + s->pos;
		*avail = want < have ? want : have;
		return 0;
	}
	have = s->len - s->off;
	if (have < want) {
		if (s->off > 0) {
			memmove(s->buf, s->buf + s->off, have);
			s->len = have;
			s->off = 0;
		}
		if (s->cap < want) {
			size_t cap = s->cap ? s->cap : GZ_CHUNK;
			unsigned char *b;

			while (cap < want)
				cap = cap > SIZE_MAX / 2 ? want : 2 * cap;
			if ((b = realloc(s->buf, cap)) == NULL)
				return vx_err_set(e, VX_ENOMEM, "%s: out of memory "
				    "for %zu bytes", s->gz == 1 ? "gzip" : "input",
				    cap);
			s->buf = b;
			s->cap = cap;
		}
		if ((rc = s->gz == 1 ? gz_inflate(s, s->buf + s->len, want - have,
		    &got, e) : fd_read(s, s->buf + s->len, want - have, &got, e)))
			return rc;
		s->len += got;
		have += got;
	}
	{
		static const unsigned char none[1];

		/* nothing buffered yet (want 0): no null pointer arithmetic */
		*p = s->buf != NULL ? s->buf + s->off : none;
	}
	*avail = want < have ? want : have;
	return 0;
}

int
vx_imp_skip(vx_imp_src *s, uint64_t k, vx_err *e)
{
	if (s->gz == 0) {
		if (k > s->n - s->pos)
			return vx_err_set(e, VX_EDATA, "input ends after %llu "
			    "bytes, %llu needed", (unsigned long long)s->n,
			    (unsigned long long)(s->pos + k));
		s->pos += (size_t)k;
		s->done += k;
		return 0;
	}
	while (k > 0) {
		const unsigned char *p;
		size_t avail, want = k < GZ_CHUNK ? (size_t)k : GZ_CHUNK;
		int rc;

		if ((rc = vx_imp_peek(s, want, &p, &avail, e)) != 0)
			return rc;
		if (avail == 0)
			return vx_err_set(e, VX_EDATA, "input ends after %llu "
			    "bytes, %llu needed", (unsigned long long)s->done,
			    (unsigned long long)(s->done + k));
		s->off += avail;
		s->done += avail;
		k -= avail;
	}
	return 0;
}

int
vx_imp_read(vx_imp_src *s, void *dst, size_t n, size_t *got, vx_err *e)
{
	unsigned char *d = dst;
	size_t k;
	int rc;

	if (s->gz == 0) {
		k = s->n - s->pos;
		if (k > n)
			k = n;
		if (k > 0)
			memcpy(d, s->mem + s->pos, k);
		s->pos += k;
		s->done += k;
		*got = k;
		return 0;
	}
	k = s->len - s->off;
	if (k > n)
		k = n;
	if (k > 0)
		memcpy(d, s->buf + s->off, k);
	s->off += k;
	*got = k;
	if (k < n) {
		size_t more;

		rc = s->gz == 1 ? gz_inflate(s, d + k, n - k, &more, e) :
		    fd_read(s, d + k, n - k, &more, e);
		*got += more;
		if (rc != 0)
			return rc;
	}
	s->done += *got;
	return 0;
}

uint64_t
vx_imp_left_max(const vx_imp_src *s)
{
	uint64_t in, buffered;

	if (s->gz == 0)
		return s->n - s->pos;
	buffered = s->len - s->off;
	if (s->gz == 2)     /* not known before the end is read */
		return s->eof ? buffered : UINT64_MAX;
	in = vx_imp_left_max(s->under);
	if (in > (UINT64_MAX - buffered - GZ_CHUNK) / IMP_GZ_RATIO)
		return UINT64_MAX;
	/* inflate may hold back up to a window's worth of output */
	return buffered + in * IMP_GZ_RATIO + GZ_CHUNK;
}

int
vx_imp_streamed(const vx_imp_src *s)
{
	return s->gz == 2 || (s->gz == 1 && vx_imp_streamed(s->under));
}

int
vx_imp_need(vx_imp_src *s, uint64_t n, const char *what, vx_err *e)
{
	uint64_t left = vx_imp_left_max(s);

	if (vx_imp_streamed(s)) {
		/* no size to check: the bytes themselves, read ahead with
		 * the buffer growing as they arrive (never on the header's
		 * word alone) */
		const unsigned char *p;
		size_t want = GZ_CHUNK, avail;
		int rc;

		if (n == 0)
			return 0;
		if (n > SIZE_MAX / 2)
			return vx_err_set(e, VX_EDATA, "%s: %llu bytes: too many",
			    what, (unsigned long long)n);
		for (;;) {
			if (want > n)
				want = (size_t)n;
			if ((rc = vx_imp_peek(s, want, &p, &avail, e)) != 0)
				return rc;
			if (avail >= n)
				return 0;
			if (avail < want)
				return vx_err_set(e, VX_EDATA, "%s: truncated: the "
				    "input ends after %zu of %llu bytes", what, avail,
				    (unsigned long long)n);
			want *= 2;
		}
	}
	if (left >= n)
		return 0;
	if (s->gz != 1)
		return vx_err_set(e, VX_EDATA, "%s: truncated: %llu bytes left, "
		    "%llu needed", what, (unsigned long long)left,
		    (unsigned long long)n);
	return vx_err_set(e, VX_EDATA, "%s: truncated: the compressed data "
	    "left can hold at most %llu bytes, %llu needed", what,
	    (unsigned long long)left, (unsigned long long)n);
}

int
vx_imp_trailing(vx_imp_src *s, size_t slack, int *more, vx_err *e)
{
	const unsigned char *p;
	size_t avail;
	int rc;

	if ((rc = vx_imp_peek(s, slack + 1, &p, &avail, e)) != 0)
		return rc;
	*more = avail > slack;
	return 0;
}

/* ---- files ---- */

static int
load_fd(vx_imp_file *f, int fd, const char *path, vx_err *e)
{
	size_t cap = 0, n = 0;
	unsigned char *p = NULL;

	for (;;) {
		ssize_t r;

		if (n == cap) {
			size_t nc = cap ? 2 * cap : (size_t)1 << 20;
			unsigned char *q;

			if (nc < cap || (q = realloc(p, nc)) == NULL) {
				free(p);
				return vx_err_set(e, VX_ENOMEM, "%s: out of memory "
				    "after %zu bytes", path, n);
			}
			p = q;
			cap = nc;
		}
		r = read(fd, p + n, cap - n);
		if (r < 0) {
			if (errno == EINTR)
				continue;
			int err = errno;

			free(p);
			return vx_err_set(e, VX_EIO, "%s: read: %s", path,
			    strerror(err));
		}
		if (r == 0)
			break;
		n += (size_t)r;
	}
	f->p = p;
	f->n = n;
	f->mapped = 0;
	return 0;
}

int
vx_imp_file_load(vx_imp_file *f, const char *path, vx_err *e)
{
	struct stat st;
	int fd, rc;

	memset(f, 0, sizeof *f);
	if (strcmp(path, "-") == 0) {
		rc = load_fd(f, STDIN_FILENO, "<stdin>", e);
		if (rc == 0 && f->n == 0) {
			vx_imp_file_free(f);
			return vx_err_set(e, VX_ENOINPUT, "<stdin>: empty input");
		}
		return rc;
	}
	if ((fd = open(path, O_RDONLY)) < 0)
		return vx_err_set(e, VX_ENOINPUT, "%s: %s", path, strerror(errno));
	if (fstat(fd, &st) != 0) {
		int err = errno;

		close(fd);
		return vx_err_set(e, VX_EIO, "%s: %s", path, strerror(err));
	}
	if (S_ISDIR(st.st_mode)) {
		close(fd);
		return vx_err_set(e, VX_ENOINPUT, "%s: is a directory", path);
	}
	if (S_ISREG(st.st_mode) && st.st_size > 0 &&
	    (uint64_t)st.st_size <= SIZE_MAX) {
		void *m = mmap(NULL, (size_t)st.st_size, PROT_READ, MAP_PRIVATE,
		    fd, 0);

		if (m != MAP_FAILED) {
			close(fd);
			madvise(m, (size_t)st.st_size, MADV_SEQUENTIAL);
			f->p = m;
			f->n = (size_t)st.st_size;
			f->mapped = 1;
			return 0;
		}
	}
	rc = load_fd(f, fd, path, e);
	close(fd);
	if (rc == 0 && f->n == 0) {
		vx_imp_file_free(f);
		return vx_err_set(e, VX_ENOINPUT, "%s: empty file", path);
	}
	return rc;
}

void
vx_imp_file_free(vx_imp_file *f)
{
	if (f->mapped)
		munmap(f->p, f->n);
	else
		free(f->p);
	memset(f, 0, sizeof *f);
}

int
vx_imp_open(vx_imp_in *in, const char *path, vx_err *e)
{
	const unsigned char *p;
	struct stat st;
	size_t avail;
	int rc, fl;

	memset(in, 0, sizeof *in);
	in->fd = -1;
	if (strcmp(path, "-") == 0) {
		if (fstat(STDIN_FILENO, &st) == 0 && S_ISREG(st.st_mode))
			goto whole;      /* a file on stdin: its size is known */
		in->fd = STDIN_FILENO;
		path = "<stdin>";
	} else {
		/* no wait for a FIFO's writer (none: an empty input) */
		if ((in->fd = open(path, O_RDONLY | O_NONBLOCK)) < 0)
			return vx_err_set(e, VX_ENOINPUT, "%s: %s", path,
			    strerror(errno));
		in->own_fd = 1;
		if (fstat(in->fd, &st) != 0) {
			rc = vx_err_set(e, VX_EIO, "%s: %s", path, strerror(errno));
			goto fail;
		}
		if (S_ISDIR(st.st_mode)) {
			rc = vx_err_set(e, VX_ENOINPUT, "%s: is a directory", path);
			goto fail;
		}
		if (S_ISREG(st.st_mode)) {
			close(in->fd);
			in->fd = -1;
			in->own_fd = 0;
			goto whole;
		}
		if ((fl = fcntl(in->fd, F_GETFL)) == -1 ||
		    fcntl(in->fd, F_SETFL, fl & ~O_NONBLOCK) == -1) {
			rc = vx_err_set(e, VX_EIO, "%s: %s", path, strerror(errno));
			goto fail;
		}
	}
	in->stream = 1;
	vx_imp_src_fd(&in->raw, in->fd);
	if ((rc = vx_imp_peek(&in->raw, 3, &p, &avail, e)) != 0) {
		vx_err_push(e, "%s", path);
		goto fail;
	}
	if (avail == 0) {
		rc = vx_err_set(e, VX_ENOINPUT, "%s: empty %s", path,
		    in->own_fd ? "file" : "input");
		goto fail;
	}
	in->top = &in->raw;
	if (vx_imp_is_gzip(p, avail)) {
		if ((rc = vx_imp_src_gzip(&in->gz, &in->raw, e)) != 0)
			goto fail;
		in->top = &in->gz;
	}
	return 0;
whole:
	if ((rc = vx_imp_file_load(&in->f, path, e)) != 0)
		return rc;
	vx_imp_src_mem(&in->raw, in->f.p, in->f.n);
	in->top = &in->raw;
	if (vx_imp_is_gzip(in->f.p, in->f.n)) {
		if ((rc = vx_imp_src_gzip(&in->gz, &in->raw, e)) != 0) {
			vx_imp_file_free(&in->f);
			return rc;
		}
		in->top = &in->gz;
	}
	return 0;
fail:
	vx_imp_close(in);
	return rc;
}

void
vx_imp_close(vx_imp_in *in)
{
	if (in->top == &in->gz)
		vx_imp_src_close(&in->gz);
	vx_imp_src_close(&in->raw);
	if (in->own_fd && in->fd >= 0)
		close(in->fd);
	vx_imp_file_free(&in->f);
	memset(in, 0, sizeof *in);
	in->fd = -1;
}

int
vx_imp_slurp(vx_imp_src *s, uint64_t max, unsigned char **out, size_t *n,
    vx_err *e)
{
	size_t cap = 0, got;
	unsigned char *p = NULL, *q;
	int rc;

	*out = NULL;
	*n = 0;
	for (;;) {
		if (*n == cap) {
			size_t nc = cap ? 2 * cap : (size_t)1 << 20;

			if (nc > max + 1)
				nc = (size_t)max + 1;
			if (nc <= cap) {
				free(p);
				return vx_err_set(e, VX_EDATA, "more than %llu bytes "
				    "(the most read from a pipe or device when the "
				    "header names no size)", (unsigned long long)max);
			}
			if ((q = realloc(p, nc)) == NULL) {
				free(p);
				return vx_err_set(e, VX_ENOMEM, "out of memory after "
				    "%zu bytes", *n);
			}
			p = q;
			cap = nc;
		}
		if ((rc = vx_imp_read(s, p + *n, cap - *n, &got, e)) != 0) {
			free(p);
			return rc;
		}
		*n += got;
		if (got == 0)
			break;
	}
	*out = p;
	return 0;
}

void
vx_imp_stem(const char *path, char *out, size_t cap)
{
	const char *b = strrchr(path, '/');
	size_t k;

	b = b ? b + 1 : path;
	for (k = 0; b[k] && b[k] != '.' && k + 1 < cap; k++)
		out[k] = b[k];
	out[k] = '\0';
}
