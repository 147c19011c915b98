/* tool.c: shared plumbing of the voxlux programs (see tool.h). */
#include "tool.h"

#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "vx_image.h"
#include "vx_imageio.h"
#include "vx_macro.h"
#include "vx_macroio.h"
#include "vx_scan.h"
#include "vx_scene.h"
#include "vx_tetleaf.h"
#include "vx_tonemap.h"
#include "vx_version.h"

#ifdef _OPENMP
#include <omp.h>
#include <pthread.h>
#endif

const char *tool_name = "voxlux";
static char history[8192];
static tool_out *live_out;   /* removed on failure exits */
static char notes[2048];     /* tool_note's, printed by tool_finish */
static size_t nnotes;
/* the temporary a signal handler removes (a copy: the handler reads no
 * tool_out); armed while one exists */
static char sig_tmp[4096];
static volatile sig_atomic_t sig_armed;

/* hold_fd: a closed standard descriptor fd held by /dev/null, opened so
 * that using fd still fails (EBADF), as it would closed */
static void
hold_fd(int fd, int flags)
{
	int h;

	if (fcntl(fd, F_GETFD) != -1 || errno != EBADF)
		return;
	if ((h = open("/dev/null", flags)) < 0)
		return;
	if (h != fd) {      /* the lowest free number, so fd unless a lower
	                       one was closed too (then it is held first) */
		dup2(h, fd);
		close(h);
	}
}

void
tool_init(const char *name, int argc, char **argv)
{
	size_t k;
	int i;

	hold_fd(STDIN_FILENO, O_WRONLY);
	hold_fd(STDOUT_FILENO, O_RDONLY);
	hold_fd(STDERR_FILENO, O_RDONLY);
	tool_name = name;
	opterr = 0;     /* getopt's own messages would make a second line */
	k = (size_t)snprintf(history, sizeof history, "%s %s", name, VX_VERSION);
	for (i = 1; i < argc && k < sizeof history; i++)
		k += (size_t)snprintf(history + k, sizeof history - k, " %s",
		    argv[i]);
	if (k >= sizeof history)
		memcpy(history + sizeof history - 4, "...", 4);
}

const char *
tool_history_line(void)
{
	return history;
}

void
tool_note(const char *fmt, ...)
{
	va_list ap;
	int n;

	if (nnotes >= sizeof notes - 1)
		return;
	n = snprintf(notes + nnotes, sizeof notes - nnotes, "%s: note: ",
	    tool_name);
	if (n > 0 && (size_t)n < sizeof notes - nnotes) {
		nnotes += (size_t)n;
		va_start(ap, fmt);
		n = vsnprintf(notes + nnotes, sizeof notes - nnotes, fmt, ap);
		va_end(ap);
		if (n > 0)
			nnotes += (size_t)n;
	}
	if (nnotes > sizeof notes - 2)
		nnotes = sizeof notes - 2;
	notes[nnotes++] = '\n';
	notes[nnotes] = '\0';
}

static _Noreturn void
die(int code)
{
	if (live_out != NULL)
		tool_out_abort(live_out);
	exit(code);
}

void
tool_fail(int code, const char *fmt, ...)
{
	va_list ap;

	fprintf(stderr, "%s: ", tool_name);
	va_start(ap, fmt);
	vfprintf(stderr, fmt, ap);
	va_end(ap);
	fputc('\n', stderr);
	die(code);
}

void
tool_fail_err(const vx_err *e)
{
	fprintf(stderr, "%s: %s\n", tool_name, e->msg[0] ? e->msg :
	    vx_err_name(e->code));
	die(e->code ? e->code : VX_EINTERNAL);
}

