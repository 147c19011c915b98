#!/usr/bin/python3
"""Volume and image I/O shared by the benchmark peers (NRRD, raw, NIfTI-1, PFM, PNG).

Only numpy and the standard library are used, so every peer sees the same samples
and the same world frame: world = origin + index * spacing, index (i,j,k) with i
fastest in the file.  Volumes come back as numpy arrays indexed [k, j, i].

Command line:
  volio.py tonrrd IN OUT.nrrd [volume flags]   convert a volume to a raw NRRD that
                                               teem, VTK and voxlux's vread can read
  volio.py topng IMG OUT.png [--range LO HI]   float image (PFM/NRRD) to 8-bit gray PNG
  volio.py info IN [volume flags]              print dims, type, spacing, origin, range
  volio.py nodeheader IN.nrrd OUT.nhdr          detached header for IN, adding
                                               "centers: node" if IN has no centers
Volume flags: --raw-dims X Y Z --raw-type u8|i8|u16|i16|u32|i32|f32|f64
  [--raw-endian little|big] [--raw-skip BYTES] [--spacing SX SY SZ] [--origin OX OY OZ]
"""
import gzip
import os
import struct
import sys
import zlib

import numpy as np

RAW_TYPES = {"u8": "u1", "i8": "i1", "u16": "u2", "i16": "i2", "u32": "u4",
             "i32": "i4", "f32": "f4", "f64": "f8"}

NRRD_TYPES = {
    "signed char": "i1", "int8": "i1", "int8_t": "i1",
    "uchar": "u1", "unsigned char": "u1", "uint8": "u1", "uint8_t": "u1",
    "short": "i2", "short int": "i2", "signed short": "i2", "signed short int": "i2",
    "int16": "i2", "int16_t": "i2",
    "ushort": "u2", "unsigned short": "u2", "unsigned short int": "u2", "uint16": "u2",
    "uint16_t": "u2",
    "int": "i4", "signed int": "i4", "int32": "i4", "int32_t": "i4",
    "uint": "u4", "unsigned int": "u4", "uint32": "u4", "uint32_t": "u4",
    "float": "f4", "double": "f8",
}
NRRD_NAMES = {"i1": "signed char", "u1": "uchar", "i2": "short", "u2": "ushort",
              "i4": "int", "u4": "uint", "f4": "float", "f8": "double"}

# Refuse headers that promise more than this many samples before reading the data.
MAX_SAMPLES = 1 << 31


class Volume:
    """A scalar volume: data[k, j, i], spacing and origin as (x, y, z) tuples."""

    def __init__(self, data, spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0)):
        self.data = data
        self.spacing = tuple(float(s) for s in spacing)
        self.origin = tuple(float(o) for o in origin)

    @property
    def dims(self):
        """(nx, ny, nz)"""
        return tuple(int(d) for d in self.data.shape[::-1])

    def world_box(self):
        """(lo, hi) world corners of the sample lattice (sample centres, not cell faces)."""
        lo = np.array(self.origin)
        hi = lo + (np.array(self.dims) - 1) * np.array(self.spacing)
        return lo, hi


def fail(msg):
    sys.exit("%s: %s" % (os.path.basename(sys.argv[0]), msg))


def _open_maybe_gz(path):
    with open(path, "rb") as f:
        magic = f.read(2)
    return gzip.open(path, "rb") if magic == b"\x1f\x8b" else open(path, "rb")


def _check_count(dims):
    n = 1
    for d in dims:
        if d <= 0:
            raise ValueError("bad dimension %d" % d)
        n *= d
    if n > MAX_SAMPLES:
        raise ValueError("volume of %d samples is larger than the limit %d" % (n, MAX_SAMPLES))
    return n


def read_raw(path, dims, rtype, endian="little", skip=0, spacing=(1, 1, 1), origin=(0, 0, 0)):
    """Header-less volume (optionally gzipped), x fastest."""
    if rtype not in RAW_TYPES:
        raise ValueError("unknown raw type %r (one of %s)" % (rtype, ", ".join(RAW_TYPES)))
    dt = np.dtype(("<" if endian == "little" else ">") + RAW_TYPES[rtype])
    n = _check_count(dims)
    with _open_maybe_gz(path) as f:
        if skip:
            f.read(skip)
        buf = f.read(n * dt.itemsize)
    if len(buf) != n * dt.itemsize:
        raise ValueError("%s: %d bytes of data, %d needed" % (path, len(buf), n * dt.itemsize))
    a = np.frombuffer(buf, dtype=dt).reshape(dims[2], dims[1], dims[0])
    return Volume(a.astype(dt.newbyteorder("=")), spacing, origin)


