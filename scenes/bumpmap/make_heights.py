#!/usr/bin/env python3
"""Writes the height fields of scenes/bumpmap (deterministic; the standard library only):

* `bumps.png`, 64x32 8-bit grey: smooth bumps `0.5 + 0.3 sin(3·2πx/64) cos(2·2πy/32)`,
  periodic across the edges (the texture wraps);
* `ridges.png`, 48x48 8-bit RGB: ridges along a diagonal with a coloured tint, so that the
  luminance (not one channel) drives the gradient;
* `ramp.png`, 16x4 8-bit grey: 10 + 8x in column x (a linear ramp, wrapping at the edge);
* `flat.png`, 4x4 8-bit grey: 128 everywhere (no gradient).

    python3 scenes/bumpmap/make_heights.py
"""
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def png(path, width, height, channels, pixel):
    """An 8-bit PNG (grey or RGB) of `pixel(x, y)` (a tuple of `channels` bytes)."""
    colour_type = {1: 0, 3: 2}[channels]
    raw = b"".join(
        b"\x00" + bytes(v for x in range(width) for v in pixel(x, y)) for y in range(height)
    )

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))

    ihdr = struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def byte(v):
    return max(0, min(255, round(255 * v)))


def bumps(x, y):
    return (byte(0.5 + 0.3 * math.sin(3 * 2 * math.pi * x / 64) * math.cos(2 * 2 * math.pi * y / 32)),)


def ridges(x, y):
    h = 0.5 + 0.35 * math.sin(2 * 2 * math.pi * (x + y) / 48)
    return (byte(h), byte(0.8 * h + 0.1), byte(0.6 * h + 0.2))


png(os.path.join(HERE, "bumps.png"), 64, 32, 1, bumps)
png(os.path.join(HERE, "ridges.png"), 48, 48, 3, ridges)
png(os.path.join(HERE, "ramp.png"), 16, 4, 1, lambda x, y: (10 + 8 * x,))
png(os.path.join(HERE, "flat.png"), 4, 4, 1, lambda x, y: (128,))