void
tool_usage_fail(const char *usage, const char *fmt, ...)
{
	va_list ap;

	/* one line, like every other error, for scripts and logs; a person
	 * at a terminal also gets the synopsis */
	fprintf(stderr, "%s: ", tool_name);
	va_start(ap, fmt);
	vfprintf(stderr, fmt, ap);
	va_end(ap);
	if (isatty(STDERR_FILENO))
		fprintf(stderr, "\nusage: %s\n", usage);
	else
		fprintf(stderr, " (see %s --help)\n", tool_name);
	die(VX_EUSAGE);
}

double
tool_parse_double(const char *opt, const char *s, double lo, double hi)
{
	double v;

	if (vx_num_f64(s, strlen(s), 0, &v) != 0)
		tool_fail(VX_EUSAGE, "%s: '%s' is not a number", opt, s);
	if (v < lo || v > hi)
		tool_fail(VX_EUSAGE, "%s: %s is out of range [%g, %g]", opt, s,
		    lo, hi);
	return v;
}

long
tool_parse_long(const char *opt, const char *s, long lo, long hi)
{
	int64_t v;

	if (vx_num_i64(s, strlen(s), INT64_MIN, INT64_MAX, &v) != 0)
		tool_fail(VX_EUSAGE, "%s: '%s' is not an integer", opt, s);
	if (v < lo || v > hi)
		tool_fail(VX_EUSAGE, "%s: %s is out of range [%ld, %ld]", opt, s,
		    lo, hi);
	return (long)v;
}

int
tool_parse_bits(const char *s)
{
	long v = tool_parse_long("--bits", s, 8, 16);

	if (v != 8 && v != 16)
		tool_fail(VX_EUSAGE, "--bits: 8 or 16");
	return (int)v;
}

void
tool_parse_doubles(const char *opt, const char *s, double *out, int n)
{
	const char *p = s;
	int i;

	for (i = 0; i < n; i++) {
		size_t w;

		while (*p == ' ' || *p == ',')
			p++;
		w = strcspn(p, " ,");
		if (vx_num_f64(p, w, 0, &out[i]) != 0)
			tool_fail(VX_EUSAGE, "%s: '%s': expected %d numbers", opt,
			    s, n);
		p += w;
	}
	while (*p == ' ')
		p++;
	if (*p != '\0')
		tool_fail(VX_EUSAGE, "%s: '%s': expected %d numbers", opt, s, n);
}

int
tool_parse_enum(const char *opt, const vx_enum *en, const char *s)
{
	vx_err e;
	int v;

	if (vx_enum_parse(en, s, &v, VX_EUSAGE, &e) != 0)
		tool_fail(e.code, "%s: %s", opt, e.msg);
	return v;
}

void
tool_opt_other(int ch, const char *usage, char **argv)
{
	const char *arg = argv[optind - 1];
	char opt[8];

	if (ch == 'h') {
		printf("usage: %s\n", usage);
		exit(tool_finish());
	}
	if (strncmp(arg, "--", 2) != 0 && optopt > 0 && optopt < 256) {
		snprintf(opt, sizeof opt, "-%c", optopt);   /* in a cluster */
		arg = opt;
	}
	if (ch == ':')
		tool_usage_fail(usage, "%s needs a value", arg);
	tool_usage_fail(usage, "unknown option '%s'", arg);
}

const char *
tool_opt_input(int argc, char **argv, const char *usage)
{
	if (argc - optind > 1)
		tool_usage_fail(usage, "at most one input");
	return optind < argc ? argv[optind] : "-";
}

/* pipe_widen: a pipe's buffer as large as an unprivileged process may make
 * it (1 MiB by default, /proc/sys/fs/pipe-max-size): a 126 MB stream then
 * crosses in 1 MiB turns instead of 64 KiB ones.  Not a pipe, or not
 * allowed: nothing changes. */
static void
pipe_widen(int fd)
{
#ifdef F_SETPIPE_SZ
	struct stat st;

	if (fstat(fd, &st) == 0 && S_ISFIFO(st.st_mode))
		(void)fcntl(fd, F_SETPIPE_SZ, 1 << 20);
#else
	(void)fd;
#endif
}

