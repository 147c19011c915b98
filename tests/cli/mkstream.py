#!/usr/bin/env python3
"""mkstream.py: build and take apart voxlux streams for the CLI tests,
independently of the C code (written from formats/stream.md alone).

  mkstream.py volume OUT --type T --dims NX NY NZ [--layout L] [--zlib]
              [--name N] [--spacing SX SY SZ] [--origin OX OY OZ]
              [--range LO HI | --no-range] [--formula EXPR] [--key K V]...
      a stream with one VOLM chunk; EXPR is a Python expression in x, y, z
      (default x + 3*y + 11*z); the range is computed unless given; each
      --key adds a header line "K: V" (before encoding).
  mkstream.py image OUT --size W H C [--formula EXPR]
      a stream with one IMAG chunk; EXPR in x, y, c.
  mkstream.py tetm OUT
      a stream with one TETM chunk (formats/tetmesh.md): the unit corner
      tetrahedron, scalars 0.5 1.5 2.5 3.5 on its vertices.
  mkstream.py add IN OUT TYPE TEXT [--at N]
      insert a chunk with payload TEXT at position N (default: the end).
  mkstream.py cat OUT IN...
      one stream with the chunks of all the inputs, in order.
  mkstream.py payload IN TYPE [--name N]
      write the payload of the first chunk of TYPE (with that name) to stdout.
  mkstream.py samples IN [--name N]
      write the volume's samples to stdout in x-fastest order, little-endian
      (what an NRRD body holds), whatever the stream's layout.
"""
import argparse
import math
import os
import struct
import sys
import zlib

SIG = b"\x89VXL\r\n\x1a\n"
FMT = {"u8": "B", "u16": "H", "i16": "h", "f32": "f"}


def chunk(typ, payload):
    t = typ.encode()
    return t + struct.pack("<Q", len(payload)) + payload + \
        struct.pack("<I", zlib.crc32(t + payload))


def write_stream(path, chunks):
    data = SIG + b"".join(chunk(t, p) for t, p in chunks) + chunk("VEND", b"")
    with open(path, "wb") as f:
        f.write(data)


def read_stream(path):
    data = open(path, "rb").read() if path != "-" else sys.stdin.buffer.read()
    assert data[:8] == SIG, "bad signature"
    pos, out = 8, []
    while True:
        typ = data[pos:pos + 4].decode()
        n = struct.unpack("<Q", data[pos + 4:pos + 12])[0]
        payload = data[pos + 12:pos + 12 + n]
        crc = struct.unpack("<I", data[pos + 12 + n:pos + 16 + n])[0]
        assert crc == zlib.crc32(typ.encode() + payload), "crc"
        pos += 16 + n
        if typ == "VEND":
            assert pos == len(data), "trailing bytes"
            return out
        out.append((typ, payload))


def parse_payload(payload):
    end = 0 if payload.startswith(b"\n") else payload.index(b"\n\n") + 1
    hdr = {}
    for line in payload[:end].decode("utf-8").split("\n")[:-1]:
        k, _, v = line.partition(":")
        hdr[k] = v[1:]
    body = payload[end + 1:]
    if hdr.get("encoding", "raw") == "zlib":
        body = zlib.decompress(body)
    return hdr, body


