#!/usr/bin/python3
"""Coverage of two renderings of the same surface with the same camera: voxlux's depth
(raycast --depth: +inf where the ray misses) and a peer's gray picture (embree_render:
0 where the ray misses, |n.d| > 0 where it hits).

usage: coverage.py VOXLUX_DEPTH.pfm PEER.pfm [--diff-png OUT.png]

Prints: covered pixels of each, pixels covered by one only, that count as a fraction
of the union, and how many of those lie on an outline (a 4-neighbour is uncovered in
either picture).  --diff-png: gray 128 where both agree on a hit, white = voxlux only,
black = peer only, dark gray = both miss.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "peers"))
import numpy as np  # noqa: E402
import volio  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("depth")
    p.add_argument("peer")
    p.add_argument("--diff-png")
    a = p.parse_args()
    d = volio.read_pfm(a.depth)
    g = volio.read_pfm(a.peer)
    d = d[..., 0] if d.ndim == 3 else d
    g = g[..., 0] if g.ndim == 3 else g
    if d.shape != g.shape:
        sys.exit("coverage.py: sizes differ: %s %s" % (d.shape, g.shape))
    cv = np.isfinite(d)
    cp = g > 0
    only_v = cv & ~cp
    only_p = cp & ~cv
    diff = only_v | only_p
    both = cv & cp
    # outline: a pixel with a 4-neighbour that one of the pictures leaves uncovered
    pad = np.pad(both, 1, constant_values=False)
    inner = pad[1:-1, 1:-1] & pad[:-2, 1:-1] & pad[2:, 1:-1] & pad[1:-1, :-2] & pad[1:-1, 2:]
    edge = diff & ~inner
    union = int((cv | cp).sum())
    print("covered voxlux %d peer %d union %d" % (cv.sum(), cp.sum(), union))
    print("only_voxlux %d only_peer %d mismatch %.5f of the union, %d of them on an outline"
          % (only_v.sum(), only_p.sum(), diff.sum() / max(union, 1), edge.sum()))
    if a.diff_png:
        img = np.where(both, 0.5, np.where(only_v, 1.0, np.where(only_p, 0.0, 0.15)))
        volio.write_png_gray(a.diff_png, img.astype(np.float32), 0.0, 1.0)


if __name__ == "__main__":
    main()
