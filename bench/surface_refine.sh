#!/usr/bin/env bash
# bench/surface_refine.sh: the refinement of a surface too coarse for its
# size (solver/prepare.c, issue 29), binaries interleaved per model, for
# before / after comparisons: per model and binary the triangles solved, the
# refinement line, the seconds per phase (refine, cross field, oscillators u,
# extraction), quads, the extraction's path (grid, local repair, local
# split, split h/2, last resort), irregular interior vertices, SJ min,
# Hausdorff / h, valid.
# A "binary" is a command word list (BIN_A may be "env X=1 path/glpgp").
# Models (MODELS, "spec|options" separated by ';'): the surface_solve.sh set
# plus the hemisphere, holes20 at 5 rings and the bumpy scan at 2000 faces
# (BUMPY=0 leaves it out).
# Usage: bash bench/surface_refine.sh BIN_A [BIN_B ...]   (BACKEND, default
# reference; OUT, default out/surface_refine: logs, statistics, summary.md)
set -u
[ $# -ge 1 ] || { echo "usage: surface_refine.sh BIN_A [BIN_B ...]" >&2; exit 2; }
OUT=${OUT:-out/surface_refine}
BACKEND=${BACKEND:-reference}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
python3 "$HERE/surface_models.py" holes 20 4 "$OUT/holes20.obj" >/dev/null
DEF="shape:sphere:5000|--faces 200;shape:genus2:5000|--faces 400;shape:torus:12500|--faces 500;shape:cube:5000|--faces 400;shape:hemisphere:5000|--faces 300;$OUT/holes20.obj|--faces 300"
if [ "${BUMPY:-1}" != 0 ]; then
    [ -f "$OUT/b82.obj" ] || python3 "$HERE/surface_models.py" bumpy 6 "$OUT/b82.obj" >/dev/null
    DEF="$DEF;$OUT/b82.obj|--faces 2000"
fi
MODELS=${MODELS:-$DEF}
{
    echo "| model | binary | triangles | refined | refine s | field s | u s | extraction s | total s | quads | path | irregular | SJ min | Hausdorff/h | valid |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
} >"$OUT/summary.md"
IFS=';' read -r -a specs <<<"$MODELS"
for spec in "${specs[@]}"; do
    model=${spec%%|*}
    opts=${spec#*|}
    [ "$opts" = "$spec" ] && opts=""
    for bin in "$@"; do
        tag=$(basename "$model" | tr ':.' '__')_$(echo "$bin" | md5sum | cut -c1-6)
        # shellcheck disable=SC2086
        $bin solve "$model" $opts --backend "$BACKEND" --quads "$OUT/$tag.obj" --stats "$OUT/$tag.json" \
            >"$OUT/$tag.txt" 2>&1
        python3 - "$OUT/$tag.json" "$OUT/$tag.txt" "$model" "$bin" >>"$OUT/summary.md" <<'PY'
import json, re, sys
js, txt, model, b = sys.argv[1:]
try:
    d = json.load(open(js)); q = d["quads"]; s = q["surface"]
except Exception as e:
    print("| %s | %s | failed: %s |" % (model, b, e)); sys.exit(0)
out = open(txt).read()
m = re.search(r"refined\s+\d+ -> \d+ vertices, \d+ -> \d+ triangles \(([^)]*)\)", out)
ph = d["phases"]
vi = q["valence"]["interior"]; nint = sum(vi.values()); irr = nint - vi.get("4", 0)
sec = d["seconds"]
quads_s = sum(ph[k]["seconds"] for k in ("extraction",) if k in ph)
x = re.search(r"time\s+([0-9.]+) s", out)
path = s.get("steps", {}).get("path") or ("coarse last resort" if "coarsened triangulation" in out else "last resort" if "last resort" in out
        else "split (h/2)" if "Catmull-Clark" in out else "local split" if "split locally" in out
        else "local repair" if "repaired locally" in out else "grid")
print("| %s | %s | %d | %s | %.2f | %.1f | %.1f | %.2f | %s | %d | %s | %d (%.1f%%) | %.3f | %.3f | %s |" % (
    model, b, d["triangles"], m.group(1).split(":")[0] if m else "-", ph["refine"]["seconds"], sec["field"],
    sec["u"] + sec["v"], quads_s, x.group(1) if x else "?", q["quads"], path, irr, 100.0 * irr / max(nint, 1),
    q["scaled_jacobian"]["min"], s["hausdorff_over_h"], "yes" if q["valid"] else "no"))
PY
    done
done
cat "$OUT/summary.md"
