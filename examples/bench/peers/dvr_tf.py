#!/usr/bin/python3
"""The transfer function and camera of a voxlux dvr scene, for the DVR peers.

Reads the `transfer opacity`, `transfer color` and `transfer step` lines of a scene
(formats/scene.md section 5, formats/transfer.md) and the camera, image, lights and
ambient lines, and exports them to what the peers read:

  dvr_tf.py txf SCENE OUT.nrrd --range LO HI [--cells N]
      teem miter's 1D transfer function (formats/transfer.md "teem miter txf"): a 2-D
      float NRRD, axis 0 "RGBA", axis 1 "gage(v)" over [LO, HI] in N cells (default
      16 per unit of value, at most 65536); cell i holds the scene's colour and opacity
      at its centre LO + (i + 0.5) (HI - LO) / N.  miter looks its txf up at the
      nearest cell (teem's airIndexClamp), so the cells are fine enough that the lookup
      differs from voxlux's linear interpolation by at most 1/32 of a value unit.
  dvr_tf.py camera SCENE VOLUME.nrrd
      the scene's camera as camera.py's flags (--eye --look --up --fov|--ortho --size),
      an auto camera framed on the volume's box as formats/scene.md says.
  dvr_tf.py scene SCENE VARIANT CAMERA-FLAGS
      the scene a voxlux variant renders (see VARIANTS), with an explicit camera.

Opacity: voxlux's opacity is per reference step (`transfer step S`, 0 = one voxel of
the smallest spacing) and corrected along each ray: 1 - (1 - alpha)^(d / ref).  miter
corrects with (step / ref) for its -ref; VTK with (sample distance / scalar opacity
unit distance).  The peers are given ref as those, so the table is the scene's as it
stands.  Only the opacity and colour lists are exported (the unshaded picture is
emission-absorption with those); transport, surface and gradient lists belong to
voxlux's lighting and are left out.
"""
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import volio  # noqa: E402

# the voxlux variants of a scene (VARIANT: how the scene is changed)
#   unshaded   colour E over opacity only: `light none` (not even the default
#              headlight), ambient 1 (radiance = E),
#              no surface list, effects none.  The emission-absorption picture the
#              unshaded peers draw.
#   local      the scene's lights and surface list, effects specular only: local
#              Blinn-Phong, no light buffer (VTK's shaded mapper's counterpart)
#   lit        the scene as it is (volumetric shadows and scattering)
VARIANTS = ("unshaded", "local", "lit")


def parse_scene(path):
    """The scene's lines as (keyword, words) with comments dropped, in order."""
    out = []
    with open(path) as fh:
        for line in fh:
            line = line.split("#", 1)[0].split()
            if line:
                out.append(line)
    return out


def transfer(lines):
    """{'opacity': [(v, a)], 'color': [(v, r, g, b)], 'step': s} from the transfer
    lines (a later line replaces an earlier one of the same channel)."""
    tf = {"opacity": None, "color": None, "step": 0.0}
    for w in lines:
        if w[0] != "transfer" or len(w) < 2:
            continue
        nums = [float(x) for x in w[2:]] if w[1] in ("opacity", "color", "step") else None
        if w[1] == "opacity":
            tf["opacity"] = [tuple(nums[i:i + 2]) for i in range(0, len(nums), 2)]
        elif w[1] == "color":
            tf["color"] = [tuple(nums[i:i + 4]) for i in range(0, len(nums), 4)]
        elif w[1] == "step":
            tf["step"] = nums[0]
        elif w[1] in ("file", "none"):
            raise ValueError("transfer %s: export the lists only" % w[1])
    if tf["opacity"] is None:
        raise ValueError("no transfer opacity line")
    if tf["color"] is None:
        tf["color"] = [(0.0, 1.0, 1.0, 1.0)]
    return tf


def piecewise(points, x):
    """formats/transfer.md's lookup: linear between control points, clamped to the
    ends, two equal abscissae a step (the second point's value at and right of it).
    points: [(abscissa, value...)]; x: array.  Returns [len(x), nvalues]."""
    xs = np.array([p[0] for p in points])
    ys = np.array([p[1:] for p in points], dtype=np.float64)
    x = np.asarray(x, dtype=np.float64)
    hi = np.searchsorted(xs, x, side="right")          # first abscissa > x
    lo = np.clip(hi - 1, 0, len(xs) - 1)
    hi = np.clip(hi, 0, len(xs) - 1)
    span = xs[hi] - xs[lo]
    t = np.where(span > 0, (x - xs[lo]) / np.where(span > 0, span, 1), 0.0)
    t = np.clip(t, 0.0, 1.0)[:, None]
    return ys[lo] * (1 - t) + ys[hi] * t


