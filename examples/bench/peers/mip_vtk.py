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

try:
    import vtk
    from vtk.util import numpy_support as ns
except ImportError:
    sys.exit("mip_vtk.py: VTK for Python is missing (make -C examples/bench bench-deps)")

FP_ONE = 32767.0   # VTKKW_FP_SCALE: the mapper's fixed-point 1.0


def internal_image(mapper, w, h):
    """The mapper's last ray-cast image as a float [h, w] array in [0, 1], row 0 at the
    top, placed in the window by the image origin (rays are one per pixel), and the mask
    of pixels whose rays met the volume (alpha > 0)."""
    ri = mapper.GetRayCastImage()
    vs = ri.GetImageViewportSize()
    if tuple(vs) != (w, h) or ri.GetImageSampleDistance() != 1.0:
        raise RuntimeError("ray-cast image %s at sample distance %g, not one ray per pixel"
                           % (vs, ri.GetImageSampleDistance()))
    mw, mh = ri.GetImageMemorySize()
    uw, uh = ri.GetImageInUseSize()
    ox, oy = ri.GetImageOrigin()
    buf = vtk.vtkUnsignedShortArray()
    buf.SetNumberOfComponents(4)
    buf.SetVoidArray(ri.GetImage(), mw * mh * 4, 1)
    a = ns.vtk_to_numpy(buf).reshape(mh, mw, 4)[:uh, :uw].astype(np.float64) / FP_ONE
    out = np.zeros((h, w, 2))
    x0, y0 = max(ox, 0), max(oy, 0)
    x1, y1 = min(ox + uw, w), min(oy + uh, h)
    out[y0:y1, x0:x1] = a[y0 - oy:y1 - oy, x0 - ox:x1 - ox][:, :, [0, 3]]
    return np.flipud(out[:, :, 0]), np.flipud(out[:, :, 1] > 0)


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

    img = vtk.vtkImageData()
    img.SetDimensions(*vol.dims)
    img.SetSpacing(*vol.spacing)
    img.SetOrigin(*vol.origin)
    img.GetPointData().SetScalars(ns.numpy_to_vtk(np.ascontiguousarray(vol.data).ravel(),
                                                  deep=1))
    mapper = vtk.vtkFixedPointVolumeRayCastMapper()
    mapper.SetInputData(img)
    mapper.SetBlendModeToMaximumIntensity()
    mapper.SetAutoAdjustSampleDistances(0)
    mapper.SetImageSampleDistance(1.0)
    mapper.SetSampleDistance(args.step)
    mapper.SetLockSampleDistanceToInputSpacing(0)
    if args.threads > 0:
        mapper.SetNumberOfThreads(args.threads)
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
    actor = vtk.vtkVolume()
    actor.SetMapper(mapper)
    actor.SetProperty(prop)
    ren = vtk.vtkRenderer()
    ren.AddVolume(actor)
    ren.SetBackground(0, 0, 0)
    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetMultiSamples(0)
    win.AddRenderer(ren)
    win.SetSize(w, h)
    camera.vtk_camera(ren.GetActiveCamera(), args)
    ren.ResetCameraClippingRange()

    win.Render()   # warm-up: tables, min-max volume, GL context
    times, cpu = [], []
    for _ in range(args.runs):
        c0, t0 = time.process_time(), time.perf_counter()
        win.Render()
        times.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    try:
        frac, hit = internal_image(mapper, w, h)
    except RuntimeError as e:
        sys.exit("mip_vtk.py: %s" % e)
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
