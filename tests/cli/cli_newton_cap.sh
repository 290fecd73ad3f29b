#!/usr/bin/env bash
# cli_newton_cap.sh: an eps level stopped at the Newton cap is reported, never
# passed off as converged: a vortex disk (3k vertices, h = 10 mean edges)
# with --newton-max 2, with both globalizations. Checks: exit 0 with a
# warning line naming the cap, and the statistics JSON has capped = true on
# a level and converged.all = false; the same solve without the cap has no
# such warning and converged.all = true.
# The plateau stop (--newton-ftol): the coupled oscillators of a torus
# (shape:torus:6000 --faces 225, reference backend) reach |g| ~ 1e-4 |g0| and
# then creep along a near-flat direction, E + P falling by about 1e-9 of
# itself per step; without the stop the last level runs to the cap of 50
# (58 Newton steps, a warning).
# Checks: no cap warning, a `plateau` line in the summary, that level
# `stalled` after 20 steps with |g| <= 1e-3 |g0|, every other level converged
# by |g| (not stalled), all quads valid.
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
if [ "$have_python" -eq 1 ]; then
    python3 - free.json <<'PY' || fail "disk: a level that converges by |g| reported stalled"
import json, sys
d = json.load(open(sys.argv[1]))
assert not any(l["stalled"] for o in "uv" for l in d["eps_schedule"][o])
PY
fi

run_ok "plateau" solve shape:torus:6000 --faces 225 --backend reference --stats plateau.json --quads plateau.obj
if grep -qi "Newton cap" err.txt; then fail "plateau: the level ran to the Newton cap"; fi
expect_out "plateau +1 eps level" "plateau: the summary names the stopped level"
if [ "$have_python" -eq 1 ]; then
    python3 - plateau.json <<'PY' || fail "plateau: the torus's last level was not stopped by the plateau test"
import json, sys
d = json.load(open(sys.argv[1]))
u = d["eps_schedule"]["u"]
last = u[-1]
assert last["stalled"] and not last["capped"], last
assert 20 <= last["newton"] <= 25, last["newton"]
assert last["grad"] <= 1e-3 * last["grad0"], (last["grad"], last["grad0"])
assert not any(l["stalled"] or l["capped"] for l in u[:-1]), u
assert d["converged"]["all"], d["converged"]
assert d["options"]["newton_ftol"] == 1e-8, d["options"]
q = d["quads"]
assert q["valid"] and q["faces"] == q["quads"] and q["faces"] > 150, q
PY
fi
finish
