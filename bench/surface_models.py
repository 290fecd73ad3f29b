#!/usr/bin/env python3
"""bench/surface_models.py: surfaces the bench and the tests generate
(download-free), written as OBJ:
  holes N SUBDIV OUT.obj   a unit sphere (icosphere, SUBDIV subdivisions:
                           20 * 4^SUBDIV triangles) with N round holes of
                           radius min(0.15, 0.9 / sqrt(N)) at Fibonacci
                           points: N boundary loops (N = 120: SUBDIV 6).
  roundholes N SUBDIV OUT.obj
                           the same sphere and holes cut along their
                           circles (each triangle clipped by the rim, the
                           vertices near it snapped onto it first): round
                           holes, as a perforated CAD shell, where `holes`
                           leaves them jagged.
  bumpy SUBDIV OUT.obj [J]  a scan-like closed surface: the icosphere
                           (20 * 4^SUBDIV triangles) stretched to an
                           ellipsoid, with bumps and a vertex jitter of J
                           (default 0.002: 0.2%; SUBDIV 6: 82k triangles,
                           7: 328k).
  slab GX GY SUB OUT.obj    a CAD-like plate of genus GX * GY: a 2 GX + 1 by
                           2 GY + 1 by 1 block of unit cubes with every
                           other interior cube removed (GX by GY square
                           holes), sharp edges everywhere; each cube face
                           SUB x SUB squares, two triangles each.
  prism N SUB OUT.obj       a regular N-gon prism (side creases of 360 / N
                           degrees; N = 8: 45, 9: 40), each side SUB x 2 SUB
                           squares, the caps fans: CAD creases near the
                           feature angle.
  box SUB OUT.obj           the unit cube [0, 1]^3, SUB x SUB squares per
                           face (SUB 1: two triangles per face, coarse CAD).
  jitter IN.obj OUT.obj F   IN's vertices moved by a uniform jitter of F
                           mean edges in every coordinate (seeded).
  implicit KIND N OUT.obj   marching tetrahedra of an implicit surface on an
                           N^3 grid (the output of marching-cubes tools:
                           needle slivers, uneven sizes, about 5% of the
                           triangles under 5 degrees): KIND blob (a lumpy
                           closed surface), genus3 (three fused tori),
                           schwarz (Schwarz's P surface in a box: open, 18
                           boundary loops, 13 components), gyroid (a
                           gyroid in a ball, many handles) or part (a plate
                           with a round hole turned off the grid's axes:
                           sharp edges cut into staircases, as a CT scan of
                           a machined part); N 30-48: 16k-48k triangles.
  speck SUBDIV OUT.obj      scan debris: the unit icosphere and, 1 away
                           from it, a tetrahedron 0.01 across (two
                           connected components, one far below any size).
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


def hole_centers(n):
    """n hole centres at Fibonacci points of the unit sphere and the holes' radius."""
    g = math.pi * (3 - 5 ** 0.5)
    radius = min(0.15, 0.9 / math.sqrt(n))  # apart at any n (Fibonacci spacing ~ 3.5 / sqrt(n))
    centers = []
    for i in range(n):
        z = 1 - 2 * (i + 0.5) / n
        r = math.sqrt(1 - z * z)
        centers.append((r * math.cos(g * i), r * math.sin(g * i), z))
    return centers, radius