void
tool_read_stream(vx_stream *s, const char *path)
{
	FILE *f = stdin;
	vx_err e = { 0, "" };
	int rc;

	if (strcmp(path, "-") != 0) {
		if ((f = fopen(path, "rb")) == NULL)
			tool_fail(VX_ENOINPUT, "%s: %s", path, strerror(errno));
	} else if (isatty(STDIN_FILENO))
		tool_fail(VX_EUSAGE, "standard input is a terminal: pipe a "
		    "voxlux stream in (see vread(1))");
	else
		pipe_widen(STDIN_FILENO);
	rc = vx_stream_read(s, f, &e);
	if (f != stdin)
		fclose(f);
	if (rc != 0) {
		vx_err_push(&e, "%s", strcmp(path, "-") ? path : "<stdin>");
		tool_fail_err(&e);
	}
}

/* on_signal: remove the armed temporary, then die of sig as the run
 * would have without the handler (async-signal-safe calls only) */
static void
on_signal(int sig)
{
	if (sig_armed)
		unlink(sig_tmp);
	signal(sig, SIG_DFL);
	raise(sig);
}

/* catch_signals: on_signal for the signals that end a run (those the
 * caller ignored stay ignored), once; SIGXFSZ ignored: writes beyond the
 * file size limit fail with EFBIG instead, and the error path cleans up */
static void
catch_signals(void)
{
	static const int sigs[] = { SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGPIPE };
	static int done;
	struct sigaction sa, old;
	size_t i;

	if (done)
		return;
	done = 1;
	memset(&sa, 0, sizeof sa);
	sigemptyset(&sa.sa_mask);
	for (i = 0; i < sizeof sigs / sizeof sigs[0]; i++)
		sigaddset(&sa.sa_mask, sigs[i]);
	sa.sa_handler = on_signal;
	for (i = 0; i < sizeof sigs / sizeof sigs[0]; i++)
		if (sigaction(sigs[i], NULL, &old) == 0 &&
		    old.sa_handler != SIG_IGN)
			sigaction(sigs[i], &sa, NULL);
#ifdef SIGXFSZ
	signal(SIGXFSZ, SIG_IGN);
#endif
}

/* arm: the handler's copy of o's temporary (disarmed while it changes) */
static void
arm(const tool_out *o)
{
	sig_armed = 0;
	memcpy(sig_tmp, o->tmp, sizeof sig_tmp);
	sig_armed = 1;
}

void
tool_out_open(tool_out *o, const char *path)
{
	struct stat st;
	mode_t um;
	int fd;

	memset(o, 0, sizeof *o);
	if (strcmp(path, "-") == 0) {
		o->f = stdout;
		o->is_stdout = 1;
		pipe_widen(STDOUT_FILENO);
		snprintf(o->path, sizeof o->path, "<stdout>");
		return;
	}
	if (strlen(path) + 16 >= sizeof o->path)
		tool_fail(VX_EUSAGE, "%s: path too long", path);
	snprintf(o->path, sizeof o->path, "%s", path);
	if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
		if ((o->f = fopen(path, "wb")) == NULL)
			tool_fail(VX_ECANTCREAT, "%s: %s", path, strerror(errno));
		o->is_direct = 1;
		return;
	}
	snprintf(o->tmp, sizeof o->tmp, "%s.tmpXXXXXX", path);
	catch_signals();
	/* the signals blocked from mkstemp to arm: a temporary is never
	 * made unseen by the handler */
	sigset_t all, prev;
	sigfillset(&all);
	sigprocmask(SIG_BLOCK, &all, &prev);
	fd = mkstemp(o->tmp);
	if (fd >= 0)
		arm(o);
	sigprocmask(SIG_SETMASK, &prev, NULL);
	if (fd < 0)
		tool_fail(VX_ECANTCREAT, "%s: %s", path, strerror(errno));
	/* mkstemp makes the file 0600; give it the mode open(2) would */
	um = umask(0);
	umask(um);
	if (fchmod(fd, 0666 & ~um) != 0 || (o->f = fdopen(fd, "wb")) == NULL) {
		int err = errno;

		close(fd);
		unlink(o->tmp);
		sig_armed = 0;
		tool_fail(VX_ECANTCREAT, "%s: %s", path, strerror(err));
	}
	live_out = o;
}

