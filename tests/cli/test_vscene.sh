#!/bin/sh
# test_vscene.sh: the scene rides in the stream: vscene puts it there, later
# filters keep it, raycast uses it, options change it.
. tests/cli/lib.sh
vread --synth sphere --size 24 > "$T/s.vx"
vscene --scene examples/scenes/head.scn --iso 0.6 --size 64x48 "$T/s.vx" > "$T/sc.vx"
check_eq "the scene is in the stream" "$(vinfo "$T/sc.vx" | grep -c '^chunk .*SCNE')" 1
check "brick and macrocell pass it through" sh -c "brick < '$T/sc.vx' | macrocell > '$T/scm.vx'"
check_eq "options applied: the surface" "$(vscene --print "$T/scm.vx" | grep '^surface' | cut -d' ' -f1-3)" "surface iso 0.6"
check_eq "options applied: the image" "$(vscene --print "$T/scm.vx" | grep '^image')" "image width 64 height 48"
raycast --hdr "$T/scm.vx" > "$T/r.vx" 2>/dev/null
check_eq "raycast renders the stream's scene: 64x48" "$(vinfo "$T/r.vx" | sed -n 's/^ *width: \([0-9]*\)$/\1/p' | head -1)" 64
check_eq "the stream's history records vscene" "$(vinfo "$T/scm.vx" | grep -c '^    vscene ')" 1
vscene --remove "$T/scm.vx" > "$T/nos.vx"
check_eq "--remove drops it" "$(vinfo "$T/nos.vx" | grep -c 'SCNE')" 0
expect_fail "bad --set directive: usage" 64 "sideways" vscene --set "camera sideways" "$T/s.vx"
printf "camera sideways\n" > "$T/bad.scn"
expect_fail "bad scene file: data error with its line" 65 "line 1" vscene --scene "$T/bad.scn" "$T/s.vx"
expect_fail "missing scene file" 66 "nope.scn" vscene --scene "$T/nope.scn" "$T/s.vx"
expect_fail "--remove with options: usage" 64 "remove" vscene --remove --iso 3 "$T/s.vx"
done_testing
