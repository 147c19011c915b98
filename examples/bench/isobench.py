#!/usr/bin/python3
"""isobench.py: voxlux's ray-cast isosurfaces against the extraction route
(VTK flying edges -> Embree BVH -> Lambert+headlight ray casting), and
Parker et al.'s Tables 1-3 for voxlux alone.  Run by `make -C examples/bench
iso` (see the Makefile there for the datasets and cameras); writes Markdown
tables and the raw numbers (JSON) into --out.

    isobench.py --out DIR --work DIR --runs N [--frames F]
        --dataset NAME NRRD BRICKED.vx LINEAR.vx FACEVIEW 'CAMERA FLAGS' ...
        --case NAME:ISO ... [--only frames,latency,table3,pictures]

Every measurement is repeated in --runs rounds, and each round runs the
peers and voxlux back to back, case after case, so that the load of a
shared machine falls on both alike; the tables give medians over the rounds
and the median of the per-round ratios.

frames    (a) voxlux's frame against Embree's frame (same camera, 512x512),
          1 and 2 threads; also Table 2 (thread scaling) and Table 1 (time
          shares, one extra frame with the phase clocks on).  A round is one
          process per side rendering --frames frames after a warm-up: the
          median frame of the round.
latency   (b) time to a new image after an isovalue change: voxlux renders
          another isovalue, then the new one (the hierarchy is reused; the
          new isovalue's cell mask is built inside its frame), against
          VTK extraction + Embree BVH build + one Embree frame; also the
          whole raycast(1) process (reading the stream included).
table3    (c) plain (linear layout, no hierarchy), bricking only (bricked,
          no hierarchy), hierarchy + bricking (and hierarchy alone), for
          five views; one thread.
sizes     macrocell level sizes (the stream's default against smaller
          level-1 cells): frame time and the hierarchy's size; one thread.
pictures  each case's voxlux and Embree frames as PNG, their difference
          (tonemap --compare) and the silhouette mismatch.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "peers"))
import volio  # noqa: E402

PY = sys.executable
SIZE = ["--size", "512", "512"]


def run(cmd, log):
    """Run cmd; return (stdout, wall seconds).  The command and its output
    go to the log."""
    t0 = time.monotonic()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       universal_newlines=True)
    wall = time.monotonic() - t0
    log.write("$ " + " ".join(cmd) + "\n" + p.stdout + p.stderr)
    log.flush()
    if p.returncode != 0:
        sys.exit("isobench.py: failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stderr))
    return p.stdout, wall


def keys(text):
    """'key value ...' lines -> {key: first value as float, or the text}."""
    out = {}
    for line in text.splitlines():
        w = line.split()
        if len(w) >= 2:
            try:
                out[w[0]] = float(w[1])
            except ValueError:
                out[w[0]] = w[1]
    return out


def med(v):
    return statistics.median(v) if v else float("nan")


def scene_camera(flags):
    """The peers' camera flags as a voxlux scene camera line."""
    w = flags.split()
    kv = {}
    i = 0
    while i < len(w):
        k = w[i].lstrip("-")
        n = 3 if k in ("eye", "look", "up") else 1
        kv[k] = " ".join(w[i + 1:i + 1 + n])
        i += 1 + n
    proj = "orthographic" if "ortho" in kv else "perspective"
    line = "camera %s eye %s look %s up %s" % (proj, kv["eye"], kv["look"], kv.get("up", "0 0 1"))
    return line + (" width %s" % kv["ortho"] if "ortho" in kv else " fov %s" % kv.get("fov", "30"))


