#!/bin/sh
# test_tet.sh: tetrahedral meshes through the programs: vread of VTK legacy
# unstructured grids (ASCII and BINARY) and gmsh 2.2 and 4.1 files written
# here, --split of volumes, macrocell's TLEF chunk, raycast's mesh path
# checked by numbers (the depth of an exact plane, coverage against the
# grid renderer, bit-identical pictures across threads and with or without
# the stored leaf grid), and errors with their exit codes.  Images are read
# by tests/cli/vximg.py.
. tests/cli/lib.sh
if ! command -v python3 >/dev/null 2>&1; then
	skip "tet mesh CLI tests" "python3 not installed"; done_testing; exit
fi
px() { python3 tests/cli/vximg.py "$@"; }

# The mesh: the cube [0,1]^3 with 3 points per axis, each of its 8 cells
# cut into 6 Kuhn tets (48 tets, 27 points), f = x + 2y + 3z at the points.
# Written as VTK ASCII, VTK BINARY (big-endian), gmsh 2.2 and gmsh 4.1,
# plus variants for the error cases.
python3 - "$T" <<'EOF'
import itertools, struct, sys
d = sys.argv[1]
P = [(i / 2, j / 2, k / 2) for k in range(3) for j in range(3) for i in range(3)]
F = [x + 2 * y + 3 * z for x, y, z in P]
idx = lambda i, j, k: i + 3 * (j + 3 * k)
T = []
for k, j, i in itertools.product(range(2), repeat=3):
    for perm in itertools.permutations(range(3)):
        c = [i, j, k]; tet = [idx(*c)]
        for a in perm:
            c[a] += 1; tet.append(idx(*c))
        T.append(tet)

def vtk_ascii(path, extra_cell=None):
    cells = T + ([extra_cell[1]] if extra_cell else [])
    types = [10] * len(T) + ([extra_cell[0]] if extra_cell else [])
    with open(path, "w") as f:
        f.write("# vtk DataFile Version 3.0\nkuhn cube\nASCII\nDATASET UNSTRUCTURED_GRID\n")
        f.write("POINTS %d float\n" % len(P))
        for p in P: f.write("%g %g %g\n" % p)
        f.write("CELLS %d %d\n" % (len(cells), sum(len(c) + 1 for c in cells)))
        for c in cells: f.write("%d %s\n" % (len(c), " ".join(map(str, c))))
        f.write("CELL_TYPES %d\n" % len(cells))
        for t in types: f.write("%d\n" % t)
        f.write("POINT_DATA %d\nSCALARS other float 1\nLOOKUP_TABLE default\n" % len(P))
        for v in F: f.write("%g\n" % (0.0 - v))
        f.write("SCALARS f float 1\nLOOKUP_TABLE default\n")
        for v in F: f.write("%g\n" % v)

def vtk_binary(path, cut=0):
    b = b"# vtk DataFile Version 3.0\nkuhn cube\nBINARY\nDATASET UNSTRUCTURED_GRID\n"
    b += b"POINTS %d float\n" % len(P) + b"".join(struct.pack(">3f", *p) for p in P)
    b += b"\nCELLS %d %d\n" % (len(T), 5 * len(T)) + b"".join(struct.pack(">5i", 4, *t) for t in T)
    b += b"\nCELL_TYPES %d\n" % len(T) + struct.pack(">%di" % len(T), *([10] * len(T)))
    b += b"\nPOINT_DATA %d\nSCALARS f float 1\nLOOKUP_TABLE default\n" % len(P)
    b += struct.pack(">%df" % len(F), *F) + b"\n"
    open(path, "wb").write(b[:len(b) - cut] if cut else b)

def gmsh2(path):
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(P))
        for n, p in enumerate(P): f.write("%d %g %g %g\n" % ((n + 1,) + p))
        f.write("$EndNodes\n$Elements\n%d\n" % len(T))
        for n, t in enumerate(T): f.write("%d 4 2 0 1 %s\n" % (n + 1, " ".join(str(v + 1) for v in t)))
        f.write("$EndElements\n$NodeData\n1\n\"f\"\n1\n0.0\n3\n0\n1\n%d\n" % len(P))
        for n, v in enumerate(F): f.write("%d %g\n" % (n + 1, v))
        f.write("$EndNodeData\n")

