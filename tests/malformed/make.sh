#!/bin/sh
# tests/malformed/make.sh: regenerate the malformed-input catalog: one small
# file per case in tests/malformed/, the machine-readable list `cases` that
# tests/cli/test_malformed.sh runs, and the table in README.md.  The files
# are committed; run this (from the top directory) after changing a case.
set -eu
cd "$(dirname "$0")"
exec python3 - <<'EOF'
import gzip
import os
import struct
import zlib

SIG = b"\x89VXL\r\n\x1a\n"


def chunk(typ, payload, length=None, crc=None):
    t = typ.encode() if isinstance(typ, str) else typ
    n = len(payload) if length is None else length
    c = zlib.crc32(t + payload) if crc is None else crc
    return t + struct.pack("<Q", n) + payload + struct.pack("<I", c)


END = chunk("VEND", b"")


def stream(*chunks, end=True):
    return SIG + b"".join(chunks) + (END if end else b"")


def payload(lines, body=b""):
    return ("".join(l + "\n" for l in lines) + "\n").encode() + body


VOLM_KEYS = [("name", "density"), ("dims", "2 2 2"), ("type", "u8"),
             ("spacing", "1 1 1"), ("origin", "0 0 0"), ("layout", "linear"),
             ("encoding", "raw")]


def volm(body=bytes(range(8)), **kw):
    """A VOLM chunk: the keys above with kw replacing (value None drops)."""
    keys = []
    for k, v in VOLM_KEYS:
        k2 = k.replace("-", "_")
        v = kw.pop(k2, v)
        if v is not None:
            keys.append("%s: %s" % (k, v))
    keys += ["%s: %s" % (k.replace("_", "-"), v) for k, v in kw.items()]
    return chunk("VOLM", payload(keys, body))


def imag(body=None, **kw):
    keys = dict(name="image", width="2", height="1", channels="1",
                colorspace="linear", encoding="raw")
    keys.update(kw)
    if body is None:
        body = struct.pack("<2f", 0.25, 0.5)
    return chunk("IMAG", payload(["%s: %s" % kv for kv in keys.items()
                                  if kv[1] is not None], body))


def gz(b):
    return gzip.compress(b, mtime=0)


NRRD = ("NRRD0004", "type: uchar", "dimension: 3", "sizes: 2 2 2",
        "encoding: raw")


def nrrd(*lines, body=bytes(range(8)), drop=()):
    keep = [l for l in NRRD if l.split(":")[0] not in drop]
    over = {l.split(":")[0]: l for l in lines}
    out = [over.pop(l.split(":")[0], l) for l in keep] + list(over.values())
    return ("\n".join(out) + "\n\n").encode() + body


def nifti(dims=(2, 2, 2), datatype=2, bitpix=8, body=bytes(range(8)),
          pixdim=(1, 1, 1), magic=b"n+1\0", offset=352.0, sizeof_hdr=348,
          dim0=None, qform=0):
    h = bytearray(348)
    struct.pack_into("<i", h, 0, sizeof_hdr)
    dim = [len(dims) if dim0 is None else dim0] + list(dims) + \
        [1] * (7 - len(dims))
    struct.pack_into("<8h", h, 40, *dim)
    struct.pack_into("<hh", h, 70, datatype, bitpix)
    struct.pack_into("<8f", h, 76, 1, *pixdim, 0, 0, 0, 0)
    struct.pack_into("<f", h, 108, offset)
    struct.pack_into("<h", h, 252, qform)   # quatern_b..d stay 0: identity
    h[344:348] = magic
    return bytes(h) + bytes(4) + body


VTK = ("# vtk DataFile Version 3.0", "catalog", "{enc}",
       "DATASET STRUCTURED_POINTS", "DIMENSIONS 2 2 2", "SPACING 1 1 1",
       "ORIGIN 0 0 0", "POINT_DATA 8", "SCALARS density {t} 1",
       "LOOKUP_TABLE default")


def vtk(body, enc="ASCII", t="float", **repl):
    lines = [l.format(enc=enc, t=t) for l in VTK]
    for k, v in repl.items():
        lines = [v if l.startswith(k) else l for l in lines]
    return ("\n".join(lines) + "\n").encode() + body


ASC8 = b"0 1 2 3 4 5 6 7\n"


def pfm(head, vals=8):
    return head + struct.pack("<%df" % vals, *range(vals))


TETM_PTS = struct.pack("<12d", 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1)
TETM_VAL = struct.pack("<4f", 0.5, 1.5, 2.5, 3.5)


def tetm(tets=(0, 1, 2, 3), points=4, ntet=1):
    body = TETM_PTS + struct.pack("<%dI" % len(tets), *tets) + TETM_VAL
    return chunk("TETM", payload(["name: mesh", "points: %d" % points,
                                  "tets: %d" % ntet, "scalar: scalar",
                                  "encoding: raw"], body))


V = stream(volm())
# name, program (FILE: the case file, <FILE: on stdin; OUT: an output file
# that must not exist afterwards), exit code, phrase, what is wrong, bytes
C = []


def case(name, prog, code, phrase, what, data):
    C.append((name, prog, code, phrase, what, data))


# ---- streams: the container (vinfo) ----
S = "vinfo FILE"
case("empty.vxs", "vinfo <FILE", 66, "empty input", "empty standard input", b"")
case("empty-file.vxs", S, 66, "empty input", "empty file", b"")
case("garbage.vxs", S, 65, "bad signature", "text, not a stream",
     b"hello: world\nthis is not a stream\n")
case("short-signature.vxs", S, 65, "bad signature", "4 bytes of the signature",
     SIG[:4])
case("signature-only.vxs", S, 65, "no end chunk", "signature, no chunks", SIG)
case("missing-end.vxs", S, 65, "no end chunk", "a chunk, no end chunk",
     stream(volm(), end=False))
case("partial-header.vxs", S, 65, "partial chunk header",
     "stream cut inside a chunk header", V[:8 + 7])
case("truncated-payload.vxs", S, 65, "truncated stream",
     "stream cut inside a payload", V[:60])
case("truncated-crc.vxs", S, 65, "missing CRC", "stream cut inside a CRC",
     SIG + volm()[:-2])
case("bitflip.vxs", S, 65, "CRC mismatch", "one payload bit flipped",
     V[:40] + bytes([V[40] ^ 0x10]) + V[41:])
case("bad-crc-end.vxs", "vinfo <FILE", 65, "CRC mismatch",
     "end chunk with a wrong CRC (stdin)", SIG + volm() +
     chunk("VEND", b"", crc=1))
case("length-max.vxs", S, 65, "exceeds the limit",
     "chunk length 2^64 - 1", SIG + b"VOLM" + struct.pack("<Q", 2**64 - 1))
case("length-2e63.vxs", S, 65, "exceeds the limit", "chunk length 2^63",
     SIG + b"note" + struct.pack("<Q", 2**63) + b"abc")
case("length-over-limit.vxs", S, 65, "exceeds the limit",
     "chunk length 2^40 + 1 (one past the limit)",
     SIG + b"note" + struct.pack("<Q", 2**40 + 1) + b"abc")
case("length-beyond.vxs", S, 65, "truncated stream",
     "chunk length one past the data", SIG + chunk("note", b"abc", length=4))
case("length-beyond-huge.vxs", S, 65, "truncated stream",
     "chunk length 2^40 with 3 bytes present",
     SIG + chunk("note", b"abc", length=2**40))
case("unknown-critical.vxs", S, 65, "unknown critical chunk",
     "critical chunk type ZZZZ", stream(chunk("ZZZZ", b"x")))
case("bad-type.vxs", S, 65, "invalid type bytes", "chunk type '12 \\0'",
     stream(chunk(b"12 \0", b"")))
case("end-not-empty.vxs", S, 65, "end chunk must be empty",
     "end chunk with a payload", SIG + chunk("VEND", b"x"))
case("trailing.vxs", S, 65, "trailing bytes", "bytes after the end chunk",
     V + b"\n")
case("two-streams.vxs", S, 65, "trailing bytes", "two streams concatenated",
     V + V)

# ---- streams: VOLM contents (vwrite decodes the volume) ----
W = "vwrite -o OUT FILE"
case("volm-dims-zero.vxs", W, 65, "dims", "dims 0 2 2",
     stream(volm(dims="0 2 2")))
case("volm-dims-negative.vxs", W, 65, "dims", "dims 2 -2 2",
     stream(volm(dims="2 -2 2")))
case("volm-dims-huge.vxs", W, 65, "dims", "dims 2^21 per axis",
     stream(volm(dims="2097152 1 1")))
case("volm-dims-overflow.vxs", W, 65, "dims",
     "dims whose product overflows 64 bits",
     stream(volm(dims="1048576 1048576 1048576")))
