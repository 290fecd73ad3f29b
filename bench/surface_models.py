#!/usr/bin/env python3
"""surface_models.py DIR [N]: surfaces the surface path was not tuned on, about N
vertices each (default 20000), written in every input format glpgp reads:

  ellipsoid.ply   an icosphere scaled to 1.6 x 1.0 x 0.7 (binary little-endian PLY)
  bumpy.off       an icosphere with radius 1 + 0.12 sin(4x) sin(3y) sin(2z) (OFF)
  trefoil.obj     a tube of radius 0.35 around a trefoil knot (genus 1, OBJ)
  can.stl         a closed cylinder of radius 1, height 1.5, sharp rims (binary STL)
  saddle.obj      the open patch z = 0.4 (x^2 - y^2) over [-1, 1]^2 (four corners, OBJ)

Deterministic; the Python standard library only."""
import math
import struct
import sys


def add(a, b): return (a[0] + b[0], a[1] + b[1], a[2] + b[2])
def sub(a, b): return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
def mul(a, s): return (a[0] * s, a[1] * s, a[2] * s)
def dot(a, b): return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def unit(a): return mul(a, 1.0 / math.sqrt(dot(a, a)))


def icosphere(n):
    """Vertices (unit sphere) and triangles of a subdivided icosahedron with >= n vertices."""
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
         (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
         (8, 6, 7), (9, 8, 1)]
    v = [unit(p) for p in v]
    while len(v) < n:
        mid = {}

        def m(a, b):
            k = (min(a, b), max(a, b))
            if k not in mid:
                v.append(unit(add(v[a], v[b])))
                mid[k] = len(v) - 1
            return mid[k]

        g = []
        for a, b, c in f:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            g += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = g
    return v, f


def grid_tube(curve, nu, nw, radius):
    """A tube around the closed curve(u) (u in [0, 1)), nu x nw periodic grid, outward normals."""
    c = [curve(k / nu) for k in range(nu)]
    d = [unit(sub(c[(k + 1) % nu], c[k - 1])) for k in range(nu)]
    # a rotation-minimising frame along the curve, closed up by twisting
    ns = [unit(cross(d[0], (0.3, 0.5, 0.8)))]
    for k in range(1, nu):
        ns.append(unit(sub(ns[-1], mul(d[k], dot(ns[-1], d[k])))))
    last = unit(sub(ns[-1], mul(d[0], dot(ns[-1], d[0]))))
    twist = math.atan2(dot(cross(last, ns[0]), d[0]), dot(last, ns[0]))
    bs = [cross(d[k], ns[k]) for k in range(nu)]
    pts = []
    for k in range(nu):
        a0 = twist * k / nu
        n = add(mul(ns[k], math.cos(a0)), mul(bs[k], math.sin(a0)))
        b = add(mul(ns[k], -math.sin(a0)), mul(bs[k], math.cos(a0)))
        for j in range(nw):
            w = 2 * math.pi * j / nw
            pts.append(add(c[k], mul(add(mul(n, math.cos(w)), mul(b, math.sin(w))), radius)))
    tris = []
    for k in range(nu):
        for j in range(nw):
            p, q = k * nw + j, ((k + 1) % nu) * nw + j
            p1, q1 = k * nw + (j + 1) % nw, ((k + 1) % nu) * nw + (j + 1) % nw
            tris += [(p, q, q1), (p, q1, p1)]
    return pts, tris


def can(n):
    """A closed cylinder: side grid, caps as rings of a polar grid, shared rims."""
    nr = max(8, int(round(math.sqrt(n / 10))))  # rings per cap
    nc = 4 * nr  # points per circle
    nh = max(4, int(round(n / nc - 2 * nr)))  # side rows
    pts, tris = [], []
    rim = {}
    for i in range(nh + 1):  # side, i = 0 bottom rim, nh top rim
        for j in range(nc):
            a = 2 * math.pi * j / nc
            pts.append((math.cos(a), math.sin(a), 1.5 * i / nh))
    for i in range(nh):
        for j in range(nc):
            p, q = i * nc + j, i * nc + (j + 1) % nc
            tris += [(p, q, q + nc), (p, q + nc, p + nc)]
    for top in (0, 1):
        zc = 1.5 * top
        ring_prev = [(nh * nc if top else 0) + j for j in range(nc)]
        for r in range(nr - 1, 0, -1):
            m = max(4, int(round(nc * r / nr)))
            ring = []
            for j in range(m):
                a = 2 * math.pi * j / m
                pts.append((r / nr * math.cos(a), r / nr * math.sin(a), zc))
                ring.append(len(pts) - 1)
            tris += zipper(ring_prev, ring, top)
            ring_prev = ring
        pts.append((0.0, 0.0, zc))
        cidx = len(pts) - 1
        for j in range(len(ring_prev)):
            a, b = ring_prev[j], ring_prev[(j + 1) % len(ring_prev)]
            tris.append((a, cidx, b) if not top else (a, b, cidx))
    return pts, tris


