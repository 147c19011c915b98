#!/usr/bin/python3
"""gipeer.py: voxlux's path-traced reference (`raycast --set "illumination
pathtrace"`) against an Embree path tracer of the extracted mesh
(peers/embree_pt.c): the same scene, camera, image size and samples per
pixel; time per path (a sample of a covered pixel) and the difference of the
pictures.  Run by `make -C examples/bench gipeer` (gipeer.mk).

The scene (one place: SCENE below): the skin or the scalp of the MRI head
lit by a sky and a directional light with shadows, one bounce of light
between the surfaces, Lambertian albedo; voxlux reads it as a scene file,
embree_pt as flags (--sky, --sun, --albedo, --bounces).

What is timed, per round (every configuration runs once per round, the
order rotated from round to round, so both tools see the same load):
  voxlux  raycast --scene S --spp N --hdr --stats -j J STREAM: raycast's own
          render time (its --stats line: set-up, bins, the frame; reading
          the stream excluded) and the whole process's CPU time (wait4).
  Embree  embree_pt ... --spp N -j J -n 1 -w 0: one frame, no warm-up (like
          raycast's one frame): its wall and process CPU time (the BVH build
          before it excluded).
Each runs at spp N and at spp 1; per path = time / paths at spp N, and the
marginal cost of a sample = (t_N - t_1) / (paths_N - paths_1), which leaves
out what does not scale with the samples (primary rays, the primary hit's
shadow ray, set-up, reading, cold caches).

Pictures: relative RMSE = RMSE over the pixels both cover (all three
channels) / the mean of voxlux's there, at spp N, and with --ref-spp R the
same at R samples per pixel, which splits it into Monte Carlo noise (each
tool's N against its own R) and the difference of the surfaces (mesh and
flat triangles with interpolated normals, against the trilinear surface and
its gradient).

usage: gipeer.py --out DIR --work DIR --bin BINDIR --embree-pt EXE --nrrd NRRD
                 --stream STREAM [--probe EXE] [--case ISO]... [--size N]
                 [--spp N] [--ref-spp R] [--threads "1 2"] [--runs N]
                 [--camera "CAMERA FLAGS"] [--packets]
"""
import argparse
import datetime
import json
import os
import re
import shlex
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
import numpy as np  # noqa: E402

PY = sys.executable
# a bluish sky, a warm key light with shadows and the skin's colour of the
# README's head (examples/scenes/head-gi.scn, which lights it by an environment
# map instead: the peer scene is a sky of radiance L)
SCENE = {
    "sky": (0.55, 0.65, 0.85), "sky_i": 0.4,
    "sun_dir": (1, -1.5, -1), "sun": (1, 0.95, 0.85), "sun_i": 0.7,
    "color": (0.93, 0.78, 0.68), "kd": 0.9,
    "bounces": 1,
}
CAMERA = "--eye 295 495 123 --look 0 -17 19 --up 0 0 1 --fov 30"


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def run(cmd):
    """Run cmd (a list): (stdout + stderr, wall s, child CPU s)."""
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    out = p.stdout.read()
    _, status, ru = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
    dt = time.perf_counter() - t0
    text = out.decode(errors="replace")
    if p.returncode != 0:
        sys.exit("gipeer.py: failed (%d): %s\n%s" % (p.returncode,
                 " ".join(map(shlex.quote, cmd)), text[-2000:]))
    return text, dt, ru.ru_utime + ru.ru_stime


def num(pattern, text, what):
    m = re.search(pattern, text)
    if not m:
        sys.exit("gipeer.py: no %s in:\n%s" % (what, text[-2000:]))
    return float(m.group(1))


def cam_scene_line(flags):
    """--eye X Y Z --look X Y Z --up X Y Z --fov D as a scene camera line."""
    f = flags.split()
    v = {f[i]: f[i + 1:i + 4] for i in range(len(f)) if f[i].startswith("--")}
    return "camera perspective eye %s look %s up %s fov %s" % (
        " ".join(v["--eye"]), " ".join(v["--look"]), " ".join(v["--up"]), v["--fov"][0])


def rgb(c, s=1.0):
    return " ".join("%.6g" % (x * s) for x in c)


