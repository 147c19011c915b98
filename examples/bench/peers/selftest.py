#!/usr/bin/python3
"""Self-test of the peers on small synthetic volumes (a few seconds): camera conventions,
world frame, mesh format, image orientation.  Run by `make -C examples/bench check`.

usage: selftest.py --embree PATH/embree_render --work DIR [--probe PATH/camera_probe]
                   [--embree-pt PATH/embree_pt] [--vxbin VOXLUX/bin]

1. Sphere (anisotropic spacing, non-zero origin) -> extract.py -> embree_render, both
   orthographic and perspective.  Oracle: analytic ray-sphere intersection written here
   with numpy from the camera convention in camera.py's docstring; the Lambert headlight
   shade is |n . d| with the exact sphere normal.  The sphere sits in the upper left of
   the image, so a flipped axis cannot pass.
2. mip_ref.py against brute-force trilinear sampling (step 0.002) along a few rays.
3. teem-mrender and VTK against mip_ref.py on a blob volume (fine steps), axis-aligned
   views along x, y and z with non-square images: checks that both peers sample the same
   pixel grid and world box.
4. With --embree-pt: the path tracer on the sphere's mesh.  Oracles: the white furnace
   (a sky of radiance 1, albedo a, no light: every covered pixel is a, at any bounce
   count, for a convex surface: every bounce ray escapes); a directional light alone
   (bounces 0): a * I * max(0, n . l) with the exact sphere normal; -j 1 and -j 2, and
   --packets and single rays, give the same bytes.
5. DVR peers (dvr_miter.sh, dvr_vtk.py and, with --vxbin, voxlux's dvr) on a box of
   constant material: emission-absorption by formula (test_dvr_peers says how).
0. With --probe (camera_probe.c, linked with libvoxlux): voxlux's own vx_camera_ray
   against camera.py and this file's ray generator, for perspective and orthographic
   cameras, non-square images, a slanted up and an up parallel to the view.
Prints TAP-style lines; exits 1 if any check fails.
"""
import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import numpy as np  # noqa: E402
import dvr_tf  # noqa: E402
import volio  # noqa: E402

PY = sys.executable
failures = 0
count = 0


def check(ok, what):
    global failures, count
    count += 1
    print("%s %d - %s" % ("ok" if ok else "not ok", count, what))
    if not ok:
        failures += 1


def run(cmd):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        print(r.stdout, file=sys.stderr)
        raise SystemExit("selftest: failed: %s" % " ".join(cmd))
    return r.stdout


def rays(eye, look, up, w, h, fov=None, ortho=None):
    """Origins and directions [h, w, 3] by the convention (independent of the C code)."""
    eye, look, up = (np.array(x, float) for x in (eye, look, up))
    f = (look - eye) / np.linalg.norm(look - eye)
    u = np.cross(f, up)
    u /= np.linalg.norm(u)
    v = np.cross(u, f)
    sx = 2 * (np.arange(w) + 0.5) / w - 1
    sy = 1 - 2 * (np.arange(h) + 0.5) / h
    SX, SY = np.meshgrid(sx, sy)
    if ortho:   # ortho = the view's width, like voxlux's view_width
        o = eye + (SX * ortho / 2)[..., None] * u + (SY * ortho / 2 * h / w)[..., None] * v
        d = np.broadcast_to(f, o.shape)
    else:
        t = np.tan(np.radians(fov) / 2)
        d = f + (SX * t * w / h)[..., None] * u + (SY * t)[..., None] * v
        d = d / np.linalg.norm(d, axis=-1, keepdims=True)
        o = np.broadcast_to(eye, d.shape)
    return o, d


def sphere_shade(o, d, c, r):
    """Lambert headlight shade of the sphere (centre c, radius r), 0 where missed."""
    oc = o - c
    b = np.sum(oc * d, axis=-1)
    disc = b * b - (np.sum(oc * oc, axis=-1) - r * r)
    hit = disc > 0
    t = -b - np.sqrt(np.where(hit, disc, 0))
    p = o + t[..., None] * d
    n = (p - c) / r
    return np.where(hit, np.abs(np.sum(n * d, axis=-1)), 0.0), hit


