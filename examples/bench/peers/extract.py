#!/usr/bin/python3
"""Benchmark peer: isosurface extraction with VTK (vtkFlyingEdges3D, or vtkMarchingCubes),
written as a VXMESH01 triangle mesh for embree_render.

usage: extract.py VOLUME --iso VALUE -o MESH [--method fe|mc] [--runs N] [--threads N]
                  [volume flags: see volio.py]

Prints the vertex and triangle counts and the extraction time (median of N runs of the
filter's Update(); reading the volume and writing the mesh are not timed).  Vertex
positions are world coordinates, world = origin + index * spacing; normals are VTK's
gradient normals, unit length (their sign does not matter to embree_render).

Mesh file (little-endian): "VXMESH01" | u32 nverts | u32 ntris | f32 xyz[nverts][3] |
u32 tri[ntris][3] | f32 normal[nverts][3].
"""
import argparse
import os
import statistics
import struct
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np  # noqa: E402
import volio  # noqa: E402

try:
    import vtk
    from vtk.util import numpy_support as ns
except ImportError:
    sys.exit("extract.py: VTK for Python is missing (make -C examples/bench bench-deps)")


def to_vtk_image(vol):
    """A vtkImageData holding vol's samples (deep copy) with its spacing and origin."""
    img = vtk.vtkImageData()
    img.SetDimensions(*vol.dims)
    img.SetSpacing(*vol.spacing)
    img.SetOrigin(*vol.origin)
    arr = ns.numpy_to_vtk(np.ascontiguousarray(vol.data).ravel(), deep=1)
    arr.SetName("scalars")
    img.GetPointData().SetScalars(arr)
    return img


def make_filter(method, img, iso):
    if method == "fe":
        f = vtk.vtkFlyingEdges3D()
        f.ComputeGradientsOff()
    else:
        f = vtk.vtkMarchingCubes()
    f.SetInputData(img)
    f.SetValue(0, iso)
    f.ComputeNormalsOn()
    f.ComputeScalarsOff()
    return f


def mesh_arrays(poly):
    """(positions f32 [n,3], triangles u32 [m,3], normals f32 [n,3]) of a triangle-only
    vtkPolyData."""
    pts = ns.vtk_to_numpy(poly.GetPoints().GetData()).astype("<f4")
    cells = poly.GetPolys()
    off = ns.vtk_to_numpy(cells.GetOffsetsArray())
    conn = ns.vtk_to_numpy(cells.GetConnectivityArray())
    if len(off) > 1 and not np.all(np.diff(off) == 3):
        raise ValueError("the extracted surface has non-triangle cells")
    tri = conn.reshape(-1, 3)
    if len(pts) >= 2 ** 32:
        raise ValueError("too many vertices for the mesh format")
    nrm_arr = poly.GetPointData().GetNormals()
    if nrm_arr is None:
        raise ValueError("the filter produced no normals")
    nrm = ns.vtk_to_numpy(nrm_arr).astype("<f4")
    return pts, tri.astype("<u4"), nrm


def write_mesh(path, pts, tri, nrm):
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(b"VXMESH01" + struct.pack("<II", len(pts), len(tri)))
        f.write(np.ascontiguousarray(pts).tobytes())
        f.write(np.ascontiguousarray(tri).tobytes())
        f.write(np.ascontiguousarray(nrm).tobytes())
    os.replace(tmp, path)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("volume")
    p.add_argument("--iso", type=float, required=True)
    p.add_argument("-o", "--output", required=True, help="mesh file (VXMESH01)")
    p.add_argument("--method", choices=("fe", "mc"), default="fe",
                   help="fe: vtkFlyingEdges3D (default), mc: vtkMarchingCubes")
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--threads", type=int, default=0,
                   help="vtkSMPTools threads for flying edges (0: VTK's default)")
    volio.add_volume_args(p)
    args = p.parse_args()
    if args.runs < 1:
        p.error("--runs must be at least 1")
    try:
        vol = volio.read_volume(args.volume, args)
    except (OSError, ValueError) as e:
        sys.exit("extract.py: %s" % e)
    if args.threads > 0:
        vtk.vtkSMPTools.Initialize(args.threads)
    nthreads = vtk.vtkSMPTools.GetEstimatedNumberOfThreads() if args.method == "fe" else 1
    img = to_vtk_image(vol)
    flt = make_filter(args.method, img, args.iso)
    times, cpu = [], []
    for _ in range(args.runs):
        flt.Modified()
        c0, t0 = time.process_time(), time.perf_counter()
        flt.Update()
        times.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    try:
        pts, tri, nrm = mesh_arrays(flt.GetOutput())
        if len(tri) == 0:
            raise ValueError("no surface at isovalue %g" % args.iso)
        write_mesh(args.output, pts, tri, nrm)
    except (OSError, ValueError) as e:
        sys.exit("extract.py: %s" % e)
    name = "vtkFlyingEdges3D" if args.method == "fe" else "vtkMarchingCubes"
    print("volume %s dims %d %d %d iso %g" % ((args.volume,) + vol.dims + (args.iso,)))
    print("mesh %s vertices %d triangles %d" % (args.output, len(pts), len(tri)))
    print("extract_ms %.3f (median of %d, %s, VTK %s, SMP %s, threads %d)"
          % (1e3 * statistics.median(times), args.runs, name, vtk.vtkVersion.GetVTKVersion(),
             vtk.vtkSMPTools.GetBackend(), nthreads))
    print("extract_cpu_ms %.3f (process CPU time, median of %d)"
          % (1e3 * statistics.median(cpu), args.runs))


if __name__ == "__main__":
    main()
