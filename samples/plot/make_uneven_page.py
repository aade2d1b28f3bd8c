#!/usr/bin/env python3
"""Writes samples/plot/uneven-page.pgm: a 240 x 120 px 'scan' lit from the top left (paper
from grey 250 down to 90 at the bottom right) with six letters, I bars and O rings, 70 greys
darker than the paper around them, so the letters on the left are lighter than the paper on
the right and no single threshold finds them all (`strand trace --highpass`). The same page
as uneven_page() in tests/slicer/trace_test.cpp. Pure Python; deterministic."""
import math
import sys

W, H = 240, 120


def grey(x, y):
    paper = 250 - 120.0 * x / 239 - 40.0 * y / 119
    ink = False
    for k in range(6):
        dx, dy = x + 0.5 - (20 + 40 * k), y + 0.5 - 60
        if k % 2 == 0:
            ink |= abs(dx) <= 2.5 and abs(dy) <= 15
        else:
            ink |= 8 <= math.hypot(dx, dy) <= 12
    v = paper - (70 if ink else 0)
    return int(math.floor(v + 0.5))  # std::lround for positive values


def main(path):
    data = bytes(grey(x, y) for y in range(H) for x in range(W))
    with open(path, "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (W, H) + data)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "uneven-page.pgm")