def round_holes(n, subdiv, out):
    """The holes cut along their rims: the signed distance to the nearest
    rim, sd = |x - c| - radius, clipped triangle by triangle (marching
    triangles; the crossings pushed onto the sphere), after the vertices
    within a fifth of an edge of a rim were snapped onto it (along the
    great circle from the centre: no slivers)."""
    v, f = icosphere(subdiv)
    centers, radius = hole_centers(n)
    edge = math.dist(v[f[0][0]], v[f[0][1]])
    ang = 2 * math.asin(radius / 2)

    def sd(x):
        return min(math.dist(x, c) for c in centers) - radius

    def onto_rim(x):
        p = min(centers, key=lambda c: math.dist(x, c))
        d = sum(x[i] * p[i] for i in range(3))
        t = [x[i] - d * p[i] for i in range(3)]
        tn = math.sqrt(sum(c * c for c in t))
        return tuple(math.cos(ang) * p[i] + math.sin(ang) * t[i] / tn for i in range(3))

    v = [onto_rim(x) if abs(sd(x)) < 0.2 * edge else x for x in v]
    s = [sd(x) for x in v]
    s = [0.0 if abs(q) < 1e-12 else q for q in s]
    mid = {}

    def cut(a, b):  # the rim's crossing of edge ab, once per edge
        k = (min(a, b), max(a, b))
        if k not in mid:
            t = s[a] / (s[a] - s[b])
            p = [v[a][i] + t * (v[b][i] - v[a][i]) for i in range(3)]
            m = math.sqrt(sum(c * c for c in p))
            v.append(tuple(c / m for c in p))
            s.append(0.0)
            mid[k] = len(v) - 1
        return mid[k]

    keep = []
    for t in f:
        sv = [s[k] for k in t]
        if min(sv) >= 0:
            keep.append(t)
            continue
        if max(sv) <= 0:
            continue
        poly = []  # the triangle's part outside the holes, in order
        for j in range(3):
            a, b = t[j], t[(j + 1) % 3]
            if s[a] >= 0:
                poly.append(a)
            if (s[a] > 0 > s[b]) or (s[a] < 0 < s[b]):
                poly.append(cut(a, b))
        for j in range(1, len(poly) - 1):
            keep.append((poly[0], poly[j], poly[j + 1]))
    used = sorted({k for t in keep for k in t})
    idx = {k: i for i, k in enumerate(used)}
    write_obj(out, "a unit sphere with %d round holes" % n, [v[k] for k in used], [tuple(idx[k] for k in t) for t in keep])


def holes(n, subdiv, out):
    v, f = icosphere(subdiv)
    centers, radius = hole_centers(n)
    keep = []
    for t in f:
        c = [sum(v[k][i] for k in t) / 3 for i in range(3)]
        if all(sum((c[i] - p[i]) ** 2 for i in range(3)) > radius ** 2 for p in centers):
            keep.append(t)
    used = sorted({k for t in keep for k in t})
    idx = {k: i + 1 for i, k in enumerate(used)}
    with open(out, "w") as fh:
        fh.write("# a unit sphere with %d holes (bench/surface_models.py)\n" % n)
        for k in used:
            fh.write("v %.17g %.17g %.17g\n" % v[k])
        for a, b, c in keep:
            fh.write("f %d %d %d\n" % (idx[a], idx[b], idx[c]))


def write_obj(out, title, v, f):
    with open(out, "w") as fh:
        fh.write("# %s (bench/surface_models.py)\n" % title)
        for p in v:
            fh.write("v %.17g %.17g %.17g\n" % tuple(p))
        for a, b, c in f:
            fh.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))


def bumpy(subdiv, out, seed=1, noise=0.002):
    import random
    v, f = icosphere(subdiv)
    rng = random.Random(seed)
    w = []
    for x, y, z in v:
        r = 1 + 0.08 * math.sin(5 * x) * math.cos(4 * y) + 0.05 * math.sin(7 * z + 1) + rng.uniform(-noise, noise)
        w.append((x * r, 0.8 * y * r, 1.3 * z * r))
    write_obj(out, "a bumpy ellipsoid, %d triangles" % len(f), w, f)


def speck(subdiv, out):
    v, f = icosphere(subdiv)
    n, s = len(v), 0.01
    v += [(2, 0, 0), (2 + s, 0, 0), (2, s, 0), (2, 0, s)]
    f += [(n, n + 2, n + 1), (n, n + 1, n + 3), (n + 1, n + 2, n + 3), (n, n + 3, n + 2)]
    write_obj(out, "a sphere and a speck, %d triangles" % len(f), v, f)


def slab(gx, gy, sub, out):
    nx, ny = 2 * gx + 1, 2 * gy + 1
    solid = lambda i, j: 0 <= i < nx and 0 <= j < ny and not (i % 2 == 1 and j % 2 == 1)
    vid, v, f = {}, [], []

    def vert(p):
        if p not in vid:
            vid[p] = len(v)
            v.append(tuple(c / sub for c in p))
        return vid[p]

    for i in range(nx):
        for j in range(ny):
            if not solid(i, j):
                continue
            for ax, sg in ((0, 1), (0, -1), (1, 1), (1, -1), (2, 1), (2, -1)):
                q = [i, j, 0]
                q[ax] += sg
                if ax < 2 and solid(q[0], q[1]):
                    continue
                base = [i, j, 0]
                if sg > 0:
                    base[ax] += 1
                a1, a2 = (ax + 1) % 3, (ax + 2) % 3
                if sg < 0:
                    a1, a2 = a2, a1
                for u in range(sub):
                    for t in range(sub):
                        def corner(du, dt):
                            p = [c * sub for c in base]
                            p[a1] += u + du
                            p[a2] += t + dt
                            return vert(tuple(p))
                        c00, c10, c11, c01 = corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)
                        f += [(c00, c10, c11), (c00, c11, c01)]
    write_obj(out, "a plate of genus %d" % (gx * gy), v, f)


