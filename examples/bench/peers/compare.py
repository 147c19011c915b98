#!/usr/bin/python3
"""Compare a peer's image with a reference (voxlux's exact result, or mip_ref.py's).

usage: compare.py REFERENCE IMAGE [--threshold T | --rel-threshold R] [--mask ref|both|all]
                  [--flip-image] [--shift DX DY] [--diff-png OUT.png] [--label NAME]

Both images are PFM or NRRD (2-D), read with row 0 at the top (PFM is stored bottom-up
and flipped on reading; teem-mrender's NRRD has v rows top first).  All the peers here
already sample the reference's pixel grid (pixel centres, row 0 at the top, see
README.md), so alignment is the identity; --flip-image (turn IMAGE upside down) and
--shift DX DY (IMAGE pixel (x, y) is compared with REFERENCE pixel (x + DX, y + DY)) are
for images from elsewhere.

Pixels compared (--mask): all (default) every pixel; ref: where the reference is nonzero
(its rays met the volume); both: where both are nonzero.  Prints one line:
  NAME max_abs E at (x,y) ref R img I  rmse E  over_T F  n N  ref_range LO HI
where over_T is the fraction of compared pixels with |image - reference| > T (default
T = 1% of the reference's range, or --rel-threshold R times that range).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np  # noqa: E402
import volio  # noqa: E402


def align(ref, img, flip, shift):
    if flip:
        img = np.flipud(img)
    dx, dy = shift
    if dx or dy:
        h, w = ref.shape
        out = np.full_like(ref, np.nan)
        ys, xs = np.mgrid[0:img.shape[0], 0:img.shape[1]]
        ty, tx = ys + dy, xs + dx
        ok = (ty >= 0) & (ty < h) & (tx >= 0) & (tx < w)
        out[ty[ok], tx[ok]] = img[ok]
        img = out
    elif img.shape != ref.shape:
        raise ValueError("sizes differ: reference %dx%d, image %dx%d"
                         % (ref.shape[1], ref.shape[0], img.shape[1], img.shape[0]))
    return img


def compare(ref, img, mask="all", threshold=None, rel=0.01):
    """Dict of max_abs (with its pixel and values), rmse, over (fraction > threshold), n."""
    sel = np.isfinite(img) & np.isfinite(ref)
    if mask == "ref":
        sel &= ref != 0
    elif mask == "both":
        sel &= (ref != 0) & (img != 0)
    if not sel.any():
        raise ValueError("no pixels to compare")
    lo, hi = float(ref[sel].min()), float(ref[sel].max())
    t = threshold if threshold is not None else rel * ((hi - lo) or 1.0)
    d = np.where(sel, np.abs(img - ref), -1.0)
    k = int(np.argmax(d))
    y, x = divmod(k, ref.shape[1])
    dd = d[sel]
    return {"max_abs": float(dd.max()), "x": x, "y": y, "ref": float(ref[y, x]),
            "img": float(img[y, x]), "rmse": float(np.sqrt(np.mean(dd ** 2))),
            "threshold": t, "over": float(np.mean(dd > t)), "n": int(sel.sum()),
            "lo": lo, "hi": hi, "diff": np.where(sel, np.abs(img - ref), 0.0)}


def main():
    p = argparse.ArgumentParser(description="image error against a reference")
    p.add_argument("reference")
    p.add_argument("image")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--threshold", type=float)
    g.add_argument("--rel-threshold", type=float, default=0.01)
    p.add_argument("--mask", choices=("all", "ref", "both"), default="all")
    p.add_argument("--flip-image", action="store_true")
    p.add_argument("--shift", type=int, nargs=2, default=(0, 0), metavar=("DX", "DY"))
    p.add_argument("--diff-png", metavar="OUT.png", help="|difference| as a gray PNG")
    p.add_argument("--label", default=None)
    args = p.parse_args()
    try:
        ref = volio.read_image(args.reference)
        img = align(ref, volio.read_image(args.image), args.flip_image, args.shift)
        r = compare(ref, img, args.mask, args.threshold, args.rel_threshold)
        if args.diff_png:
            volio.write_png_gray(args.diff_png, r["diff"], 0.0, r["max_abs"] or 1.0)
    except (OSError, ValueError) as e:
        sys.exit("compare.py: %s" % e)
    print("%s max_abs %.6g at (%d,%d) ref %.6g img %.6g  rmse %.6g  over_%.6g %.6f  n %d  "
          "ref_range %.6g %.6g" % (args.label or os.path.basename(args.image), r["max_abs"],
                                   r["x"], r["y"], r["ref"], r["img"], r["rmse"],
                                   r["threshold"], r["over"], r["n"], r["lo"], r["hi"]))


if __name__ == "__main__":
    main()
