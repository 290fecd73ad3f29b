#!/usr/bin/env bash
# cli_petsc_mg.sh: the PETSc backend's default preconditioner, glpgp's own
# aggregation multigrid on each rank's rows (backends/petsc_amg.c).
# Usage: bash cli_petsc_mg.sh <path-to-glpgp> <data-dir>
# Checks, against --backend reference with its default multigrid:
#  - one rank, a disk with vortices (trust region) and the L-shape (line
#    search): the result file byte-identical to the reference's, the same
#    Newton and CG counts (the same cycle, the same arithmetic);
#  - two ranks (block Jacobi across ranks, fine level global), the disk and
#    data/plate_holes.msh: the reference's singularity counts, final energies
#    within 1e-6 relative, every level converged, Newton steps within 25%
#    of the reference's and CG iterations per Newton step at most 1.6x;
#  - two ranks on a square: the global coarse space of one level's
#    aggregates (-glpgp_mg_global 256) takes at most 0.85x the CG per Newton
#    step of one node per rank (the default), the same state; a negative
#    bound fails;
#  - -glpgp_mg gamg still selects KSPCG + GAMG (another CG count on one
#    rank, the same singularities); a bad -glpgp_mg fails with one line.
# Skipped (exit 77) without PETSc in the build or without mpirun.
. "$(dirname "$0")/lib.sh" "$@"

if ! "$GLPGP" --version | grep -q "PETSc: yes"; then
    echo "cli_petsc_mg: SKIPPED: glpgp was built without PETSc"
    exit 77
fi
if ! command -v mpirun >/dev/null 2>&1; then
    echo "cli_petsc_mg: SKIPPED: no mpirun (install openmpi-bin)"
    exit 77
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=${OMPI_MCA_btl_vader_single_copy_mechanism:-none}
MPIRUN=(mpirun --oversubscribe)
unset PETSC_OPTIONS

mpi() {
    local name=$1 np=$2
    shift 2
    runs=$((runs + 1))
    timeout 240 "${MPIRUN[@]}" -n "$np" "$GLPGP" "$@" >"$name.out" 2>"$name.err" </dev/null
    local rc=$?
    [ "$rc" -eq 0 ] || fail "$name: mpirun -n $np glpgp $*: exit $rc: $(head -c 400 "$name.err")"
}

# check A.json REF.json WHAT MODE: MODE "same" (equal counts) or "close"
# (singularities, energies 1e-6, converged, Newton within 25%, CG per Newton <= 1.6x)
check() {
    python3 - "$1" "$2" "$3" "$4" <<'EOF' || fail "$3"
import json, sys
a, r, what, mode = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), sys.argv[3], sys.argv[4]
bad = []
for k in ("u", "v"):
    if a["singularities"][k] != r["singularities"][k]:
        bad.append(f"{k} singularities {a['singularities'][k]} vs {r['singularities'][k]}")
    ea, er = a["final_energy"][k], r["final_energy"][k]
    if not abs(ea - er) <= 1e-6 * abs(er):
        bad.append(f"{k} energy {ea!r} vs {er!r}")
if not a["converged"]["all"]:
    bad.append("not every level converged")
na, nr = a["newton_iterations"]["total"], r["newton_iterations"]["total"]
ca, cr = a["cg_iterations"]["total"], r["cg_iterations"]["total"]
if mode == "same":
    if (na, ca) != (nr, cr):
        bad.append(f"Newton / CG {na} / {ca}, the reference's {nr} / {cr}")
else:
    if abs(na - nr) > 0.25 * nr:
        bad.append(f"Newton {na} vs {nr}")
    if ca / na > 1.6 * cr / nr:
        bad.append(f"CG per Newton step {ca / na:.1f} vs the reference's {cr / nr:.1f}")
if bad:
    print(f"{what}: " + "; ".join(bad))
    sys.exit(1)
print(f"{what}: Newton {na} (ref {nr}), CG {ca} (ref {cr})")
EOF
}