def test_sphere(embree, work):
    sp, org, c, r = (1.0, 0.8, 1.25), (-10.0, 4.0, 2.0), np.array([8.0, 20.0, 24.0]), 11.0
    dims = (40, 44, 36)
    k, j, i = np.mgrid[0:dims[2], 0:dims[1], 0:dims[0]]
    pts = [org[a] + idx * sp[a] for a, idx in enumerate((i, j, k))]
    dist = np.sqrt(sum((pts[a] - c[a]) ** 2 for a in range(3))).astype(np.float32)
    vol = os.path.join(work, "sphere.nrrd")
    volio.write_nrrd(vol, volio.Volume(dist, sp, org))
    mesh = os.path.join(work, "sphere.mesh")
    out = run([PY, os.path.join(HERE, "extract.py"), vol, "--iso", str(r), "--runs", "1",
               "-o", mesh])
    check("triangles" in out, "extract.py writes a sphere mesh")
    # the look point is offset so that the sphere lands in the upper left quadrant
    look = c + np.array([9.0, 0.0, -9.0])
    views = [("ortho", ["--ortho", "60"], dict(ortho=60.0)),
             ("perspective", ["--fov", "40"], dict(fov=40.0))]
    for name, flags, kw in views:
        eye = look + np.array([0.0, -90.0, 0.0])
        img = os.path.join(work, "sphere-%s.pfm" % name)
        w, h = 96, 80
        run([embree, "-m", mesh, "-o", img, "-n", "1", "--size", str(w), str(h),
             "--eye"] + ["%g" % x for x in eye] + ["--look"] + ["%g" % x for x in look]
            + ["--up", "0", "0", "1"] + flags)
        got = volio.read_image(img)
        o, d = rays(eye, look, (0, 0, 1), w, h, **kw)
        want, hit = sphere_shade(o, d, c, r)
        ys, xs = np.nonzero(hit)
        check(xs.mean() < w / 2 and ys.mean() < h / 2,
              "%s: analytic sphere in the upper left (oracle sanity)" % name)
        gy, gx = np.nonzero(got > 0)
        check(abs(gx.mean() - xs.mean()) < 0.5 and abs(gy.mean() - ys.mean()) < 0.5,
              "%s: hit centroid (%.2f,%.2f) vs analytic (%.2f,%.2f)"
              % (name, gx.mean(), gy.mean(), xs.mean(), ys.mean()))
        mism = np.mean((got > 0) != hit)
        check(mism < 0.01, "%s: coverage differs on %.4f of the pixels" % (name, mism))
        inner = hit & (want > 0.4)
        err = np.abs(got - want)[inner].max()
        check(err < 0.03, "%s: max shade error %.4f inside the silhouette" % (name, err))


