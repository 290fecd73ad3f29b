#!/usr/bin/env bash
# cli_cross.sh: `glpgp solve --field cross` end to end: the stats JSON has the
# cross field's singularities (a disk: 4 of index +1/4, index sum = the
# Poincare-Hopf value 1; a square: none, sum 0), the VTK result carries
# cross_w and cross_index4 and reads back; `glpgp render --image-kind cross`
# draws it and `glpgp figure --cross` makes the Fig. 1 triptych (skipped
# without OpenImageIO), and render refuses a result without a cross field
# with one error line.
# Usage: bash cli_cross.sh <path-to-glpgp> <data-dir>
. "$(dirname "$0")/lib.sh" "$@"

run_ok "disk cross" solve shape:disk:3000 --field cross --backend reference -o d.vtk --stats d.json
python3 - d.json <<'PY' || fail "disk cross stats"
import json, sys
c = json.load(open(sys.argv[1]))["cross_field"]
assert c["singularities"] == 4, c["singularities"]
assert all(s["index"] == 0.25 for s in c["singular"]), c["singular"]
assert c["index_sum"] == 1.0 and c["index_expected"] == 1.0 and c["poincare_hopf"] is True
PY
grep -q "^SCALARS cross_w double 2" d.vtk || fail "d.vtk has no cross_w"
grep -q "^SCALARS cross_index4 int 1" d.vtk || fail "d.vtk has no cross_index4"

run_ok "square cross" solve shape:square:2000 --field cross --backend reference --stats s.json
python3 - s.json <<'PY' || fail "square cross stats"
import json, sys
c = json.load(open(sys.argv[1]))["cross_field"]
assert c["singularities"] == 0 and c["index_sum"] == 0 and c["poincare_hopf"] is True, c
PY

if "$GLPGP" render d.vtk --image-kind cross -o probe.png >/dev/null 2>probe.txt; then
    [ -s probe.png ] || fail "render --image-kind cross wrote nothing"
    run_ok "plain result" solve shape:square:500 --backend reference -o p.vtk
    run_fail "render cross of a result without one" 1 "no cross field" render p.vtk --image-kind cross -o p.png
    [ ! -e p.png ] || fail "p.png written"
    run_ok "figure --cross" figure shape:disk:2000 --cross --backend reference --image-size 200 -o fig1.png
    expect_out "cross field: 4 singularities \(index sum 1\)" "figure --cross"
    [ -s fig1.png ] || fail "figure --cross wrote nothing"
elif ! grep -qi "without OpenImageIO\|module" probe.txt; then
    fail "render --image-kind cross: $(cat probe.txt)"
fi
finish
