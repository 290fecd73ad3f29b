#!/usr/bin/env bash
# hard_sweep.sh: the quad meshes of every hard domain of
# tests/quads/hard_domains.h (slots, strips, small holes, wedges, cusps,
# graded far fields, perforated plates, I-beams, laminations, fillets,
# cracks, airfoils, gaskets, combs, stars, keyholes) at glpgp's default size
# and at h = 0.5 H, one table row per run: quads, irregular vertices (and per
# 100 quads), smallest and mean scaled Jacobian, Hausdorff distance to the
# domain, area ratio, quads over area / h^2 (h the global size: features
# smaller than h and the local size need more), validity, wall seconds; the
# totals at the end; and the rows as JSON. The measure behind changes to the size field, the extraction
# or the repair (bench/results/size_field.md): run it before and after, same
# machine, and compare the totals (single cases swing both ways: the
# extraction near holes smaller than h is chaotic).
#
# Usage: bash bench/hard_sweep.sh <glpgp-binary> [edges] [out.json]
#   edges: the domains' mesh size is H / edges (default 8: Gmsh's point size
#   H / 8); the domains come from glpgp-domains next to the binary
#   (GLPGP_DOMAINS overrides). About 1 minute on 2 cores (reference backend).
# Exit 1 when a run fails or gives an invalid mesh.
set -u
GLPGP=${1:?usage: hard_sweep.sh <glpgp-binary> [edges] [out.json]}
EDGES=${2:-8}
JSON=${3:-}
DOMAINS=${GLPGP_DOMAINS:-$(dirname "$GLPGP")/bench/glpgp-domains}
[ -x "$DOMAINS" ] || { echo "hard_sweep: $DOMAINS not found (build the bench, or set GLPGP_DOMAINS)" >&2; exit 1; }
command -v python3 >/dev/null || { echo "hard_sweep: python3 is needed to read the statistics" >&2; exit 1; }
T=$(mktemp -d "${TMPDIR:-/tmp}/glpgp_hard.XXXXXX")
trap 'rm -rf "$T"' EXIT
"$DOMAINS" 1 "$EDGES" "$T" >/dev/null || exit 1
bad=0
: >"$T/rows.txt"
echo "| domain | size | quads | irregular | per 100 quads | SJ min | SJ min / corner bound | below 0.3 unforced | SJ mean | Hausdorff / h | area ratio | quads / (area / h^2) | valid | s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for poly in "$T"/*.poly; do
    d=$(basename "$poly" .poly)
    if ! "$GLPGP" mesh "$poly" -o "$T/$d.msh" --quiet 2>"$T/err.txt"; then
        echo "| $d | | mesh failed: $(head -c 200 "$T/err.txt") |"
        bad=1
        continue
    fi
    for size in default 0.5; do
        opt=()
        [ "$size" = default ] || opt=(--size "$size")
        rm -f "$T/s.json"
        t0=$(date +%s.%N)
        "$GLPGP" solve "$T/$d.msh" "${opt[@]}" --backend reference --quads "$T/q.obj" --allow-invalid \
            --stats "$T/s.json" --quiet >/dev/null 2>"$T/err.txt"
        rc=$?
        t1=$(date +%s.%N)
        if [ "$rc" -ne 0 ] || [ ! -s "$T/s.json" ]; then
            echo "| $d | $size | failed (exit $rc): $(head -c 200 "$T/err.txt") |"
            bad=1
            continue
        fi
        python3 - "$T/s.json" "$d" "$size" "$t0" "$t1" "$T/rows.txt" <<'PY' || bad=1
import json, sys
q = json.load(open(sys.argv[1]))["quads"]
d, size, secs, rows = sys.argv[2], sys.argv[3], float(sys.argv[5]) - float(sys.argv[4]), sys.argv[6]
irr = q["irregular_vertices"]["total"]
row = {"domain": d, "size": size, "quads": q["quads"], "irregular": irr,
       "sj_min": q["scaled_jacobian"]["min"], "sj_mean": q["scaled_jacobian"]["mean"],
       "sj_min_corner": q["scaled_jacobian"]["min_of_corner_bound"], "below_goal": q["scaled_jacobian"]["below_goal"],
       "hausdorff": q["boundary_distance_over_h"]["hausdorff"], "area_ratio": q["area_ratio"],
       "valid": bool(q["valid"]), "seconds": secs,
       "quads_per_area": q["quads"] / max(q["domain_area"] / q["h"] ** 2, 1e-300)}
open(rows, "a").write(json.dumps(row) + "\n")
print("| %s | %s | %d | %d | %.1f | %.3f | %.3f | %d | %.3f | %.3f | %.4f | %.2f | %s | %.1f |" % (
    d, size, row["quads"], irr, 100.0 * irr / max(row["quads"], 1), row["sj_min"], row["sj_min_corner"],
    row["below_goal"], row["sj_mean"],
    row["hausdorff"], row["area_ratio"], row["quads_per_area"], "yes" if row["valid"] else "no", secs))
sys.exit(0 if row["valid"] else 1)
PY
    done
done
python3 - "$T/rows.txt" "$EDGES" "$JSON" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
nq = sum(r["quads"] for r in rows)
ni = sum(r["irregular"] for r in rows)
nv = sum(r["valid"] for r in rows)
print("\n%d runs: %d quads, %d irregular vertices (%.1f per 100 quads), %d valid; lowest SJ %.3f, "
      "lowest SJ over its corner bound %.3f, %d quads below 0.3 that no corner forces" % (
    len(rows), nq, ni, 100.0 * ni / max(nq, 1), nv, min(r["sj_min"] for r in rows),
    min(r["sj_min_corner"] for r in rows), sum(r["below_goal"] for r in rows)))
far = ["%s@%s %.2f" % (r["domain"], r["size"], r["quads_per_area"]) for r in rows
       if not (1 / 1.5 <= r["quads_per_area"] <= 1.5)]
print("quads within 1.5x of area / h^2: %d of %d runs%s" % (len(rows) - len(far), len(rows),
      (" (not: " + ", ".join(far) + ")") if far else ""))
if sys.argv[3]:
    json.dump({"edges_per_H": int(sys.argv[2]), "runs": rows, "quads": nq, "irregular": ni, "valid": nv},
              open(sys.argv[3], "w"), indent=1)
PY
exit $bad
