#!/bin/sh
# mip_teem.sh: benchmark peer: maximum-intensity projection with teem-mrender (Debian
# teem-apps: hoover ray casting, gage probing, nrrd "max" measure), voxlux's camera.
#
# usage: mip_teem.sh [-n RUNS] [-j THREADS] [-s STEP] [-k KERNEL] VOLUME.nrrd OUT CAMERA...
#   CAMERA: --eye X Y Z --look X Y Z [--up X Y Z] (--ortho WIDTH | --fov DEG) [--size W H]
#   OUT: .nrrd (teem's 2-D double image) or .pfm (converted); STEP in world units
#   (default 1), KERNEL a teem kernel spec (default tent = trilinear).
# Prints the median over RUNS of teem's own "rendering time" (gage set-up and ray casting,
# not reading the volume), of the whole process's wall time and of its CPU time.
# VOLUME must be a NRRD with space directions and origin (voxlux's vwrite and volio.py
# tonrrd write them), so that teem's world frame is voxlux's: world = origin + index *
# spacing.  Teem reads it through a detached header adding "centers: node" where the file
# has none (without it gage samples half a voxel beyond the box).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
PYTHON=${PYTHON:-/usr/bin/python3}
runs=5 threads=1 step=1 kernel=tent
while getopts n:j:s:k: o; do
	case $o in
	n) runs=$OPTARG ;;
	j) threads=$OPTARG ;;
	s) step=$OPTARG ;;
	k) kernel=$OPTARG ;;
	*) echo "usage: mip_teem.sh [-n RUNS] [-j THREADS] [-s STEP] [-k KERNEL] VOLUME.nrrd OUT CAMERA..." >&2; exit 64 ;;
	esac
done
shift $((OPTIND - 1))
[ $# -ge 2 ] || { echo "mip_teem.sh: need VOLUME.nrrd OUT CAMERA..." >&2; exit 64; }
vol=$1 out=$2
shift 2
command -v teem-mrender >/dev/null || { echo "mip_teem.sh: teem-mrender missing (apt-get install teem-apps)" >&2; exit 69; }
cam=$("$PYTHON" "$here/camera.py" teem "$vol" "$@") || exit 64

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM
# teem reads the volume through a detached header that states node centring
"$PYTHON" "$here/volio.py" nodeheader "$vol" "$tmp/vol.nhdr" || exit 65
. "$here/teemruns.sh"
# shellcheck disable=SC2086 # $cam is a list of options
teem_runs mip_teem.sh teem-mrender -i "$tmp/vol.nhdr" -k scalar $cam -k00 "$kernel" -q val -m max \
	    -step "$step" -nt "$threads" -o "$tmp/img.nrrd"
case $out in
*.pfm) "$PYTHON" -c 'import sys; sys.path.insert(0, sys.argv[1]); import volio; volio.write_pfm(sys.argv[3], volio.read_image(sys.argv[2]))' "$here" "$tmp/img.nrrd" "$out" ;;
*) mv "$tmp/img.nrrd" "$out" ;;
esac
echo "mip_teem $out step $step kernel $kernel"
echo "render_ms $(median "$tmp/render") (teem's rendering time, median of $runs, threads $threads)"
echo "wall_ms $(median "$tmp/wall") (whole teem-mrender process, median of $runs)"
echo "cpu_ms $(median "$tmp/cpu") (its CPU time, user + system, median of $runs)"
echo "teem-mrender $cam -k00 $kernel -q val -m max -step $step -nt $threads"
