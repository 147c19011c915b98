#!/usr/bin/python3
"""bench-tet: isosurfaces of the three CFD tet meshes, voxlux against VTK + Embree.

usage: bench.py [--bin DIR] [--embree PROG] [--data DIR] [--runs N] [--threads N]
                [--out DIR] [--only NAME]

For each mesh (bluntfin, comb, post from --data, *_tets.vtk.gz) and its isovalue and
camera (MESHES below), RUNS rounds, the tools interleaved within each round:
  voxlux  vread MESH.vtk (import, process wall time)
          macrocell --stats (leaf grid + levels: build time and bytes per tet)
          raycast --scene --stats --hdr (frame time: raycast's own render time; peak RSS)
  peers   contour.py --method filter (vtkUnstructuredGridReader time, vtkContourFilter time)
          contour.py --method linear (vtkContour3DLinearGrid time)
          embree_render -n 1 -b 1 (BVH build and frame time of the filter's triangles)
Every process's peak RSS comes from wait4().  Reported: medians over the rounds.  The
same camera (../peers/camera.py: the scene embree_render's Lambert headlight equals) and
512x512 pixels on both sides; coverage is compared pixel by pixel (coverage.py) and the
pictures are written as PNGs.  Writes OUT/results.md (table + commands) and prints it.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PEERS = os.path.join(HERE, "..", "peers")
PY = sys.executable

# name: (file, isovalue, camera flags); cameras look at the box centre from azimuth,
# elevation (-60, 35), (-50, 25) and (-70, 55) degrees, fov 30, the box's bounding
# sphere filling the view.
MESHES = {
    "bluntfin": ("bluntfin_tets.vtk.gz", 1.2,
                 "--eye 23.52 -30.91 31.22 --look 3.273 4.164 2.862 --up 0 0 1 --fov 30"),
    "comb": ("comb_tets.vtk.gz", 0.4,
             "--eye 36.38 -33.51 50.16 --look 8.255 0 29.76 --up 0 0 1 --fov 30"),
    "post": ("post_tets.vtk.gz", 2.5,
             "--eye 15.4 -42.4 51.4 --look 0 0 2.41 --up 0 0 1 --fov 30"),
}


def run(cmd, log, env=None):
    """Run cmd (list), stdout+stderr into log; returns (wall seconds, peak RSS MiB, text)."""
    with open(log, "w") as f:
        f.write("cmd: %s\n" % " ".join(cmd))
        f.flush()
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT, env=env)
        _, status, ru = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
        p.returncode = os.waitstatus_to_exitcode(status)
    text = open(log).read()
    if p.returncode != 0:
        sys.exit("bench.py: %s failed (%d):\n%s" % (cmd[0], p.returncode, text[-2000:]))
    return wall, ru.ru_maxrss / 1024.0, text


def grab(pattern, text, what):
    m = re.search(pattern, text, re.M)
    if not m:
        sys.exit("bench.py: no %s in:\n%s" % (what, text[-2000:]))
    return float(m.group(1))


def med(v):
    return statistics.median(v)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default=os.path.join(HERE, "..", "..", "..", "bin"))
    ap.add_argument("--embree", default=os.path.join(HERE, "..", "out", "embree_render"))
    ap.add_argument("--data", default="/work/shared/data")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--threads", type=int, default=os.cpu_count())
    ap.add_argument("--out", default=os.path.join(HERE, "..", "out", "tet"))
    ap.add_argument("--only")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    b = lambda p: os.path.join(a.bin, p)
    o = lambda p: os.path.join(a.out, p)
    nt = str(a.threads)
    rows, cmds = [], []
    for name, (src, iso, cam) in MESHES.items():
        if a.only and name != a.only:
            continue
        cam = cam.split()
        vtk = o(name + ".vtk")
        if not os.path.exists(vtk):
            subprocess.run("gzip -dc %s > %s.tmp && mv %s.tmp %s" % (
                os.path.join(a.data, src), vtk, vtk, vtk), shell=True, check=True)
        scn = o(name + ".scn")
        with open(scn, "w") as f:
            subprocess.run([PY, os.path.join(PEERS, "camera.py"), "scene", "--iso", str(iso)]
                           + cam + ["--size", "512", "512"], stdout=f, check=True)
        steps = [
            ("vread", [b("vread"), vtk, "-o", o(name + ".vx")]),
            ("macrocell", [b("macrocell"), "--stats", "-j", nt, "-o", o(name + ".vxm"),
                           o(name + ".vx")]),
            ("raycast", [b("raycast"), "--scene", scn, "--stats", "--hdr", "-j", nt,
                         "--depth", o(name + "-vx-depth.pfm"), "-o", o(name + "-vx.vxs"),
                         o(name + ".vxm")]),
            ("filter", [PY, os.path.join(HERE, "contour.py"), vtk, "--iso", str(iso),
                        "--method", "filter", "--runs", "1", "--threads", nt,
                        "-o", o(name + ".mesh")]),
            ("linear", [PY, os.path.join(HERE, "contour.py"), vtk, "--iso", str(iso),
                        "--method", "linear", "--runs", "1", "--threads", nt,
                        "-o", o(name + "-linear.mesh")]),
            ("embree", [a.embree, "-m", o(name + ".mesh"), "-o", o(name + "-em.pfm")] + cam
             + ["-j", nt, "-n", "1", "-b", "1", "--size", "512", "512"]),
        ]
        if not cmds:
            cmds = [" ".join(c) for _, c in steps]
        m = {k: [] for k in ("vread", "vread_rss", "build", "bpt", "mesh_bpt", "frame",
                             "rc_wall", "rc_rss", "read", "contour", "filter_rss", "linear",
                             "tris", "bvh", "emframe", "em_rss", "covered", "tets_per_ray",
                             "entries_per_ray")}
        for r in range(a.runs):
            for step, cmd in steps:
                wall, rss, t = run(cmd, o("%s-%s.log" % (name, step)))
                if step == "vread":
                    m["vread"].append(wall)
                    m["vread_rss"].append(rss)
                elif step == "macrocell":
                    m["build"].append(grab(r"build ([0-9.]+) s", t, "build time"))
                    m["bpt"].append(grab(r"= ([0-9.]+) B/tet", t, "bytes per tet"))
                    m["mesh_bpt"].append(grab(r"the mesh itself ([0-9.]+) B/tet", t, "mesh"))
                elif step == "raycast":
                    m["frame"].append(grab(r"^raycast: 512x512, \d+ threads?, ([0-9.]+) s", t,
                                           "frame time"))
                    m["rc_wall"].append(wall)
                    m["rc_rss"].append(rss)
                    m["covered"].append(grab(r"covered pixels ([0-9.]+)%", t, "coverage"))
                    m["tets_per_ray"].append(grab(r"tets tested \d+ \(([0-9.]+) per ray", t,
                                                  "tets"))
                    m["entries_per_ray"].append(grab(r"list entries \d+ \(([0-9.]+) per ray",
                                                     t, "entries"))
                elif step == "filter":
                    m["read"].append(grab(r"^read_s ([0-9.]+)", t, "read time"))
                    m["contour"].append(grab(r"^contour_s ([0-9.]+)", t, "contour time"))
                    m["filter_rss"].append(rss)
                    m["tris"].append(grab(r"^tris (\d+)", t, "triangles"))
                elif step == "linear":
                    m["linear"].append(grab(r"^contour_s ([0-9.]+)", t, "contour time"))
                else:
                    m["bvh"].append(grab(r"^build_ms ([0-9.]+)", t, "BVH build") / 1e3)
                    m["emframe"].append(grab(r"^render_ms ([0-9.]+)", t, "frame") / 1e3)
                    m["em_rss"].append(rss)
            print("%s: round %d of %d done" % (name, r + 1, a.runs), file=sys.stderr)
        # pictures and coverage (last round)
        subprocess.run([b("tonemap"), "--pfm", "--name", "color", "-o", o(name + "-vx.pfm"),
                        o(name + "-vx.vxs")], check=True)
        for p in ("vx", "em"):
            subprocess.run([PY, os.path.join(PEERS, "volio.py"), "topng",
                            o("%s-%s.pfm" % (name, p)), o("%s-%s.png" % (name, p))], check=True)
        cov = subprocess.run([PY, os.path.join(HERE, "coverage.py"),
                              o(name + "-vx-depth.pfm"), o(name + "-em.pfm"),
                              "--diff-png", o(name + "-cov.png")],
                             check=True, capture_output=True, text=True).stdout
        open(o(name + "-coverage.txt"), "w").write(cov)
        mm = {k: med(v) for k, v in m.items()}
        mm["cov"] = cov.strip().replace("\n", "; ")
        mm["name"], mm["iso"] = name, iso
        rows.append(mm)

    ntet = {"bluntfin": 187395, "comb": 215040, "post": 513375}
    out = []
    out.append("Medians of %d interleaved rounds, %s threads, 512x512, one isovalue per mesh."
               % (a.runs, nt))
    out.append("")
    out.append("| mesh (tets) | iso | voxlux import | VTK read | ratio | leaf grid build "
               "| leaf grid | voxlux frame | Embree frame | ratio |")
    out.append("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in rows:
        out.append("| %s (%d) | %g | %.3f s | %.3f s | %.2f | %.3f s (%.2f us/tet) | %.1f B/tet "
                   "(+ mesh %.1f) | %.3f s | %.4f s | %.1f |" % (
                       r["name"], ntet.get(r["name"], 0), r["iso"], r["vread"], r["read"],
                       r["vread"] / r["read"], r["build"],
                       1e6 * r["build"] / ntet.get(r["name"], 1), r["bpt"], r["mesh_bpt"],
                       r["frame"], r["emframe"], r["frame"] / r["emframe"]))
    out.append("")
    out.append("A new isovalue: voxlux draws it directly (one frame, the leaf grid does not "
               "depend on the isovalue); the peers extract, build a BVH, then draw.")
    out.append("")
    out.append("| mesh | voxlux frame | vtkContourFilter | vtkContour3DLinearGrid | triangles "
               "| Embree BVH | Embree frame | peers total (filter / linear) | ratio voxlux / "
               "peers (filter / linear) |")
    out.append("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in rows:
        tf = r["contour"] + r["bvh"] + r["emframe"]
        tl = r["linear"] + r["bvh"] + r["emframe"]
        out.append("| %s | %.3f s | %.3f s | %.3f s | %d | %.4f s | %.4f s | %.3f / %.3f s "
                   "| %.2f / %.2f |" % (r["name"], r["frame"], r["contour"], r["linear"],
                                        r["tris"], r["bvh"], r["emframe"], tf, tl,
                                        r["frame"] / tf, r["frame"] / tl))
    out.append("")
    out.append("| mesh | raycast process (load + frame) | raycast peak RSS | contour.py peak RSS "
               "| embree_render peak RSS | covered | tets tested / entries per ray | coverage "
               "against Embree |")
    out.append("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in rows:
        out.append("| %s | %.3f s | %.0f MiB | %.0f MiB | %.0f MiB | %.1f%% | %.1f / %.1f | %s |"
                   % (r["name"], r["rc_wall"], r["rc_rss"], r["filter_rss"], r["em_rss"],
                      r["covered"], r["tets_per_ray"], r["entries_per_ray"], r["cov"]))
    out.append("")
    out.append("Commands (one round, bluntfin; the others alike):")
    out.append("")
    for c in cmds:
        out.append("    " + c)
    text = "\n".join(out) + "\n"
    open(o("results.md"), "w").write(text)
    print(text)


if __name__ == "__main__":
    main()
