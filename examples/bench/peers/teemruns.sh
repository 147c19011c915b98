# teemruns.sh: sourced by the teem peers (mip_teem.sh, dvr_miter.sh): timed runs
# of a teem renderer.  Needs $tmp (a scratch directory) and $runs.

# cpu_of FILE: CPU seconds (user + system) of all finished children in the output of the
# shell's `times` builtin, which must run in this shell (a subshell starts at zero).
cpu_of() {
	awk 'NR == 2 { split($1, u, "m"); split($2, s, "m"); sub("s", "", u[2]); sub("s", "", s[2]);
		printf "%.6f\n", u[1] * 60 + u[2] + s[1] * 60 + s[2] }' "$1"
}

# teem_runs NAME CMD...: run CMD (a teem renderer; its standard error into $tmp/log) $runs
# times, appending each run's wall seconds to $tmp/wall, its CPU seconds to $tmp/cpu and
# teem's own "rendering time" to $tmp/render; on failure the log's tail and "NAME: CMD
# failed", exit 70.
teem_runs() {
	_name=$1
	shift
	_i=0
	while [ $_i -lt "$runs" ]; do
		times >"$tmp/times0"
		_t0=$(date +%s.%N)
		if ! "$@" 2>"$tmp/log"; then
			grep -v '^ *[0-9]*/[0-9]* ' "$tmp/log" | tail -5 >&2
			echo "$_name: $1 failed" >&2
			exit 70
		fi
		_t1=$(date +%s.%N)
		times >"$tmp/times1"
		echo "$_t0 $_t1" | awk '{ printf "%.6f\n", $2 - $1 }' >>"$tmp/wall"
		echo "$(cpu_of "$tmp/times0") $(cpu_of "$tmp/times1")" |
		    awk '{ printf "%.6f\n", $2 - $1 }' >>"$tmp/cpu"
		sed -n 's/.*rendering time = \([0-9.e+-]*\) secs.*/\1/p' "$tmp/log" >>"$tmp/render"
		_i=$((_i + 1))
	done
}

# median FILE: the median of FILE's numbers (seconds) in milliseconds
median() { sort -g "$1" | awk '{ v[NR] = $1 } END { printf "%.3f", 1e3 * (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
