#!/usr/bin/env bash
# quads_sweep.sh: quad meshes of the built-in shapes over a grid of sizes and
# both guiding fields, one table row per run (non-quad faces, inverted and
# degenerate faces, irregular vertices, scaled Jacobian, strips). It checks
# the claim of README "Quad meshes" that every run gives only quads.
#
# Usage: bash bench/quads_sweep.sh <glpgp-binary> [vertices] [sizes...]
#   vertices: per shape (default 20000); sizes: default 0.05 0.08 0.13.
# About 2 minutes on 2 cores with the defaults (PoCL). Exit 1 when a run
# fails or leaves a non-quad or inverted face.
set -u
GLPGP=${1:?usage: quads_sweep.sh <glpgp> [vertices] [sizes...]}
N=${2:-20000}
shift $(($# >= 2 ? 2 : 1))
SIZES=${*:-0.05 0.08 0.13}
T=$(mktemp -d "${TMPDIR:-/tmp}/glpgp_sweep.XXXXXX")
trap 'rm -rf "$T"' EXIT
bad=0
echo "| shape | h | field | quads | other | inverted | degenerate | irregular | SJ min | SJ mean | closed | turns |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for shape in square disk annulus lshape; do
    for h in $SIZES; do
        for field in boundary radial; do
            if ! "$GLPGP" solve "shape:$shape:$N" --size "$h" --field "$field" --quiet \
                --stats "$T/s.json" --quads "$T/q.obj" >"$T/out.txt" 2>"$T/err.txt"; then
                echo "| $shape | $h | $field | failed: $(head -c 200 "$T/err.txt") |"
                bad=1
                continue
            fi
            python3 - "$T/s.json" "$shape" "$h" "$field" <<'PY' || bad=1
import json, sys
q = json.load(open(sys.argv[1]))["quads"]
c = q["closing"]
print("| %s | %s | %s | %d | %d | %d | %d | %d | %.3f | %.3f | %d | %d |" % (
    sys.argv[2], sys.argv[3], sys.argv[4], q["quads"], q["other_faces"], q["inverted"],
    q["degenerate"], q["irregular_vertices"]["total"], q["scaled_jacobian"]["min"],
    q["scaled_jacobian"]["mean"], c["odd_faces_closed"], c["turns"]))
sys.exit(1 if q["other_faces"] or q["inverted"] or q["degenerate"] else 0)
PY
        done
    done
done
exit $bad
