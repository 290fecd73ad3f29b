#!/usr/bin/env bash
# bench/petsc_scaling.sh: strong scaling of the PETSc backend (1 -> P ranks)
# beside the OpenCL and reference backends, whole GL solves, in one run.
#
#   bash bench/petsc_scaling.sh [--sizes 1000000,4000000] [--ranks 1,2]
#        [--shape square] [--glpgp build/glpgp] [--out bench/results/petsc_scaling]
#        [--globalization line-search] [--no-opencl] [--no-reference]
#        [--solver-args "--newton-max 2 --cg-max 100"] [--compare OTHER_GLPGP] [--gamg]
#
# Per size N (input shape:SHAPE:N, the same mesh for every run), one whole
# `glpgp solve` per configuration: --backend reference, --backend opencl
# (skipped when no OpenCL device answers), --backend petsc under
# `mpirun -n P` for each P of --ranks. Every run uses the backend's default
# preconditioner (glpgp's multigrid; on petsc on each rank's rows, block
# Jacobi across ranks) and the same --globalization
# (line-search by default: the multigrid / GAMG then runs in every Newton
# step). Recorded per run: wall time of the process (mpirun included), CPU
# time (user + sys of all processes), the solve's own time, Newton and CG
# iterations, singularity counts, final energies, and memory: max RSS of the
# process (/usr/bin/time), per rank for petsc (stats JSON per_rank).
# Writes OUT.json (every run) and OUT.md (one table, speed-ups of P ranks
# over 1 rank by solve time; $PETSC_OPTIONS, which every rank inherits, is
# recorded). --solver-args: more options for every solve
# (e.g. a capped continuation for a memory series: the peak memory is set by
# the system, the matrices and the preconditioner, built alike however many
# steps run). --compare: a second glpgp (e.g. a build of an earlier commit)
# whose petsc runs follow each of this one's, named "petscP (compare)" --
# a before / after series in one run. --gamg: after each petsc run the same
# with PETSc's GAMG (PETSC_OPTIONS="-glpgp_mg gamg"), named "petscP (gamg)".
# Benchmarks, not tests: nothing is asserted.
# As root, OpenMPI needs OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# (set here); --oversubscribe lets P exceed the cores.
set -euo pipefail

SIZES=1000000,4000000
RANKS=1,2
SHAPE=square
GLPGP=build/glpgp
OUT=bench/results/petsc_scaling
GLOB=line-search
OPENCL=1
REFERENCE=1
EXTRA=""
COMPARE=""
GAMG=0
while [ $# -gt 0 ]; do
    case "$1" in
    --sizes) SIZES=$2; shift 2 ;;
    --ranks) RANKS=$2; shift 2 ;;
    --shape) SHAPE=$2; shift 2 ;;
    --glpgp) GLPGP=$2; shift 2 ;;
    --out) OUT=$2; shift 2 ;;
    --globalization) GLOB=$2; shift 2 ;;
    --no-opencl) OPENCL=0; shift ;;
    --no-reference) REFERENCE=0; shift ;;
    --solver-args) EXTRA=$2; shift 2 ;;
    --compare) COMPARE=$2; shift 2 ;;
    --gamg) GAMG=1; shift ;;
    -h | --help) sed -n '2,32p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "petsc_scaling.sh: unknown argument '$1'" >&2; exit 2 ;;
    esac
