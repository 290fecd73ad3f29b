#!/usr/bin/env bash
# bench/surface_features.sh: feature edges of CAD-like and noisy surfaces
# (glpgp_surface_features: creases, not a scan's noise). Generates the
# models with bench/surface_models.py (feature cube, slabs, a 12-triangle
# cube, 45 and 40 degree prisms, jittered boxes and prisms, bumpy scans
# with a 0.2-1% jitter, genus 2 and a torus jittered in every coordinate)
# and writes one JSON line per model (triangles, edges above the feature
# angle, features, the angle defects' rms, and what --denoise auto makes
# of it: noise edges before and after, vertices moved, the largest move,
# features and defects after) to $OUT/features.jsonl and a table to
# $OUT/summary.md.
# Seconds on 2 cores. Results: bench/results/surface_features.md.
# Usage: bash bench/surface_features.sh [path/to/build]   (default build)
set -eu
BUILD=${1:-build}
OUT=${OUT:-out/surface_features}
HERE=$(cd "$(dirname "$0")" && pwd)
M="python3 $HERE/surface_models.py"
mkdir -p "$OUT"
"$BUILD/glpgp" generate shape:cube:5000 -o "$OUT/cube.obj" > /dev/null
"$BUILD/glpgp" generate shape:genus2:20000 -o "$OUT/genus2.obj" > /dev/null
"$BUILD/glpgp" generate shape:torus:20000 -o "$OUT/torus.obj" > /dev/null
$M slab 4 4 4 "$OUT/slab16.obj"
$M slab 2 2 1 "$OUT/slab4_coarse.obj"
$M box 1 "$OUT/box12.obj"
$M box 20 "$OUT/box20.obj"
$M prism 8 6 "$OUT/prism8.obj"
$M prism 9 6 "$OUT/prism9.obj"
for j in 0.2 0.3 0.5; do $M jitter "$OUT/box20.obj" "$OUT/box20_j$j.obj" $j; done
$M jitter "$OUT/prism9.obj" "$OUT/prism9_j0.06.obj" 0.06
$M jitter "$OUT/genus2.obj" "$OUT/genus2_j0.2.obj" 0.2
$M jitter "$OUT/torus.obj" "$OUT/torus_j0.2.obj" 0.2
$M bumpy 5 "$OUT/bumpy5_1pc.obj" 0.01
$M bumpy 6 "$OUT/bumpy6_clean.obj" 0
$M bumpy 6 "$OUT/bumpy6_0.2pc.obj" 0.002
$M bumpy 6 "$OUT/bumpy6_0.5pc.obj" 0.005
$M bumpy 6 "$OUT/bumpy6_1pc.obj" 0.01
$M bumpy 7 "$OUT/bumpy7_0.2pc.obj" 0.002
cd "$OUT"
"$OLDPWD/$BUILD/bench/glpgp-features" cube.obj slab16.obj slab4_coarse.obj box12.obj box20.obj prism8.obj \
    prism9.obj prism9_j0.06.obj box20_j0.2.obj box20_j0.3.obj box20_j0.5.obj genus2_j0.2.obj torus_j0.2.obj \
    bumpy5_1pc.obj bumpy6_clean.obj bumpy6_0.2pc.obj bumpy6_0.5pc.obj bumpy6_1pc.obj bumpy7_0.2pc.obj > features.jsonl
python3 - <<'PY'
import json
rows = [json.loads(l) for l in open("features.jsonl")]
with open("summary.md", "w") as o:
    o.write("| model | triangles | edges above %g degrees | features | angle defect rms | --denoise auto: noise "
            "edges before -> after | folded triangles before -> after | vertices moved | largest move (mean edges) | features after | angle defect "
            "rms after |\n|---|---|---|---|---|---|---|---|---|---|---|\n" % rows[0]["feature_angle"])
    for r in rows:
        d = r["denoise"]
        o.write("| %s | %d | %d | %d | %.4f | %d -> %d | %d -> %d | %d | %.3f | %d | %.4f |\n" % (
            r["model"], r["triangles"], r["edges_above"], r["features"], r["defect_rms"], d["noise_edges"],
            d["noise_edges_after"], d["folds"], d["folds_after"], d["moved"], d["max_move_edges"], d["features"], d["defect_rms"]))
print(open("summary.md").read())
PY