def read_rgb_pfm(path):
    """(h, w, 3) float64, row 0 at the top."""
    with open(path, "rb") as fh:
        data = fh.read()
    parts = data.split(maxsplit=3)
    kind, w, h, scale = parts[0], int(parts[1]), int(parts[2]), float(parts[3][:16].split()[0])
    nc = 3 if kind == b"PF" else 1
    a = np.frombuffer(data[len(data) - w * h * nc * 4:],
                      dtype=("<" if scale < 0 else ">") + "f4").reshape(h, w, nc)
    return np.flipud(a).astype(np.float64)


def relrmse(ref, img):
    """(relative RMSE over the pixels both cover, covered by ref only, by img only)."""
    cr, ci = ref.sum(2) > 0, img.sum(2) > 0
    m = cr & ci
    d = (img - ref)[m]
    return (float(np.sqrt(np.mean(d ** 2)) / np.mean(ref[m])),
            int((cr & ~ci).sum()), int((ci & ~cr).sum()), int(m.sum()))


class Bench:
    def __init__(self, a):
        self.a = a
        self.cmds = {}
        self.times = {}
        self.text = {}
        self.prep = []

    def scene_file(self, iso, size):
        s = SCENE
        path = os.path.join(self.a.work, "ch2-gi-%s-%d.scn" % (iso, size))
        with open(path, "w") as fh:
            fh.write("voxlux-scene 1\n# gipeer.py: the scene embree_pt draws from flags\n")
            fh.write(cam_scene_line(self.a.camera) + "\n")
            fh.write("image width %d height %d\n" % (size, size))
            fh.write("background color 0 0 0\n")
            fh.write("light sky color %s intensity %g\n" % (rgb(s["sky"]), s["sky_i"]))
            fh.write("light directional direction %s color %s intensity %g shadows on\n"
                     % (rgb(s["sun_dir"]), rgb(s["sun"]), s["sun_i"]))
            fh.write("surface iso %s color %s kd %g\n" % (iso, rgb(s["color"]), s["kd"]))
            fh.write("interreflection bounces %d samples %d\n" % (s["bounces"], self.a.spp))
            fh.write("effects shadows interreflection\nillumination pathtrace\n")
        return path

    def embree_flags(self):
        s = SCENE
        return (self.a.camera.split() +
                ["--sky"] + rgb(s["sky"], s["sky_i"]).split() +
                ["--sun"] + rgb(s["sun_dir"]).split() + rgb(s["sun"], s["sun_i"]).split() +
                ["--albedo"] + rgb(s["color"], s["kd"]).split() +
                ["--bounces", str(s["bounces"])])

    def mesh(self, iso):
        path = os.path.join(self.a.work, "ch2-iso-%s.mesh" % iso)
        cmd = [PY, os.path.join(HERE, "peers", "extract.py"), self.a.nrrd, "--iso", iso,
               "--runs", "1", "-o", path]
        self.prep.append(" ".join(map(shlex.quote, cmd)))
        if not os.path.exists(path):
            log(" ".join(cmd))
            text, _, _ = run(cmd)
            self.extract_text = getattr(self, "extract_text", {})
            self.extract_text[iso] = text
        return path

    # ---- one run of each tool ----
    def voxlux(self, iso, j, spp, keep=None, size=None):
        size = size or self.a.size
        out = keep or "/dev/null"
        cmd = [os.path.join(self.a.bin, "raycast"), "--scene", self.scn[(iso, size)],
               "--spp", str(spp), "--hdr", "--stats", "-j", str(j), "-o", out, self.a.stream]
        text, wall, cpu = run(cmd)
        r = {"ms": 1e3 * num(r"raycast: \d+x\d+, \d+ threads?, ([0-9.e+-]+) s", text, "time"),
             "cpu_ms": 1e3 * cpu, "proc_ms": 1e3 * wall,
             "paths": num(r"pathtrace: (\d+) paths", text, "paths")}
        return cmd, r, text

    def embree(self, iso, j, spp, keep=None, size=None, packets=False):
        size = size or self.a.size
        out = keep or os.path.join(self.a.work, "embree-scratch.pfm")
        cmd = [self.a.embree_pt, "-m", self.meshes[iso], "-o", out] + self.embree_flags() + \
            ["--size", str(size), str(size), "--spp", str(spp), "-j", str(j), "-n", "1", "-w", "0"] + \
            (["--packets"] if packets else [])
        text, wall, cpu = run(cmd)
        r = {"ms": num(r"render_ms ([0-9.]+)", text, "render_ms"),
             "cpu_ms": num(r"render_cpu_ms ([0-9.]+)", text, "render_cpu_ms"),
             "proc_ms": 1e3 * wall, "build_ms": num(r"build_ms ([0-9.]+)", text, "build"),
             "paths": num(r"paths (\d+)", text, "paths")}
        return cmd, r, text

    def configs(self):
        out = []
        for iso in self.a.case:
            for j in self.a.threads:
                for spp in (self.a.spp, 1):
                    out.append((("voxlux", iso, j, spp),
                                lambda iso=iso, j=j, spp=spp: self.voxlux(iso, j, spp)))
                    out.append((("embree", iso, j, spp),
                                lambda iso=iso, j=j, spp=spp: self.embree(iso, j, spp)))
                    if self.a.packets:
                        out.append((("embree16", iso, j, spp),
                                    lambda iso=iso, j=j, spp=spp: self.embree(iso, j, spp,
                                                                              packets=True)))
        return out

    def go(self):
        a = self.a
        os.makedirs(a.out, exist_ok=True)
        os.makedirs(a.work, exist_ok=True)
        self.scn = {}
        for iso in a.case:
            self.scn[(iso, a.size)] = self.scene_file(iso, a.size)
            if a.ref_spp:
                self.scn[(iso, a.ref_size)] = self.scene_file(iso, a.ref_size)
        self.meshes = {iso: self.mesh(iso) for iso in a.case}
        self.load = [os.getloadavg()]
        self.t_start = datetime.datetime.now()
        work = self.configs()
        for rnd in range(a.runs):
            k = (rnd * 3) % len(work)
            order = work[k:] + work[:k]
            log("round %d of %d (%d runs)" % (rnd + 1, a.runs, len(order)))
            for key, fn in order:
                cmd, r, text = fn()
                self.cmds[key] = cmd
                self.times.setdefault(key, []).append(r)
                self.text[key] = text
            self.load.append(os.getloadavg())
        self.t_end = datetime.datetime.now()
        self.pictures()
        self.probes()
        with open(os.path.join(a.out, "gipeer.json"), "w") as fh:
            json.dump({"times": {"/".join(map(str, k)): v for k, v in self.times.items()},
                       "errors": self.errors, "probe": self.probe_text,
                       "load": self.load, "args": vars(a)}, fh, indent=1)
        self.report()

    # ---- pictures and their difference ----
    def pictures(self):
        a = self.a
        self.errors = []
        self.pic_cmds = []
        jmax = max(a.threads)
        sets = [(a.size, a.spp)]
        if a.ref_spp:
            sets.append((a.ref_size, a.ref_spp))
        for iso in a.case:
            img = {}
            for size, spp in sets:
                vxs = os.path.join(a.out, "ch2-%s-%d-spp%d-voxlux.vx" % (iso, size, spp))
                pv = vxs[:-3] + ".pfm"
                pe = os.path.join(a.out, "ch2-%s-%d-spp%d-embree.pfm" % (iso, size, spp))
                log("pictures: iso %s, %dx%d, spp %d" % (iso, size, size, spp))
                cv, _, _ = self.voxlux(iso, jmax, spp, keep=vxs, size=size)
                ce, _, _ = self.embree(iso, jmax, spp, keep=pe, size=size)
                tm = os.path.join(a.bin, "tonemap")
                run([tm, "--pfm", "--name", "color", "-o", pv, vxs])
                for p in (pv, pe):
                    run([tm, "-o", p[:-4] + ".png", p])
                os.remove(vxs)
                self.pic_cmds += [" ".join(map(shlex.quote, cv)), " ".join(map(shlex.quote, ce))]
                img[(size, spp, "v")] = read_rgb_pfm(pv)
                img[(size, spp, "e")] = read_rgb_pfm(pe)
                e, only_v, only_e, n = relrmse(img[(size, spp, "v")], img[(size, spp, "e")])
                self.errors.append({"iso": iso, "size": size, "what": "Embree vs voxlux, spp %d" % spp,
                                    "relrmse": e, "only_voxlux": only_v, "only_embree": only_e,
                                    "both": n})
            if a.ref_spp and a.ref_size == a.size:
                for t, name in (("v", "voxlux"), ("e", "Embree")):
                    e, ov, oe, n = relrmse(img[(a.size, a.ref_spp, t)], img[(a.size, a.spp, t)])
                    self.errors.append({"iso": iso, "size": a.size,
                                        "what": "%s spp %d vs its own spp %d (noise)"
                                        % (name, a.spp, a.ref_spp), "relrmse": e,
                                        "only_voxlux": ov, "only_embree": oe, "both": n})

    # ---- the GI rays' work per ray (giprobe), once per case ----
    def probes(self):
        a = self.a
        self.probe_text = {}
        self.probe_cmds = []
        if not a.probe:
            return
        for iso in a.case:
            for mode in (["--walks"], ["--mask"]):
                cmd = [a.probe, "--scene", self.scn[(iso, a.size)], "--spp", str(a.spp)] + \
                    mode + [a.stream]
                text, _, _ = run(cmd)
                self.probe_cmds.append(" ".join(map(shlex.quote, cmd)))
                self.probe_text["%s %s" % (iso, " ".join(mode))] = text

    # ---- the tables ----
    def med(self, key, f):
        return statistics.median(r[f] for r in self.times[key])

    def per_path(self, key, f):
        return statistics.median(1e6 * r[f] / r["paths"] for r in self.times[key])

    def marginal(self, hi, lo, f):
        """per round: (t_N - t_1) / (paths_N - paths_1), ns; their median"""
        return statistics.median(1e6 * (h[f] - l[f]) / (h["paths"] - l["paths"])
                                 for h, l in zip(self.times[hi], self.times[lo]))

    def ratio(self, f, ka, kb, lo_a=None, lo_b=None):
        """median of the per-round ratios a / b (per path, or marginal)"""
        rs = []
        for i in range(len(self.times[ka])):
            A, B = self.times[ka][i], self.times[kb][i]
            if lo_a:
                La, Lb = self.times[lo_a][i], self.times[lo_b][i]
                va = (A[f] - La[f]) / (A["paths"] - La["paths"])
                vb = (B[f] - Lb[f]) / (B["paths"] - Lb["paths"])
            else:
                va, vb = A[f] / A["paths"], B[f] / B["paths"]
            rs.append(va / vb)
        return statistics.median(rs)

    def report(self):
        a = self.a
        L = []
        cpu = ""
        try:
            with open("/proc/cpuinfo") as fh:
                cpu = next(line.split(":", 1)[1].strip() for line in fh
                           if line.startswith("model name"))
        except (OSError, StopIteration):
            pass
        L.append("# voxlux's path-traced reference against an Embree path tracer\n")
        L.append("ch2 (MRI head, 181x217x181 u8), %dx%d, spp %d, %d bounce, sky + directional "
                 "light with shadows; %d rounds, %s to %s; %s, %d CPUs; load average at the "
                 "start %s, after each round %s.\n" % (
                     a.size, a.size, a.spp, SCENE["bounces"], a.runs,
                     self.t_start.strftime("%Y-%m-%d %H:%M"), self.t_end.strftime("%H:%M"),
                     cpu, os.cpu_count(), " ".join("%.1f" % x for x in self.load[0]),
                     ", ".join("%.1f" % x[0] for x in self.load[1:])))
        L.append("Times: medians over the rounds; ratios: median of the per-round ratios "
                 "voxlux / Embree (< 1: voxlux faster). ns/path = frame / paths; marginal = "
                 "(t(spp %d) - t(spp 1)) / (paths(spp %d) - paths(spp 1)). voxlux CPU: the "
                 "whole raycast process; Embree CPU: the frame.\n" % (a.spp, a.spp))
        L.append("| iso | threads | paths voxlux / Embree | frame ms voxlux / Embree | "
                 "ns/path wall | ratio | ns/path CPU | ratio | marginal ns/sample wall | ratio | "
                 "marginal CPU | ratio |")
        L.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
        for iso in a.case:
            for j in a.threads:
                v, e = ("voxlux", iso, j, a.spp), ("embree", iso, j, a.spp)
                v1, e1 = ("voxlux", iso, j, 1), ("embree", iso, j, 1)
                f = lambda x: "%.0f" % x  # noqa: E731
                L.append("| %s | %d | %d / %d | %s / %s | %s / %s | %.2f | %s / %s | %.2f | "
                         "%s / %s | %.2f | %s / %s | %.2f |" % (
                             iso, j, self.med(v, "paths"), self.med(e, "paths"),
                             f(self.med(v, "ms")), f(self.med(e, "ms")),
                             f(self.per_path(v, "ms")), f(self.per_path(e, "ms")),
                             self.ratio("ms", v, e),
                             f(self.per_path(v, "cpu_ms")), f(self.per_path(e, "cpu_ms")),
                             self.ratio("cpu_ms", v, e),
                             f(self.marginal(v, v1, "ms")), f(self.marginal(e, e1, "ms")),
                             self.ratio("ms", v, e, v1, e1),
                             f(self.marginal(v, v1, "cpu_ms")), f(self.marginal(e, e1, "cpu_ms")),
                             self.ratio("cpu_ms", v, e, v1, e1)))
        if a.packets:
            L.append("")
            L.append("Embree with `--packets` (a pixel's first bounce rays 16 at a time, "
                     "`rtcIntersect16`, a common origin) against Embree with single rays, "
                     "same rounds:\n")
            L.append("| iso | threads | ns/path CPU packets / single | ratio | marginal CPU "
                     "packets / single | ratio |")
            L.append("|---|---|---|---|---|---|")
            for iso in a.case:
                for j in a.threads:
                    p, e = ("embree16", iso, j, a.spp), ("embree", iso, j, a.spp)
                    p1, e1 = ("embree16", iso, j, 1), ("embree", iso, j, 1)
                    L.append("| %s | %d | %.0f / %.0f | %.2f | %.0f / %.0f | %.2f |" % (
                        iso, j, self.per_path(p, "cpu_ms"), self.per_path(e, "cpu_ms"),
                        self.ratio("cpu_ms", p, e), self.marginal(p, p1, "cpu_ms"),
                        self.marginal(e, e1, "cpu_ms"), self.ratio("cpu_ms", p, e, p1, e1)))
        L.append("")
        L.append("Embree BVH build (not in the frame times), median ms: " + ", ".join(
            "iso %s %d thread%s %.0f" % (iso, j, "" if j == 1 else "s",
                                         self.med(("embree", iso, j, a.spp), "build_ms"))
            for iso in a.case for j in a.threads) + ".\n")
        L.append("## Pictures\n")
        L.append("relative RMSE = RMSE over the pixels both cover / voxlux's mean there "
                 "(RGB); covered by one only: pixels.\n")
        L.append("| iso | size | compared | relative RMSE | voxlux only | Embree only | both |")
        L.append("|---|---|---|---|---|---|---|")
        for r in self.errors:
            L.append("| %s | %d | %s | %.4f | %d | %d | %d |" % (
                r["iso"], r["size"], r["what"], r["relrmse"], r["only_voxlux"],
                r["only_embree"], r["both"]))
        L.append("")
        if self.probe_text:
            L.append("## voxlux's GI rays (giprobe, one thread)\n")
            L.append("```")
            for k, t in self.probe_text.items():
                L.append("# iso " + k)
                L.append(t.rstrip())
            L.append("```\n")
        L.append("## Commands\n")
        L.append("```")
        L += self.prep
        for key in sorted(self.cmds, key=str):
            L.append(" ".join(map(shlex.quote, self.cmds[key])))
        L += self.pic_cmds + getattr(self, "probe_cmds", [])
        L.append("```")
        with open(os.path.join(a.out, "gipeer.md"), "w") as fh:
            fh.write("\n".join(L) + "\n")
        print("\n".join(L))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--out", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--bin", required=True)
    p.add_argument("--embree-pt", required=True)
    p.add_argument("--probe")
    p.add_argument("--nrrd", required=True)
    p.add_argument("--stream", required=True)
    p.add_argument("--case", action="append", help="isovalue (repeatable)")
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--spp", type=int, default=16)
    p.add_argument("--ref-spp", type=int, default=0)
    p.add_argument("--ref-size", type=int, default=0)
    p.add_argument("--threads", default="1 2")
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--camera", default=CAMERA)
    p.add_argument("--packets", action="store_true",
                   help="also time embree_pt --packets (rtcIntersect16)")
    a = p.parse_args()
    a.case = a.case or ["40", "127.5"]
    a.threads = [int(x) for x in a.threads.split()]
    a.ref_size = a.ref_size or a.size
    if a.runs < 1 or a.spp < 2 or a.size < 1:
        sys.exit("gipeer.py: --runs >= 1, --spp >= 2, --size >= 1")
    Bench(a).go()


if __name__ == "__main__":
    main()