done
"$GLPGP" --version | grep -q "PETSc: yes" || { echo "petsc_scaling.sh: $GLPGP was built without PETSc" >&2; exit 1; }
command -v mpirun >/dev/null || { echo "petsc_scaling.sh: no mpirun (openmpi-bin)" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# containers often forbid the cross-memory attach of OpenMPI's shared-memory transport
export OMPI_MCA_btl_vader_single_copy_mechanism=${OMPI_MCA_btl_vader_single_copy_mechanism:-none}
export POCL_CACHE_DIR=${POCL_CACHE_DIR:-$PWD/build/pocl-cache}
mkdir -p "$(dirname "$OUT")" "$POCL_CACHE_DIR"
W=$(mktemp -d "${TMPDIR:-/tmp}/glpgp_petsc_scaling.XXXXXX")
trap 'rm -rf "$W"' EXIT

runs=()
# one NAME NP CMD...: run CMD, record time / CPU / RSS and the stats JSON
one() {
    local name=$1 np=$2
    shift 2
    echo "== $name: $*" >&2
    # shellcheck disable=SC2086 # EXTRA: several options
    if /usr/bin/time -f "%e %U %S %M" -o "$W/$name.time" "$@" --stats "$W/$name.json" \
        --globalization "$GLOB" $EXTRA >"$W/$name.out" 2>"$W/$name.err" </dev/null; then
        runs+=("$name:$np")
        tail -3 "$W/$name.out" >&2
    else
        echo "   failed: $(tail -2 "$W/$name.err")" >&2
    fi
}

IFS=, read -r -a sizes <<<"$SIZES"
IFS=, read -r -a ranks <<<"$RANKS"
for n in "${sizes[@]}"; do
    in=shape:$SHAPE:$n
    [ "$REFERENCE" = 1 ] && one "ref_$n" 0 "$GLPGP" solve "$in" --backend reference
    if [ "$OPENCL" = 1 ] && "$GLPGP" devices >/dev/null 2>&1; then
        one "ocl_$n" 0 "$GLPGP" solve "$in" --backend opencl
    fi
    for p in "${ranks[@]}"; do
        one "petsc${p}_$n" "$p" mpirun --oversubscribe -n "$p" "$GLPGP" solve "$in" --backend petsc
        [ -n "$COMPARE" ] &&
            one "petsc${p}compare_$n" "$p" mpirun --oversubscribe -n "$p" "$COMPARE" solve "$in" --backend petsc
        [ "$GAMG" = 1 ] && PETSC_OPTIONS="${PETSC_OPTIONS:-} -glpgp_mg gamg" \
            one "petsc${p}gamg_$n" "$p" mpirun --oversubscribe -n "$p" "$GLPGP" solve "$in" --backend petsc
    done
done

python3 - "$W" "$OUT" "$SHAPE" "$GLOB" "$(uptime)" "$EXTRA" "$COMPARE" "${runs[@]}" <<'EOF'
import json, os, sys, platform
w, out, shape, glob, load, extra, compare = sys.argv[1:8]
rows = []
for tag in sys.argv[8:]:
    name, np = tag.rsplit(":", 1)
    d = json.load(open(os.path.join(w, name + ".json")))
    wall, user, sys_, rss = open(os.path.join(w, name + ".time")).read().split()[:4]
    kind, n = name.split("_", 1)
    r = {
        "run": kind, "ranks": int(np) if int(np) > 0 else None, "vertices": d["vertices"],
        "input": d["input"], "backend": d["backend"], "wall_s": float(wall),
        "cpu_s": float(user) + float(sys_), "solve_s": d["seconds"]["total"],
        "newton": d["newton_iterations"]["total"], "cg": d["cg_iterations"]["total"],
        "singularities": d["singularities"], "final_energy": d["final_energy"],
        "max_rss_mib": float(rss) / 1024.0,
    }
    if "per_rank" in d:
        r["per_rank"] = d["per_rank"]
        r["max_rss_mib_per_rank"] = max(x["max_rss_mib"] for x in d["per_rank"])
    rows.append(r)
meta = {"shape": shape, "globalization": glob, "solver_args": extra, "compare": compare,
        "petsc_options": os.environ.get("PETSC_OPTIONS", ""),
        "machine": platform.node(), "cpus": os.cpu_count(),
        "load_at_end": load.strip(), "note": "shared machine: compare runs within this file only"}
if compare:
    lines_compare = f"(compare): the petsc runs of {compare}"
else:
    lines_compare = ""
json.dump({"meta": meta, "runs": rows}, open(out + ".json", "w"), indent=1)
base = {}
for r in rows:
    if r["run"] in ("petsc1", "petsc1compare", "petsc1gamg"):
        base[(r["vertices"], r["run"][6:])] = r["solve_s"]
lines = [f"# PETSc strong scaling beside OpenCL and reference ({shape}, --globalization {glob}"
         + (f", {extra}" if extra else "") + ")", "",
         f"Machine: {meta['cpus']} CPUs, {meta['load_at_end']} (shared: times are comparable within this table only)."
         + (f" {lines_compare}." if compare else "")
         + (f" PETSC_OPTIONS=\"{meta['petsc_options']}\"." if meta["petsc_options"] else ""), "",
         "| vertices | run | solve s | wall s | CPU s | speed-up vs 1 rank | vs reference | Newton | CG | singular u / v | E_u | max RSS MiB (per rank) |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|"]
ref = {r["vertices"]: r["solve_s"] for r in rows if r["run"] == "ref"}
for r in rows:
    su = ""
    key = (r["vertices"], r["run"][6:])
    if r["run"].startswith("petsc") and key in base:
        su = f"{base[key] / r['solve_s']:.2f}"
    s = r["singularities"]
    sing = f"+{s['u']['plus']}-{s['u']['minus']} / +{s['v']['plus']}-{s['v']['minus']}"
    rss = f"{r['max_rss_mib']:.0f}"
    if "max_rss_mib_per_rank" in r:
        rss = " + ".join(f"{x['max_rss_mib']:.0f}" for x in r["per_rank"])
    name = r["backend"] + (f" x{r['ranks']}" if r["ranks"] else "") + (" (compare)" if "compare" in r["run"] else "") + (" (gamg)" if "gamg" in r["run"] else "")
    vr = f"{r['solve_s'] / ref[r['vertices']]:.2f}x" if r["vertices"] in ref else ""
    lines.append(f"| {r['vertices']} | {name} | {r['solve_s']:.2f} | {r['wall_s']:.2f} | {r['cpu_s']:.2f} | {su} | {vr} | "
                 f"{r['newton']} | {r['cg']} | {sing} | {r['final_energy']['u']:.9g} | {rss} |")
open(out + ".md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
EOF
