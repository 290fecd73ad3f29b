#!/usr/bin/env bash
# cli_surface.sh: surfaces end to end (issue 28): `glpgp generate sphere`
# writes a 3D OBJ that `solve` reads as a surface (the cross field by
# default; stats: chi, genus, loops, index sum = Poincare-Hopf; .vtu and
# .vtk with 3D points and field vectors, read back by `render`); a cube's
# eight corners; the same surface as PLY and OFF; bad 3D inputs (non-manifold
# edge, a lone degenerate face, Moebius strip) each one error line, exit 1,
# no output; what the reader repairs with a warning (a zero-area cap, a face
# oriented against its neighbours, two tetrahedra touching at a vertex or
# sharing an edge)
# solved with the repaired topology; --planar-face keeps a box STL's
# bottom; --quads on a surface writes an all-quad OBJ (issue 29; the
# details in cli_surfquads.sh), `figure --cross` on a surface draws the
# surface figure (input, texture, quads), `extract` of a surface's result
# the surface pipeline (cli_surfextract.sh: the same mesh); a surface picture (skipped
# without OpenImageIO).
# Usage: bash cli_surface.sh <path-to-glpgp> <data-dir>
. "$(dirname "$0")/lib.sh" "$@"

run_ok "generate sphere" generate sphere --vertices 6000 -o s.obj
grep -q '^v .* .* .*[1-9]' s.obj || fail "s.obj has no 3D vertices"
run_ok "solve sphere" solve s.obj --backend reference -o s.vtu --stats s.json
expect_out "surface +chi 2, genus 0, 0 boundary loop" "summary names the topology"
python3 - s.json <<'PY' || fail "sphere stats"
import json, sys
d = json.load(open(sys.argv[1]))
s = d["mesh"]["surface"]
assert s["euler_characteristic"] == 2 and s["genus"] == 0 and d["mesh"]["boundary_loops"] == 0, s
c = d["cross_field"]
assert d["field"] == "cross", d["field"]
assert c["index_sum"] == 2.0 and c["index_expected"] == 2.0 and c["poincare_hopf"] is True, c
assert c["singularities"] == 8 and all(x["index"] == 0.25 for x in c["singular"]), c["singular"]
assert all(abs(x["x"]**2 + x["y"]**2 + x["z"]**2 - 1) < 0.01 for x in c["singular"]), "singularities off the sphere"
assert d["zabs"]["u"]["median"] > 0.9, d["zabs"]
PY
run_ok "solve sphere vtk" solve s.obj --backend reference --method pgp -o s.vtk --quiet
grep -q '^VECTORS cross_dir double' s.vtk || fail "s.vtk has no cross_dir vectors"
awk '/^POINTS/{getline; if ($3 == 0) exit 1}' s.vtk || fail "s.vtk points are not 3D"

run_ok "cube" solve shape:cube:4000 --backend reference --stats c.json --quiet
python3 - c.json <<'PY' || fail "cube stats"
import json, sys
d = json.load(open(sys.argv[1]))
c = d["cross_field"]
assert d["mesh"]["surface"]["feature_edges"] > 0, d["mesh"]
assert c["singularities"] == 8 and c["index_sum"] == 2.0, c
for s in c["singular"]: # one at each corner
    assert all(abs(abs(v) - 0.5) < 0.1 for v in (s["x"], s["y"], s["z"])), s
PY

# the same surface as PLY and OFF
python3 - s.obj <<'PY' || fail "writing PLY/OFF"
import sys
v, f = [], []
for line in open(sys.argv[1]):
    w = line.split()
    if w and w[0] == "v": v.append(w[1:4])
    if w and w[0] == "f": f.append([int(x) - 1 for x in w[1:4]])
with open("s.ply", "w") as o:
    o.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty double x\nproperty double y\nproperty double z\n"
            "element face %d\nproperty list uchar int vertex_indices\nend_header\n" % (len(v), len(f)))
    for p in v: o.write(" ".join(p) + "\n")
    for t in f: o.write("3 %d %d %d\n" % tuple(t))
with open("s.off", "w") as o:
    o.write("OFF\n%d %d 0\n" % (len(v), len(f)))
    for p in v: o.write(" ".join(p) + "\n")
    for t in f: o.write("3 %d %d %d\n" % tuple(t))
PY
for e in ply off; do
    run_ok "solve s.$e" solve s.$e --backend reference --method pgp --quiet
    expect_out "surface +chi 2" "s.$e read as the sphere"
done

# bad 3D inputs: one line each, exit 1, no output
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0.5\nf 1 2 3\nf 2 1 4\nf 1 2 5\n' >in_1.obj
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv -1 0 0\nv 0 -1 0\nv 0 0 -1\n' >in_2.obj
printf 'f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\nf 1 5 6\nf 1 7 5\nf 5 7 6\nf 1 6 7\n' >>in_2.obj
printf 'v 0 0 0\nv 1 0 0.1\nv 0 1 0.2\nv 0.3 0.3 1\nf 1 3 2\nf 1 4 2\nf 2 3 4\nf 3 1 4\n' >in_3.obj
printf 'v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n' >in_4.obj
printf 'v 0 0 0\nv 1 1 1\nv 2 2 2\nv 0 1 0\nf 1 2 3\nf 1 4 2\n' >cap.obj
python3 - <<'PY' || fail "writing the Moebius strip"
import math
k = 8
with open("in_5.obj", "w") as o:
    for i in range(k):
        u = 2 * math.pi * i / k
        for w in (-0.3, 0.3):
            o.write("v %r %r %r\n" % ((1 + w * math.cos(u / 2)) * math.cos(u), (1 + w * math.cos(u / 2)) * math.sin(u),
                                      w * math.sin(u / 2)))
    for i in range(k):
        a, b = 2 * i + 1, 2 * i + 2
        c, d = 2 * ((i + 1) % k) + 1, 2 * ((i + 1) % k) + 2
        if i == k - 1: c, d = d, c
        o.write("f %d %d %d\nf %d %d %d\n" % (a, c, d, a, d, b))
