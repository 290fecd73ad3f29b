#!/bin/bash
# cli_crosscheck.sh: `glpgp crosscheck` end to end: passes (exit 0) on a
# generated disk and on data/annulus.msh, and fails (exit 1, QUAD assembly
# FAIL) when GLPGP_CL_CORRUPT=1 corrupts the OpenCL assembly; the disk run
# includes the sized QUAD assembly rows (set_size, both energies).
# Args: GLPGP_BINARY DATA_DIR. Exit 77 (skip) if `glpgp devices` fails.
set -u
glpgp=$1
data=${2:-}
out=$(mktemp)
trap 'rm -f "$out"' EXIT
fail=0

if ! "$glpgp" devices >"$out" 2>&1; then
    echo "skipped: no OpenCL device"; cat "$out"; exit 77
fi
if ! grep -q "fp64 yes" "$out"; then
    echo "skipped: no OpenCL device with fp64"; cat "$out"; exit 77
fi

# 1. a generated disk, whole pipeline included: must pass
if "$glpgp" crosscheck shape:disk:2000 >"$out" 2>&1; then
    grep -q "all stages PASS" "$out" || { echo "FAIL: no PASS summary"; cat "$out"; fail=1; }
    # the local size field (set_size) on both backends, both energies
    for k in p1 transport; do
        grep -q "^QUAD assembly ($k, sized) .*PASS" "$out" ||
            { echo "FAIL: no passing sized QUAD assembly row for $k"; cat "$out"; fail=1; }
    done
else
    echo "FAIL: crosscheck shape:disk:2000 exited $?"; cat "$out"; fail=1
fi

# 2. a file mesh with the transport energy (no whole solve): must pass
if [ -n "$data" ] && [ -r "$data/annulus.msh" ]; then
    if ! "$glpgp" crosscheck "$data/annulus.msh" --energy transport --no-solve >"$out" 2>&1; then
        echo "FAIL: crosscheck annulus.msh --energy transport exited non-zero"; cat "$out"; fail=1
    fi
fi

# 3. corrupted OpenCL assembly: must fail with exit 1 and a FAIL row for QUAD
GLPGP_CL_CORRUPT=1 "$glpgp" crosscheck shape:disk:500 --no-solve >"$out" 2>&1
rc=$?
if [ "$rc" -ne 1 ]; then
    echo "FAIL: corrupted crosscheck exited $rc (expected 1)"; cat "$out"; fail=1
elif ! grep -q "^QUAD assembly .*FAIL" "$out"; then
    echo "FAIL: corrupted crosscheck did not flag QUAD assembly"; cat "$out"; fail=1
fi

# 4. usage errors exit 2
"$glpgp" crosscheck >/dev/null 2>&1; rc=$?
[ "$rc" -eq 2 ] || { echo "FAIL: crosscheck without INPUT exited $rc (expected 2)"; fail=1; }
"$glpgp" crosscheck shape:disk:500 --energy nope >/dev/null 2>&1; rc=$?
[ "$rc" -eq 2 ] || { echo "FAIL: bad --energy exited $rc (expected 2)"; fail=1; }

[ "$fail" -eq 0 ] && echo "cli_crosscheck: all checks passed"
exit $fail
