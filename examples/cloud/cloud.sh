#!/bin/sh
# examples/cloud/cloud.sh: a cloud from a coarse volume, rendered by dvr with
# the scene's perturb lines (Kniss et al. 2003, section 5, Figs. 10-13): the
# coarse shape (a 32x32x20 ellipsoid distance field with 2x2x2 macrocells),
# then the same scene without its perturbation (the macrostructure alone),
# with it (the cloud), and with the sun behind the cloud.  Run from this
# folder after `make` at the top: make -C examples/cloud
set -eu
bin=${VX_BIN:-../../bin}
mkdir -p out
PATH="$bin:$PATH"
set -x
vread --synth sphere --size 32,32,20 --spacing 0.1,0.1,0.1 \
    --origin -1.55,-1.55,-0.95 | macrocell --levels 1 --sizes 2x2x2 >out/blob.vx
dvr --scene cloud.scn --set 'perturb none' --slices 160 --light-size 160 \
    -o out/coarse.png out/blob.vx
dvr --scene cloud.scn --slices 160 --light-size 160 --stats \
    -o out/cloud.png out/blob.vx
# the sun behind the cloud: forward scattering lights its rim
dvr --scene cloud.scn --lights none \
    --light 'directional direction 0.35 -1 -0.25 color 1 0.95 0.85 intensity 1.3' \
    --slices 160 --light-size 160 --stats -o out/backlit.png out/blob.vx
set +x
echo "cloud: wrote out/coarse.png (the coarse volume), out/cloud.png (perturbed)" \
    "and out/backlit.png (lit from behind)"