def gmsh4(path):
    with open(path, "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
        f.write("$Nodes\n1 %d 1 %d\n3 1 0 %d\n" % (len(P), len(P), len(P)))
        for n in range(len(P)): f.write("%d\n" % (n + 1))
        for p in P: f.write("%g %g %g\n" % p)
        f.write("$EndNodes\n$Elements\n1 %d 1 %d\n3 1 4 %d\n" % (len(T), len(T), len(T)))
        for n, t in enumerate(T): f.write("%d %s\n" % (n + 1, " ".join(str(v + 1) for v in t)))
        f.write("$EndElements\n$NodeData\n1\n\"f\"\n1\n0.0\n3\n0\n1\n%d\n" % len(P))
        for n, v in enumerate(F): f.write("%d %g\n" % (n + 1, v))
        f.write("$EndNodeData\n")

vtk_ascii(d + "/ka.vtk")
vtk_binary(d + "/kb.vtk")
gmsh2(d + "/k2.msh")
gmsh4(d + "/k4.msh")
vtk_ascii(d + "/hex.vtk", (12, [0, 1, 4, 3, 9, 10, 13, 12]))   # a hexahedron
vtk_ascii(d + "/tri.vtk", (5, [0, 1, 3]))                     # a triangle
vtk_binary(d + "/short.vtk", cut=60)
open(d + "/bin.msh", "w").write("$MeshFormat\n4.1 1 8\n$EndMeshFormat\n")
EOF

# ---- vread: four files, one mesh ----
for f in ka.vtk kb.vtk k2.msh k4.msh; do
	vread --name kuhn --scalar f "$T/$f" >"$T/$f.vx" 2>"$T/$f.err"
	check_eq "vread $f: exit 0, silent" "$?$(cat "$T/$f.err")" 0
	vinfo "$T/$f.vx" >"$T/$f.txt"
	check "vread $f: 27 points, 48 tets" grep -q "points: 27, tets: 48" "$T/$f.txt"
	# f = x + 2y + 3z on [0,1]^3 (oracle: the formula at the corners)
	check "vread $f: range 0 6" grep -q "range: 0 6 (recomputed)" "$T/$f.txt"
	check "vread $f: bounds" grep -q "bounds: 0 0 0 to 1 1 1" "$T/$f.txt"
done
gzip -n -c "$T/kb.vtk" >"$T/kb.vtk.gz"
vread "$T/kb.vtk.gz" >"$T/kbz.vx"
check "gzipped binary VTK, named after the file" grep -q "name: kb$" "$(vinfo "$T/kbz.vx" >"$T/kbz.txt"; echo "$T/kbz.txt")"
# the first point array unless --scalar: 'other' = -f
vread "$T/ka.vtk" | vinfo - >"$T/first.txt"
check "default scalar: the first array" grep -q "range: -6 0 (recomputed)" "$T/first.txt"
# the TETM chunk is the same whatever the file format (history aside)
body() { vinfo --json "$1" | python3 -c 'import json,sys; c=[c for c in json.load(sys.stdin)["chunks"] if c["type"]=="TETM"][0]; print(c["mesh"], c["header"])'; }
check_eq "VTK binary = VTK ASCII" "$(body "$T/kb.vtk.vx")" "$(body "$T/ka.vtk.vx")"
check_eq "gmsh 2.2 = VTK ASCII" "$(body "$T/k2.msh.vx")" "$(body "$T/ka.vtk.vx")"
check_eq "gmsh 4.1 = VTK ASCII" "$(body "$T/k4.msh.vx")" "$(body "$T/ka.vtk.vx")"
# lower-dimensional cells are skipped; other volume cells need --skip-cells
vread --scalar f "$T/tri.vtk" | vinfo - >"$T/tri.txt"
check "a triangle cell is skipped" grep -q "points: 27, tets: 48" "$T/tri.txt"
vread --scalar f --skip-cells "$T/hex.vtk" 2>"$T/hex.err" | vinfo - >"$T/hex.txt"
check "--skip-cells: the hexahedron is skipped" grep -q "points: 27, tets: 48" "$T/hex.txt"
check "--skip-cells: a note says so" grep -q "skipped 1 volume cells" "$T/hex.err"

# ---- raycast: the plane x + 2y + 3z = 3 through the Kuhn cube ----
# Orthographic from above (eye z = 5, width 1 over 65 pixels): pixel (px, py)
# looks down at x = 0.5 + (2 (px + 0.5) / 65 - 1) / 2, y likewise (rows
# downward); the plane is at z = (3 - x - 2y) / 3, so the depth is
# 5 - z (oracle: ray/plane intersection by hand).
cam="camera orthographic eye 0.5 0.5 5 look 0.5 0.5 0.5 up 0 1 0 width 1"
for f in ka.vtk k4.msh; do
	raycast --iso 3 --size 65x65 --set "$cam" --depth "$T/d.pfm" --hdr "$T/$f.vx" >"$T/p.vx" 2>/dev/null
	check_close "$f: centre depth 4.5" "$(px pfm "$T/d.pfm" 32 32 0)" 4.5 1e-6
	# pixel (10, 50): x = 0.161538, y = 0.5 - 0.5 * (101/65 - 1) = 0.223077
	check_close "$f: depth at (10,50)" "$(px pfm "$T/d.pfm" 10 50 0)" \
	    "$(awk 'BEGIN { x = 0.5 + (21 / 65 - 1) / 2; y = 0.5 - (101 / 65 - 1) / 2; printf "%.9f", 5 - (3 - x - 2 * y) / 3 }')" 1e-6
	check_eq "$f: covered" "$(px img "$T/p.vx" color 10 50 3)" 1.0
done
# the normal is the plane's, towards the eye: (1, 2, 3) / sqrt(14)
raycast --iso 3 --size 65x65 --set "$cam" --normals "$T/n.pfm" "$T/ka.vtk.vx" >/dev/null 2>&1
check_close "normal z" "$(px pfm "$T/n.pfm" 32 32 2)" 0.8017837 1e-6

# ---- macrocell: the TLEF chunk ----
macrocell --stats "$T/ka.vtk.vx" >"$T/km.vx" 2>"$T/km.err"
check "macrocell --stats: memory per tet" grep -q "B/tet" "$T/km.err"
check "macrocell --stats: build time" grep -q "us/tet" "$T/km.err"
vinfo "$T/km.vx" >"$T/km.txt"
check "vinfo: TLEF right after the mesh" grep -q "chunk 2: TLEF" "$T/km.txt"
check "vinfo: the leaf grid matches its mesh" grep -q "mesh: kuhn (matches)" "$T/km.txt"
check_eq "vinfo --json: the leaf grid and its status" "$(vinfo --json "$T/km.vx" | python3 -c 'import json,sys; c=[c for c in json.load(sys.stdin)["chunks"] if c["type"]=="TLEF"][0]["leaf_grid"]; print(c["mesh"], c["status"], c["levels"], c["entries"] > 0)')" "kuhn matches 2 True"
macrocell "$T/km.vx" >"$T/km2.vx"
check_eq "macrocell again replaces the TLEF chunk" "$(vinfo "$T/km2.vx" | grep -c TLEF)" 1
# stored or built on the fly: the same picture; a note only when built
raycast --iso 2.2,3.7 --set "surface iso 2.2 opacity 0.5" --size 50x40 --view 30,20 \
    --light "directional direction 1 1 -1 shadows on" "$T/km.vx" >"$T/a.png" 2>"$T/a.err"
raycast --iso 2.2,3.7 --set "surface iso 2.2 opacity 0.5" --size 50x40 --view 30,20 \
    --light "directional direction 1 1 -1 shadows on" "$T/ka.vtk.vx" >"$T/b.png" 2>"$T/b.err"
check_eq "stored leaf grid = built one, pixel for pixel" "$(px pngsame "$T/a.png" "$T/b.png")" same
check_eq "stored leaf grid: no note" "$(cat "$T/a.err")" ""
check "no leaf grid: a note" grep -q "note: no leaf grid for mesh 'kuhn'" "$T/b.err"
raycast --iso 2.2,3.7 --set "surface iso 2.2 opacity 0.5" --size 50x40 --view 30,20 \
    --light "directional direction 1 1 -1 shadows on" -j 1 --flat "$T/km.vx" >"$T/c.png"
check_eq "-j 1 --flat = -j N hierarchical" "$(px pngsame "$T/a.png" "$T/c.png")" same

# ---- --split: a volume as tets; the grid renderer's coverage ----
# The field |x|+|y|+|z| would be exact; a sphere shows the tolerance: the
# trilinear and piecewise-linear silhouettes lie within 0.05 pixel here,
# so at most a few outline pixels may differ (oracle: the grid renderer)
vread --synth sphere --size 16 >"$T/s.vx"
vread --synth sphere --size 16 --split 5 >"$T/s5.vx"
vread --synth sphere --size 16 --split 6 >"$T/s6.vx"
check "--split 5: 5 x 15^3 tets" grep -q "points: 4096, tets: 16875" "$(vinfo "$T/s5.vx" >"$T/s5.txt"; echo "$T/s5.txt")"
check "--split 6: 6 x 15^3 tets" grep -q "tets: 20250" "$(vinfo "$T/s6.vx" >"$T/s6.txt"; echo "$T/s6.txt")"
raycast --iso 0.6 --size 64x64 --view 30,20 --depth "$T/dg.pfm" "$T/s.vx" >/dev/null 2>&1
for s in 5 6; do
	raycast --iso 0.6 --size 64x64 --view 30,20 --depth "$T/d$s.pfm" --stats "$T/s$s.vx" >/dev/null 2>"$T/st$s.err"
	n=$(px covdiff "$T/dg.pfm" "$T/d$s.pfm")
	check "split $s: coverage of the grid, up to 4 outline pixels ($n)" test "$n" -le 4
done
check "--stats: leaves, entries, tets tested" grep -q "leaves searched .* list entries .* tets tested .* crossings" "$T/st5.err"
check "--stats: the share of tet tests" grep -q "tet tests [0-9]*%" "$T/st5.err"
raycast --iso 0.6 --explain -n "$T/s5.vx" 2>"$T/ex.err" >/dev/null
check "--explain: the mesh and its tets" grep -q "mesh 'density' (16875 tets)" "$T/ex.err"

# ---- a mesh and a volume in one stream (--add); --name picks ----
vread --synth linear --size 16 --name tex --add "$T/s5.vx" >"$T/st.vx"
vinfo "$T/st.vx" >"$T/st.txt"
check "--add: the volume joins the mesh" grep -q "chunk 2: VOLM" "$T/st.txt"
# texture on the mesh: the linear field x + 2y + 3z + 1/2 at the front
# point (0, -0.5, 0) of the sphere of radius 0.5 is -0.5, mapped by window
# -1.5..0.5 to gray 0.5; kd 1, no ambient, headlight straight on: the centre
# radiance is 0.5 * (n . l), n the facet's normal (oracle: the field's
# formula and the shading formula; facets tilt by a few degrees)
raycast --iso 0.5 --size 65x65 --set "camera perspective eye 0 -5 0 look 0 0 0 up 0 0 1 fov 30" \
    --set "ambient intensity 0" --set "surface iso 0.5 ks 0 texture tex window -1.5 0.5" \
    --hdr "$T/st.vx" >"$T/t.vx" 2>/dev/null
check_close "texture on a mesh: centre albedo from the volume" "$(px img "$T/t.vx" color 32 32 0)" 0.5 0.02
raycast --name tex --iso 0.5 --size 32x32 --stats "$T/st.vx" >/dev/null 2>"$T/tex.err"
check "--name picks the volume" grep -q "cells visited" "$T/tex.err"

# ---- errors ----
expect_fail "hexahedron without --skip-cells" 65 "hexahedron" vread --scalar f "$T/hex.vtk"
expect_fail "truncated binary VTK" 65 "kb.vtk\|short.vtk" vread "$T/short.vtk"
expect_fail "binary gmsh" 65 "binary" vread "$T/bin.msh"
expect_fail "no such point array" 65 "nosuch" vread --scalar nosuch "$T/ka.vtk"
expect_fail "--split of a mesh" 64 "tet mesh already" vread --split 5 "$T/ka.vtk"
expect_fail "--spacing of a mesh" 64 "apply to volumes" vread --spacing 1,1,1 "$T/ka.vtk"
expect_fail "--scalar with --synth" 64 "apply to tet mesh files" vread --synth sphere --scalar f
printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n01234567' >"$T/v.nrrd"
expect_fail "--scalar of a volume" 64 "apply to tet mesh files" vread --scalar f "$T/v.nrrd"
expect_fail "--split 4" 64 "--split" vread --synth sphere --split 4
expect_fail "--add: the name is taken" 64 "already has a volume or mesh named 'kuhn'" \
    vread --name kuhn --add "$T/ka.vtk.vx" "$T/k2.msh"
expect_fail "macrocell --density of a volume" 64 "apply to tet meshes" macrocell --density 2 "$T/s.vx"
expect_fail "macrocell: no such mesh" 65 "no volume or mesh named 'q'" macrocell --name q "$T/km.vx"
expect_fail "mip: a mesh is refused with a pointer to raycast" 65 "is a tet mesh: mip draws volumes" mip "$T/km.vx"
expect_fail "raycast: no such mesh" 65 "no volume or mesh named 'q'" raycast --iso 1 --name q "$T/km.vx"
# a TLEF chunk whose header lies (one entry more than the body holds; the
# CRC recomputed so that only the leaf-grid reader can tell)
python3 - "$T/km.vx" "$T/bad.vx" <<'EOF'
import struct, sys, zlib
d = open(sys.argv[1], "rb").read()
out, p = bytearray(d[:8]), 8
while p < len(d):
    t = d[p:p + 4]; n = struct.unpack("<Q", d[p + 4:p + 12])[0]; pay = d[p + 12:p + 12 + n]
    if t == b"TLEF":
        head, body = pay.split(b"\n\n", 1)
        lines = [l if not l.startswith(b"entries: ") else b"entries: %d" % (int(l[9:]) + 1)
                 for l in head.split(b"\n")]
        pay = b"\n".join(lines) + b"\n\n" + body
    out += t + struct.pack("<Q", len(pay)) + pay + struct.pack("<I", zlib.crc32(t + pay))
    p += 16 + n
open(sys.argv[2], "wb").write(out)
EOF
expect_fail "raycast: a malformed leaf grid" 65 "leaf grid" raycast --iso 1 "$T/bad.vx"
vinfo "$T/bad.vx" >"$T/bad.txt" 2>"$T/bad.err"
check_eq "vinfo: a malformed leaf grid, exit 65" "$?" 65
check "vinfo: says why" grep -q "leaf grid" "$T/bad.err"

# the catalog's TLEF (tests/malformed/make.sh): the good one is used as is;
# a stale one (mesh-crc32 not its mesh's: formats/tetmesh.md) is rebuilt
# with a note, and the picture (depth and normals, bit for bit) is the one
# without any TLEF; macrocell
# replaces a malformed TLEF of its mesh by a good one
M=tests/malformed
python3 - "$M/good-tlef.vxs" "$T/notlef.vx" <<'EOF'
import sys
sys.path.insert(0, "tests/cli")
import mkstream as m
m.write_stream(sys.argv[2], [c for c in m.read_stream(sys.argv[1]) if c[0] != "TLEF"])
EOF
for f in "$M/good-tlef.vxs" "$M/stale-tlef.vxs" "$T/notlef.vx"; do
	b=$T/$(basename "$f")
	raycast --iso 1 --size 64x48 --depth "$b.d.pfm" --normals "$b.n.pfm" \
	    -o "$b.png" "$f" 2>"$b.err"
	cat "$b.d.pfm" "$b.n.pfm" >"$b.pfm"
done
check_eq "the mesh is seen: 47 pixels of finite depth" "$(python3 -c '
import math, struct, sys
d = open(sys.argv[1], "rb").read()[-64 * 48 * 4:]
print(sum(math.isfinite(v) for v in struct.unpack("<3072f", d)))' "$T/notlef.vx.d.pfm")" 47
check_eq "catalog TLEF: loaded, no note" "$(cat "$T/good-tlef.vxs.err")" ""
check "stale TLEF: rebuilt, with a note" grep -q "^raycast: note: stale leaf grid for mesh 'mesh'" "$T/stale-tlef.vxs.err"
check_eq "stale TLEF: the picture without TLEF" "$(cksum <"$T/stale-tlef.vxs.pfm")" "$(cksum <"$T/notlef.vx.pfm")"
check_eq "good TLEF: the same picture" "$(cksum <"$T/good-tlef.vxs.pfm")" "$(cksum <"$T/notlef.vx.pfm")"
check_eq "vinfo: stale" "$(vinfo "$M/stale-tlef.vxs" | grep -c '(stale)')" 1
macrocell -o "$T/fixed.vx" "$M/tlef-nan-leaf.vxs"
check_eq "macrocell replaces a malformed TLEF" "$(vinfo "$T/fixed.vx" | grep -c -e '(matches)' -e '^chunk .*TLEF')" 2
done_testing
