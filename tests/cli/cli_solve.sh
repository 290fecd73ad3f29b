#!/usr/bin/env bash
# cli_solve.sh: end-to-end runs of the glpgp CLI on small generated domains.
# Usage: bash cli_solve.sh <path-to-glpgp> <data-dir>
# Checks: `generate` writes .obj/.msh and reports the counts; `solve` with the
# reference backend writes a VTK (all arrays, right counts), a textured OBJ
# (one vt per corner) and a statistics JSON that parses (python3, when
# available) with consistent keys; overwriting existing outputs; built-in
# shape: inputs; --oscillators concurrent and sequential write the same file
# and say which ran; an STL-style fan of slivers (a warning naming `glpgp
# mesh`, the default h), unwelded (welded, same h), remeshed by `glpgp mesh`
# and by `solve --remesh` (no slivers); at
# most one warning line with --backend auto; no temporary files left behind.
. "$(dirname "$0")/lib.sh" "$@"

ok_run() { run_ok "$@"; }
have_python=0
if command -v python3 >/dev/null 2>&1; then have_python=1; fi
json_ok() { # FILE NV: parses, has the documented keys, vertices == NV
    [ "$have_python" -eq 1 ] || { echo "note: python3 not found, JSON parse check skipped"; return 0; }
    python3 - "$1" "$2" <<'EOF' || fail "JSON $1 is invalid or incomplete"
import json, sys
d = json.load(open(sys.argv[1]))
nv = int(sys.argv[2])
need = ["vertices", "triangles", "size", "method", "energy", "newton", "backend", "field",
        "singularities", "zabs", "newton_iterations", "cg_iterations", "eps_schedule",
        "dirichlet", "seconds", "input", "mesh"]
missing = [k for k in need if k not in d]
assert not missing, "missing keys %s" % missing
assert d["vertices"] == nv, (d["vertices"], nv)
for o in ("u", "v"):
    assert set(d["singularities"][o]) >= {"plus", "minus"}
    assert set(d["zabs"][o]) >= {"min", "p10", "median"}
    assert isinstance(d["eps_schedule"][o], list)
assert set(d["seconds"]) >= {"setup", "field", "u", "v", "total"}
assert set(d["mesh"]) >= {"area", "mean_edge", "boundary_loops"}
assert d["newton_iterations"]["total"] == d["newton_iterations"]["u"] + d["newton_iterations"]["v"]
dc = d["device_calls"]
if d["backend"] == "reference":  # the drivers read scalars; no kernels
    assert dc["kernel_launches"] == 0 and dc["host_round_trips"] > 0, dc
    assert d["device"] is None, d["device"]
else:
    assert dc["kernel_launches"] > dc["host_round_trips"] > 0, dc
    assert d["device"].startswith("device "), d["device"]
EOF
}

# ---- generate -------------------------------------------------------------
ok_run "generate sq.obj" generate square --vertices 2000 -o sq.obj
[ -s sq.obj ] || fail "generate did not write sq.obj"
grep -qE "[0-9]+ vertices, [0-9]+ triangles" out.txt || fail "generate prints no counts"
NV=$(grep -c '^v ' sq.obj)
NT=$(grep -c '^f ' sq.obj)
[ "$NV" -ge 1500 ] && [ "$NV" -le 2600 ] || fail "sq.obj has $NV vertices, expected about 2000"

# ---- solve -> VTK + JSON --------------------------------------------------
ok_run "solve -> vtk" solve sq.obj --size 0.25 --backend reference --out r.vtk --stats r.json --quiet
[ -s r.vtk ] || fail "r.vtk missing"
[ -s r.json ] || fail "r.json missing"
[ ! -s err.txt ] || fail "--quiet run wrote to stderr: $(head -c 300 err.txt)"
grep -qi "singular" out.txt || fail "summary does not mention singularities"
if [ -s r.vtk ]; then
    head -1 r.vtk | grep -q "^# vtk DataFile" || fail "r.vtk: bad header"
    grep -qx "POINTS $NV double" r.vtk || fail "r.vtk: POINTS $NV missing"
    grep -qx "CELLS $NT $((4 * NT))" r.vtk || fail "r.vtk: CELLS $NT missing"
    grep -qx "POINT_DATA $NV" r.vtk || fail "r.vtk: POINT_DATA missing"
    grep -qx "CELL_DATA $NT" r.vtk || fail "r.vtk: CELL_DATA missing"
    for a in "SCALARS z_u double 2" "SCALARS z_v double 2" "SCALARS theta_u double 1" \
        "SCALARS theta_v double 1" "SCALARS zabs_u double 1" "SCALARS zabs_v double 1" \
        "VECTORS field_u double" "SCALARS singular_u int 1" "SCALARS singular_v int 1"; do
        grep -qx "$a" r.vtk || fail "r.vtk: array '$a' missing"
    done
    # theta values in [0, 1)
    awk '/^SCALARS theta_/{on=1; getline; next} /^(SCALARS|VECTORS|CELL_DATA)/{on=0}
         on && ($1 < 0 || $1 >= 1) {bad++} END {exit bad > 0}' r.vtk ||
        fail "r.vtk: theta outside [0, 1)"