class Bench:
    def __init__(self, a):
        self.a = a
        self.data = {}
        for d in a.dataset:
            name, nrrd, bricked, linear, face, cam = d
            self.data[name] = dict(nrrd=nrrd, bricked=bricked, linear=linear, face=face,
                                   cam=cam, camline=scene_camera(cam))
        self.cases = []
        for c in a.case:
            name, iso = c.split(":")
            if name not in self.data:
                sys.exit("isobench.py: --case %s: no --dataset %s" % (c, name))
            self.cases.append((name, iso))
        os.makedirs(a.out, exist_ok=True)
        os.makedirs(a.work, exist_ok=True)
        self.log = open(os.path.join(a.out, "isobench.log"), "a")
        self.log.write("# %s\n" % time.strftime("%Y-%m-%d %H:%M:%S"))
        self.bin = a.bin
        self.scene = a.scene

    def w(self, *parts):
        return os.path.join(self.a.work, "-".join(parts))

    def mesh(self, name, iso):
        """The flying-edges mesh of a case (made once; the latency table
        times extraction itself)."""
        path = self.w(name, "iso", iso, "fe.mesh")
        if not os.path.exists(path):
            out, _ = run([PY, os.path.join(HERE, "peers", "extract.py"), self.data[name]["nrrd"],
                          "--iso", iso, "--runs", "1", "-o", path], self.log)
        return path

    def vox_cmd(self, name, iso, extra, stream="bricked"):
        d = self.data[name]
        return [self.a.isobench, "--scene", self.scene, "--set", d["camline"],
                "--iso", iso] + extra + [d[stream]]

    def embree_cmd(self, name, iso, extra):
        d = self.data[name]
        return [self.a.embree, "-m", self.mesh(name, iso)] + d["cam"].split() + SIZE + extra

    def vox(self, name, iso, extra, stream="bricked"):
        return keys(run(self.vox_cmd(name, iso, extra, stream), self.log)[0])

    def embree(self, name, iso, extra):
        return keys(run(self.embree_cmd(name, iso, extra), self.log)[0])

    def pair(self, cmds):
        """Run two commands side by side (one per vCPU); their outputs as keys()."""
        procs = [subprocess.Popen(c, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                  universal_newlines=True) for c in cmds]
        outs = []
        for c, p in zip(cmds, procs):
            o, e = p.communicate()
            self.log.write("$ " + " ".join(c) + " &\n" + o + e)
            if p.returncode != 0:
                sys.exit("isobench.py: failed (%d): %s\n%s" % (p.returncode, " ".join(c), e))
            outs.append(keys(o))
        self.log.flush()
        return outs

    def side_by_side(self, name, iso, F):
        """Two 1-thread processes of each side by side: the mean of their frame
        medians (ms), voxlux's and Embree's."""
        vc = self.vox_cmd(name, iso, ["-j", "1", "-n", F, "--warm", "1"])
        v = self.pair([vc, vc])
        e = self.pair([self.embree_cmd(name, iso, [
            "-j", "1", "-n", F, "-b", "1", "-o",
            self.w(name, iso, "embree-pair%d.pfm" % k)]) for k in (1, 2)])
        return (statistics.mean(x["frame_ms"] for x in v),
                statistics.mean(x["render_ms"] for x in e))

    def save(self, what, rows, md):
        with open(os.path.join(self.a.out, what + ".json"), "w") as f:
            json.dump(rows, f, indent=1)
        with open(os.path.join(self.a.out, what + ".md"), "w") as f:
            f.write(md)
        sys.stdout.write(md + "\n")

    # ---- (a) frames, Table 2, Table 1 ----
    def frames(self):
        R, F = self.a.runs, str(self.a.frames)
        rows = {"%s:%s" % c: {"j1": [], "j2": []} for c in self.cases}
        for name, iso in self.cases:
            self.mesh(name, iso)
        for r in range(R):
            for name, iso in self.cases:
                for j in ("1", "2"):
                    e = self.embree(name, iso, ["-j", j, "-n", F, "-b", "1", "-o",
                                                self.w(name, iso, "embree.pfm")])
                    extra = ["-j", j, "-n", F, "--warm", "1"]
                    if j == "1":
                        extra += ["--stats", "--pfm", self.w(name, iso, "voxlux.pfm")]
                    v = self.vox(name, iso, extra)
                    nm = self.vox(name, iso, ["-j", j, "-n", F, "--warm", "1",
                                              "--no-cellmask"])
                    rows["%s:%s" % (name, iso)]["j" + j].append(dict(
                        nomask_ms=nm["frame_ms"], nomask_cpu_ms=nm["frame_cpu_ms"],
                        mask_kib=v["mask_bytes"] / 1024.0, mask_set=v["mask_set"],
                        mask_built=v["mask_built"], mask_blocks=v["mask_blocks"],
                        embree_ms=e["render_ms"], embree_cpu_ms=e["render_cpu_ms"],
                        vox_ms=v["frame_ms"], tile_ms=v.get("tile_ms"),
                        thread_ms=v.get("thread_ms"), bin_ms=v.get("bin_ms"),
                        vox_cpu_ms=v["frame_cpu_ms"], shares=[v.get("share_traverse"),
                                                              v.get("share_isect"),
                                                              v.get("share_shade")],
                        cells=v["cells"], roots=v["roots"], covered=v["covered"]))
                    if j == "2":
                        # the same minute's 1-thread frames run as two
                        # processes side by side: what two threads could do
                        # on this machine now, with no sharing between them
                        pv, pe = self.side_by_side(name, iso, F)
                        rows["%s:%s" % (name, iso)]["j2"][-1].update(
                            pair_vox_ms=pv, pair_embree_ms=pe)
                    print("round %d %s %s j%s: voxlux %.1f ms, embree %.1f ms" % (
                        r + 1, name, iso, j, v["frame_ms"], e["render_ms"]), flush=True)
        md = ["### (a) Frame time: voxlux raycast against Embree on the extracted mesh",
              "", "Median over %d interleaved rounds of each round's median of %s frames "
              "(512x512, the same camera); ratio = voxlux / Embree, the median of the "
              "per-round ratios (< 1: voxlux faster). CPU = process CPU time per frame. "
              "Best rounds = voxlux's fastest round / Embree's fastest round (each the "
              "round's median of %s frames): the two in their quietest minutes, for a VM "
              "whose noise slows one more than the other." % (R, F, F),
              "", "| case | threads | voxlux ms | Embree ms | ratio | voxlux CPU ms | Embree CPU ms | CPU ratio | best rounds |",
              "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
        t2 = ["### Table 2: thread scaling (this machine has 2 cores)", "",
              "Speedup = T1 / T2 from the medians; efficiency = speedup / 2; CPU growth = "
              "CPU time per frame at 2 threads / at 1 (1.0: no parallel overhead).  voxlux's "
              "frame split (`vx_raycast_stats`): tile work = the threads' time in the "
              "tiles at 2 threads / at 1 (1.0: the same work, only spread; above: each "
              "thread slower side by side); balance = that time / (2 x the tiles' wall "
              "time) at 2 threads; outside = the frame's time outside the tiles (set-up, "
              "bins, the bins' centre pixels drawn first), at 1 / 2 threads, and of it "
              "the bins' making (bins ms).", "",
              "| case | voxlux T1 ms | T2 ms | speedup | efficiency | CPU growth | tile work | balance | outside ms | bins ms | Embree speedup | Embree efficiency |",
              "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
        tp = ["### Table 2, side by side: two threads against two 1-thread processes", "",
              "In the same rounds as Table 2, right after the 2-thread frames: two 1-thread "
              "processes of each run side by side (one per vCPU; the mean of their frame "
              "medians).  Two processes share nothing but the machine, so their "
              "throughput, 2 frames in T1 pair, is what 2 threads could reach in that "
              "minute; against the pair = T1 pair / (2 x T2), the median of the "
              "per-round ratios (100%: "
              "the threads lose nothing to each other; the machine's own slowdown of a "
              "second busy vCPU, RESULTS.md \"Two threads\", is in T1 pair too); efficiency = "
              "T1 / (2 x T2) as in Table 2.", "",
              "| case | voxlux T1 ms | T1 pair ms | T2 ms | efficiency | against the pair | Embree T1 ms | T1 pair ms | T2 ms | efficiency | against the pair |",
              "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
        tm = ["### The cell mask: frames with and without it", "",
              "voxlux's frame with the cell mask (kept between the frames of one "
              "isovalue, as Embree keeps its BVH; a new isovalue's first frame, table "
              "(b), builds its own) and with `--no-cellmask`, the same rounds; saving = 1 - with / "
              "without, the median of the per-round CPU-time ratios.  Memory: the mask's "
              "bits and tables; macrocells: bracketing level-1 macrocells, and of them "
              "those rays entered (whose bits were built).", "",
              "| case | threads | with mask ms (CPU) | without ms (CPU) | saving (CPU) | memory KiB | macrocells bracketing / entered / all |",
              "| --- | --- | --- | --- | --- | --- | --- |"]
        t1 = ["### Table 1: where voxlux's frame time goes (1 thread, phase clocks on)", "",
              "| case | traversal | intersection | shading | cells visited / ray | roots / ray | covered |",
              "| --- | --- | --- | --- | --- | --- | --- |"]
        for key, js in rows.items():
            for j in ("j1", "j2"):
                x = js[j]
                ratio = med([a["vox_ms"] / a["embree_ms"] for a in x])
                cratio = med([a["vox_cpu_ms"] / a["embree_cpu_ms"] for a in x])
                best = min(a["vox_ms"] for a in x) / min(a["embree_ms"] for a in x)
                md.append("| %s | %s | %.1f | %.1f | %.2f | %.1f | %.1f | %.2f | %.2f |" % (
                    key, j[1:], med([a["vox_ms"] for a in x]), med([a["embree_ms"] for a in x]),
                    ratio, med([a["vox_cpu_ms"] for a in x]), med([a["embree_cpu_ms"] for a in x]),
                    cratio, best))
            for j in ("j1", "j2"):
                x = js[j]
                tm.append("| %s | %s | %.1f (%.1f) | %.1f (%.1f) | %.0f%% | %.0f | %d / %d / %d |" % (
                    key, j[1:], med([a["vox_ms"] for a in x]), med([a["vox_cpu_ms"] for a in x]),
                    med([a["nomask_ms"] for a in x]), med([a["nomask_cpu_ms"] for a in x]),
                    100 * (1 - med([a["vox_cpu_ms"] / a["nomask_cpu_ms"] for a in x])),
                    x[-1]["mask_kib"], x[-1]["mask_set"], x[-1]["mask_built"],
                    x[-1]["mask_blocks"]))
            v1 = med([a["vox_ms"] for a in js["j1"]])
            v2 = med([a["vox_ms"] for a in js["j2"]])
            c1 = med([a["vox_cpu_ms"] for a in js["j1"]])
            c2 = med([a["vox_cpu_ms"] for a in js["j2"]])
            e1 = med([a["embree_ms"] for a in js["j1"]])
            e2 = med([a["embree_ms"] for a in js["j2"]])
            b1 = med([a["thread_ms"] for a in js["j1"]])
            b2 = med([a["thread_ms"] for a in js["j2"]])
            bal = med([a["thread_ms"] / (2 * a["tile_ms"]) for a in js["j2"]])
            o1 = med([a["vox_ms"] - a["tile_ms"] for a in js["j1"]])
            o2 = med([a["vox_ms"] - a["tile_ms"] for a in js["j2"]])
            n1 = med([a["bin_ms"] for a in js["j1"] if a.get("bin_ms") is not None])
            n2 = med([a["bin_ms"] for a in js["j2"] if a.get("bin_ms") is not None])
            t2.append("| %s | %.1f | %.1f | %.2f | %.0f%% | %.2f | %.2f | %.0f%% | %.1f / %.1f | %.1f / %.1f | %.2f | %.0f%% |" % (
                key, v1, v2, v1 / v2, 50 * v1 / v2, c2 / c1, b2 / b1, 100 * bal, o1, o2,
                n1, n2, e1 / e2, 50 * e1 / e2))
            pr = [a for a in js["j2"] if "pair_vox_ms" in a]
            if pr:
                pv = med([a["pair_vox_ms"] for a in pr])
                pe = med([a["pair_embree_ms"] for a in pr])
                tp.append("| %s | %.1f | %.1f | %.1f | %.0f%% | %.0f%% | %.1f | %.1f | %.1f | %.0f%% | %.0f%% |" % (
                    key, v1, pv, v2, 50 * v1 / v2,
                    100 * med([a["pair_vox_ms"] / (2 * a["vox_ms"]) for a in pr]),
                    e1, pe, e2, 50 * e1 / e2,
                    100 * med([a["pair_embree_ms"] / (2 * a["embree_ms"]) for a in pr])))
            sh = [med([a["shares"][k] for a in js["j1"]]) for k in range(3)]
            x = js["j1"][-1]
            t1.append("| %s | %.0f%% | %.0f%% | %.0f%% | %.2f | %.2f | %.1f%% |" % (
                key, 100 * sh[0], 100 * sh[1], 100 * sh[2], x["cells"] / 262144.0,
                x["roots"] / 262144.0, 100 * x["covered"] / 262144.0))
        self.save("frames", rows, "\n".join(md + [""] + t2 + [""] + tp + [""] + tm + [""] + t1) + "\n")

    # ---- (b) a new isovalue ----
    def latency(self):
        R = self.a.runs
        rows = {"%s:%s" % c: {"j1": [], "j2": []} for c in self.cases}
        others = {}
        for name, iso in self.cases:
            isos = [i for n, i in self.cases if n == name and i != iso]
            others[(name, iso)] = isos[0] if isos else iso
        for r in range(R):
            for name, iso in self.cases:
                d = self.data[name]
                for j in ("1", "2"):
                    mesh = self.w(name, iso, "lat.mesh")
                    x, _ = run([PY, os.path.join(HERE, "peers", "extract.py"), d["nrrd"], "--iso",
                                iso, "--runs", "1", "--threads", j, "-o", mesh], self.log)
                    x = keys(x)
                    e = keys(run([self.a.embree, "-m", mesh, "-j", j, "-n", "1", "-b", "1", "-o",
                                  self.w(name, iso, "lat.pfm")] + d["cam"].split() + SIZE,
                                 self.log)[0])
                    os.remove(mesh)
                    out, _ = run([self.a.isobench, "--scene", self.scene, "--set",
                                  d["camline"], "--iso", others[(name, iso)], "-j", j, "-n",
                                  "1", "--warm", "0", "--latency", iso, d["bricked"]], self.log)
                    v = keys(out)
                    lat = [ln.split() for ln in out.splitlines() if ln.startswith("latency")][0]
                    _, cli = run([os.path.join(self.bin, "raycast"), "--scene", self.scene,
                                  "--set", d["camline"], "--iso", iso, "-j", j, d["bricked"],
                                  "-o", self.w(name, iso, "cli.png")], self.log)
                    route = x["extract_ms"] + e["build_ms"] + e["render_ms"]
                    rows["%s:%s" % (name, iso)]["j" + j].append(dict(
                        extract_ms=x["extract_ms"], build_ms=e["build_ms"],
                        render_ms=e["render_ms"], route_ms=route, vox_ms=float(lat[4]),
                        vox_cpu_ms=float(lat[6]), cli_ms=1e3 * cli, load_ms=v["load_ms"]))
                    print("round %d %s %s j%s: voxlux %.1f ms (process %.0f ms), route %.1f ms" % (
                        r + 1, name, iso, j, float(lat[4]), 1e3 * cli, route), flush=True)
        md = ["### (b) A new isovalue: voxlux against extraction + BVH build + render", "",
              "Medians over %d interleaved rounds. voxlux: the first frame of the new "
              "isovalue in a running process (the hierarchy is reused; the new isovalue's "
              "cell mask is built during this frame, in its time); "
              "process: the whole `raycast` command (reading the stream, checking its "
              "macrocells, rendering, writing the PNG). Route: VTK flying edges `Update()` "
              "+ Embree `rtcCommitScene` + one frame (mesh I/O not counted). Ratio = the "
              "median of the per-round ratios; the goal is <= 0.2." % R, "",
              "| case | threads | extract ms | BVH ms | Embree frame ms | route ms | voxlux ms | ratio | process ms | process ratio |",
              "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
        for key, js in rows.items():
            for j in ("j1", "j2"):
                x = js[j]
                md.append("| %s | %s | %.0f | %.0f | %.1f | %.0f | %.1f | %.3f | %.0f | %.2f |" % (
                    key, j[1:], med([a["extract_ms"] for a in x]), med([a["build_ms"] for a in x]),
                    med([a["render_ms"] for a in x]), med([a["route_ms"] for a in x]),
                    med([a["vox_ms"] for a in x]), med([a["vox_ms"] / a["route_ms"] for a in x]),
                    med([a["cli_ms"] for a in x]), med([a["cli_ms"] / a["route_ms"] for a in x])))
        self.save("latency", rows, "\n".join(md) + "\n")

    # ---- (c) Table 3 ----
    def table3(self):
        R = self.a.runs
        configs = [("plain", "linear", ["--flat"]), ("bricking", "bricked", ["--flat"]),
                   ("hierarchy", "linear", []), ("hierarchy+bricking", "bricked", [])]
        views = ["face", "side", "top", "close-up", "feet"]
        rows = {}
        cases = [c for c in self.cases if not self.a.t3_case or "%s:%s" % c in self.a.t3_case]
        for r in range(R):
            for name, iso in cases:
                d = self.data[name]
                face = d["face"]
                vset = {"face": ["--view", face], "side": ["--view", "right"],
                        "top": ["--view", "top"], "feet": ["--view", "bottom"],
                        "close-up": ["--set", "camera auto view %s distance 0.4" % face]}
                for view in views:
                    for cname, stream, flags in configs:
                        cmd = [self.a.isobench, "--scene", self.scene, "--iso", iso] + vset[view] + \
                              ["-j", "1", "-n", "1", "--warm", "1"] + flags + [d[stream]]
                        v = keys(run(cmd, self.log)[0])
                        rows.setdefault("%s:%s" % (name, iso), {}).setdefault(view, {}) \
                            .setdefault(cname, []).append((v["frame_ms"], v["frame_cpu_ms"]))
                    print("round %d %s %s %s: %s" % (r + 1, name, iso, view, " ".join(
                        "%.0f" % rows["%s:%s" % (name, iso)][view][c][-1][0]
                        for c, _, _ in configs)), flush=True)
        md = ["### Table 3: layout and hierarchy (ms per frame, 1 thread, 512x512)", "",
              "Median over %d interleaved rounds (one frame after one warm-up frame per "
              "round). plain: linear layout, every cell walked (`--flat`); bricking: the "
              "bricked stream, `--flat`; hierarchy: linear layout with the macrocells; "
              "hierarchy+bricking: both (what `vread | brick | macrocell | raycast` does). "
              "Views: `camera auto` from the face, the side (right), the top, from the feet "
              "(bottom), and a close-up of the face (distance 0.4)." % R, "",
              "Each entry: wall ms (CPU ms).", "",
              "| case | view | plain | bricking | hierarchy | hierarchy+bricking | plain / h+b (CPU) |",
              "| --- | --- | --- | --- | --- | --- | --- |"]
        for key, vs in rows.items():
            for view in views:
                m = [med([x[0] for x in vs[view][c]]) for c, _, _ in configs]
                u = [med([x[1] for x in vs[view][c]]) for c, _, _ in configs]
                md.append("| %s | %s | %s | %.1f (%.1f) |" % (
                    key, view, " | ".join("%.0f (%.0f)" % (m[k], u[k]) for k in range(4)),
                    m[0] / m[3], u[0] / u[3]))
        self.save("table3", rows, "\n".join(md) + "\n")

    # ---- macrocell sizes ----
    def sizes(self):
        R = self.a.runs
        variants = ["stream"] + self.a.sizes.split()
        rows = {}
        for r in range(R):
            for name, iso in self.cases:
                for sz in variants:
                    extra = ["-j", "1", "-n", "3", "--warm", "1"]
                    if sz != "stream":
                        extra += ["--sizes", sz]
                    v = self.vox(name, iso, extra)
                    x = rows.setdefault("%s:%s" % (name, iso), {}).setdefault(sz, dict(ms=[],
                                                                                      cpu=[]))
                    x["ms"].append(v["frame_ms"])
                    x["cpu"].append(v["frame_cpu_ms"])
                    x["share"] = v["macro_share"]
                    x["build_ms"] = v.get("build_ms")
                print("round %d %s %s: %s" % (r + 1, name, iso, " ".join(
                    "%.0f" % rows["%s:%s" % (name, iso)][z]["ms"][-1] for z in variants)), flush=True)
        md = ["### Macrocell sizes (ms per frame, 1 thread, the cameras of (a))", "",
              "Median over %d interleaved rounds of each round's median of 3 frames; "
              "'stream' is `macrocell`'s default (level 1 covers 2 KiB of samples: u8 "
              "16x16x8, i16 16x8x8; level 2 64^3 cells). Each entry: wall ms / CPU ms (the "
              "hierarchy's size as a share of the samples' bytes)." % R, "",
              "| case | " + " | ".join(variants) + " |", "| --- |" + " --- |" * len(variants)]
        for key, vs in rows.items():
            md.append("| %s | " % key + " | ".join(
                "%.0f / %.0f (%.2f%%)" % (med(vs[z]["ms"]), med(vs[z]["cpu"]), 100 * vs[z]["share"])
                for z in variants) + " |")
        self.save("sizes", rows, "\n".join(md) + "\n")

    # ---- pictures ----
    def pictures(self):
        rows = {}
        md = ["### Pictures: voxlux against Embree, same camera", "",
              "Gray radiance |n.d| over black. rmse and max_abs from `tonemap --compare` "
              "(Embree's frame as the reference); silhouette mismatch: pixels covered by "
              "one image only, over the pixels either covers.", "",
              "| case | triangles | rmse | max_abs | silhouette mismatch | covered (voxlux) | covered (Embree) | pictures |",
              "| --- | --- | --- | --- | --- | --- | --- | --- |"]
        for name, iso in self.cases:
            vp, ep = self.w(name, iso, "voxlux.pfm"), self.w(name, iso, "embree.pfm")
            if not os.path.exists(vp):
                self.vox(name, iso, ["-j", "2", "-n", "1", "--pfm", vp])
            if not os.path.exists(ep):
                self.embree(name, iso, ["-j", "2", "-n", "1", "-b", "1", "-o", ep])
            with open(self.mesh(name, iso), "rb") as f:
                tri = int.from_bytes(f.read(16)[12:16], "little")   # VXMESH01 ntris
            base = os.path.join(self.a.out, "%s-%s" % (name, iso))
            cmp_ = keys(run([os.path.join(self.bin, "tonemap"), "--compare", ep, "--diff",
                             base + "-diff.png", vp], self.log)[0])
            for src, dst in ((vp, base + "-voxlux.png"), (ep, base + "-embree.png")):
                run([os.path.join(self.bin, "tonemap"), "-o", dst, src], self.log)
            a, b = volio.read_pfm(vp), volio.read_pfm(ep)
            ca, cb = a > 0, b > 0
            union = int((ca | cb).sum())
            mis = int((ca ^ cb).sum())
            rows["%s:%s" % (name, iso)] = dict(triangles=tri, rmse=cmp_["rmse"],
                                               max_abs=cmp_["max_abs"], mismatch=mis,
                                               union=union, cov_vox=int(ca.sum()),
                                               cov_embree=int(cb.sum()))
            md.append("| %s:%s | %d | %.4f | %.3f | %.2f%% (%d px) | %d | %d | %s |" % (
                name, iso, tri, cmp_["rmse"], cmp_["max_abs"], 100.0 * mis / max(union, 1), mis,
                int(ca.sum()), int(cb.sum()), ", ".join(os.path.basename(base) + s for s in
                                                          ("-voxlux.png", "-embree.png",
                                                           "-diff.png"))))
        self.save("pictures", rows, "\n".join(md) + "\n")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--out", required=True, help="tables and logs")
    p.add_argument("--work", required=True, help="meshes and images")
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--frames", type=int, default=5)
    p.add_argument("--bin", default=os.path.join(HERE, "..", "..", "bin"))
    p.add_argument("--isobench", required=True)
    p.add_argument("--embree", required=True)
    p.add_argument("--scene", required=True)
    p.add_argument("--dataset", nargs=6, action="append", required=True,
                   metavar=("NAME", "NRRD", "BRICKED", "LINEAR", "FACEVIEW", "CAMERA"))
    p.add_argument("--case", action="append", required=True, metavar="NAME:ISO")
    p.add_argument("--only", default="frames,latency,table3,sizes,pictures")
    p.add_argument("--t3-case", action="append", metavar="NAME:ISO",
                   help="Table 3 only for these cases (default: all)")
    p.add_argument("--sizes", default="8x8x8,8x8x8 4x4x4,8x8x8 4x4x4,4x4x4,4x4x4",
                   help="macrocell level sizes for the sizes table (blank-separated)")
    a = p.parse_args()
    b = Bench(a)
    for what in a.only.split(","):
        getattr(b, what)()


if __name__ == "__main__":
    main()
