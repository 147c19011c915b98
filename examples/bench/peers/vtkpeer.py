"""What the VTK peers (mip_vtk.py, dvr_vtk.py) share: the volume as vtkImageData,
vtkFixedPointVolumeRayCastMapper with one ray per pixel at a fixed sample distance, an
offscreen window on the voxlux camera, the timed renders, and the mapper's own 15-bit
ray-cast image read back.  Importing it exits with a message when VTK is missing."""
import sys
import time

import numpy as np
import camera

try:
    import vtk
    from vtk.util import numpy_support as ns
except ImportError:
    sys.exit("%s: VTK for Python is missing (make -C examples/bench bench-deps)"
             % sys.argv[0].rsplit("/", 1)[-1])

FP_ONE = 32767.0   # VTKKW_FP_SCALE: the mapper's fixed-point 1.0


def image_data(vol):
    """vol (volio's) as vtkImageData (a deep copy of its samples)."""
    img = vtk.vtkImageData()
    img.SetDimensions(*vol.dims)
    img.SetSpacing(*vol.spacing)
    img.SetOrigin(*vol.origin)
    img.GetPointData().SetScalars(ns.numpy_to_vtk(np.ascontiguousarray(vol.data).ravel(),
                                                  deep=1))
    return img


def mapper(img, step, threads):
    """The fixed-point ray caster on img: a sample every step world units, automatic
    adjustment off, one ray per pixel, threads (0: VTK's default, all cores)."""
    m = vtk.vtkFixedPointVolumeRayCastMapper()
    m.SetInputData(img)
    m.SetAutoAdjustSampleDistances(0)
    m.SetImageSampleDistance(1.0)
    m.SetSampleDistance(step)
    m.SetLockSampleDistanceToInputSpacing(0)
    if threads > 0:
        m.SetNumberOfThreads(threads)
    return m


def window(ren, mapper_, prop, args):
    """ren with the volume of mapper_ and prop, in an offscreen window of args.size on
    the voxlux camera of args (camera.py), black background."""
    actor = vtk.vtkVolume()
    actor.SetMapper(mapper_)
    actor.SetProperty(prop)
    ren.AddVolume(actor)
    ren.SetBackground(0, 0, 0)
    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetMultiSamples(0)
    win.AddRenderer(ren)
    win.SetSize(*args.size)
    camera.vtk_camera(ren.GetActiveCamera(), args)
    ren.ResetCameraClippingRange()
    return win


def timed_renders(win, runs):
    """One warm-up Render() (tables, the min-max volume, gradients when shaded, the GL
    context), then runs timed ones: (warm-up s, wall s each, process CPU s each)."""
    t0 = time.perf_counter()
    win.Render()
    first = time.perf_counter() - t0
    times, cpu = [], []
    for _ in range(runs):
        c0, t0 = time.process_time(), time.perf_counter()
        win.Render()
        times.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return first, times, cpu


def internal_rgba(mapper_, w, h):
    """The mapper's last ray-cast image as float [h, w, 4] in [0, 1] (colour
    premultiplied by alpha), row 0 at the top, placed in the window by its image origin
    (one ray per pixel), not the 8-bit framebuffer VTK draws it into as a texture."""
    ri = mapper_.GetRayCastImage()
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
    out = np.zeros((h, w, 4))
    x0, y0 = max(ox, 0), max(oy, 0)
    x1, y1 = min(ox + uw, w), min(oy + uh, h)
    out[y0:y1, x0:x1] = a[y0 - oy:y1 - oy, x0 - ox:x1 - ox]
    return np.flipud(out)