def _parse_vec(s):
    s = s.strip()
    if s == "none":
        return None
    if not (s.startswith("(") and s.endswith(")")):
        raise ValueError("bad vector %r" % s)
    return [float(x) for x in s[1:-1].split(",")]


def _split_vecs(s):
    out, depth, cur = [], 0, ""
    for ch in s.strip():
        if ch == "(":
            depth += 1
        if depth or ch not in " \t":
            cur += ch
        if ch == ")":
            depth -= 1
            out.append(cur)
            cur = ""
        elif ch in " \t" and depth == 0 and cur:
            out.append(cur)
            cur = ""
    if cur:
        out.append(cur)
    return out


def read_nrrd_header(f):
    """Read the text header of an open NRRD file; returns (fields dict, keyvals)."""
    magic = f.readline()
    if not magic.startswith(b"NRRD000"):
        raise ValueError("not a NRRD file (magic %r)" % magic[:8])
    fields, keyvals = {}, {}
    while True:
        line = f.readline()
        if len(line) > 65536:
            raise ValueError("NRRD header line too long")
        if not line:
            break
        line = line.decode("latin-1").rstrip("\r\n")
        if line == "":
            break
        if line.startswith("#"):
            continue
        if ":=" in line:
            k, v = line.split(":=", 1)
            keyvals[k] = v
            continue
        if ": " not in line:
            raise ValueError("bad NRRD header line %r" % line)
        k, v = line.split(": ", 1)
        fields[k.strip().lower()] = v.strip()
    return fields, keyvals


def nrrd_geometry(fields):
    """(sizes, spacing, origin) of a 3-D NRRD from its header fields; space directions
    must be axis-aligned (diagonal)."""
    sizes = [int(x) for x in fields["sizes"].split()]
    spacing, origin = [1.0, 1.0, 1.0], [0.0, 0.0, 0.0]
    if "space directions" in fields:
        vecs = [_parse_vec(v) for v in _split_vecs(fields["space directions"])]
        if len(vecs) != 3 or any(v is None or len(v) != 3 for v in vecs):
            raise ValueError("NRRD space directions: need three 3-vectors")
        for ax in range(3):
            for c in range(3):
                if c != ax and vecs[ax][c] != 0.0:
                    raise ValueError("NRRD space directions are not axis-aligned")
            spacing[ax] = vecs[ax][ax]
    elif "spacings" in fields:
        spacing = [float(x) if x != "nan" else 1.0 for x in fields["spacings"].split()]
    if "space origin" in fields:
        origin = _parse_vec(fields["space origin"])
    return sizes, spacing, origin


def read_nrrd(path):
    """NRRD volume or image: raw or gzip encoding, attached or detached (data file:) data.
    Space directions must be axis-aligned (diagonal); returns a Volume for 3-D data and a
    plain 2-D float64 array for 2-D data (axis 0 fastest, as rows of the array)."""
    fields, a = read_nrrd_array(path)
    if a.ndim == 2:
        return a.astype(np.float64)
    _, spacing, origin = nrrd_geometry(fields)
    return Volume(a, spacing, origin)


def read_nrrd_array(path):
    """(fields, samples) of a 2-D or 3-D NRRD, the array indexed [axis 2, axis 1, axis 0]
    in the file's type (native byte order); no geometry is looked at."""
    with open(path, "rb") as f:
        fields, _ = read_nrrd_header(f)
        offset = f.tell()
    dim = int(fields.get("dimension", "0"))
    if dim not in (2, 3):
        raise ValueError("NRRD dimension %d (2 or 3 supported)" % dim)
    sizes = [int(x) for x in fields["sizes"].split()]
    if len(sizes) != dim:
        raise ValueError("NRRD sizes do not match dimension")
    t = fields.get("type", "").lower()
    if t not in NRRD_TYPES:
        raise ValueError("NRRD type %r not supported" % t)
    dt = np.dtype(NRRD_TYPES[t])
    if dt.itemsize > 1:
        endian = fields.get("endian", "little")
        dt = dt.newbyteorder("<" if endian == "little" else ">")
    enc = fields.get("encoding", "raw")
    if enc not in ("raw", "gzip", "gz"):
        raise ValueError("NRRD encoding %r not supported (raw, gzip)" % enc)
    n = _check_count(sizes)
    datafile = fields.get("data file", fields.get("datafile"))
    if datafile:
        dpath = os.path.join(os.path.dirname(path), datafile)
        src, start = dpath, 0
    else:
        src, start = path, offset
    with open(src, "rb") as f:
        f.seek(start)
        for _ in range(int(fields.get("line skip", "0"))):
            f.readline()
        bskip = int(fields.get("byte skip", "0"))
        if bskip > 0:
            f.read(bskip)
        if enc == "raw":
            if bskip == -1:
                f.seek(-n * dt.itemsize, 2)
            buf = f.read(n * dt.itemsize)
        else:
            z = zlib.decompressobj(16 + zlib.MAX_WBITS)
            buf = z.decompress(f.read(), n * dt.itemsize)
    if len(buf) != n * dt.itemsize:
        raise ValueError("%s: %d bytes of data, %d needed" % (path, len(buf), n * dt.itemsize))
    return fields, np.frombuffer(buf, dtype=dt).reshape(sizes[::-1]).astype(dt.newbyteorder("="))


