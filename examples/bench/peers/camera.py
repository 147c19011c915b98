#!/usr/bin/python3
"""The benchmark camera, and its translation into each peer's own camera.

Convention: voxlux's explicit camera (src/core/data/vx_camera.h, vx_camera_ray), which
embree_render.c implements too and the README documents:
  f = unit(look - eye); u = unit(f x unit(up)) (image right); v = u x f (image up);
  (u, v, -f) is right-handed; if up is (nearly) parallel to f, up becomes z, or y when
  |f.z| >= 0.9.  Pixel (px, py), (0,0) top-left, is sampled through
  sx = 2 (px + 0.5) / W - 1,  sy = 1 - 2 (py + 0.5) / H.
  perspective (--fov DEG, vertical full angle): origin eye,
      direction unit(f + sx tan(fov/2) (W/H) u + sy tan(fov/2) v)
  orthographic (--ortho WIDTH, world units spanned by the W columns, like voxlux's
  view_width): origin eye + sx (WIDTH / 2) u + sy (WIDTH H / W / 2) v, direction f.
  Rays start at the eye (t >= 0); for the MIP peers the eye must lie outside the volume.

Command line:
  camera.py teem VOLUME.nrrd [--near-offset D] CAMERA-FLAGS
                                            print teem-mrender's (and teem-miter's)
                                            camera options (mip_teem.sh, dvr_miter.sh)
  camera.py scene [--iso V] CAMERA-FLAGS    print the voxlux scene (formats/scene.md) of the
                                            same picture: this camera and image size, black
                                            background, no ambient, the headlight, and with
                                            --iso a white Lambert surface (kd 1, ks 0), which
                                            is what embree_render draws
"""
import math
import sys

import numpy as np


def add_camera_args(p, size=(512, 512)):
    """Add --eye --look --up --fov/--ortho --size to an argparse parser."""
    p.add_argument("--eye", type=float, nargs=3, required=True, metavar=("X", "Y", "Z"))
    p.add_argument("--look", type=float, nargs=3, required=True, metavar=("X", "Y", "Z"))
    p.add_argument("--up", type=float, nargs=3, default=[0.0, 0.0, 1.0], metavar=("X", "Y", "Z"))
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--fov", type=float, metavar="DEG", help="perspective, vertical full angle")
    g.add_argument("--ortho", type=float, metavar="WIDTH",
                   help="orthographic, horizontal extent of the view in world units")
    p.add_argument("--size", type=int, nargs=2, default=list(size), metavar=("W", "H"))


def frame(args):
    """(f, u, v) unit vectors of the camera described by parsed camera args."""
    eye, look, up = (np.array(x, dtype=np.float64) for x in (args.eye, args.look, args.up))
    f = look - eye
    if np.linalg.norm(f) == 0:
        raise ValueError("eye and look coincide")
    f /= np.linalg.norm(f)
    if not np.linalg.norm(up) > 0:
        raise ValueError("up must be a nonzero vector")
    u = np.cross(f, up / np.linalg.norm(up))
    if not np.linalg.norm(u) > 1e-9:
        # voxlux's fallback: the world axis least aligned with forward, z else y
        u = np.cross(f, [0.0, 0.0, 1.0] if abs(f[2]) < 0.9 else [0.0, 1.0, 0.0])
    u /= np.linalg.norm(u)
    v = np.cross(u, f)
    v /= np.linalg.norm(v)
    return f, u, v


def half_extents(args):
    """(half width, half height) of an orthographic view in world units."""
    w, h = args.size
    return args.ortho / 2.0, args.ortho / 2.0 * h / w