# one rank: the reference's multigrid, bit for bit
for c in "disk shape:disk:3000" "lshape $DATA/lshape.msh --globalization line-search"; do
    read -r name args <<<"$c"
    # shellcheck disable=SC2086
    run_ok "$name reference" solve $args --backend reference -o "ref_$name.vtu" --stats "ref_$name.json"
    # shellcheck disable=SC2086
    mpi "${name}_1" 1 solve $args --backend petsc -o "p1_$name.vtu" --stats "p1_$name.json"
    [ -f "p1_$name.json" ] && check "p1_$name.json" "ref_$name.json" "$name, 1 rank" same
    cmp -s "p1_$name.vtu" "ref_$name.vtu" || fail "$name: one rank is not byte-identical to the reference"
done

# two ranks: block Jacobi across ranks
mpi disk_2 2 solve shape:disk:3000 --backend petsc --stats p2_disk.json
[ -f p2_disk.json ] && check p2_disk.json ref_disk.json "disk, 2 ranks" close
if [ -n "$DATA" ] && [ -f "$DATA/plate_holes.msh" ]; then
    run_ok "plate_holes reference" solve "$DATA/plate_holes.msh" --backend reference --stats ref_holes.json
    mpi holes_2 2 solve "$DATA/plate_holes.msh" --backend petsc --stats p2_holes.json
    [ -f p2_holes.json ] && check p2_holes.json ref_holes.json "plate_holes, 2 ranks" close
else
    fail "data/plate_holes.msh not found (data dir '$DATA')"
fi

# bad_option OPTIONS PATTERN: two ranks with PETSC_OPTIONS=OPTIONS fail with
# one glpgp line matching PATTERN
bad_option() {
    runs=$((runs + 1))
    PETSC_OPTIONS="$1" timeout 240 "${MPIRUN[@]}" -n 2 "$GLPGP" solve shape:disk:3000 --backend petsc \
        --quiet >/dev/null 2>err.txt </dev/null
    local rc=$?
    [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] || fail "$1: exit $rc"
    [ "$(grep -c '^glpgp: ' err.txt)" = 1 ] || fail "$1: expected one glpgp line: $(head -c 400 err.txt)"
    expect_err "$2" "$1"
}

# the global coarse space of one level's aggregates (-glpgp_mg_global 256:
# 81 nodes here) against one node per rank (the default): fewer CG per
# Newton step, the same state
PETSC_OPTIONS="-glpgp_mg_global 256" mpi sq_2 2 solve shape:square:20000 --backend petsc --stats p2_sq.json
mpi sq0_2 2 solve shape:square:20000 --backend petsc --stats p2_sq0.json
if [ -f p2_sq.json ] && [ -f p2_sq0.json ]; then
    python3 - p2_sq.json p2_sq0.json <<'EOF' || fail "square, 2 ranks: the global coarse space does not pay"
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
ca = a["cg_iterations"]["total"] / a["newton_iterations"]["total"]
cb = b["cg_iterations"]["total"] / b["newton_iterations"]["total"]
print(f"square, 2 ranks: CG per Newton step {ca:.1f}, one node per rank {cb:.1f}")
assert a["singularities"] == b["singularities"], (a["singularities"], b["singularities"])
for k in ("u", "v"):
    assert abs(a["final_energy"][k] - b["final_energy"][k]) <= 1e-6 * abs(b["final_energy"][k])
assert ca <= 0.85 * cb, (ca, cb)
EOF
fi
bad_option "-glpgp_mg_global -1" "glpgp_mg_global -1: expected a node count"

# GAMG stays selectable: another solver (other CG counts), the same state
PETSC_OPTIONS="-glpgp_mg gamg" mpi gamg_1 1 solve shape:disk:3000 --backend petsc --stats p1_gamg.json
if [ -f p1_gamg.json ] && [ -f p1_disk.json ]; then
    python3 - p1_gamg.json p1_disk.json <<'EOF' || fail "-glpgp_mg gamg: not GAMG, or another state"
import json, sys
g, m = (json.load(open(f)) for f in sys.argv[1:3])
assert g["singularities"] == m["singularities"], (g["singularities"], m["singularities"])
assert g["cg_iterations"]["total"] != m["cg_iterations"]["total"], "the same CG count as the multigrid"
EOF
fi
bad_option "-glpgp_mg boomer" "glpgp_mg 'boomer'"

finish
