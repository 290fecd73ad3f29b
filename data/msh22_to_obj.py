#!/usr/bin/env python3
"""msh22_to_obj.py: convert the 3-node triangles of a Gmsh MSH 2.2 ASCII file
to a Wavefront OBJ (v x y z / f a b c), dropping nodes no triangle uses.
Usage: python3 msh22_to_obj.py in.msh out.obj"""
import sys


def main(src, dst):
    lines = open(src).read().split("\n")
    i = 0
    nodes, tris = {}, []
    while i < len(lines):
        s = lines[i].strip()
        if s == "$Nodes":
            n = int(lines[i + 1])
            for k in range(n):
                t = lines[i + 2 + k].split()
                nodes[int(t[0])] = t[1:4]
            i += n + 2
        elif s == "$Elements":
            n = int(lines[i + 1])
            for k in range(n):
                t = [int(x) for x in lines[i + 2 + k].split()]
                if t[1] == 2:
                    tris.append(t[3 + t[2]:6 + t[2]])
            i += n + 2
        else:
            i += 1
    used = sorted({v for t in tris for v in t})
    index = {tag: k + 1 for k, tag in enumerate(used)}
    with open(dst, "w") as f:
        f.write("# %s: %d vertices, %d triangles (from %s)\n" % (dst.split("/")[-1], len(used), len(tris), src.split("/")[-1]))
        for tag in used:
            f.write("v %s\n" % " ".join(nodes[tag]))
        for t in tris:
            f.write("f %d %d %d\n" % tuple(index[v] for v in t))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