case("volm-dims-2e64.vxs", W, 65, "dims", "dims 2^64 (beyond int64)",
     stream(volm(dims="18446744073709551616 1 1")))
case("volm-spacing-nan.vxs", W, 65, "spacing", "spacing nan",
     stream(volm(spacing="nan 1 1")))
case("volm-spacing-inf.vxs", W, 65, "spacing",
     "spacing 1e999 (overflows to inf)", stream(volm(spacing="1e999 1 1")))
case("volm-spacing-zero.vxs", W, 65, "spacing", "spacing 0",
     stream(volm(spacing="1 0 1")))
case("volm-spacing-negative.vxs", W, 65, "spacing", "spacing -1",
     stream(volm(spacing="1 1 -1")))
case("volm-origin-inf.vxs", W, 65, "origin", "origin 1e400",
     stream(volm(origin="0 1e400 0")))
case("volm-extent-overflow.vxs", W, 65, "extent overflows",
     "dims 3 2 2, spacing 1e308: the far corner is beyond the double range",
     stream(volm(dims="3 2 2", spacing="1e308 1 1", body=bytes(12))))
case("volm-extent-diagonal.vxs", W, 65, "extent overflows",
     "sides 1.5e308 on two axes: the diagonal is beyond the double range",
     stream(volm(spacing="1.5e308 1.5e308 1")))
case("volm-type.vxs", W, 65, "type", "type u32 (not a voxlux type)",
     stream(volm(type="u32")))
case("volm-encoding.vxs", W, 65, "encoding", "encoding gzip",
     stream(volm(encoding="gzip")))
case("volm-body-short.vxs", W, 65, "body", "raw body 7 of 8 bytes",
     stream(volm(body=bytes(7))))
case("volm-body-long.vxs", W, 65, "body", "raw body 9 of 8 bytes",
     stream(volm(body=bytes(9))))
case("volm-zlib-short.vxs", W, 65, "zlib",
     "zlib body that inflates to 7 of 8 bytes",
     stream(volm(encoding="zlib", body=zlib.compress(bytes(7)))))
case("volm-zlib-long.vxs", W, 65, "zlib",
     "zlib body that inflates to 9 of 8 bytes",
     stream(volm(encoding="zlib", body=zlib.compress(bytes(9)))))
case("volm-zlib-cut.vxs", W, 65, "zlib", "zlib body cut short",
     stream(volm(encoding="zlib", body=zlib.compress(bytes(range(8)))[:-5])))
case("volm-zlib-bomb.vxs", W, 65, "",
     "dims 1024^3 with a 20-byte zlib body (ratio far beyond deflate's)",
     stream(volm(dims="1024 1024 1024", encoding="zlib",
                 body=zlib.compress(bytes(4096)))))
case("volm-header-garbage.vxs", W, 65, "header", "a header line without ': '",
     stream(chunk("VOLM", b"dims 2 2 2\n\n" + bytes(8))))
case("volm-header-unended.vxs", W, 65, "header",
     "header without its empty line", stream(chunk("VOLM", b"dims: 2 2 2\n")))
case("volm-header-dup.vxs", W, 65, "duplicate", "key dims twice",
     stream(chunk("VOLM", payload(["dims: 2 2 2", "dims: 2 2 2", "type: u8",
                                   "encoding: raw"], bytes(8)))))
case("volm-header-nul.vxs", W, 65, "header", "NUL byte in the header",
     stream(chunk("VOLM", b"name: a\0b\n" + payload(["dims: 2 2 2"]))))
case("volm-header-utf8.vxs", W, 65, "UTF-8", "invalid UTF-8 in a value",
     stream(chunk("VOLM", b"name: caf\xe9\n" + payload(
         ["%s: %s" % kv for kv in VOLM_KEYS[1:]], bytes(range(8))))))
case("volm-dims-missing.vxs", W, 65, "dims", "no dims key",
     stream(volm(dims=None)))
case("volm-dims-hex.vxs", W, 65, "dims", "dims in hex (0x2)",
     stream(volm(dims="0x2 2 2")))
case("volm-layout.vxs", W, 65, "layout", "layout 'bricked 3x3x3'",
     stream(volm(layout="bricked 3x3x3")))
case("volm-range.vxs", W, 65, "range", "range 5 1 (min > max)",
     stream(volm(range="5 1")))
case("volm-none.vxs", W, 65, "no volume", "a stream with no VOLM chunk",
     stream(chunk("note", b"nothing here")))

# ---- streams: IMAG, TETM, MCEL contents ----
I = "tonemap -o OUT FILE"
case("imag-width-zero.vxs", I, 65, "width", "width 0",
     stream(imag(width="0", body=b"")))
case("imag-channels.vxs", I, 65, "channels", "channels 5",
     stream(imag(channels="5")))
case("imag-size-overflow.vxs", I, 65, "", "65536 x 65536 x 4 (over the limit)",
     stream(imag(width="65536", height="65536", channels="4")))
case("imag-body-short.vxs", I, 65, "", "body 4 of 8 bytes",
     stream(imag(body=bytes(4))))
case("imag-colorspace.vxs", I, 65, "colorspace", "colorspace srgb",
     stream(imag(colorspace="srgb")))
T = "vinfo FILE"   # vinfo lists the stream, then reports the bad chunk
case("tetm-index.vxs", T + " (listing)", 65, "tet",
     "tet vertex index 4 of 4 points", stream(tetm(tets=(0, 1, 2, 4))))
case("tetm-count.vxs", T + " (listing)", 65, "", "tets: 2^40 with one tet's bytes",
     stream(tetm(ntet=2**40)))
case("mcel-levels.vxs", T + " (listing)", 65, "levels", "levels 9",
     stream(chunk("MCEL", payload(["leaves: explicit", "leaf-dims: 1 1 1",
                                   "levels: 9", "sizes: ", "range: 0 1",
                                   "encoding: raw"], bytes(8)))))

# ---- NRRD (vread) ----
R = "vread -o OUT FILE"
case("nrrd-truncated.nrrd", R, 65, "truncated", "raw data 5 of 8 bytes",
     nrrd(body=bytes(5)))
case("nrrd-long.nrrd", R, 65, "longer than", "raw data 8 + 4097 bytes "
     "(4096 are tolerated)", nrrd(body=bytes(8 + 4097)))
case("nrrd-type.nrrd", R, 65, "type", "type: complex",
     nrrd("type: complex"))
case("nrrd-encoding.nrrd", R, 65, "encoding", "encoding: bzip2",
     nrrd("encoding: bzip2"))
case("nrrd-gzip-short.nrrd", R, 65, "gzip", "gzip data inflating to 5 of 8",
     nrrd("encoding: gzip", body=gz(bytes(5))))
case("nrrd-gzip-long.nrrd", R, 65, "gzip", "gzip data inflating to 12 of 8",
     nrrd("encoding: gzip", body=gz(bytes(12))))
case("nrrd-gzip-cut.nrrd", R, 65, "gzip", "gzip stream cut short",
     nrrd("encoding: gzip", body=gz(bytes(range(8)))[:-6]))
case("nrrd-gzip-crc.nrrd", R, 65, "gzip", "gzip trailer CRC wrong",
     nrrd("encoding: gzip", body=gz(bytes(range(8)))[:-8] + b"\0\0\0\0" +
          gz(bytes(range(8)))[-4:]))
case("nrrd-sizes-lie.nrrd", R, 65, "", "sizes 200 200 200 with 8 bytes",
     nrrd("sizes: 200 200 200"))
case("nrrd-sizes-zero.nrrd", R, 65, "sizes", "sizes 2 0 2",
     nrrd("sizes: 2 0 2"))
case("nrrd-sizes-negative.nrrd", R, 65, "sizes", "sizes 2 -2 2",
     nrrd("sizes: 2 -2 2"))
case("nrrd-sizes-overflow.nrrd", R, 65, "", "sizes whose product overflows",
     nrrd("sizes: 4294967296 4294967296 4294967296"))
case("nrrd-spacing-ninf.nrrd", R, 65, "spacings", "spacings 1 1 -inf",
     nrrd("spacings: 1 1 -inf"))
case("nrrd-spacing-inf.nrrd", R, 65, "spacings", "spacings 1 inf 1",
     nrrd("spacings: 1 inf 1"))
case("nrrd-spacing-zero.nrrd", R, 65, "spacings", "spacings 1 1 0",
     nrrd("spacings: 1 1 0"))
case("nrrd-magic.nrrd", R, 65, "", "magic NRRD0009", nrrd()[:4] + b"0009" +
     nrrd()[8:])
case("nrrd-garbage-line.nrrd", R, 65, "", "a header line that is no field",
     nrrd("what is this"))
