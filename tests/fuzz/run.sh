#!/bin/sh
# tests/fuzz/run.sh: run each libFuzzer target for FUZZ_TIME seconds over a
# scratch corpus (FUZZ_WORK/NAME, kept between runs) plus the committed
# seeds (tests/fuzz/corpus/NAME); print executions and exec/s per target.
# Exits nonzero if any target crashed (sanitizer report, leak, timeout,
# out of memory), naming the file that reproduces it.
#   usage: FUZZ_TIME=15 sh tests/fuzz/run.sh build/fuzz/fuzz_NAME...
#   FUZZ_TIME  seconds per target (default 30)
#   FUZZ_WORK  scratch corpus and logs (default build/fuzz/work)
#   FUZZ_ARGS  extra libFuzzer flags (e.g. -jobs=2, -max_len=65536)
set -u
: "${FUZZ_TIME:=30}" "${FUZZ_WORK:=build/fuzz/work}" "${FUZZ_ARGS:=}"
[ $# -gt 0 ] || { echo "usage: sh tests/fuzz/run.sh build/fuzz/fuzz_NAME..." >&2; exit 64; }
OMP_NUM_THREADS=1; export OMP_NUM_THREADS   # one thread: reproducible runs
nfail=0; failed=""; ntarget=$#
for bin in "$@"; do
	name=$(basename "$bin"); name=${name#fuzz_}
	seeds=tests/fuzz/corpus/$name
	work=$FUZZ_WORK/$name
	log=$FUZZ_WORK/$name.log
	mkdir -p "$work" "$FUZZ_WORK/crashes"
	set -- "$work"
	[ -d "$seeds" ] && set -- "$work" "$seeds"
	# shellcheck disable=SC2086
	"$bin" -max_total_time="$FUZZ_TIME" -print_final_stats=1 -timeout=10 \
	    -rss_limit_mb=2048 -artifact_prefix="$FUZZ_WORK/crashes/$name-" \
	    $FUZZ_ARGS "$@" >"$log" 2>&1
	rc=$?
	execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
	rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
	cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1)
	if [ "$rc" -eq 0 ]; then
		printf '%-8s ok    %10s execs  %7s exec/s  %s\n' "$name" \
		    "${execs:-?}" "${rate:-?}" "$cov"
	else
		nfail=$((nfail + 1)); failed="$failed $name"
		printf '%-8s CRASH (exit %d) after %s execs; log %s\n' "$name" \
		    "$rc" "${execs:-?}" "$log"
		grep -E '^==[0-9]+==ERROR|runtime error|^SUMMARY|ALARM|fuzz invariant|out-of-memory|Test unit written to' \
		    "$log" | head -8 | sed 's/^/    /'
	fi
done
if [ "$nfail" -gt 0 ]; then
	echo "fuzz: $nfail target(s) failed:$failed"
	exit 1
fi
echo "fuzz: all $ntarget targets ran clean for ${FUZZ_TIME}s each"
