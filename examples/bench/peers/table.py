#!/usr/bin/python3
"""Gather the peers' logs in OUT (written by examples/bench/Makefile) into Markdown tables.

usage: table.py OUT > OUT/peers.md

Log names: D-iso-I-fe-jN.log, D-iso-I-mc.log, D-iso-I-embree-jN.log, D-iso-I-voxlux-jN.log,
D-mip-V-teem-sS.log, D-mip-V-vtk-sS.log, D-mip-V-voxlux.log (each starts with a "cmd: "
line).  Embree's picture D-iso-I-embree-jN.pfm is compared with voxlux's
D-iso-I-voxlux-jN.pfm when both exist.  A MIP image
D-mip-V-P-sS.pfm is compared with D-mip-V-voxlux.pfm when it exists (voxlux's exact
maximum), else with D-mip-V-ref.pfm (mip_ref.py, axis-aligned views only).
"""
import glob
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np  # noqa: E402
import compare  # noqa: E402
import volio  # noqa: E402


def parse(path):
    d = {"cmd": ""}
    with open(path) as f:
        for line in f:
            if line.startswith("cmd: "):
                d["cmd"] = line[5:].strip()
            m = re.match(r"(\w+_ms) ([0-9.]+)", line)
            if m:
                d[m.group(1)] = float(m.group(2))
            m = re.search(r"vertices (\d+) triangles (\d+)", line)
            if m:
                d["verts"], d["tris"] = int(m.group(1)), int(m.group(2))
            m = re.search(r"threads (\d+)", line)
            if m and "threads" not in d:
                d["threads"] = int(m.group(1))
    return d


def ms(d, key):
    return "%.1f" % d[key] if key in d else "-"