case("nrrd-dimension.nrrd", R, 65, "dimension", "dimension 4",
     nrrd("dimension: 4", "sizes: 2 2 2 1"))
case("nrrd-no-sizes.nrrd", R, 65, "sizes", "no sizes field",
     nrrd(drop=("sizes",)))
case("nrrd-ascii-short.nrrd", R, 65, "", "ascii data: 7 of 8 values",
     nrrd("encoding: ascii", body=b"0 1 2 3 4 5 6\n"))
case("nrrd-ascii-word.nrrd", R, 65, "", "ascii data with a word in it",
     nrrd("encoding: ascii", body=b"0 1 2 x 4 5 6 7\n"))
case("nrrd-hex-odd.nrrd", R, 65, "", "hex data with an odd digit count",
     nrrd("encoding: hex", body=b"000102030405060\n"))
case("nrrd-extent-overflow.nrrd", R, 65, "extent overflows",
     "sizes 3 2 2, spacings 1e308 1 1", nrrd("sizes: 3 2 2",
                                               "spacings: 1e308 1 1",
                                               body=bytes(12)))
case("nrrd-ascii-overflow.nrrd", R, 65, "beyond the double range",
     "ascii double data holding 1e999", nrrd("type: double",
                                             "encoding: ascii",
                                             body=b"0 1 2 1e999 4 5 6 7\n"))
case("nrrd-ascii-overflow-float.nrrd", R, 65, "beyond the double range",
     "ascii float data holding -1e999", nrrd("type: float", "encoding: ascii",
                                             body=b"0 1 2 -1e999 4 5 6 7\n"))
case("nrrd-ascii-overflow-u8.nrrd", R, 65, "beyond the double range",
     "ascii uchar data holding 1e400", nrrd("encoding: ascii",
                                            body=b"0 1 2 3 1e400 5 6 7\n"))
case("nrrd-ascii-float-range.nrrd", R, 65, "beyond the float range",
     "ascii float data holding 1e39 (finite, beyond float)",
     nrrd("type: float", "encoding: ascii", body=b"0 1 2 3 4 5 6 1e39\n"))
case("nrrd-data-devzero.nhdr", R, 65, "longer than",
     "detached data file /dev/zero (endless): read up to the 8 bytes the "
     "header implies and the slack", nrrd("data file: /dev/zero", body=b""))
case("nrrd-data-devzero-ascii.nhdr", R, 65, "",
     "ascii data from /dev/zero (NUL bytes, endless)",
     nrrd("data file: /dev/zero", "encoding: ascii", body=b""))
case("nrrd-data-devzero-gzip.nhdr", R, 65, "gzip",
     "gzip data from /dev/zero (endless, not gzip)",
     nrrd("data file: /dev/zero", "encoding: gzip", body=b""))
case("nrrd-data-devzero-skip.nhdr", R, 65, "regular data file",
     "byte skip -1 (data at the file's end) in /dev/zero",
     nrrd("data file: /dev/zero", "byte skip: -1", body=b""))
case("nrrd-pattern-width.nhdr", R, 65, "conversion",
     "a data file pattern %3333333333d (its width overflowed an int)",
     nrrd("data file: x%3333333333d.raw 1 2 1", body=b""))
case("nrrd-detached-missing.nhdr", R, 66, "No such file",
     "detached data file that does not exist",
     nrrd("data file: no-such-file.raw", body=b""))

# ---- NIfTI-1 (vread) ----
case("nifti-truncated.nii", R, 65, "", "data 5 of 8 bytes",
     nifti(body=bytes(5)))
case("nifti-datatype.nii", R, 65, "datatype", "datatype 1234",
     nifti(datatype=1234))
case("nifti-bitpix.nii", R, 65, "bitpix", "bitpix 16 for u8 data",
     nifti(bitpix=16))
case("nifti-dims-zero.nii", R, 65, "dim", "dim 2 0 2", nifti(dims=(2, 0, 2)))
case("nifti-dims-negative.nii", R, 65, "dim", "dim 2 -2 2",
     nifti(dims=(2, -2, 2)))
case("nifti-dims-overflow.nii", R, 65, "dim", "dim 32767^3 (over the limit)",
     nifti(dims=(32767, 32767, 32767)))
case("nifti-dim0.nii", R, 65, "dim", "dim[0] 9", nifti(dim0=9))
case("nifti-pixdim-nan.nii", R, 65, "", "pixdim nan with a qform",
     nifti(pixdim=(float("nan"), 1, 1), qform=1))
case("nifti-pixdim-inf.nii", R, 65, "", "pixdim inf with a qform",
     nifti(pixdim=(1, float("inf"), 1), qform=1))
case("nifti-offset.nii", R, 65, "", "vox_offset beyond the file",
     nifti(offset=1e9))
case("nifti-offset-nan.nii", R, 65, "vox_offset", "vox_offset nan",
     nifti(offset=float("nan")))
case("nifti-magic.nii", R, 65, "", "magic 'ni1' in a single file",
     nifti(magic=b"ni1\0"))
case("nifti-sizeof.nii", R, 65, "", "sizeof_hdr 349 (not NIfTI-1)",
     nifti(sizeof_hdr=349))
case("nifti-short.nii", R, 65, "", "100 bytes of a header",
     nifti()[:100])
case("nifti-pair-devzero.hdr", R, 65, "more than",
     "a .hdr whose .img links to /dev/zero (endless)",
     nifti(magic=b"ni1\0", offset=0.0)[:348])
case("nifti-gz-cut.nii.gz", R, 65, "gzip", "gzip stream cut short",
     gz(nifti())[:-10])

# ---- VTK structured points (vread) ----
case("vtk-truncated.vtk", R, 65, "truncated", "binary data 10 of 32 bytes",
     vtk(bytes(10), enc="BINARY"))
case("vtk-ascii-short.vtk", R, 65, "", "ascii data: 7 of 8 values",
     vtk(b"0 1 2 3 4 5 6\n"))
case("vtk-ascii-word.vtk", R, 65, "", "ascii data with a word in it",
     vtk(b"0 1 2 x 4 5 6 7\n"))
case("vtk-type.vtk", R, 65, "", "SCALARS type complex",
     vtk(ASC8, t="complex"))
case("vtk-encoding.vtk", R, 65, "", "encoding line XML",
     vtk(ASC8, enc="XML"))
case("vtk-dataset.vtk", R, 65, "", "DATASET POLYDATA",
     vtk(ASC8, DATASET="DATASET POLYDATA"))
case("vtk-dims-zero.vtk", R, 65, "DIMENSIONS", "DIMENSIONS 2 0 2",
     vtk(ASC8, DIMENSIONS="DIMENSIONS 2 0 2"))
case("vtk-dims-overflow.vtk", R, 65, "", "DIMENSIONS whose product overflows",
     vtk(ASC8, DIMENSIONS="DIMENSIONS 4294967296 4294967296 4294967296"))
case("vtk-spacing-nan.vtk", R, 65, "SPACING", "SPACING nan 1 1",
     vtk(ASC8, SPACING="SPACING nan 1 1"))
case("vtk-spacing-zero.vtk", R, 65, "SPACING", "SPACING 0 1 1",
     vtk(ASC8, SPACING="SPACING 0 1 1"))
case("vtk-point-data.vtk", R, 65, "POINT_DATA", "POINT_DATA 9 for 8 points",
     vtk(ASC8, POINT_DATA="POINT_DATA 9"))
case("vtk-extent-overflow.vtk", R, 65, "extent overflows",
     "DIMENSIONS 3 2 2, SPACING 1e308 1 1",
     vtk(b"0 1 2 3 4 5 6 7 8 9 10 11\n", DIMENSIONS="DIMENSIONS 3 2 2",
         SPACING="SPACING 1e308 1 1", POINT_DATA="POINT_DATA 12"))
case("vtk-ascii-overflow.vtk", R, 65, "beyond the double range",
     "ascii double data holding -1e999", vtk(b"0 1 2 3 -1e999 5 6 7\n",
                                             t="double"))
case("vtk-ascii-overflow-float.vtk", R, 65, "beyond the double range",
     "ascii float data holding 1e999", vtk(b"0 1 2 3 4 5 6 1e999\n"))
case("vtk-header.vtk", R, 65, "", "first line not a VTK header",
     b"hello vtk\n" + vtk(ASC8)[27:])

# ---- raw (vread --raw) ----
case("raw-short.raw", "vread --raw 2,2,2 --type u16 -o OUT FILE", 65,
     "truncated", "8 bytes for 2x2x2 u16", bytes(8))
case("raw-long.raw", "vread --raw 2,2,2 --type u8 -o OUT FILE", 65, "",
     "9 bytes for 2x2x2 u8", bytes(9))

