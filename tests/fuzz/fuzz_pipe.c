/* fuzz_pipe.c: libFuzzer target for the readers of inputs that are not
 * regular files: the input reaches vx_import_file and
 * vx_import_volume_or_mesh through a pipe (its path /dev/fd/N), so every
 * reader runs over the descriptor source that reads only what its header
 * implies (import_src.c).  The first byte chooses the call and, for raw
 * data, the parameters (as fuzz_raw: dims from the next 6 bytes, type,
 * byte order and skip from the 8th); the rest is the file.  Inputs beyond
 * what a pipe holds at once are skipped (libFuzzer's default length is
 * far below it). */
#include <fcntl.h>
#include <unistd.h>

#include "fuzz.h"
#include "vx_import.h"
#include "vx_tetimport.h"

static void
one(int rc, vx_grid *g, vx_err *e)
{
	volatile double sink = 0;

	fuzz_err_check(rc, e);
	if (rc == 0) {
		sink += fuzz_grid_touch(g);
		vx_grid_free(g);
	}
	(void)sink;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	vx_import_opts o;
	vx_grid g;
	vx_tetmesh m;
	vx_tetimport_info info;
	vx_err e;
	char path[64];
	int fd[2], mode, is_mesh, rc;

	if (size < 1 || pipe(fd) != 0)
		return 0;
#ifdef F_SETPIPE_SZ
	(void)fcntl(fd[1], F_SETPIPE_SZ, 1 << 20);
#endif
	mode = data[0] % 3;
	data++;
	size--;
	vx_import_opts_init(&o);
	if (mode == 2) {
		if (size < 8)
			goto out;
		o.format = VX_FORMAT_RAW;
		for (int a = 0; a < 3; a++)
			o.raw.dims[a] = (int16_t)(data[2 * a] | data[2 * a + 1] << 8);
		o.raw.type = (vx_scalar)(data[6] % (VX_SCALAR_LAST + 1));
		o.raw.big_endian = data[7] & 1;
		o.raw.skip = data[7] >> 1;
		data += 8;
		size -= 8;
	}
	if (size > 0 && (write(fd[1], data, size) != (ssize_t)size))
		goto out;
	close(fd[1]);
	fd[1] = -1;
	snprintf(path, sizeof path, "/dev/fd/%d", fd[0]);
	vx_err_clear(&e);
	if (mode == 1) {
		memset(&info, 0, sizeof info);
		rc = vx_import_volume_or_mesh(&g, &m, &is_mesh, path, &o, NULL,
		    &info, &e);
		fuzz_err_check(rc, &e);
		if (rc == 0 && is_mesh) {
			volatile double sink = fuzz_tetmesh_touch(&m, 0);

			(void)sink;
			vx_tetmesh_free(&m);
		} else if (rc == 0)
			one(0, &g, &e);
	} else
		one(vx_import_file(&g, path, &o, &e), &g, &e);
out:
	if (fd[1] >= 0)
		close(fd[1]);
	close(fd[0]);
	return 0;
}
