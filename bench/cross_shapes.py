#!/usr/bin/env python3
"""bench/cross_shapes.py: writes the curved test domains of issue 14 as
Triangle .poly files for `glpgp mesh X.poly -o X.msh` (host/README.md,
"Cross field"): flower.poly, a 4 x 4 square with the hole
r = 0.8 (1 + 0.25 cos 5 phi), and airfoil.poly, a NACA 0012 (chord 1) in a
3 x 2 box; boundary points every `edge` (default 0.04).
Usage: python3 bench/cross_shapes.py OUTDIR [edge]"""
import math, os, sys


def square(x0, y0, x1, y1, edge):
    """Counter-clockwise points on the rectangle's sides, spacing <= edge."""
    pts = []
    for (ax, ay), (bx, by) in (((x0, y0), (x1, y0)), ((x1, y0), (x1, y1)), ((x1, y1), (x0, y1)), ((x0, y1), (x0, y0))):
        n = max(1, math.ceil(math.hypot(bx - ax, by - ay) / edge))
        pts += [(ax + (bx - ax) * k / n, ay + (by - ay) * k / n) for k in range(n)]
    return pts


def resample(curve, edge):
    """Closed polyline curve (dense) resampled at arc-length spacing ~ edge."""
    seg = [math.dist(curve[i], curve[(i + 1) % len(curve)]) for i in range(len(curve))]
    total = sum(seg)
    n = max(8, math.ceil(total / edge))
    out, acc, i = [], 0.0, 0
    for k in range(n):
        s = total * k / n
        while acc + seg[i] < s:
            acc += seg[i]
            i += 1
        t = (s - acc) / seg[i]
        a, b = curve[i], curve[(i + 1) % len(curve)]
        out.append((a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])))
    return out


def write_poly(path, loops, holes, edge):
    """Triangle .poly: loops of points (closed), hole seeds; size attribute = edge."""
    pts = [p for l in loops for p in l]
    with open(path, "w") as f:
        f.write("%d 2 1 0\n" % len(pts))
        for i, (x, y) in enumerate(pts):
            f.write("%d %.9f %.9f %g\n" % (i + 1, x, y, edge))
        f.write("%d 0\n" % len(pts))
        base, k = 0, 1
        for l in loops:
            for i in range(len(l)):
                f.write("%d %d %d\n" % (k, base + i + 1, base + (i + 1) % len(l) + 1))
                k += 1
            base += len(l)
        f.write("%d\n" % len(holes))
        for i, (x, y) in enumerate(holes):
            f.write("%d %.9f %.9f\n" % (i + 1, x, y))


def main():
    out = sys.argv[1]
    edge = float(sys.argv[2]) if len(sys.argv) > 2 else 0.04
    os.makedirs(out, exist_ok=True)
    # flower hole: r(phi) = 0.8 (1 + 0.25 cos 5 phi), centered in [-2, 2]^2
    fl = [(0.8 * (1 + 0.25 * math.cos(5 * p)) * math.cos(p), 0.8 * (1 + 0.25 * math.cos(5 * p)) * math.sin(p))
          for p in (2 * math.pi * k / 4000 for k in range(4000))]
    write_poly(os.path.join(out, "flower.poly"), [square(-2, -2, 2, 2, edge), resample(fl, edge)], [(0.0, 0.0)], edge)
    # NACA 0012: y = +-0.6 (0.2969 sqrt x - 0.126 x - 0.3516 x^2 + 0.2843 x^3 - 0.1036 x^4), x in [0, 1]
    t = lambda x: 0.6 * (0.2969 * math.sqrt(x) - 0.126 * x - 0.3516 * x * x + 0.2843 * x ** 3 - 0.1036 * x ** 4)
    xs = [0.5 * (1 - math.cos(math.pi * k / 2000)) for k in range(2001)]  # clustered at both ends
    upper = [(x, t(x)) for x in reversed(xs)]          # trailing edge -> leading edge
    lower = [(x, -t(x)) for x in xs[1:-1]]             # leading edge -> trailing edge
    foil = [(x - 0.5, y) for x, y in upper + lower]
    write_poly(os.path.join(out, "airfoil.poly"), [square(-1.5, -1, 1.5, 1, edge), resample(foil, edge / 2)],
               [(0.0, 0.0)], edge)


if __name__ == "__main__":
    main()
