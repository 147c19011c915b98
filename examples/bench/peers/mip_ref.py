#!/usr/bin/python3
"""Exact maximum-intensity projection of the trilinear field for orthographic views
along a grid axis, to check the peers' alignment (and their error) without voxlux.

usage: mip_ref.py VOLUME -o OUT.pfm --eye X Y Z --look X Y Z [--up X Y Z] --ortho WIDTH
                  [--size W H] [volume flags]

Why it is exact: along a ray parallel to a grid axis only one coordinate varies, so the
trilinear field is linear between two sample planes and its maximum is at a plane; the
value there is the bilinear interpolation of that slice at the ray's (u, v) position.
The result is the maximum over all slices (float64 arithmetic, stored as float32).
Rays that miss the sample lattice's box [origin, origin + (n-1) spacing] give 0; the
volume must lie in front of the eye.  View direction and up must make u and v
axis-aligned too (for example --up along another grid axis).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np  # noqa: E402
import camera  # noqa: E402
import volio  # noqa: E402


def axis_of(vec, name):
    a = int(np.argmax(np.abs(vec)))
    if abs(abs(vec[a]) - 1.0) > 1e-12:
        raise ValueError("%s = %s is not along a grid axis" % (name, vec))
    return a, (1.0 if vec[a] > 0 else -1.0)


def interp_weights(x, n):
    """For index positions x: (i0, i1, t, inside) for linear interpolation on 0..n-1."""
    inside = (x >= 0) & (x <= n - 1)
    xc = np.clip(x, 0, n - 1)
    i0 = np.minimum(np.floor(xc).astype(np.int64), max(n - 2, 0))
    i1 = np.minimum(i0 + 1, n - 1)
    return i0, i1, xc - i0, inside


def reference_mip(vol, args):
    f, u, v = camera.frame(args)
    af, _ = axis_of(f, "view direction")
    au, su = axis_of(u, "u (image right)")
    av, sv = axis_of(v, "v (image up)")
    w, h = args.size
    hw, hh = camera.half_extents(args)
    eye = np.array(args.eye, dtype=np.float64)
    lo, hi = vol.world_box()
    if (f[af] > 0 and eye[af] > lo[af]) or (f[af] < 0 and eye[af] < hi[af]):
        raise ValueError("the eye must lie outside the volume, looking at it")
    sx = 2.0 * (np.arange(w) + 0.5) / w - 1.0
    sy = 1.0 - 2.0 * (np.arange(h) + 0.5) / h
    xu = (eye[au] + su * sx * hw - vol.origin[au]) / vol.spacing[au]
    xv = (eye[av] + sv * sy * hh - vol.origin[av]) / vol.spacing[av]
    dims = vol.dims
    iu0, iu1, tu, inu = interp_weights(xu, dims[au])
    iv0, iv1, tv, inv = interp_weights(xv, dims[av])
    # numpy axis of world axis a is 2 - a; order the array [slice, v, u]
    data = np.transpose(vol.data, (2 - af, 2 - av, 2 - au))
    out = np.full((h, w), -np.inf)
    for k0 in range(0, data.shape[0], 16):
        blk = data[k0:k0 + 16].astype(np.float64)
        cu = blk[:, :, iu0] * (1 - tu) + blk[:, :, iu1] * tu          # [s, nv, w]
        cv = cu[:, iv0, :] * (1 - tv)[:, None] + cu[:, iv1, :] * tv[:, None]  # [s, h, w]
        np.maximum(out, cv.max(axis=0), out=out)
    out[~(inv[:, None] & inu[None, :])] = 0.0
    return out


def main():
    p = argparse.ArgumentParser(description="exact axis-aligned orthographic MIP")
    p.add_argument("volume")
    p.add_argument("-o", "--output", required=True)
    camera.add_camera_args(p)
    volio.add_volume_args(p)
    args = p.parse_args()
    if args.ortho is None:
        p.error("only orthographic views (--ortho)")
    try:
        vol = volio.read_volume(args.volume, args)
        volio.write_pfm(args.output, reference_mip(vol, args))
    except (OSError, ValueError) as e:
        sys.exit("mip_ref.py: %s" % e)


if __name__ == "__main__":
    main()
