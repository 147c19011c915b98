#!/bin/sh
# tests/run.sh: run every unit test binary and every command-line test script;
# each speaks TAP ("ok N - name" / "not ok N - name").  Prints a summary per
# file and ends with the line "N passed, N failed".
#   VX_BIN       directory of the programs under test (default bin)
#   VX_UNIT_DIR  directory of the unit test binaries (default build/tests)
#   VX_ONLY      "unit" or "cli" to run just one kind
#   VX_FILTER    run only files whose name contains this string
#   VX_TEST_TIMEOUT  seconds a file may run (default 900; where timeout(1)
#                is there): past it, the file counts as failed, so a hang
#                (a walk that never ends) fails instead of stalling the run
set -u
: "${VX_BIN:=bin}" "${VX_UNIT_DIR:=build/tests}" "${VX_ONLY:=}" "${VX_FILTER:=}"
: "${VX_TEST_TIMEOUT:=900}"
VX_BIN=$(cd "$VX_BIN" && pwd); export VX_BIN
CMOCKA_MESSAGE_OUTPUT=TAP; export CMOCKA_MESSAGE_OUTPUT
top=$(pwd)
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT INT TERM
pass=0; fail=0; failed_files=""
lim=""
if command -v timeout >/dev/null 2>&1; then lim="timeout $VX_TEST_TIMEOUT"; fi

run_one() { # name, command...
	name=$1; shift
	case "$name" in *"$VX_FILTER"*) ;; *) return ;; esac
	log="$tmp/log"
	$lim "$@" >"$log" 2>&1; rc=$?
	note=""
	if [ -n "$lim" ] && [ "$rc" -eq 124 ]; then
		note=", timed out after $VX_TEST_TIMEOUT s"
	fi
	# cmocka writes a skipped test as "not ok N # SKIP name": a skip
	p=$(grep -c '^ok ' "$log"); f=$(grep -v '^not ok [0-9]* # SKIP' "$log" | grep -c '^not ok ')
	s=$(grep -c '^not ok [0-9]* # SKIP' "$log")
	if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; fi
	pass=$((pass + p)); fail=$((fail + f))
	if [ "$f" -gt 0 ]; then
		failed_files="$failed_files $name"
		printf '%-36s %4d passed, %d FAILED (exit %d%s)\n' "$name" "$p" \
		    "$f" "$rc" "$note"
		grep -v '^ok ' "$log" | sed 's/^/    /' | head -40
	elif [ "$s" -gt 0 ]; then
		printf '%-36s %4d passed, %d skipped:\n' "$name" "$p" "$s"
		grep '^# SKIP' "$log" | sort -u | sed 's/^/    /'
	else
		printf '%-36s %4d passed\n' "$name" "$p"
	fi
}

if [ "$VX_ONLY" != cli ]; then
	for t in "$VX_UNIT_DIR"/test_*; do
		[ -x "$t" ] || continue
		run_one "unit/$(basename "$t")" "$t"
	done
fi
if [ "$VX_ONLY" != unit ]; then
	for t in tests/cli/test_*.sh; do
		[ -e "$t" ] || continue
		run_one "cli/$(basename "$t" .sh)" sh "$t"
	done
fi
[ -n "$failed_files" ] && echo "failed:$failed_files"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