case("raw-extent-x.raw", "vread --raw 3,2,2 --type u8 --spacing 1e308,1,1 "
     "-o OUT FILE", 65, "extent overflows", "3 samples 1e308 apart along x",
     bytes(12))

# ---- tet meshes: ASCII numbers beyond the double range (vread) ----
TV = ("# vtk DataFile Version 3.0", "catalog", "ASCII",
      "DATASET UNSTRUCTURED_GRID", "POINTS 4 double",
      "0 0 0 1 0 0 0 1 0 0 0 {z}", "CELLS 1 5", "4 0 1 2 3", "CELL_TYPES 1",
      "10", "POINT_DATA 4", "SCALARS d double 1", "LOOKUP_TABLE default",
      "0.5 1.5 2.5 {v}")


def tetvtk(z="1", v="3.5"):
    return ("\n".join(TV) + "\n").format(z=z, v=v).encode()


case("tetvtk-point-overflow.vtk", R, 65, "POINTS",
     "a tet mesh point coordinate 1e999", tetvtk(z="1e999"))
case("tetvtk-scalar-overflow.vtk", R, 65, "SCALARS",
     "a tet mesh scalar -1e999", tetvtk(v="-1e999"))
case("gmsh-node-overflow.msh", R, 65, "$Nodes",
     "a gmsh node coordinate 1e999",
     b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n"
     b"2 1 0 0\n3 0 1 0\n4 0 0 1e999\n$EndNodes\n$Elements\n1\n"
     b"1 4 2 0 0 1 2 3 4\n$EndElements\n")

# ---- PFM (tonemap) ----
P = "tonemap -o OUT FILE"
case("pfm-truncated.pfm", P, 65, "needs", "2x2 gray with 3 values",
     pfm(b"Pf\n2 2\n-1\n", 3))
case("pfm-long.pfm", P, 65, "", "2x2 gray with 5 values",
     pfm(b"Pf\n2 2\n-1\n", 5))
case("pfm-size-word.pfm", P, 65, "size", "width 'two'",
     pfm(b"Pf\ntwo 2\n-1\n", 4))
case("pfm-size-zero.pfm", P, 65, "size", "width 0", pfm(b"Pf\n0 2\n-1\n", 0))
case("pfm-size-negative.pfm", P, 65, "size", "height -2",
     pfm(b"Pf\n2 -2\n-1\n", 4))
case("pfm-size-huge.pfm", P, 65, "", "65537 x 65537 RGB",
     pfm(b"PF\n65537 65537\n-1\n", 3))
case("pfm-size-2e64.pfm", P, 65, "size", "width 2^64",
     pfm(b"PF\n18446744073709551616 1\n-1\n", 3))
case("pfm-scale-nan.pfm", P, 65, "scale", "scale nan", pfm(b"Pf\n2 2\nnan\n", 4))
case("pfm-scale-zero.pfm", P, 65, "scale", "scale 0", pfm(b"Pf\n2 2\n0\n", 4))
case("pfm-scale-word.pfm", P, 65, "scale", "scale 'big'",
     pfm(b"Pf\n2 2\nbig\n", 4))
case("pfm-magic.pfm", P, 65, "not a voxlux stream", "magic 'Pg'",
     pfm(b"Pg\n2 2\n-1\n", 4))
case("pfm-header-only.pfm", P, 65, "", "header and no data", b"PF\n1 1\n-1\n")
case("pfm-no-separator.pfm", P, 65, "", "no whitespace after the scale",
     b"Pf\n1 1\n-1" + struct.pack("<f", 1))

# ---- the renderers and filters on bad streams (the same files; skipped
# where the program is not built yet) ----
for prog in ("brick", "macrocell", "raycast", "mip"):
    case("bitflip.vxs", prog + " -o OUT FILE", 65, "CRC mismatch",
         "one payload bit flipped", None)
    case("volm-dims-zero.vxs", prog + " -o OUT FILE", 65, "dims",
         "dims 0 2 2", None)
    case("volm-none.vxs", prog + " -o OUT FILE", 65, "no volume",
         "a stream with no VOLM chunk", None)
    case("empty.vxs", prog + " -o OUT <FILE", 66, "empty input",
         "empty standard input", None)

# ---- scenes: a scene file (raycast --scene) and the SCNE chunk ----
def scne(text, version="1", length=None):
    t = text.encode()
    return chunk("SCNE", payload(["version: " + version, "length: %d" % (
        len(t) if length is None else length), "encoding: raw"], t))


G = "raycast --size 8x8 --scene FILE -o OUT GOOD"
case("scene-directive.scn", G, 65, "line 2", "unknown directive",
     "surface iso 1\nfrobnicate 3\n")
case("scene-number.scn", G, 65, "line 1", "a number that is a word",
     "surface iso one\n")
case("scene-nan.scn", G, 65, "line 1", "background color nan",
     "background color nan 0 0\n")
case("scene-surfaces.scn", G, 65, "", "17 surfaces (the limit is 16)",
     "".join("surface iso %d\n" % i for i in range(17)))
case("scene-long-line.scn", G, 65, "", "a 20000-byte line",
     "# " + "x" * 20000 + "\n")
case("scene-nul.scn", G, 65, "", "a NUL byte", "surface iso 1\0\n")
RS = "raycast --size 8x8 -o OUT FILE"
case("scne-version.vxs", RS, 65, "version", "SCNE version 2",
     stream(volm(), scne("surface iso 1\n", version="2")))
case("scne-length.vxs", RS, 65, "header implies 1000", "SCNE length 1000 for 14 bytes",
     stream(volm(), scne("surface iso 1\n", length=1000)))
case("scne-text.vxs", RS, 65, "line 1", "SCNE with a bad scene line",
     stream(volm(), scne("surface iso x\n")))
for name in ("scene-directive.scn", "scene-nul.scn"):
    case(name, "vscene --scene FILE -o OUT GOOD", 65, "line", "(as above)",
         None)
for name in ("scne-version.vxs", "scne-length.vxs"):
    case(name, "vscene -o OUT FILE", 65, "scene chunk", "(as above)", None)

# ---- a malformed MCEL chunk for the volume the renderers read ----
MC = stream(volm(), chunk("MCEL", payload([
    "leaves: cells", "volume: density", "volume-dims: 2 2 2",
    "volume-type: u8", "volume-crc32: 00000000", "leaf-dims: 1 1 1",
    "levels: 9", "sizes: ", "range: 0 1", "encoding: raw"])))
case("mcel-levels-volume.vxs", "raycast --iso 3 --size 8x8 -o OUT FILE", 65,
     "levels 9", "the volume's MCEL with levels 9", MC)
case("mcel-levels-volume.vxs", "mip --size 8x8 -o OUT FILE", 65, "levels 9",
     "(as above)", None)
MCNV = stream(volm(), chunk("MCEL", payload([
    "leaves: cells", "volume-dims: 2 2 2", "volume-type: u8",
    "volume-crc32: 00000000", "leaf-dims: 1 1 1", "levels: 0", "sizes: ",
    "range: 0 1", "encoding: raw"])))
case("mcel-no-volume.vxs", "raycast --iso 3 --size 8x8 -o OUT FILE", 65,
     "no 'volume' key", "volume macrocells (leaves: cells) without the "
     "required volume key", MCNV)
case("mcel-no-volume.vxs", "mip --size 8x8 -o OUT FILE", 65,
     "no 'volume' key", "(as above)", None)
case("mcel-no-volume.vxs", "macrocell -o OUT FILE", 65,
     "no 'volume' key", "(as above)", None)
MCCC = stream(volm(), chunk("MCEL", payload([
    "leaves: cells", "volume: density", "volume-dims: 2 2 2",
    "volume-type: u8", "volume-crc32: 00000000",
    "volume-chunk-crc32: 0ABCDEF0", "leaf-dims: 1 1 1", "levels: 0",
    "sizes: ", "range: 0 1", "encoding: raw"])))
case("mcel-chunk-crc.vxs", "raycast --iso 3 --size 8x8 -o OUT FILE", 65,
     "volume-chunk-crc32", "the volume's MCEL with an upper-case "
     "volume-chunk-crc32", MCCC)
case("mcel-chunk-crc.vxs", "mip --size 8x8 -o OUT FILE", 65,
     "volume-chunk-crc32", "(as above)", None)

# ---- TLEF: a tet mesh's leaf grid (formats/tetmesh.md), read by raycast
# (for the mesh it names) and vinfo (every one); macrocell only replaces it.
# The good one: the corner tet of tetm() in one leaf, one level above.
TETS = (0, 1, 2, 3)
MESH_CRC = "%08x" % zlib.crc32(TETM_PTS + struct.pack("<4I", *TETS) + TETM_VAL)
TLEF_KEYS = [("mesh", "mesh"), ("mesh-points", "4"), ("mesh-tets", "1"),
             ("mesh-crc32", MESH_CRC), ("leaf-dims", "1 1 1"),
             ("leaf-origin", "-0.5 -0.5 -0.5"), ("leaf-size", "2 2 2"),
             ("entries", "1"), ("levels", "1"), ("sizes", "8x8x8"),
             ("dims-1", "1 1 1"), ("range", "0.5 3.5"), ("encoding", "raw")]