def read_nifti(path):
    """NIfTI-1 single file (.nii or .nii.gz).  Spacing = pixdim[1..3].  Origin: the sform
    translation when sform_code > 0 and the sform is diagonal with positive entries, else
    the qform offset when qform_code > 0 and the quaternion is the identity, else 0."""
    with _open_maybe_gz(path) as f:
        hdr = f.read(352)
        if len(hdr) < 348:
            raise ValueError("NIfTI header too short")
        e = "<" if struct.unpack("<i", hdr[:4])[0] == 348 else ">"
        if struct.unpack(e + "i", hdr[:4])[0] != 348:
            raise ValueError("not a NIfTI-1 file")
        dim = struct.unpack(e + "8h", hdr[40:56])
        if dim[0] < 3 or any(d > 1 for d in dim[4:dim[0] + 1]):
            raise ValueError("NIfTI: need a 3-D scalar volume, dim = %s" % (dim,))
        datatype = struct.unpack(e + "h", hdr[70:72])[0]
        codes = {2: "u1", 4: "i2", 8: "i4", 16: "f4", 64: "f8", 256: "i1", 512: "u2", 768: "u4"}
        if datatype not in codes:
            raise ValueError("NIfTI datatype %d not supported" % datatype)
        pixdim = struct.unpack(e + "8f", hdr[76:108])
        vox_offset = int(struct.unpack(e + "f", hdr[108:112])[0])
        slope, inter = struct.unpack(e + "2f", hdr[112:120])
        qcode, scode = struct.unpack(e + "2h", hdr[252:256])
        quat = struct.unpack(e + "3f", hdr[256:268])
        qoff = struct.unpack(e + "3f", hdr[268:280])
        srow = [struct.unpack(e + "4f", hdr[280 + 16 * r:296 + 16 * r]) for r in range(3)]
        dims = dim[1:4]
        dt = np.dtype(e + codes[datatype])
        n = _check_count(dims)
        f.read(vox_offset - 352) if vox_offset > 352 else None
        buf = f.read(n * dt.itemsize)
    if len(buf) != n * dt.itemsize:
        raise ValueError("NIfTI: %d bytes of data, %d needed" % (len(buf), n * dt.itemsize))
    a = np.frombuffer(buf, dtype=dt).reshape(dims[2], dims[1], dims[0]).astype(dt.newbyteorder("="))
    if slope not in (0.0, 1.0) or inter != 0.0:
        a = a.astype(np.float32) * (slope or 1.0) + inter
    spacing = [abs(p) if p else 1.0 for p in pixdim[1:4]]
    origin = [0.0, 0.0, 0.0]
    diag = all(srow[r][c] == 0.0 for r in range(3) for c in range(3) if r != c)
    if scode > 0 and diag and all(srow[r][r] > 0 for r in range(3)):
        origin = [srow[r][3] for r in range(3)]
        spacing = [srow[r][r] for r in range(3)]
    elif qcode > 0 and quat == (0.0, 0.0, 0.0):
        origin = list(qoff)
    return Volume(a, spacing, origin)


