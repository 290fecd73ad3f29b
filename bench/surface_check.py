#!/usr/bin/env python3
"""bench/surface_check.py: the checks of a peer's quad mesh (OBJ) that need
no surface distance, as one row of bench/surface_compare.sh's table: all
quads, manifold edges, Euler characteristic and boundary loops against the
input's (OBJ), irregular interior vertices, scaled Jacobian in each face's
own (Newell) plane. Hausdorff: not measured ("-").
Usage: surface_check.py INPUT.obj QUADS.obj MODEL FACES TOOL SECONDS"""
import math
import sys
from collections import defaultdict


def read_obj(path):
    v, f = [], []
    for line in open(path):
        w = line.split()
        if not w:
            continue
        if w[0] == "v":
            v.append(tuple(float(x) for x in w[1:4]))
        elif w[0] == "f":
            f.append([int(x.split("/")[0]) - 1 for x in w[1:]])
    return v, f


def topo(v, f):
    edges = defaultdict(int)
    for face in f:
        for i in range(len(face)):
            a, b = face[i], face[(i + 1) % len(face)]
            edges[(min(a, b), max(a, b))] += 1
    used = {k for face in f for k in face}
    bnd = [e for e, c in edges.items() if c == 1]
    parent = {}

    def find(x):
        while parent.get(x, x) != x:
            x = parent[x]
        return x
    for a, b in bnd:
        parent[find(a)] = find(b)
    loops = len({find(a) for e in bnd for a in e})
    return len(used) - len(edges) + len(f), loops, all(c <= 2 for c in edges.values()), edges, {a for e in bnd for a in e}


def sj(v, face):
    n = len(face)
    N = [0.0, 0.0, 0.0]
    for i in range(n):
        a, b = v[face[i]], v[face[(i + 1) % n]]
        N[0] += (a[1] - b[1]) * (a[2] + b[2]); N[1] += (a[2] - b[2]) * (a[0] + b[0]); N[2] += (a[0] - b[0]) * (a[1] + b[1])
    nn = math.sqrt(sum(x * x for x in N)) or 1e-300
    worst = 1.0
    for i in range(n):
        p, a, b = v[face[i]], v[face[(i + 1) % n]], v[face[(i - 1) % n]]
        e1 = [a[k] - p[k] for k in range(3)]; e2 = [b[k] - p[k] for k in range(3)]
        x = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        l = math.sqrt(sum(t * t for t in e1) * sum(t * t for t in e2)) or 1e-300
        worst = min(worst, sum(x[k] * N[k] for k in range(3)) / (nn * l))
    return worst


def main():
    inp, quads, model, n, tool, secs = sys.argv[1:]
    try:
        vi, fi = read_obj(inp)
        v, f = read_obj(quads)
    except OSError:
        print("| %s | %s | %s | no output |" % (model, n, tool)); return
    if not f:
        print("| %s | %s | %s | no faces |" % (model, n, tool)); return
    e_in, l_in, _, _, _ = topo(vi, fi)
    e, l, manifold, edges, bverts = topo(v, f)
    allq = all(len(x) == 4 for x in f)
    val = defaultdict(int)
    for a, b in edges:
        val[a] += 1; val[b] += 1
    inner = [k for k in val if k not in bverts]
    irr = sum(1 for k in inner if val[k] != 4)
    sjs = [sj(v, x) for x in f if len(x) == 4] or [0.0]
    print("| %s | %s | %s | %d | - / %s / %s | %s | %d (%.1f%%) | %.3f | %.3f | - | - | %.1f |" % (
        model, n, tool, sum(1 for x in f if len(x) == 4), "yes" if manifold else "no", "yes" if allq else "no",
        "yes" if (e, l) == (e_in, l_in) else "no (%d, %d of %d, %d)" % (e, l, e_in, l_in),
        irr, 100.0 * irr / max(len(inner), 1), min(sjs), sum(sjs) / len(sjs), float(secs)))


if __name__ == "__main__":
    main()