def depth_range(args, lo, hi):
    """(tmin, tmax): distances along f from the eye plane to the nearest and farthest
    corner of the world box [lo, hi]."""
    f, _, _ = frame(args)
    eye = np.array(args.eye)
    ts = [np.dot(np.array([x, y, z]) - eye, f)
          for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    return min(ts), max(ts)


def teem_args(args, lo, hi, near_offset=0.0):
    """teem-mrender options for this camera over the world box [lo, hi].

    -rh makes teem's V point down, so vRange runs from the top row to the bottom row;
    -fv nan makes teem use -ur/-vr instead of deriving them from the default 20 degrees.
    Near and far clip the rays tightly to the box (rays start at the eye at the
    earliest); near_offset moves the near plane that far (world units along f) into
    the box: hoover's first sample lies on the near plane and the next ones on planes
    parallel to it, one step apart."""
    w, h = args.size
    d = float(np.linalg.norm(np.array(args.look) - np.array(args.eye)))
    tmin, tmax = depth_range(args, lo, hi)
    near = max(tmin + near_offset, 1e-6 * max(d, 1.0))
    if tmax <= near:
        raise ValueError("the volume lies behind the eye")
    f, _, v = frame(args)
    out = ["-fr"] + ["%.17g" % x for x in args.eye]
    out += ["-at"] + ["%.17g" % x for x in args.look]
    out += ["-up"] + ["%.17g" % x for x in v]
    out += ["-rh", "-dn", "%.17g" % near, "-di", "%.17g" % d, "-df", "%.17g" % tmax]
    out += ["-is", str(w), str(h)]
    if args.ortho is not None:
        hw, hh = half_extents(args)
        out += ["-or", "-fv", "nan", "-ur", "%.17g" % -hw, "%.17g" % hw,
                "-vr", "%.17g" % -hh, "%.17g" % hh]
    else:
        # teem's perspective window lies on the image plane at distance d
        hh = d * math.tan(math.radians(args.fov) / 2.0)
        hw = hh * w / h
        out += ["-fv", "nan", "-ur", "%.17g" % -hw, "%.17g" % hw,
                "-vr", "%.17g" % -hh, "%.17g" % hh]
    return out


def vtk_camera(cam, args):
    """Set a vtkCamera to this camera.  VTK's view angle is vertical and its parallel
    scale is half the view's height (WIDTH H / W / 2); VTK shoots pixel (x, y) through x + 0.5 from the
    bottom-left, so its image read back bottom-up and flipped matches ours."""
    f, _, v = frame(args)
    cam.SetPosition(*args.eye)
    cam.SetFocalPoint(*args.look)
    cam.SetViewUp(*v)
    if args.ortho is not None:
        cam.ParallelProjectionOn()
        cam.SetParallelScale(half_extents(args)[1])
    else:
        cam.ParallelProjectionOff()
        cam.SetViewAngle(args.fov)


def scene_text(args, iso=None):
    """A voxlux scene (version 1) with this camera; see the module doc."""
    vec = lambda a: " ".join("%.17g" % x for x in a)  # noqa: E731
    if args.ortho is not None:
        cam = "camera orthographic eye %s look %s up %s width %.17g" % (
            vec(args.eye), vec(args.look), vec(args.up), args.ortho)
    else:
        cam = "camera perspective eye %s look %s up %s fov %.17g" % (
            vec(args.eye), vec(args.look), vec(args.up), args.fov)
    lines = ["voxlux-scene 1", "# written by examples/bench/peers/camera.py", cam,
             "image width %d height %d" % tuple(args.size), "background color 0 0 0",
             "ambient color 1 1 1 intensity 0",
             "light headlight color 1 1 1 intensity 1 falloff none shadows off"]
    if iso is not None:
        lines.append("surface iso %.17g color 1 1 1 kd 1 ks 0" % iso)
    lines.append("effects none")
    return "\n".join(lines) + "\n"


def main():
    import argparse
    import os
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import volio
    p = argparse.ArgumentParser(description="camera translation for the peers")
    sub = p.add_subparsers(dest="cmd", required=True)
    t = sub.add_parser("teem")
    t.add_argument("volume")
    t.add_argument("--near-offset", type=float, default=0.0,
                   help="move the near plane this far into the box (world units)")
    add_camera_args(t)
    sc = sub.add_parser("scene")
    sc.add_argument("--iso", type=float)
    add_camera_args(sc)
    args = p.parse_args()
    if args.cmd == "scene":
        sys.stdout.write(scene_text(args, args.iso))
        return
    try:
        with open(args.volume, "rb") as fh:
            fields, _ = volio.read_nrrd_header(fh)
        sizes, spacing, origin = volio.nrrd_geometry(fields)
        lo = np.array(origin)
        hi = lo + (np.array(sizes) - 1) * np.array(spacing)
        print(" ".join(teem_args(args, np.minimum(lo, hi), np.maximum(lo, hi),
                                 args.near_offset)))
    except (OSError, ValueError, KeyError) as e:
        sys.exit("camera.py: %s" % e)


if __name__ == "__main__":
    main()
