#!/bin/sh
# test_install.sh: `make install` puts programs, man pages, the library, its
# headers and voxlux.pc in place, and a program built against the installed
# library with pkg-config reads a stream vread wrote.
. tests/cli/lib.sh
top=$(pwd)
case "$VX_BIN" in
"$top/bin") ;;
*) skip "make install" "only for the default build (VX_BIN=$VX_BIN)"; done_testing; exit ;;
esac
if ! command -v pkg-config >/dev/null 2>&1; then
	skip "make install" "no pkg-config"; done_testing; exit
fi
make -s install PREFIX="$T/inst" >"$T/inst.log" 2>&1
check_eq "make install exits 0" "$?" 0
for p in $(cd src/tools && ls *.c | sed "s/\.c$//"); do
	check "installed bin/$p and its man page" test -x "$T/inst/bin/$p" -a -f "$T/inst/share/man/man1/$p.1"
done
check "man5 and man7 pages" test -f "$T/inst/share/man/man5/voxlux-stream.5" -a -f "$T/inst/share/man/man7/voxlux.7"
check "library and pkg-config file" test -f "$T/inst/lib/libvoxlux.a" -a -f "$T/inst/lib/pkgconfig/voxlux.pc"
cat >"$T/dims.c" <<'EOC'
#include <stdio.h>
#include "vx_grid.h"
int
main(void)
{
	vx_stream s;
	vx_grid g;
	vx_err e = { 0, "" };

	vx_stream_init(&s);
	if (vx_stream_read(&s, stdin, &e) != 0 ||
	    vx_grid_from_stream(&g, &s, NULL, NULL, &e) != 0) {
		fprintf(stderr, "dims: %s\n", e.msg);
		return e.code;
	}
	printf("%lld %lld %lld %s\n", (long long)g.dims[0], (long long)g.dims[1],
	    (long long)g.dims[2], vx_enum_str(&vx_type_enum, g.type));
	return 0;
}
EOC
PKG_CONFIG_PATH="$T/inst/lib/pkgconfig"; export PKG_CONFIG_PATH
${CC:-cc} -o "$T/dims" "$T/dims.c" $(pkg-config --cflags --libs --static voxlux) 2>"$T/cc.log"
check_eq "a program builds against the installed library" "$?" 0
check_eq "and reads vread's stream" "$("$T/inst/bin/vread" --synth torus --size 7,5,3 | "$T/dims")" "7 5 3 f32"
make -s uninstall PREFIX="$T/inst" >/dev/null 2>&1
check "make uninstall removes programs and man pages" test ! -e "$T/inst/bin/raycast" -a ! -e "$T/inst/share/man/man1/raycast.1" -a ! -e "$T/inst/share/man/man5/voxlux-stream.5"
done_testing
