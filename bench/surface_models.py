#!/usr/bin/env python3
"""bench/surface_models.py: surfaces the bench and the tests generate
(download-free), written as OBJ:
  holes N SUBDIV OUT.obj   a unit sphere (icosphere, SUBDIV subdivisions:
                           20 * 4^SUBDIV triangles) with N round holes of
                           radius 0.15 at Fibonacci points: N boundary loops.
Usage: python3 bench/surface_models.py holes 20 4 holes20.obj"""
import math
import sys


def icosphere(subdiv):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
         (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
         (8, 6, 7), (9, 8, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    for _ in range(subdiv):
        mid = {}

        def m(a, b):
            k = (min(a, b), max(a, b))
            if k not in mid:
                p = [(v[a][i] + v[b][i]) / 2 for i in range(3)]
                n = math.sqrt(sum(x * x for x in p))
                v.append(tuple(x / n for x in p))
                mid[k] = len(v) - 1
            return mid[k]

        nf = []
        for a, b, c in f:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = nf
    return v, f


def holes(n, subdiv, out):
    v, f = icosphere(subdiv)
    g = math.pi * (3 - 5 ** 0.5)
    centers = []
    for i in range(n):
        z = 1 - 2 * (i + 0.5) / n
        r = math.sqrt(1 - z * z)
        centers.append((r * math.cos(g * i), r * math.sin(g * i), z))
    keep = []
    for t in f:
        c = [sum(v[k][i] for k in t) / 3 for i in range(3)]
        if all(sum((c[i] - p[i]) ** 2 for i in range(3)) > 0.15 ** 2 for p in centers):
            keep.append(t)
    used = sorted({k for t in keep for k in t})
    idx = {k: i + 1 for i, k in enumerate(used)}
    with open(out, "w") as fh:
        fh.write("# a unit sphere with %d holes (bench/surface_models.py)\n" % n)
        for k in used:
            fh.write("v %.17g %.17g %.17g\n" % v[k])
        for a, b, c in keep:
            fh.write("f %d %d %d\n" % (idx[a], idx[b], idx[c]))


if __name__ == "__main__":
    if len(sys.argv) != 5 or sys.argv[1] != "holes":
        sys.exit(__doc__)
    holes(int(sys.argv[2]), int(sys.argv[3]), sys.argv[4])
