/* bakemain.h: the program behind bake-irr and bake-sh (bakemain.c). */
#ifndef BAKEMAIN_H
#define BAKEMAIN_H

/* tool_bake_main: run the baker on the command line; sh 0: bake-irr (an
 * irradiance volume, IRRV), 1: bake-sh (an SH transfer volume, SHTV).
 * Returns the exit status. */
int tool_bake_main(int argc, char **argv, int sh);

#endif
