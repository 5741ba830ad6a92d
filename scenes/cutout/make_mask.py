#!/usr/bin/env python3
"""Writes the opacity map of scenes/cutout (deterministic; the standard library only):

`lattice.png`, 96x96 8-bit grey (sRGB-encoded, as a mask's bitmap usually is): a 4x4 grid of
round holes (byte 0: opacity 0) in an opaque sheet (byte 255), each hole ringed by a band of
byte 128 (opacity 0.216 once decoded), so that a cut-out of partial opacity is seen too.

    python3 scenes/cutout/make_mask.py
"""
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
SIDE = 96
CELL = SIDE // 4


def png(path, width, height, pixel):
    """An 8-bit grey PNG of `pixel(x, y)` (a byte)."""
    raw = b"".join(b"\x00" + bytes(pixel(x, y) for x in range(width)) for y in range(height))

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))

    ihdr = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def lattice(x, y):
    # Distance from the centre of the pixel's cell, in cells.
    dx = (x % CELL + 0.5) / CELL - 0.5
    dy = (y % CELL + 0.5) / CELL - 0.5
    r = math.hypot(dx, dy)
    if r < 0.28:
        return 0
    if r < 0.38:
        return 128
    return 255


png(os.path.join(HERE, "lattice.png"), SIDE, SIDE, lattice)
