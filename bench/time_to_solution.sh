#!/usr/bin/env bash
# bench/time_to_solution.sh: issue 32's CPU targets in one run, one after the
# other on this machine (results: bench/results/time_to_solution.md):
#   1. a multigrid iteration against a Jacobi-CG iteration at 1M vertices
#      (glpgp-bench --precond both, h = 10 mean edges, one Newton step, OpenCL);
#   2. the 107k-vertex CAD part (the motor lamination of glpgp-domains,
#      meshed by Gmsh's Delaunay) solved with the multigrid and with
#      --precond jacobi (needs Gmsh);
#   3. whole commands `glpgp solve shape:square:N` at 1M and 4M vertices,
#      interleaved 1M, 4M, 1M (wall and CPU seconds, the 4M / 1M ratio);
#   4. the phases the statistics name (every solve above);
#   5. with PETSc: the 1M square on the reference backend, on one PETSc rank
#      and on two (--globalization line-search, as bench/petsc_scaling.sh).
# Usage: bash bench/time_to_solution.sh [BUILD_DIR [OUTDIR]] [--quick] [--no-petsc]
#   --quick: 64k / 256k instead of 1M / 4M, the CAD part at 20 edges per H
#   (seconds: a check that the script works).
set -u
QUICK=0 PETSC=1 POS=()
for a in "$@"; do
    case "$a" in
    --quick) QUICK=1 ;;
    --no-petsc) PETSC=0 ;;
    *) POS+=("$a") ;;
    esac
done
BUILD=${POS[0]:-build}
OUT=${POS[1]:-tts-$(date +%Y%m%d-%H%M%S)}
G=$BUILD/glpgp B=$BUILD/bench/glpgp-bench D=$BUILD/bench/glpgp-domains
[ -x "$G" ] && [ -x "$B" ] || { echo "time_to_solution: $G or $B missing (build first)" >&2; exit 2; }
mkdir -p "$OUT" || exit 1
exec > >(tee "$OUT/log.txt") 2>&1
export POCL_CACHE_DIR=${POCL_CACHE_DIR:-$BUILD/pocl-cache}
if [ $QUICK -eq 1 ]; then N1=64000 N4=256000 PC=64000 CADN=20; else N1=1000000 N4=4000000 PC=1000000 CADN=40; fi
TIME=/usr/bin/time
[ -x $TIME ] || { echo "time_to_solution: /usr/bin/time missing" >&2; exit 2; }
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2), load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "commit: $(git -C "$(dirname "$0")/.." rev-parse --short HEAD 2>/dev/null)"

# run NAME CMD...: wall / user / sys seconds and peak RSS into $OUT/NAME.time
run() {
    local name=$1
    shift
    echo "=== $name: $*"
    $TIME -f "%e %U %S %M" -o "$OUT/$name.time" "$@" >"$OUT/$name.out" 2>"$OUT/$name.err"
    local rc=$?
    echo "=== $name rc=$rc wall/user/sys/maxrss_kb: $(cat "$OUT/$name.time" | tail -1)"
}

# 1. the ladder: ms per iteration of both preconditioners, one run
run ladder "$B" --precond both --sizes $PC --precond-h edges --newton-steps 1 --no-reference --no-petsc \
    --no-cholmod --keep-pocl-cache --json "$OUT/ladder.json"
grep -E "^\| 1 \||^per Newton" "$OUT/ladder.out"

# 2. the CAD part
if [ -x "$D" ] && "$G" --version | grep -q "Gmsh: yes"; then
    "$D" 1 $CADN "$OUT" motor >/dev/null 2>&1 &&
        "$G" mesh "$OUT/motor.poly" -o "$OUT/motor.msh" --algorithm delaunay >/dev/null 2>&1
    run cad_amg "$G" solve "$OUT/motor.msh" --stats "$OUT/cad_amg.json"
    run cad_jacobi "$G" solve "$OUT/motor.msh" --precond jacobi --stats "$OUT/cad_jacobi.json"
else
    echo "time_to_solution: no glpgp-domains or Gmsh: the CAD part skipped"
fi