def quad_patch(v, f, vid, P, U, W, nu, nw):
    """Two triangles per cell of the planar patch P + s U + t W, nu x nw cells."""
    def vert(i, j):
        p = tuple(round(P[k] + U[k] * i / nu + W[k] * j / nw, 12) for k in range(3))
        if p not in vid:
            vid[p] = len(v)
            v.append(p)
        return vid[p]
    for i in range(nu):
        for j in range(nw):
            a, b, c, d = vert(i, j), vert(i + 1, j), vert(i + 1, j + 1), vert(i, j + 1)
            f += [(a, b, c), (a, c, d)]


def prism(n, sub, out):
    v, f, vid = [], [], {}
    pts = [(math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n)) for i in range(n)]
    for i in range(n):
        a, b = pts[i], pts[(i + 1) % n]
        quad_patch(v, f, vid, (a[0], a[1], 0), (b[0] - a[0], b[1] - a[1], 0), (0, 0, 2), sub, 2 * sub)
    for z, up in ((0, False), (2, True)):  # the caps: fans about their centres
        c = len(v)
        v.append((0, 0, z))
        ring = [vid[(round(a[0] + (b[0] - a[0]) * k / sub, 12), round(a[1] + (b[1] - a[1]) * k / sub, 12), z)]
                for a, b in zip(pts, pts[1:] + pts[:1]) for k in range(sub)]
        for i in range(len(ring)):
            t = (c, ring[i], ring[(i + 1) % len(ring)])
            f.append(t if up else (t[0], t[2], t[1]))
    write_obj(out, "a %d-gon prism" % n, v, f)


def box(sub, out):
    v, f, vid = [], [], {}
    for P, U, W in (((0, 0, 0), (0, 1, 0), (1, 0, 0)), ((0, 0, 1), (1, 0, 0), (0, 1, 0)),
                    ((0, 0, 0), (1, 0, 0), (0, 0, 1)), ((0, 1, 0), (0, 0, 1), (1, 0, 0)),
                    ((0, 0, 0), (0, 0, 1), (0, 1, 0)), ((1, 0, 0), (0, 1, 0), (0, 0, 1))):
        quad_patch(v, f, vid, P, U, W, sub, sub)
    write_obj(out, "the unit cube, %d x %d squares per face" % (sub, sub), v, f)


def jitter(src, out, frac, seed=7):
    import random
    v, f = [], []
    for line in open(src):
        w = line.split()
        if w and w[0] == "v":
            v.append([float(x) for x in w[1:4]])
        elif w and w[0] == "f":
            f.append(tuple(int(x.split("/")[0]) - 1 for x in w[1:4]))
    edge = sum(math.dist(v[t[k]], v[t[(k + 1) % 3]]) for t in f for k in range(3)) / (3 * len(f))
    rng = random.Random(seed)
    w = [tuple(x + frac * edge * rng.uniform(-1, 1) for x in p) for p in v]
    write_obj(out, "%s with a jitter of %g mean edges" % (src, frac), w, f)


def _implicit_kinds():
    def blob(x, y, z):
        r = math.sqrt(x * x + y * y + z * z)
        return r - 1.0 - 0.25 * math.sin(5 * x) * math.sin(4 * y) * math.sin(3 * z + 1)

    def genus3(x, y, z):
        def torus(cx):
            return math.hypot(math.hypot(x - cx, y) - 1.0, z) - 0.35
        return min(torus(-1.7), torus(0.0), torus(1.7))

    def schwarz(x, y, z):
        return math.cos(x) + math.cos(y) + math.cos(z)

    def gyroid(x, y, z):
        g = math.sin(x) * math.cos(y) + math.sin(y) * math.cos(z) + math.sin(z) * math.cos(x)
        return max(g - 0.3, math.sqrt(x * x + y * y + z * z) - 5.0)

    def part(x, y, z):
        # a plate with a round hole, turned off the grid's axes: sharp CSG edges
        ca, sa, cb, sb = math.cos(0.35), math.sin(0.35), math.cos(0.2), math.sin(0.2)
        x, y = ca * x + sa * y, -sa * x + ca * y
        y, z = cb * y + sb * z, -sb * y + cb * z
        plate = max(abs(x) - 1.5, abs(y) - 1.0, abs(z) - 0.4)
        return max(plate, 0.5 - math.hypot(x, y))

    return {"blob": (blob, 1.6), "genus3": (genus3, 3.2), "schwarz": (schwarz, 4.7), "gyroid": (gyroid, 5.6),
            "part": (part, 2.0)}


