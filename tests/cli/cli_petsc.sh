#!/usr/bin/env bash
# cli_petsc.sh: the PETSc backend (--backend petsc) under mpirun.
# Usage: bash cli_petsc.sh <path-to-glpgp> <data-dir>
# Checks:
#  - always: `glpgp --version` maps no PETSc / MPI library (LD_DEBUG=files),
#    `ldd glpgp` lists none; a glpgp built without PETSc answers
#    --backend petsc with exit 1 and the one line "glpgp was built without
#    PETSc (install petsc-dev and rebuild)" (then the test skips, exit 77);
#  - mpirun -n 1 and -n 2 against --backend reference (--precond jacobi on
#    both: the same Jacobi-PCG driver) on a disk and an annulus: the same
#    singularity counts, final energies within 1e-6 relative; on one rank
#    the result file is byte-identical to the reference's;
#  - the default preconditioner (glpgp's multigrid on each rank's rows;
#    tests/cli/cli_petsc_mg.sh checks it closer) on 2 ranks: same counts,
#    energies within 1e-6; KSPCG + GAMG (-glpgp_mg gamg) with the line-search
#    Newton (GAMG with the near null space [z, iz] in every step): same
#    counts, energies within 1e-3 (another inexact path, a neighbouring
#    minimum: see below);
#  - 3 ranks on their parts of the mesh with the radial field, and 2 ranks
#    with a per-vertex field file (the whole mesh on every rank): the
#    reference's counts, energies within 1e-6;
#  - data/plate_holes.msh (a domain with holes) on 2 ranks: the reference's
#    singularity counts, energies within 1e-6, stats JSON with ranks = 2,
#    per_rank owned vertices summing to the vertex count and fewer than
#    owned / 10 ghosts per rank (the coordinate-bisection renumbering);
#  - 2 ranks write the result in the input's vertex order: the annulus's
#    VTK points and cells are the reference's, line for line;
#  - a missing input file under mpirun -n 2: non-zero exit within the
#    timeout (no hang), exactly one "glpgp: error:" line;
#  - --out FILE.pvtu: 2 ranks write FILE_p0.vtu, FILE_p1.vtu and the index
#    (read back with Python's xml + zlib): every global vertex owned exactly
#    once, the ghosts owned elsewhere, the cells' count the triangle count,
#    the triangles (by coordinates) those of the 1-rank gathered .vtu, z and
#    the field at every point within 1e-6 of it (and exactly the 2-rank
#    gathered .vtu's); 1 rank: one piece, exactly the gathered .vtu's values;
#    a piece that cannot be written (its name taken by a directory) on rank
#    1: every rank exits non-zero, one error line naming the rank, no file
#    of the set left; --gather-max below the vertex count: --out .vtu fails
#    before the solve with one line, --out .pvtu runs; .pvtu without
#    --backend petsc: a usage error.
# Skipped (exit 77) without PETSc in the build or without mpirun.
. "$(dirname "$0")/lib.sh" "$@"

# ---- no PETSc / MPI for commands that do not ask for it ---------------------
HEAVY='libpetsc|libmpi|glpgp_petsc'
if ldd "$GLPGP" | grep -Eq "$HEAVY"; then fail "ldd glpgp lists $(ldd "$GLPGP" | grep -E "$HEAVY" | tr '\n' ' ')"; fi
LD_DEBUG=files "$GLPGP" --version >out.txt 2>maps.txt </dev/null
grep -Eq "$HEAVY" maps.txt && fail "--version loaded: $(grep -E "$HEAVY" maps.txt | head -3 | tr '\n' ' ')"
if ! "$GLPGP" --version | grep -q "PETSc: yes"; then
    run_fail "built without PETSc" 1 "built without PETSc \(install petsc-dev and rebuild\)" \
        solve shape:disk:500 --backend petsc
    one_error_line "built without PETSc"
    [ "$fails" -eq 0 ] || finish
    echo "cli_petsc: SKIPPED: glpgp was built without PETSc ($("$GLPGP" --version))"
    exit 77
fi
if ! command -v mpirun >/dev/null 2>&1; then
    echo "cli_petsc: SKIPPED: no mpirun (install openmpi-bin)"
    exit 77
fi

# OpenMPI refuses root without these (CI runs as root) and 2 ranks may exceed the cores
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# containers often forbid the cross-memory attach of OpenMPI's shared-memory transport
export OMPI_MCA_btl_vader_single_copy_mechanism=${OMPI_MCA_btl_vader_single_copy_mechanism:-none}
MPIRUN=(mpirun --oversubscribe)
unset PETSC_OPTIONS

