#!/bin/sh
# examples/demo.sh: the README's first command (`make deps demo`).
# Renders a real MRI head (Debian's mricron-data: the Colin Holmes "ch2" T1
# template, 181x217x181 u8) as a shaded skin isosurface with shadows, and
# its maximum-intensity projection, printing what each render spent.
set -eu
bin=${VX_BIN:-bin}
head=/usr/share/mricron/templates/ch2.nii.gz
out=${VX_DEMO_OUT:-examples/out}
[ -r "$head" ] || { echo "demo: $head: missing (run: make deps)" >&2; exit 66; }
mkdir -p "$out"
PATH="$bin:$PATH"
set -x
# -o: each picture is written whole or not at all (a temporary file renamed
# into place), even if the run is cut short
vread "$head" | brick | macrocell | tee "$out/ch2.vx" |
    raycast --scene examples/scenes/head.scn --stats --explain -o "$out/head.png"
mip --stats -o "$out/head-mip.png" < "$out/ch2.vx"
set +x
echo "demo: wrote $out/head.png and $out/head-mip.png"