void
tool_out_abort(tool_out *o)
{
	if (o->is_stdout || o->f == NULL)
		return;
	fclose(o->f);
	o->f = NULL;
	if (!o->is_direct) {
		unlink(o->tmp);
		sig_armed = 0;
	}
	if (live_out == o)
		live_out = NULL;
}

void
tool_out_close(tool_out *o)
{
	if (o->is_stdout) {
		if (fflush(stdout) != 0 || ferror(stdout))
			tool_fail(VX_EIO, "write <stdout>: %s", strerror(errno));
		return;
	}
	live_out = NULL;
	if (o->is_direct) {
		int bad = fflush(o->f) != 0 || ferror(o->f), err = errno;

		if (fclose(o->f) != 0 && !bad) {
			bad = 1;
			err = errno;
		}
		o->f = NULL;
		if (bad)
			tool_fail(VX_EIO, "write %s: %s", o->path, strerror(err));
		return;
	}
	if (fflush(o->f) != 0 || ferror(o->f) || fsync(fileno(o->f)) != 0) {
		int err = errno;

		tool_out_abort(o);
		tool_fail(VX_EIO, "write %s: %s", o->path, strerror(err));
	}
	if (fclose(o->f) != 0) {
		int err = errno;

		o->f = NULL;
		unlink(o->tmp);
		sig_armed = 0;
		tool_fail(VX_EIO, "write %s: %s", o->path, strerror(err));
	}
	o->f = NULL;
	if (rename(o->tmp, o->path) != 0) {
		int err = errno;

		unlink(o->tmp);
		sig_armed = 0;
		tool_fail(VX_ECANTCREAT, "%s: %s", o->path, strerror(err));
	}
	/* disarmed after the rename: a signal before it still removes the
	 * temporary; one after finds it gone */
	sig_armed = 0;
}

void
tool_write_stream(vx_stream *s, const char *path)
{
	vx_err e = { 0, "" };
	tool_out o;

	if (vx_stream_history_add(s, history, &e) != 0)
		tool_fail_err(&e);
	tool_out_open(&o, path);
	if (vx_stream_write(s, o.f, &e) != 0) {
		tool_out_abort(&o);
		vx_err_push(&e, "%s", o.path);
		tool_fail_err(&e);
	}
	tool_out_close(&o);
}

int
tool_finish(void)
{
	if (nnotes > 0) {
		fputs(notes, stderr);
		nnotes = 0;
	}
	if (fflush(stdout) != 0 || ferror(stdout))
		tool_fail(VX_EIO, "write <stdout>: %s", strerror(errno));
	if (fclose(stdout) != 0)
		tool_fail(VX_EIO, "write <stdout>: %s", strerror(errno));
	return 0;
}

#ifdef _OPENMP
/* The thread probe: threads that wait until released, so that all exist
 * at once, as OpenMP's team will. */
typedef struct probe {
	pthread_mutex_t mu;
	pthread_cond_t cv;
	int go;
} probe;

static void *
probe_wait(void *arg)
{
	probe *p = arg;

	pthread_mutex_lock(&p->mu);
	while (!p->go)
		pthread_cond_wait(&p->cv, &p->mu);
	pthread_mutex_unlock(&p->mu);
	return NULL;
}

/* stack_size: OMP_STACKSIZE (or GOMP_STACKSIZE) as OpenMP reads it: a
 * number with an optional B, K, M or G (K when none); 0 when unset or
 * not understood (the default stack then, as OpenMP's) */
