#!/usr/bin/env bash
# cli_crosscoupled.sh: u and v coupled across the cross field's cuts (issue 14,
# item 3; --cross-coupling, solver/coupled.c), on a disk at h = 0.1:
#  - `--field cross` (coupling auto) solves them coupled ("coupled": true in
#    the stats, one Newton count in the summary), converges, and its quads
#    are valid and all quads, with an interior vertex of valence 3 within
#    h of each of the 4 cross-field singularities;
#  - against `--field boundary` at the same size (the default `--cross-size
#    auto`, issue 14's target): fewer irregular vertices per 100 quads and a
#    higher minimum scaled Jacobian; the irregular count of `--cross-coupling
#    off` is printed, not asserted;
#  - `--cross-coupling off` solves them apart ("coupled": false), as before;
#  - `extract` of the saved coupled result reads its matching back (the
#    cross_coupled cell array) and gives the same quad mesh counts;
#  - `--cross-size on` (disk, h = 0.15): valid, at most 8 irregular interior
#    vertices, the 4 singularities each with one, min scaled Jacobian >= 0.7;
#  - plain `--field cross` (`--cross-size auto`) at the disk's default size
#    (shape:disk:8000, the singularities half a period from the boundary:
#    their pentagons close as three quads around one valence-3 vertex,
#    quads/close.c): valid, all quads, at most 4 irregular vertices, none
#    away from the singularities, and against `--field boundary` at the same
#    size fewer irregular vertices and a higher minimum scaled Jacobian
#    (`--cross-size off` gives 20 there, 16 of them dislocations);
#  - OpenCL (when a device is there): the same coupled solve, the same
#    Newton steps and frame windings as the reference.
# Usage: bash cli_crosscoupled.sh <path-to-glpgp> <data-dir>
. "$(dirname "$0")/lib.sh" "$@"

run_ok "coupled disk" solve shape:disk:16000 --size 0.1 --field cross --backend reference \
    --quads c.obj --stats c.json -o c.vtk
expect_out "newton [0-9]+ \(u and v coupled" "coupled summary line"
run_ok "boundary disk" solve shape:disk:16000 --size 0.1 --field boundary --backend reference --quads b.obj --stats b.json
run_ok "uncoupled disk" solve shape:disk:16000 --size 0.1 --field cross --cross-coupling off \
    --backend reference --quads o.obj --stats o.json
expect_out "newton [0-9]+ \(u [0-9]+, v [0-9]+\)" "uncoupled summary line"
python3 - c.json b.json o.json c.obj <<'PY' || fail "coupled disk report"
import json, math, sys
c, b, o = (json.load(open(p)) for p in sys.argv[1:4])
cf = c["cross_field"]
assert cf["coupled"] is True and o["cross_field"]["coupled"] is False, (cf["coupled"], o["cross_field"]["coupled"])
assert cf["singularities"] == 4 and cf["poincare_hopf"], cf
assert c["converged"]["all"] is True, c["converged"]
q, qb = c["quads"], b["quads"]
assert q["valid"] is True and q["quads"] == q["faces"] and q["other_faces"] == 0, q
iv, ivb = q["irregular_vertices"]["interior"], qb["irregular_vertices"]["interior"]
ivo = o["quads"]["irregular_vertices"]["interior"]
sj, sjb = q["scaled_jacobian"]["min"], qb["scaled_jacobian"]["min"]
assert sj > sjb, ("min scaled Jacobian, coupled vs boundary", sj, sjb)
ivt, ivbt = q["irregular_vertices"]["total"], qb["irregular_vertices"]["total"]
assert ivt / q["quads"] < ivbt / qb["quads"], ("irregular per quad, cross vs boundary", ivt, q["quads"], ivbt, qb["quads"])
# valence of every interior vertex of the OBJ quads
v, f = [], []
for line in open(sys.argv[4]):
    p = line.split()
    if p and p[0] == "v":
        v.append((float(p[1]), float(p[2])))
    elif p and p[0] == "f":
        f.append([int(t.split("/")[0]) - 1 for t in p[1:]])
val, edges = {}, {}
for fa in f:
    for k, i in enumerate(fa):
        val[i] = val.get(i, 0) + 1
        e = tuple(sorted((i, fa[(k + 1) % len(fa)])))
        edges[e] = edges.get(e, 0) + 1