def test_pathtracer(embree_pt, work):
    """embree_pt on test_sphere's mesh (made there)."""
    c, r = np.array([8.0, 20.0, 24.0]), 11.0
    mesh = os.path.join(work, "sphere.mesh")
    look = c + np.array([9.0, 0.0, -9.0])
    eye = look + np.array([0.0, -90.0, 0.0])
    w, h = 96, 80
    cam = ["--eye"] + ["%g" % x for x in eye] + ["--look"] + ["%g" % x for x in look] + \
        ["--up", "0", "0", "1", "--fov", "40", "--size", str(w), str(h)]
    o, d = rays(eye, look, (0, 0, 1), w, h, fov=40.0)
    want_lit, hit = sphere_shade(o, d, c, r)
    oc = o - c
    b = np.sum(oc * d, axis=-1)
    t = -b - np.sqrt(np.maximum(b * b - (np.sum(oc * oc, axis=-1) - r * r), 0))
    n = (o + t[..., None] * d - c) / r
    inner = hit & (want_lit > 0.4)

    def render(name, flags, j="2"):
        img = os.path.join(work, "pt-%s.pfm" % name)
        out = run([embree_pt, "-m", mesh, "-o", img, "-j", j] + cam + flags)
        with open(img, "rb") as fh:
            data = fh.read()
        a = np.frombuffer(data[len(data) - w * h * 12:], dtype="<f4").reshape(h, w, 3)
        return np.flipud(a).astype(float), out

    alb = (0.8, 0.6, 0.4)
    for bounces in ("0", "1", "3"):
        img, out = render("furnace-%s" % bounces, ["--sky", "1", "1", "1", "--albedo"] +
                          ["%g" % x for x in alb] + ["--bounces", bounces, "--spp", "8"])
        got = img[inner]
        exact = np.mean(np.all(np.abs(got - np.array(alb)) < 1e-6, axis=1))
        mean = got.mean(0)
        # a bounce ray blocked by the mesh itself (a direction about the interpolated
        # normal below a facet's plane) darkens its pixel by a / spp: rare on this sphere
        check(exact > 0.97 and np.abs(mean - alb).max() < 0.002,
              "embree_pt: white furnace, bounces %s: mean %s, %.4f of the pixels exact"
              % (bounces, " ".join("%.4f" % x for x in mean), exact))
    cov = np.mean((img.sum(2) > 0) != hit)
    check(cov < 0.01, "embree_pt: coverage differs on %.4f of the pixels" % cov)
    ldir = np.array([0.5, 2.0, -1.0])          # the light travels along ldir (away from the eye)
    l = -ldir / np.linalg.norm(ldir)
    want = 0.5 * 1.5 * np.maximum(0, np.sum(n * l, axis=-1))
    img, out = render("sun", ["--sky", "0", "0", "0", "--albedo", "0.5", "0.5", "0.5",
                              "--sun"] + ["%g" % x for x in ldir] + ["1.5", "1.5", "1.5"] +
                      ["--bounces", "0", "--spp", "2"])
    sel = inner & (np.sum(n * l, axis=-1) > 0.2)
    err = np.abs(img[..., 1] - want)[sel].max()
    check(err < 0.02, "embree_pt: directional light a I max(0, n.l): max error %.4f "
          "(%d pixels)" % (err, sel.sum()))
    img1, _ = render("sun-j1", ["--sky", "0.3", "0.3", "0.3", "--albedo", "0.5", "0.5", "0.5",
                                "--sun"] + ["%g" % x for x in ldir] + ["1.5", "1.5", "1.5"] +
                     ["--spp", "4"], j="1")
    img2, _ = render("sun-j2", ["--sky", "0.3", "0.3", "0.3", "--albedo", "0.5", "0.5", "0.5",
                                "--sun"] + ["%g" % x for x in ldir] + ["1.5", "1.5", "1.5"] +
                     ["--spp", "4"], j="2")
    check(np.array_equal(img1, img2), "embree_pt: -j 1 and -j 2 give the same picture")
    flags = ["--sky", "0.3", "0.3", "0.3", "--albedo", "0.5", "0.5", "0.5", "--sun"] + \
        ["%g" % x for x in ldir] + ["1.5", "1.5", "1.5"] + ["--spp", "20", "--bounces", "2"]
    img1, _ = render("single", flags)
    img2, _ = render("packets", flags + ["--packets"])
    check(np.array_equal(img1, img2), "embree_pt: --packets (16 + 4 rays) gives the same picture")


PROBE_CAMERAS = [
    ("perspective", 35.0, 96, 64, (3, -40, 12), (1, 2, 5), (0.2, 0.1, 1)),
    ("ortho", 70.0, 64, 96, (30, 20, -50), (0, 1, 2), (0, 1, 0)),
    ("ortho", 25.0, 50, 50, (0, 0, 90), (0, 0, 0), (0, 0, 1)),        # up parallel: fallback
    ("perspective", 60.0, 40, 30, (5, -80, 3), (5, 0, 3), (0, 1, 0)),  # up parallel: fallback
]


