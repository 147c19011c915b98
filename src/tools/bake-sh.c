/* bake-sh: bake an SH transfer volume (Wyman et al. 2006, §4.1.2) into the
 * stream (src/tools/common/bakemain.c, bake-sh(1)). */
#include "bakemain.h"

int
main(int argc, char **argv)
{
	return tool_bake_main(argc, argv, 1);
}
