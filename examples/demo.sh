#!/bin/sh
# examples/demo.sh: the README's first command (`make deps demo`).
# Renders a real MRI head (Debian's mricron-data: the Colin Holmes "ch2" T1
# template, 181x217x181 u8) as a globally illuminated skin isosurface (an
# HDR environment from Debian's blender-data and a key light, shadows, one
# bounce, from an irradiance volume baked lazily for the texels the view
# reads), the same skin with local Phong shading
# and shadows, and its maximum-intensity projection, printing what each
# spent.
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
    raycast --scene examples/scenes/head-gi.scn --lazy \
        --lazy-save "$out/ch2-irr.vx" --stats --explain -o "$out/head-gi.png"
raycast --scene examples/scenes/head.scn --stats -o "$out/head.png" < "$out/ch2.vx"
mip --stats -o "$out/head-mip.png" < "$out/ch2.vx"
set +x
echo "demo: wrote $out/head-gi.png (global illumination), $out/head.png (Phong), $out/head-mip.png;"
echo "demo: $out/ch2-irr.vx keeps the baked texels for the next view or isovalue"
