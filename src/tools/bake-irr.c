/* bake-irr: bake an irradiance volume (Wyman et al. 2006, §4.1.1) into the
 * stream (src/tools/common/bakemain.c, bake-irr(1)). */
#include "bakemain.h"

int
main(int argc, char **argv)
{
	return tool_bake_main(argc, argv, 0);
}
