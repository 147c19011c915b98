#!/bin/sh
# test_pipeline.sh: real pipelines through vread, vinfo and vwrite: the ch2
# MRI head (Debian mricron-data) and a synthetic f32 field; vread -> vwrite
# -> vread must give back the very same VOLM payload, raw and gzip NRRD;
# Teem agrees with vinfo on the range.
. tests/cli/lib.sh
# Debian's python3 (what CI has), not a version manager's slower shim
PY=python3; [ -x /usr/bin/python3 ] && PY=/usr/bin/python3
MK="$PY tests/cli/mkstream.py"
CH2=/usr/share/mricron/templates/ch2.nii.gz
# vol JSONFILE EXPR: evaluate EXPR over the first volume v of a vinfo --json
vol() {
	$PY -c "import json,sys
v = [c['volume'] for c in json.load(open(sys.argv[1]))['chunks'] if 'volume' in c][0]
print($2)" "$1"
}

if [ ! -x "$VX_BIN/vread" ]; then
	skip "pipelines" "vread is not built yet"
	done_testing
	exit
fi

# payload STREAM: the payload bytes of its first VOLM chunk, cut out with
# the offset and length vinfo --chunks reports
payload() {
	set -- "$1" $(vinfo --chunks "$1" |
	    sed -n 's/^chunk [0-9]*: VOLM at \([0-9]*\), length \([0-9]*\),.*/\1 \2/p' | head -1)
	tail -c +$(($2 + 13)) "$1" | head -c "$3"
}

# roundtrip NAME STREAM: export STREAM to raw and gzip NRRD, read both back
# with vread, and compare the VOLM payloads byte for byte with the original
# (same header text, same samples).  Leaves $T/rt-raw.nrrd behind.
roundtrip() {
	payload "$2" >"$T/orig.payload"
	for enc in raw gzip; do
		opt=; [ $enc = gzip ] && opt=--gzip
		if ! vwrite $opt -o "$T/rt-$enc.nrrd" "$2" 2>"$T/rt.err" ||
		    ! vread "$T/rt-$enc.nrrd" >"$T/rt.vx" 2>>"$T/rt.err"; then
			not_ok "$1: $enc NRRD round trip" "$(cat "$T/rt.err")"
			continue
		fi
		payload "$T/rt.vx" >"$T/rt.payload"
		check "$1: $enc NRRD round trip, identical VOLM payload" \
		    cmp "$T/orig.payload" "$T/rt.payload"
	done
}

if [ -r "$CH2" ]; then
	vread "$CH2" >"$T/ch2.vx"
	vinfo --json "$T/ch2.vx" >"$T/ch2.json"
	check_eq "ch2: dims" "$(vol "$T/ch2.json" 'v["dims"]')" "[181, 217, 181]"
	check_eq "ch2: type" "$(vol "$T/ch2.json" 'v["type"]')" "u8"
	check_eq "ch2: range from the samples" "$(vol "$T/ch2.json" 'v["range"]')" "[0, 254]"
	check_eq "ch2: header range agrees" "$(vol "$T/ch2.json" 'v["range_agrees"]')" "True"
	check_eq "ch2: histogram counts every sample" \
	    "$(vol "$T/ch2.json" 'sum(v["histogram"]["counts"]) == v["samples"] == 181*217*181')" "True"
	check_eq "ch2: payload cut out as mkstream.py sees it" \
	    "$(payload "$T/ch2.vx" | cksum)" "$($MK payload "$T/ch2.vx" VOLM | cksum)"
	roundtrip ch2 "$T/ch2.vx"
	if command -v teem-unu >/dev/null 2>&1; then
		check_eq "ch2: unu minmax = vinfo range" \
		    "$(teem-unu minmax "$T/rt-raw.nrrd" | tr '\n' ' ')" \
		    "$(vol "$T/ch2.json" '"min: %g max: %g " % tuple(v["range"])')"
		check_eq "ch2: unu histo = vinfo histogram (16 bins)" \
		    "$(teem-unu histo -b 16 -min 0 -max 254 -i "$T/rt-raw.nrrd" -o - |
		      teem-unu save -f text -i - -o - | tr -s '\n ' '  ')" \
		    "$(vol "$T/ch2.json" '" ".join(map(str, v["histogram"]["counts"])) + " "')"
	else
		skip "ch2: unu minmax = vinfo range" "teem-unu not installed (Debian teem-apps)"
		skip "ch2: unu histo = vinfo histogram" "teem-unu not installed"
	fi
else
	skip "ch2" "$CH2 missing (Debian mricron-data)"
fi

# A synthetic f32 field with a non-trivial spacing and origin: floats and
# the geometry survive the NRRD round trip exactly.
vread --synth ml --size 33,20,17 --spacing 0.1,0.25,1.5 --origin -1.7,0.3,2 >"$T/ml.vx"
vinfo --json "$T/ml.vx" >"$T/ml.json"
check_eq "ml: f32 dims" "$(vol "$T/ml.json" 'v["type"], v["dims"]')" "f32 [33, 20, 17]"
roundtrip ml "$T/ml.vx"
# exporting twice gives the same bytes (no time stamps in the gzip member)
vwrite --gzip <"$T/ml.vx" >"$T/x1.nrrd"
vwrite --gzip <"$T/ml.vx" >"$T/x2.nrrd"
check "ml: export is deterministic" cmp "$T/x1.nrrd" "$T/x2.nrrd"
cp "$T/rt-raw.nrrd" "$T/ml.nrrd"
check_eq "ml: NRRD geometry" \
    "$(sed -n 's/^space directions: //p; s/^space origin: //p' "$T/ml.nrrd" | tr '\n' ' ')" \
    "(0.10000000000000001,0,0) (0,0.25,0) (0,0,1.5) (-1.7,0.29999999999999999,2) "
if command -v teem-unu >/dev/null 2>&1; then
	# unu prints floats with %g-like rounding: compare within 1e-6
	set -- $(teem-unu minmax "$T/ml.nrrd" | sed 's/^.*: //')
	check_close "ml: unu min = vinfo min" "$1" "$(vol "$T/ml.json" 'v["range"][0]')" 1e-6
	check_close "ml: unu max = vinfo max" "$2" "$(vol "$T/ml.json" 'v["range"][1]')" 1e-6
else
	skip "ml: unu minmax" "teem-unu not installed"
fi

# vinfo lists an unknown ancillary chunk that travels with a real volume
$MK add "$T/ml.vx" "$T/mlz.vx" zzzz "kept as is" --at 1
check_eq "unknown ancillary chunk listed" \
    "$(vinfo --chunks "$T/mlz.vx" | sed -n 's/^chunk 1: \(zzzz\) at [0-9]*, length \([0-9]*\), \(.*\)$/\1 \2 \3/p')" \
    "zzzz 10 ancillary, unknown"
vwrite <"$T/mlz.vx" >"$T/mlz.nrrd"
vwrite <"$T/ml.vx" >"$T/ml2.nrrd"
check "vwrite passes over it" cmp "$T/mlz.nrrd" "$T/ml2.nrrd"
done_testing