# mpi NAME NP ARGS...: run glpgp under mpirun -n NP (stdout NAME.out, stderr NAME.err)
mpi() {
    local name=$1 np=$2
    shift 2
    runs=$((runs + 1))
    timeout 240 "${MPIRUN[@]}" -n "$np" "$GLPGP" "$@" >"$name.out" 2>"$name.err" </dev/null
    local rc=$?
    [ "$rc" -eq 0 ] || fail "$name: mpirun -n $np glpgp $*: exit $rc: $(head -c 400 "$name.err")"
}

# compare A.json B.json WHAT [RTOL]: same singularity counts, final energies within RTOL (1e-6) relative
compare() {
    python3 - "$1" "$2" "$3" "${4:-1e-6}" <<'EOF' || fail "$3"
import json, sys
a, b, what = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), sys.argv[3]
rtol = float(sys.argv[4])
bad = []
for k in ("u", "v"):
    if a["singularities"][k] != b["singularities"][k]:
        bad.append(f"{k} singularities {a['singularities'][k]} vs {b['singularities'][k]}")
    ea, eb = a["final_energy"][k], b["final_energy"][k]
    if not abs(ea - eb) <= rtol * abs(eb):
        bad.append(f"{k} energy {ea!r} vs {eb!r} (rel {abs(ea - eb) / abs(eb):.2e})")
if a["vertices"] != b["vertices"]:
    bad.append("vertices differ")
if bad:
    print(f"{what}: " + "; ".join(bad))
    sys.exit(1)
EOF
}

for shape in disk annulus; do
    in=shape:$shape:2500
    run_ok "$shape reference" solve "$in" --backend reference --precond jacobi -o "ref_$shape.vtk" \
        --stats "ref_$shape.json"
    for np in 1 2; do
        mpi "${shape}_$np" "$np" solve "$in" --backend petsc --precond jacobi -o "p${np}_$shape.vtk" \
            --stats "p${np}_$shape.json"
        [ -f "p${np}_$shape.json" ] && compare "p${np}_$shape.json" "ref_$shape.json" "$shape, $np rank(s), jacobi"
    done
    cmp -s "p1_$shape.vtk" "ref_$shape.vtk" || fail "$shape: one rank is not byte-identical to the reference"
    # only rank 0 prints: one summary
    [ "$(grep -c '^  singularities' "${shape}_2.out")" = 1 ] || fail "$shape: 2 ranks printed $(grep -c '^  singularities' "${shape}_2.out") summaries"
done

# the result comes back in the input's vertex order
if [ -f p2_annulus.vtk ]; then
    python3 - p2_annulus.vtk ref_annulus.vtk <<'EOF' || fail "annulus, 2 ranks: VTK points / cells differ from the reference's"
import sys
a, r = (open(f).read().split("\n") for f in sys.argv[1:3])
i = next(k for k, l in enumerate(r) if l.startswith("POINTS"))
j = next(k for k, l in enumerate(r) if l.startswith("CELL_TYPES"))
sys.exit(0 if a[i:j] == r[i:j] else 1)
EOF
fi

# the default preconditioner with the trust region, 2 ranks: glpgp's
# multigrid on each rank's rows (the uniform size: with the chord budget's
# local size on this disk GAMG and the reference ended in neighbouring
# minima, a singularity pair apart): energies within 1e-6
run_ok "disk reference default" solve shape:disk:2500 --backend reference --size-chord-area 0 \
    --size-chord-depth 0 --stats ref_amg.json
mpi amg 2 solve shape:disk:2500 --backend petsc --size-chord-area 0 --size-chord-depth 0 --stats p2_amg.json
[ -f p2_amg.json ] && compare p2_amg.json ref_amg.json "disk, 2 ranks, GAMG (trust region)" 1e-6
if [ -f p2_amg.json ]; then
    python3 -c 'import json, sys; sys.exit(json.load(open("p2_amg.json"))["options"]["globalization"] != "trust-region")' ||
        fail "petsc: the default globalization is not the trust region"
fi
# GAMG in every Newton step (line search): inexact steps (eta up to 1e-2)
# with another preconditioner take another path and end in a neighbouring
# minimum (measured 5e-5 relative on this disk; the reference's Jacobi and
# multigrid paths agree to 4e-10, the PETSc backend with Jacobi to 1e-15):
# the same counts, energies within 1e-3
run_ok "disk reference line search" solve shape:disk:2500 --backend reference --globalization line-search \
    --stats ref_ls.json
