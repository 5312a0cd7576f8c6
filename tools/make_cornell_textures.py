#!/usr/bin/env python3
"""Writes the maps of scenes/cornell-textured (no dependencies beyond Python):

- textures/checker.png: 8 x 8 checks over 512 x 512 texels, 8-bit sRGB, for the floor;
- textures/egg-crate.png: a 16-bit grey height map, h = 0.5 + 0.5 sin(12 pi u) sin(12 pi v)
  (6 x 6 smooth bumps), 256 x 256, for the back wall's bump map.

Usage: tools/make_cornell_textures.py [output folder]   (default: scenes/cornell-textured/textures)
"""
import math
import os
import struct
import sys
import zlib


def png(path, width, height, rows, bit_depth, colour_type):
    """rows: one bytes object per row, top row first (PNG order)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    raw = b"".join(b"\x00" + row for row in rows)  # filter type 0 on every row
    data = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(data)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "scenes", "cornell-textured", "textures")
    os.makedirs(out, exist_ok=True)

    size, checks = 512, 8
    light, dark = bytes([232, 226, 214]), bytes([58, 54, 50])
    rows = []
    for j in range(size):
        row = bytearray()
        for i in range(size):
            row += light if ((i * checks // size) + (j * checks // size)) % 2 == 0 else dark
        rows.append(bytes(row))
    png(os.path.join(out, "checker.png"), size, size, rows, 8, 2)

    size = 256
    rows = []
    for j in range(size):
        v = 1 - (j + 0.5) / size  # the top row is v = 1
        row = bytearray()
        for i in range(size):
            u = (i + 0.5) / size
            h = 0.5 + 0.5 * math.sin(12 * math.pi * u) * math.sin(12 * math.pi * v)
            row += struct.pack(">H", round(h * 65535))
        rows.append(bytes(row))
    png(os.path.join(out, "egg-crate.png"), size, size, rows, 16, 0)


if __name__ == "__main__":
    main()