fi
json_ok r.json "$NV"
no_tmp "solve -> vtk"

# ---- solve -> OBJ, overwriting the existing JSON --------------------------
ok_run "solve -> obj" solve sq.obj --size 0.25 --backend reference --out r.obj --stats r.json --quiet
[ -s r.obj ] || fail "r.obj missing"
if [ -s r.obj ]; then
    nvo=$(grep -c '^v ' r.obj)
    nvt=$(grep -c '^vt ' r.obj)
    nf=$(grep -c '^f ' r.obj)
    [ "$nvo" -eq "$NV" ] || fail "r.obj: $nvo vertices, expected $NV"
    [ "$nf" -eq "$NT" ] || fail "r.obj: $nf faces, expected $NT"
    [ "$nvt" -eq $((3 * NT)) ] || fail "r.obj: $nvt texture coordinates, expected $((3 * NT))"
    grep -qE '^f [0-9]+/[0-9]+ [0-9]+/[0-9]+ [0-9]+/[0-9]+$' r.obj || fail "r.obj: bad face lines"
fi
json_ok r.json "$NV"
grep -q '"output": "r.obj"' r.json || fail "r.json was not overwritten by the second run"
no_tmp "solve -> obj"

# ---- .msh round trip and a built-in shape with PGP -------------------------
ok_run "generate disk.msh" generate disk --vertices 1500 -o disk.msh
[ -s disk.msh ] || fail "generate did not write disk.msh"
ok_run "solve disk.msh" solve disk.msh --size 0.4 --backend reference --method pgp --out d.vtk --quiet
[ -s d.vtk ] || fail "d.vtk missing"
ok_run "solve shape:annulus" solve shape:annulus:1500 --size 0.4 --backend reference \
    --energy transport --stats a.json --quiet
json_ok a.json "$(grep -o '"vertices": [0-9]*' a.json | grep -o '[0-9]*$')"
grep -q '"energy": "transport"' a.json || fail "a.json does not record --energy transport"
grep -q '"boundary_loops": 2' a.json || fail "a.json: annulus should have 2 boundary loops"

# ---- an OpenCL run counts its kernel launches --------------------------------
if "$GLPGP" devices 2>/dev/null | grep -q "fp64 yes"; then
    ok_run "solve opencl stats" solve shape:disk:1500 --size 0.4 --backend opencl --stats o.json --quiet
    json_ok o.json "$(grep -o '"vertices": [0-9]*' o.json | grep -o '[0-9]*$')"
    # `devices` marks one default, and a solve without --device / GLPGP_DEVICE uses it
    "$GLPGP" devices >dev.txt 2>&1
    [ "$(grep -c '(default)$' dev.txt)" -eq 1 ] || fail "devices does not mark exactly one default: $(cat dev.txt)"
    def=$(grep '(default)$' dev.txt | grep -oE 'device [0-9]+' | grep -oE '[0-9]+')
    (unset GLPGP_DEVICE; "$GLPGP" solve shape:disk:500 --size 0.4 --backend opencl --verbose >/dev/null 2>dv.txt)
    grep -q "OpenCL device $def:" dv.txt || fail "solve did not use the default device $def: $(grep -i 'opencl device' dv.txt)"
    # the summary names that device in full (names have parentheses of their own: "Intel(R)")
    name=$(grep '(default)$' dev.txt | sed -e 's/^  device [0-9]*: //' -e 's/ (default)$//')
    (unset GLPGP_DEVICE; "$GLPGP" solve shape:disk:500 --size 0.4 --backend opencl --quiet >sum.txt 2>&1)
    grep -qF "backend opencl (device $def: $name)" sum.txt || fail "summary does not name the device: $(head -1 sum.txt)"
