#!/usr/bin/env bash
# bench/surface_repair.sh: the surface cases whose extraction leaves bad
# faces (issue 29's local repair targets), one row per model and binary,
# the binaries interleaved per model so that they share the machine's load:
# quads, valid / manifold / all-quad, Euler and boundary loops kept,
# irregular interior vertices, SJ min / mean, Hausdorff / h, the path
# (grid, local repair, split, coarse last resort), the local repair's
# regions (faces in -> quads out), the seconds of the quad pipeline
# (phases.extraction: extraction, candidates, repair, smoothing, check) and
# of the whole command.
# Writes OUT/summary.md (OUT=out/surface_repair).
# Usage: bash bench/surface_repair.sh GLPGP [GLPGP2 ...]   (MODELS="model:faces ..." to choose;
#        faces 0: the default h)
set -u
[ $# -ge 1 ] || { echo "usage: bash bench/surface_repair.sh GLPGP [GLPGP2 ...]" >&2; exit 2; }
OUT=${OUT:-out/surface_repair}
BACKEND=${BACKEND:-reference}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
python3 "$HERE/surface_models.py" holes 20 5 "$OUT/holes20.obj"
MODELS=${MODELS:-"shape:torus:5000:150 shape:torus:5000:400 shape:sphere:5000:400 shape:genus2:20000:0 shape:genus2:5000:150 shape:genus2:5000:400 $OUT/holes20.obj:0"}
{
    echo "| model | faces | binary | quads | valid / manifold / all-quad | Euler, loops kept | irregular interior | SJ min | SJ mean | Hausdorff/h | path | local regions (faces in -> quads out) | extraction s | seconds |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
} >"$OUT/summary.md"
for spec in $MODELS; do
    model=${spec%:*}
    n=${spec##*:}
    k=0
    for bin in "$@"; do
        k=$((k + 1))
        tag=$(basename "$model" | tr ':.' '__')_${n}_$k
        opt=""
        [ "$n" != 0 ] && opt="--faces $n"
        t0=$(date +%s.%N)
        # shellcheck disable=SC2086
        "$bin" solve "$model" $opt --backend "$BACKEND" --quads "$OUT/$tag.obj" --stats "$OUT/$tag.json" >"$OUT/$tag.txt" 2>&1
        t1=$(date +%s.%N)
        python3 - "$OUT/$tag.json" "$OUT/$tag.txt" "$model" "$n" "$bin" "$(echo "$t1 - $t0" | bc)" >>"$OUT/summary.md" <<'PY'
import json, sys
js, txt, model, n, binary, secs = sys.argv[1:]
try:
    d = json.load(open(js)); q = d["quads"]; s = q["surface"]
except Exception as e:
    print("| %s | %s | %s | failed: %s |" % (model, n, binary, e)); sys.exit(0)
vi = q["valence"]["interior"]; nint = sum(vi.values()); irr = nint - vi.get("4", 0)
out = open(txt).read()
path = ("coarse last resort" if "coarsened triangulation" in out else "last resort" if "last resort" in out
        else "split (h/2)" if "Catmull-Clark" in out else "local split" if "split locally" in out else "grid")
if "repaired locally" in out:
    path = "local repair" if path == "grid" else path + " + local repair"
r = q.get("repair", {})
regs = "%d (%d -> %d)" % (r.get("regions", 0), r.get("removed_faces", 0), r.get("new_quads", 0)) if r.get("regions") else "-"
ext = d.get("phases", {}).get("extraction", {}).get("seconds", -1.0)
manifold = "nonmanifold" not in q["invalid_reasons"] and "pinched" not in q["invalid_reasons"]
print("| %s | %s | %s | %d | %s / %s / %s | %s | %d (%.1f%%) | %.3f | %.3f | %.3f | %s | %s | %.2f | %.1f |" % (
    model, n if n != "0" else "default h", binary, q["quads"], "yes" if q["valid"] else "no", "yes" if manifold else "no",
    "yes" if q["other_faces"] == 0 else "no",
    "yes" if (s["euler"], s["boundary_loops"]) == (s["input_euler"], s["input_boundary_loops"]) else "no",
    irr, 100.0 * irr / max(nint, 1), q["scaled_jacobian"]["min"], q["scaled_jacobian"]["mean"],
    s["hausdorff_over_h"], path, regs, ext, float(secs)))
PY
    done
done
cat "$OUT/summary.md"
