#!/bin/sh
# tests/cli/test_malformed.sh: every case of the malformed-input catalog
# (tests/malformed/README.md) fails cleanly: the documented exit code,
# exactly one line "program: ..." on stderr containing the case's phrase
# (and for usage errors, code 64, maybe the usage line after it),
# nothing on stdout (vinfo's listing excepted where marked), no sanitizer
# report, and no output file left behind.
. tests/cli/lib.sh
dir=tests/malformed
tab=$(printf '\t')
while IFS="$tab" read -r file cmd code phrase; do
	case "$file" in '#'*|'') continue ;; esac
	set -- $cmd
	prog=$1; shift
	if [ ! -x "$VX_BIN/$prog" ]; then
		skip "$file: $prog" "no $prog"
		continue
	fi
	listing=0; stdin=/dev/null; out=""
	args=""
	for a in "$@"; do
		case "$a" in
		FILE) a=$dir/$file ;;
		'<FILE') stdin=$dir/$file; continue ;;
		NOFILE) a=$T/no-such-file ;;
		GOOD) a=$dir/good.vxs ;;
		OUT) out=$T/out.$prog; a=$out ;;
		'(listing)') listing=1; continue ;;
		esac
		args="$args $a"
	done
	rm -f "$out"
	# shellcheck disable=SC2086
	"$VX_BIN/$prog" $args <"$stdin" >"$T/o" 2>"$T/e"; rc=$?
	n=$(wc -l <"$T/e" | tr -d ' ')
	# a usage error may add the usage line
	if [ "$code" -eq 64 ] && [ "$n" -eq 2 ] && sed -n 2p "$T/e" | grep -q '^usage: '; then
		n=1
	fi
	why=""
	[ "$rc" -eq "$code" ] || why="exit $rc, want $code;"
	[ "$n" -eq 1 ] || why="$why $n lines on stderr;"
	head -1 "$T/e" | grep -q "^$prog: " || why="$why not '$prog: ...';"
	[ -z "$phrase" ] || grep -qF -- "$phrase" "$T/e" || why="$why no '$phrase';"
	[ "$listing" -eq 1 ] || [ ! -s "$T/o" ] || why="$why output on stdout;"
	if grep -qE 'Sanitizer|runtime error' "$T/e"; then why="$why sanitizer report;"; fi
	[ -z "$out" ] || [ ! -e "$out" ] || why="$why $out left behind;"
	[ -z "$out" ] || ! ls "$T"/*.tmp* >/dev/null 2>&1 || why="$why temporary left behind;"
	if [ -z "$why" ]; then
		ok "$file: $prog exits $code: $(head -1 "$T/e")"
	else
		not_ok "$file: $prog" "$why stderr: $(head -3 "$T/e")"
	fi
done <"$dir/cases"
done_testing
