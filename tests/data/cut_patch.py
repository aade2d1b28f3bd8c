#!/usr/bin/env python3
"""Cut an open patch out of a triangle mesh (OBJ), scaled by SCALE first: the triangles whose
corners all lie within RADIUS of the vertex nearest CENTRE, measured along the mesh's edges
(Dijkstra), and whose normals are within MAX_TILT degrees of the patch's area-weighted mean
normal, connected to the triangle nearest CENTRE. Writes an OBJ (v and f only, mm,
fixed digits). Plain Python 3, no packages.

Then placed as samples/meshes/sphere-cap.stl is, for a robot to hold: turned (the smallest
rotation) so its mean normal faces the workpiece frame's +x, the vertex nearest CENTRE moved to
(20, 0, 40) mm.

usage: cut_patch.py IN.obj OUT.obj SCALE CX CY CZ RADIUS MAX_TILT
"""
import heapq
import math
import sys


def read_obj(path, scale):
    vs, fs = [], []
    for line in open(path):
        p = line.split()
        if not p:
            continue
        if p[0] == 'v':
            vs.append([scale * float(x) for x in p[1:4]])
        elif p[0] == 'f':
            idx = [int(t.split('/')[0]) for t in p[1:]]
            idx = [i - 1 if i > 0 else len(vs) + i for i in idx]
            for k in range(1, len(idx) - 1):
                fs.append((idx[0], idx[k], idx[k + 1]))
    return vs, fs


def sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def unit(a):
    n = math.sqrt(dot(a, a))
    return [x / n for x in a] if n > 0 else a


def main():
    src, out = sys.argv[1], sys.argv[2]
    scale = float(sys.argv[3])
    centre = [float(x) for x in sys.argv[4:7]]
    radius, max_tilt = float(sys.argv[7]), float(sys.argv[8])
    vs, fs = read_obj(src, scale)
    normal = [unit(cross(sub(vs[b], vs[a]), sub(vs[c], vs[a]))) for a, b, c in fs]
    adj = {}
    for a, b, c in fs:
        for p, q in ((a, b), (b, c), (c, a)):
            adj.setdefault(p, set()).add(q)
            adj.setdefault(q, set()).add(p)
    start = min(adj, key=lambda i: math.dist(vs[i], centre))
    dist, heap = {start: 0.0}, [(0.0, start)]
    while heap:
        d, i = heapq.heappop(heap)
        if d > dist[i] or d > radius:
            continue
        for j in sorted(adj[i]):
            nd = d + math.dist(vs[i], vs[j])
            if nd < dist.get(j, math.inf):
                dist[j] = nd
                heapq.heappush(heap, (nd, j))
    inside = [all(dist.get(i, math.inf) <= radius for i in f) for f in fs]
    seed = min(range(len(fs)),
               key=lambda t: math.dist([sum(vs[i][k] for i in fs[t]) / 3 for k in range(3)],
                                       centre))
    facing = [0.0, 0.0, 0.0]
    for t, f in enumerate(fs):
        if inside[t]:
            n = cross(sub(vs[f[1]], vs[f[0]]), sub(vs[f[2]], vs[f[0]]))
            facing = [facing[k] + n[k] for k in range(3)]
    facing = unit(facing)
    cos_max = math.cos(math.radians(max_tilt))
    keep = [inside[t] and dot(normal[t], facing) >= cos_max for t in range(len(fs))]
    by_edge = {}
    for t, f in enumerate(fs):
        for k in range(3):
            by_edge.setdefault(frozenset((f[k], f[(k + 1) % 3])), []).append(t)
    seen, todo = {seed}, [seed]
    while todo:
        t = todo.pop()
        f = fs[t]
        for k in range(3):
            for u in by_edge[frozenset((f[k], f[(k + 1) % 3]))]:
                if u not in seen and keep[u]:
                    seen.add(u)
                    todo.append(u)
    tris = sorted(seen)
    # A disk: one border, Euler characteristic 1 (V - E + F).
    edges = {}
    for t in tris:
        f = fs[t]
        for k in range(3):
            e = frozenset((f[k], f[(k + 1) % 3]))
            edges[e] = edges.get(e, 0) + 1
    verts = {i for t in tris for i in fs[t]}
    euler = len(verts) - len(edges) + len(tris)
    # Smallest rotation taking `facing` onto +x (Rodrigues), then the centre to (20, 0, 40).
    x = [1.0, 0.0, 0.0]
    axis, c = cross(facing, x), dot(facing, x)
    s = math.sqrt(dot(axis, axis))
    k = unit(axis) if s > 1e-12 else [0.0, 0.0, 1.0]
    angle = math.atan2(s, c)

    def turned(p):
        kxp, kdp = cross(k, p), dot(k, p)
        return [p[i] * math.cos(angle) + kxp[i] * math.sin(angle) +
                k[i] * kdp * (1 - math.cos(angle)) for i in range(3)]

    origin = turned(vs[start])
    place = [20.0, 0.0, 40.0]
    vs = [[q[i] - origin[i] + place[i] for i in range(3)] for q in map(turned, vs)]
    index = {}
    with open(out, 'w') as o:
        o.write('# %s: patch of %d triangles cut by cut_patch.py %s\n' %
                (out.split('/')[-1], len(tris), ' '.join(sys.argv[3:])))
        for t in tris:
            for i in fs[t]:
                if i not in index:
                    index[i] = len(index) + 1
                    o.write('v %.4f %.4f %.4f\n' % tuple(vs[i]))
        for t in tris:
            o.write('f %d %d %d\n' % tuple(index[i] for i in fs[t]))
    print('%s: %d triangles, %d vertices, Euler characteristic %d, facing %.3f %.3f %.3f' %
          (out, len(tris), len(index), euler, *facing))


main()
