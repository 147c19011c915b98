/* tool.h: what every voxlux program shares: error exits, option parsing
 * helpers, reading and writing the stream (with the history line), and
 * writing output files atomically (temporary file, then rename).
 * Unlike the core, these functions print and exit. */
#ifndef VX_TOOL_H
#define VX_TOOL_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "vx_enum.h"
#include "vx_err.h"
#include "vx_stream.h"

extern const char *tool_name;

/* tool_init: remember the program name and the command line (for history).
 * A standard descriptor (0, 1, 2) that the caller left closed is held by
 * /dev/null opened the other way round (write-only for 0, read-only for 1
 * and 2): files the run opens never take its number, a run that does not
 * use it succeeds (closing an unused stdout is no error), and one that
 * reads or writes it still fails with EBADF. */
void tool_init(const char *name, int argc, char **argv);

/* tool_note: a note for standard error ("name: note: ..."), kept until
 * tool_finish prints it: a run that fails prints only its error line. */
void tool_note(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* tool_fail: print "name: message" and exit with code. */
_Noreturn void tool_fail(int code, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));
/* tool_fail_err: print "name: e->msg" and exit with e->code. */
_Noreturn void tool_fail_err(const vx_err *e);
/* tool_usage_fail: print "name: message (see name --help)", exit 64: one
 * line, like every error; when stderr is a terminal, the message and then
 * the usage synopsis instead. */
