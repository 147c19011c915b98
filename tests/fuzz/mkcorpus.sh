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
bin/vread --synth torus --size 4,3,2 | bin/vwrite -o "$out/nrrd/vwrite.nrrd"
bin/vread --synth linear --size 2 | bin/vwrite --gzip -o "$out/nrrd/vwrite-gzip.nrrd"
bin/tonemap --pfm -o "$out/pfm/tonemap.pfm" "$tmp/img.vxs"
bin/tonemap -o "$out/png/tonemap8.png" "$tmp/img.vxs"
bin/tonemap --bits 16 -o "$out/png/tonemap16.png" "$tmp/img.vxs"
mkdir -p "$out/scene"
cp examples/scenes/*.scn "$out/scene/"
python3 tests/fuzz/mkcorpus.py "$out"
du -sk "$out"