def wc(d, key, cpu_key):
    """'wall / cpu' milliseconds."""
    if key not in d:
        return "-"
    return "%.0f / %.0f" % (d[key], d[cpu_key]) if cpu_key in d else "%.0f" % d[key]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    logs = {os.path.basename(p)[:-4]: parse(p) for p in glob.glob(os.path.join(out, "*.log"))}
    cmds = []
    print("# voxlux benchmark peers\n")
    print("Produced by `make -C examples/bench`; every time is a median (the commands below"
          " say over how many runs), given as wall / CPU milliseconds: CPU is the process's"
          " user + system time over all its threads, which is the steadier number on a"
          " shared machine.  512x512 images.\n")

    print("## Isosurfaces: VTK extraction, Embree BVH build and frames\n")
    print("| data | iso | extraction | triangles | extract ms (1 thr) | extract ms (N thr) |"
          " BVH build ms (1 thr) | BVH build ms (N thr) | frame ms (1 thr) | frame ms (N thr) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    img_cmp = []
    isos = sorted({(m.group(1), m.group(2)) for k in logs
                   for m in [re.match(r"(\w+)-iso-([0-9.]+)-", k)] if m},
                  key=lambda t: (t[0], float(t[1])))
    for data, iso in isos:
        pre = "%s-iso-%s-" % (data, iso)
        fe = {int(k[len(pre) + 4:]): v for k, v in logs.items() if k.startswith(pre + "fe-j")}
        eb = {int(k[len(pre) + 8:]): v for k, v in logs.items() if k.startswith(pre + "embree-j")}
        nmax = max(list(fe) + list(eb) + [1])
        f1, fn = fe.get(1, {}), fe.get(nmax, {})
        e1, en = eb.get(1, {}), eb.get(nmax, {})
        print("| %s | %s | flying edges | %s | %s | %s | %s | %s | %s | %s |"
              % (data, iso, fn.get("tris", f1.get("tris", "-")),
                 wc(f1, "extract_ms", "extract_cpu_ms"), wc(fn, "extract_ms", "extract_cpu_ms"),
                 wc(e1, "build_ms", "build_cpu_ms"), wc(en, "build_ms", "build_cpu_ms"),
                 wc(e1, "render_ms", "render_cpu_ms"), wc(en, "render_ms", "render_cpu_ms")))
        mc = logs.get(pre + "mc")
        if mc:
            print("| %s | %s | marching cubes | %s | %s | - | - | - | - | - |"
                  % (data, iso, mc.get("tris", "-"), wc(mc, "extract_ms", "extract_cpu_ms")))
        vx = {int(k[len(pre) + 8:]): v for k, v in logs.items() if k.startswith(pre + "voxlux-j")}
        v1, vn = vx.get(1, {}), vx.get(nmax, {})
        if vx:
            print("| %s | %s | voxlux raycast (no mesh) | - | - | - | - | - | %s | %s |"
                  % (data, iso, wc(v1, "render_ms", "render_cpu_ms"),
                     wc(vn, "render_ms", "render_cpu_ms")))
            emb = os.path.join(out, pre + "embree-j%d.pfm" % nmax)
            ref = os.path.join(out, pre + "voxlux-j%d.pfm" % nmax)
            if os.path.exists(emb) and os.path.exists(ref):
                r_img, e_img = volio.read_image(ref), volio.read_image(emb)
                a = compare.compare(r_img, e_img, "all")
                b = compare.compare(r_img, e_img, "both")
                cov = float(np.mean((r_img > 0) != (e_img > 0)))
                img_cmp.append("| %s | %s | %.4g | %.4g | %.4g | %.4f | %.4f |"
                               % (data, iso, a["max_abs"], b["max_abs"], a["rmse"], a["over"], cov))
        for d in [f1, fn, mc or {}, e1, en, v1, vn]:
            if d.get("cmd") and d["cmd"] not in cmds:
                cmds.append(d["cmd"])
    print("\nN thr = %s (all cores of this machine); Embree: rtcIntersect1 per pixel, "
          "OpenMP dynamic schedule over rows; voxlux: `raycast --stats` time (exact trilinear "
          "isosurface through the macrocells, no mesh; the macrocell build is not counted)."
          "\n" % (max([1] + [d.get("threads", 1) for k, d in logs.items() if "-iso-" in k])))
    if img_cmp:
        print("Embree's picture (flying-edges mesh, VTK's gradient normals) against voxlux's "
              "(exact trilinear surface, its own normals), Lambert headlight, values in [0, 1]; "
              "coverage: fraction of pixels hit by one and not the other.\n")
        print("| data | iso | max err (all) | max err (hit) | RMSE | over 0.01 | coverage |")
        print("|---|---|---|---|---|---|---|")
        for row in img_cmp:
            print(row)
        print()

    print("## MIP: teem-mrender and VTK vtkFixedPointVolumeRayCastMapper\n")
    print("Errors against the exact maximum of the trilinear field (reference column); "
          "`all`: every pixel, `hit`: pixels both images cover; over 1%: fraction of "
          "pixels off by more than 1% of the reference's range.\n")
    print("| data | view | peer | step | threads | ms wall / CPU | reference | max err (all) | "
          "max err (hit) | RMSE (all) | over 1% (all) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    mips = sorted(k for k in logs if re.match(r"\w+-mip-\w+-((teem|vtk)-s[0-9.]+|voxlux)$", k))
    for k in mips:
        m = re.match(r"(\w+)-mip-(\w+)-(teem|vtk|voxlux)(?:-s([0-9.]+))?$", k)
        data, view, peer, step = m.groups()
        if peer == "voxlux":
            d = logs[k]
            if d.get("cmd") and d["cmd"] not in cmds:
                cmds.append(d["cmd"])
            print("| %s | %s | voxlux mip (exact) | - | %s | %s | itself | 0 | 0 | 0 | 0 |"
                  % (data, view, d.get("threads", "-"), wc(d, "render_ms", "render_cpu_ms")))
            continue
        d = logs[k]
        if d.get("cmd") and d["cmd"] not in cmds:
            cmds.append(d["cmd"])
        ref = None
        for name in ("voxlux", "ref"):
            p = os.path.join(out, "%s-mip-%s-%s.pfm" % (data, view, name))
            if os.path.exists(p):
                ref = (name, p)
                break
        errs = ["-"] * 4
        img_path = os.path.join(out, k + ".pfm")
        if ref and os.path.exists(img_path):
            r_img = volio.read_image(ref[1])
            p_img = volio.read_image(img_path)
            a = compare.compare(r_img, p_img, "all")
            b = compare.compare(r_img, p_img, "both")
            errs = ["%.4g" % a["max_abs"], "%.4g" % b["max_abs"], "%.4g" % a["rmse"],
                    "%.4f" % a["over"]]
        print("| %s | %s | %s | %s | %s | %s | %s | %s |"
              % (data, view, "teem-mrender (tent)" if peer == "teem" else "VTK fixed-point",
                 step, d.get("threads", "-"), wc(d, "render_ms", "cpu_ms" if peer == "teem"
                                                 else "render_cpu_ms"),
                 ref[0] if ref else "none", " | ".join(errs)))
    print("\nteem: wall = its own \"rendering time\" (gage set-up and rays, not reading the"
          " volume), CPU = the whole teem-mrender process (reading the volume included);"
          " VTK: Render() after a warm-up render; voxlux: `mip --stats` time, CPU of the"
          " whole process (reading the stream included).  voxlux gives rays that miss the"
          " volume its minimum, the peers 0: the same here (both volumes have minimum 0).\n")
    print("## Commands\n")
    print("```")
    for c in cmds:
        print(c)
    print("```")


if __name__ == "__main__":
    main()
