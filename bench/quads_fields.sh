#!/usr/bin/env bash
# quads_fields.sh: the quad meshes of the boundary-aligned and the cross
# guiding field over three sets of domains, one table row per run, the
# totals per set, field and binary at the end, and the rows as JSON. The
# measure behind the default guiding field of `solve --quads` (README "Quad
# meshes") and behind "no worse than before" on the bundled and smooth
# domains (run it with the old binary as a second NAME=PATH).
#   bundled  data/*.msh, data/square.obj and the built-in shapes at their
#            default sizes, three smooth domains at a finer size;
#   hard     the hard domains of tests/quads/hard_domains.h (glpgp-domains,
#            point size H / 8) at the default size;
#   random   random polygons with holes, spikes and slits (glpgp-domains
#            random), point size H / 8, at the default size.
# Columns: quads, irregular vertices (all) and per 100 quads, smallest
# scaled Jacobian, and that over what the sharp corners allow, the share of
# quads from the repair, validity, seconds.
#
# Usage: bash bench/quads_fields.sh [--quick] NAME=GLPGP [NAME=GLPGP ...] [-- out.json]
#   the first binary's bench/glpgp-domains writes the domains (GLPGP_DOMAINS
#   overrides); --quick: fewer domains (a smoke test, cli_bench). Reference
#   backend. About 20 minutes per binary on a 2-core machine.
set -u
QUICK=0
[ "${1:-}" = "--quick" ] && { QUICK=1; shift; }
BINS=()
JSON=
while [ $# -gt 0 ]; do
    if [ "$1" = "--" ]; then JSON=${2:-}; break; fi
    BINS+=("$1")
    shift
done
[ ${#BINS[@]} -gt 0 ] || { echo "usage: quads_fields.sh [--quick] NAME=GLPGP [...] [-- out.json]" >&2; exit 2; }
FIRST=${BINS[0]#*=}
DOMAINS=${GLPGP_DOMAINS:-$(dirname "$FIRST")/bench/glpgp-domains}
DATA=$(cd "$(dirname "$0")/../data" && pwd)
[ -x "$DOMAINS" ] || { echo "quads_fields: $DOMAINS not found (build the bench, or set GLPGP_DOMAINS)" >&2; exit 1; }
command -v python3 >/dev/null || { echo "quads_fields: python3 is needed" >&2; exit 1; }
T=$(mktemp -d "${TMPDIR:-/tmp}/glpgp_fields.XXXXXX")
trap 'rm -rf "$T"' EXIT
mkdir -p "$T/hard" "$T/random"
if [ $QUICK = 1 ]; then
    "$DOMAINS" 1 8 "$T/hard" slot smallhole >/dev/null || exit 1
    "$DOMAINS" 1 8 "$T/random" random 1 1 >/dev/null || exit 1
else
    "$DOMAINS" 1 8 "$T/hard" >/dev/null || exit 1
    "$DOMAINS" 1 8 "$T/random" random 1 12 >/dev/null || exit 1
fi
for d in "$T"/hard/*.poly "$T"/random/*.poly; do
    "$FIRST" mesh "$d" -o "${d%.poly}.msh" --quiet >/dev/null 2>&1 || echo "quads_fields: cannot mesh $d" >&2
done
# set|input|extra options
{
    if [ $QUICK = 1 ]; then
        echo "bundled|shape:disk:3000|"
        echo "bundled|$DATA/lshape.msh|"
    else
        for f in annulus.msh lshape.msh plate_holes.msh square.obj; do echo "bundled|$DATA/$f|"; done
        for s in disk:3000 disk:8000 disk:20000 annulus:20000 lshape:20000 square:8000; do echo "bundled|shape:$s|"; done
        echo "bundled|shape:disk:16000|--size 0.1"
        echo "bundled|$DATA/plate_holes.msh|--size 0.12"
        echo "bundled|$DATA/annulus.msh|--size 0.15"
    fi
    for m in "$T"/hard/*.msh; do echo "hard|$m|"; done
    for m in "$T"/random/*.msh; do echo "random|$m|"; done
} >"$T/inputs.txt"
: >"$T/rows.txt"
echo "| binary | set | domain | field | quads | irregular | per 100 quads | SJ min | SJ / corner | repaired | valid | s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for b in "${BINS[@]}"; do
    name=${b%%=*}
    bin=${b#*=}
    while IFS='|' read -r set input extra; do
        for field in boundary cross; do
            rm -f "$T/s.json"
            t0=$(date +%s.%N)
            # shellcheck disable=SC2086
            "$bin" solve "$input" $extra --field "$field" --backend reference --quads "$T/q.obj" --allow-invalid \
                --stats "$T/s.json" --quiet >/dev/null 2>"$T/err.txt"
            rc=$?
            t1=$(date +%s.%N)
            label=$(basename "$input")
            [ -n "$extra" ] && label="$label $extra"
            if [ ! -s "$T/s.json" ]; then
                echo "| $name | $set | $label | $field | failed (exit $rc): $(head -c 150 "$T/err.txt") |"
                continue
            fi
            python3 - "$T/s.json" "$name" "$set" "$label" "$field" "$t0" "$t1" "$T/rows.txt" <<'PY'
import json, sys
q = json.load(open(sys.argv[1]))["quads"]
name, st, label, field, secs = sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5], float(sys.argv[7]) - float(sys.argv[6])
sj = q["scaled_jacobian"]
row = {"binary": name, "set": st, "domain": label, "field": field, "quads": q["quads"],
       "irregular": q["irregular_vertices"]["total"], "sj_min": sj["min"],
       "sj_corner": sj.get("min_of_corner_bound", sj["min"]),
       "repaired": q.get("origin", {}).get("repaired_share", 0.0), "valid": bool(q["valid"]), "seconds": secs}
open(sys.argv[8], "a").write(json.dumps(row) + "\n")
print("| %s | %s | %s | %s | %d | %d | %.1f | %.3f | %.3f | %.0f%% | %s | %.1f |" % (
    name, st, label, field, row["quads"], row["irregular"], 100.0 * row["irregular"] / max(1, row["quads"]),
    row["sj_min"], row["sj_corner"], 100 * row["repaired"], "yes" if row["valid"] else "no", secs))
PY
        done
    done <"$T/inputs.txt"
done
python3 - "$T/rows.txt" "$JSON" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
print("\n| binary | set | field | runs | valid | quads | irregular per 100 quads | SJ min (worst) | SJ min (median) | SJ / corner (worst) |")
print("|---|---|---|---|---|---|---|---|---|---|")
keys = sorted({(r["binary"], r["set"], r["field"]) for r in rows}, key=lambda k: (k[0], ["bundled", "hard", "random"].index(k[1]), k[2]))
for k in keys:
    rs = [r for r in rows if (r["binary"], r["set"], r["field"]) == k]
    nq = sum(r["quads"] for r in rs)
    ni = sum(r["irregular"] for r in rs)
    sjs = sorted(r["sj_min"] for r in rs)
    print("| %s | %s | %s | %d | %d | %d | %.1f | %.3f | %.3f | %.3f |" % (
        k[0], k[1], k[2], len(rs), sum(r["valid"] for r in rs), nq, 100.0 * ni / max(1, nq), sjs[0],
        sjs[len(sjs) // 2], min(r["sj_corner"] for r in rs)))
if sys.argv[2]:
    json.dump(rows, open(sys.argv[2], "w"), indent=1)
PY
