#!/usr/bin/python3
"""gibench.py: global illumination benchmarks (Wyman et al. 2006) for
bake-irr, bake-sh and raycast's `illumination irradiance` and `sh`.  Run by
`make -C examples/bench gi` and `gi-sh` (gi.mk names the datasets and
scenes); writes Markdown tables (gi.md) and the raw numbers (gi.json) into
--out.

    gibench.py --bin DIR --out DIR --runs N
        --dataset NAME STREAM SCENE ISO_RANGE ...  [--parts t1,t2,acc,mem]
        [--samples 16,100,625] [--max-paths P] [--max-lazy-paths P]
        [--acc-size N]
        [--acc-spp N] [--acc-samples N]
        [--sh-order N] [--sh-cost-scale S] [--sh-vhf-band A,B]

t1   Wyman's Table 1: the full bake (the scene's isovalue band, and an
     --iso-range band of isovalues) against the lazy first image (raycast
     --lazy at the scene's 512x512) at each sample count, and every texel
     (--all; the first dataset).  Each bake is measured at a quarter of the
     first sample count too; a bake of more than --max-paths paths is not
     run but put on the line through the two measured runs of the same
     texels with the most samples (a fixed cost and a cost per sample), and
     the table marks it so; a lazy image of more than --max-lazy-paths
     paths likewise.  Every texel is measured at --scale 0.5 with 1 and 4
     samples and extrapolated to scale 1 by the texel counts of the two
     lattices.
t2   Wyman's Table 2: the frame time of each shading mode in one raycast
     build (--runs rounds, the modes interleaved in each round): Lambert
     without shadows, Lambert with shadows, Blinn-Phong with shadows,
     irradiance lookup (trilinear) from the accum, f32 and f16 stores,
     SH shading (illumination sh, trilinear, the scene's sky projected)
     from f32 and f16 transfer volumes of --sh-order; SH frames are also
     compared with the same round's irradiance f32 frame.
acc  irradiance shading against the path-traced reference on the first
     dataset's skin at lattice scale 1 (--acc-size pixels square): the
     relative RMSE over the covered pixels (tests/cli/vximg.py relrmse), and
     the reference's own noise from a second reference of 1/4 the paths.
mem  bytes per texel of each store and the band's saving (bricks stored of
     all, wanted texels of the lattice).
sht1 Table 1's SH rows on the first dataset: bake-sh --order N --final of
     the scene's isovalue band against the lazy first image (bake-sh
     --lazy, raycast --lazy --set "illumination sh"), measured and
     extrapolated as t1's.
shcost  bake-sh's CPU seconds a path against bake-irr's: the same texels
     (the band at --sh-cost-scale), one bounce, bake-irr lit by the scene's
     sky alone; each round bakes 4 and 16 samples with each baker, and the
     cost a path is the difference of CPU over the difference of paths.
shmem bytes a texel at orders 3, 5, 8, one and three channels, each store,
     and the band's size (bake-sh -n --explain); the second dataset at
     order 5 over --sh-vhf-band (an --iso-range and the two isovalues),
     and a one-sample bake of its scene's band whose maximum resident size
     checks the prediction.

Times: wall seconds and CPU seconds (user + system, of the process and its
children) of each process; paths per core-second are paths over CPU
seconds, so that a shared machine's other load does not count against
them.  The machine these were written for is shared: the tables give
medians and ratios within one run.
"""
import argparse
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
VXIMG = os.path.join(HERE, '..', '..', 'tests', 'cli', 'vximg.py')
PAPER_PATHS_PER_CPU_S = 3.41e6 * 100 / (18.2 * 60 * 30)   # ~10,400


def run(cmd, out=None, log=None):
    """Run cmd (a list), stdout to file `out` (or discarded), stderr
    returned.  Returns (wall, cpu, stderr text)."""
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    with open(out if out else os.devnull, 'wb') as f:
        p = subprocess.run(cmd, stdout=f, stderr=subprocess.PIPE)
    wall = time.monotonic() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    err = p.stderr.decode(errors='replace')
    if log is not None:
        log.write('$ %s%s\n%s' % (' '.join(cmd), ' > ' + out if out else '',
                                  err))
        log.write('# wall %.3f s, cpu %.3f s\n' % (wall, cpu))
        log.flush()
    if p.returncode != 0:
        sys.exit('gibench: %s: exit %d: %s' % (cmd[0], p.returncode,
                                               err.strip()[-500:]))
    return wall, cpu, err


def grab(pat, text, cast=float):
    m = re.search(pat, text)
    if not m:
        sys.exit('gibench: no match for %r in:\n%s' % (pat, text))
    return cast(m.group(1))


