#!/usr/bin/env bash
# size_compare.sh: the local size field's effect on the hard domains
# (tests/quads/hard_domains.h): `glpgp solve --size-field auto` against
# `--size-field none` (uniform h, today's pipeline), in one run, at h = 1 with
# glpgp's triangle mesh at 12 and at 6 mean edges per h (the graded airfoil at
# 12 only, as in bench/gmsh_compare.sh), every mesh measured by the quality
# report of `solve --quads` (one orientation for the whole mesh).
#
# Usage: bash bench/size_compare.sh <glpgp-binary> [work-dir] > table.md
#   GLPGP_DOMAINS=<glpgp-domains> (default: next to the binary, bench/);
#   SIZE_MODES="none auto" (default) picks the --size-field values run;
#   QUAD_ARGS="..." extra options of every solve (e.g. --no-cleanup).
# Both modes: --backend reference --newton-max 30 --allow-invalid (an invalid
# mesh is measured too, its row says so); auto refines the input where its
# triangles are coarser than the local h / 4 (the default; "vertices" is the
# solved mesh), none solves the input as it is.
# Columns: valid (the report's verdict, reasons), non-quad faces, repair
# (faces removed / quads made by the local repair), irregular vertices per 100
# quads, min scaled Jacobian, area ratio, Hausdorff / h, seconds (wall, the
# whole command; shared machine: compare within a run only).
set -u
GLPGP=${1:?usage: size_compare.sh <glpgp> [work-dir]}
GLPGP=$(cd "$(dirname "$GLPGP")" && pwd)/$(basename "$GLPGP")
DOMAINS_BIN=${GLPGP_DOMAINS:-$(dirname "$GLPGP")/bench/glpgp-domains}
command -v python3 >/dev/null 2>&1 || { echo "size_compare: python3 not found: skipped"; exit 0; }
[ -x "$DOMAINS_BIN" ] || { echo "size_compare: $DOMAINS_BIN not found"; exit 1; }
if [ -n "${2:-}" ]; then
    W=$2
    mkdir -p "$W"
else
    W=$(mktemp -d "${TMPDIR:-/tmp}/glpgp_size.XXXXXX")
    trap 'rm -rf "$W"' EXIT
fi
W=$(cd "$W" && pwd)
rows=()
for edges in 12 6; do
    mkdir -p "$W/hard$edges"
    for name in $("$DOMAINS_BIN" 1 "$edges" "$W/hard$edges"); do
        [ "$name" = graded ] && [ "$edges" = 6 ] && continue
        # the point sizes as bench/gmsh_compare.sh: Gmsh's mean edge is about
        # 0.7 of the point size (the graded far field as written)
        scale=$(python3 -c "print(1 if '$name' == 'graded' else 1 / 0.7)")
        python3 - "$W/hard$edges/$name.poly" "$scale" <<'PY'
import sys
p, s = sys.argv[1], float(sys.argv[2])
L = open(p).read().split('\n')
nv = int(L[1].split()[0])
for i in range(2, 2 + nv):
    t = L[i].split()
    t[3] = repr(float(t[3]) * s)
    L[i] = ' '.join(t)
open(p, 'w').write('\n'.join(L))
PY
        tri=$W/$name.tri$edges.msh
        "$GLPGP" mesh "$W/hard$edges/$name.poly" -o "$tri" --quiet >/dev/null 2>&1 ||
            { rows+=("$name|$edges|-|mesh failed|"); continue; }
        for mode in ${SIZE_MODES:-none auto}; do
            tag=$name.$edges.$mode
            t0=$(date +%s.%N)
            if "$GLPGP" solve "$tri" --backend reference --quiet --newton-max 30 --allow-invalid --size 1 \
                --size-field "$mode" --stats "$W/$tag.json" --quads "$W/$tag.msh" ${QUAD_ARGS:-} >"$W/$tag.txt" 2>&1; then
                t1=$(date +%s.%N)
                rows+=("$name|$edges|$mode|$W/$tag.json|$(python3 -c "print('%.1f' % ($t1 - $t0))")")
            else
                rows+=("$name|$edges|$mode|failed: $(grep -m1 error "$W/$tag.txt" | cut -c1-100)|")
            fi
        done
    done
done

printf '%s\n' "${rows[@]}" | python3 -c '
import json, sys
print("| domain | edges/h | size field | vertices | valid | non-quad | repair removed/made | irreg / 100 quads | SJ min | area | Hausdorff/h | s |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
agg = {}
for line in sys.stdin.read().splitlines():
    name, edges, mode, what, secs = line.split("|")
    if not what.endswith(".json"):
        print("| %s | %s | %s | %s |" % (name, edges, mode, what)); continue
    d = json.load(open(what)); q = d["quads"]
    nq = max(q["quads"], 1)
    irr = 100.0 * q["irregular_vertices"]["total"] / nq
    valid = "yes" if q["valid"] else "no: " + ", ".join(q["invalid_reasons"])
    rep = q["repair"]
    print("| %s | %s | %s | %d | %s | %d | %d / %d | %.1f | %.3f | %.4f | %.3f | %s |" % (
        name, edges, mode, d["vertices"], valid, q["non_quad_faces"], rep["removed_faces"], rep["new_quads"],
        irr, q["scaled_jacobian"]["min"], q["area_ratio"], q["boundary_distance_over_h"]["hausdorff"], secs))
    a = agg.setdefault((edges, mode), [0, 0, 0, 0, 0, 0])
    a[0] += 1; a[1] += q["valid"]; a[2] += q["non_quad_faces"] == 0; a[3] += rep["removed_faces"] > 0
    a[4] += q["irregular_vertices"]["total"]; a[5] += q["quads"]
print()
print("| edges/h | size field | runs | valid | all quads | repaired | irreg / 100 quads (summed) |")
print("|---|---|---|---|---|---|---|")
for (edges, mode), a in sorted(agg.items()):
    print("| %s | %s | %d | %d | %d | %d | %.1f |" % (edges, mode, a[0], a[1], a[2], a[3], 100.0 * a[4] / max(a[5], 1)))
'
