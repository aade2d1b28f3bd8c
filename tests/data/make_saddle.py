#!/usr/bin/env python3
"""Write a coarse saddle patch for Strand's tests (CC0): height (y^2 - z^2) / (2 R) along the
workpiece's +x over a SIZE x SIZE mm square in y, z centred on (0, 40), N x N cells, each cut
into two triangles, placed as samples/meshes/sphere-cap.stl is (its centre at (20, 0, 40), its
outside facing +x). Plain Python 3.

usage: make_saddle.py OUT.obj R SIZE N
"""
import sys

out, r, size, n = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
with open(out, 'w') as o:
    o.write('# %s: saddle x = 20 + (y^2 - (z - 40)^2) / (2 * %g) mm, %g mm square, %d x %d '
            'cells (make_saddle.py)\n' % (out.split('/')[-1], r, size, n, n))
    for i in range(n + 1):
        for j in range(n + 1):
            y = -size / 2 + size * i / n
            z = -size / 2 + size * j / n
            o.write('v %.4f %.4f %.4f\n' % (20 + (y * y - z * z) / (2 * r), y, 40 + z))
    for i in range(n):
        for j in range(n):
            a = i * (n + 1) + j + 1
            b, c, d = a + n + 1, a + n + 2, a + 1
            o.write('f %d %d %d\nf %d %d %d\n' % (a, b, c, a, c, d))