def vtk_points(points):
    """Control points for vtkPiecewiseFunction / vtkColorTransferFunction, which keep
    one node per abscissa: the second of two equal abscissae moves right by 1e-6 of
    the list's span (the step then ramps over that width)."""
    eps = 1e-6 * max(points[-1][0] - points[0][0], 1.0)
    out = []
    for p in points:
        x = p[0]
        if out and x <= out[-1][0]:
            x = out[-1][0] + eps
        out.append((x,) + tuple(p[1:]))
    return out


def write_txf(path, tf, lo, hi, cells):
    x = lo + (np.arange(cells) + 0.5) * (hi - lo) / cells
    rgba = np.concatenate([piecewise(tf["color"], x), piecewise(tf["opacity"], x)], axis=1)
    hdr = ("NRRD0004\n# the transfer function of a voxlux scene (examples/bench/peers/dvr_tf.py)\n"
           "type: float\ndimension: 2\nsizes: 4 %d\nlabels: \"RGBA\" \"gage(v)\"\n"
           "axis mins: NaN %.17g\naxis maxs: NaN %.17g\ncenters: ??? cell\n"
           "endian: little\nencoding: raw\n\n" % (cells, lo, hi))
    with open(path, "wb") as fh:
        fh.write(hdr.encode())
        fh.write(rgba.astype("<f4").tobytes())


def key_light(lines):
    """(direction of travel, colour, intensity) of the scene's first directional light,
    the one that drives voxlux's light buffer when it comes first; None if the scene
    has none (a default headlight, or `light none`)."""
    for w in lines:
        if w[0] == "light" and len(w) > 1 and w[1] == "none":
            return None
        if w[0] == "light" and len(w) > 1 and w[1] == "directional":
            kv, i = {}, 2
            while i < len(w):
                n = 3 if w[i] in ("direction", "color") else 1
                kv[w[i]] = [float(x) if n == 3 or w[i] == "intensity" else x
                            for x in w[i + 1:i + 1 + n]]
                i += 1 + n
            return (kv["direction"], kv.get("color", [1.0, 1.0, 1.0]),
                    kv.get("intensity", [1.0])[0])
    return None


def ambient(lines):
    """The scene's ambient intensity times the mean of its colour (default 0.1)."""
    amb = 0.1
    for w in lines:
        if w[0] == "ambient":
            kv, i = {"color": [1.0, 1.0, 1.0], "intensity": [0.1]}, 1
            while i < len(w):
                n = 3 if w[i] == "color" else 1
                kv[w[i]] = [float(x) for x in w[i + 1:i + 1 + n]]
                i += 1 + n
            amb = kv["intensity"][0] * sum(kv["color"]) / 3
    return amb


