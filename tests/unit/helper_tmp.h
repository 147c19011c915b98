/* helper_tmp.h: a scratch directory for the unit tests that write files
 * (helper_tmp.c): cmocka group set-up and tear-down. */
#ifndef HELPER_TMP_H
#define HELPER_TMP_H

/* the directory while the group runs (made by helper_tmp_setup) */
extern char helper_tmpdir[64];

/* helper_tmp_setup: make a fresh /tmp/vxtestXXXXXX; -1 if it cannot. */
int helper_tmp_setup(void **state);
/* helper_tmp_teardown: remove it and all it holds; -1 if that fails. */
int helper_tmp_teardown(void **state);

#endif
