#!/usr/bin/env bash
# bench/surface_compare.sh: quad meshes of surfaces against the peers
# (issue 29): generated models (sphere, torus, genus 2, the feature cube,
# the hemisphere, a sphere with 20 jagged holes and one with 20 round ones) and any user models (MODELS="a.obj
# b.ply"), each at the target face counts FACES (default "300 1000"), with
# `glpgp solve MODEL --faces N --quads`; per row: valid / manifold /
# all-quad, Euler characteristic and boundary loops kept, irregular
# interior vertices (% of the interior ones), SJ min / mean, Hausdorff / h
# and the seconds of the solve and of the quad phase. A peer runs when its
# binary is named (QUADRIFLOW=/path/to/quadriflow: -i IN -o OUT -f N;
# INSTANT_MESHES=/path/to/Instant\ Meshes: -o OUT -f N -D IN), else its
# column is skipped; its OBJ is checked by `glpgp quality --domain INPUT`
# at glpgp's h for that row (the same checks as glpgp's own: all quads,
# manifold, Euler, loops, irregular %, SJ in the faces' own planes, two-sided
# Hausdorff / h, area), one row per tool by bench/surface_row.py.
# Writes $OUT/summary.md (default out/surface_compare).
# HELD_OUT=1 adds models never tuned on (bench/surface_models.py: a bumpy
# 82k-triangle scan, the same with a 1% vertex jitter (noise above the
# feature angle), a plate of genus 16 with sharp edges, a sphere with 120
# jagged holes and one with 120 round ones; minutes each on 2 cores).
# ARGS: more `glpgp solve` options for every row (e.g. ARGS="--size-chord-depth 0.125").
# ALIGN="0 5": one glpgp row per --cross-align weight (the principal-curvature
# term; default: one row at the default weight).
# Usage: bash bench/surface_compare.sh [path/to/glpgp]   (SCALE: triangles of the generated models, default 20000)
set -u
GLPGP=${1:-build/glpgp}
OUT=${OUT:-out/surface_compare}
FACES=${FACES:-"300 1000"}
SCALE=${SCALE:-20000}
BACKEND=${BACKEND:-reference}
read -r -a ARGS_A <<<"${ARGS:-}"
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
python3 "$HERE/surface_models.py" holes 20 5 "$OUT/holes20.obj"
python3 "$HERE/surface_models.py" roundholes 20 5 "$OUT/roundholes20.obj"
MODELS_ALL="shape:sphere:$SCALE shape:torus:$SCALE shape:genus2:$SCALE shape:cube:$SCALE shape:hemisphere:$SCALE $OUT/holes20.obj $OUT/roundholes20.obj ${MODELS:-}"
if [ -n "${HELD_OUT:-}" ]; then # models never tuned on: an 82k-triangle scan (clean and noisy), a plate of genus 16 with sharp edges, 120 loops
    python3 "$HERE/surface_models.py" bumpy 6 "$OUT/bumpy82k.obj"
    python3 "$HERE/surface_models.py" bumpy 6 "$OUT/bumpy82k_noisy.obj" 0.01
    python3 "$HERE/surface_models.py" slab 4 4 2 "$OUT/slab16.obj"
    python3 "$HERE/surface_models.py" holes 120 6 "$OUT/holes120.obj"
    python3 "$HERE/surface_models.py" roundholes 120 5 "$OUT/roundholes120.obj"
    MODELS_ALL="$MODELS_ALL $OUT/bumpy82k.obj $OUT/bumpy82k_noisy.obj $OUT/slab16.obj $OUT/holes120.obj $OUT/roundholes120.obj"
fi
peers=""
[ -n "${QUADRIFLOW:-}" ] && peers="$peers quadriflow"
[ -n "${INSTANT_MESHES:-}" ] && peers="$peers instant"
{
    echo "| model | faces | tool | quads | valid / manifold / all-quad | Euler, loops kept | irregular interior | SJ min | SJ mean | Hausdorff/h | path | seconds (quads) |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
} >"$OUT/summary.md"
for model in $MODELS_ALL; do
    for n in $FACES; do
        tag=$(basename "$model" | tr ':.' '__')_$n
        for a in ${ALIGN:--}; do
            va=() tool=glpgp
            [ "$a" != - ] && va=(--cross-align "$a") tool="glpgp (align $a)"
            t0=$(date +%s.%N)
            "$GLPGP" solve "$model" --faces "$n" --backend "$BACKEND" --quads "$OUT/$tag.obj" --stats "$OUT/$tag.json" \
                "${va[@]}" "${ARGS_A[@]}" >"$OUT/$tag.txt" 2>&1
            t1=$(date +%s.%N)
            python3 "$HERE/surface_row.py" "$OUT/$tag.json" "$OUT/$tag.txt" "$model" "$n" "$tool" \
                "$(echo "$t1 - $t0" | bc)" >>"$OUT/summary.md"
        done
        h=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["quads"]["h"])' "$OUT/$tag.json" 2>/dev/null)
        for p in $peers; do
            in="$OUT/${tag}_in.obj"
            case $model in shape:*) "$GLPGP" generate "$model" -o "$in" >/dev/null 2>&1 ;; *) cp "$model" "$in" ;; esac
            rm -f "$OUT/${tag}_$p.obj"
            t0=$(date +%s.%N)
            if [ "$p" = quadriflow ]; then
                "$QUADRIFLOW" -i "$in" -o "$OUT/${tag}_$p.obj" -f "$n" >"$OUT/${tag}_$p.txt" 2>&1
            else
                "$INSTANT_MESHES" -o "$OUT/${tag}_$p.obj" -f "$n" -D "$in" >"$OUT/${tag}_$p.txt" 2>&1
            fi
            t1=$(date +%s.%N)
            rm -f "$OUT/${tag}_$p.json"
            [ -s "$OUT/${tag}_$p.obj" ] && "$GLPGP" quality "$OUT/${tag}_$p.obj" --domain "$in" ${h:+--size "$h"} \
                --stats "$OUT/${tag}_$p.json" --allow-invalid >"$OUT/${tag}_$p.check.txt" 2>&1
            python3 "$HERE/surface_row.py" "$OUT/${tag}_$p.json" "$OUT/${tag}_$p.txt" "$model" "$n" "$p" \
                "$(echo "$t1 - $t0" | bc)" >>"$OUT/summary.md"
        done
    done
done
cat "$OUT/summary.md"
