#!/usr/bin/python3
"""dvrpeers.py: voxlux's dvr against teem-miter and VTK's vtkFixedPointVolumeRayCastMapper
on the CT and MRI heads (issue 23's peer benchmark), every run of every tool interleaved
round by round.  Run by `make -C examples/bench dvr-peers` under xvfb-run (VTK needs a
display); the results and how to read them: examples/bench/RESULTS-dvr.md, "Peers".

usage: dvrpeers.py --out DIR --bin VX_BIN [--runs N] [--threads N] [--datasets vhf,ch2]
       dvrpeers.py --report-only DIR     the tables again from DIR/dvr-peers.json

Each dataset is one line of DATASETS: its source, vread's flags, the voxlux scene whose
camera and transfer function every tool renders, and the value range of miter's txf.
A dataset whose source is missing is skipped.  Every tool gets the same volume (one
NRRD written by vread | vwrite; voxlux reads vread | macrocell), the same camera
(peers/camera.py's convention; an auto camera framed as voxlux frames it,
peers/dvr_tf.py camera), 512x512, samples 1 world unit (= one voxel here) apart, the
opacity given for that reference step, and the same thread count (--threads: dvr -j,
teem-miter -nt, VTK's mapper SetNumberOfThreads).

What runs, per dataset and round (rounds rotate the order, so that a slow minute of the
shared machine hits every configuration alike):
  miter         peers/dvr_miter.sh -n 1: unshaded (-ss none), step 1, ref 1, tent kernel;
                teem's own "rendering time" (reading excluded)
  vtk           peers/dvr_vtk.py --runs 1: composite, unshaded; one Render() after a
                warm-up render (tables, min-max volume)
  vtk-shaded    the same with ShadeOn (VTK's local Phong, the scene's key light); the
                warm-up also builds the encoded gradient normals (first_ms)
  vx-unshaded   dvr, the scene's colour and opacity lists only, `light none`, ambient
                1, effects none (dvr_tf.py scene VARIANT)
  vx-local      dvr, the scene's lights and surface list, effects specular: local
                Blinn-Phong only, no light buffer
  vx-lit        dvr, the scene as it is: volumetric shadows and scattering
voxlux's time is the frame dvr --stats reports (reading the stream and building
macrocells excluded: the macrocells come with the stream).  Every tool's process wall
time is recorded too (it includes reading the volume, and VTK's Python start and
warm-up render), and CPU time (user + system): teem-miter's whole process, VTK's
process during the timed Render(), dvr's whole process (os.wait4's usage; reading the
stream, measured once by `dvr -n`, is a small part).  On a machine shared with other
jobs the wall times swing by several times from one run to the next; CPU time swings
far less, so the tables give both.

Ratios pair two runs of the same round; the tables give the median of the per-round
ratios and the ratio of the minima, of wall and of CPU time.

Pictures: before the rounds, miter renders once more with early ray termination off
(-n1 1: it composites every sample; dvr stops at transmittance 0.001), and dvr unshaded
once more with --no-jitter (its samples on the slice planes, which miter samples too;
by default dvr shifts each eye ray's samples by a per-pixel fraction of a slice).  That
picture is compared with miter -n1 1, with the timed miter picture (-n1 0.99) and with
VTK's unshaded one, and the timed (jittered) dvr picture with miter -n1 1: relative
RMSE of the premultiplied RGB over the pixels either image covers (any channel > 0),
divided by voxlux's mean there (tests/cli/vximg.py relrmse-all's measure), and the
relative difference of the means.  D-side-by-side.png holds the pictures, D-diff.png
the absolute differences (times 10, linear codes: white is a difference of 0.1).
"""
import argparse
import datetime
import json
import os
import platform
import shlex
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PEERS = os.path.join(HERE, "peers")
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, PEERS)
import numpy as np  # noqa: E402
import dvr_tf  # noqa: E402
import volio  # noqa: E402

PY = "/usr/bin/python3"
DATA = os.environ.get("DATA", "/work/shared/data")
SCENES = os.path.join(ROOT, "examples", "scenes")