def test_probe(probe, work):
    import camera
    for kind, val, w, h, eye, look, up in PROBE_CAMERAS:
        px = [0, w - 1, w // 2, 3, w - 2]
        py = [0, h - 1, h // 3, h - 1, 1]
        args = ["ortho" if kind == "ortho" else "persp"] + [str(x) for x in
                                                              (val, w, h) + eye + look + up]
        pix = [str(v) for pair in zip(px, py) for v in pair]
        lines = run([probe] + args + pix).split("\n")
        got = np.array([[float(x) for x in ln.split()[2:]] for ln in lines if ln.strip()])
        ns = argparse.Namespace(eye=list(eye), look=list(look), up=list(up), size=[w, h],
                                fov=None if kind == "ortho" else val,
                                ortho=val if kind == "ortho" else None)
        f, u, v = camera.frame(ns)
        sx = 2 * (np.array(px) + 0.5) / w - 1
        sy = 1 - 2 * (np.array(py) + 0.5) / h
        if kind == "ortho":
            hw, hh = camera.half_extents(ns)
            o = np.array(eye) + sx[:, None] * hw * u + sy[:, None] * hh * v
            d = np.broadcast_to(f, o.shape)
        else:
            t = np.tan(np.radians(val) / 2)
            d = f + (sx * t * w / h)[:, None] * u + (sy * t)[:, None] * v
            d /= np.linalg.norm(d, axis=1, keepdims=True)
            o = np.broadcast_to(np.array(eye, float), d.shape)
        err = np.abs(got - np.hstack([o, d])).max()
        check(err < 1e-9, "camera.py vs vx_camera_ray, %s %dx%d up %s: %.3g"
              % (kind, w, h, up, err))
        scn = os.path.join(work, "probe.scn")
        with open(scn, "w") as fh:
            fh.write(camera.scene_text(ns, 12.5))
        r = subprocess.run([probe, "scene", scn] + pix, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
        sc = np.array([[float(x) for x in ln.split()[2:]] for ln in r.stdout.split("\n")
                       if ln.strip()]) if r.returncode == 0 else None
        check(sc is not None and np.array_equal(sc, got) and "iso 12.5" in r.stderr,
              "camera.py scene: vx_scene_read gives the same camera and the iso (%s)"
              % (r.stderr.strip() if r.returncode else "rays identical"))
        if np.linalg.norm(np.cross(np.subtract(look, eye), up)) > 0:
            ro, rd = rays(eye, look, up, w, h, **({"ortho": val} if kind == "ortho"
                                                    else {"fov": val}))
            err = max(np.abs(ro[py, px] - got[:, :3]).max(), np.abs(rd[py, px] - got[:, 3:]).max())
            check(err < 1e-9, "selftest rays() vs vx_camera_ray, %s: %.3g" % (kind, err))


def trilinear(a, q):
    """a[k, j, i] at index positions q [n, 3] (x, y, z) inside the lattice."""
    n = np.array(a.shape[::-1])
    i0 = np.minimum(np.floor(q).astype(int), n - 2)
    f = q - i0
    s = np.zeros(len(q))
    for dk in (0, 1):
        for dj in (0, 1):
            for di in (0, 1):
                wgt = ((f[:, 0] if di else 1 - f[:, 0]) * (f[:, 1] if dj else 1 - f[:, 1])
                       * (f[:, 2] if dk else 1 - f[:, 2]))
                s += wgt * a[i0[:, 2] + dk, i0[:, 1] + dj, i0[:, 0] + di]
    return s


def blob_volume(work):
    sp, org = (1.5, 1.0, 2.0), (-10.0, 5.0, 3.0)
    k, j, i = np.mgrid[0:20, 0:30, 0:40]
    x, y, z = org[0] + i * sp[0], org[1] + j * sp[1], org[2] + k * sp[2]
    a = (1000 * np.exp(-((x - 20) ** 2 + (y - 18) ** 2 + (z - 20) ** 2) / 72.0)
         + 300 * np.exp(-((x - 5) ** 2 + (y - 25) ** 2 + (z - 35) ** 2) / 18.0))
    # a thin bright line off the lattice planes makes the maximum fall between samples
    a[10, 12, 5:35] += 400 * (np.arange(30) % 3 == 0)
    path = os.path.join(work, "blob.nrrd")
    vol = volio.Volume(a.astype(np.float32), sp, org)
    volio.write_nrrd(path, vol)
    return path, vol


BLOB_VIEWS = [
    ("along +y", "--eye 19.25 -100 22 --look 19.25 19.5 22 --up 0 0 1 --ortho 50 --size 64 48"),
    ("along -x", "--eye 100 19.5 22 --look 0 19.5 22 --up 0 0 1 --ortho 45 --size 50 56"),
    ("along -z", "--eye 19.25 19.5 200 --look 19.25 19.5 22 --up 0 1 0 --ortho 61 --size 40 70"),
]


def test_mip_ref(work):
    path, vol = blob_volume(work)
    data = vol.data.astype(np.float64)
    for name, cam in BLOB_VIEWS:
        img = os.path.join(work, "blob-ref.pfm")
        run([PY, os.path.join(HERE, "mip_ref.py"), path, "-o", img] + cam.split())
        ref = volio.read_image(img)
        a = cam.split()
        eye = [float(x) for x in a[1:4]]
        look = [float(x) for x in a[5:8]]
        up = [float(x) for x in a[9:12]]
        w, h = int(a[15]), int(a[16])
        o, d = rays(eye, look, up, w, h, ortho=float(a[13]))
        rng = np.random.default_rng(7)
        worst = 0.0
        for _ in range(12):
            py, px = int(rng.integers(h)), int(rng.integers(w))
            t = np.arange(0, 300, 0.002)
            q = ((o[py, px] + t[:, None] * d[py, px]) - np.array(vol.origin)) \
                / np.array(vol.spacing)
            q = q[np.all((q >= 0) & (q <= np.array(vol.dims) - 1), axis=1)]
            best = trilinear(data, q).max() if len(q) else 0.0
            worst = max(worst, abs(best - ref[py, px]))
        check(worst < 0.05, "mip_ref %s: brute force differs by %.4g" % (name, worst))


def test_mip_peers(work):
    path, _ = blob_volume(work)
    for name, cam in BLOB_VIEWS:
        ref_p = os.path.join(work, "blob-ref.pfm")
        run([PY, os.path.join(HERE, "mip_ref.py"), path, "-o", ref_p] + cam.split())
        ref = volio.read_image(ref_p)
        rng = ref.max()
        tp = os.path.join(work, "blob-teem.pfm")
        run(["sh", os.path.join(HERE, "mip_teem.sh"), "-n", "1", "-s", "0.01", path, tp]
            + cam.split())
        t = volio.read_image(tp)
        err = np.abs(t - ref).max()
        check(err < 1e-3 * rng, "teem %s: max error %.4g (range %.4g)" % (name, err, rng))
        vp = os.path.join(work, "blob-vtk.pfm")
        run(["xvfb-run", "-a", PY, os.path.join(HERE, "mip_vtk.py"), path, "-o", vp,
             "--step", "0.01", "--runs", "1"] + cam.split())
        v = volio.read_image(vp)
        both = (v != 0) & (ref != 0)
        err = np.abs(v - ref)[both].max()
        check(err < 5e-3 * rng, "vtk %s: max error %.4g where it renders" % (name, err))
        missed = (ref != 0) & (v == 0)
        # pixels next to the outline: a neighbour (8-connected, or off the image)
        # whose ray misses the volume
        out = np.pad(ref == 0, 1, constant_values=True)
        near = np.zeros_like(missed)
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                near |= out[1 + dy:out.shape[0] - 1 + dy, 1 + dx:out.shape[1] - 1 + dx]
        extra = int(np.sum((ref == 0) & (v != 0)))
        check(not np.any(missed & ~near) and extra == 0,
              "vtk %s: %d pixels (%.3f of those covered) unrendered, all next to the "
              "outline; %d extra" % (name, missed.sum(), missed.sum() / np.sum(ref != 0),
                                     extra))


SLAB_VIEWS = [
    # (name, camera flags, thickness along the view in world units)
    ("along -z", "--eye 30 17 200 --look 30 17 20 --up 0 1 0 --ortho 80 --size 64 48", 38.0),
    ("along +y", "--eye 30 -100 20 --look 30 17 20 --up 0 0 1 --ortho 70 --size 50 56", 29.0),
]
SLAB_ALPHA, SLAB_RGB = 0.05, (0.8, 0.5, 0.2)


def test_dvr_peers(work, vxbin=None):
    """A box of constant value (40 x 30 x 20 samples, spacing 1.5 1 2, origin 0 2 1),
    opacity 0.05 per world unit, colour (0.8, 0.5, 0.2), viewed orthographically along
    two axes.  Oracle: emission-absorption through a thickness L of constant material,
    premultiplied colour C (1 - (1 - a)^L), alpha 1 - (1 - a)^L, for rays whose footprint
    lies inside the box (a pixel away from its outline), 0 for rays that miss it (a pixel
    away too).  miter (-n1 1, its near plane half a step inside the box) samples L planes
    and must be exact to float rounding (1e-5); voxlux's dvr, when --vxbin is given, too
    (its alpha is read from the red channel).  VTK steps 1 along each ray from where it
    enters the box and takes L samples here, in 15-bit fixed point: within 2e-3 (one
    sample more or less is off by 4e-3 to 6e-3)."""
    sp, org, dims = (1.5, 1.0, 2.0), (0.0, 2.0, 1.0), (40, 30, 20)
    vol = volio.Volume(np.full(dims[::-1], 100, dtype=np.uint8), sp, org)
    path = os.path.join(work, "slab.nrrd")
    volio.write_nrrd(path, vol)
    scene = os.path.join(work, "slab.scn")
    with open(scene, "w") as fh:
        fh.write("voxlux-scene 1\ntransfer opacity 0 %g 255 %g\n"
                 "transfer color 0 %g %g %g 255 %g %g %g\ntransfer step 1\n"
                 % ((SLAB_ALPHA, SLAB_ALPHA) + SLAB_RGB + SLAB_RGB))
    txf = os.path.join(work, "slab.txf")
    run([PY, os.path.join(HERE, "dvr_tf.py"), "txf", scene, txf, "--range", "0", "255"])
    lo = np.array(org)
    hi = lo + (np.array(dims) - 1) * np.array(sp)
    for name, cam, thick in SLAB_VIEWS:
        a = cam.split()
        eye = [float(x) for x in a[1:4]]
        look = [float(x) for x in a[5:8]]
        up = [float(x) for x in a[9:12]]
        w, h = int(a[15]), int(a[16])
        o, d = rays(eye, look, up, w, h, ortho=float(a[13]))
        # footprint: the ray's position across the view axis, inside the box by a pixel
        pix = float(a[13]) / w
        axis = int(np.argmax(np.abs(d[0, 0])))
        inside = np.ones((h, w), bool)
        outside = np.zeros((h, w), bool)
        for c in range(3):
            if c == axis:
                continue
            inside &= (o[:, :, c] > lo[c] + pix) & (o[:, :, c] < hi[c] - pix)
            outside |= (o[:, :, c] < lo[c] - pix) | (o[:, :, c] > hi[c] + pix)
        cov = 1 - (1 - SLAB_ALPHA) ** thick
        want = np.array(SLAB_RGB) * cov

        def verdict(tool, rgb, alpha, tol):
            ok_in = np.all(np.abs(rgb[inside] - want) <= tol)
            ok_a = np.all(np.abs(alpha[inside] - cov) <= tol)
            ok_out = not np.any(rgb[outside] != 0)
            check(ok_in and ok_a and ok_out and inside.sum() > 100 and outside.sum() > 100,
                  "dvr %s %s: colour %s alpha %.5f..%.5f inside (want %s, %.5f), "
                  "%d of %d outside pixels 0" % (
                      tool, name, np.round(rgb[inside].mean(0), 5), alpha[inside].min(),
                      alpha[inside].max(), np.round(want, 5), cov,
                      int(np.sum(~np.any(rgb[outside] != 0, axis=1))), int(outside.sum())))
        mp = os.path.join(work, "slab-miter.pfm")
        run(["sh", os.path.join(HERE, "dvr_miter.sh"), "-n", "1", "-t", "1", path, txf, mp]
            + a)
        verdict("teem-miter", volio.read_pfm_rgb(mp), volio.read_pfm(mp[:-4] + ".alpha.pfm"),
                1e-5)
        vp = os.path.join(work, "slab-vtk.pfm")
        run(["xvfb-run", "-a", PY, os.path.join(HERE, "dvr_vtk.py"), path, "--scene", scene,
             "-o", vp, "--runs", "1"] + a)
        verdict("VTK", volio.read_pfm_rgb(vp), volio.read_pfm(vp[:-4] + ".alpha.pfm"), 2e-3)
        if vxbin:
            sc = os.path.join(work, "slab-%d.scn" % axis)
            with open(sc, "w") as fh:
                fh.write(dvr_tf.variant_scene(dvr_tf.parse_scene(scene), "unshaded", a))
            xp = os.path.join(work, "slab-voxlux.pfm")
            run(["sh", "-c", "%s %s | %s --scene %s --hdr --pfm %s -o %s" % (
                os.path.join(vxbin, "vread"), path, os.path.join(vxbin, "dvr"), sc, xp,
                os.path.join(work, "slab-voxlux.vx"))])
            rgb = volio.read_pfm_rgb(xp)
            verdict("voxlux", rgb, rgb[:, :, 0] / SLAB_RGB[0], 1e-5)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--embree", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--probe", help="camera_probe (voxlux's vx_camera_ray)")
    p.add_argument("--embree-pt", help="embree_pt (the path tracer)")
    p.add_argument("--vxbin", help="voxlux's bin/ (its dvr against the slab's oracle)")
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    if args.probe:
        test_probe(args.probe, args.work)
    test_sphere(args.embree, args.work)
    if args.embree_pt:
        test_pathtracer(args.embree_pt, args.work)
    test_mip_ref(args.work)
    test_mip_peers(args.work)
    test_dvr_peers(args.work, args.vxbin)
    print("1..%d" % count)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
