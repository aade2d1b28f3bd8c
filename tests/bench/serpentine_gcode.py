#!/usr/bin/env python3
"""Benchmark G-code for `strand check`: LAYERS layers, each one serpentine of ROWS long
parallel lines joined by short straight U-turns (2 * ROWS deposit segments per layer), the
rows along x on even layers and along y on odd ones, like a log-pile.
Usage: serpentine_gcode.py OUT.gcode [--layers 4] [--rows 125000] [--length 1250] [--pitch 0.01]"""
import argparse

ap = argparse.ArgumentParser()
ap.add_argument("out")
ap.add_argument("--layers", type=int, default=4)
ap.add_argument("--rows", type=int, default=125000)
ap.add_argument("--length", type=float, default=1250.0)  # mm, row length
ap.add_argument("--pitch", type=float, default=0.01)  # mm between rows (> check's touch distance)
a = ap.parse_args()
with open(a.out, "w") as f:
    f.write("G21\nG90\n")
    for layer in range(a.layers):
        z = 0.2 * (layer + 1)
        swap = layer % 2 == 1
        xy = (lambda u, v: (v, u)) if swap else (lambda u, v: (u, v))
        f.write(f";LAYER_CHANGE\n;Z:{z:.3f}\n;HEIGHT:0.200\n;LAYER:{layer}\nG0 Z{z:.3f}\n")
        x, y = xy(0.0, 0.0)
        f.write(f"G0 X{x:.3f} Y{y:.3f}\n")
        lines = []
        for r in range(a.rows):
            v = r * a.pitch
            u = a.length if r % 2 == 0 else 0.0
            x, y = xy(u, v)
            lines.append(f"G1 X{x:.3f} Y{y:.3f}\n")
            x, y = xy(u, v + a.pitch)
            lines.append(f"G1 X{x:.3f} Y{y:.3f}\n")
        f.write("".join(lines))
