#!/usr/bin/python3
"""Benchmark peer: maximum-intensity projection with VTK's
vtkFixedPointVolumeRayCastMapper (CPU ray casting, trilinear samples every --step world
units), offscreen.  Needs an X display: run it under `xvfb-run -a`.

usage: xvfb-run -a mip_vtk.py VOLUME -o OUT.pfm CAMERA [--step S] [--runs N]
                              [--threads N] [volume flags]
CAMERA: --eye X Y Z --look X Y Z [--up X Y Z] (--ortho WIDTH | --fov DEG) [--size W H]

The image is the maximum in data units.  The colour transfer function is a gray ramp from
the volume's minimum to its maximum and the opacity is 1 everywhere, so the mapper's
colour for a ray is (max - min) / (max - min of the volume) in its 15-bit fixed point.
That 15-bit image is read straight from the mapper (vtkFixedPointRayCastImage, one ray
per window pixel), not from the 8-bit framebuffer, which VTK fills by drawing the image
as a linearly filtered texture.  Pixels whose rays miss the volume (alpha 0) are 0.  Time: median of N Render() calls after one warm-up
render, with automatic sample-distance adjustment off and one ray per pixel.
"""
import argparse
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np  # noqa: E402
import camera  # noqa: E402
import volio  # noqa: E402

import vtkpeer  # noqa: E402
from vtkpeer import vtk  # noqa: E402


def main():
    p = argparse.ArgumentParser(description="VTK fixed-point ray-cast MIP peer")
    p.add_argument("volume")
    p.add_argument("-o", "--output", required=True, help="output PFM (data units)")
    camera.add_camera_args(p)
    p.add_argument("--step", type=float, default=1.0, help="sample distance (world units)")
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--threads", type=int, default=0, help="mapper threads (0: all cores)")
    volio.add_volume_args(p)
    args = p.parse_args()
    if args.runs < 1 or args.step <= 0:
        p.error("--runs must be at least 1 and --step positive")
    try:
        vol = volio.read_volume(args.volume, args)
        camera.frame(args)
    except (OSError, ValueError) as e:
        sys.exit("mip_vtk.py: %s" % e)
    if min(vol.spacing) <= 0:
        sys.exit("mip_vtk.py: VTK needs positive spacings")
    w, h = args.size
    lo, hi = float(vol.data.min()), float(vol.data.max())
    if hi <= lo:
        hi = lo + 1.0

    mapper = vtkpeer.mapper(vtkpeer.image_data(vol), args.step, args.threads)
    mapper.SetBlendModeToMaximumIntensity()
    ctf = vtk.vtkColorTransferFunction()
    ctf.AddRGBPoint(lo, 0, 0, 0)
    ctf.AddRGBPoint(hi, 1, 1, 1)
    otf = vtk.vtkPiecewiseFunction()
    otf.AddPoint(lo, 1.0)
    otf.AddPoint(hi, 1.0)
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(ctf)
    prop.SetScalarOpacity(otf)
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOff()
    win = vtkpeer.window(vtk.vtkRenderer(), mapper, prop, args)
    _, times, cpu = vtkpeer.timed_renders(win, args.runs)
    try:
        rgba = vtkpeer.internal_rgba(mapper, w, h)
    except RuntimeError as e:
        sys.exit("mip_vtk.py: %s" % e)
    frac, hit = rgba[:, :, 0], rgba[:, :, 3] > 0
    if frac.shape != (h, w):
        sys.exit("mip_vtk.py: read back %s, expected %dx%d" % (frac.shape, w, h))
    out = np.where(hit, lo + frac * (hi - lo), 0.0)
    volio.write_pfm(args.output, out)
    print("mip_vtk %s %dx%d step %g" % (args.output, w, h, args.step))
    print("render_ms %.3f (median of %d after 1 warm-up, vtkFixedPointVolumeRayCastMapper "
          "MIP, VTK %s, threads %d)" % (1e3 * statistics.median(times), args.runs,
                                        vtk.vtkVersion.GetVTKVersion(),
                                        mapper.GetNumberOfThreads()))
    print("render_cpu_ms %.3f (process CPU time, median of %d)"
          % (1e3 * statistics.median(cpu), args.runs))


if __name__ == "__main__":
    main()
