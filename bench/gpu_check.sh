#!/usr/bin/env bash
# bench/gpu_check.sh: one prepared run of glpgp's OpenCL path on a GPU, sized
# for a short loan of a GPU machine (about 3-4 minutes on an H200): the
# cross-checks on a generated disk and on data/plate_holes.msh, the device's
# bandwidth and the per-operation ladder, Jacobi against multigrid per Newton
# step with the K-cycle on every level and with the launch-bound default, and
# whole solves of the 1M and 4M squares (1M also with u and v concurrent). Every step has its own time cap;
# everything is written to OUTDIR (log.txt, *.md, *.json) as it goes, so a
# run cut short still leaves what it measured. bench/results/gpu_h200/ holds
# the first such run and how to read it.
#
# Usage: bash bench/gpu_check.sh [--smoke] [BUILD_DIR [OUTDIR]]
#   --smoke:   the same steps on small sizes (seconds, any OpenCL device; ctest
#              runs it through tests/cli/cli_bench.sh so the script cannot rot
#              between GPU loans)
#   BUILD_DIR: holds glpgp and bench/glpgp-bench (default: build)
#   OUTDIR:    default: gpu-check-<date>
# Exit status: 0 when every step succeeded, 1 otherwise (the log names it).
# Environment: GLPGP_DEVICE picks the device (default: the first GPU listed
# by `glpgp devices`, else the first fp64 device).
#
# The NVIDIA driver's OpenCL library must be known to the ICD loader. When no
# NVIDIA platform is listed but libnvidia-opencl.so.1 is found (a driver
# mounted into a container, e.g. /usr/local/nvidia/lib64), the script
# registers it through OCL_ICD_VENDORS, a directory of its own that lists
# that library alone.
set -u
SMOKE=0
if [ "${1:-}" = --smoke ]; then
    SMOKE=1
    shift
fi
BUILD=${1:-build}
OUT=${2:-gpu-check-$(date +%Y%m%d-%H%M%S)}
SRC=$(cd "$(dirname "$0")/.." && pwd)
G=$BUILD/glpgp
B=$BUILD/bench/glpgp-bench
[ -x "$G" ] && [ -x "$B" ] || { echo "gpu_check: $G or $B missing (build first)" >&2; exit 2; }
mkdir -p "$OUT" || exit 1
exec > >(tee "$OUT/log.txt") 2>&1

step() { # CAP NAME STDOUT_FILE|- COMMAND...: run with a time cap, report rc and wall ms
    local cap=$1 name=$2 to=$3
    shift 3
    echo
    local redir=""
    [ "$to" = - ] || redir=" > $to"
    echo "=== $name (cap ${cap}s): $*$redir"
    local t0
    t0=$(date +%s%N)
    if [ "$to" = - ]; then timeout "$cap" "$@"; else timeout "$cap" "$@" >"$to"; fi
    local rc=$?
    [ $rc -eq 0 ] || FAILED="$FAILED $name"
    echo "=== $name rc=$rc wall_ms=$((($(date +%s%N) - t0) / 1000000))"
    return $rc
}

FAILED=""
# sizes: the loan's, or seconds-long ones for --smoke
if [ $SMOKE -eq 1 ]; then
    DISK=shape:disk:4000 LADDER=4000,8000 PC=8000 SQ1=shape:square:20000 SQ4=shape:square:40000
else
    DISK=shape:disk:20000 LADDER=64000,256000,1000000,4000000 PC=1000000
    SQ1=shape:square:1000000 SQ4=shape:square:4000000
fi

command -v nvidia-smi >/dev/null 2>&1 &&
    nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm,clocks.max.mem --format=csv
echo "host: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"

if ! "$G" devices 2>/dev/null | grep -qi nvidia; then
    for lib in /usr/local/nvidia/lib64/libnvidia-opencl.so.1 /usr/lib/x86_64-linux-gnu/libnvidia-opencl.so.1 \
        /usr/lib64/libnvidia-opencl.so.1; do
        if [ -e "$lib" ]; then
            mkdir -p "$OUT/icd"
            echo "$lib" >"$OUT/icd/nvidia.icd"
            export OCL_ICD_VENDORS=$OUT/icd
            export LD_LIBRARY_PATH=$(dirname "$lib")${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
            echo "gpu_check: registered $lib through OCL_ICD_VENDORS=$OCL_ICD_VENDORS"
            break
        fi
    done
fi
"$G" devices | tee "$OUT/devices.txt"
if [ -z "${GLPGP_DEVICE:-}" ]; then
    gpu=$(grep -E "^  device [0-9]+:" -A1 "$OUT/devices.txt" | grep -B1 "| GPU" | grep -oE "^  device [0-9]+" |
        head -1 | grep -oE "[0-9]+")
    if [ -n "$gpu" ]; then export GLPGP_DEVICE=$gpu; else echo "gpu_check: no GPU listed; using the default device"; fi
fi
echo "GLPGP_DEVICE=${GLPGP_DEVICE:-default}"

step 60 crosscheck-disk - "$G" crosscheck "$DISK" --quiet
step 60 crosscheck-plate - "$G" crosscheck "$SRC/data/plate_holes.msh" --quiet
step 60 bench-ladder "$OUT/bench_ladder.md" "$B" --sizes "$LADDER" --repeat 2 \
    --no-reference --no-cholmod --max-solve-vertices-opencl 1 --json "$OUT/bench_ladder.json"
grep -E "device bandwidth|^\| [0-9]+ \| [0-9]+ \|" "$OUT/bench_ladder.md"
for k in 0 auto; do
    step 60 "precond-1m-kcycle-$k" "$OUT/precond_1m_k$k.md" "$B" --precond both --sizes "$PC" --no-reference --no-cholmod --no-petsc \
        --newton-steps 2 --amg-kcycle-min "$k" --json "$OUT/precond_1m_k$k.json"
    grep -E "^per Newton step|^multigrid:" "$OUT/precond_1m_k$k.md"
done
step 40 solve-square1m-amg - "$G" solve "$SQ1" --quiet --stats "$OUT/square1m_amg.json"
# u and v at the same time (two command queues from two host threads): not
# measured on a GPU yet, so auto keeps them sequential there
step 40 solve-square1m-amg-concurrent - "$G" solve "$SQ1" --oscillators concurrent --quiet \
    --stats "$OUT/square1m_amg_concurrent.json"
step 40 solve-square1m-jacobi - "$G" solve "$SQ1" --precond jacobi --quiet --stats "$OUT/square1m_jacobi.json"
step 60 solve-square4m-amg - "$G" solve "$SQ4" --quiet --stats "$OUT/square4m_amg.json"
echo
if [ -n "$FAILED" ]; then
    echo "gpu_check: FAILED steps:$FAILED; results in $OUT"
    exit 1
fi
echo "gpu_check: done; results in $OUT"