def tlef_body(off=(0, 1), idx=(0,), lev=(0.5, 3.5, 0.5, 3.5)):
    return struct.pack("<%dI" % len(off), *off) + \
        struct.pack("<%dI" % len(idx), *idx) + struct.pack("<%df" % len(lev), *lev)


def tlef(body=None, crc=None, **kw):
    """A TLEF chunk: the keys above with kw replacing (value None drops)."""
    keys = []
    for k, v in TLEF_KEYS:
        v = kw.pop(k.replace("-", "_"), v)
        if v is not None:
            keys.append("%s: %s" % (k, v))
    assert not kw, kw
    return chunk("TLEF", payload(keys, tlef_body() if body is None else body),
                 crc=crc)


def mesh_tlef(*a, **kw):
    return stream(tetm(), tlef(*a, **kw))


GOOD_TLEF = mesh_tlef()    # raycast renders it, vinfo says "matches"
TL = [
    ("tlef-body-short.vxs", "body", "raw body one byte short",
     mesh_tlef(body=tlef_body()[:-1])),
    ("tlef-body-long.vxs", "body", "raw body one byte long",
     mesh_tlef(body=tlef_body() + b"\0")),
    ("tlef-cut.vxs", "truncated stream", "stream cut inside the TLEF body",
     mesh_tlef()[:-40]),
    ("tlef-crc.vxs", "CRC mismatch", "TLEF chunk with a wrong CRC",
     mesh_tlef(crc=0x12345678)),
    ("tlef-entries-lie.vxs", "body", "entries 2, the body holds 1",
     mesh_tlef(entries="2")),
    ("tlef-leaf-dims-lie.vxs", "body", "leaf-dims 2 1 1, the body holds 1 leaf",
     mesh_tlef(leaf_dims="2 1 1")),
    ("tlef-huge.vxs", "body", "2^31 leaves and 2^32-1 entries (25 GB) with "
     "a 24-byte body", mesh_tlef(leaf_dims="1024 1024 2048",
                                 entries="4294967295", levels="0", sizes="",
                                 dims_1=None)),
    ("tlef-huge-zlib.vxs", "zlib body", "the same claim with a 12-byte zlib "
     "body (far beyond 1032:1)",
     mesh_tlef(body=zlib.compress(bytes(64)), leaf_dims="1024 1024 2048",
               entries="4294967295", levels="0", sizes="", dims_1=None,
               encoding="zlib")),
    ("tlef-leaves-limit.vxs", "leaves (limit", "leaf-dims 2048^3: 2^33 leaves",
     mesh_tlef(leaf_dims="2048 2048 2048")),
    ("tlef-leaf-dims-zero.vxs", "leaf-dims", "leaf-dims 0 1 1",
     mesh_tlef(leaf_dims="0 1 1")),
    ("tlef-entries-negative.vxs", "entries", "entries -1",
     mesh_tlef(entries="-1")),
    ("tlef-entries-2e32.vxs", "entries", "entries 2^32",
     mesh_tlef(entries="4294967296")),
    ("tlef-leaf-size-zero.vxs", "leaf-size", "leaf-size 0 2 2",
     mesh_tlef(leaf_size="0 2 2")),
    ("tlef-leaf-size-nan.vxs", "leaf-size", "leaf-size nan 2 2",
     mesh_tlef(leaf_size="nan 2 2")),
    ("tlef-leaf-origin-huge.vxs", "leaf-origin", "leaf-origin 1e300",
     mesh_tlef(leaf_origin="1e300 0 0")),
    ("tlef-leaf-origin-comma.vxs", "leaf-origin", "leaf-origin with decimal "
     "commas", mesh_tlef(leaf_origin="-0,5 -0,5 -0,5")),
    ("tlef-levels.vxs", "levels 9", "levels 9", mesh_tlef(levels="9")),
    ("tlef-sizes.vxs", "sizes", "sizes 8x8 (not AxBxC)", mesh_tlef(sizes="8x8")),
    ("tlef-sizes-zero.vxs", "sizes", "sizes 0x8x8",
     mesh_tlef(sizes="0x8x8")),
    ("tlef-dims-1.vxs", "dims-1", "dims-1 2 1 1 (leaf-dims and sizes give 1 1 1)",
     mesh_tlef(dims_1="2 1 1")),
    ("tlef-dims-1-missing.vxs", "dims-1", "no dims-1 key",
     mesh_tlef(dims_1=None)),
    ("tlef-crc32-key.vxs", "mesh-crc32", "mesh-crc32 in upper case",
     mesh_tlef(mesh_crc32=MESH_CRC.upper() if MESH_CRC.upper() != MESH_CRC
               else "XYZ")),
    ("tlef-mesh-points.vxs", "mesh counts", "mesh-points -4",
     mesh_tlef(mesh_points="-4")),
    ("tlef-offsets-start.vxs", "offsets", "offsets 1 1",
     mesh_tlef(body=tlef_body(off=(1, 1)))),
    ("tlef-offsets-end.vxs", "offsets", "offsets 0 0 (the entry count is 1)",
     mesh_tlef(body=tlef_body(off=(0, 0)))),
    ("tlef-offsets-decrease.vxs", "offsets decrease", "offsets 0 2 1 of two "
     "leaves", mesh_tlef(leaf_dims="2 1 1", entries="1",
                         body=tlef_body(off=(0, 2, 1), lev=(0.5, 3.5) * 3))),
    ("tlef-tet-range.vxs", "out of range", "a list holds tet 1 of 1 "
     "(consistent counts and CRC)", mesh_tlef(body=tlef_body(idx=(1,)))),
    ("tlef-tet-order.vxs", "out of order", "a list holds 0 0",
     mesh_tlef(entries="2", body=tlef_body(off=(0, 2), idx=(0, 0)))),
    ("tlef-nan-leaf.vxs", "NaN", "NaN in level 0",
     mesh_tlef(body=tlef_body(lev=(float("nan"), 3.5, 0.5, 3.5)))),
    ("tlef-nan-level.vxs", "NaN", "NaN in level 1",
     mesh_tlef(body=tlef_body(lev=(0.5, 3.5, 0.5, float("nan"))))),
    ("tlef-encoding.vxs", "encoding", "encoding lz4",
     mesh_tlef(encoding="lz4")),
    ("tlef-zlib-cut.vxs", "zlib", "zlib body cut short",
     mesh_tlef(body=zlib.compress(tlef_body())[:-3], encoding="zlib")),
]
case("tlef-no-mesh.vxs", "raycast --iso 1 --size 8x8 -o OUT FILE", 65,
     "no 'mesh' key", "TLEF without the required mesh key",
     mesh_tlef(mesh=None))
case("tlef-no-mesh.vxs", "macrocell -o OUT FILE", 65, "no 'mesh' key",
     "(as above)", None)
for name, phrase, what, data in TL:
    case(name, T + " (listing)", 65, phrase, what, data)
    # raycast reads the leaf grid of the mesh it draws (a stream error is
    # found on reading, before any chunk)
    case(name, "raycast --iso 1 --size 8x8 -o OUT FILE", 65, phrase,
         "(as above)", None)

# ---- IRRV, SHTV (formats/irradiance.md) and SHLC (formats/shlight.md) ----
# The good stream: good.vxs's volume (2x2x2 u8, 0 10 .. 70), a scene that
# draws it lit by the chunk, and a 2x2x2 lattice in one brick, f16 store
# (raw: 1 map byte and 512 records of 2 + 2K bytes), every texel wanted
# with value 1.  A case breaks one thing; each is read by vinfo (IRRV and
# SHTV), raycast, vwrite --chunk and the baker (which reads the stream's
# bake to resume it).
IRR_VOL = bytes([0, 10, 20, 30, 40, 50, 60, 70])
IRR_KEYS = [("volume", "density"), ("volume-dims", "2 2 2"),
            ("volume-crc32", "%08x" % zlib.crc32(IRR_VOL)),
            ("lattice-dims", "2 2 2"), ("scale", "1"), ("brick", "8"),
            ("bricks", "1"), ("store", "f16"), ("first-sample", "0"),
            ("samples", "4"), ("offset", "0.5"), ("seed", "1"),
            ("side", "low"), ("key", "0123456789abcdef"),
            ("encoding", "raw")]


