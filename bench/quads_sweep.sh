#!/usr/bin/env bash
# quads_sweep.sh: quad meshes of the built-in shapes over a grid of sizes and
# both guiding fields, one table row per run (non-quad faces, inverted and
# degenerate faces, irregular vertices and per 100 quads, scaled Jacobian,
# strips, repair, validity). It checks the claim of README "Quad meshes"
# that every run gives a valid all-quad mesh. A binary whose report has no
# validity (older glpgp) gets "-" in that column.
#
# Usage: bash bench/quads_sweep.sh <glpgp-binary> [vertices] [sizes...]
#   vertices: per shape (default 20000); sizes: default 0.05 0.08 0.13.
# About 2 minutes on 2 cores with the defaults (PoCL). Exit 1 when a run
# fails or leaves a non-quad or inverted face or an invalid mesh (exit 3:
# the statistics are still read).
set -u
GLPGP=${1:?usage: quads_sweep.sh <glpgp> [vertices] [sizes...]}
N=${2:-20000}
shift $(($# >= 2 ? 2 : 1))
SIZES=${*:-0.05 0.08 0.13}
T=$(mktemp -d "${TMPDIR:-/tmp}/glpgp_sweep.XXXXXX")
trap 'rm -rf "$T"' EXIT
bad=0
echo "| shape | h | field | quads | other | inverted | degenerate | irregular | irregular / 100 quads | SJ min | SJ mean | closed | turns | repaired faces | valid |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for shape in square disk annulus lshape; do
    for h in $SIZES; do
        for field in boundary radial; do
            rm -f "$T/s.json"
            "$GLPGP" solve "shape:$shape:$N" --size "$h" --field "$field" --quiet \
                --stats "$T/s.json" --quads "$T/q.obj" >"$T/out.txt" 2>"$T/err.txt"
            rc=$?
            if [ "$rc" -ne 0 ] && { [ "$rc" -ne 3 ] || [ ! -s "$T/s.json" ]; }; then
                echo "| $shape | $h | $field | failed: $(head -c 200 "$T/err.txt") |"
                bad=1
                continue
            fi
            python3 - "$T/s.json" "$shape" "$h" "$field" <<'PY' || bad=1
import json, sys
q = json.load(open(sys.argv[1]))["quads"]
c = q["closing"]
valid = "-" if "valid" not in q else ("yes" if q["valid"] else "no: " + ", ".join(q["invalid_reasons"]))
rep = q.get("repair", {}).get("removed_faces", "-")
irr = q["irregular_vertices"]["total"]
print("| %s | %s | %s | %d | %d | %d | %d | %d | %.1f | %.3f | %.3f | %d | %d | %s | %s |" % (
    sys.argv[2], sys.argv[3], sys.argv[4], q["quads"], q["other_faces"], q["inverted"],
    q["degenerate"], irr, 100.0 * irr / max(1, q["quads"]), q["scaled_jacobian"]["min"],
    q["scaled_jacobian"]["mean"], c["odd_faces_closed"], c["turns"], rep, valid))
sys.exit(1 if q["other_faces"] or q["inverted"] or q["degenerate"] or q.get("valid") is False else 0)
PY
        done
    done
done
exit $bad
