#!/bin/sh
# tests/fuzz/mkcorpus.sh: regenerate the committed seed corpus
# tests/fuzz/corpus/NAME/ (run from the top directory after `make`).
# Stream seeds come from the library's writers (mkseed.c) and the tools;
# the other formats from mkcorpus.py (written from the specs), a few from
# the tools (vwrite, tonemap).
set -eu
out=tests/fuzz/corpus
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT INT TERM
rm -rf "$out"; mkdir -p "$out/stream" "$out/nrrd" "$out/pfm" "$out/png"
cc $(make -s print-core-inc) -D_GNU_SOURCE -fopenmp -o "$tmp/mkseed" tests/fuzz/mkseed.c \
    build/libvoxlux.a -lpng $(pkg-config --libs OpenEXR) -lstdc++ -lz -lm
"$tmp/mkseed" "$out/stream"
bin/vread --synth sphere --size 3 -z 6 -o "$out/stream/synth-zlib.vxs"
python3 tests/cli/mkstream.py volume "$out/stream/f32-bricked.vxs" --type f32 \
    --dims 3 3 2 --layout "bricked 2x2x2" --no-range
python3 tests/cli/mkstream.py image "$tmp/img.vxs" --size 3 2 3
cp "$tmp/img.vxs" "$out/stream/imag-rgb.vxs"
# malformed streams: truncated, bad CRC, unknown critical chunk
head -c 100 "$out/stream/volume-mcel.vxs" >"$out/stream/truncated.vxs"
python3 -c 'import sys; d = bytearray(open(sys.argv[1], "rb").read()); d[40] ^= 1; sys.stdout.buffer.write(d)' \
    "$out/stream/tetm.vxs" >"$out/stream/bad-crc.vxs"
python3 tests/cli/mkstream.py add "$out/stream/imag-rgb.vxs" \
    "$out/stream/unknown-critical.vxs" ZZZZ "whatever"
bin/vread --synth sphere --size 3 --split 6 | bin/macrocell -o "$out/stream/tetm-tlef.vxs"
# irradiance and SH transfer volumes of a small sphere, every store (zlib;
# one raw f16 of each kind so records can be mutated in place), and SH
# lighting turned by sh-rotate
bin/vread --synth sphere --size 8 >"$tmp/s8.vxs"
# (standard input, so the history names no scratch path)
irr() { bin/bake-irr --light sky --iso 0.5 --side high --samples 4 --scale 0.3 "$@" <"$tmp/s8.vxs" 2>/dev/null; }
shtv() { bin/bake-sh --iso 0.5 --side high --samples 4 --scale 0.3 "$@" <"$tmp/s8.vxs" 2>/dev/null; }
irr -z 9 >"$out/stream/irrv-accum.vxs"
irr -z 9 --final >"$out/stream/irrv-f32.vxs"
irr -z 9 --half >"$out/stream/irrv-f16.vxs"
irr -z 0 --half --scale 0.15 >"$out/stream/irrv-f16-raw.vxs"
shtv -z 9 --order 1 --channels 1 >"$out/stream/shtv-o1c1-accum.vxs"
shtv -z 9 --order 3 --channels 3 >"$out/stream/shtv-o3c3-accum.vxs"
shtv -z 0 --order 1 --channels 1 --scale 0.15 >"$out/stream/shtv-o1c1-accum-raw.vxs"
shtv -z 9 --order 3 --channels 3 --final >"$out/stream/shtv-o3c3-f32.vxs"
shtv -z 9 --order 3 --channels 1 --half >"$out/stream/shtv-o3c1-f16.vxs"
shtv -z 0 --order 1 --channels 3 --half --scale 0.15 >"$out/stream/shtv-o1c3-f16-raw.vxs"
bin/sh-rotate --env tests/malformed/env-good.hdr --order 3 --axis 0,0,1,30 \
    -o "$out/stream/shlc.vxs"
shtv -z 9 --order 2 --channels 1 | bin/sh-rotate --env tests/malformed/env-good.hdr \
    --order 2 --euler 10,20,30 - >"$out/stream/shtv-shlc.vxs"
bin/vread --synth torus --size 4,3,2 | bin/vwrite -o "$out/nrrd/vwrite.nrrd"
bin/vread --synth linear --size 2 | bin/vwrite --gzip -o "$out/nrrd/vwrite-gzip.nrrd"
bin/tonemap --pfm -o "$out/pfm/tonemap.pfm" "$tmp/img.vxs"
bin/tonemap -o "$out/png/tonemap8.png" "$tmp/img.vxs"
bin/tonemap --bits 16 -o "$out/png/tonemap16.png" "$tmp/img.vxs"
# volumes whose box overflows (the malformed catalog's)
cp tests/malformed/volm-extent-overflow.vxs tests/malformed/volm-extent-diagonal.vxs \
    "$out/stream/"
mkdir -p "$out/scene"
cp examples/scenes/*.scn examples/cloud/cloud.scn "$out/scene/"
python3 tests/fuzz/mkcorpus.py "$out"
du -sk "$out"
