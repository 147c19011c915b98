#!/usr/bin/python3
"""Benchmark peer: direct volume rendering (composite) with VTK's
vtkFixedPointVolumeRayCastMapper (CPU ray casting), offscreen, the transfer function
of a voxlux scene.  Needs an X display: run it under `xvfb-run -a`.

usage: xvfb-run -a dvr_vtk.py VOLUME --scene SCENE -o OUT.pfm CAMERA [--shade]
                              [--step S] [--runs N] [--threads N] [volume flags]
CAMERA: --eye X Y Z --look X Y Z [--up X Y Z] (--ortho WIDTH | --fov DEG) [--size W H]

Transfer function: the scene's `transfer color` list as a vtkColorTransferFunction
(RGB nodes, linear) and its `transfer opacity` list as the scalar-opacity
vtkPiecewiseFunction (dvr_tf.py; equal abscissae are 1e-6 of the span apart), trilinear
interpolation.  Opacity correction: VTK corrects each sample's opacity as
1 - (1 - a)^(S / U) for its sample distance S and the property's scalar opacity unit
distance U; U is set to the scene's reference step (`transfer step`, 0 = the smallest
spacing), as voxlux's alpha' = 1 - (1 - a)^(d / ref).  Sample distance --step (world
units, along each ray), automatic sample-distance adjustment off, one ray per pixel.

Unshaded (default): ShadeOff; a sample's colour is the colour list's.  --shade: ShadeOn,
VTK's local Phong on the gradient (its encoded normals): ambient = the scene's ambient
intensity, diffuse 1, specular 0.2, specular power 32 (voxlux's surface term with the
specular effect), lit by the scene's first directional light (a vtkLight, scene light,
not positional, its colour and intensity), else a headlight.  VTK shades every sample;
voxlux only blends the surface term in by the scene's surface weight, so the shaded
pictures are not meant to be equal, only the work comparable.

Output: OUT.pfm, the mapper's own 15-bit ray-cast image (colour premultiplied by its
alpha, as voxlux's), read straight from the mapper (mip_vtk.py says why), and OUT's alpha
beside it (.alpha.pfm).  Time: median of N Render() calls after one warm-up render;
the warm-up (tables, the min-max volume and, shaded, the gradient normals and their
encoding) is printed too, as first_ms.  Threads: mapper.SetNumberOfThreads(--threads).
"""
import argparse
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np  # noqa: E402
import camera  # noqa: E402
import dvr_tf  # noqa: E402
import volio  # noqa: E402

import vtkpeer  # noqa: E402
from vtkpeer import vtk  # noqa: E402


def main():
    p = argparse.ArgumentParser(description="VTK fixed-point ray-cast DVR peer")
    p.add_argument("volume")
    p.add_argument("--scene", required=True, help="the voxlux scene with the transfer lines")
    p.add_argument("-o", "--output", required=True, help="output PFM (RGB, premultiplied)")
    camera.add_camera_args(p)
    p.add_argument("--shade", action="store_true", help="VTK's local Phong shading")
    p.add_argument("--step", type=float, default=1.0, help="sample distance (world units)")
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--threads", type=int, default=0, help="mapper threads (0: all cores)")
    volio.add_volume_args(p)
    args = p.parse_args()
    if args.runs < 1 or args.step <= 0:
        p.error("--runs must be at least 1 and --step positive")
    try:
        lines = dvr_tf.parse_scene(args.scene)
        tf = dvr_tf.transfer(lines)
        key = dvr_tf.key_light(lines)
        amb = dvr_tf.ambient(lines)
        t0 = time.perf_counter()
        vol = volio.read_volume(args.volume, args)
        camera.frame(args)
    except (OSError, ValueError, KeyError, IndexError) as e:
        sys.exit("dvr_vtk.py: %s" % e)
    if min(vol.spacing) <= 0:
        sys.exit("dvr_vtk.py: VTK needs positive spacings")
    w, h = args.size
    ref = tf["step"] if tf["step"] > 0 else min(vol.spacing)

    img = vtkpeer.image_data(vol)
    load_s = time.perf_counter() - t0
    mapper = vtkpeer.mapper(img, args.step, args.threads)
    mapper.SetBlendModeToComposite()
    ctf = vtk.vtkColorTransferFunction()
    for x, r, g, b in dvr_tf.vtk_points(tf["color"]):
        ctf.AddRGBPoint(x, r, g, b)
    otf = vtk.vtkPiecewiseFunction()
    for x, a in dvr_tf.vtk_points(tf["opacity"]):
        otf.AddPoint(x, a)
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(ctf)
    prop.SetScalarOpacity(otf)
    prop.SetScalarOpacityUnitDistance(ref)
    prop.SetInterpolationTypeToLinear()
    ren = vtk.vtkRenderer()
    if args.shade:
        prop.ShadeOn()
        prop.SetAmbient(amb)
        prop.SetDiffuse(1.0)
        prop.SetSpecular(0.2)
        prop.SetSpecularPower(32.0)
        if key is not None:
            d, col, k = key
            light = vtk.vtkLight()
            light.SetLightTypeToSceneLight()
            light.SetPositional(0)
            light.SetFocalPoint(0.0, 0.0, 0.0)
            light.SetPosition(-d[0], -d[1], -d[2])
            light.SetColor(*col)
            light.SetIntensity(k)
            ren.AddLight(light)
    else:
        prop.ShadeOff()
    win = vtkpeer.window(ren, mapper, prop, args)
    first, times, cpu = vtkpeer.timed_renders(win, args.runs)
    try:
        rgba = vtkpeer.internal_rgba(mapper, w, h)
    except RuntimeError as e:
        sys.exit("dvr_vtk.py: %s" % e)
    if not args.output.endswith(".pfm"):
        sys.exit("dvr_vtk.py: OUT must end in .pfm")
    volio.write_pfm_rgb(args.output, rgba[:, :, :3])
    volio.write_pfm(args.output[:-4] + ".alpha.pfm", rgba[:, :, 3])
    print("dvr_vtk %s %dx%d step %g unit distance %g %s" % (
        args.output, w, h, args.step, ref, "shaded" if args.shade else "unshaded"))
    print("render_ms %.3f (median of %d after 1 warm-up, vtkFixedPointVolumeRayCastMapper "
          "composite, VTK %s, threads %d)" % (1e3 * statistics.median(times), args.runs,
                                              vtk.vtkVersion.GetVTKVersion(),
                                              mapper.GetNumberOfThreads()))
    print("render_cpu_ms %.3f (process CPU time, median of %d)"
          % (1e3 * statistics.median(cpu), args.runs))
    print("first_ms %.3f (the warm-up render)" % (1e3 * first))
    print("load_ms %.3f (reading the volume into vtkImageData)" % (1e3 * load_s))


if __name__ == "__main__":
    main()