static size_t
stack_size(void)
{
	const char *s = getenv("OMP_STACKSIZE");
	unsigned long long v, mul = 1024;
	char *end;

	if (s == NULL && (s = getenv("GOMP_STACKSIZE")) == NULL)
		return 0;
	errno = 0;
	v = strtoull(s, &end, 10);
	if (end == s || errno != 0)
		return 0;
	while (*end == ' ')
		end++;
	switch (*end) {
	case 'b': case 'B': mul = 1; end++; break;
	case 'k': case 'K': mul = 1024; end++; break;
	case 'm': case 'M': mul = 1024 * 1024; end++; break;
	case 'g': case 'G': mul = 1024ull * 1024 * 1024; end++; break;
	}
	if (*end != '\0' || v > SIZE_MAX / mul)
		return 0;
	return (size_t)(v * mul);
}

/* probe_threads: how many of want threads (the caller's included) can
 * exist at once: want - 1 are made with OpenMP's stack size and released;
 * *err the first failure's error number */
static int
probe_threads(int want, int *err)
{
	pthread_t *th;
	pthread_attr_t at;
	probe p;
	size_t ss = stack_size();
	int n = 1, i;

	*err = 0;
	if (want <= 1)
		return want < 1 ? 1 : want;
	if ((th = malloc((size_t)(want - 1) * sizeof *th)) == NULL) {
		*err = ENOMEM;
		return 1;
	}
	pthread_mutex_init(&p.mu, NULL);
	pthread_cond_init(&p.cv, NULL);
	p.go = 0;
	pthread_attr_init(&at);
	if (ss > 0)
		pthread_attr_setstacksize(&at, ss);
	for (i = 0; i < want - 1; i++) {
		if ((*err = pthread_create(&th[i], &at, probe_wait, &p)) != 0)
			break;
		n++;
	}
	pthread_mutex_lock(&p.mu);
	p.go = 1;
	pthread_cond_broadcast(&p.cv);
	pthread_mutex_unlock(&p.mu);
	for (i = 0; i < n - 1; i++)
		pthread_join(th[i], NULL);
	pthread_attr_destroy(&at);
	pthread_cond_destroy(&p.cv);
	pthread_mutex_destroy(&p.mu);
	free(th);
	return n;
}
#endif

int
tool_threads(long j)
{
#ifdef _OPENMP
	int want = j <= 0 ? omp_get_num_procs() : (int)j, n, err;

	n = probe_threads(want, &err);
	if (n < want && j > 0)
		tool_fail(VX_ENOMEM, "-j %ld: cannot start %ld threads: %s", j,
		    j, strerror(err));
	/* every parallel region of the run, not only those given n: -j N
	 * bounds the threads (a batch scheduler granted N cores) */
	omp_set_num_threads(n);
	/* OpenMP's team made now, while the probe's stacks are free: later
	 * regions of at most n threads take it as it is */
#pragma omp parallel num_threads(n)
	{
		(void)0;
	}
	return n;
#else
	(void)j;
	return 1;
#endif
}

int
tool_scene_opt(tool_scene_opts *so, int c, const char *val,
    const char *usage)
{
	static const char *const names[] = { "set", "iso", "size", "view",
	    "fov", "light", "lights", "effects", "background" };

	if (c == TOOL_O_SCENE) {
		so->file = val;
		return 1;
	}
	if (c < TOOL_O_SET || c > TOOL_O_BG)
		return 0;
	if (so->n == TOOL_SCENE_MAXSET)
		tool_usage_fail(usage, "more than %d scene options",
		    TOOL_SCENE_MAXSET);
	so->name[so->n] = names[c - TOOL_O_SET];
	so->val[so->n++] = val;
	return 1;
}

void
tool_scene_opts_load(vx_scene *s, const tool_scene_opts *so,
    const vx_stream *st)
{
	tool_scene_load(s, so->file, st, so->n, so->name, so->val);
}