def irr_body(store="f16", ncomp=3, val=1.0, nmap=1, mapbits=1, nbrick=1):
    """The map and nbrick bricks; lattice texels (x, y, z < 2) wanted."""
    out = bytes([mapbits]) + bytes(nmap - 1)
    for _ in range(nbrick):
        for t in range(512):
            x, y, z = t % 8, t // 8 % 8, t // 64
            inside = x < 2 and y < 2 and z < 2
            fl, v = (16, val) if inside else (0, 0.0)
            if store == "f16":
                out += struct.pack("<H%de" % ncomp, fl, *[v] * ncomp)
            elif store == "f32":
                out += struct.pack("<I%df" % ncomp, fl, *[v] * ncomp)
            else:
                n = 4 if inside else 0
                s = int(v * n * (1 << 24))
                out += struct.pack("<II%dqQQ" % ncomp, n, fl,
                                   *[s] * ncomp, 0, 0)
    return out


def irrv(typ="IRRV", body=None, **kw):
    """An IRRV (or SHTV) chunk: the keys above with kw replacing (None
    drops); SHTV adds order 1, channels 1 unless kw says."""
    keys = []
    extra = [("order", "1"), ("channels", "1")] if typ == "SHTV" else []
    for k, v in IRR_KEYS[:5] + extra + IRR_KEYS[5:]:
        v = kw.pop(k.replace("-", "_"), v)
        if v is not None:
            keys.append("%s: %s" % (k, v))
    keys += ["%s: %s" % (k.replace("_", "-"), v) for k, v in kw.items()]
    if body is None:
        body = irr_body(ncomp=3 if typ == "IRRV" else 1)
    return chunk(typ, payload(keys, body))


def lit(c, illum="irradiance"):
    """The good volume, a scene that draws it lit by c, and c."""
    return stream(volm(body=IRR_VOL),
                  scne("surface iso 35\nillumination %s\nlight sky\n" % illum),
                  c)


IR = [
    ("irrv-map-bricks.vxs", "brick map has 0 bricks", "bricks 1, the map's "
     "bit is clear", lit(irrv(body=irr_body(mapbits=0)))),
    ("irrv-map-past.vxs", "bits past the last brick", "a map bit past the "
     "one brick", lit(irrv(body=irr_body(mapbits=3)))),
    ("irrv-bricks-more.vxs", "bricks 2: the lattice has 1", "bricks 2 of "
     "a one-brick lattice", lit(irrv(bricks="2"))),
    ("irrv-body-short.vxs", "body", "raw body one byte short",
     lit(irrv(body=irr_body()[:-1]))),
    ("irrv-body-long.vxs", "body", "raw body one byte long",
     lit(irrv(body=irr_body() + b"\0"))),
    ("irrv-zlib-bomb.vxs", "zlib body", "lattice 2^20 x 2^14 x 1 (2^28 "
     "bricks, a 32 MiB map) with a 12-byte zlib body",
     lit(irrv(body=zlib.compress(bytes(64)), encoding="zlib", bricks="0",
              lattice_dims="1048576 16384 1", volume_dims="2 2 1"))),
    ("irrv-lattice-fit.vxs", "do not fit volume-dims", "lattice-dims 2 2 1 "
     "for volume-dims 2 2 2", lit(irrv(lattice_dims="2 2 1"))),
    ("irrv-lattice-zero.vxs", "do not fit volume-dims", "lattice-dims 0 2 2",
     lit(irrv(lattice_dims="0 2 2"))),
    ("irrv-lattice-huge.vxs", "do not fit volume-dims", "lattice-dims "
     "2^21 2 2", lit(irrv(lattice_dims="2097152 2 2"))),
    ("irrv-texels.vxs", "too many texels", "lattice-dims 2^20 2^20 2^20 "
     "(2^60 texels, at most 2^34)",
     lit(irrv(lattice_dims="1048576 1048576 1048576"))),
    ("irrv-store.vxs", "store 'f64'", "store f64",
     lit(irrv(store="f64"))),
    ("irrv-fixed.vxs", "fixed 41: at most 40", "accum store, fixed 41",
     lit(irrv(store="accum", fixed="41", body=irr_body("accum")))),
    ("irrv-key.vxs", "key: not 16 hex digits", "key of 15 hex digits",
     lit(irrv(key="0123456789abcde"))),
    ("irrv-key-upper.vxs", "key: not 16 hex digits", "key in upper case",
     lit(irrv(key="0123456789ABCDEF"))),
    ("irrv-nan-f32.vxs", "irradiance nan", "a NaN irradiance (f32 store)",
     lit(irrv(store="f32", body=irr_body("f32", val=float("nan"))))),
    ("irrv-negative-f16.vxs", "irradiance -1", "irradiance -1 (f16 store)",
     lit(irrv(body=irr_body(val=-1.0)))),
    ("irrv-inf-f16.vxs", "irradiance inf", "irradiance +inf (f16 store)",
     lit(irrv(body=irr_body(val=float("inf"))))),
    ("irrv-negative-sum.vxs", "negative irradiance sum", "an accum sum "
     "of -4 (2^-24 units)",
     lit(irrv(store="accum", fixed="24", body=irr_body("accum", val=-1.0)))),
    ("shtv-order-0.vxs", "order 0", "SHTV order 0",
     lit(irrv("SHTV", order="0"), "sh")),
    ("shtv-order-17.vxs", "order 17", "SHTV order 17",
     lit(irrv("SHTV", order="17"), "sh")),
    ("shtv-channels-2.vxs", "channels 2", "SHTV channels 2",
     lit(irrv("SHTV", channels="2"), "sh")),
    ("shtv-order-body.vxs", "body", "order 2 (4 coefficients a texel), "
     "a body sized for order 1", lit(irrv("SHTV", order="2"), "sh")),
    ("shtv-nan-f32.vxs", "coefficient nan", "a NaN coefficient (f32 store)",
     lit(irrv("SHTV", store="f32", body=irr_body("f32", ncomp=1,
                                                 val=float("nan"))), "sh")),
]
for name, phrase, what, data in IR:
    sh = name.startswith("shtv")
    case(name, T + " (listing)", 65, phrase, what, data)
    case(name, "raycast --size 8x8 -o OUT FILE", 65, phrase, "(as above)",
         None)
    case(name, "vwrite --chunk %s -o OUT FILE" % ("SHTV" if sh else "IRRV"),
         65, phrase, "(as above)", None)
    case(name, ("bake-sh --iso 35 -o OUT FILE" if sh else
                "bake-irr --light sky --iso 35 -o OUT FILE"), 65, phrase,
         "(as above)", None)


def shlc(order=1, channels="3", rot="1 0 0 0 1 0 0 0 1", coef=None,
         phase="condon-shortley", body=None):
    """An SHLC chunk of the given order: coefficient 0 of each channel 1."""
    if body is None:
        n = 3 * order * order
        c = coef if coef is not None else \
            [1.0 if i % (order * order) == 0 else 0.0 for i in range(n)]
        body = struct.pack("<%dd" % n, *c)
    return chunk("SHLC", payload([
        "order: %d" % order, "channels: %s" % channels, "phase: " + phase,
        "source-hash: none", "rotation: " + rot, "encoding: raw"], body))


def sh_lit(c):
    """The good volume lit by a good SHTV and c."""
    return stream(volm(body=IRR_VOL),
                  scne("surface iso 35\nillumination sh\n"), irrv("SHTV"), c)


SL = [
    ("shlc-channels.vxs", "channels 1: must be 3", "SHLC channels 1",
     sh_lit(shlc(channels="1"))),
    ("shlc-order-0.vxs", "order 0 outside", "SHLC order 0",
     sh_lit(shlc(order=0, body=b""))),
    ("shlc-order-17.vxs", "order 17 outside", "SHLC order 17",
     sh_lit(shlc(order=17, body=b""))),
    ("shlc-rotation.vxs", "not a rotation", "rotation 1 0 0 0 1 0 0 0 2 "
     "(not orthogonal)", sh_lit(shlc(rot="1 0 0 0 1 0 0 0 2"))),
    ("shlc-reflection.vxs", "not a rotation", "rotation diag(1, 1, -1) "
     "(a reflection)", sh_lit(shlc(rot="1 0 0 0 1 0 0 0 -1"))),
    ("shlc-nan.vxs", "not finite", "a NaN coefficient",
     sh_lit(shlc(coef=[float("nan"), 0, 0]))),
    ("shlc-body-short.vxs", "body", "raw body one byte short",
     sh_lit(shlc(body=struct.pack("<3d", 1, 1, 1)[:-1]))),
]
for name, phrase, what, data in SL:
    case(name, "raycast --size 8x8 -o OUT FILE", 65, phrase, what, data)
    case(name, "sh-rotate --euler 0,0,90 -o OUT FILE", 65, phrase,
         "(as above)", None)
    case(name, "vinfo FILE (listing)", 65, phrase, "(as above)", None)

