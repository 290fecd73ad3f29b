"""examples/python/meshio_file.py: a mesh file read with meshio (any format
meshio reads: Gmsh .msh, .vtu, .obj, .ply, ...), solved, and the result and
its quad mesh written back with meshio.

    python3 examples/python/meshio_file.py INPUT [--size H] [-o result.vtu] [--quads quads.vtu]

Without INPUT a Gmsh file of a disk is made first (glpgp.shape(...).write).
"""
import argparse

import meshio

import glpgp


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("input", nargs="?", default=None)
    ap.add_argument("--size", type=float, default=None)
    ap.add_argument("-o", "--out", default="result.vtu")
    ap.add_argument("--quads", default="quads.vtu")
    args = ap.parse_args()
    path = args.input
    if path is None:
        path = "disk.msh"
        glpgp.shape("disk", 5000).write(path)
    m = meshio.read(path)
    print("meshio:", m)
    mesh = glpgp.Mesh.from_meshio(m, name=path)
    r = glpgp.solve(mesh, size=args.size)
    print(r)
    meshio.write(args.out, r.to_meshio())
    q = r.quads()
    meshio.write(args.quads, q.to_meshio())
    print("wrote", args.out, "and", args.quads, "(%d quads, valid: %s)" % (q.report["faces"], q.valid))


if __name__ == "__main__":
    main()