def read_volume(path, args=None):
    """Read by content: NRRD magic, NIfTI (.nii/.nii.gz), else raw (needs args.raw_dims)."""
    raw_dims = getattr(args, "raw_dims", None) if args else None
    if raw_dims:
        vol = read_raw(path, raw_dims, args.raw_type, args.raw_endian, args.raw_skip)
    else:
        with _open_maybe_gz(path) as f:
            head = f.read(352)
        if head.startswith(b"NRRD000"):
            vol = read_nrrd(path)
        elif len(head) >= 348 and head[344:347] in (b"n+1", b"ni1"):
            vol = read_nifti(path)
        else:
            raise ValueError("%s: neither NRRD nor NIfTI-1; give --raw-dims and --raw-type"
                             % path)
    if args is not None:
        if getattr(args, "spacing", None):
            vol.spacing = tuple(args.spacing)
        if getattr(args, "origin", None):
            vol.origin = tuple(args.origin)
    return vol


def add_volume_args(p):
    """Add the volume flags (see the module doc) to an argparse parser."""
    p.add_argument("--raw-dims", type=int, nargs=3, metavar=("X", "Y", "Z"))
    p.add_argument("--raw-type", default="u8", choices=sorted(RAW_TYPES))
    p.add_argument("--raw-endian", default="little", choices=("little", "big"))
    p.add_argument("--raw-skip", type=int, default=0, metavar="BYTES")
    p.add_argument("--spacing", type=float, nargs=3, metavar=("SX", "SY", "SZ"))
    p.add_argument("--origin", type=float, nargs=3, metavar=("OX", "OY", "OZ"))


def write_nrrd(path, vol):
    """Raw little-endian NRRD with node centring, axis-aligned space directions and the
    space origin, so teem's gage and VTK agree with world = origin + index * spacing."""
    a = np.ascontiguousarray(vol.data)
    code = a.dtype.str[1:]
    if code not in NRRD_NAMES:
        raise ValueError("cannot write %s as NRRD" % a.dtype)
    sx, sy, sz = vol.spacing
    hdr = ("NRRD0005\n# written by voxlux examples/bench/peers/volio.py\n"
           "type: %s\ndimension: 3\nspace dimension: 3\nsizes: %d %d %d\n"
           "space directions: (%.17g,0,0) (0,%.17g,0) (0,0,%.17g)\n"
           "centers: node node node\nspace origin: (%.17g,%.17g,%.17g)\n"
           "endian: little\nencoding: raw\n\n"
           % ((NRRD_NAMES[code],) + vol.dims + (sx, sy, sz) + vol.origin))
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(hdr.encode())
        f.write(a.astype(a.dtype.newbyteorder("<")).tobytes())
    os.replace(tmp, path)


# ---- images: float arrays indexed [row, col], row 0 at the top ----

def _read_pfm_any(path):
    """A PFM's pixels as float64 [row, col, channels] (1 or 3), row 0 at the top (PFM
    stores rows bottom to top)."""
    with open(path, "rb") as f:
        kind = f.readline().strip()
        if kind not in (b"Pf", b"PF"):
            raise ValueError("%s: not a PFM file" % path)
        dims = f.readline().split()
        while len(dims) < 2:
            dims += f.readline().split()
        w, h = int(dims[0]), int(dims[1])
        scale = float(f.readline())
        ch = 3 if kind == b"PF" else 1
        _check_count((w, h, ch))
        buf = f.read(w * h * ch * 4)
    if len(buf) != w * h * ch * 4:
        raise ValueError("%s: truncated PFM" % path)
    a = np.frombuffer(buf, dtype="<f4" if scale < 0 else ">f4").reshape(h, w, ch)
    return np.flipud(a).astype(np.float64)


def read_pfm(path):
    """PFM ('Pf' gray or 'PF' RGB; RGB is reduced to its first channel), row 0 at the
    top."""
    return _read_pfm_any(path)[:, :, 0]


def write_pfm(path, img):
    """Gray PFM, little-endian, rows bottom to top as the format requires."""
    img = np.asarray(img, dtype="<f4")
    h, w = img.shape
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(b"Pf\n%d %d\n-1.0\n" % (w, h))
        f.write(np.flipud(img).tobytes())
    os.replace(tmp, path)


def write_pfm_rgb(path, img):
    """RGB PFM of img[row, col, 3] (row 0 at the top), little-endian, rows bottom to top."""
    img = np.asarray(img, dtype="<f4")
    h, w, _ = img.shape
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (w, h))
        f.write(np.ascontiguousarray(np.flipud(img)).tobytes())
    os.replace(tmp, path)


def read_pfm_rgb(path):
    """img[row, col, 3] (row 0 at the top) of an RGB PFM; a gray one is repeated."""
    a = _read_pfm_any(path)
    return a if a.shape[2] == 3 else np.repeat(a, 3, axis=2)


