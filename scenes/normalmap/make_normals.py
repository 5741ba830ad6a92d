#!/usr/bin/env python3
"""Writes the normal maps of scenes/normalmap (deterministic; the standard library only).
Each texel holds a unit normal `n` in the tangent frame as the bytes of `(n + 1) / 2`
(Mitsuba's `normalmap` convention, read `raw`):

* `waves.png`, 64x64: waves tilting the normal toward +-u (two periods across) and toward
  +-v (three periods), with different amplitudes, so that swapping or mirroring the tangent
  axes shows;
* `facets.png`, 32x32: 8x8-texel facets, the k-th (row by row) tilted 35 degrees toward
  the azimuth 45 k degrees from +u, so that each of the eight directions of tilt appears
  twice.

    python3 scenes/normalmap/make_normals.py
"""
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def png(path, width, height, pixel):
    """An 8-bit RGB PNG of `pixel(x, y)` (a tuple of three bytes)."""
    raw = b"".join(b"\x00" + bytes(v for x in range(width) for v in pixel(x, y)) for y in range(height))

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))

    ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def encode(n):
    length = math.sqrt(sum(c * c for c in n))
    return tuple(max(0, min(255, round(255 * (c / length + 1) / 2))) for c in n)


def waves(x, y):
    return encode((0.7 * math.sin(2 * 2 * math.pi * (x + 0.5) / 64), 0.35 * math.cos(3 * 2 * math.pi * (y + 0.5) / 64), 1.0))


def facets(x, y):
    k = (x // 8) + 4 * (y // 8)
    phi, theta = math.radians(45 * k), math.radians(35)
    return encode((math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta)))


png(os.path.join(HERE, "waves.png"), 64, 64, waves)
png(os.path.join(HERE, "facets.png"), 32, 32, facets)
