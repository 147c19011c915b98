#!/bin/sh
# dvr_miter.sh: benchmark peer: direct volume rendering with teem-miter (Debian
# teem-apps: hoover ray casting, gage probing, mite's 1D transfer function),
# unshaded, voxlux's camera.
#
# usage: dvr_miter.sh [-n RUNS] [-j THREADS] [-s STEP] [-r REF] [-o OFFSET] [-t NEAR1] VOLUME.nrrd TXF.nrrd OUT.pfm CAMERA...
#   CAMERA: --eye X Y Z --look X Y Z [--up X Y Z] (--ortho WIDTH | --fov DEG) [--size W H]
#   TXF: a miter txf (dvr_tf.py txf); STEP the sample spacing and REF the opacity's
#   reference step, world units (default 1 and 1: the txf's opacity as it stands).
# Writes OUT.pfm, the colour premultiplied by the coverage (miter's R, G, B, which it
# stores divided by its alpha, times that alpha: voxlux's convention), and OUT's
# alpha beside it (OUT with .pfm replaced by .alpha.pfm).  Prints the median over RUNS of
# teem's own "rendering time" (gage set-up and rays; reading the volume and the txf
# are not in it), of the whole process's wall time and of its CPU time.
#
# Unshaded: -ss none (no gradient is measured) and -ads 1 0 0 with ambient 1 1 1, so a
# sample's colour is the txf's RGB (mite: (E - 1 + ka amb) RGB, E 1 by default).
# Threads: -nt THREADS (hoover's pthreads).  Early ray termination: a ray stops once its
# opacity reaches NEAR1 (-n1; default 0.99, miter's own default, as a user runs it; 1
# turns it off; voxlux's dvr stops at transmittance 0.001, its --cutoff).
# The volume is read through a detached header stating node centring (mip_teem.sh says
# why); camera.py teem gives the camera: the near and far planes clip to the box, and
# the near plane, where hoover takes its first sample, lies OFFSET (default STEP / 2)
# inside the box's nearest corner, so that miter samples the planes voxlux's unshaded
# dvr does (slices perpendicular to the view, k + 1/2 steps from that corner).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
PYTHON=${PYTHON:-/usr/bin/python3}
runs=5 threads=1 step=1 ref=1 offset= near1=0.99
while getopts n:j:s:r:o:t: o; do
	case $o in
	n) runs=$OPTARG ;;
	j) threads=$OPTARG ;;
	s) step=$OPTARG ;;
	r) ref=$OPTARG ;;
	o) offset=$OPTARG ;;
	t) near1=$OPTARG ;;
	*) echo "usage: dvr_miter.sh [-n RUNS] [-j THREADS] [-s STEP] [-r REF] [-o OFFSET] [-t NEAR1] VOLUME.nrrd TXF.nrrd OUT.pfm CAMERA..." >&2; exit 64 ;;
	esac
done
shift $((OPTIND - 1))
[ $# -ge 3 ] || { echo "dvr_miter.sh: need VOLUME.nrrd TXF.nrrd OUT.pfm CAMERA..." >&2; exit 64; }
vol=$1 txf=$2 out=$3
shift 3
case $out in *.pfm) ;; *) echo "dvr_miter.sh: OUT must end in .pfm" >&2; exit 64 ;; esac
command -v teem-miter >/dev/null || { echo "dvr_miter.sh: teem-miter missing (apt-get install teem-apps)" >&2; exit 69; }
cam=$("$PYTHON" "$here/camera.py" teem "$vol" --near-offset "${offset:-$(echo "$step" | awk '{ print $1 / 2 }')}" "$@") || exit 64

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM
"$PYTHON" "$here/volio.py" nodeheader "$vol" "$tmp/vol.nhdr" || exit 65
. "$here/teemruns.sh"
# shellcheck disable=SC2086 # $cam is a list of options
teem_runs dvr_miter.sh teem-miter -i "$tmp/vol.nhdr" -txf "$txf" $cam -k00 tent -ss none \
	    -ads 1 0 0 -am 1 1 1 -step "$step" -ref "$ref" -n1 "$near1" -nt "$threads" \
	    -o "$tmp/img.nrrd"
# miter's image: 5 x W x H doubles, R G B A Z per pixel, RGB divided by A
"$PYTHON" -c '
import sys
sys.path.insert(0, sys.argv[1])
import numpy as np
import volio
_, a = volio.read_nrrd_array(sys.argv[2])
a = np.nan_to_num(a.astype(np.float64))           # [row, col, RGBAZ], row 0 at the top
alpha = a[:, :, 3]
volio.write_pfm_rgb(sys.argv[3], a[:, :, :3] * alpha[:, :, None])
volio.write_pfm(sys.argv[4], alpha)
' "$here" "$tmp/img.nrrd" "$out" "${out%.pfm}.alpha.pfm"
echo "dvr_miter $out step $step ref $ref"
echo "render_ms $(median "$tmp/render") (teem's rendering time, median of $runs, threads $threads)"
echo "wall_ms $(median "$tmp/wall") (whole teem-miter process, median of $runs)"
echo "cpu_ms $(median "$tmp/cpu") (its CPU time, user + system, median of $runs)"
echo "teem-miter -txf $txf $cam -k00 tent -ss none -ads 1 0 0 -am 1 1 1 -step $step -ref $ref -n1 $near1 -nt $threads"
