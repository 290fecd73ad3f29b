#!/usr/bin/env bash
# bench/gpu_check.sh: one prepared run of glpgp's OpenCL path on a GPU, sized
# for a short loan of a GPU machine (about 4 minutes on an H200, every step
# capped, 6 minutes at most): the cross-checks on a generated disk and on
# data/plate_holes.msh; the device's bandwidth and the per-operation ladder;
# Jacobi against multigrid per Newton step with the K-cycle on every level
# and with the launch-bound default (2000 nodes), and the multigrid with
# aggregates of ~8 on its coarse levels (--amg-coarse-passes 3: half the
# launches per cycle on the CPU shape); whole solves of the 1M
# square (u and v one after the other and at the same time, and Jacobi), the
# 4M square (default, and with --phase-sync: every phase's device work in its
# own time) and the 10M square, each with the statistics' phase shares
# (phases, solve_split: the host's share of the solve); the 1M solve's device
# time per kernel (GLPGP_CL_PROFILE=1); then summary.md, one table of it all.
# Everything is written to OUTDIR (log.txt, *.md, *.json, *.txt) as it goes,
# so a run cut short still leaves what it measured. bench/results/gpu_h200/
# holds the first such run and how to read it.
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

# the whole run's deadline: a step gets its cap or what is left of it, and
# none starts with less than 5 s left (DEADLINE_S, default 360)
END=$((SECONDS + ${DEADLINE_S:-360}))
step() { # CAP NAME STDOUT_FILE|- COMMAND...: run with a time cap, report rc and wall ms
    local cap=$1 name=$2 to=$3
    shift 3
    local left=$((END - SECONDS))
    if [ $left -lt 5 ]; then
        echo "=== $name skipped: the run's deadline"
        FAILED="$FAILED $name(skipped)"
        return 124
    fi
    [ $cap -le $left ] || cap=$left
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
    SQ10=shape:square:60000 PLATE_ARGS=--no-solve LADDER_ARGS="--repeat 1 --min-time 0 --stream-mb 8"
else
    DISK=shape:disk:20000 LADDER=64000,256000,1000000,4000000 PC=1000000
    SQ1=shape:square:1000000 SQ4=shape:square:4000000 SQ10=shape:square:10000000 PLATE_ARGS= LADDER_ARGS="--repeat 2"
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

step 45 crosscheck-disk - "$G" crosscheck "$DISK" --quiet
step 30 crosscheck-plate - "$G" crosscheck "$SRC/data/plate_holes.msh" --quiet $PLATE_ARGS
# whole solves: the statistics hold every phase (phases, solve_split); the
# step's wall_ms is the whole command's time
step 30 solve-square1m-amg-sequential - "$G" solve "$SQ1" --oscillators sequential --quiet \
    --stats "$OUT/square1m_amg_sequential.json"
# the default: u and v at the same time on a GPU (two command queues, two host threads)
step 30 solve-square1m-amg - "$G" solve "$SQ1" --quiet --stats "$OUT/square1m_amg.json"
cp "$OUT/square1m_amg.json" "$OUT/square1m_amg_concurrent.json" 2>/dev/null
step 30 solve-square1m-jacobi - "$G" solve "$SQ1" --precond jacobi --quiet --stats "$OUT/square1m_jacobi.json"
step 60 solve-square4m-amg - "$G" solve "$SQ4" --verbose --stats "$OUT/square4m_amg.json" \
    2>"$OUT/square4m_verbose_stderr.txt"
tail -n 8 "$OUT/square4m_verbose_stderr.txt"
step 90 solve-square10m-amg - "$G" solve "$SQ10" --quiet --stats "$OUT/square10m_amg.json"
step 60 solve-square4m-amg-phasesync - "$G" solve "$SQ4" --phase-sync --quiet \
    --stats "$OUT/square4m_amg_phasesync.json"
step 40 bench-ladder "$OUT/bench_ladder.md" "$B" --sizes "$LADDER" $LADDER_ARGS \
    --no-reference --no-cholmod --max-solve-vertices-opencl 1 --keep-pocl-cache --json "$OUT/bench_ladder.json"
grep -E "device bandwidth|^\| [0-9]+ \| [0-9]+ \|" "$OUT/bench_ladder.md"
for k in 0 auto; do
    step 40 "precond-1m-kcycle-$k" "$OUT/precond_1m_k$k.md" "$B" --precond both --sizes "$PC" --no-reference --no-cholmod --no-petsc \
        --newton-steps 2 --amg-kcycle-min "$k" --json "$OUT/precond_1m_k$k.json"
    grep -E "^per Newton step|^multigrid:" "$OUT/precond_1m_k$k.md"
done
# aggregates of ~8 on the coarse levels: fewer levels and launches per cycle
step 40 "precond-1m-passes3" "$OUT/precond_1m_p3.md" "$B" --precond amg --sizes "$PC" --no-reference --no-cholmod \
    --no-petsc --newton-steps 2 --amg-coarse-passes 3 --json "$OUT/precond_1m_p3.json"
grep -E "^multigrid:|^\| [0-9]+ \| amg \|" "$OUT/precond_1m_p3.md"
# device time per kernel (each launch waited for: slower, for the shares only)
GLPGP_CL_PROFILE=1 step 45 profile-square1m - "$G" solve "$SQ1" --verbose \
    --stats "$OUT/profile_square1m.json" 2>"$OUT/profile_square1m.txt"
grep -A12 "OpenCL profile" "$OUT/profile_square1m.txt" | head -30
# one table of the whole solves (python3; skipped without it)
if command -v python3 >/dev/null 2>&1; then
    python3 - "$OUT" >"$OUT/summary.md" <<'PYEOF'
import json, os, re, sys
d = sys.argv[1]
walls = {}
for line in open(os.path.join(d, "log.txt"), errors="replace"):
    m = re.match(r"=== (\S+) rc=(\d+) wall_ms=(\d+)", line)
    if m:
        walls[m.group(1)] = (int(m.group(2)), int(m.group(3)) / 1000.0)
rows = [("solve-square1m-amg-sequential", "square1m_amg_sequential.json"),
        ("solve-square1m-amg", "square1m_amg.json"), ("solve-square1m-jacobi", "square1m_jacobi.json"),
        ("solve-square4m-amg", "square4m_amg.json"), ("solve-square4m-amg-phasesync", "square4m_amg_phasesync.json"),
        ("solve-square10m-amg", "square10m_amg.json")]
print("| step | rc | whole command s | solve s | oscillators | Newton | CG | host share | top phases (s, of which wait) |")
print("|---|---|---|---|---|---|---|---|---|")
for step, f in rows:
    rc, wall = walls.get(step, (None, None))
    p = os.path.join(d, f)
    if not os.path.exists(p):
        print("| %s | %s | %s | - | - | - | - | - | (no statistics) |" % (step, rc, wall))
        continue
    j = json.load(open(p))
    ph = sorted(j.get("phases", {}).items(), key=lambda kv: -kv[1]["seconds"])[:6]
    top = ", ".join("%s %.2f (%.2f)" % (k, v["seconds"], v["wait"]) for k, v in ph)
    sp = j.get("solve_split", {})
    print("| %s | %s | %.2f | %.2f | %s | %d | %d | %.0f%% | %s |" % (
        step, rc, wall or 0.0, j["seconds"]["total"], j.get("oscillators"), j["newton_iterations"]["total"],
        j["cg_iterations"]["total"], 100.0 * sp.get("host_share", 0.0), top))
for name, title in (("k0", "K-cycle on levels of >= 0 nodes"), ("kauto", "K-cycle on levels of >= auto nodes"),
                    ("p3", "--amg-coarse-passes 3")):
    p = os.path.join(d, "precond_1m_%s.md" % name)
    if os.path.exists(p):
        print("\n%s (glpgp-bench --precond): " % title)
        for line in open(p):
            if line.startswith(("per Newton step", "multigrid:", "| 1 | amg |", "| 2 | amg |")):
                print("    " + line.rstrip())
PYEOF
    cat "$OUT/summary.md"
fi
echo
if [ -n "$FAILED" ]; then
    echo "gpu_check: FAILED steps:$FAILED; results in $OUT"
    exit 1
fi
echo "gpu_check: done; results in $OUT"
