"""examples/python/quads_picture.py: a domain -> GL-PGP solve -> quad mesh ->
a matplotlib picture (the parametrization's grid lines under the quads, the
singularities marked).

    python3 examples/python/quads_picture.py [--shape disk] [--vertices 20000] [--size H] [-o quads.png]

Without matplotlib the picture is the library's own rendering (glpgp.render).
"""
import argparse
import logging

import numpy as np

import glpgp


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shape", default="disk", help="square, disk, annulus, lshape, or a mesh file")
    ap.add_argument("--vertices", type=int, default=20000)
    ap.add_argument("--size", type=float, default=None, help="target quad size h (default: the library's)")
    ap.add_argument("-o", "--out", default="quads.png")
    args = ap.parse_args()
    logging.basicConfig(level=logging.INFO, format="%(name)s: %(message)s")
    logging.getLogger("glpgp").setLevel(logging.WARNING)  # INFO shows every Newton step

    mesh = glpgp.shape(args.shape, args.vertices) if ":" not in args.shape and "." not in args.shape \
        else glpgp.read(args.shape)
    r = glpgp.solve(mesh, size=args.size)
    q = r.quads()
    print(r)
    print(q)
    print("singularities:", r.stats["singularities"], " irregular vertices:", q.report["irregular_vertices"]["total"])

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.collections import PolyCollection
        from matplotlib.tri import Triangulation
    except ImportError:
        glpgp.render(r, args.out, size=1024)
        print("matplotlib is not installed: wrote glpgp.render's picture to", args.out)
        return
    m = r.mesh
    tri = Triangulation(m.vertices[:, 0], m.vertices[:, 1], m.triangles)
    fig, ax = plt.subplots(figsize=(8, 8))
    # theta as a periodic colour under the quads
    ax.tripcolor(tri, r.theta_u, shading="gouraud", cmap="twilight", alpha=0.5)
    faces = [q.vertices[f] for f in (q.faces if isinstance(q.faces, list) else list(q.faces))]
    ax.add_collection(PolyCollection(faces, facecolors="none", edgecolors="k", linewidths=0.6))
    for k, c in (("u", "red"), ("v", "blue")):
        s = getattr(r, "singular_" + k)
        ax.plot(s["x"], s["y"], "o", color=c, ms=4, label="singular %s (%d)" % (k, len(s)))
    ax.set_aspect("equal")
    ax.set_title("%s: %d quads, h = %.3g, %d irregular vertices" % (
        m.source, q.report["faces"], r.size, q.report["irregular_vertices"]["total"]))
    ax.legend(loc="lower right")
    fig.savefig(args.out, dpi=120)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