/* scene_paths: a relative file name in a scene file names a file beside
 * the scene: prefix the scene's directory (formats/scene.md). */
static void
scene_paths(vx_scene *s, const char *file)
{
	const char *slash = strrchr(file, '/');
	size_t dl = slash != NULL ? (size_t)(slash - file) + 1 : 0;

	if (dl == 0)
		return;
	for (int k = 0; k < s->nlight; k++) {
		vx_light *l = &s->light[k];
		size_t fl = strlen(l->file);

		if (l->type != VX_LIGHT_ENVIRONMENT || l->file[0] == '/')
			continue;
		if (dl + fl >= sizeof l->file)
			tool_fail(VX_EDATA, "%s: light %d: file name longer than "
			    "%zu bytes with the scene's directory", file, k + 1,
			    sizeof l->file - 1);
		memmove(l->file + dl, l->file, fl + 1);
		memcpy(l->file, file, dl);
	}
	if (s->tf_file[0] != '\0' && s->tf_file[0] != '/') {
		size_t fl = strlen(s->tf_file);

		if (dl + fl >= sizeof s->tf_file)
			tool_fail(VX_EDATA, "%s: transfer file: name longer than "
			    "%zu bytes with the scene's directory", file,
			    sizeof s->tf_file - 1);
		memmove(s->tf_file + dl, s->tf_file, fl + 1);
		memcpy(s->tf_file, file, dl);
	}
}

void
tool_scene_load(vx_scene *s, const char *file, const vx_stream *st, int n,
    const char *const *names, const char *const *vals)
{
	vx_err e = { 0, "" };
	int i;

	if (file != NULL) {
		FILE *f = fopen(file, "r");

		if (f == NULL)
			tool_fail(VX_ENOINPUT, "%s: cannot open scene: %s", file,
			    strerror(errno));
		if (vx_scene_read(s, f, &e) != 0) {
			fclose(f);
			vx_err_push(&e, "%s", file);
			tool_fail_err(&e);
		}
		fclose(f);
		scene_paths(s, file);
	} else if (vx_scene_from_stream(s, st, NULL, &e) != 0)
		tool_fail_err(&e);
	for (i = 0; i < n; i++)
		if (vx_scene_option(s, names[i], vals[i], &e) != 0)
			tool_fail_err(&e);
}

void
tool_write_pfm(const char *path, const vx_image *img)
{
	vx_err e = { 0, "" };
	tool_out out;

	tool_out_open(&out, path);
	if (vx_pfm_write(img, out.f, &e) != 0) {
		tool_out_abort(&out);
		vx_err_push(&e, "%s", path);
		tool_fail_err(&e);
	}
	tool_out_close(&out);
}

void
tool_stream_keep(vx_stream *out, vx_stream *in, const char *const *drop)
{
	vx_err e = { 0, "" };
	size_t i;
	int k;

	for (i = 0; i < in->n; i++) {
		vx_chunk c;

		for (k = 0; drop[k] != NULL; k++)
			if (memcmp(in->chunk[i].type, drop[k], 4) == 0)
				break;
		if (drop[k] != NULL)
			continue;
		c = in->chunk[i];
		memset(&in->chunk[i], 0, sizeof in->chunk[i]);
		if (vx_stream_append(out, &c, &e) != 0)
			tool_fail_err(&e);
	}
}

/* build_note: the note that a hierarchy (what, of `name`) is built now */
static void
build_note(int status, const char *what, const char *name, const char *them)
{
	tool_note("%s %s '%s'; built %s (run macrocell(1) in the pipeline to "
	    "keep %s)", status == VX_MACRO_STALE ? "stale" : "no", what, name,
	    them, them);
}

