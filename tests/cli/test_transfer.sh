#!/bin/sh
# tests/cli/test_transfer.sh: transfer-function imports through
# `vinfo --transfer` (formats/transfer.md, Imports).  One function,
# colour (1,0,.25) (0,1,.5) (.25,.5,1) and opacity 0 .5 1 at x = 0 100 200,
# written by hand as a ParaView preset, a Slicer .vp and .vp.json and a
# miter txf, and by teem's own unu (a third party's NRRD writer) as a txf:
# each reads into the same points (the oracle is that hand-written table).
# A 2-D txf written by unu becomes the table with the ranges given.
. tests/cli/lib.sh

want_color='[[0,1,0,0.25],[100,0,1,0.5],[200,0.25,0.5,1]]'
want_alpha='[[0,0],[100,0.5],[200,1]]'

cat >"$T/pv.json" <<'EOF'
[ { "ColorSpace": "RGB", "Name": "hand", "NanColor": [1, 1, 0],
    "RGBPoints": [0, 1, 0, 0.25, 100, 0, 1, 0.5, 200, 0.25, 0.5, 1],
    "Points": [0, 0, 0.5, 0, 100, 0.5, 0.5, 0, 200, 1, 0.5, 0] } ]
EOF
printf '1\n1\n0.7\n0.1\n0.2\n10\n6 0 0 100 0.5 200 1\n4 0 1 255 1\n12 0 1 0 0.25 100 0 1 0.5 200 0.25 0.5 1\n' \
    >"$T/hand.vp"
cat >"$T/hand.vp.json" <<'EOF'
{"volumeProperties": [{"components": [{
  "scalarOpacityUnitDistance": 2.5,
  "rgbTransferFunction": {"points": [
    {"x": 0, "color": [1, 0, 0.25]}, {"x": 100, "color": [0, 1, 0.5]},
    {"x": 200, "color": [0.25, 0.5, 1]}]},
  "scalarOpacity": {"points": [{"x": 0, "y": 0}, {"x": 100, "y": 0.5},
    {"x": 200, "y": 1, "midpoint": 0.5, "sharpness": 0}]}}]}]}
EOF
printf 'NRRD0004\ntype: float\ndimension: 2\nsizes: 4 3\naxis mins: nan -50\naxis maxs: nan 250\nlabels: "RGBA" "gage(v)"\nencoding: ascii\n\n1 0 0.25 0\n0 1 0.5 0.5\n0.25 0.5 1 1\n' \
    >"$T/hand.txf"

# field NAME FILE: the JSON of transfer.NAME in vinfo's output
field() {
	python3 -c 'import json, sys
print(json.dumps(json.load(open(sys.argv[2]))["transfer"][sys.argv[1]],
                 separators=(",", ":")))' "$1" "$2"
}

for f in pv.json hand.vp hand.vp.json hand.txf; do
	if vinfo --json --transfer auto "$T/$f" >"$T/$f.out" 2>"$T/err"; then
		check_eq "$f: colour" "$(field color "$T/$f.out")" "$want_color"
		check_eq "$f: opacity" "$(field opacity "$T/$f.out")" "$want_alpha"
	else
		not_ok "$f: vinfo --transfer" "$(cat "$T/err")"
		not_ok "$f: opacity"
	fi
done
check_eq "hand.vp.json: unit distance is the reference step" \
    "$(field ref_step "$T/hand.vp.json.out")" "2.5"
check_eq "hand.vp: gradient opacity" "$(field gradient "$T/hand.vp.out")" \
    '[[0,1],[255,1]]'
check_eq "standard input, format named" \
    "$(vinfo --json --transfer slicer - <"$T/hand.vp" | tr -d '\n' |
      python3 -c 'import json,sys; print(json.load(sys.stdin)["transfer"]["opacity"])')" \
    "[[0, 0], [100, 0.5], [200, 1]]"
check_eq "text listing" "$(vinfo --transfer paraview "$T/pv.json" | sed -n 3p)" \
    "color: 3 points over [0, 200]"

if command -v teem-unu >/dev/null 2>&1; then
	printf '1 0 0.25 0\n0 1 0.5 0.5\n0.25 0.5 1 1\n' >"$T/txf.txt"
	teem-unu make -i "$T/txf.txt" -t float -s 4 3 -e ascii \
	    -l RGBA "gage(scalar:v)" -o - 2>/dev/null |
	    teem-unu axinfo -i - -a 1 -mm -50 250 -o "$T/unu.txf"
	vinfo --json --transfer miter "$T/unu.txf" >"$T/unu.out" 2>"$T/err"
	check_eq "unu txf (raw floats): colour" "$(field color "$T/unu.out")" \
	    "$want_color"
	check_eq "unu txf: opacity" "$(field opacity "$T/unu.out")" "$want_alpha"
	# a 2-D txf: gm along axis 1, value along axis 2, gzip, uchar
	# samples 0, 10, ..., 230 in order: channel c's least is c * 10 and
	# its greatest 200 + c * 10, each v read as (v + 0.5) / 256
	i=0; : >"$T/t2.txt"
	while [ $i -lt 24 ]; do echo $((i * 10)) >>"$T/t2.txt"; i=$((i + 1)); done
	teem-unu make -i "$T/t2.txt" -t uchar -s 4 2 3 -e ascii \
	    -l RGBA "gage(gm)" "gage(v)" -o - 2>/dev/null |
	    teem-unu axinfo -i - -a 1 -mm 0 4 -o - |
	    teem-unu axinfo -i - -a 2 -mm 10 40 -o - |
	    teem-unu save -f nrrd -e gzip -o "$T/unu2.txf"
	vinfo --json --transfer auto "$T/unu2.txf" >"$T/unu2.out" 2>"$T/err"
	check_eq "unu 2-D txf: the table" "$(field table "$T/unu2.out")" \
	    '{"size":[3,2],"value_range":[10,40],"gradient_range":[0,4],"min":[0.001953125,0.041015625,0.080078125,0.119140625],"max":[0.783203125,0.822265625,0.861328125,0.900390625]}'
else
	skip "unu txf" "teem-unu not installed (Debian teem-apps)"
fi

expect_fail "a count larger than the points" 65 \
    "line 7 (scalar opacity): the count is 8 but 6 numbers follow it" \
    sh -c "printf '1\n1\n1\n1\n1\n1\n8 0 0 100 1 200 1\n' >'$T/bad.vp' &&
    vinfo --transfer auto '$T/bad.vp'"
done_testing