class Bench:
    def __init__(self, a):
        self.a = a
        self.bin = a.bin
        self.out = a.out
        os.makedirs(self.out, exist_ok=True)
        self.log = open(os.path.join(self.out, 'gi.log'), 'a')
        self.res = {'paper_paths_per_cpu_s': PAPER_PATHS_PER_CPU_S,
                    'nproc': os.cpu_count()}

    def b(self, tool):
        return os.path.join(self.bin, tool)

    def f(self, name):
        return os.path.join(self.out, name)

    def vinfo(self, stream, kind='IRRV'):
        p = subprocess.run([self.b('vinfo'), '--json', '--histogram', '0',
                            stream], stdout=subprocess.PIPE, check=True)
        d = json.loads(p.stdout)
        key = 'irradiance' if kind == 'IRRV' else 'sh_transfer'
        return [c[key] for c in d['chunks'] if c['type'] == kind][0]

    # ---- Table 1 ----
    def bake(self, ds, tag, extra, samples, tool='bake-irr', keep=None):
        """One full bake: bake-irr (or bake-sh) with the scene and extra
        flags; the stream is kept when `keep` says so (default: the band's
        bake at the smallest sample count)."""
        name, stream, scene = ds[0], ds[1], ds[2]
        o = self.f('%s-%s-s%d.vx' % (name, tag, samples))
        wall, cpu, err = run([self.b(tool), '--scene', scene,
                              '--samples', str(samples), '--stats'] + extra +
                             [stream], out=o, log=self.log)
        r = {'wall': wall, 'cpu': cpu, 'samples': samples,
             'wanted': grab(r'texels\), (\d+) wanted', err, int),
             'baked': grab(r'wanted, (\d+) baked', err, int),
             'paths': grab(r'(\d+) samples \(paths\)', err, int),
             'plan_s': grab(r'plan ([\d.]+) s', err),
             'bake_s': grab(r'bake ([\d.]+) s', err),
             'threads': grab(r'on (\d+) thread', err, int),
             'measured': True}
        r['paths_per_cpu_s'] = r['paths'] / cpu
        info = self.vinfo(o, 'SHTV' if tool == 'bake-sh' else 'IRRV')
        r['bricks'] = info['bricks']
        r['bricks_total'] = info['bricks_total']
        r['lattice'] = info['texels']
        r['bytes'] = info['bytes']
        if keep is None:
            keep = tag == 'band' and samples == min(self.samples)
        if not keep:
            os.remove(o)
        else:
            r['stream'] = o
        return r

    def explain(self, ds, extra):
        """Wanted texels of a plan (bake-irr -n: nothing baked)."""
        _, _, err = run([self.b('bake-irr'), '--scene', ds[2], '-n'] +
                        extra + [ds[1]], log=self.log)
        return grab(r'texels at scale [\d.]+ \([^)]*\), (\d+) wanted', err,
                    int)

    def lazy(self, ds, samples, tool='bake-irr', extra=(), rextra=()):
        name, stream, scene = ds[0], ds[1], ds[2]
        tag = 'lazy' if tool == 'bake-irr' else 'shlazy'
        empty = self.f('%s-%s-s%d.vx' % (name, tag, samples))
        w0, c0, _ = run([self.b(tool), '--scene', scene, '--samples',
                         str(samples), '--lazy'] + list(extra) + [stream],
                        out=empty, log=self.log)
        png = self.f('%s-%s-s%d.png' % (name, tag, samples))
        wall, cpu, err = run([self.b('raycast'), '--scene', scene, '--lazy',
                              '--stats', '-o', png] + list(rextra) + [empty],
                             log=self.log)
        os.remove(empty)
        return {'wall': wall, 'cpu': cpu, 'samples': samples,
                'read': grab(r'the view reads (\d+) texels', err, int),
                'baked': grab(r'texels: (\d+) baked now', err, int),
                'paths': grab(r'baked now \((\d+) paths', err, int),
                'lazy_s': grab(r'paths, ([\d.]+) s\)', err),
                'frame_s': grab(r'threads?, ([\d.]+) s \(', err),
                'setup_wall': w0, 'setup_cpu': c0, 'measured': True}

    @staticmethod
    def fit(p, q, samples):
        """The same bake at `samples`, by the line through measured runs p
        and q (fewer samples first) in samples: a fixed cost (reading,
        planning, writing) and a cost per sample."""
        k = (samples - q['samples']) / (q['samples'] - p['samples'])
        r = dict(q)
        r.update({'samples': samples,
                  'paths': int(q['paths'] * samples / q['samples']),
                  'cpu': q['cpu'] + k * (q['cpu'] - p['cpu']),
                  'wall': q['wall'] + k * (q['wall'] - p['wall']),
                  'measured': False,
                  'fit': [p['samples'], q['samples']]})
        r.pop('stream', None)
        return r

    def table1(self):
        res = self.res.setdefault('t1', {})
        for n, ds in enumerate(self.a.dataset):
            name, lo_hi = ds[0], ds[3]
            d = res[name] = {'band': [], 'range': [], 'all': [], 'lazy': [],
                             'cal': {}}
            d['iso_range'] = lo_hi
            s0 = self.samples[0]
            cases = [('band', []), ('range', ['--iso-range', lo_hi])]
            for tag, extra in cases:
                wanted = self.explain(ds, extra)
                # a calibration run at a quarter of the first sample count:
                # with it, the line through two measured runs
                cal = d['cal'][tag] = self.bake(ds, tag, extra,
                                                max(1, s0 // 4))
                last = [cal]
                for s in self.samples:
                    if s != s0 and wanted * s > self.a.max_paths:
                        r = self.fit(last[-2], last[-1], s)
                    else:
                        r = self.bake(ds, tag, extra, s)
                        last.append(r)
                    d[tag].append(r)
                    self.save()
            # every texel (the first dataset): measured at scale 0.5 with 1
            # and 4 samples, extrapolated in samples and, by the texel
            # counts of the two lattices, to scale 1
            if n == 0:
                extra = ['--all', '--scale', '0.5']
                p = d['cal']['all1'] = self.bake(ds, 'all', extra, 1)
                q = d['cal']['all4'] = self.bake(ds, 'all', extra, 4)
                w1 = self.explain(ds, ['--all'])
                for s in self.samples:
                    r = self.fit(p, q, s)
                    k = w1 / r['wanted']
                    r.update({'wanted': w1, 'paths': int(r['paths'] * k),
                              'cpu': r['cpu'] * k, 'wall': r['wall'] * k,
                              'from_scale': 0.5})
                    d['all'].append(r)
                self.save()
            for s in self.samples:
                lz = d['lazy']
                if len(lz) >= 2 and lz[0]['read'] * s > self.a.max_lazy_paths:
                    # linear in the samples through the last two runs
                    p, q = lz[-2], lz[-1]
                    k = (s - q['samples']) / (q['samples'] - p['samples'])
                    r = dict(q)
                    r.update({'samples': s, 'paths': q['read'] * s,
                              'cpu': q['cpu'] + k * (q['cpu'] - p['cpu']),
                              'wall': q['wall'] + k * (q['wall'] - p['wall']),
                              'measured': False})
                    lz.append(r)
                else:
                    lz.append(self.lazy(ds, s))
                self.save()

    # ---- Table 2 ----
    def table2(self):
        ds = self.a.dataset[0]
        name, stream, scene = ds[0], ds[1], ds[2]
        # the irradiance volume: the smallest sample count's band bake
        # (the frame time does not depend on the sample count: without
        # Table 1's bake, one of 4 samples)
        band = self.f('%s-band-s%d.vx' % (name, min(self.samples)))
        if not os.path.exists(band):
            band = self.f('%s-t2band-s4.vx' % name)
            if not os.path.exists(band):
                run([self.b('bake-irr'), '--scene', scene, '--samples', '4',
                     stream], out=band, log=self.log)
        f32, f16 = self.f('%s-f32.vx' % name), self.f('%s-f16.vx' % name)
        run([self.b('bake-irr'), '--scene', scene, '--samples', '0',
             '--final', band], out=f32, log=self.log)
        run([self.b('bake-irr'), '--scene', scene, '--samples', '0',
             '--half', band], out=f16, log=self.log)
        local = ['--set', 'illumination local']
        modes = [
            ('Lambert, no shadows', stream,
             local + ['--effects', '-shadows -specular -interreflection']),
            ('Lambert, shadows', stream,
             local + ['--effects', '-specular -interreflection']),
            ('Blinn-Phong, shadows', stream,
             local + ['--effects', '-interreflection']),
            ('irradiance (trilinear), accum store', band, []),
            ('irradiance (trilinear), f32 store', f32, []),
            ('irradiance (trilinear), f16 store', f16, []),
        ]
        shf32, shf16 = self.sh_stores(ds)
        sh = ['--set', 'illumination sh']
        modes += [
            ('SH order %d (trilinear), f32 store' % self.a.sh_order, shf32,
             sh),
            ('SH order %d (trilinear), f16 store' % self.a.sh_order, shf16,
             sh),
        ]
        times = {m[0]: [] for m in modes}
        ratios = {m[0]: [] for m in modes}
        irr = 'irradiance (trilinear), f32 store'
        ratios_irr = {m[0]: [] for m in modes}
        for rnd in range(self.a.runs):
            t = {}
            for label, src, extra in modes:
                png = self.f('%s-t2-%d.png' % (name, modes.index(
                    (label, src, extra))))
                _, _, err = run([self.b('raycast'), '--scene', scene,
                                 '--stats', '-o', png] + extra + [src],
                                log=self.log)
                t[label] = grab(r'threads?, ([\d.]+) s \(', err)
                times[label].append(t[label])
            ref = t['Blinn-Phong, shadows']
            for label in t:
                ratios[label].append(t[label] / ref)
                ratios_irr[label].append(t[label] / t[irr])
        self.res['t2'] = {'dataset': name, 'runs': self.a.runs,
                          'modes': [m[0] for m in modes],
                          'times': times, 'ratios': ratios,
                          'ratios_irr': ratios_irr}
        self.save()

    # ---- accuracy ----
    def accuracy(self):
        ds = self.a.dataset[0]
        name, stream, scene = ds[0], ds[1], ds[2]
        n = self.a.acc_size
        size = ['--size', '%dx%d' % (n, n), '--hdr']
        ref = self.f('%s-ref-spp%d.vx' % (name, self.a.acc_spp))
        ref4 = self.f('%s-ref-spp%d.vx' % (name, self.a.acc_spp // 4))
        pt = ['--set', 'illumination pathtrace']
        r = {'size': n, 'spp': self.a.acc_spp, 'samples': self.a.acc_samples}
        w, c, _ = run([self.b('raycast'), '--scene', scene] + size + pt +
                      ['--spp', str(self.a.acc_spp), stream], out=ref,
                      log=self.log)
        r['ref_wall'], r['ref_cpu'] = w, c
        run([self.b('raycast'), '--scene', scene] + size + pt +
            ['--spp', str(self.a.acc_spp // 4), stream], out=ref4,
            log=self.log)
        empty = self.f('%s-acc-lazy.vx' % name)
        run([self.b('bake-irr'), '--scene', scene, '--samples',
             str(self.a.acc_samples), '--lazy', stream], out=empty,
            log=self.log)
        irr = self.f('%s-acc-irr.vx' % name)
        w, c, err = run([self.b('raycast'), '--scene', scene, '--lazy',
                         '--stats'] + size + [empty], out=irr, log=self.log)
        r['irr_cpu'] = c
        r['texels'] = grab(r'the view reads (\d+) texels', err, int)
        rel = lambda a, b: float(subprocess.run(
            ['python3', VXIMG, 'relrmse', a, b], stdout=subprocess.PIPE,
            check=True).stdout)
        r['relrmse'] = rel(ref, irr)
        r['relrmse_ref4'] = rel(ref, ref4)
        # ref4 - ref has the variance of both: sigma4^2 (1 + 1/4); the
        # reference's own relative noise is sigma4 / 2
        r['ref_noise'] = r['relrmse_ref4'] / (1.25 ** 0.5) / 2
        for p in (empty, ref4):
            os.remove(p)
        self.res['acc'] = r
        self.save()

    # ---- memory ----
    def memory(self):
        out = {}
        for ds in self.a.dataset:
            name = ds[0]
            band = self.f('%s-band-s%d.vx' % (name, min(self.samples)))
            if not os.path.exists(band):
                continue
            i = self.vinfo(band)
            out[name] = {k: i[k] for k in ('lattice_dims', 'texels',
                                           'bricks', 'bricks_total',
                                           'wanted', 'bytes')}
            for store, flag in (('f32', '--final'), ('f16', '--half')):
                p = self.f('%s-mem-%s.vx' % (name, store))
                run([self.b('bake-irr'), '--scene', ds[2], '--samples', '0',
                     flag, band], out=p, log=self.log)
                out[name]['bytes_' + store] = self.vinfo(p)['bytes']
                os.remove(p)
        self.res['mem'] = out
        self.save()

    # ---- SH: bake-sh and illumination sh ----
    def sh_flags(self, store):
        return ['--order', str(self.a.sh_order)] + (
            [store] if store else [])

    def sh_stores(self, ds):
        """The f32 and f16 SH transfer volumes of the scene's isovalue band
        for Table 2 (4 samples a texel: the frame time does not depend on
        it); Table 1's 4-sample f32 bake when it is there."""
        name, stream, scene = ds[0], ds[1], ds[2]
        out = []
        for store, flag in (('f32', '--final'), ('f16', '--half')):
            p = self.f('%s-shband-%s-s4.vx' % (name, store))
            if not os.path.exists(p):
                run([self.b('bake-sh'), '--scene', scene, '--samples', '4'] +
                    self.sh_flags(flag) + [stream], out=p, log=self.log)
            out.append(p)
        return out

    def sh_table1(self):
        """Table 1's SH rows: bake-sh of the scene's isovalue band (f32
        store: no accumulators) against the lazy first image of
        `illumination sh` (the scene's sky projected), on the first
        dataset; extrapolated as table1 does."""
        ds = self.a.dataset[0]
        name = ds[0]
        d = self.res.setdefault('sht1', {})[name] = {
            'band': [], 'lazy': [], 'cal': {}, 'order': self.a.sh_order}
        s0 = self.samples[0]
        wanted = self.explain(ds, [])
        extra = self.sh_flags('--final')
        cal = d['cal']['band'] = self.bake(
            ds, 'shband-f32', extra, max(1, s0 // 4), 'bake-sh',
            keep=max(1, s0 // 4) == 4)
        last = [cal]
        for s in self.samples:
            if s != s0 and wanted * s > self.a.max_paths:
                r = self.fit(last[-2], last[-1], s)
            else:
                r = self.bake(ds, 'shband-f32', extra, s, 'bake-sh',
                              keep=False)
                last.append(r)
            d['band'].append(r)
            self.save()
        lz = d['lazy']
        for s in self.samples:
            if len(lz) >= 2 and lz[0]['read'] * s > self.a.max_lazy_paths:
                p, q = lz[-2], lz[-1]
                k = (s - q['samples']) / (q['samples'] - p['samples'])
                r = dict(q)
                r.update({'samples': s, 'paths': q['read'] * s,
                          'cpu': q['cpu'] + k * (q['cpu'] - p['cpu']),
                          'wall': q['wall'] + k * (q['wall'] - p['wall']),
                          'measured': False})
                lz.append(r)
            else:
                lz.append(self.lazy(ds, s, 'bake-sh', self.sh_flags(None),
                                    ['--set', 'illumination sh']))
            self.save()

    def sh_cost(self):
        """bake-sh's cost a sample against bake-irr's: the same texels
        (the scene's isovalue band at --sh-cost-scale), the same bounces,
        bake-irr lit by the scene's sky alone (its delta lights dropped:
        no shadow rays, so that both trace the same paths).  Each round
        runs every baker at 4 and 16 samples, interleaved; the cost a path
        is the difference of CPU seconds over the difference of paths (the
        fixed costs cancel), and the whole process's CPU over its paths."""
        ds = self.a.dataset[0]
        name, stream, scene = ds[0], ds[1], ds[2]
        sky = self.f('%s-skyonly.scn' % name)
        with open(scene) as f, open(sky, 'w') as g:
            for line in f:
                w = line.split()
                if w[:1] == ['light'] and w[1:2] != ['sky']:
                    continue
                g.write(line)
        sc = ['--scale', str(self.a.sh_cost_scale)]
        bakers = [
            ('bake-irr (sky)', 'bake-irr', []),
            ('bake-sh order %d, 3 channels' % self.a.sh_order, 'bake-sh',
             self.sh_flags(None) + ['--channels', '3']),
            ('bake-sh order %d, 1 channel' % self.a.sh_order, 'bake-sh',
             self.sh_flags(None) + ['--channels', '1']),
        ]
        per = {b[0]: [] for b in bakers}
        whole = {b[0]: [] for b in bakers}
        dsky = (name, stream, sky)
        for rnd in range(self.a.runs):
            for label, tool, extra in bakers:
                lo = self.bake(dsky, 'cost', sc + extra, 4, tool, keep=False)
                hi = self.bake(dsky, 'cost', sc + extra, 16, tool,
                               keep=False)
                per[label].append((hi['cpu'] - lo['cpu']) /
                                  (hi['paths'] - lo['paths']))
                whole[label].append(hi['cpu'] / hi['paths'])
                wanted = hi['wanted']
            self.res['shcost'] = {'runs': rnd + 1, 'scale':
                                  self.a.sh_cost_scale, 'wanted': wanted,
                                  'bakers': [b[0] for b in bakers],
                                  'per_path': per, 'whole': whole}
            self.save()

    def sh_explain(self, ds, extra):
        _, _, err = run([self.b('bake-sh'), '--scene', ds[2], '-n',
                         '--explain'] + extra + [ds[1]], log=self.log)
        m = re.search(r'(\d+) bytes a texel in memory \((\d+) in the '
                      r'stream\), (\d+) bricks of 8\^3: ([\d.]+) MB', err)
        if not m:
            sys.exit('gibench: no memory line in:\n' + err)
        return {'mem': int(m.group(1)), 'stream': int(m.group(2)),
                'bricks': int(m.group(3)), 'mb': float(m.group(4)),
                'wanted': grab(r', (\d+) wanted', err, int)}

    def sh_memory(self):
        """bytes a texel at orders 3, 5, 8, one and three channels, each
        store, from bake-sh -n --explain on the first dataset's band; the
        second dataset (the CT head) at order 5, scale 1, over
        --sh-vhf-band (skin to bone), and a --samples 1 bake of its
        scene's isovalue band whose maximum resident size (GNU time)
        checks the prediction."""
        res = self.res['shmem'] = {'orders': {}, 'big': {}}
        ds = self.a.dataset[0]
        for n in (3, 5, 8):
            for ch in (1, 3):
                for store, flag in (('accum', None), ('f32', '--final'),
                                    ('f16', '--half')):
                    e = self.sh_explain(ds, ['--order', str(n), '--channels',
                                             str(ch)] + ([flag] if flag
                                                         else []))
                    res['orders']['%d/%d/%s' % (n, ch, store)] = e
                    res['dataset'] = ds[0]
                    self.save()
        if len(self.a.dataset) < 2:
            return
        ds = self.a.dataset[1]
        res['big_dataset'] = ds[0]
        res['big_band'] = self.a.sh_vhf_band
        for band in (['--iso-range', self.a.sh_vhf_band],
                     ['--iso', self.a.sh_vhf_band]):
            for ch in (3, 1):
                for store, flag in (('accum', None), ('f32', '--final'),
                                    ('f16', '--half')):
                    e = self.sh_explain(ds, band + self.sh_flags(flag) +
                                        ['--channels', str(ch)])
                    res['big']['%s/%d/%s' % (band[0][2:], ch, store)] = e
                    self.save()
        # the check: a real bake, one sample a texel
        v = {}
        for store, flag in (('f16', '--half'), ('accum', None)):
            e = self.sh_explain(ds, self.sh_flags(flag))
            o = self.f('%s-shcheck.vx' % ds[0])
            _, _, err = run(['/usr/bin/time', '-f', 'maxrss %M',
                             self.b('bake-sh'), '--scene', ds[2],
                             '--samples', '1'] + self.sh_flags(flag) +
                            [ds[1]], out=o, log=self.log)
            os.remove(o)
            v[store] = {'predicted_mb': e['mb'], 'wanted': e['wanted'],
                        'maxrss_mb': grab(r'maxrss (\d+)', err, int) *
                        1024 / 1e6}
        res['check'] = v
        self.save()

    def save(self):
        with open(self.f('gi.json'), 'w') as f:
            json.dump(self.res, f, indent=1)


# ---- the Markdown tables ----

def fmt_t(r):
    s = '%.1f / %.1f' % (r['wall'], r['cpu'])
    return s if r['measured'] else '*%s*' % s


def tables(res):
    L = []
    P = res['paper_paths_per_cpu_s']
    if 't1' in res:
        L.append('## Table 1: full bake against the lazy first image\n')
        L.append('Times: wall / CPU seconds (CPU = user + system of the '
                 'process).  *Italics*: extrapolated, not measured (see the '
                 'notes).  Paths per core-second: paths / CPU seconds of '
                 'the measured run; the paper: %.0f.\n' % P)
        for name, d in res['t1'].items():
            L.append('### %s\n' % name)
            L.append('| samples | full: the scene\'s isovalue | paths/core-s '
                     '| full: --iso-range %s | every texel (scale 1) | '
                     'lazy first image | lazy paths | lazy / full (CPU) | '
                     'lazy / every texel (CPU) |' % d['iso_range'])
            L.append('| --- | --- | --- | --- | --- | --- | --- | --- | --- |')
            for i, lz in enumerate(d['lazy']):
                b, g = d['band'][i], d['range'][i]
                a = d['all'][i] if d['all'] else None
                pc = b['paths_per_cpu_s'] if b['measured'] else None
                L.append('| %d | %s | %s | %s | %s | %s | %d | '
                         '1/%.1f | %s |' % (
                             lz['samples'], fmt_t(b),
                             '%.0f (%.0fx the paper)' % (pc, pc / P)
                             if pc else '-', fmt_t(g), fmt_t(a) if a else '-', fmt_t(lz),
                             lz['paths'], b['cpu'] / lz['cpu'],
                             '1/%.0f' % (a['cpu'] / lz['cpu']) if a else '-'))
            b0, g0 = d['band'][0], d['range'][0]
            cal = d['cal']
            meas = [r for k in ('band', 'range') for r in
                    [cal[k]] + [x for x in d[k] if x['measured']]]
            L.append('')
            L.append('Texels: the scene\'s isovalue band %d wanted (%d of %d '
                     'bricks), --iso-range %s %d wanted; the lazy view reads '
                     '%d.' % (b0['wanted'], b0['bricks'], b0['bricks_total'],
                              d['iso_range'], g0['wanted'],
                              d['lazy'][0]['read']))
            if 'all1' in cal:
                L.append('Every texel: %d at scale 1; measured at scale 0.5 '
                         '(%d texels, %d of them baked, the rest flat) with '
                         '1 and 4 samples (%.1f / %.1f and %.1f / %.1f s, '
                         '%.0f and %.0f paths per core-second), then '
                         'extrapolated.' % (
                             d['all'][0]['wanted'], cal['all1']['wanted'],
                             cal['all1']['baked'], cal['all1']['wall'],
                             cal['all1']['cpu'], cal['all4']['wall'],
                             cal['all4']['cpu'],
                             cal['all1']['paths_per_cpu_s'],
                             cal['all4']['paths_per_cpu_s']))
            L.append('Measured bakes (samples: wall / CPU s, paths per '
                     'core-second): %s.  Extrapolated rows lie on the line '
                     'through the two measured runs of the same texels.\n' %
                     '; '.join('%s %d: %.1f / %.1f, %.0f' % (
                         'band' if r in [cal['band']] + d['band'] else
                         'range', r['samples'], r['wall'], r['cpu'],
                         r['paths_per_cpu_s']) for r in meas))
    if 't2' in res:
        t = res['t2']
        L.append('## Table 2: frame time per shading mode (%s, 512x512, '
                 '%d rounds)\n' % (t['dataset'], t['runs']))
        bmin = min(t['times']['Blinn-Phong, shadows'])
        L.append('| mode | median frame (s) | fps | median ratio to '
                 'Blinn-Phong with shadows (same round) | fastest frame '
                 '(s) | ratio of the fastest frames |')
        L.append('| --- | --- | --- | --- | --- | --- |')
        for m in t['modes']:
            med = statistics.median(t['times'][m])
            L.append('| %s | %.3f | %.2f | %.2f | %.3f | %.2f |' % (
                m, med, 1 / med, statistics.median(t['ratios'][m]),
                min(t['times'][m]), min(t['times'][m]) / bmin))
        L.append('')
    if 't2' in res and 'ratios_irr' in res['t2']:
        t = res['t2']
        irr = 'irradiance (trilinear), f32 store'
        mi = statistics.median(t['times'][irr])
        L.append('SH frames against the irradiance frame (f32 store):\n')
        L.append('| mode | median frame (s) | ratio of the medians | '
                 'median of the rounds\' ratios (quartiles) |')
        L.append('| --- | --- | --- | --- |')
        for m in t['modes']:
            if not m.startswith('SH') and m != irr:
                continue
            med = statistics.median(t['times'][m])
            q = statistics.quantiles(t['ratios_irr'][m], n=4) \
                if len(t['ratios_irr'][m]) > 1 else [0, 0, 0]
            L.append('| %s | %.3f | %.2f | %.2f (%.2f-%.2f) |' % (
                m, med, med / mi, statistics.median(t['ratios_irr'][m]),
                q[0], q[2]))
        L.append('')
    if 'sht1' in res:
        L.append('## SH Table 1: bake-sh of the band against the lazy first '
                 'image\n')
        for name, d in res['sht1'].items():
            L.append('### %s, order %d\n' % (name, d['order']))
            L.append('| samples | full: the scene\'s isovalue (f32) | '
                     'paths/core-s | lazy first image | lazy paths | '
                     'lazy / full (CPU) |')
            L.append('| --- | --- | --- | --- | --- | --- |')
            for b, lz in zip(d['band'], d['lazy']):
                pc = b['paths_per_cpu_s'] if b['measured'] else None
                L.append('| %d | %s | %s | %s | %d | 1/%.1f |' % (
                    b['samples'], fmt_t(b), '%.0f' % pc if pc else '-',
                    fmt_t(lz), lz['paths'], b['cpu'] / lz['cpu']))
            c = d['cal'].get('band')
            if c is None or not d['lazy']:
                L.append('')
                continue
            L.append('')
            L.append('Texels: %d wanted; the lazy view reads %d.  '
                     'Calibration: %d samples, %.1f / %.1f s, %.0f paths '
                     'per core-second.\n' % (
                         c['wanted'], d['lazy'][0]['read'], c['samples'],
                         c['wall'], c['cpu'], c['paths_per_cpu_s']))
    if 'shcost' in res:
        r = res['shcost']
        irr = r['bakers'][0]
        mi = statistics.median(r['per_path'][irr])
        wi = statistics.median(r['whole'][irr])
        L.append('## bake-sh against bake-irr: CPU a path (%d texels, '
                 'scale %g, %d rounds)\n' % (r['wanted'], r['scale'],
                                             r['runs']))
        L.append('| baker | CPU us a path (16 - 4 samples) | ratio | '
                 'CPU us a path (whole process, 16 samples) | ratio |')
        L.append('| --- | --- | --- | --- | --- |')
        for b in r['bakers']:
            m = statistics.median(r['per_path'][b])
            w = statistics.median(r['whole'][b])
            L.append('| %s | %.2f | %.2f | %.2f | %.2f |' % (
                b, 1e6 * m, m / mi, 1e6 * w, w / wi))
        L.append('')
    if 'shmem' in res:
        r = res['shmem']
        L.append('## SH memory: bytes a texel (in memory / in the stream) '
                 'and the band (%s)\n' % r.get('dataset', '?'))
        L.append('| order | channels | accum | f32 | f16 | band: accum / '
                 'f32 / f16 (MB in memory) |')
        L.append('| --- | --- | --- | --- | --- | --- |')
        for n in (3, 5, 8):
            for ch in (1, 3):
                e = [r['orders'].get('%d/%d/%s' % (n, ch, st))
                     for st in ('accum', 'f32', 'f16')]
                if None in e:
                    continue
                L.append('| %d | %d | %s | %.1f / %.1f / %.1f |' % (
                    n, ch, ' | '.join('%d / %d' % (x['mem'], x['stream'])
                                      for x in e),
                    e[0]['mb'], e[1]['mb'], e[2]['mb']))
        L.append('')
        if r.get('big'):
            L.append('%s at scale 1, order 5, band %s (predicted by '
                     'bake-sh -n --explain):\n' % (r['big_dataset'],
                                                    r['big_band']))
            L.append('| band | channels | store | wanted texels | bricks | '
                     'MB in memory | under 8 GB |')
            L.append('| --- | --- | --- | --- | --- | --- | --- |')
            for k, e in r['big'].items():
                band, ch, st = k.split('/')
                L.append('| --%s %s | %s | %s | %d | %d | %.0f | %s |' % (
                    band, r['big_band'], ch, st, e['wanted'], e['bricks'],
                    e['mb'], 'yes' if e['mb'] < 8000 else 'no'))
            L.append('')
        if r.get('check'):
            L.append('Check (the scene\'s isovalue band, --samples 1):\n')
            L.append('| store | wanted | predicted MB | max RSS MB |')
            L.append('| --- | --- | --- | --- |')
            for st, v in r['check'].items():
                L.append('| %s | %d | %.0f | %.0f |' % (
                    st, v['wanted'], v['predicted_mb'], v['maxrss_mb']))
            L.append('')
    if 'acc' in res:
        r = res['acc']
        L.append('## Accuracy: irradiance shading against the path-traced '
                 'reference\n')
        L.append('%dx%d, lattice scale 1, %d samples a texel (%d texels '
                 'read, baked lazily), reference %d paths a pixel: relative '
                 'RMSE over covered pixels %.4f (%.2f%%); the reference\'s '
                 'own noise about %.4f (from a reference of %d paths: '
                 'RMSE %.4f against it).\n' % (
                     r['size'], r['size'], r['samples'], r['texels'],
                     r['spp'], r['relrmse'], 100 * r['relrmse'],
                     r['ref_noise'], r['spp'] // 4, r['relrmse_ref4']))
    if 'mem' in res:
        L.append('## Memory\n')
        L.append('| dataset | lattice | bricks stored / all | wanted texels '
                 '| accum (48 B) | f32 (16 B) | f16 (8 B) | every brick as '
                 'accum |')
        L.append('| --- | --- | --- | --- | --- | --- | --- | --- |')
        for name, m in res['mem'].items():
            full = m['bricks_total'] * 512 * 48 + m['bricks_total'] * 4
            L.append('| %s | %s | %d / %d (%.0f%%) | %d of %d (%.0f%%) | '
                     '%.1f MB | %.1f MB | %.1f MB | %.1f MB |' % (
                         name, 'x'.join(map(str, m['lattice_dims'])),
                         m['bricks'], m['bricks_total'],
                         100.0 * m['bricks'] / m['bricks_total'], m['wanted'],
                         m['texels'], 100.0 * m['wanted'] / m['texels'],
                         m['bytes'] / 1e6, m['bytes_f32'] / 1e6,
                         m['bytes_f16'] / 1e6, full / 1e6))
        L.append('')
    return '\n'.join(L) + '\n'


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--bin', default='../../bin')
    ap.add_argument('--out', default='out/gi')
    ap.add_argument('--runs', type=int, default=5)
    ap.add_argument('--dataset', nargs=4, action='append', default=[],
                    metavar=('NAME', 'STREAM', 'SCENE', 'ISO_RANGE'))
    ap.add_argument('--parts', default='t1,t2,acc,mem')
    ap.add_argument('--samples', default='16,100,625')
    ap.add_argument('--max-paths', type=float, default=2e7)
    ap.add_argument('--max-lazy-paths', type=float, default=8e7)
    ap.add_argument('--acc-size', type=int, default=256)
    ap.add_argument('--acc-spp', type=int, default=1024)
    ap.add_argument('--acc-samples', type=int, default=256)
    ap.add_argument('--sh-order', type=int, default=5)
    ap.add_argument('--sh-cost-scale', type=float, default=0.5)
    ap.add_argument('--sh-vhf-band', default='600.5,1224.5')
    ap.add_argument('--tables', action='store_true',
                    help='only write gi.md from gi.json')
    a = ap.parse_args()
    if a.tables:
        res = json.load(open(os.path.join(a.out, 'gi.json')))
    else:
        b = Bench(a)
        b.samples = [int(s) for s in a.samples.split(',')]
        jp = os.path.join(a.out, 'gi.json')
        if os.path.exists(jp):
            b.res.update(json.load(open(jp)))
        parts = a.parts.split(',')
        # sht1 before t2: its 4-sample f32 bake is Table 2's SH store
        for p, fn in (('t1', b.table1), ('sht1', b.sh_table1),
                      ('t2', b.table2), ('acc', b.accuracy),
                      ('mem', b.memory), ('shcost', b.sh_cost),
                      ('shmem', b.sh_memory)):
            if p in parts:
                fn()
        res = b.res
    with open(os.path.join(a.out, 'gi.md'), 'w') as f:
        f.write(tables(res))
    sys.stdout.write(tables(res))


if __name__ == '__main__':
    main()