void
tool_macro_load(vx_macro *m, const vx_stream *st, const vx_grid *g,
    long src, int nthr, int quiet)
{
	int sizes[VX_MACRO_MAXLEV][3], nlev, status;
	vx_err e = { 0, "" };

	vx_macro_init(m);
	if (vx_macro_from_stream(m, st, g, src, &status, NULL, &e) != 0)
		tool_fail_err(&e);
	if (status == VX_MACRO_LOADED)
		return;
	nlev = vx_macro_default_sizes(g->type, VX_MACRO_DEFAULT_LEVELS, sizes);
	if (!quiet)
		build_note(status, "macrocells for", g->name, "them");
	if (vx_macro_build(m, g, nlev, (const int (*)[3])sizes, nthr, &e) != 0)
		tool_fail_err(&e);
}

void
tool_tetleaf_load(vx_tetleaf *lg, const vx_stream *st, const vx_tetmesh *mesh,
    int nlev, int nthr, int quiet, int dry)
{
	int sizes[VX_MACRO_MAXLEV][3], status = VX_MACRO_ABSENT;
	vx_err e = { 0, "" };

	vx_tetleaf_init(lg);
	if (nlev > 0 && vx_tetleaf_from_stream(lg, st, mesh, &status, NULL,
	    &e) != 0)
		tool_fail_err(&e);
	if (status == VX_MACRO_LOADED)
		return;
	if (nlev > 0)
		vx_macro_default_sizes(VX_F32, nlev, sizes);
	if (!quiet && nlev > 0)
		build_note(status, "leaf grid for mesh", mesh->name, "it");
	if (!dry && vx_tetleaf_build_levels(lg, mesh, 1, 0, nlev,
	    (const int (*)[3])sizes, nthr, &e) != 0)
		tool_fail_err(&e);
}

void
tool_write_png(const char *path, const vx_image *img, int bits, double gamma,
    const char *hist, size_t hlen, const vx_text *extra, size_t nextra)
{
	vx_text text[8];
	vx_err e = { 0, "" };
	size_t n = 0, line = strlen(history);
	char *all;
	tool_out o;

	if (nextra > sizeof text / sizeof text[0] - 2)
		tool_fail(VX_EINTERNAL, "too many PNG text chunks");
	if (strcmp(path, "-") == 0 && isatty(STDOUT_FILENO))
		tool_fail(VX_EUSAGE, "standard output is a terminal: give -o "
		    "FILE or redirect");
	if (hist == NULL)
		hlen = 0;
	if ((all = malloc(hlen + line + 1)) == NULL)
		tool_fail(VX_ENOMEM, "out of memory");
	memcpy(all, hist != NULL ? hist : "", hlen);
	memcpy(all + hlen, history, line + 1);
	text[n].key = "Software";
	text[n++].value = "voxlux " VX_VERSION;
	text[n].key = "voxlux-history";
	text[n++].value = all;
	for (size_t k = 0; k < nextra; k++)
		text[n++] = extra[k];
	tool_out_open(&o, path);
	if (vx_image_png_write_gamma(img, o.f, bits, gamma, text, n, &e) != 0) {
		tool_out_abort(&o);
		free(all);
		vx_err_push(&e, "%s", o.path);
		tool_fail_err(&e);
	}
	tool_out_close(&o);
	free(all);
}

void
tool_write_png_radiance(const char *path, const vx_image *color,
    double exposure, const double bg[3], int bits, const vx_stream *in)
{
	vx_tonemap_opts tm;
	vx_image disp;
	vx_err e = { 0, "" };
	const char *h;
	size_t hl = 0;

	vx_tonemap_defaults(&tm);
	tm.exposure = exposure;
	tm.flatten = 1;
	memcpy(tm.background, bg, sizeof tm.background);
	if (vx_tonemap_image(&disp, color, &tm, NULL, &e) != 0)
		tool_fail_err(&e);
	h = in != NULL ? vx_stream_history(in, &hl) : NULL;
	tool_write_png(path, &disp, bits, 0, h, hl, NULL, 0);
	vx_image_free(&disp);
}
