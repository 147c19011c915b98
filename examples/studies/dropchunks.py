#!/usr/bin/python3
"""dropchunks.py TYPE...: copy a voxlux stream (formats/stream.md) from
standard input to standard output without its chunks of the given types
(e.g. SHTV IRRV: a renderer's --hdr output keeps the baked volumes it read,
gigabytes that an error measurement does not need).  Streams: chunks are
copied in blocks, never held whole."""
import struct
import sys

MAGIC = b'\x89VXL\r\n\x1a\n'
drop = {t.encode() for t in sys.argv[1:]}
src, dst = sys.stdin.buffer, sys.stdout.buffer
if src.read(8) != MAGIC:
    sys.exit('dropchunks: not a voxlux stream')
dst.write(MAGIC)
while True:
    head = src.read(12)
    if not head:
        break
    if len(head) != 12:
        sys.exit('dropchunks: truncated chunk header')
    n = struct.unpack('<Q', head[4:12])[0] + 4          # payload and CRC
    keep = head[:4] not in drop
    if keep:
        dst.write(head)
    while n > 0:
        b = src.read(min(n, 1 << 20))
        if not b:
            sys.exit('dropchunks: truncated chunk')
        if keep:
            dst.write(b)
        n -= len(b)
