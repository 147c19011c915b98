/* helper_tmp.c: the unit tests' scratch directory (helper_tmp.h). */
#include <stdio.h>
#include <stdlib.h>

#include "helper_tmp.h"

char helper_tmpdir[64];

int
helper_tmp_setup(void **state)
{
	(void)state;
	snprintf(helper_tmpdir, sizeof helper_tmpdir, "/tmp/vxtestXXXXXX");
	return mkdtemp(helper_tmpdir) == NULL ? -1 : 0;
}

int
helper_tmp_teardown(void **state)
{
	char cmd[128];

	(void)state;
	snprintf(cmd, sizeof cmd, "rm -rf '%s'", helper_tmpdir);
	return system(cmd) == 0 ? 0 : -1;
}
