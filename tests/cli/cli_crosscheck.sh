#!/usr/bin/env bash
# cli_crosscheck.sh: `glpgp crosscheck` end to end: passes (exit 0) on a
# generated disk and on data/annulus.msh, and fails (exit 1, QUAD assembly
# FAIL) when GLPGP_CL_CORRUPT=1 corrupts the OpenCL assembly; the disk run
# includes the sized QUAD assembly rows (set_size, both energies).
# Args: GLPGP_BINARY DATA_DIR. Skipped (77) without an fp64 OpenCL device.
. "$(dirname "$0")/lib.sh" "$@"
need_opencl_fp64

# 1. a generated disk, whole pipeline included: must pass
run_ok "crosscheck disk" crosscheck shape:disk:2000
expect_out "all stages PASS" "crosscheck disk"
for k in p1 transport; do # the local size field (set_size) on both backends, both energies
    expect_out "^QUAD assembly \($k, sized\) .*PASS" "crosscheck disk: sized QUAD assembly ($k)"
done

# 2. a file mesh with the transport energy (no whole solve): must pass
run_ok "crosscheck annulus.msh transport" crosscheck "$DATA/annulus.msh" --energy transport --no-solve
expect_out "all stages PASS" "crosscheck annulus.msh transport"

# 3. corrupted OpenCL assembly: must fail with exit 1 and a FAIL row for QUAD
runs=$((runs + 1))
GLPGP_CL_CORRUPT=1 "$GLPGP" crosscheck shape:disk:500 --no-solve >out.txt 2>err.txt </dev/null
rc=$?
[ "$rc" -eq 1 ] || fail "corrupted crosscheck exited $rc (expected 1)"
expect_out "^QUAD assembly .*FAIL" "corrupted crosscheck"

# 4. usage errors exit 2
run 2 "crosscheck without INPUT" crosscheck
run 2 "bad --energy" crosscheck shape:disk:500 --energy nope
finish