def write_png_rgb(path, img, scale=1.0, srgb=True):
    """8-bit PNG of an RGB image img[row, col, 3] times scale, clipped to [0, 1]:
    with srgb, a linear image through the sRGB transfer curve (as voxlux's PNGs);
    without, the codes are linear in the values (difference images)."""
    x = np.clip(np.nan_to_num(np.asarray(img, dtype=np.float64)) * scale, 0, 1)
    if srgb:
        x = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    g = (x * 255 + 0.5).astype(np.uint8)
    h, w, _ = g.shape
    raw = b"".join(b"\x00" + g[r].tobytes() for r in range(h))

    def chunk(t, d):
        c = struct.pack(">I", len(d)) + t + d
        return c + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(png)


def read_image(path):
    """A 2-D float image from PFM or NRRD (teem-mrender writes 2-D double NRRDs with
    axis 0 = u = columns, axis 1 = v = rows, row 0 first)."""
    with open(path, "rb") as f:
        magic = f.read(8)
    if magic.startswith(b"NRRD"):
        img = read_nrrd(path)
        if not isinstance(img, np.ndarray):
            raise ValueError("%s: a 3-D NRRD, not an image" % path)
        return img
    return read_pfm(path)


def write_png_gray(path, img, lo=None, hi=None):
    """8-bit gray PNG of img mapped linearly from [lo, hi] (default: image min/max)."""
    img = np.nan_to_num(np.asarray(img, dtype=np.float64))
    lo = float(img.min()) if lo is None else lo
    hi = float(img.max()) if hi is None else hi
    g = np.clip((img - lo) / ((hi - lo) or 1.0), 0, 1)
    g = (g * 255 + 0.5).astype(np.uint8)
    h, w = g.shape
    raw = b"".join(b"\x00" + g[r].tobytes() for r in range(h))

    def chunk(t, d):
        c = struct.pack(">I", len(d)) + t + d
        return c + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(png)


def node_header(src, dst):
    """Write dst, a detached NRRD header for the attached NRRD src with the same fields,
    plus "centers: node node node" unless src states its centring.  Teem's gage takes a
    NRRD without centers as cell-centred and then samples half a voxel beyond the
    lattice's box (voxlux's vwrite writes no centers)."""
    with open(src, "rb") as f:
        fields, keyvals = read_nrrd_header(f)
        f.seek(0)
        nlines = 0
        while True:
            line = f.readline()
            nlines += 1
            if not line or line.strip() == b"":
                break
    if "data file" in fields or "datafile" in fields:
        raise ValueError("%s: detached data is not supported here" % src)
    out = ["NRRD0004", "# node-centred view of %s" % os.path.abspath(src)]
    out += ["%s: %s" % (k, v) for k, v in fields.items()]
    if "centers" not in fields and "centerings" not in fields:
        out.append("centers: node node node")
    out += ["data file: %s" % os.path.abspath(src), "line skip: %d" % nlines]
    out += ["%s:=%s" % kv for kv in keyvals.items()]
    with open(dst, "w") as f:
        f.write("\n".join(out) + "\n\n")


def main():
    import argparse
    p = argparse.ArgumentParser(description="volume/image conversion for the peers")
    sub = p.add_subparsers(dest="cmd", required=True)
    a = sub.add_parser("tonrrd")
    a.add_argument("input")
    a.add_argument("output")
    add_volume_args(a)
    b = sub.add_parser("topng")
    b.add_argument("input")
    b.add_argument("output")
    b.add_argument("--range", type=float, nargs=2, metavar=("LO", "HI"))
    c = sub.add_parser("info")
    c.add_argument("input")
    add_volume_args(c)
    d = sub.add_parser("nodeheader")
    d.add_argument("input")
    d.add_argument("output")
    args = p.parse_args()
    try:
        if args.cmd == "tonrrd":
            write_nrrd(args.output, read_volume(args.input, args))
        elif args.cmd == "topng":
            img = read_image(args.input)
            lo, hi = args.range if args.range else (None, None)
            write_png_gray(args.output, img, lo, hi)
        elif args.cmd == "nodeheader":
            node_header(args.input, args.output)
        else:
            v = read_volume(args.input, args)
            print("dims %d %d %d type %s spacing %g %g %g origin %g %g %g range %g %g"
                  % (v.dims + (v.data.dtype,) + v.spacing + v.origin
                     + (v.data.min(), v.data.max())))
    except (OSError, ValueError, KeyError) as e:
        fail(str(e))


if __name__ == "__main__":
    main()
