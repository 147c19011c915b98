#!/usr/bin/python3
"""bench_mip.py: voxlux's exact MIP (`mip`) against teem-mrender and VTK's
vtkFixedPointVolumeRayCastMapper, interleaved in one session, with the peers' errors
against our exact maximum and the use-last-t saving.  Run by `make -C examples/bench
bench-mip` under xvfb-run (VTK needs a display); see examples/bench/RESULTS-mip.md.

usage: bench_mip.py --out DIR --bin VX_BIN [--runs N] [--threads "1 2"]
                    [--teem-steps "1 0.5"] [--vtk-steps "1"] [--datasets ch2,vhf]
                    [--views front,oblique] [--timed-views front]
       bench_mip.py --report-only DIR     the tables again from DIR/bench-mip.pickle

Every dataset is one line of DATASETS below: its source, vread's flags and the camera of
each view (the peers' conventions: examples/bench/peers/README.md).  A dataset whose
source is missing is skipped.

What is timed, per round (rounds interleave every configuration, in an order rotated
each round, so that a slow minute of the shared machine hits all of them alike):
  voxlux   mip --scene S --stats -j J [--no-last-t] --hdr: its own render time (--stats:
           wall and CPU of the ray loop; reading the stream excluded)
  teem     mip_teem.sh -n 1 -j J -s STEP: teem-mrender's own "rendering time" (gage
           set-up and rays; reading the volume excluded)
  VTK      mip_vtk.py --runs 1 --threads J --step STEP: one Render() after a warm-up
           render (tables and min-max volume built), wall and process CPU
Tables give medians over the rounds and, for ratios, the median of the per-round ratios
(each ratio pairs two runs of the same round).  Views not in --timed-views run once
(their images for the error table).

Errors: each peer image against voxlux's exact maximum on the same pixel grid (no
resampling: every tool is given the same camera, pixel centres at (i + 0.5) / W, the
lattice's box [origin, origin + (n - 1) spacing], rays along f; misses are 0 in all,
voxlux's miss value being the volume minimum, 0 here).  Max |error|, RMSE, and the
signed extremes.  VTK leaves pixels next to the volume's outline unrendered (0), so its
errors are over the pixels both rendered (the count left out is given).  For the front
views mip_ref.py (an independent exact MIP for axis-aligned views) checks voxlux too.
"""
import argparse
import datetime
import json
import os
import pickle
import platform
import re
import shlex
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PEERS = os.path.join(os.path.dirname(HERE), "peers")
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, PEERS)
import numpy as np  # noqa: E402
import compare  # noqa: E402
import volio  # noqa: E402

PY = "/usr/bin/python3"
DATA = os.environ.get("DATA", "/work/shared/data")