bnd = {i for e, n in edges.items() if n == 1 for i in e}
h = c["size"]
for s in cf["singular"]:
    near = [i for i in val if i not in bnd and math.hypot(v[i][0] - s["x"], v[i][1] - s["y"]) <= h]
    assert any(val[i] == 3 for i in near), ("no valence-3 vertex within h of", s, [val[i] for i in near])
print("coupled: irregular interior %d (uncoupled %d, boundary %d), min SJ %.3f (boundary %.3f)" % (iv, ivo, ivb, sj, sjb))
PY

# the saved coupled result: extract reads the matching back
run_ok "extract coupled" extract c.vtk --quads e.obj --stats e.json
python3 - c.json e.json <<'PY' || fail "extract of the coupled result differs"
import json, sys
a = json.load(open(sys.argv[1]))["quads"]
b = json.load(open(sys.argv[2]))["quads"]
for k in ("faces", "quads", "vertices"):
    assert a[k] == b[k], (k, a[k], b[k])
assert a["irregular_vertices"] == b["irregular_vertices"], (a["irregular_vertices"], b["irregular_vertices"])
PY
grep -q "cross_coupled" c.vtk || fail "c.vtk has no cross_coupled array"

# --cross-size on: the cross field's conformal size removes the dislocations
# around the singularities: the four valence-3 vertices and (almost) nothing else
run_ok "coupled disk, cross size" solve shape:disk:20000 --size 0.15 --field cross --cross-size on \
    --backend reference --quads s.obj --stats s.json
python3 - s.json <<'PY' || fail "cross-size disk report"
import json, sys
d = json.load(open(sys.argv[1]))
q = d["quads"]
assert d["cross_field"]["coupled"] is True and d["cross_field"]["singularities"] == 4
assert q["valid"] is True and q["quads"] == q["faces"], q
iv = q["irregular_vertices"]
assert iv["interior"] <= 8 and iv["interior_near_cross"] >= 4, iv
assert q["cross_singularities"]["with_irregular_vertex"] == 4, q["cross_singularities"]
assert q["scaled_jacobian"]["min"] >= 0.7, q["scaled_jacobian"]
PY

# the disk at its default size: the ideal cross mesh (a valence-3 vertex at
# each singularity, nothing else) with the default --cross-size auto, better
# than the boundary field's
run_ok "default-size disk, cross" solve shape:disk:8000 --field cross \
    --backend reference --quads d.obj --stats d.json
run_ok "default-size disk, boundary" solve shape:disk:8000 --field boundary --backend reference --quads db.obj --stats db.json
python3 - d.json db.json <<'PY' || fail "default-size disk: cross vs boundary"
import json, sys
d, b = (json.load(open(p)) for p in sys.argv[1:3])
assert d["options"]["cross_size"] == "auto", d["options"]
q, qb = d["quads"], b["quads"]
assert q["valid"] is True and q["quads"] == q["faces"] and q["other_faces"] == 0, q
iv, ivb = q["irregular_vertices"], qb["irregular_vertices"]
assert iv["total"] <= 4 and iv["interior_far_cross"] == 0, iv
assert q["cross_singularities"]["with_irregular_vertex"] == 4, q["cross_singularities"]
assert qb["valid"] is True, qb["invalid_reasons"]
assert 100.0 * iv["total"] / q["quads"] < 100.0 * ivb["total"] / qb["quads"], (iv, q["quads"], ivb, qb["quads"])
assert q["scaled_jacobian"]["min"] > qb["scaled_jacobian"]["min"], (q["scaled_jacobian"], qb["scaled_jacobian"])
PY

# OpenCL: the same coupled solve (kernels/backend_coupled.cl), the same Newton count
if "$GLPGP" devices >/dev/null 2>&1 && "$GLPGP" devices 2>/dev/null | grep -qi "device"; then
    run_ok "opencl coupled" solve shape:disk:2000 --field cross --backend opencl --stats k.json
    run_ok "reference coupled" solve shape:disk:2000 --field cross --backend reference --stats r.json
    python3 - k.json r.json <<'PY' || fail "opencl coupled solve"
import json, sys
k, r = (json.load(open(p)) for p in sys.argv[1:3])
assert k["cross_field"]["coupled"] is True and r["cross_field"]["coupled"] is True
assert k["newton_iterations"] == r["newton_iterations"], (k["newton_iterations"], r["newton_iterations"])
assert k["singularities"] == r["singularities"], (k["singularities"], r["singularities"])
PY
fi
finish