PETSC_OPTIONS="-glpgp_mg gamg" mpi gamg 2 solve shape:disk:2500 --backend petsc --globalization line-search \
    --stats p2_ls.json
[ -f p2_ls.json ] && compare p2_ls.json ref_ls.json "disk, 2 ranks, GAMG line search" 1e-3
# GAMG's rebuild modes (-glpgp_gamg_rebuild: every step, per eps level, per
# oscillator): the same state (singularity counts; energies within 1e-3, as
# above: another preconditioner, other inexact steps); a bad mode fails every
# rank with one line
for mode in step oscillator; do
    PETSC_OPTIONS="-glpgp_mg gamg -glpgp_gamg_rebuild $mode" mpi "gamg_$mode" 2 solve shape:disk:2500 --backend petsc \
        --size-chord-area 0 --size-chord-depth 0 --stats "p2_$mode.json"
    [ -f "p2_$mode.json" ] && [ -f ref_amg.json ] && compare "p2_$mode.json" ref_amg.json "GAMG rebuild $mode" 1e-3
done
runs=$((runs + 1))
PETSC_OPTIONS="-glpgp_mg gamg -glpgp_gamg_rebuild sometimes" timeout 240 "${MPIRUN[@]}" -n 2 "$GLPGP" solve shape:disk:2500 \
    --backend petsc --quiet >/dev/null 2>err.txt </dev/null
rc=$?
[ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] || fail "-glpgp_gamg_rebuild sometimes: exit $rc"
[ "$(grep -c '^glpgp: ' err.txt)" = 1 ] || fail "-glpgp_gamg_rebuild sometimes: expected one glpgp line: $(head -c 400 err.txt)"
expect_err "glpgp_gamg_rebuild 'sometimes'" "-glpgp_gamg_rebuild sometimes"

# a domain with holes
if [ -n "$DATA" ] && [ -f "$DATA/plate_holes.msh" ]; then
    run_ok "plate_holes reference" solve "$DATA/plate_holes.msh" --backend reference --precond jacobi \
        --stats ref_holes.json
    mpi holes 2 solve "$DATA/plate_holes.msh" --backend petsc --precond jacobi --stats p2_holes.json -o p2_holes.vtu
    if [ -f p2_holes.json ]; then
        compare p2_holes.json ref_holes.json "plate_holes, 2 ranks"
        python3 - p2_holes.json <<'EOF' || fail "plate_holes: stats JSON per-rank section"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["ranks"] == 2, d.get("ranks")
assert len(d["per_rank"]) == 2
assert sum(r["owned"] for r in d["per_rank"]) == d["vertices"]
assert all(r["ghosts"] > 0 and r["max_rss_mib"] > 0 for r in d["per_rank"])
# the partition (coordinate bisection of the renumbered mesh): a thin
# interface, not the input numbering's (Gmsh order: ghosts about = owned)
assert all(r["ghosts"] < r["owned"] / 10 for r in d["per_rank"]), d["per_rank"]
EOF
    fi
    [ -s p2_holes.vtu ] || fail "plate_holes: no .vtu written"
else
    fail "data/plate_holes.msh not found (data dir '$DATA')"
fi

# 3 ranks, each on its part of the mesh: the radial field (its center from
# the whole mesh) against the reference; a per-vertex field file keeps the
# whole mesh on every rank: 2 ranks against the reference
run_ok "annulus radial reference" solve shape:annulus:2500 --field radial --backend reference --precond jacobi \
    --stats ref_radial.json
mpi radial 3 solve shape:annulus:2500 --field radial --backend petsc --precond jacobi --stats p3_radial.json
[ -f p3_radial.json ] && compare p3_radial.json ref_radial.json "annulus radial, 3 ranks"
# (a field file turns the refinement off: one line per vertex of the input as generated)
run_ok "annulus unrefined" solve shape:annulus:2500 --no-refine --backend reference --precond jacobi \
    --stats ref_unrefined.json
if [ -f ref_unrefined.json ]; then
    python3 -c "import json; print('0.6 0.8\n' * json.load(open('ref_unrefined.json'))['vertices'], end='')" >field.txt
    run_ok "annulus field file reference" solve shape:annulus:2500 --field field.txt --backend reference \
        --precond jacobi --stats ref_ffile.json
    mpi ffile 2 solve shape:annulus:2500 --field field.txt --backend petsc --precond jacobi --stats p2_ffile.json
    [ -f p2_ffile.json ] && compare p2_ffile.json ref_ffile.json "annulus field file, 2 ranks (whole mesh per rank)"