# name: (source, vread flags, {view: camera flags}); world = origin + index * spacing
DATASETS = {
    # MRIcron's ch2 T1 MRI, 181x217x181 u8, 1 mm, origin (-90,-125,-71); face at high y
    "ch2": ("/usr/share/mricron/templates/ch2.nii.gz", [],
            {"front": "--eye 0 600 19 --look 0 -17 19 --up 0 0 1 --ortho 240",
             "oblique": "--eye 329 553 258 --look 0 -17 19 --up 0 0 1 --ortho 260"}),
    # Visible Human Female head CT, 512x512x234 i16, 1 mm; face at low y, z up
    "vhf": (os.path.join(DATA, "vhf_head_ct_512x512x234_int16le.raw.gz"),
            ["--raw", "512,512,234", "--type", "i16"],
            {"front": "--eye 260 -600 117 --look 260 295 117 --up 0 0 1 --ortho 400",
             "oblique": "--eye 683 -438 425 --look 260 295 117 --up 0 0 1 --ortho 420"}),
}
SIZE = "--size 512 512"


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def run(cmd, **kw):
    """Run a command (list), return (stdout + stderr text, wall seconds); fail loudly."""
    t0 = time.perf_counter()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, **kw)
    dt = time.perf_counter() - t0
    if p.returncode != 0:
        sys.exit("bench_mip.py: failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stdout[-2000:]))
    return p.stdout, dt


def sh(cmd):
    """Run a shell pipeline string; fail loudly."""
    p = subprocess.run(cmd, shell=True, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        sys.exit("bench_mip.py: failed: %s\n%s" % (cmd, p.stderr[-2000:]))


def num(pattern, text, what):
    m = re.search(pattern, text)
    if not m:
        sys.exit("bench_mip.py: no %s in:\n%s" % (what, text[-2000:]))
    return float(m.group(1))


class Bench:
    def __init__(self, a):
        self.a = a
        self.out = a.out
        self.vx = a.bin
        self.cmds = {}      # config key -> command line (as run)
        self.times = {}     # config key -> list of dicts per round
        self.stats = {}     # voxlux config key -> stats text
        self.prep_cmds = []

    # ---- preparation: NRRD for the peers, voxlux stream, scenes ----
    def prepare(self, d):
        src, vflags, views = DATASETS[d]
        o = self.out
        vread = [os.path.join(self.vx, "vread")] + vflags + [src]
        nrrd = os.path.join(o, d + ".nrrd")
        vxs = os.path.join(o, d + ".vxs")
        c1 = "%s | %s/vwrite -o %s" % (" ".join(map(shlex.quote, vread)), self.vx, nrrd)
        c2 = "%s | %s/brick | %s/macrocell -o %s" % (" ".join(map(shlex.quote, vread)),
                                                      self.vx, self.vx, vxs)
        for c, f in ((c1, nrrd), (c2, vxs)):
            self.prep_cmds.append(c)
            if not os.path.exists(f):
                log(c)
                sh(c)
        for v, cam in views.items():
            scn = os.path.join(o, "%s-%s.scn" % (d, v))
            c = "%s %s/camera.py scene %s %s > %s" % (PY, PEERS, cam, SIZE, scn)
            self.prep_cmds.append(c)
            sh(c)

    # ---- one run of each tool ----
    def voxlux(self, d, v, j, lastt, keep):
        o = self.out
        img = os.path.join(o, "%s-%s-voxlux%s.vxs" % (d, v, "" if lastt else "-nolt"))
        cmd = [os.path.join(self.vx, "mip"), "--scene", os.path.join(o, "%s-%s.scn" % (d, v)),
               "--stats", "-j", str(j)] + ([] if lastt else ["--no-last-t"]) + \
            ["--hdr", "-o", img if keep else "/dev/null", os.path.join(o, d + ".vxs")]
        text, wall = run(cmd)
        r = {"ms": 1e3 * num(r"threads?, ([0-9.]+) s \(cpu", text, "mip time"),
             "cpu_ms": 1e3 * num(r"\(cpu ([0-9.]+) s\)", text, "mip cpu"),
             "proc_ms": 1e3 * wall,
             "pushes": num(r"queue pushes (\d+)", text, "pushes"),
             "pops": num(r"pops (\d+)", text, "pops"),
             "saved": num(r"saved by last t (\d+)", text, "saved"),
             "cells": num(r"cells solved (\d+)", text, "cells")}
        return cmd, r, text

    def teem(self, d, v, j, step):
        o = self.out
        pfm = os.path.join(o, "%s-%s-teem-s%s.pfm" % (d, v, step))
        cmd = ["sh", os.path.join(PEERS, "mip_teem.sh"), "-n", "1", "-j", str(j), "-s", str(step),
               os.path.join(o, d + ".nrrd"), pfm] + DATASETS[d][2][v].split() + SIZE.split()
        text, wall = run(cmd)
        r = {"ms": num(r"render_ms ([0-9.]+)", text, "teem time"),
             "proc_ms": num(r"wall_ms ([0-9.]+)", text, "teem wall"),
             "proc_cpu_ms": num(r"cpu_ms ([0-9.]+)", text, "teem cpu")}
        return cmd, r, text

    def vtk(self, d, v, j, step):
        o = self.out
        pfm = os.path.join(o, "%s-%s-vtk-s%s.pfm" % (d, v, step))
        cmd = [PY, os.path.join(PEERS, "mip_vtk.py"), os.path.join(o, d + ".nrrd"), "-o", pfm,
               "--step", str(step), "--runs", "1", "--threads", str(j)] + \
            DATASETS[d][2][v].split() + SIZE.split()
        text, wall = run(cmd)
        r = {"ms": num(r"render_ms ([0-9.]+)", text, "vtk time"),
             "cpu_ms": num(r"render_cpu_ms ([0-9.]+)", text, "vtk cpu"),
             "proc_ms": 1e3 * wall}
        return cmd, r, text

    def configs(self, d, v):
        a = self.a
        out = []
        for j in a.threads:
            for lastt in (True, False):
                out.append((("voxlux", d, v, j, lastt), lambda j=j, lt=lastt, k=False:
                            self.voxlux(d, v, j, lt, k)))
            for s in a.teem_steps:
                out.append((("teem", d, v, j, s), lambda j=j, s=s: self.teem(d, v, j, s)))
            for s in a.vtk_steps:
                out.append((("vtk", d, v, j, s), lambda j=j, s=s: self.vtk(d, v, j, s)))
        return out

    def go(self):
        a = self.a
        os.makedirs(self.out, exist_ok=True)
        self.datasets = [d for d in a.datasets if os.path.exists(DATASETS[d][0])]
        self.skipped = [d for d in a.datasets if d not in self.datasets]
        for d in self.skipped:
            log("bench_mip.py: %s: %s is absent, skipped" % (d, DATASETS[d][0]))
        for d in self.datasets:
            self.prepare(d)
        self.load = [os.getloadavg()]
        self.t_start = datetime.datetime.now()
        # the images: one run of everything, each view (also the untimed ones)
        for d in self.datasets:
            for v in a.views:
                for lt in (True, False):
                    cmd, r, text = self.voxlux(d, v, 1, lt, True)
                    self.cmds[("image", d, v, lt)] = cmd
                if v not in a.timed_views:
                    for key, fn in self.configs(d, v):
                        if key[3] != a.threads[0]:
                            continue
                        cmd, r, text = fn()
                        self.cmds[key] = cmd
                        self.times.setdefault(key, []).append(r)
                        if key[0] == "voxlux":
                            self.stats[key] = text
        # the timed rounds
        work = [c for d in self.datasets for v in a.timed_views for c in self.configs(d, v)]
        for rnd in range(a.runs):
            k = (rnd * 7) % len(work)
            order = work[k:] + work[:k]
            log("round %d of %d (%d runs)" % (rnd + 1, a.runs, len(order)))
            for key, fn in order:
                cmd, r, text = fn()
                self.cmds[key] = cmd
                self.times.setdefault(key, []).append(r)
                if key[0] == "voxlux":
                    self.stats[key] = text
            self.load.append(os.getloadavg())
        self.t_end = datetime.datetime.now()
        self.images()
        with open(os.path.join(self.out, "bench-mip.pickle"), "wb") as fh:
            pickle.dump({k: v for k, v in self.__dict__.items() if k != "a"} |
                        {"args": vars(self.a)}, fh)
        self.report()

    # ---- images and errors ----
    def images(self):
        o, a = self.out, self.a
        self.errors = []
        for d in self.datasets:
            for v in a.views:
                ours_vxs = os.path.join(o, "%s-%s-voxlux.vxs" % (d, v))
                ours = os.path.join(o, "%s-%s-voxlux.pfm" % (d, v))
                cmd = [os.path.join(self.vx, "tonemap"), "--pfm", "--name", "mip", "-o", ours, ours_vxs]
                run(cmd)
                self.cmds[("tonemap", d, v)] = cmd
                same = run([PY, os.path.join(ROOT, "tests", "cli", "vximg.py"), "same", ours_vxs,
                            os.path.join(o, "%s-%s-voxlux-nolt.vxs" % (d, v))])[0].strip()
                ref = volio.read_image(ours)
                lo, hi = float(ref.min()), float(ref.max())
                row = {"data": d, "view": v, "lastt_same": same, "range": (lo, hi), "peers": []}
                if v == "front":
                    rp = os.path.join(o, "%s-%s-ref.pfm" % (d, v))
                    cmd = [PY, os.path.join(PEERS, "mip_ref.py"), os.path.join(o, d + ".nrrd"),
                           "-o", rp] + DATASETS[d][2][v].split() + SIZE.split()
                    if not os.path.exists(rp):
                        run(cmd)
                    self.cmds[("ref", d, v)] = cmd
                    r = compare.compare(volio.read_image(rp), ref)
                    row["ref"] = r
                pngs = [("voxlux mip (exact)", ref)]
                for tool, steps in (("teem", a.teem_steps), ("vtk", a.vtk_steps)):
                    for s in steps:
                        p = os.path.join(o, "%s-%s-%s-s%s.pfm" % (d, v, tool, s))
                        if not os.path.exists(p):
                            continue
                        img = volio.read_image(p)
                        mask = "both" if tool == "vtk" else "all"
                        r = compare.compare(ref, img, mask)
                        sel = np.isfinite(img) & ((ref != 0) & (img != 0) if mask == "both" else True)
                        diff = np.where(sel, img - ref, 0.0)
                        r["signed_min"] = float(diff.min())
                        r["signed_max"] = float(diff.max())
                        r["left_out"] = int(((ref != 0) & (img == 0)).sum()) if mask == "both" else 0
                        r["under_frac"] = float(np.mean(diff[sel] < -1e-3 * (hi - lo)))
                        r["p99"] = float(np.percentile(np.abs(diff[sel]), 99))
                        row["peers"].append((tool, s, r))
                        pngs.append(("%s step %s" % ("teem-mrender" if tool == "teem" else "VTK", s), img))
                        volio.write_png_gray(os.path.join(o, "%s-%s-%s-s%s.png" % (d, v, tool, s)),
                                             img, lo, hi)
                        # under-estimate map: ours - peer, white = peer lower by 5% of range
                        volio.write_png_gray(os.path.join(o, "%s-%s-%s-s%s-under.png" % (d, v, tool, s)),
                                             np.where(sel, ref - img, 0.0), 0.0, 0.05 * (hi - lo))
                volio.write_png_gray(os.path.join(o, "%s-%s-voxlux.png" % (d, v)), ref, lo, hi)
                # one picture with all of them side by side, same window
                tiles = [np.clip((t - lo) / ((hi - lo) or 1), 0, 1) for _, t in pngs]
                gap = np.ones((ref.shape[0], 8))
                strip = np.concatenate(sum([[t, gap] for t in tiles], [])[:-1], axis=1)
                volio.write_png_gray(os.path.join(o, "%s-%s-side-by-side.png" % (d, v)), strip, 0, 1)
                row["tiles"] = [n for n, _ in pngs]
                self.errors.append(row)

    # ---- the report ----
    def med(self, key, field):
        xs = [r[field] for r in self.times.get(key, []) if field in r]
        return statistics.median(xs) if xs else None

    def ratio(self, k1, k2, field="ms"):
        """Median over rounds of t(k1) / t(k2), pairing runs of the same round."""
        xs = [r1[field] / r2[field] for r1, r2 in zip(self.times.get(k1, []), self.times.get(k2, []))
              if field in r1 and field in r2 and r2[field] > 0]
        return statistics.median(xs) if xs else None

    def report(self):
        a, L = self.a, []
        f = lambda x, p="%.0f": "-" if x is None else p % x  # noqa: E731
        host = platform.node()
        cpu = ""
        try:
            with open("/proc/cpuinfo") as fh:
                cpu = next(line.split(":", 1)[1].strip() for line in fh if line.startswith("model name"))
        except (OSError, StopIteration):
            pass
        L.append("Date: %s to %s.  Machine: %s, %s, %d cores (shared; load average %s at the"
                 " start, %s at the end).  Kernel %s.  Rounds: %d (medians; ratios are medians of"
                 " per-round ratios).  Images 512x512."
                 % (self.t_start.strftime("%Y-%m-%d %H:%M"), self.t_end.strftime("%H:%M"), host,
                    cpu, os.cpu_count(), " ".join("%.1f" % x for x in self.load[0]),
                    " ".join("%.1f" % x for x in self.load[-1]), platform.release(), a.runs))
        if self.skipped:
            L.append("\nSkipped (data absent): %s." % ", ".join(self.skipped))
        for v in a.timed_views:
            L.append("\n### Time, %s view (ms, median of %d; wall / CPU where both)\n" % (v, a.runs))
            L.append("| data | threads | voxlux mip | voxlux --no-last-t | VTK step %s |"
                     % " | VTK step ".join(a.vtk_steps) +
                     " teem step %s |" % " | teem step ".join(a.teem_steps) +
                     " voxlux / VTK (wall, CPU) | teem / voxlux |")
            L.append("|---" * (6 + len(a.vtk_steps) + len(a.teem_steps)) + "|")
            for d in self.datasets:
                for j in a.threads:
                    ours, nolt = ("voxlux", d, v, j, True), ("voxlux", d, v, j, False)
                    cells = ["%s" % d, "%d" % j,
                             "%s / %s" % (f(self.med(ours, "ms")), f(self.med(ours, "cpu_ms"))),
                             "%s / %s" % (f(self.med(nolt, "ms")), f(self.med(nolt, "cpu_ms")))]
                    for s in a.vtk_steps:
                        k = ("vtk", d, v, j, s)
                        cells.append("%s / %s" % (f(self.med(k, "ms")), f(self.med(k, "cpu_ms"))))
                    for s in a.teem_steps:
                        cells.append(f(self.med(("teem", d, v, j, s), "ms")))
                    vt = ("vtk", d, v, j, a.vtk_steps[0])
                    cells.append("%s, %s" % (f(self.ratio(ours, vt), "%.2f"),
                                             f(self.ratio(ours, vt, "cpu_ms"), "%.2f")))
                    cells.append(", ".join("%s (step %s)" % (f(self.ratio(("teem", d, v, j, s), ours), "%.1f"), s)
                                           for s in a.teem_steps))
                    L.append("| " + " | ".join(cells) + " |")
            L.append("\n### Use last t (%s view): the lower bound's saving\n" % v)
            L.append("| data | threads | queue pushes (bound on) | pushes (off) | pushes saved |"
                     " pops (both) | cells solved (both) | time on / off (wall, CPU) | same image |")
            L.append("|---|---|---|---|---|---|---|---|---|")
            for d in self.datasets:
                for j in a.threads:
                    on, off = ("voxlux", d, v, j, True), ("voxlux", d, v, j, False)
                    r_on, r_off = self.times[on][-1], self.times[off][-1]
                    same = next((e["lastt_same"] for e in self.errors if e["data"] == d and e["view"] == v), "?")
                    L.append("| %s | %d | %.0f | %.0f | %.0f (%.0f%%) | %.0f | %.0f | %s, %s | %s |"
                             % (d, j, r_on["pushes"], r_off["pushes"], r_on["saved"],
                                100 * (1 - r_on["pushes"] / r_off["pushes"]) if r_off["pushes"] else 0,
                                r_on["pops"],
                                r_on["cells"], f(self.ratio(on, off), "%.2f"),
                                f(self.ratio(on, off, "cpu_ms"), "%.2f"), same))
        L.append("\n### Peers' error against the exact maximum (data units)\n")
        L.append("| data | view | range | peer | step | max abs error (at pixel) | 99th percentile |"
                 " RMSE | most under / over | pixels under by > 0.1% of range |"
                 " left out (VTK: unrendered) |")
        L.append("|---|---|---|---|---|---|---|---|---|---|---|")
        for e in self.errors:
            lo, hi = e["range"]
            if "ref" in e:
                r = e["ref"]
                L.append("| %s | %s | %.0f..%.0f | voxlux vs mip_ref.py | - | %.3g | - | %.3g | - | - | - |"
                         % (e["data"], e["view"], lo, hi, r["max_abs"], r["rmse"]))
            for tool, s, r in e["peers"]:
                L.append("| %s | %s | %.0f..%.0f | %s | %s | %.1f (%.1f%%) at (%d,%d) | %.1f | %.2f |"
                         " %.1f / +%.1f | %.1f%% | %d |"
                         % (e["data"], e["view"], lo, hi, "teem-mrender" if tool == "teem" else "VTK",
                            s, r["max_abs"], 100 * r["max_abs"] / ((hi - lo) or 1), r["x"], r["y"],
                            r["p99"], r["rmse"], r["signed_min"], r["signed_max"],
                            100 * r["under_frac"], r["left_out"]))
        L.append("\nPictures (in %s): D-V-side-by-side.png (%s, one window: the exact"
                 " range), D-V-TOOL-sS-under.png (exact minus peer, white = 5%% of the range)."
                 % (self.out, ", ".join(self.errors[0]["tiles"]) if self.errors else ""))
        L.append("\n### Commands\n")
        L.append("```")
        L.extend(self.prep_cmds)
        seen = set()
        for k, c in sorted(self.cmds.items(), key=lambda kv: str(kv[0])):
            s = " ".join(shlex.quote(x) for x in c)
            if s not in seen:
                seen.add(s)
                L.append(s)
        L.append("```")
        text = "\n".join(L) + "\n"
        with open(os.path.join(self.out, "bench-mip.md"), "w") as fh:
            fh.write(text)
        with open(os.path.join(self.out, "bench-mip.json"), "w") as fh:
            json.dump({"times": {" ".join(map(str, k)): v for k, v in self.times.items()},
                       "errors": [{kk: vv for kk, vv in e.items() if kk != "peers"} |
                                  {"peers": [(t, s, {kk: vv for kk, vv in r.items() if kk != "diff"})
                                             for t, s, r in e["peers"]]} for e in self.errors]},
                      fh, indent=1, default=str)
        print(text)


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--report-only":
        with open(os.path.join(sys.argv[2], "bench-mip.pickle"), "rb") as fh:
            st = pickle.load(fh)
        b = Bench(argparse.Namespace(**st.pop("args")))
        b.__dict__.update(st)
        b.report()
        return
    p = argparse.ArgumentParser(description="voxlux mip against teem-mrender and VTK")
    p.add_argument("--out", required=True)
    p.add_argument("--bin", required=True, help="voxlux's bin directory")
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--threads", default="1 2")
    p.add_argument("--teem-steps", default="1 0.5")
    p.add_argument("--vtk-steps", default="1")
    p.add_argument("--datasets", default="ch2,vhf")
    p.add_argument("--views", default="front,oblique")
    p.add_argument("--timed-views", default="front")
    a = p.parse_args()
    a.threads = [int(x) for x in a.threads.split()]
    a.teem_steps = a.teem_steps.split()
    a.vtk_steps = a.vtk_steps.split()
    a.datasets = [x for x in a.datasets.split(",") if x]
    a.views = [x for x in a.views.split(",") if x]
    a.timed_views = [x for x in a.timed_views.split(",") if x]
    a.bin = os.path.abspath(a.bin)
    a.out = os.path.abspath(a.out)
    for d in a.datasets:
        if d not in DATASETS:
            p.error("unknown dataset %s" % d)
    if a.runs < 1 or not set(a.timed_views) <= set(a.views):
        p.error("--runs >= 1, and timed views among --views")
    Bench(a).go()


if __name__ == "__main__":
    main()
