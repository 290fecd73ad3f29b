#!/usr/bin/env bash
# cli_dist_lib.sh: the distributed solve as a library call (tests/io/dist_solve.c,
# glpgp_solve_distributed) on one rank and under mpirun -n 2. Skipped (77)
# without PETSc or mpirun. Usage: cli_dist_lib.sh GLPGP_BINARY DATA_DIR
set -u
BIN_DIR=$(dirname "$1")
PROG="$BIN_DIR/tests/dist_solve"
[ -x "$PROG" ] || PROG="$BIN_DIR/dist_solve"
[ -x "$PROG" ] || { echo "cli_dist_lib: no dist_solve next to $1"; exit 1; }
command -v mpirun >/dev/null 2>&1 || { echo "cli_dist_lib: SKIPPED: no mpirun"; exit 77; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=${OMPI_MCA_btl_vader_single_copy_mechanism:-none}
T=$(mktemp -d "${TMPDIR:-/tmp}/glpgp_dist_lib.XXXXXX")
trap 'rm -rf "$T"' EXIT
mkdir -p "$T/one" "$T/two"
"$PROG" "$T/one"; rc=$?
[ "$rc" -eq 77 ] && exit 77
[ "$rc" -eq 0 ] || { echo "cli_dist_lib: one rank: exit $rc"; exit 1; }
timeout 240 mpirun --oversubscribe -n 2 "$PROG" "$T/two" || { echo "cli_dist_lib: mpirun -n 2: exit $?"; exit 1; }
[ -f "$T/two/d1.pvtu" ] && [ -f "$T/two/d1_p1.vtu" ] || { echo "cli_dist_lib: no pieces"; exit 1; }
echo "cli_dist_lib: ok"
