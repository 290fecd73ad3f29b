#!/usr/bin/env bash
# bench/surface_compare.sh [GLPGP] [OUT.json]: GL-PGP against naive PGP on
# surfaces the surface path was not tuned on (bench/surface_models.py:
# ellipsoid.ply, bumpy.off, trefoil.obj, can.stl, saddle.obj) and on the
# built-in sphere, torus, genus2 and cube: per model and method the
# oscillators' singular triangles (u + v), median and 10th percentile of
# |z|, Newton steps and seconds, default options (the cross field, the
# default size), one after the other in one run. Prints a table, writes
# JSON. BACKEND (default auto) picks the backend; N (default 20000) the
# models' size.
set -eu
G=${1:-build/glpgp}
OUT=${2:-surface_compare.json}
BACKEND=${BACKEND:-auto}
N=${N:-20000}
D=$(mktemp -d "${TMPDIR:-/tmp}/glpgp_surface_compare.XXXXXX")
trap 'rm -rf "$D"' EXIT
python3 "$(dirname "$0")/surface_models.py" "$D" "$N"
inputs="$D/ellipsoid.ply $D/bumpy.off $D/trefoil.obj $D/can.stl $D/saddle.obj shape:sphere:$N shape:torus:$N shape:genus2:$N shape:cube:$N"
rows=()
printf '%-12s %-4s %9s %9s %8s %8s %7s %8s\n' model meth vertices singular med_zabs p10_zabs newton seconds
for in in $inputs; do
    name=$(basename "${in#shape:}")
    for m in pgp gl; do
        "$G" solve "$in" --method $m --backend "$BACKEND" --stats "$D/s.json" --quiet >/dev/null
        row=$(python3 - "$D/s.json" "$name" "$m" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
s = d["singularities"]
sing = s["u"]["plus"] + s["u"]["minus"] + s["v"]["plus"] + s["v"]["minus"]
z = d["zabs"]
med = min(z["u"]["median"], z["v"]["median"])
p10 = min(z["u"]["p10"], z["v"]["p10"])
print(json.dumps({"model": sys.argv[2], "method": sys.argv[3], "vertices": d["vertices"], "singular": sing,
                  "median_zabs": med, "p10_zabs": p10, "newton": d["newton_iterations"]["total"],
                  "seconds": d["seconds"]["total"], "cross_singularities": d["cross_field"]["singularities"],
                  "backend": d["backend"]}))
PY
)
        rows+=("$row")
        python3 -c "import json,sys; r=json.loads(sys.argv[1]); print('%-12s %-4s %9d %9d %8.4f %8.4f %7d %8.2f' % (r['model'], r['method'], r['vertices'], r['singular'], r['median_zabs'], r['p10_zabs'], r['newton'], r['seconds']))" "$row"
    done
done
(IFS=,; echo "[${rows[*]}]") | python3 -c "import json,sys; json.dump({'runs': json.load(sys.stdin)}, open(sys.argv[1], 'w'), indent=1)" "$OUT"
echo "wrote $OUT"