def zipper(outer, inner, top):
    """Triangles between two concentric rings (angles increasing), oriented for the cap side."""
    tr = []
    i = j = 0
    no, ni = len(outer), len(inner)
    while i < no or j < ni:
        a, b = outer[i % no], inner[j % ni]
        if j >= ni or (i < no and (i + 1) / no <= (j + 1) / ni):
            c = outer[(i + 1) % no]
            t = (a, c, b)
            i += 1
        else:
            c = inner[(j + 1) % ni]
            t = (a, c, b)
            j += 1
        tr.append(t if top else (t[0], t[2], t[1]))
    return tr


def saddle(n):
    k = int(round(math.sqrt(n))) - 1
    xs = [-1 + 2.0 * i / k for i in range(k + 1)]
    pts = [(x, y, 0.4 * (x * x - y * y)) for y in xs for x in xs]
    tris = []
    for j in range(k):
        for i in range(k):
            p = j * (k + 1) + i
            tris += [(p, p + 1, p + k + 2), (p, p + k + 2, p + k + 1)] if (i + j) % 2 else \
                    [(p, p + 1, p + k + 1), (p + 1, p + k + 2, p + k + 1)]
    return pts, tris


def trefoil(t):
    a = 2 * math.pi * t
    return (math.sin(a) + 2 * math.sin(2 * a), math.cos(a) - 2 * math.cos(2 * a), -math.sin(3 * a))


def write_obj(path, v, f):
    with open(path, "w") as o:
        for p in v:
            o.write("v %.17g %.17g %.17g\n" % tuple(p))
        for t in f:
            o.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def write_off(path, v, f):
    with open(path, "w") as o:
        o.write("OFF\n%d %d 0\n" % (len(v), len(f)))
        for p in v:
            o.write("%.17g %.17g %.17g\n" % tuple(p))
        for t in f:
            o.write("3 %d %d %d\n" % tuple(t))


def write_ply(path, v, f):
    with open(path, "wb") as o:
        o.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty double x\nproperty double y\n"
                 "property double z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
                 % (len(v), len(f))).encode())
        for p in v:
            o.write(struct.pack("<3d", *p))
        for t in f:
            o.write(struct.pack("<B3i", 3, *t))


def write_stl(path, v, f):
    with open(path, "wb") as o:
        o.write(b"glpgp bench surface".ljust(80, b" "))
        o.write(struct.pack("<I", len(f)))
        for t in f:
            o.write(struct.pack("<12fH", 0, 0, 0, *v[t[0]], *v[t[1]], *v[t[2]], 0))


def main():
    d = sys.argv[1]
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 20000
    v, f = icosphere(n)
    write_ply(d + "/ellipsoid.ply", [(1.6 * p[0], p[1], 0.7 * p[2]) for p in v], f)
    write_off(d + "/bumpy.off", [mul(p, 1 + 0.12 * math.sin(4 * p[0]) * math.sin(3 * p[1]) * math.sin(2 * p[2]))
                                 for p in v], f)
    nw = max(8, int(round(math.sqrt(n / 8))))
    v, f = grid_tube(trefoil, max(16, n // nw), nw, 0.35)
    write_obj(d + "/trefoil.obj", v, f)
    v, f = can(n)
    write_stl(d + "/can.stl", v, f)
    v, f = saddle(n)
    write_obj(d + "/saddle.obj", v, f)


if __name__ == "__main__":
    main()