# ---- HDR images (tonemap reads them) and environment maps (vscene) ----
HDRH = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n"


def exr(chans, w, h, vals, dw=None, dp=None, cut=0):
    """An uncompressed float OpenEXR file, from the OpenEXR file layout."""
    def attr(name, typ, val):
        return (name.encode() + b"\0" + typ.encode() + b"\0" +
                struct.pack("<i", len(val)) + val)
    dw = dw or (0, 0, w - 1, h - 1)
    dp = dp or dw
    cl = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1)
                  for c in chans) + b"\0"
    head = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) +
            attr("channels", "chlist", cl) +
            attr("compression", "compression", b"\0") +
            attr("dataWindow", "box2i", struct.pack("<4i", *dw)) +
            attr("displayWindow", "box2i", struct.pack("<4i", *dp)) +
            attr("lineOrder", "lineOrder", b"\0") +
            attr("pixelAspectRatio", "float", struct.pack("<f", 1)) +
            attr("screenWindowCenter", "v2f", struct.pack("<2f", 0, 0)) +
            attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    size = 4 * len(chans) * w
    first = len(head) + 8 * h
    out = head + b"".join(struct.pack("<Q", first + y * (8 + size))
                          for y in range(h))
    for y in range(h):
        out += struct.pack("<ii", dw[1] + y, size)
        for c in chans:
            out += b"".join(struct.pack("<f", vals(c, x, y)) for x in range(w))
    return out[:len(out) - cut]


def pfm3(w, h, vals):
    return ("PF\n%d %d\n-1.0\n" % (w, h)).encode() + struct.pack(
        "<%df" % (3 * w * h), *vals)


def gray(c, x, y):
    return 0.5 + x + 0.25 * y


T = "tonemap -o OUT FILE"
case("hdr-rle-cut.hdr", T, 65, "truncated",
     "run-length scanline cut short",
     HDRH + b"-Y 2 +X 8\n" + bytes([2, 2, 0, 8, 136, 100, 8, 1, 2]))
case("hdr-run-long.hdr", T, 65, "passes the scanline's end",
     "a run of 9 in an 8-pixel scanline",
     HDRH + b"-Y 1 +X 8\n" + bytes([2, 2, 0, 8, 137, 100]))
case("hdr-rle-width.hdr", T, 65, "gives 9 pixels",
     "run-length start for 9 pixels in an 8-pixel image",
     HDRH + b"-Y 1 +X 8\n" + bytes([2, 2, 0, 9, 137, 100]))
case("hdr-width-huge.hdr", T, 65, "beyond the limits", "-Y 1 +X 70000 (a huge width)",
     HDRH + b"-Y 1 +X 70000\n" + bytes(16))
case("hdr-pixels-huge.hdr", T, 65, "beyond the limits", "65536 x 65536 (over the limit)",
     HDRH + b"-Y 65536 +X 65536\n" + bytes(16))
