#!/usr/bin/env bash
# subdir_consumer.sh: glpgp used from another project's build through
# add_subdirectory() (tests/install/subdir): the parent configures with
# glpgp's tests and bench off by default, builds only what the consumer
# links (the reference-only configuration, to stay short), and the consumer
# solves a square with no singularity.
# Usage: bash subdir_consumer.sh <cmake> <glpgp-source-dir> [cmake args...]
set -u
CMAKE=${1:?usage: subdir_consumer.sh <cmake> <glpgp-source-dir> [cmake args]}
SRC=${2:?glpgp source dir}
shift 2
T=$(mktemp -d "${TMPDIR:-/tmp}/glpgp_subdir.XXXXXX")
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
"$CMAKE" -S "$SRC/tests/install/subdir" -B "$T/b" -DGLPGP_SOURCE="$SRC" -DCMAKE_BUILD_TYPE=Release \
    -DGLPGP_WITH_OPENCL=OFF -DGLPGP_WITH_IMAGES=OFF -DGLPGP_WITH_PETSC=OFF "$@" >"$T/configure.log" 2>&1 ||
    fail "configure: $(tail -c 1500 "$T/configure.log")"
grep -q "GLPGP_BUILD_TESTS:BOOL=OFF" "$T/b/CMakeCache.txt" || fail "glpgp's tests are on in a subproject"
[ -e "$T/b/glpgp/tests" ] && fail "glpgp's tests were configured in a subproject"
"$CMAKE" --build "$T/b" --target consumer -j2 >"$T/build.log" 2>&1 || fail "build: $(tail -c 1500 "$T/build.log")"
out=$("$T/b/consumer") || fail "consumer failed: $out"
echo "$out"
case "$out" in *", ok") ;; *) fail "consumer: $out" ;; esac
echo "subdir_consumer: passed"
