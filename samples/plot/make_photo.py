#!/usr/bin/env python3
"""Renders samples/plot/photo.png: a grey 'photo' of a shaded ball and a block on a table
(soft light from the upper left, a shadow, a gradient backdrop) for `strand plot --trace
--levels 2`. Pure Python (zlib + struct) so it needs nothing installed; deterministic."""
import math
import struct
import sys
import zlib

W, H = 240, 160


def shade(x, y):
    # backdrop: light at the top, darker towards the table edge
    g = 0.92 - 0.25 * y / H
    if y > 105:  # table
        g = 0.78 - 0.2 * (y - 105) / (H - 105)
    # shadow of the ball on the table (an ellipse to the lower right)
    sx, sy = (x - 150) / 48.0, (y - 120) / 12.0
    if sx * sx + sy * sy < 1:
        g *= 0.55 + 0.45 * (sx * sx + sy * sy)
    # the block: two faces, front darker than the top
    if 30 <= x <= 90 and 70 <= y <= 118:
        g = 0.35 if y > 82 else 0.7
    # the ball: Lambert shading, light from the upper left
    dx, dy = (x - 135) / 38.0, (y - 78) / 38.0
    r2 = dx * dx + dy * dy
    if r2 < 1:
        nz = math.sqrt(1 - r2)
        lx, ly, lz = -0.55, -0.6, 0.58
        g = 0.08 + 0.85 * max(0.0, -dx * lx - dy * ly + nz * lz) / math.sqrt(lx * lx + ly * ly + lz * lz)
    return max(0, min(255, int(round(g * 255))))


def png(width, height, rows):
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "photo.png"
    with open(out, "wb") as f:
        f.write(png(W, H, [[shade(x, y) for x in range(W)] for y in range(H)]))