def ch2_source():
    p = "/usr/share/mricron/templates/ch2.nii.gz"
    return p if os.path.exists(p) else os.path.join(DATA, "ch2_mri_181x217x181_uint8.nii.gz")


# name: (source, vread flags, scene, txf value range)
DATASETS = {
    # Visible Human Female head CT, 512x512x234 i16 (0..4087), 1 mm
    "vhf": (os.path.join(DATA, "vhf_head_ct_512x512x234_int16le.raw.gz"),
            ["--raw", "512,512,234", "--type", "i16"],
            os.path.join(SCENES, "head-ct-dvr.scn"), (0.0, 4095.0)),
    # MRIcron's ch2 T1 MRI, 181x217x181 u8, 1 mm
    "ch2": (ch2_source(), [], os.path.join(SCENES, "head-dvr.scn"), (0.0, 255.0)),
}
TOOLS = ("miter", "vtk", "vtk-shaded", "vx-unshaded", "vx-local", "vx-lit")
NAMES = {"miter": "teem-miter, unshaded", "vtk": "VTK fixed-point, unshaded",
         "vtk-shaded": "VTK fixed-point, shaded (local Phong)",
         "vx-unshaded": "voxlux dvr, unshaded (effects none)",
         "vx-local": "voxlux dvr, local (surface term, no light buffer)",
         "vx-lit": "voxlux dvr, volumetric shadows + scattering"}


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def run(cmd):
    """Run a command (list); (stdout + stderr, wall seconds, CPU seconds of the process
    and the children it waited for, user + system); fail loudly."""
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    out = p.stdout.read()
    _, status, ru = os.wait4(p.pid, 0)
    dt = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    p.stdout.close()
    if p.returncode != 0:
        sys.exit("dvrpeers.py: failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), out[-2000:]))
    return out, dt, ru.ru_utime + ru.ru_stime


def sh(cmd):
    p = subprocess.run(cmd, shell=True, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        sys.exit("dvrpeers.py: failed: %s\n%s" % (cmd, p.stderr[-2000:]))


def num(key, text):
    for line in text.splitlines():
        w = line.split()
        if len(w) >= 2 and w[0] == key:
            return float(w[1])
    sys.exit("dvrpeers.py: no %s in:\n%s" % (key, text[-2000:]))


class Bench:
    def __init__(self, a):
        self.a = a
        self.out = a.out
        self.vx = a.bin
        self.cmds = {}
        self.times = {}          # "D tool" -> [ {ms, proc_ms, ...} per round ]
        self.prep = []
        self.cam = {}
        self.stats = {}
        self.read_cpu = {}

    def path(self, *parts):
        return os.path.join(self.out, *parts)

    def prepare(self, d):
        src, vflags, scene, rng = DATASETS[d]
        vread = " ".join(shlex.quote(x) for x in [os.path.join(self.vx, "vread")] + vflags + [src])
        nrrd, vxs = self.path(d + ".nrrd"), self.path(d + ".vxs")
        for c, f in (("%s | %s/vwrite -o %s" % (vread, self.vx, nrrd), nrrd),
                     ("%s | %s/macrocell -o %s" % (vread, self.vx, vxs), vxs)):
            self.prep.append(c)
            if not os.path.exists(f):
                log(c)
                sh(c)
        lines = dvr_tf.parse_scene(scene)
        self.cam[d] = dvr_tf.camera_flags(lines, nrrd)
        self.prep.append("%s %s/dvr_tf.py camera %s %s   # %s" % (
            PY, PEERS, scene, nrrd, " ".join(self.cam[d])))
        for v in ("unshaded", "local", "lit"):
            with open(self.path("%s-%s.scn" % (d, v)), "w") as fh:
                fh.write(dvr_tf.variant_scene(lines, v, self.cam[d]))
            self.prep.append("%s %s/dvr_tf.py scene %s %s CAMERA > %s" % (
                PY, PEERS, scene, v, self.path("%s-%s.scn" % (d, v))))
        c = [PY, os.path.join(PEERS, "dvr_tf.py"), "txf", scene, self.path(d + ".txf"),
             "--range", str(rng[0]), str(rng[1])]
        self.prep.append(" ".join(c))
        run(c)
        # what reading the stream costs dvr (its plan, no frame): in voxlux's CPU time
        c = [os.path.join(self.vx, "dvr"), "--scene", self.path(d + "-lit.scn"), "-n",
             self.path(d + ".vxs")]
        self.read_cpu[d] = 1e3 * min(run(c)[2] for _ in range(3))
        self.prep.append(" ".join(c) + "   # CPU %.0f ms (reading, planning)" % self.read_cpu[d])

    # ---- one run of each tool ----
    def miter(self, d, near1="0.99", tag="miter"):
        cmd = ["sh", os.path.join(PEERS, "dvr_miter.sh"), "-n", "1", "-j", str(self.a.threads),
               "-t", near1, self.path(d + ".nrrd"), self.path(d + ".txf"),
               self.path("%s-%s.pfm" % (d, tag))] + self.cam[d]
        text, wall, cpu = run(cmd)
        return cmd, {"ms": num("render_ms", text), "proc_ms": num("wall_ms", text),
                     "cpu_ms": num("cpu_ms", text)}

    def vtk(self, d, shade):
        tag = "vtk-shaded" if shade else "vtk"
        cmd = [PY, os.path.join(PEERS, "dvr_vtk.py"), self.path(d + ".nrrd"),
               "--scene", DATASETS[d][2], "-o", self.path("%s-%s.pfm" % (d, tag)),
               "--runs", "1", "--threads", str(self.a.threads)] + \
            (["--shade"] if shade else []) + self.cam[d]
        text, wall, cpu = run(cmd)
        return cmd, {"ms": num("render_ms", text), "cpu_ms": num("render_cpu_ms", text),
                     "first_ms": num("first_ms", text), "proc_ms": 1e3 * wall}

    def voxlux(self, d, v, extra=(), suffix=""):
        tag = "vx-" + v + suffix
        cmd = [os.path.join(self.vx, "dvr"), "--scene", self.path("%s-%s.scn" % (d, v)),
               "-j", str(self.a.threads), "--stats"] + list(extra) + \
            ["--pfm", self.path("%s-%s.pfm" % (d, tag)),
             "-o", self.path("%s-%s.png" % (d, tag)), self.path(d + ".vxs")]
        text, wall, cpu = run(cmd)
        ms = None
        for line in text.splitlines():
            w = line.split()
            if len(w) >= 6 and w[0] == "dvr:" and w[2] == "slices," and w[-1] == "s":
                ms = 1e3 * float(w[-2])
        if ms is None:
            sys.exit("dvrpeers.py: no frame time in dvr --stats:\n" + text)
        self.stats[d + " " + tag] = text.strip()
        return cmd, {"ms": ms, "proc_ms": 1e3 * wall, "cpu_ms": 1e3 * cpu}

    def configs(self, d):
        return [("miter", lambda: self.miter(d)),
                ("vtk", lambda: self.vtk(d, False)),
                ("vtk-shaded", lambda: self.vtk(d, True)),
                ("vx-unshaded", lambda: self.voxlux(d, "unshaded")),
                ("vx-local", lambda: self.voxlux(d, "local")),
                ("vx-lit", lambda: self.voxlux(d, "lit"))]

    def go(self):
        a = self.a
        os.makedirs(self.out, exist_ok=True)
        self.datasets = [d for d in a.datasets if os.path.exists(DATASETS[d][0])]
        self.skipped = [d for d in a.datasets if d not in self.datasets]
        for d in self.skipped:
            log("dvrpeers.py: %s: %s is absent, skipped" % (d, DATASETS[d][0]))
        for d in self.datasets:
            self.prepare(d)
        self.load = [os.getloadavg()]
        self.t_start = datetime.datetime.now()
        for d in self.datasets:
            log("%s: miter without early ray termination (the picture)" % d)
            cmd, r = self.miter(d, "1", "miter-n1")
            self.cmds[d + " miter-n1"] = cmd
            self.times[d + " miter-n1"] = [r]
            log("%s: dvr unshaded on the slice planes (the picture)" % d)
            cmd, r = self.voxlux(d, "unshaded", ["--no-jitter"], "-nojitter")
            self.cmds[d + " vx-unshaded-nojitter"] = cmd
            self.times[d + " vx-unshaded-nojitter"] = [r]
        work = [(d, t, fn) for d in self.datasets for t, fn in self.configs(d)]
        for rnd in range(a.runs):
            k = (rnd * 5) % len(work)
            order = work[k:] + work[:k]
            log("round %d of %d (%d runs)" % (rnd + 1, a.runs, len(order)))
            for d, t, fn in order:
                cmd, r = fn()
                r["round"] = rnd
                self.cmds["%s %s" % (d, t)] = cmd
                self.times.setdefault("%s %s" % (d, t), []).append(r)
                log("  %s %s %.0f ms" % (d, t, r["ms"]))
            self.load.append(os.getloadavg())
        self.t_end = datetime.datetime.now()
        self.errors = {d: self.pictures(d) for d in self.datasets}
        state = {k: getattr(self, k) for k in ("cmds", "times", "prep", "cam", "stats", "load",
                                                "datasets", "skipped", "errors", "read_cpu")}
        state["t_start"] = self.t_start.isoformat()
        state["t_end"] = self.t_end.isoformat()
        state["args"] = {"runs": a.runs, "threads": a.threads, "out": a.out, "bin": a.bin}
        with open(self.path("dvr-peers.json"), "w") as fh:
            json.dump(state, fh, indent=1)
        self.report()

    # ---- pictures ----
    def pictures(self, d):
        img = {t: volio.read_pfm_rgb(self.path("%s-%s.pfm" % (d, t)))
               for t in ("vx-unshaded-nojitter", "vx-unshaded", "miter-n1", "miter", "vtk",
                         "vtk-shaded", "vx-local", "vx-lit")}
        ref = img["vx-unshaded-nojitter"]
        errs = {}
        for t in ("miter-n1", "miter", "vtk", "jitter"):
            # "jitter": the timed (jittered) unshaded picture against miter -n1 1
            x = img["vx-unshaded" if t == "jitter" else t]
            if t == "jitter":
                ref = img["miter-n1"]
            m = (ref.max(axis=2) > 0) | (x.max(axis=2) > 0)
            mean = ref[m].mean()
            errs[t] = {"relrmse": float(np.sqrt(((x - ref)[m] ** 2).mean()) / mean),
                       "relmean": float(x[m].mean() / mean - 1),
                       "p99": float(np.percentile(np.abs(x - ref)[m], 99) / mean),
                       "pixels": int(m.sum())}
        ref = img["vx-unshaded-nojitter"]
        gap = np.zeros((ref.shape[0], 8, 3))
        row1 = np.concatenate([ref, gap, img["miter-n1"], gap, img["vtk"]], axis=1)
        row2 = np.concatenate([img["vx-local"], gap, img["vtk-shaded"], gap, img["vx-lit"]], axis=1)
        volio.write_png_rgb(self.path("%s-side-by-side.png" % d),
                            np.concatenate([row1, np.zeros((8, row1.shape[1], 3)), row2], axis=0))
        volio.write_png_rgb(self.path("%s-diff.png" % d), np.concatenate(
            [np.abs(img["miter-n1"] - ref), gap, np.abs(img["miter"] - ref), gap,
             np.abs(img["vtk"] - ref)], axis=1), scale=10, srgb=False)
        return errs

    # ---- the report ----
    def series(self, d, t, field="ms"):
        return [r[field] for r in self.times.get("%s %s" % (d, t), []) if field in r]

    def ratio(self, d, t1, t2, field="ms"):
        """(median of per-round t1/t2, min(t1)/min(t2))"""
        r1 = {r["round"]: r[field] for r in self.times.get("%s %s" % (d, t1), []) if field in r}
        r2 = {r["round"]: r[field] for r in self.times.get("%s %s" % (d, t2), []) if field in r}
        xs = [r1[k] / r2[k] for k in r1 if k in r2 and r2[k] > 0]
        if not xs:
            return None, None
        return statistics.median(xs), min(r1.values()) / min(r2.values())

    def report(self):
        a, L = self.a, []
        cpu = ""
        try:
            with open("/proc/cpuinfo") as fh:
                cpu = next(line.split(":", 1)[1].strip() for line in fh if line.startswith("model name"))
        except (OSError, StopIteration):
            pass
        try:
            rev = subprocess.run(["git", "-C", ROOT, "log", "-1", "--format=%h"],
                                 stdout=subprocess.PIPE, text=True).stdout.strip()
        except OSError:
            rev = "?"
        L.append("Date: %s to %s.  Commit %s.  Machine: %s, %d cores (shared; load average %s"
                 " at the start, %s at the end).  Rounds: %d.  Threads: %d for every tool"
                 " (dvr -j, teem-miter -nt, VTK SetNumberOfThreads).  Images 512x512, step 1."
                 % (self.t_start[:16].replace("T", " ") if isinstance(self.t_start, str)
                    else self.t_start.strftime("%Y-%m-%d %H:%M"),
                    (self.t_end[11:16] if isinstance(self.t_end, str) else self.t_end.strftime("%H:%M")),
                    rev, cpu, os.cpu_count(),
                    " ".join("%.1f" % x for x in self.load[0]),
                    " ".join("%.1f" % x for x in self.load[-1]), a.runs, a.threads))
        if self.skipped:
            L.append("\nSkipped (data absent): %s." % ", ".join(self.skipped))
        f = lambda x, p="%.0f": "-" if x is None else p % x  # noqa: E731
        L.append("\n### Frame time (ms; render only, loading excluded)\n")
        L.append("| data | tool | median | minimum | CPU, median | CPU, minimum |"
                 " process wall, median | notes |")
        L.append("|---|---|---|---|---|---|---|---|")
        for d in self.datasets:
            for t in TOOLS:
                xs = self.series(d, t)
                if not xs:
                    continue
                note = ""
                if t.startswith("vtk"):
                    note = "first render %s ms" % f(statistics.median(self.series(d, t, "first_ms")))
                cs = self.series(d, t, "cpu_ms")
                L.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
                    d, NAMES[t], f(statistics.median(xs)), f(min(xs)),
                    f(statistics.median(cs) if cs else None), f(min(cs) if cs else None),
                    f(statistics.median(self.series(d, t, "proc_ms"))), note))
        L.append("\nCPU: user + system time.  teem-miter: the whole process (reading the"
                 " volume included); VTK: the process during the timed Render(); voxlux: the"
                 " whole dvr process (reading the stream included: %s ms by dvr -n)."
                 % ", ".join("%s %.0f" % (d, self.read_cpu.get(d, 0))
                             for d in self.datasets))
        L.append("\n### Ratios (median of per-round ratios; ratio of the minima)\n")
        L.append("| data | ratio | goal | wall, median | wall, of minima | CPU, median |"
                 " CPU, of minima | met (wall; CPU) |")
        L.append("|---|---|---|---|---|---|---|---|")
        rows = [("miter", "vx-lit", "teem-miter unshaded / voxlux lit", ">= 10", lambda x: x >= 10),
                ("vx-lit", "vtk-shaded", "voxlux lit / VTK shaded", "<= 1.0", lambda x: x <= 1.0),
                ("vx-lit", "vx-unshaded", "voxlux lit / voxlux unshaded", "<= 1.6", lambda x: x <= 1.6),
                ("vx-unshaded", "vtk", "voxlux unshaded / VTK unshaded", "", None),
                ("vx-unshaded", "miter", "voxlux unshaded / teem-miter unshaded", "", None),
                ("vx-local", "vtk-shaded", "voxlux local / VTK shaded", "", None)]
        for d in self.datasets:
            for t1, t2, what, goal, ok in rows:
                med, mins = self.ratio(d, t1, t2)
                cmed, cmins = self.ratio(d, t1, t2, "cpu_ms")
                if med is None:
                    continue

                def met(a, b):
                    if ok is None or a is None:
                        return ""
                    return "yes" if ok(a) and ok(b) else "no" if not ok(a) and not ok(b) \
                        else "mixed"
                L.append("| %s | %s | %s | %.2f | %.2f | %s | %s | %s |" % (
                    d, what, goal, med, mins, f(cmed, "%.2f"), f(cmins, "%.2f"),
                    "; ".join(x for x in (met(med, mins), met(cmed, cmins)) if x)))
        L.append("\n### Pictures: voxlux unshaded (--no-jitter) against the unshaded peers\n")
        L.append("| data | peer | relative RMSE | mean, relative | 99th percentile of abs diff / mean | pixels |")
        L.append("|---|---|---|---|---|---|")
        for d in self.datasets:
            for t, what in (("miter-n1", "teem-miter, -n1 1 (no early termination)"),
                            ("miter", "teem-miter, -n1 0.99 (timed)"),
                            ("vtk", "VTK unshaded"),
                            ("jitter", "teem-miter -n1 1 against the timed (jittered) dvr")):
                e = self.errors[d].get(t)
                if e is None:
                    continue
                L.append("| %s | %s | %.2f%% | %+.2f%% | %.2f%% | %d |" % (
                    d, what, 100 * e["relrmse"], 100 * e["relmean"], 100 * e["p99"], e["pixels"]))
        L.append("\nPictures in %s: D-side-by-side.png (top: voxlux unshaded, teem-miter -n1 1,"
                 " VTK unshaded; bottom: voxlux local, VTK shaded, voxlux lit; linear RGB to"
                 " sRGB, no exposure; voxlux unshaded is the --no-jitter picture),"
                 " D-diff.png (|miter -n1 1 - voxlux|, |miter - voxlux|,"
                 " |VTK - voxlux|, times 10, linear: white = 0.1)." % self.out)
        L.append("\n### dvr --stats (last round)\n")
        L.append("```")
        for k in sorted(self.stats):
            L.append("# " + k)
            L.append(self.stats[k])
        L.append("```")
        L.append("\n### Commands\n")
        L.append("```")
        L.extend(self.prep)
        for k in sorted(self.cmds):
            L.append(" ".join(shlex.quote(x) for x in self.cmds[k]))
        L.append("```")
        text = "\n".join(L) + "\n"
        with open(self.path("dvr-peers.md"), "w") as fh:
            fh.write(text)
        print(text)


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--report-only":
        with open(os.path.join(sys.argv[2], "dvr-peers.json")) as fh:
            st = json.load(fh)
        b = Bench(argparse.Namespace(**st.pop("args")))
        b.__dict__.update(st)
        b.report()
        return
    p = argparse.ArgumentParser(description="voxlux dvr against teem-miter and VTK")
    p.add_argument("--out", required=True)
    p.add_argument("--bin", required=True, help="voxlux's bin directory")
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--datasets", default="vhf,ch2")
    a = p.parse_args()
    a.bin = os.path.abspath(a.bin)
    a.out = os.path.abspath(a.out)
    a.datasets = [x for x in a.datasets.split(",") if x]
    for d in a.datasets:
        if d not in DATASETS:
            p.error("unknown dataset %s" % d)
    if a.runs < 1 or a.threads < 1:
        p.error("--runs and --threads at least 1")
    for t in ("dvr", "vread", "vwrite", "macrocell"):
        if not os.access(os.path.join(a.bin, t), os.X_OK):
            sys.exit("dvrpeers.py: %s/%s missing: run make at the top first" % (a.bin, t))
    Bench(a).go()


if __name__ == "__main__":
    main()
