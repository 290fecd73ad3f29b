#!/usr/bin/env bash
# cli_newton_cap.sh: an eps level stopped at the Newton cap is reported, never
# passed off as converged: a vortex disk (3k vertices, h = 10 mean edges)
# with --newton-max 2, with both globalizations. Checks: exit 0 with a
# warning line naming the cap, and the statistics JSON has capped = true on
# a level and converged.all = false; the same solve without the cap has no
# such warning and converged.all = true.
# Usage: bash cli_newton_cap.sh <path-to-glpgp> <data-dir>
. "$(dirname "$0")/lib.sh" "$@"

have_python=0
if command -v python3 >/dev/null 2>&1; then have_python=1; fi
json_capped() { # FILE WANT(0|1): some level capped and converged.all false iff WANT
    [ "$have_python" -eq 1 ] || { echo "note: python3 not found, JSON check skipped"; return 0; }
    python3 - "$1" "$2" <<'PY' || fail "JSON $1: capped flags do not say what happened (want $2)"
import json, sys
d = json.load(open(sys.argv[1]))
want = sys.argv[2] == "1"
capped = any(l["capped"] for o in "uv" for l in d["eps_schedule"][o])
assert capped == want, ("capped", capped)
assert d["converged"]["all"] == (not want), d["converged"]
assert (d["converged"]["capped_levels_u"] + d["converged"]["capped_levels_v"] > 0) == want
PY
}

for g in trust-region line-search; do
    run_ok "$g capped" solve shape:disk:3000 --size 0.4 --backend reference --globalization "$g" \
        --newton-max 2 --stats capped.json
    expect_err "warning: .*stopped at the Newton cap of 2 steps" "$g capped"
    json_capped capped.json 1
done
run_ok "uncapped" solve shape:disk:3000 --size 0.4 --backend reference --stats free.json
if grep -qi "Newton cap" err.txt; then fail "uncapped: unexpected cap warning"; fi
json_capped free.json 0
finish
