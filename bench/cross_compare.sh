#!/usr/bin/env bash
# bench/cross_compare.sh: --field boundary against --field cross (coupled),
# with --cross-size off, on and auto (the default), at the same --size, on the curved domains
# of issue 14 and the bundled meshes; one markdown table on stdout
# (bench/results/crossreg.md). Counts are deterministic; no times.
# Usage: bash bench/cross_compare.sh path/to/glpgp SHAPES_DIR
#   SHAPES_DIR: flower.msh and airfoil.msh (bench/cross_shapes.py, then
#   glpgp mesh X.poly -o X.msh); rows whose file is missing are skipped.
set -u
G=${1:?glpgp}; S=${2:?shapes dir}; D=$(dirname "$0")/../data
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
echo "| input | size | field | quads | valid | irregular (/100 quads) | interior near / far from cross singularities | min SJ |"
echo "|---|---|---|---|---|---|---|---|"
row() { # input size-args label
    local in=$1 sz=$2
    for f in "boundary" "cross --cross-size off" "cross --cross-size on" "cross"; do
        # shellcheck disable=SC2086
        if ! "$G" solve "$in" $sz --field $f --backend reference --quads "$T/q.obj" --stats "$T/s.json" \
            --quiet >/dev/null 2>"$T/err"; then
            echo "| $in | $sz | $f | failed: $(tail -1 "$T/err") | | | | |"; continue
        fi
        python3 - "$T/s.json" "$in" "$sz" "$f" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); q = d["quads"]; iv = q["irregular_vertices"]
nf = "%d / %d" % (iv["interior_near_cross"], iv["interior_far_cross"]) if "interior_near_cross" in iv else "-"
print("| %s | %s | %s | %d | %s | %d (%.1f) | %s | %.3f |" % (sys.argv[2], sys.argv[3] or "default (%.3g)" % d["size"],
      sys.argv[4] + (" (auto)" if sys.argv[4] == "cross" else ""), q["quads"], "yes" if q["valid"] else "no", iv["total"], 100.0 * iv["total"] / max(1, q["quads"]),
      nf, q["scaled_jacobian"]["min"]))
PY
    done
}
row shape:disk:8000 ""
row shape:disk:16000 "--size 0.1"
[ -f "$S/flower.msh" ] && row "$S/flower.msh" "--size 0.1"
[ -f "$S/airfoil.msh" ] && row "$S/airfoil.msh" "--size 0.12"
for m in annulus.msh plate_holes.msh lshape.msh square.obj; do row "$D/$m" ""; done