def camera_flags(lines, volume=None):
    """camera.py's flags for the scene's camera (and image size)."""
    cam, w, h = None, 512, 512
    for wd in lines:
        if wd[0] == "camera":
            cam = wd[1:]
        elif wd[0] == "image":
            kv = dict(zip(wd[1::2], wd[2::2]))
            w, h = int(kv.get("width", w)), int(kv.get("height", h))
    if cam is None:
        cam = ["auto"]
    kind = cam[0] if cam[0] in ("auto", "perspective", "orthographic") else "auto"
    kv = dict(zip(cam[1::2], cam[2::2])) if kind == "auto" else {}
    if kind != "auto":
        words = cam[1:]
        i = 0
        while i < len(words):
            k = words[i]
            n = 3 if k in ("eye", "look", "up") else 1
            kv[k] = words[i + 1:i + 1 + n]
            i += 1 + n
        up = kv.get("up", ["0", "0", "1"])
        flags = ["--eye"] + kv["eye"] + ["--look"] + kv["look"] + ["--up"] + up
        flags += ["--ortho", kv["width"][0]] if kind == "orthographic" else \
            ["--fov", kv.get("fov", ["30"])[0]]
        return flags + ["--size", str(w), str(h)]
    # auto framing (formats/scene.md): perspective only
    if kv.get("projection", "perspective") != "perspective":
        raise ValueError("auto orthographic cameras are not exported")
    if volume is None:
        raise ValueError("an auto camera needs the volume")
    with open(volume, "rb") as fh:
        fields, _ = volio.read_nrrd_header(fh)
    sizes, spacing, origin = volio.nrrd_geometry(fields)
    a = np.array(origin, dtype=np.float64)
    b = a + (np.array(sizes) - 1) * np.array(spacing)
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    c = (lo + hi) / 2
    views = {"front": ((0, 1, 0), (0, 0, 1)), "back": ((0, -1, 0), (0, 0, 1)),
             "right": ((1, 0, 0), (0, 0, 1)), "left": ((-1, 0, 0), (0, 0, 1)),
             "top": ((0, 0, 1), (0, -1, 0)), "bottom": ((0, 0, -1), (0, 1, 0))}
    if "azimuth" in kv or "elevation" in kv:
        az, el = math.radians(float(kv.get("azimuth", 0))), math.radians(float(kv.get("elevation", 0)))
        u = np.array([math.sin(az) * math.cos(el), math.cos(az) * math.cos(el), math.sin(el)])
        up = np.array([0.0, 0.0, 1.0])
        if abs(float(kv.get("elevation", 0))) == 90:
            s = -1 if float(kv["elevation"]) > 0 else 1
            up = s * np.array([math.sin(az), math.cos(az), 0.0])
    else:
        u, up = (np.array(x, dtype=np.float64) for x in views[kv.get("view", "front")])
    if "up" in kv:
        raise ValueError("auto camera with up: not exported")
    fov = float(kv.get("fov", 30))
    F = float(kv.get("distance", 1.1))
    f = -u
    right = np.cross(f, up)
    right /= np.linalg.norm(right)
    upw = np.cross(right, f)
    tv = math.tan(math.radians(fov) / 2)
    th = tv * w / h
    D = 0.0
    for x in (lo[0], hi[0]):
        for y in (lo[1], hi[1]):
            for z in (lo[2], hi[2]):
                p = np.array([x, y, z]) - c
                D = max(D, np.dot(p, u) + max(abs(np.dot(p, right)) / th,
                                              abs(np.dot(p, upw)) / tv))
    eye = c + F * D * u
    g = lambda v: ["%.17g" % t for t in v]  # noqa: E731
    return ["--eye"] + g(eye) + ["--look"] + g(c) + ["--up"] + g(up) + \
        ["--fov", "%.17g" % fov, "--size", str(w), str(h)]


def variant_scene(lines, variant, camflags):
    """The scene text of a voxlux variant (VARIANTS) with camera.py's flags."""
    if variant not in VARIANTS:
        raise ValueError("unknown variant %s" % variant)
    import argparse
    import camera
    p = argparse.ArgumentParser()
    camera.add_camera_args(p)
    a = p.parse_args(camflags)
    out = [l for l in camera.scene_text(a).splitlines()
           if l.split()[0] in ("voxlux-scene", "camera", "image")]
    for w in lines:
        k = w[0]
        if k in ("voxlux-scene", "camera", "image"):
            continue
        if variant == "unshaded":
            if k in ("light", "ambient", "effects", "background", "medium") or \
                    (k == "transfer" and w[1] not in ("opacity", "color", "step")):
                continue
        elif k == "effects" and variant == "local":
            w = ["effects"] + (["specular"] if "specular" in w else ["none"])
        elif k == "background":
            continue
        out.append(" ".join(w))
    out.append("background color 0 0 0")
    if variant == "unshaded":
        out += ["light none", "ambient color 1 1 1 intensity 1", "effects none"]
    return "\n".join(out) + "\n"


def main():
    import argparse
    p = argparse.ArgumentParser(description="export a voxlux dvr scene to the DVR peers")
    sub = p.add_subparsers(dest="cmd", required=True)
    t = sub.add_parser("txf")
    t.add_argument("scene")
    t.add_argument("out")
    t.add_argument("--range", type=float, nargs=2, required=True, metavar=("LO", "HI"))
    t.add_argument("--cells", type=int)
    c = sub.add_parser("camera")
    c.add_argument("scene")
    c.add_argument("volume")
    s = sub.add_parser("scene")
    s.add_argument("scene")
    s.add_argument("variant", choices=VARIANTS)
    s.add_argument("camera", nargs=argparse.REMAINDER)
    a = p.parse_args()
    try:
        lines = parse_scene(a.scene)
        if a.cmd == "txf":
            lo, hi = a.range
            if not hi > lo:
                raise ValueError("--range LO HI with LO < HI")
            cells = a.cells or int(min(65536, max(256, math.ceil(16 * (hi - lo)))))
            write_txf(a.out, transfer(lines), lo, hi, cells)
        elif a.cmd == "camera":
            print(" ".join(camera_flags(lines, a.volume)))
        else:
            sys.stdout.write(variant_scene(lines, a.variant, a.camera))
    except (OSError, ValueError, KeyError, IndexError) as e:
        sys.exit("dvr_tf.py: %s" % e)


if __name__ == "__main__":
    main()