case("hdr-header.hdr", T, 65, "header", "a header without its empty line",
     b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n-Y 1 +X 1\n" + bytes(4))
case("hdr-xyze.hdr", T, 65, "XYZE", "FORMAT=32-bit_rle_xyze",
     b"#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n" + bytes(4))
case("hdr-exposure.hdr", T, 65, "EXPOSURE", "EXPOSURE=0",
     b"#?RADIANCE\nEXPOSURE=0\n\n-Y 1 +X 1\n" + bytes(4))
case("hdr-resolution.hdr", T, 65, "resolution line", "-Y 1 +Y 1",
     HDRH + b"-Y 1 +Y 1\n" + bytes(4))
case("exr-cut.exr", T, 65, "exr", "uncompressed pixels cut short",
     exr("BGR", 4, 2, gray, cut=20))
case("exr-no-rgb.exr", T, 65, "no channel R", "channels A and Z only",
     exr("AZ", 2, 2, gray))
case("exr-width-huge.exr", T, 65, "beyond the limits",
     "display window 70000 wide (a huge width)",
     exr("BGR", 1, 1, gray, dp=(0, 0, 69999, 0)))
case("exr-garbage.exr", T, 65, "exr", "the magic, then garbage",
     b"\x76\x2f\x31\x01\x02\0\0\0garbage and more garbage")
V_ = "vscene --scene FILE -o OUT GOOD"
case("env-nan.scn", V_, 65, "is NaN", "an environment (PFM) with a NaN pixel",
     "light environment file env-nan.pfm\n")
case("env-inf.scn", V_, 65, "is infinite",
     "an environment (OpenEXR) with an infinite pixel",
     "light environment file env-inf.exr\n")
case("env-hash.scn", V_, 65, "content hash",
     "an environment whose hash is not the scene's",
     "light environment file env-good.hdr hash 0123456789abcdef\n")
case("env-angular.scn", V_, 65, "square", "an angular map of 4 x 2",
     "light environment file env-good.hdr layout angular\n")
case("env-missing.scn", V_, 66, "No such file",
     "an environment file that does not exist",
     "light environment file env-no-such-file.hdr\n")
case("env-format.scn", V_, 65, "not a PFM, Radiance HDR or OpenEXR",
     "an environment file that is a voxlux stream",
     "light environment file good.vxs\n")
case("env-hash-word.scn", V_, 65, "line 1",
     "hash with 15 digits", "light environment file env-good.hdr "
     "hash 0123456789abcde\n")

# ---- transfer functions (vinfo --transfer: vx_tf_import) ----
TF = "vinfo --transfer auto FILE"
VP6 = "1\n1\n0.7\n0.1\n0.2\n10\n"
TXF = ("NRRD0004\ntype: float\ndimension: 2\nsizes: %s\n"
       "axis mins: nan 0\naxis maxs: nan 1\nlabels: \"%s\" \"%s\"\n"
       "encoding: %s\n\n")
case("tf-json-cut.json", TF, 65, "ends inside an array or object",
     "ParaView JSON cut short", '[{"RGBPoints": [0, 1, 0, 0')
case("tf-json-deep.json", TF, 65, "nested too deep",
     "40 nested arrays (32 allowed)", "[" * 40 + "]" * 40)
case("tf-json-nan.json", TF, 65, "column 26: not a JSON value",
     "NaN in RGBPoints (not JSON)", '[{"RGBPoints": [0, 1, 0, NaN]}]')
case("tf-json-inf.json", TF, 65, "beyond the double range",
     "1e999 in RGBPoints", '[{"RGBPoints": [0, 1, 0, 1e999]}]')
case("tf-json-count.json", TF, 65, "not a positive multiple of 4",
     "RGBPoints with 6 numbers", '[{"RGBPoints": [0, 1, 0, 0, 1, 1]}]')
case("tf-json-range.json", TF, 65,
     "key \"RGBPoints\" element 6: 1.5 is outside [0, 1]",
     "a colour of 1.5", '[{"RGBPoints": [0, 1, 0, 0, 1, 1, 1.5, 1]}]')
case("tf-json-down.json", TF, 65, "less than the one before it",
     "decreasing x in Points", '[{"Points": [1, 0, 0.5, 0, 0, 1, 0.5, 0]}]')
case("tf-json-space.json", TF, 65, "\"Step\" is not supported",
     "ColorSpace Step", '[{"ColorSpace": "Step", "RGBPoints": [0, 1, 0, 0]}]')
case("tf-vp-count.vp", TF, 65, "the count is 8 but 6 numbers follow it",
     "Slicer .vp: a count larger than the points given",
     VP6 + "8 0 0 100 1 200 1\n")
case("tf-vp-huge.vp", TF, 65, "points (at most 65536)",
     "Slicer .vp: a count of 2^40", VP6 + "1099511627776 0 0\n")
case("tf-vp-nan.vp", TF, 65, "'nan' is not a finite number",
     "Slicer .vp: nan opacity", VP6 + "4 0 nan 1 1\n")
case("tf-vp-down.vp", TF, 65, "line 7 (scalar opacity): number 3",
     "Slicer .vp: decreasing x", VP6 + "4 5 0 1 1\n")
case("tf-vpjson-color.vp.json", TF, 65, "\"color\" has 2 numbers, not 3",
     "Slicer .vp.json: a colour of two numbers",
     '{"volumeProperties": [{"components": [{"scalarOpacity": {"points": '
     '[{"x": 0, "y": 1}]}, "rgbTransferFunction": {"points": [{"x": 0, '
     '"color": [1, 0]}]}}]}]}')
case("tf-txf-axis0.nrrd", TF, 65, "axis 0: label \"RGBX\"",
     "miter txf whose first axis is not a range",
     TXF % ("4 2", "RGBX", "gage(v)", "ascii") + "0 0 0 0 1 1 1 1\n")
case("tf-txf-var.nrrd", TF, 65, "label \"gage(hess)\"",
     "miter txf over a variable that is not read",
     TXF % ("1 2", "A", "gage(hess)", "ascii") + "0 1\n")
case("tf-txf-value.nrrd", TF, 65, "A = 1.5 is outside [0, 1]",
     "miter txf opacity 1.5", TXF % ("1 2", "A", "gage(v)", "ascii") +
     "0 1.5\n")
case("tf-txf-cut.nrrd", TF, 65, "truncated", "miter txf raw data cut short",
     (TXF % ("1 2", "A", "gage(v)", "raw")).replace(
         "raw\n", "raw\nendian: little\n").encode() + bytes(5))
case("tf-txf-sizes-lie.nrrd", TF, 65, "truncated",
     "miter txf claiming 4 x 65536 floats with 8 bytes",
     (TXF % ("4 65536", "RGBA", "gage(v)", "raw")).replace(
         "raw\n", "raw\nendian: little\n").encode() + bytes(8))
case("tf-garbage.txt", TF, 65, "not a transfer function",
     "text that is none of the formats", "hello\n")
case("tf-empty.vp", TF, 66, "empty file", "an empty file", b"")
case("tf-missing.vp", "vinfo --transfer auto NOFILE", 66, "No such file",
     "a transfer function that does not exist", None)

# ---- height maps (heightfield: PGM, PNG, PFM) ----
HF = "heightfield -o OUT FILE"
case("hf-pgm-truncated.pgm", HF, 65, "needs 4 data bytes",
     "2x2 8-bit PGM with 3 samples", b"P5\n2 2\n255\n" + bytes(3))
case("hf-pgm-long.pgm", HF, 65, "the file has 5",
     "2x2 8-bit PGM with 5 samples", b"P5\n2 2\n255\n" + bytes(5))
case("hf-pgm-16-odd.pgm", HF, 65, "2-byte samples",
     "2x1 16-bit PGM with 3 data bytes", b"P5\n2 1\n65535\n" + bytes(3))
case("hf-pgm-maxval-zero.pgm", HF, 65, "maxval 0",
     "maxval 0", b"P5\n1 1\n0\n" + bytes(1))
case("hf-pgm-maxval-huge.pgm", HF, 65, "maxval 65536",
     "maxval 65536", b"P5\n1 1\n65536\n" + bytes(2))
case("hf-pgm-over-maxval.pgm", HF, 65, "exceeds maxval",
     "sample 200 over maxval 100", b"P5\n2 1\n100\n" + bytes([5, 200]))
case("hf-pgm-size-zero.pgm", HF, 65, "size 0 x 2",
     "width 0", b"P5\n0 2\n255\n")
case("hf-pgm-size-huge.pgm", HF, 65, "each side",
     "65537 x 65537 (no data)", b"P5\n65537 65537\n255\n" + bytes(4))
case("hf-pgm-size-word.pgm", HF, 65, "bad or missing size",
     "width 'two'", b"P5\ntwo 2\n255\n" + bytes(4))
case("hf-pgm-size-2e64.pgm", HF, 65, "bad or missing size",
     "width 2^64", b"P5\n18446744073709551616 1\n255\n" + bytes(1))
case("hf-pgm-no-maxval.pgm", HF, 65, "maxval",
     "header ends after the size", b"P5\n2 2\n")
case("hf-pgm-plain.pgm", HF, 65, "not a PGM (P5), PNG or PFM",
     "plain (ASCII) PGM, P2", b"P2\n2 2\n255\n0 1 2 3\n")
case("hf-png-cut.png", HF, 65, "hf-png-cut.png",
     "a PNG signature and half an IHDR",
     b"\x89PNG\r\n\x1a\n\x00\x00\x00\x0dIHDR\x00\x00")
case("hf-pfm-nan.pfm", HF, 65, "pixel (1, 0): height is not finite",
     "a NaN height", pfm(b"Pf\n2 1\n-1\n", 0) +
     struct.pack("<2f", 0.5, float("nan")))
case("hf-stream.vxs", HF, 65, "(voxlux stream)",
     "a voxlux stream, not a map", V)
case("hf-missing.pgm", "heightfield -o OUT NOFILE", 66, "No such file",
     "map file does not exist", None)
case("hf-empty.pgm", "heightfield -o OUT <FILE", 66, "empty input",
     "empty standard input", b"")
case("hf-nz.pgm", "heightfield --nz 1 -o OUT FILE", 64, "--nz",
     "--nz below 2", b"P5\n1 1\n255\n\x00")
case("hf-range.pgm", "heightfield --range 1,1 -o OUT FILE", 64, "--range",
     "an empty --range", b"P5\n1 1\n255\n\x00")

# ---- no input, usage ----
case("missing.vxs", "vinfo NOFILE", 66, "No such file",
     "input file does not exist", None)
case("missing.nrrd", "vread -o OUT NOFILE", 66, "No such file",
     "input file does not exist", None)
case("missing.pfm", "tonemap -o OUT NOFILE", 66, "No such file",
     "input file does not exist", None)
case("empty.nrrd", "vread -o OUT <FILE", 66, "empty input",
     "empty standard input", b"")
case("empty.pfm", "tonemap -o OUT <FILE", 66, "empty input",
     "empty standard input", b"")
case("usage-vinfo", "vinfo FILE FILE", 64, "at most one input",
     "two inputs", V)
case("raw-long.raw", "vread --raw 2,2 --type u8 -o OUT FILE", 64,
     "expected 3 numbers", "--raw with two dims", None)
case("good.vxs", "tonemap --bits 7 -o OUT FILE", 64, "--bits",
     "--bits 7", None)
case("good.vxs", "raycast --size 0x8 -o OUT FILE", 64, "--size",
     "--size 0x8", None)

here = "."
with open("good.vxs", "wb") as f:     # GOOD: a valid volume stream
    f.write(stream(volm(body=bytes([0, 10, 20, 30, 40, 50, 60, 70]))))
with open("good-tlef.vxs", "wb") as f:  # the TLEF cases' valid original
    f.write(GOOD_TLEF)
with open("stale-tlef.vxs", "wb") as f:  # valid, but not its mesh's (CRC)
    f.write(mesh_tlef(mesh_crc32="00000000"))
# the env-*.scn cases' maps (beside the scenes)
with open("env-nan.pfm", "wb") as f:
    f.write(pfm3(2, 1, [1, 2, 3, float("nan"), 0, 0]))
with open("env-inf.exr", "wb") as f:
    f.write(exr("BGR", 2, 1, lambda c, x, y: float("inf") if x else 1.0))
with open("env-good.hdr", "wb") as f:   # 4 x 2, flat, valid
    f.write(HDRH + b"-Y 2 +X 4\n" + bytes([128, 64, 32, 129] * 8))
# the .img of nifti-pair-devzero.hdr: a link to an endless device
if os.path.lexists("nifti-pair-devzero.img"):
    os.remove("nifti-pair-devzero.img")
os.symlink("/dev/zero", "nifti-pair-devzero.img")
names = set()
with open("cases", "w") as cf:
    cf.write("# generated by make.sh: file<TAB>command<TAB>code<TAB>phrase\n")
    for name, prog, code, phrase, what, data in C:
        assert (name, prog) not in names, name
        assert data is not None or "NOFILE" in prog or os.path.exists(name)
        names.add((name, prog))
        if data is not None:
            with open(name, "wb") as f:
                f.write(data.encode() if isinstance(data, str) else data)
        cf.write("%s\t%s\t%d\t%s\n" % (name, prog, code, phrase))
with open("README.md", "w") as rf:
    rf.write("""# Malformed-input catalog

One small file per case, generated by `make.sh` (python3; run it from
anywhere, it writes here) and committed.  `tests/cli/test_malformed.sh` runs
each case's command and checks: the exit code (65 bad data, 66 no input,
64 usage), exactly one line on standard error, `program: ...`, containing
the phrase (for usage errors the usage line may follow) (an empty phrase: any message), nothing on standard output
(except for vinfo's listing where marked), no sanitizer report, and no
output file left behind for `-o OUT`.  `FILE` is the case's file, `<FILE`
the file on standard input, `NOFILE` a path that does not exist, `GOOD`
the valid volume stream `good.vxs`.  The
machine-readable list is `cases` (tab-separated).

| file | command | code | phrase | what is wrong |
| --- | --- | --- | --- | --- |
""")
    for name, prog, code, phrase, what, data in C:
        rf.write("| `%s` | `%s` | %d | %s | %s |\n" % (
            name, prog, code, ("`%s`" % phrase) if phrase else "(any)", what))
print("%d cases" % len(C))
EOF
