#!/bin/sh
# examples/cloud/cloud.sh: a cloud from a coarse volume, as Kniss et al.
# (2003) make theirs (section 5, Figs. 11-13): a 16^3 distance field (the
# coarse shape: a ball) resampled 6 times finer with its lookups displaced
# by fBm noise and its values modulated by turbulence (cloudnoise.c, on
# light/vx_noise.h), then bricked with its macrocell hierarchy for empty
# space skipping; and the transfer function it is meant to be seen with
# (cloud.json, a ParaView preset) as voxlux imports it.  Run from this
# folder after `make` at the top: make -C examples/cloud
set -eu
bin=${VX_BIN:-../../bin}
mkdir -p out
PATH="$bin:$PATH"
set -x
vread --synth sphere --size 16 | out/cloudnoise 6 1.5 5 0 | brick | macrocell >out/cloud.vx
vinfo --histogram 8 out/cloud.vx
vinfo --transfer auto cloud.json
set +x
echo "cloud: wrote out/cloud.vx (91^3 f32: distance from the centre, displaced and modulated)"