fi

# a bad input on every rank: one line, the same non-zero exit, no hang
runs=$((runs + 1))
timeout 120 "${MPIRUN[@]}" -n 2 "$GLPGP" solve "$T/missing.msh" --backend petsc -o never.vtk >bad.out 2>bad.err </dev/null
rc=$?
[ "$rc" -ne 0 ] || fail "missing input: exit 0"
[ "$rc" -ne 124 ] || fail "missing input: mpirun hung (timeout)"
n=$(grep -c '^glpgp: ' bad.err)
[ "$n" = 1 ] && grep -q '^glpgp: error: .*missing.msh' bad.err ||
    fail "missing input: expected one 'glpgp: error:' line, got $n: $(head -c 400 bad.err)"
[ ! -e never.vtk ] || fail "missing input: wrote never.vtk"


# ---- --out FILE.pvtu: a .vtu piece per rank and the index -------------------
# read_vtu.py: the arrays of a glpgp .vtu (appended raw data, UInt64 headers, zlib blocks)
cat >read_vtu.py <<'EOF'
import struct, zlib
import xml.etree.ElementTree as ET

def read_vtu(path):
    data = open(path, "rb").read()
    head, _, tail = data.partition(b'<AppendedData encoding="raw">')
    app = tail[tail.index(b"_") + 1:]
    root = ET.fromstring(head.decode().rstrip() + "</VTKFile>")
    zl = root.get("compressor") is not None
    fmt = {"Float64": "d", "Int32": "i", "Int64": "q", "Int8": "b", "UInt8": "B"}
    piece = root.find("UnstructuredGrid/Piece")
    out = {"npoints": int(piece.get("NumberOfPoints")), "ncells": int(piece.get("NumberOfCells"))}
    for da in root.iter("DataArray"):
        off = int(da.get("offset"))
        if zl:  # [nblocks, block size, last size, compressed sizes], then the blocks
            nb = struct.unpack_from("<Q", app, off)[0]
            sizes = struct.unpack_from("<%dQ" % nb, app, off + 24)
            p, raw = off + 24 + 8 * nb, b""
            for c in sizes:
                raw += zlib.decompress(app[p:p + c])
                p += c
        else:
            n = struct.unpack_from("<Q", app, off)[0]
            raw = app[off + 8:off + 8 + n]
        f = fmt[da.get("type")]
        out[da.get("Name")] = struct.unpack("<%d%s" % (len(raw) // struct.calcsize(f), f), raw)
    return out
EOF
mkdir -p pv
mpi pv1g 1 solve shape:disk:2500 --backend petsc --precond jacobi -o pv/g1.vtu
mpi pv2g 2 solve shape:disk:2500 --backend petsc --precond jacobi -o pv/g2.vtu
mpi pv2 2 solve shape:disk:2500 --backend petsc --precond jacobi -o pv/d2.pvtu --stats pv/d2.json
mpi pv1 1 solve shape:disk:2500 --backend petsc --precond jacobi -o pv/d1.pvtu
[ "$(ls pv | sort | tr '\n' ' ')" = "d1.pvtu d1_p0.vtu d2.json d2.pvtu d2_p0.vtu d2_p1.vtu g1.vtu g2.vtu " ] ||
    fail "pvtu: files written: $(ls pv | tr '\n' ' ')"
if [ -f pv/d2.pvtu ] && [ -f pv/d1.pvtu ] && [ -f pv/g1.vtu ] && [ -f pv/g2.vtu ]; then
    python3 - pv <<'EOF' || fail "pvtu: the pieces do not make the gathered result"
import json, sys, xml.etree.ElementTree as ET
sys.path.insert(0, ".")
from read_vtu import read_vtu
d = sys.argv[1]

def pieces(name):
    root = ET.parse(f"{d}/{name}.pvtu").getroot()
    src = [p.get("Source") for p in root.iter("Piece")]
    return [read_vtu(f"{d}/{s}") for s in src], src, root

def tris(v):  # the triangles as sets of point coordinates
    c = v["connectivity"]
    return {frozenset(xy(v, c[3 * t + a]) for a in range(3)) for t in range(v["ncells"])}

xy = lambda v, i: (v["Points"][3 * i], v["Points"][3 * i + 1])
stats = json.load(open(f"{d}/d2.json"))
g1, g2 = read_vtu(f"{d}/g1.vtu"), read_vtu(f"{d}/g2.vtu")
nv, nt = stats["vertices"], stats["triangles"]
assert (g1["npoints"], g1["ncells"]) == (nv, nt)
at1 = {xy(g1, i): i for i in range(nv)}
at2 = {xy(g2, i): i for i in range(nv)}
for name, nparts in (("d2", 2), ("d1", 1)):
    ps, src, root = pieces(name)
    assert src == [f"{name}_p{k}.vtu" for k in range(nparts)], src
    names = {a.get("Name") for a in root.iter("PDataArray")}
    assert {"z_u", "z_v", "field_u", "global_id", "vtkGhostType", "singular_u"} <= names, names
    owned, ghosts, cells = {}, [], set()
    for p in ps:
        gid, gh = p["global_id"], p["vtkGhostType"]
        for j in range(p["npoints"]):
            if gh[j] == 0:
                assert gid[j] not in owned, f"{name}: vertex {gid[j]} owned twice"
                owned[gid[j]] = xy(p, j)
            else:
                ghosts.append((gid[j], xy(p, j)))
        cells |= tris(p)
        # the values at every point (owned and ghost): the gathered results'
        # (bit for bit on the same ranks; one rank against two within 1e-6:
        # the reductions differ in order and each eps level stops at its
        # Newton tolerance, the last one at 1e-6 |g0|: 3e-8 seen on z_v)
        for j in range(p["npoints"]):
            i1, i2 = at1[xy(p, j)], at2[xy(p, j)]
            for a, nc in (("z_u", 2), ("z_v", 2), ("field_u", 3)):
                for c in range(nc):
                    assert abs(p[a][nc * j + c] - g1[a][nc * i1 + c]) <= 1e-6, (name, a, j)
                    same = g2[a][nc * i2 + c] if nparts == 2 else g1[a][nc * i1 + c]
                    assert p[a][nc * j + c] == same, (name, a, j)
            for a in ("dirichlet_u", "dirichlet_v"):
                assert p[a][j] == g1[a][i1], (name, a, j)
    assert sorted(owned) == list(range(nv)), f"{name}: owned ids are not 0..{nv - 1}"
    assert all(owned[g] == c for g, c in ghosts), f"{name}: a ghost point is not its owner's"
    assert sum(p["ncells"] for p in ps) == nt, (name, [p["ncells"] for p in ps], nt)
    assert cells == tris(g1), f"{name}: the pieces' triangles are not the mesh's"
EOF
fi
# a piece that cannot be written (rank 1's name is a directory): every rank
# fails, one error line naming the rank, no file of the set left (mpirun
# adds its own lines: only glpgp's are counted)
mkdir -p pvbad/bad_p1.vtu
runs=$((runs + 1))
timeout 240 "${MPIRUN[@]}" -n 2 "$GLPGP" solve shape:disk:2500 --backend petsc --precond jacobi -o pvbad/bad.pvtu \
    --stats pvbad/bad.json --quiet >pvbad.out 2>err.txt </dev/null
rc=$?
[ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] || fail "pvtu, unwritable piece: exit $rc"
[ "$(grep -c '^glpgp: ' err.txt)" = 1 ] || fail "pvtu, unwritable piece: expected one glpgp line: $(head -c 400 err.txt)"
expect_err "rank 1 .*bad_p1.vtu" "pvtu, unwritable piece"
[ "$(ls -A pvbad)" = bad_p1.vtu ] || fail "pvtu, unwritable piece: left $(ls -A pvbad | tr '\n' ' ')"
# the gather limit: --out .vtu above it fails before the solve; .pvtu gathers nothing
runs=$((runs + 1))
timeout 240 "${MPIRUN[@]}" -n 2 "$GLPGP" solve shape:disk:2500 --backend petsc --precond jacobi --gather-max 1000 \
    -o pv/over.vtu --quiet >/dev/null 2>err.txt </dev/null
rc=$?
[ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] || fail "--gather-max: exit $rc"
[ "$(grep -c '^glpgp: ' err.txt)" = 1 ] || fail "--gather-max: expected one glpgp line: $(head -c 400 err.txt)"
expect_err "gather-max 1000" "--gather-max"
[ ! -e pv/over.vtu ] || fail "--gather-max: wrote pv/over.vtu"
mpi pvmax 2 solve shape:disk:2500 --backend petsc --precond jacobi --gather-max 1000 -o pv/max.pvtu
[ -f pv/max.pvtu ] && [ -f pv/max_p1.vtu ] || fail "--gather-max with .pvtu: no pieces"
run_fail ".pvtu without petsc" 2 "needs --backend petsc" solve shape:disk:500 --backend reference -o x.pvtu
one_error_line ".pvtu without petsc"

finish
