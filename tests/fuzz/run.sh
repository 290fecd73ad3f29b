#!/usr/bin/env bash
# tests/fuzz/run.sh: run every libFuzzer harness of tests/fuzz for a while.
#
#   bash tests/fuzz/run.sh [BUILD_DIR [SECONDS [HARNESS...]]]
#
# BUILD_DIR (default build-fuzz) is configured and built first when it has
# no harnesses yet: CC=clang CXX=clang++ cmake -DGLPGP_FUZZ=ON
# -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGLPGP_WITH_OPENCL=OFF
# -DGLPGP_BUILD_BENCH=OFF. Each harness (default: all) runs SECONDS seconds
# (default 10) on one core, starting from its seed corpus tests/fuzz/corpus/NAME
# (read only) plus a working corpus BUILD_DIR/fuzz/corpus/NAME (kept between
# runs, so longer campaigns resume); crashes, leaks and timeouts (10 s per
# input) land in BUILD_DIR/fuzz/artifacts/NAME/. The log of each harness is
# BUILD_DIR/fuzz/NAME.log. Prints one line per harness (executions, corpus
# size, artifacts) and exits 1 when any harness found something.
# GLPGP_FUZZ_GMSH=1 in the environment makes fuzz_contour mesh with Gmsh too.
set -u
cd "$(dirname "${BASH_SOURCE[0]}")/../.." || exit 1
ROOT=$(pwd)
BUILD=${1:-build-fuzz}
SECS=${2:-10}
shift 2 2>/dev/null || shift $#
HARNESSES=("$@")
if [ ${#HARNESSES[@]} -eq 0 ]; then
    for f in tests/fuzz/fuzz_*.c; do
        n=$(basename "$f" .c)
        HARNESSES+=("${n#fuzz_}")
    done
fi

if [ ! -x "$BUILD/tests/fuzz/fuzz_${HARNESSES[0]}" ]; then
    echo "==> configuring and building $BUILD (clang, libFuzzer, ASan + UBSan)"
    # the logs inside BUILD_DIR (ignored by git), never beside the sources
    mkdir -p "$BUILD"
    CC=${CC:-clang} CXX=${CXX:-clang++} cmake -S . -B "$BUILD" -DGLPGP_FUZZ=ON \
        -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGLPGP_WITH_OPENCL=OFF -DGLPGP_BUILD_BENCH=OFF \
        >"$BUILD/configure.log" 2>&1 || { cat "$BUILD/configure.log"; exit 1; }
    cmake --build "$BUILD" -j2 >"$BUILD/build.log" 2>&1 || { tail -30 "$BUILD/build.log"; exit 1; }
fi

# LeakSanitizer: PoCL/LLVM are not linked in this build (no OpenCL); the
# image modules' libraries (OpenImageIO, Gmsh) keep process-lifetime caches
# intercept_tls_get_addr=0: see tests/CMakeLists.txt (LeakSanitizer tracer crash)
export LSAN_OPTIONS="suppressions=$ROOT/tests/lsan.supp:print_suppressions=0:intercept_tls_get_addr=0"
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}intercept_tls_get_addr=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# the harnesses' scratch files (and the writers' fsync) on tmpfs when there is one
if [ -z "${TMPDIR:-}" ] && [ -d /dev/shm ] && [ -w /dev/shm ]; then export TMPDIR=/dev/shm; fi
found=0
for h in "${HARNESSES[@]}"; do
    bin="$BUILD/tests/fuzz/fuzz_$h"
    [ -x "$bin" ] || { echo "fuzz_$h: no binary $bin"; found=1; continue; }
    work="$BUILD/fuzz/corpus/$h"
    art="$BUILD/fuzz/artifacts/$h"
    mkdir -p "$work" "$art"
    log="$BUILD/fuzz/$h.log"
    # fuzz_image runs OpenImageIO, which keeps per-thread error strings that
    # LeakSanitizer's fast unwinder cannot attribute (and full unwinding makes
    # it 20 times slower): no leak detection there (the other harnesses and
    # the sanitizer build of .ci/run cover the glpgp code it calls)
    leaks=1
    [ "$h" = image ] && leaks=0
    ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=$leaks" "$bin" -detect_leaks=$leaks -max_total_time="$SECS" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
        -artifact_prefix="$art/" -print_final_stats=1 "$work" "tests/fuzz/corpus/$h" >"$log" 2>&1
    rc=$?
    execs=$(grep -m1 -E '^stat::number_of_executed_units' "$log" | awk '{print $2}')
    nart=$(find "$art" -type f | wc -l)
    ncorp=$(find "$work" -type f | wc -l)
    printf 'fuzz_%-9s %8s executions in %ss, corpus %5d, artifacts %d%s\n' "$h" "${execs:-?}" "$SECS" \
        "$ncorp" "$nart" "$([ $rc -ne 0 ] && echo " (exit $rc, see $log)")"
    [ "$rc" -eq 0 ] && [ "$nart" -eq 0 ] || found=1
done
exit $found