# 3. whole commands, interleaved
run square1m_a "$G" solve shape:square:$N1 --stats "$OUT/square1m_a.json"
run square4m "$G" solve shape:square:$N4 --stats "$OUT/square4m.json"
run square1m_b "$G" solve shape:square:$N1 --stats "$OUT/square1m_b.json"

# 5. PETSc against the reference backend
if [ $PETSC -eq 1 ] && "$G" --version | grep -q "PETSc: yes" && command -v mpirun >/dev/null 2>&1; then
    MPI="mpirun --oversubscribe"
    [ "$(id -u)" = 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    run ref1m "$G" solve shape:square:$N1 --backend reference --globalization line-search --oscillators sequential \
        --stats "$OUT/ref1m.json"
    run petsc1 $MPI -n 1 "$G" solve shape:square:$N1 --backend petsc --globalization line-search \
        --stats "$OUT/petsc1.json"
    run petsc2 $MPI -n 2 "$G" solve shape:square:$N1 --backend petsc --globalization line-search \
        --stats "$OUT/petsc2.json"
fi

# the table
python3 - "$OUT" >"$OUT/summary.md" <<'PYEOF'
import json, os, sys
d = sys.argv[1]
def tm(n):
    p = os.path.join(d, n + ".time")
    if not os.path.exists(p): return None
    w, u, s, m = open(p).read().split()[-4:]
    return float(w), float(u) + float(s), int(m) / 1024.0
def st(n):
    p = os.path.join(d, n + ".json")
    return json.load(open(p)) if os.path.exists(p) else None
print("| run | wall s | CPU s | max RSS MiB | solve s | Newton | CG | phases named | host share |")
print("|---|---|---|---|---|---|---|---|---|")
for n in ("cad_amg", "cad_jacobi", "square1m_a", "square4m", "square1m_b", "ref1m", "petsc1", "petsc2"):
    t, s = tm(n), st(n)
    if not t: continue
    if s:
        named = len([k for k, v in s.get("phases", {}).items() if v["seconds"] > 0])
        print("| %s | %.1f | %.1f | %.0f | %.1f | %d | %d | %d | %.0f%% |" % (n, t[0], t[1], t[2], s["seconds"]["total"],
              s["newton_iterations"]["total"], s["cg_iterations"]["total"], named,
              100 * s.get("solve_split", {}).get("host_share", 0)))
    else:
        print("| %s | %.1f | %.1f | %.0f | - | - | - | - | - |" % (n, t[0], t[1], t[2]))
l = json.load(open(os.path.join(d, "ladder.json")))
for c in l.get("precond_ladder", []):
    j, a = c.get("jacobi"), c.get("amg")
    if j and a:
        mj = j["per_step"][0]["solve_s"] / j["per_step"][0]["cg"]
        ma = a["per_step"][0]["solve_s"] / a["per_step"][0]["cg"]
        print("\nladder, %d vertices (%s): Jacobi %.1f ms per iteration (%d it), multigrid %.1f ms (%d it): "
              "a multigrid iteration = %.2f Jacobi iterations" % (c["vertices"], c.get("h_case", ""), 1e3 * mj,
              j["per_step"][0]["cg"], 1e3 * ma, a["per_step"][0]["cg"], ma / mj))
def ratio(a, b, what):
    ta, tb = tm(a), tm(b)
    if ta and tb: print("%s: %.2f (wall), %.2f (CPU)" % (what, ta[0] / tb[0], ta[1] / tb[1]))
ratio("cad_jacobi", "cad_amg", "CAD part, Jacobi / multigrid")
t1 = [tm(n) for n in ("square1m_a", "square1m_b") if tm(n)]
if tm("square4m") and t1:
    w1 = sum(x[0] for x in t1) / len(t1); c1 = sum(x[1] for x in t1) / len(t1)
    print("4M / 1M whole command: %.2f (wall), %.2f (CPU)" % (tm("square4m")[0] / w1, tm("square4m")[1] / c1))
ratio("petsc1", "ref1m", "PETSc 1 rank / reference")
ratio("petsc1", "petsc2", "PETSc 2 ranks speed-up over 1")
PYEOF
cat "$OUT/summary.md"