_Noreturn void tool_usage_fail(const char *usage, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

/* The scene options the renderers, bakers and vscene share, by
 * vx_scene_option's names, kept in command-line order and applied after
 * the scene is loaded (tool_scene_load).  A program lists those it takes
 * in its getopt_long table with the codes TOOL_O_* and gives every option
 * its own switch does not take to tool_scene_opt first. */
enum {
	TOOL_O_SCENE = 0x4000,   /* --scene FILE */
	TOOL_O_SET, TOOL_O_ISO, TOOL_O_SIZE, TOOL_O_VIEW, TOOL_O_FOV,
	TOOL_O_LIGHT, TOOL_O_LIGHTS, TOOL_O_EFFECTS, TOOL_O_BG
};
/* Their getopt_long entries: TOOL_SCENE_LONG all of them; a program that
 * takes some lists --scene (and --iso, --background) itself beside the
 * camera's (--size, --view, --fov) or the lights' (--set, --light,
 * --lights, --effects). */
#define TOOL_SCENE_LONG_CAMERA \
	{ "size", 1, 0, TOOL_O_SIZE }, { "view", 1, 0, TOOL_O_VIEW }, \
	{ "fov", 1, 0, TOOL_O_FOV }
#define TOOL_SCENE_LONG_LIGHTS \
	{ "set", 1, 0, TOOL_O_SET }, { "light", 1, 0, TOOL_O_LIGHT }, \
	{ "lights", 1, 0, TOOL_O_LIGHTS }, { "effects", 1, 0, TOOL_O_EFFECTS }
#define TOOL_SCENE_LONG \
	{ "scene", 1, 0, TOOL_O_SCENE }, { "iso", 1, 0, TOOL_O_ISO }, \
	{ "background", 1, 0, TOOL_O_BG }, TOOL_SCENE_LONG_CAMERA, \
	TOOL_SCENE_LONG_LIGHTS
#define TOOL_SCENE_MAXSET 64
typedef struct tool_scene_opts {
	const char *file;        /* --scene, or NULL */
	int n;
	const char *name[TOOL_SCENE_MAXSET], *val[TOOL_SCENE_MAXSET];
} tool_scene_opts;

/* The options the programs share beyond the scene's: where the output
 * goes, which volume, threads, the report on standard error, and for the
 * renderers the picture's form.  A renderer or baker (raycast, mip, dvr,
 * bake-irr, bake-sh) takes the short options TOOL_RUN_SHORT and lists
 * TOOL_RUN_LONG (and TOOL_RENDER_LONG for a renderer, and any of --name,
 * --exposure, --depth, --normals, --pfm by their TOOL_O_* codes) in its
 * getopt_long table; another program (brick, macrocell, sh-rotate) lists
 * the few it takes.  Each gives every option its own switch does not take
 * to tool_run_opt, which takes only what the program's table lets
 * getopt_long return. */
enum {
	TOOL_O_STATS = 0x4100, TOOL_O_EXPLAIN, TOOL_O_HDR, TOOL_O_BITS,
	TOOL_O_EXPOSURE, TOOL_O_DEPTH, TOOL_O_NORMALS, TOOL_O_PFM, TOOL_O_NAME
};
#define TOOL_RUN_SHORT ":o:j:nhz:"
#define TOOL_RUN_LONG \
	{ "output", 1, 0, 'o' }, { "threads", 1, 0, 'j' }, \
	{ "dry-run", 0, 0, 'n' }, { "stats", 0, 0, TOOL_O_STATS }, \
	{ "explain", 0, 0, TOOL_O_EXPLAIN }, { "help", 0, 0, 'h' }
#define TOOL_RENDER_LONG \
	{ "hdr", 0, 0, TOOL_O_HDR }, { "bits", 1, 0, TOOL_O_BITS }
typedef struct tool_run_opts {
	const char *out;         /* -o, --output FILE: "-" (standard output)
	                            unless given */
	const char *name;        /* --name NAME: the volume or mesh (NULL
	                            unless given) */
	long threads;            /* -j, --threads N: 0 (all cores) unless
	                            given */
	int zlevel;              /* -z LEVEL, 0 to 9: the zlib level of the
	                            stream's images (default 1) */
	int stats, explain;      /* --stats, --explain */
	int dry;                 /* -n, --dry-run: explain, then stop */
	int hdr;                 /* --hdr: a stream of float images, not a
	                            PNG */
	int bits;                /* --bits 8|16: the PNG's (default 8) */
	double exposure;         /* --exposure STOPS, -64 to 64 (default 0) */
	const char *depth;       /* --depth FILE.pfm: the depth image */
	const char *normals;     /* --normals FILE.pfm: the normal image */
	const char *pfm;         /* --pfm FILE: the color over the background */
} tool_run_opts;

/* tool_run_opts_init: the defaults above. */
void tool_run_opts_init(tool_run_opts *r);

/* tool_run_opt: take option c (a short option of TOOL_RUN_SHORT other
 * than -h, or a TOOL_O_* code above) with value val into r; returns 0,
 * taking nothing, for any other c.  Bad values exit 64. */
int tool_run_opt(tool_run_opts *r, int c, const char *val);

/* tool_plan_print: p's text (vx_plan_format) on standard error. */
struct vx_plan;
void tool_plan_print(const struct vx_plan *p);

/* tool_render_write: a renderer's result as its options r say.  The
 * images are img[0], the picture (linear radiance, or mip's values), and
 * img[1] and img[2] (depth and normals; each NULL when not made).  First
 * --depth and --normals write img[1] and img[2] as PFMs, --pfm img[0]
 * flattened over s's background (vx_image_flatten: linear RGB).  Then with
 * --hdr the stream to r->out: the chunks of in not consumed (those whose
 * type is in drawn, a NULL-terminated list of what the picture was drawn
 * from, and every scene and image; moved from in), the scene s, then the
 * images, at -z's level; otherwise the PNG: display, its values as they
 * are with no color-space chunk, or when display is NULL img[0] made
 * display exactly as tonemap(1) would (tool_write_png_radiance, with
 * --exposure and s's background); the history from in.  Exits on error. */
struct vx_image;
struct vx_scene;
void tool_render_write(const tool_run_opts *r, vx_stream *in,
    const char *const *drawn, const struct vx_scene *s,
    const struct vx_image *const img[3], const struct vx_image *display);

/* tool_scene_opt: record scene option c (a TOOL_O_* code) with value val;
 * returns 0, recording nothing, for any other c.  More than
 * TOOL_SCENE_MAXSET options: a usage error. */
int tool_scene_opt(tool_scene_opts *so, int c, const char *val,
    const char *usage);

/* Option value parsers: exit 64 with "name: --opt: why" on bad input. */
double tool_parse_double(const char *opt, const char *s, double lo, double hi);
long tool_parse_long(const char *opt, const char *s, long lo, long hi);
/* tool_parse_bits: --bits, a PNG's bits per channel: 8 or 16. */
int tool_parse_bits(const char *s);
/* tool_parse_doubles: exactly n comma- or space-separated numbers. */
void tool_parse_doubles(const char *opt, const char *s, double *out, int n);
/* tool_parse_enum: the value s names in en; else exits 64 with "name: opt:
 * unknown WHAT 'S' (one of: ...)". */
int tool_parse_enum(const char *opt, const vx_enum *en, const char *s);

/* tool_opt_other: the getopt_long results a program leaves to every
 * program's rule: 'h' prints the usage and exits 0; ':' (a value missing,
 * with an option string that starts with ':') and any other exit 64
 * naming the option ("--size needs a value", "unknown option '-x'"). */
_Noreturn void tool_opt_other(int ch, const char *usage, char **argv);

/* tool_opt_input: the input operand after the options, "-" (standard
 * input) when there is none; a second one exits 64. */
const char *tool_opt_input(int argc, char **argv, const char *usage);

/* tool_read_stream: read a whole stream from path ("-" is stdin); exits on
 * error.  Refuses a terminal on stdin with a usage hint. */
void tool_read_stream(vx_stream *s, const char *path);

/* tool_write_stream: append this run's history line, write the stream to
 * path ("-" is stdout, otherwise atomically), exit on error. */
void tool_write_stream(vx_stream *s, const char *path);

/* tool_history_line: "name version arg1 arg2 ..." (static buffer). */
const char *tool_history_line(void);

/* Atomic output files: tool_out_open returns a FILE for path ("-": stdout;
 * an existing path that is not a regular file, such as /dev/null or a FIFO,
 * is written directly, since renaming over it would replace the node);
 * tool_out_close flushes, checks, closes and renames into place, or removes
 * the temporary and exits on error.  tool_out_abort removes the temporary.
 * While a temporary exists, SIGHUP, SIGINT, SIGQUIT, SIGTERM and SIGPIPE
 * remove it before the signal ends the run as it would have (those the
 * caller ignored stay ignored); SIGXFSZ is ignored, so that a write beyond
 * the file size limit fails with EFBIG: one line, exit 74, no temporary. */
typedef struct tool_out {
	FILE *f;
	char path[4096];
	char tmp[4096];
	int is_stdout;
	int is_direct;   /* path is not a regular file (device, FIFO): written
	                    in place, never replaced by a rename */
} tool_out;

void tool_out_open(tool_out *o, const char *path);
void tool_out_close(tool_out *o);
void tool_out_abort(tool_out *o);

/* tool_finish: print the notes (tool_note), check stdout for write errors
 * before exiting 0. */
int tool_finish(void);

/* tool_scene_load: the scene from FILE (when not NULL), else the stream's,
 * else the defaults; then the n command-line scene options (names and
 * values as vx_scene_option takes them) in order.  Exits on error. */
struct vx_scene;
void tool_scene_load(struct vx_scene *s, const char *file, const vx_stream *st,
    int n, const char *const *names, const char *const *vals);

/* tool_scene_opts_load: tool_scene_load with so's file and options. */
void tool_scene_opts_load(struct vx_scene *s, const tool_scene_opts *so,
    const vx_stream *st);

/* tool_write_pfm: write img to path as a PFM, atomically; exits on error. */
struct vx_image;
void tool_write_pfm(const char *path, const struct vx_image *img);

/* tool_stream_keep: move every chunk of in whose type is not in drop
 * (NULL-terminated) to the end of out, in order (a renderer's output keeps
 * what it did not consume).  Exits on error. */
void tool_stream_keep(vx_stream *out, vx_stream *in,
    const char *const *drop);

/* tool_macro_load: the hierarchy of volume g into m (initialized here):
 * the stream's MCEL chunk when it was built over these samples (src: the
 * index of the VOLM chunk g was decoded from, or -1; see
 * vx_macro_from_stream), else built
 * now with macrocell(1)'s default sizes and nthr threads, with a note on
 * standard error unless quiet (the note says whether the stream had none
 * or a stale one).  Exits on error. */
struct vx_grid;
struct vx_macro;
void tool_macro_load(struct vx_macro *m, const vx_stream *st,
    const struct vx_grid *g, long src, int nthr, int quiet);

/* tool_tetleaf_load: the leaf grid of tet mesh `mesh` into lg
 * (initialized here): the stream's TLEF chunk when it was built over this
 * mesh, else built now with macrocell(1)'s defaults (nlev levels above the
 * leaves: VX_MACRO_DEFAULT_LEVELS, or 0 for the leaves alone) and nthr
 * threads, with a note on standard error unless quiet (as
 * tool_macro_load).  With nlev 0 the stream's chunk is not looked at.
 * Nothing is built when dry.  Exits on error. */
struct vx_tetleaf;
struct vx_tetmesh;
void tool_tetleaf_load(struct vx_tetleaf *lg, const vx_stream *st,
    const struct vx_tetmesh *mesh, int nlev, int nthr, int quiet, int dry);

/* tool_write_png: img (display values in [0,1], encoded as gamma says,
 * vx_image_png_write_gamma: 0 sRGB, G > 0 gamma, -1 no color-space chunk)
 * as a PNG of bits 8 or 16 at path ("-": standard output, refused when it
 * is a terminal; else atomically), with the tEXt chunks Software ("voxlux
 * VERSION") and voxlux-history, the whole history: the input stream's
 * lines (hist, hlen bytes as vx_stream_history gives them; NULL: none)
 * followed by this run's; then the nextra chunks of extra.  Exits on
 * error. */
struct vx_text;
void tool_write_png(const char *path, const struct vx_image *img, int bits,
    double gamma, const char *hist, size_t hlen,
    const struct vx_text *extra, size_t nextra);

/* tool_write_png_radiance: the PNG of `color`, linear radiance (RGBA
 * premultiplied by coverage, or RGB, gray, gray+alpha), exactly as
 * tonemap(1) makes it with its defaults and --exposure `exposure`
 * --background bg: the one compositing rule of the renderers' pictures
 * (vx_tonemap.h: exposure on the color, clamp, then composited over the
 * background in display values, which exposure does not touch; sRGB).
 * History from the input stream `in` as tool_write_png.  Exits on
 * error. */
void tool_write_png_radiance(const char *path, const struct vx_image *color,
    double exposure, const double bg[3], int bits, const vx_stream *in);

/* tool_gi_setup: the global-illumination estimator (vx_gi.h) for scene s
 * over volume g and hierarchy m, with the scene's environment map (at most
 * one; read now, its content hash checked or recorded in s); exits 64
 * when the scene has no light global illumination can use (headlights
 * move with the camera), 65 or 66 for a map that cannot be read. */
struct vx_gi;
struct vx_scene;
void tool_gi_setup(struct vx_gi *gi, struct vx_scene *s,
    const struct vx_grid *g, const struct vx_macro *m);

/* tool_threads: number of threads for -j N (0: all cores), made the
 * default of every parallel region of the run (tonemapping, sample CRCs):
 * -j N bounds the run's threads, not only the frame's.  The threads are
 * started here, once (OpenMP keeps them for every later region), after a
 * probe that they can be: OpenMP's own failure to create one ends the
 * process with a bare message.  Where fewer can be made than asked, an
 * explicit -j N fails (exit 71, VX_EOSERR: "-j N: cannot start N threads:
 * why") and the default (j <= 0) takes as many as could be made (at least
 * one: the calling thread). */
int tool_threads(long j);

/* tool_scene_tf: the transfer function of scene s into tf (initialized
 * here): the scene's "transfer file" read by vx_tf_import (the format by
 * its name), then the scene's own transfer lines over it
 * (vx_tf_apply_scene), then vx_tf_check.  Exits with the import's code
 * ("transfer file NAME: why") or 65 ("transfer: why"). */
struct vx_tf;
void tool_scene_tf(struct vx_tf *tf, const struct vx_scene *s);

#endif