def implicit(kind, n, out):
    """Marching tetrahedra (6 per grid cube) of f < 0 on [-L, L]^3, the
    vertices on the grid edges shared, each triangle's normal away from f < 0."""
    f, half = _implicit_kinds()[kind]
    d = 2.0 * half / n

    def P(i, j, k):
        return (-half + i * d, -half + j * d, -half + k * d)
    val = {}
    for i in range(n + 1):
        for j in range(n + 1):
            for k in range(n + 1):
                x = f(*P(i, j, k))
                val[(i, j, k)] = x if x != 0.0 else 1e-12
    v, vid, tris = [], {}, []

    def edge_vertex(a, b):
        key = (a, b) if a < b else (b, a)
        if key not in vid:
            t = val[a] / (val[a] - val[b])
            pa, pb = P(*a), P(*b)
            v.append(tuple(pa[c] + t * (pb[c] - pa[c]) for c in range(3)))
            vid[key] = len(v) - 1
        return vid[key]

    def oriented(t, inside):
        a, b, c = (v[i] for i in t)
        u = [b[q] - a[q] for q in range(3)]
        w = [c[q] - a[q] for q in range(3)]
        nr = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
        return (t[0], t[2], t[1]) if sum(nr[q] * (inside[q] - a[q]) for q in range(3)) > 0 else t
    cube = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    tets = [(0, 5, 1, 6), (0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6)]
    for i in range(n):
        for j in range(n):
            for k in range(n):
                cs = [(i + c[0], j + c[1], k + c[2]) for c in cube]
                for tt in tets:
                    g = [cs[q] for q in tt]
                    ins = [p for p in g if val[p] < 0]
                    outs = [p for p in g if val[p] >= 0]
                    if not ins or not outs:
                        continue
                    ip = P(*ins[0])
                    if len(ins) == 1 or len(outs) == 1:
                        one, rest = (ins[0], outs) if len(ins) == 1 else (outs[0], ins)
                        cand = [tuple(edge_vertex(one, r) for r in rest)]
                    else:
                        q = [edge_vertex(ins[0], outs[0]), edge_vertex(ins[0], outs[1]),
                             edge_vertex(ins[1], outs[1]), edge_vertex(ins[1], outs[0])]
                        cand = [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
                    tris += [oriented(t, ip) for t in cand if len(set(t)) == 3]
    write_obj(out, "marching tetrahedra of %s on a %d^3 grid" % (kind, n), v, tris)


if __name__ == "__main__":
    a = sys.argv
    if len(a) == 5 and a[1] == "holes":
        holes(int(a[2]), int(a[3]), a[4])
    elif len(a) == 5 and a[1] == "roundholes":
        round_holes(int(a[2]), int(a[3]), a[4])
    elif len(a) in (4, 5) and a[1] == "bumpy":
        bumpy(int(a[2]), a[3], noise=float(a[4]) if len(a) == 5 else 0.002)
    elif len(a) == 5 and a[1] == "implicit" and a[2] in _implicit_kinds():
        implicit(a[2], int(a[3]), a[4])
    elif len(a) == 4 and a[1] == "speck":
        speck(int(a[2]), a[3])
    elif len(a) == 6 and a[1] == "slab":
        slab(int(a[2]), int(a[3]), int(a[4]), a[5])
    elif len(a) == 5 and a[1] == "prism":
        prism(int(a[2]), int(a[3]), a[4])
    elif len(a) == 4 and a[1] == "box":
        box(int(a[2]), a[3])
    elif len(a) == 5 and a[1] == "jitter":
        jitter(a[2], a[3], float(a[4]))
    else:
        sys.exit(__doc__)
