#!/usr/bin/python3
"""Benchmark peer for tet-mesh isosurfaces: VTK's contour filter on the unstructured grid,
written as a VXMESH01 triangle mesh for ../peers/embree_render.

usage: contour.py MESH.vtk[.gz] --iso V -o OUT.mesh [--method filter|linear] [--runs N]
                  [--threads N] [--scalar NAME]

MESH is a VTK legacy UNSTRUCTURED_GRID file (gzip is decompressed in memory first; that is
not timed).  Prints one line per phase, medians of N runs where a phase is repeated:
  read_s       vtkUnstructuredGridReader on the decompressed bytes (one run)
  contour_s    Update() of the contour filter (median of N)
  normals_s    vtkPolyDataNormals on the result (one run; embree_render's shading needs
               vertex normals, the contour filter on a mesh gives none)
  tris, verts  the surface's size
  rss_mb       peak resident memory of this process (ru_maxrss)
--method filter (default): vtkContourFilter (which hands unstructured grids to
vtkContourGrid); linear: vtkContour3DLinearGrid (threaded through vtkSMPTools, linear cells
only, point merging on).
"""
import argparse
import gzip
import os
import resource
import statistics
import struct
import sys
import time

import numpy as np

try:
    import vtk
    from vtk.util import numpy_support as ns
except ImportError:
    sys.exit("contour.py: VTK for Python is missing (make -C examples/bench bench-deps)")


def read_grid(path):
    data = open(path, "rb").read()
    if data[:2] == b"\x1f\x8b":
        data = gzip.decompress(data)
    r = vtk.vtkUnstructuredGridReader()
    r.ReadFromInputStringOn()
    r.SetBinaryInputString(data, len(data))
    r.ReadAllScalarsOn()
    t0 = time.perf_counter()
    r.Update()
    return r.GetOutput(), time.perf_counter() - t0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("mesh")
    p.add_argument("--iso", type=float, required=True)
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--method", choices=("filter", "linear"), default="filter")
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--scalar")
    a = p.parse_args()
    if a.threads > 0:
        vtk.vtkSMPTools.Initialize(a.threads)
    ug, tread = read_grid(a.mesh)
    pd = ug.GetPointData()
    name = a.scalar or pd.GetArrayName(0)
    if name is None or pd.GetArray(name) is None:
        sys.exit("contour.py: %s: no point array %s" % (a.mesh, name or ""))
    pd.SetActiveScalars(name)
    if a.method == "filter":
        f = vtk.vtkContourFilter()
        f.ComputeNormalsOff()
        f.ComputeGradientsOff()
        f.ComputeScalarsOff()
    else:
        f = vtk.vtkContour3DLinearGrid()
        f.MergePointsOn()
        f.ComputeNormalsOff()
        f.InterpolateAttributesOff()
    f.SetInputData(ug)
    f.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS, name)
    f.SetValue(0, a.iso)
    times = []
    for _ in range(max(1, a.runs)):
        f.Modified()
        t0 = time.perf_counter()
        f.Update()
        times.append(time.perf_counter() - t0)
    poly = f.GetOutput()
    t0 = time.perf_counter()
    nf = vtk.vtkPolyDataNormals()
    nf.SetInputData(poly)
    nf.SplittingOff()
    nf.ConsistencyOff()
    nf.ComputePointNormalsOn()
    nf.Update()
    tnorm = time.perf_counter() - t0
    out = nf.GetOutput()
    pts = ns.vtk_to_numpy(out.GetPoints().GetData()).astype("<f4") if out.GetPoints() else \
        np.zeros((0, 3), "<f4")
    polys = out.GetPolys()
    off = ns.vtk_to_numpy(polys.GetOffsetsArray())
    conn = ns.vtk_to_numpy(polys.GetConnectivityArray())
    if len(off) > 1 and not np.all(np.diff(off) == 3):
        sys.exit("contour.py: the surface has non-triangle cells")
    tri = conn.reshape(-1, 3).astype("<u4")
    nrm = ns.vtk_to_numpy(out.GetPointData().GetNormals()).astype("<f4") if len(pts) else pts
    tmp = a.output + ".tmp"
    with open(tmp, "wb") as fo:
        fo.write(b"VXMESH01" + struct.pack("<II", len(pts), len(tri)))
        fo.write(np.ascontiguousarray(pts).tobytes())
        fo.write(np.ascontiguousarray(tri).tobytes())
        fo.write(np.ascontiguousarray(nrm).tobytes())
    os.replace(tmp, a.output)
    print("method %s (%s), threads %d" % (a.method, f.GetClassName(),
          vtk.vtkSMPTools.GetEstimatedNumberOfThreads()))
    print("cells %d points %d scalar %s" % (ug.GetNumberOfCells(), ug.GetNumberOfPoints(), name))
    print("read_s %.4f" % tread)
    print("contour_s %.4f (median of %d)" % (statistics.median(times), len(times)))
    print("normals_s %.4f" % tnorm)
    print("tris %d verts %d" % (len(tri), len(pts)))
    print("rss_mb %.1f" % (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024))


if __name__ == "__main__":
    main()