def layout_offsets(dims, spec):
    """Per-axis offset tables and the padded sample count (stream.md 9.3-9.4)."""
    if spec == "linear":
        nx, ny, nz = dims
        return ([i for i in range(nx)], [j * nx for j in range(ny)],
                [k * nx * ny for k in range(nz)]), nx * ny * nz
    words = spec.split(" ")
    assert words[0] == "bricked"
    b = [[int(e) for e in w.split("x")] for w in words[1:]]
    L = len(b)
    w = []
    for l in range(L):
        w.append([(w[l - 1][a] if l else 1) * b[l][a] for a in range(3)])
    V = [w[l][0] * w[l][1] * w[l][2] for l in range(L)]
    n = [-(-dims[a] // w[L - 1][a]) for a in range(3)]
    s0 = [1, b[0][0], b[0][0] * b[0][1]]
    S = [1, n[0], n[0] * n[1]]
    tabs = []
    for a in range(3):
        t = []
        for c in range(dims[a]):
            off = (c % w[0][a]) * s0[a]
            for l in range(1, L):
                sl = [1, b[l][0], b[l][0] * b[l][1]]
                off += ((c // w[l - 1][a]) % b[l][a]) * sl[a] * V[l - 1]
            off += (c // w[L - 1][a]) * S[a] * V[L - 1]
            t.append(off)
        tabs.append(t)
    return tabs, n[0] * n[1] * n[2] * V[L - 1]


def g17(v):
    return repr(float(v)) if v != int(v) else str(int(v))


def cmd_volume(a):
    nx, ny, nz = a.dims
    tabs, total = layout_offsets(a.dims, a.layout)
    vals = [0] * total
    fin = []
    for z in range(nz):
        for y in range(ny):
            for x in range(nx):
                v = eval(a.formula, {"math": math, "nan": math.nan,
                                     "inf": math.inf}, {"x": x, "y": y, "z": z})
                if a.type == "f32":
                    v = struct.unpack("<f", struct.pack("<f", v))[0]
                else:
                    v = int(v)
                vals[tabs[0][x] + tabs[1][y] + tabs[2][z]] = v
                if math.isfinite(v):
                    fin.append(v)
    body = struct.pack("<%d%s" % (total, FMT[a.type]), *vals)
    hdr = "name: %s\ndims: %d %d %d\ntype: %s\n" % (a.name, nx, ny, nz, a.type)
    hdr += "spacing: %s\norigin: %s\nlayout: %s\n" % (
        " ".join(a.spacing), " ".join(a.origin), a.layout)
    if a.range:
        hdr += "range: %s %s\n" % tuple(a.range)
    elif not a.no_range and fin:
        hdr += "range: %s %s\n" % (g17(min(fin)), g17(max(fin)))
    for k, v in getattr(a, "key", None) or []:
        hdr += "%s: %s\n" % (k, v)
    if a.zlib:
        body = zlib.compress(body, 6)
    hdr += "encoding: %s\n\n" % ("zlib" if a.zlib else "raw")
    write_stream(a.out, [("VOLM", hdr.encode() + body)])


def cmd_image(a):
    w, h, nc = a.size
    vals = [eval(a.formula, {"math": math, "nan": math.nan, "inf": math.inf},
                 {"x": x, "y": y, "c": c})
            for y in range(h) for x in range(w) for c in range(nc)]
    body = struct.pack("<%df" % len(vals), *vals)
    hdr = "name: color\nwidth: %d\nheight: %d\nchannels: %d\n" \
          "colorspace: linear\nencoding: raw\n\n" % (w, h, nc)
    write_stream(a.out, [("IMAG", hdr.encode() + body)])


def cmd_tetm(a):
    pts = [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 2]
    body = struct.pack("<12d", *pts) + struct.pack("<4I", 0, 1, 2, 3) + \
        struct.pack("<4f", 0.5, 1.5, 2.5, 3.5)
    hdr = "name: corner\npoints: 4\ntets: 1\nscalar: heat\nencoding: raw\n\n"
    write_stream(a.out, [("TETM", hdr.encode() + body)])


def cmd_add(a):
    chunks = read_stream(a.inp)
    at = len(chunks) if a.at is None else a.at
    chunks.insert(at, (a.type, os.fsencode(a.text)))
    write_stream(a.out, chunks)


def cmd_cat(a):
    write_stream(a.out, [c for path in a.inputs for c in read_stream(path)])


def cmd_payload(a):
    for typ, payload in read_stream(a.inp):
        if typ != a.type:
            continue
        if a.name is not None and \
                parse_payload(payload)[0].get("name") != a.name:
            continue
        sys.stdout.buffer.write(payload)
        return
    sys.exit("mkstream.py: no such chunk")


def cmd_samples(a):
    for typ, payload in read_stream(a.inp):
        if typ != "VOLM":
            continue
        hdr, body = parse_payload(payload)
        if a.name is not None and hdr.get("name", "density") != a.name:
            continue
        dims = [int(d) for d in hdr["dims"].split()]
        tabs, total = layout_offsets(dims, hdr.get("layout", "linear"))
        f = FMT[hdr["type"]]
        vals = struct.unpack("<%d%s" % (total, f), body)
        out = [vals[tabs[0][x] + tabs[1][y] + tabs[2][z]]
               for z in range(dims[2]) for y in range(dims[1])
               for x in range(dims[0])]
        sys.stdout.buffer.write(struct.pack("<%d%s" % (len(out), f), *out))
        return
    sys.exit("mkstream.py: no such volume")


def main():
    p = argparse.ArgumentParser()
    sub = p.add_subparsers(dest="cmd", required=True)
    v = sub.add_parser("volume")
    v.add_argument("out")
    v.add_argument("--type", default="u8", choices=sorted(FMT))
    v.add_argument("--dims", type=int, nargs=3, required=True)
    v.add_argument("--layout", default="linear")
    v.add_argument("--zlib", action="store_true")
    v.add_argument("--name", default="density")
    v.add_argument("--spacing", nargs=3, default=["1", "1", "1"])
    v.add_argument("--origin", nargs=3, default=["0", "0", "0"])
    v.add_argument("--range", nargs=2)
    v.add_argument("--no-range", action="store_true")
    v.add_argument("--formula", default="x + 3*y + 11*z")
    v.add_argument("--key", nargs=2, action="append")
    i = sub.add_parser("image")
    i.add_argument("out")
    i.add_argument("--size", type=int, nargs=3, required=True)
    i.add_argument("--formula", default="x + 10*y + 100*c")
    m = sub.add_parser("tetm")
    m.add_argument("out")
    d = sub.add_parser("add")
    d.add_argument("inp")
    d.add_argument("out")
    d.add_argument("type")
    d.add_argument("text")
    d.add_argument("--at", type=int)
    c = sub.add_parser("cat")
    c.add_argument("out")
    c.add_argument("inputs", nargs="+")
    y = sub.add_parser("payload")
    y.add_argument("inp")
    y.add_argument("type")
    y.add_argument("--name")
    s = sub.add_parser("samples")
    s.add_argument("inp")
    s.add_argument("--name")
    a = p.parse_args()
    {"volume": cmd_volume, "image": cmd_image, "add": cmd_add,
     "cat": cmd_cat, "tetm": cmd_tetm, "payload": cmd_payload, "samples": cmd_samples}[a.cmd](a)


if __name__ == "__main__":
    main()