PY
names=("" "non-manifold edge" "" "" "degenerate" "non-orientable")
for k in 1 4 5; do
    run 1 "bad surface $k" solve in_$k.obj --out o.vtu --stats o.json --quiet
    one_error_line "bad surface $k"
    expect_err "in_$k.obj" "bad surface $k names the file"
    expect_err "${names[$k]}" "bad surface $k says what"
    [ ! -e o.vtu ] && [ ! -e o.json ] || fail "bad surface $k left an output"
done
# repaired by the reader: two tetrahedra touching at a vertex (split: two
# closed components, chi 4); a tetrahedron with one face flipped (chi 2)
run_ok "pinched vertex" solve in_2.obj --backend reference --quads q2.obj
expect_err "in_2\.obj: 1 vertices where surfaces touch" "the pinched vertex is named"
expect_out "surface +chi 4, genus 0, 0 boundary loop\(s\), 2 component" "the pinched vertex split: two components"
expect_out "valid +yes" "the pinched input's quads are valid"
# two tetrahedra sharing an edge (a body turned half a turn about it): the
# edge separated, two closed components
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0\nv 0 0 -1\n' >edge2.obj
printf 'f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\nf 1 5 2\nf 1 2 6\nf 2 5 6\nf 1 6 5\n' >>edge2.obj
run_ok "shared edge" solve edge2.obj --backend reference --quads qe.obj
expect_err "edge2\.obj: 1 edges of four or more triangles" "the shared edge is named"
expect_out "surface +chi 4, genus 0, 0 boundary loop\(s\), 2 component" "the shared edge separated: two components"
expect_out "valid +yes" "the shared-edge input's quads are valid"
run_ok "zero-area cap" solve cap.obj --backend reference --method pgp
expect_err "cap\.obj: 1 triangles of zero area" "the zero-area triangle is named"
run_ok "flipped face" solve in_3.obj --backend reference --quads q3.obj
expect_err "in_3\.obj: 1 of 4 triangles were oriented against" "the flipped face is counted"
expect_out "surface +chi 2, genus 0" "the flipped tetrahedron is a sphere"
expect_out "valid +yes" "the flipped input's quads are valid"

# a closed box: a surface (12 triangles, too coarse for a default solve) or, --planar-face, its bottom
python3 - <<'PY' || fail "writing box.stl"
X = [(0,0,0),(2,0,0),(2,1,0),(0,1,0),(0,0,.5),(2,0,.5),(2,1,.5),(0,1,.5)]
F = [(0,2,1),(0,3,2),(4,5,6),(4,6,7),(0,1,5),(0,5,4),(1,2,6),(1,6,5),(2,3,7),(2,7,6),(3,0,4),(3,4,7)]
with open("box.stl", "w") as o:
    o.write("solid box\n")
    for f in F:
        o.write("facet normal 0 0 0\nouter loop\n")
        for k in f: o.write("vertex %g %g %g\n" % X[k])
        o.write("endloop\nendfacet\n")
    o.write("endsolid box\n")
PY
run_ok "box --planar-face" solve box.stl --planar-face --size 0.5 --backend reference
expect_err "largest face" "--planar-face warns"
expect_out "refined +4 -> [0-9]+ vertices, 2 -> " "--planar-face solves the bottom (2 triangles, refined)"
grep -q "^  surface " out.txt && fail "--planar-face solved the surface"

run_ok "surface --quads" solve s.obj --backend reference --quads q.obj --quiet
python3 - <<'PY' || fail "surface --quads: an all-quad OBJ in 3D"
f = [l.split() for l in open("q.obj")]
assert any(l[0] == "f" for l in f if l) and all(len(l) == 5 for l in f if l and l[0] == "f")
assert len({l[3] for l in f if l and l[0] == "v"}) > 2
PY
run_ok "extract a surface result" extract s.vtu --quads qx.obj
expect_out "surface quads +extraction" "extract runs the surface pipeline"
[ -s qx.obj ] || fail "extract a surface result: no quads written"

if "$GLPGP" render s.vtu -o probe.png >/dev/null 2>probe.txt; then
    run_ok "render a surface" render s.vtu -o s.png --image-size 300 --view 10,40
    [ -s s.png ] || fail "s.png not written"
    run_ok "figure --cross on a surface (as --surface)" figure s.obj --cross -o f.png --image-size 200
    [ -s f.png ] || fail "figure --cross on a surface: no picture"
    run 1 "render kind cross" render s.vtu --image-kind cross -o x.png
    one_error_line "render kind cross"
else
    echo "skipped pictures: $(head -c 200 probe.txt)"
fi
no_tmp "surfaces"
finish