else
    echo "note: no OpenCL fp64 device, the OpenCL stats check skipped"
fi

# ---- --oscillators: u and v at the same time give the same result -------------
for be in reference opencl; do
    if [ "$be" = opencl ] && ! "$GLPGP" devices 2>/dev/null | grep -q "fp64 yes"; then continue; fi
    for m in concurrent sequential; do
        ok_run "solve --oscillators $m ($be)" solve shape:disk:3000 --backend "$be" --oscillators "$m" \
            --out "osc_$m.vtu" --stats "osc_$m.json"
        cp out.txt "osc_$m.txt"
    done
    cmp -s osc_concurrent.vtu osc_sequential.vtu || fail "$be: --oscillators concurrent and sequential results differ"
    grep -q "u and v concurrently" osc_concurrent.txt || fail "$be: the summary does not say u and v ran concurrently"
    ! grep -q "concurrently" osc_sequential.txt || fail "$be: a sequential run says concurrently"
    grep -q '"oscillators": "concurrent"' osc_concurrent.json || fail "$be: stats do not record the concurrent run"
    grep -q '"oscillators": "sequential"' osc_sequential.json || fail "$be: stats do not record the sequential run"
done
run_fail "--oscillators foo" 2 "oscillators" solve shape:disk:500 --oscillators foo

# ---- CAD exports: an STL-style fan of slivers, unwelded -------------------------
# a 48-gon of radius 1 fanned from its first corner (every triangle a sliver,
# no interior vertex): solve warns and names the remedy, takes h = diameter /
# 20 (not 10 of its long mean edges, beyond the domain) and refines for it
awk 'BEGIN { n = 48; pi = atan2(0, -1);
             for (i = 0; i < n; i++) printf "v %.17g %.17g 0\n", cos(2 * pi * i / n), sin(2 * pi * i / n);
             for (i = 2; i < n; i++) printf "f 1 %d %d\n", i, i + 1 }' >fan.obj
ok_run "solve fan of slivers" solve fan.obj --backend reference --newton-max 5
expect_err "warning: .*46 of 46 triangles have an angle below 5 degrees.*--remesh, or glpgp mesh fan.obj -o" "solve fan: sliver warning"
expect_out "h = 0\.1414" "solve fan: default h = diameter / 20"
# the same fan with a vertex per triangle: welded (one warning), same mesh
awk '/^v/ { v[++n] = $0 } /^f/ { print v[$2]; print v[$3]; print v[$4]; k++; f[k] = sprintf("f %d %d %d", 3*k-2, 3*k-1, 3*k) }
     END { for (i = 1; i <= k; i++) print f[i] }' fan.obj >soup.obj
ok_run "solve unwelded fan" solve soup.obj --backend reference --newton-max 5
expect_err "warning: soup.obj: 90 vertices repeat the coordinates .* 46 pieces -> 1" "solve soup: welded"
expect_out "h = 0\.1414" "solve soup: the welded fan's h"
if "$GLPGP" mesh fan.obj -o fan_re.msh --size 0.3 --quiet 2>mesh_err.txt; then
    ok_run "solve remeshed fan" solve fan_re.msh --backend reference --size 0.3 --newton-max 5
    ! grep -q "below 5 degrees" err.txt || fail "the remeshed fan still has slivers"
    ok_run "solve --remesh fan" solve fan.obj --remesh --backend reference --size 0.3 --newton-max 5
    expect_err "fan.obj: remeshed -> [0-9]+ vertices" "solve --remesh: says it remeshed"
    ! grep -q "below 5 degrees" err.txt || fail "solve --remesh: still slivers"
else
    grep -q "built without Gmsh" mesh_err.txt || fail "mesh fan.obj failed: $(head -c 300 mesh_err.txt)"
    echo "note: built without Gmsh: the remesh check skipped"
fi

# ---- backend auto: at most one warning line --------------------------------
ok_run "solve --backend auto" solve shape:square:500 --size 0.3 --backend auto --quiet
nw=$(grep -ci "warning" err.txt)
[ "$nw" -le 1 ] || fail "--backend auto printed $nw warning lines"
no_tmp "end"

finish
