#!/usr/bin/env bash
# bench/surface_solve.sh: the linear solves of the surface solve, two
# binaries interleaved per model (A then B), for before / after comparisons
# of the Newton / CG counts (issue 29/32). Per model and binary: the cross
# field's Newton steps / CG iterations and singularities, the coupled
# oscillators' Newton steps / CG iterations (CG per Newton step), the last
# E + P of the coupled solve, the frame windings and the user seconds.
# Models (MODELS, "spec|options" separated by ';'): a sphere, genus 2, a
# torus, the feature cube and a sphere with 20 holes (boundary loops).
# Usage: bash bench/surface_solve.sh BIN_A [BIN_B]   (BACKEND, default reference;
# OUT, default out/surface_solve: logs, statistics and summary.md)
set -u
A=${1:?usage: surface_solve.sh BIN_A [BIN_B]}
B=${2:-}
OUT=${OUT:-out/surface_solve}
BACKEND=${BACKEND:-reference}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
python3 "$HERE/surface_models.py" holes 20 4 "$OUT/holes20.obj"
MODELS=${MODELS:-"shape:sphere:5000|--faces 200;shape:genus2:5000|--faces 400;shape:torus:12500|--faces 500;shape:cube:5000|--faces 400;$OUT/holes20.obj|--faces 300"}
{
    echo "| model | binary | cross Newton / CG | cross sing. | coupled Newton / CG | CG per Newton | last E+P | windings | user s |"
    echo "|---|---|---|---|---|---|---|---|---|"
} >"$OUT/summary.md"
IFS=';' read -r -a specs <<<"$MODELS"
for spec in "${specs[@]}"; do
    model=${spec%%|*}
    opts=${spec#*|}
    [ "$opts" = "$spec" ] && opts=""
    for bin in "$A" $B; do
        tag=$(basename "$model" | tr ':.' '__')_$(echo "$bin" | md5sum | cut -c1-6)
        # shellcheck disable=SC2086
        /usr/bin/time -f "%U" -o "$OUT/$tag.time" "$bin" solve "$model" $opts --backend "$BACKEND" --verbose \
            --stats "$OUT/$tag.json" >"$OUT/$tag.txt" 2>&1
        python3 - "$OUT/$tag.txt" "$OUT/$tag.time" "$model" "$bin" >>"$OUT/summary.md" <<'PY'
import re, sys
txt = open(sys.argv[1]).read()
user = open(sys.argv[2]).read().strip().splitlines()[-1]
cr = re.search(r"cross: done in [\d.]+ s: (\d+) singularities.*?(\d+) Newton, (\d+) CG", txt)
cp = re.search(r"coupled u\+v: done in [\d.]+ s.*?(\d+) Newton, (\d+) CG", txt)
e = re.findall(r"coupled u\+v eps=\S+ newton\s+\d+\s+\|g\|=\S+\s+E\+P=(\S+)", txt)
w = re.search(r"frame windings (.*) \(", txt)
if not (cr and cp):
    print(f"| {sys.argv[3]} | {sys.argv[4]} | failed | | | | | | {user} |")
else:
    n, c = int(cp.group(1)), int(cp.group(2))
    print(f"| {sys.argv[3]} | {sys.argv[4]} | {cr.group(2)} / {cr.group(3)} | {cr.group(1)} | {n} / {c} | "
          f"{c / max(n, 1):.1f} | {e[-1] if e else '-'} | {w.group(1) if w else '-'} | {user} |")
PY
    done
done
cat "$OUT/summary.md"
