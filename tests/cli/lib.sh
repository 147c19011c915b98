# tests/cli/lib.sh: TAP helpers for the command-line tests (POSIX sh).
# Source it from tests/cli/test_*.sh; "$VX_BIN" holds the programs under
# test, "$T" is a scratch directory removed at exit.  End with done_testing.
set -u
: "${VX_BIN:=bin}"
PATH="$VX_BIN:$PATH"; export PATH
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT INT TERM
_n=0; _nfail=0

ok() { _n=$((_n + 1)); echo "ok $_n - $1"; }
not_ok() {
	_n=$((_n + 1)); _nfail=$((_nfail + 1)); echo "not ok $_n - $1"
	if [ $# -gt 1 ]; then printf '%s\n' "$2" | sed 's/^/# /'; fi
}
skip() { _n=$((_n + 1)); echo "ok $_n - $1 # SKIP $2"; }

# check NAME CMD...: passes when CMD exits 0.
check() { _name=$1; shift; if "$@" >"$T/.out" 2>&1; then ok "$_name"; else not_ok "$_name" "$(head -5 "$T/.out")"; fi; }

# close A B TOL: |A - B| <= TOL (numbers as text).
close() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'; }

# check_close NAME GOT WANT TOL
check_close() {
	if close "$2" "$3" "$4"; then ok "$1"; else not_ok "$1" "got '$2', want $3 +- $4"; fi
}
# check_eq NAME GOT WANT: string equality.
check_eq() {
	if [ "$2" = "$3" ]; then ok "$1"; else not_ok "$1" "got '$2', want '$3'"; fi
}

# expect_fail NAME CODE SUBSTRING CMD...: CMD must exit with CODE and print
# exactly one line on stderr that starts with the program name and contains
# SUBSTRING; nothing may be written on stdout.
expect_fail() {
	_name=$1; _code=$2; _sub=$3; shift 3
	"$@" >"$T/.fo" 2>"$T/.fe"; _rc=$?
	_lines=$(wc -l <"$T/.fe" | tr -d ' ')
	if [ "$_rc" -eq "$_code" ] && [ "$_lines" -eq 1 ] && grep -q -- "$_sub" "$T/.fe" \
	    && [ ! -s "$T/.fo" ]; then
		ok "$_name"
	else
		not_ok "$_name" "exit $_rc (want $_code), stderr: $(head -3 "$T/.fe")"
	fi
}

# slab_scene FILE [LINE...]: the homogeneous slab of the dvr tests (an
# 8x8x40 volume of 1 seen straight down z, orthographic, 8x8 pixels; emission
# 1, no light, opacity 0.05 a voxel: coverage 1 - 0.95^39), then any LINEs
slab_scene() {
	_f=$1; shift
	{
		echo "camera orthographic eye 3.5 3.5 100 look 3.5 3.5 0 up 0 1 0 width 7"
		echo "image width 8 height 8"
		echo "light none"
		echo "ambient intensity 1"
		echo "effects none"
		echo "transfer opacity 0 0.05"
		for _l in "$@"; do echo "$_l"; done
	} > "$_f"
}
done_testing() { echo "1..$_n"; [ "$_nfail" -eq 0 ]; }
