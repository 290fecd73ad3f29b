#!/usr/bin/env bash
# bench/surface_quads.sh: quad meshes of the built-in surfaces (issue 29):
# per model and size, the quads, irregular interior vertices (% of the
# interior vertices), scaled Jacobian min / mean, Hausdorff / h, the Euler
# characteristic against the input's, whether the last resort was needed,
# and the seconds of the whole command and of its quad phase. Writes
# $OUT/summary.md (default out/surface_quads, ignored by git).
# Usage: bash bench/surface_quads.sh [path/to/glpgp]   (BACKEND=reference|opencl, default reference)
set -u
GLPGP=${1:-build/glpgp}
BACKEND=${BACKEND:-reference}
OUT=${OUT:-out/surface_quads}
mkdir -p "$OUT"
CASES=${CASES:-"shape:sphere:20000| shape:torus:20000| shape:genus2:20000| shape:cube:20000| shape:hemisphere:10000| shape:halfcyl:5000| shape:sphere:40000|--faces 300 shape:torus:40000|--faces 300 shape:cube:40000|--faces 600"}
{
    echo "| model | options | quads | irregular interior | SJ min | SJ mean | Hausdorff/h | Euler | valid | path | seconds (quads) |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|"
} >"$OUT/summary.md"
IFS=' ' read -r -a items <<<"$CASES"
i=0
while [ $i -lt ${#items[@]} ]; do
    spec=${items[$i]}
    model=${spec%%|*}
    opts=${spec#*|}
    if [ "$opts" = "--faces" ]; then i=$((i + 1)); opts="--faces ${items[$i]}"; fi
    i=$((i + 1))
    tag=$(echo "$model $opts" | tr ' :' '__')
    t0=$(date +%s.%N)
    # shellcheck disable=SC2086
    "$GLPGP" solve "$model" $opts --backend "$BACKEND" --quads "$OUT/$tag.obj" --stats "$OUT/$tag.json" \
        >"$OUT/$tag.txt" 2>&1
    t1=$(date +%s.%N)
    python3 - "$OUT/$tag.json" "$OUT/$tag.txt" "$model" "$opts" "$(echo "$t1 - $t0" | bc)" >>"$OUT/summary.md" <<'PY'
import json, re, sys
js, txt, model, opts, secs = sys.argv[1:]
try:
    d = json.load(open(js)); q = d["quads"]
except Exception as e:
    print("| %s | %s | failed: %s |" % (model, opts, e)); sys.exit(0)
vi = q["valence"]["interior"]; nint = sum(vi.values()); irr = nint - vi.get("4", 0)
s = q["surface"]; out = open(txt).read()
path = "last resort" if "last resort" in out else ("split (h/2)" if "Catmull-Clark" in out else "local split" if "split locally" in out else "local repair" if "repaired locally" in out else "grid")
ph = d.get("timers", {}) if isinstance(d.get("timers"), dict) else {}
m = re.search(r"extraction ([0-9.]+)", out)
print("| %s | %s | %d | %d (%.1f%%) | %.3f | %.3f | %.3f | %d / %d | %s | %s | %.1f (%s) |" % (
    model, opts or "default h", q["quads"], irr, 100.0 * irr / max(nint, 1), q["scaled_jacobian"]["min"],
    q["scaled_jacobian"]["mean"], s["hausdorff_over_h"], s["euler"], s["input_euler"],
    "yes" if q["valid"] else "no", path, float(secs), m.group(1) if m else "?"))
PY
done
cat "$OUT/summary.md"
