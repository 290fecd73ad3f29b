#!/usr/bin/env bash
# cli_errors.sh: error handling of the glpgp CLI.
# Usage: bash cli_errors.sh <path-to-glpgp> <data-dir>
# Checks: help/version texts (every solve option documented), exit codes
# (1 = failure with "glpgp: error: ..." naming the problem, 2 = usage error),
# rejected inputs (missing, non-planar, degenerate, non-manifold, garbage),
# rejected option values, and that a failed run never leaves (or clobbers) an
# output file.
. "$(dirname "$0")/lib.sh" "$@"

expect_msg() { expect_err "$@"; }
no_outputs() {
    for f in o.vtk o.obj o.json; do
        [ ! -e "$f" ] || { fail "$1: output $f left behind"; rm -f "$f"; }
    done
    if ls -A | grep -q '\.tmp'; then fail "$1: temporary file left: $(ls -A | grep '\.tmp')"; fi
}

# ---- help / version -----------------------------------------------------
run 0 "--help" --help
grep -q "solve" out.txt && grep -q "generate" out.txt && grep -q "devices" out.txt &&
    grep -q "crosscheck" out.txt || fail "--help does not list every subcommand"
run 0 "help" help
run 0 "--version" --version
grep -qE "glpgp [0-9]" out.txt || fail "--version prints no version"
run 2 "no arguments" 
grep -qi "usage" err.txt || fail "no arguments: no usage text"
run 2 "unknown command" frobnicate
expect_msg "frobnicate" "unknown command"

run 0 "solve --help" solve --help
for opt in --size --method --energy --newton --field --center --init --eps0 --eps-ratio \
    --eps-min --newton-rtol --newton-max --cg-rtol --cg-max --cg-check --backend --device \
    --out --stats --quiet --verbose shape: gl pgp p1 transport projected paper boundary radial \
    reference opencl auto naive; do
    grep -qe "$opt" out.txt || fail "solve --help does not mention $opt"
done
grep -qi "default" out.txt || fail "solve --help shows no defaults"
run 0 "help solve" help solve
run 0 "generate --help" generate --help
grep -q -- "--vertices" out.txt || fail "generate --help does not mention --vertices"

# ---- bad inputs: exit 1 with one meaningful message line, no output ------
# The files have neutral names (in_N.*), so a message can only match the
# expected words by saying them itself.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0.5\nv 0 -1 0.5\nv 0 0 -1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n' >in_1.obj # 3D, non-manifold edge
printf 'v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n' >in_2.obj        # degenerate triangle
printf 'v 0 0\nv 1 0\nv 0 1\nv 0 -1\nv 1 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n' >in_3.obj # non-manifold edge
printf 'hello world\nthis is not a mesh\n\001\002\003\n' >in_4.obj                 # garbage
printf 'not a gmsh file\n' >in_5.msh                                                # garbage
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n' >in_6.obj                           # index out of range
: >in_7.obj                                                                         # empty

for f in missing.obj in_1.obj in_2.obj in_3.obj in_4.obj in_5.msh in_6.obj in_7.obj; do
    run 1 "solve $f" solve "$f" --out o.vtk --stats o.json --quiet
    expect_msg "^glpgp: error: " "solve $f"
    one_error_line "solve $f"
    no_outputs "solve $f"
done
run 1 "missing file" solve missing.obj --quiet
expect_msg "missing\.obj" "missing file (names the path)"
expect_msg "no such file|cannot open|not found|does not exist" "missing file"
run 1 "non-manifold edge in 3D" solve in_1.obj --quiet
expect_msg "non-manifold edge" "non-manifold edge in 3D"
run 1 "degenerate" solve in_2.obj --quiet
expect_msg "degenerate|zero.area" "degenerate"
run 1 "non-manifold" solve in_3.obj --quiet
expect_msg "manifold" "non-manifold"
run 1 "garbage" solve in_4.obj --quiet
expect_msg "format|malformed|unknown|invalid|parse|unexpected|binary|not a" "garbage"
run 1 "garbage msh" solve in_5.msh --quiet
expect_msg "format|malformed|invalid|parse|unexpected|gmsh|MeshFormat" "garbage msh"
run 1 "bad index" solve in_6.obj --quiet
expect_msg "index|range" "bad index"

# a pre-existing output survives a failed run untouched
echo "old content" >o.vtk
run 1 "failed run keeps old output" solve in_3.obj --out o.vtk --quiet
[ "$(cat o.vtk 2>/dev/null)" = "old content" ] || fail "failed run modified the existing o.vtk"
rm -f o.vtk

# output directory missing: fails before solving, creates nothing
run 1 "output dir missing" solve shape:square:200 --out nodir/o.vtk --quiet
expect_msg "nodir" "output dir missing"
[ ! -e nodir ] || fail "output dir missing: nodir was created"
run 1 "stats dir missing" solve shape:square:200 --out o.vtk --stats nodir/o.json --quiet
no_outputs "stats dir missing"

# an explicit --device that does not exist is an error (no silent fallback), no output
run 1 "no such device" solve shape:square:200 --device 99 --out o.vtk --quiet
expect_msg "OpenCL|device" "no such device"
no_outputs "no such device"

# field file missing: the solve fails, no output
run nonzero "field file missing" solve shape:square:300 --field nofield.txt --out o.vtk \
    --stats o.json --quiet
expect_msg "nofield" "field file missing"
no_outputs "field file missing"

# ---- bad option values: exit 2, naming the option -------------------------
bad_opt() { # DESCRIPTION ARGS...
    local what=$1
    shift
    run 2 "$what" solve shape:square:200 --out o.vtk --stats o.json --quiet "$@"
    expect_msg "usage" "$what"
    no_outputs "$what"
}
bad_opt "--size -1" --size -1
expect_msg "size" "--size -1"
bad_opt "--size abc" --size abc
expect_msg "abc" "--size abc"
bad_opt "--size 0" --size 0
bad_opt "--size nan" --size nan
bad_opt "--size inf" --size inf
bad_opt "--size 1e999" --size 1e999
bad_opt "--size 1x" --size 1x
bad_opt "--size 1e-300 (below 2 mean edges)" --size 1e-300
expect_msg "mean edge" "--size 1e-300"
bad_opt "--size 1e300 (beyond the domain)" --size 1e300
expect_msg "diameter" "--size 1e300"
bad_opt "--size=" --size=
bad_opt "--size (no value)" --size
bad_opt "--method foo" --method foo
expect_msg "method" "--method foo"
bad_opt "--tr-precond foo" --tr-precond foo
expect_msg "tr-precond" "--tr-precond foo"
bad_opt "--energy foo" --energy foo
bad_opt "--newton foo" --newton foo
bad_opt "--init foo" --init foo
bad_opt "--backend foo" --backend foo
bad_opt "--eps0 -2" --eps0 -2
bad_opt "--eps-ratio 1.5" --eps-ratio 1.5
bad_opt "--eps-min 0" --eps-min 0
bad_opt "--newton-rtol 2" --newton-rtol 2
bad_opt "--newton-max 0" --newton-max 0
bad_opt "--cg-rtol 0" --cg-rtol 0
bad_opt "--cg-max 1.5" --cg-max 1.5
bad_opt "--cg-max 99999999999999999999" --cg-max 99999999999999999999
bad_opt "--cg-check x" --cg-check x
bad_opt "--device -1" --device -1
bad_opt "--center 1" --center 1
bad_opt "--center a,b" --center a,b
bad_opt "--out o.txt" --out o.txt
bad_opt "--quiet=1" --quiet=1
bad_opt "unknown option" --bogus-option
expect_msg "--bogus-option" "unknown option (named in the message)"
bad_opt "second input" extra.obj
run 2 "solve without input" solve --quiet
run 2 "shape:nosuch" solve shape:nosuch --quiet
expect_msg "nosuch" "shape:nosuch"
run 2 "shape:square:abc" solve shape:square:abc --quiet
run 2 "--out == --stats" solve shape:square:200 --out o.vtk --stats o.vtk --quiet
no_outputs "--out == --stats"

# ---- generate -------------------------------------------------------------
run nonzero "generate bad shape" generate nosuchshape --vertices 500 -o g.obj
expect_msg "nosuchshape" "generate bad shape"
[ ! -e g.obj ] || fail "generate bad shape left g.obj"
run 2 "generate bad count" generate square --vertices abc -o g.obj
run 2 "generate tiny count" generate square --vertices 3 -o g.obj
run 2 "generate no output" generate square --vertices 500
run 2 "generate bad extension" generate square --vertices 500 -o g.txt
run 1 "generate into missing dir" generate square --vertices 500 -o nodir/g.obj
[ ! -e g.obj ] && [ ! -e g.txt ] || fail "generate failures left a file"
if ls -A | grep -q '\.tmp'; then fail "temporary files left: $(ls -A | grep '\.tmp')"; fi

# ---- one parser, one selector: the same option behaves the same in every command ----
run 0 "generate --vertices=N" generate square --vertices=500 -o g2.obj
[ -s g2.obj ] || fail "generate --vertices=500 wrote nothing"
run 0 "solve --size=H" solve shape:square:300 --size=0.3 --backend=reference --quiet
for cmd in solve figure crosscheck; do
    run 2 "$cmd --size -1" $cmd shape:square:200 --size -1 -o o.png
    expect_msg "size" "$cmd --size -1"
done
if "$GLPGP" --version | grep -q "OpenImageIO: yes"; then
    # an explicit --device that does not exist is an error in figure as in solve
    run 1 "figure --device 99" figure shape:square:200 --device 99 -o f.png --quiet
    expect_msg "device" "figure --device 99"
    [ ! -e f.png ] || fail "figure --device 99 wrote f.png"
fi
run 2 "extract --smooth=x" extract r.vtk --quads=q.obj --smooth=x
expect_msg "smooth" "extract --smooth=x"

# ---- --verbose adds the error's trace in every command (it was read after the
# verbosity was set in the commands with one INPUT: quality, render, extract, ...) ----
printf 'not a mesh\n' >notmsh.msh
printf '<VTKFile type="UnstructuredGrid">\n' >notres.vtu
for c in quality render extract; do
    in=notres.vtu extra=""
    [ $c = quality ] && in=notmsh.msh
    [ $c = render ] && extra="-o x.png"
    [ $c = extract ] && extra="--quads x.obj"
    run nonzero "$c bad input" $c $in $extra
    one_error_line "$c bad input"
    run nonzero "$c bad input --verbose" $c $in $extra --verbose
    [ "$(wc -l <err.txt)" -gt 1 ] && grep -q "^  at " err.txt ||
        fail "$c --verbose: no trace after the error line: $(head -c 300 err.txt)"
done

# ---- interrupted runs: exit 128 + signal, one line, no output and no temporary ----
for sig in INT TERM; do
    "$GLPGP" solve shape:disk:300000 --backend reference -o big.vtk --stats big.json >out.txt 2>err.txt </dev/null &
    pid=$!
    sleep 1
    kill -s $sig $pid
    wait $pid
    rc=$?
    want=$([ $sig = INT ] && echo 130 || echo 143)
    [ "$rc" -eq "$want" ] || fail "SIG$sig: exit $rc, expected $want"
    tail -n 1 err.txt | grep -qiE "interrupted|terminated" || fail "SIG$sig: no closing line: $(tail -n 2 err.txt)"
    [ ! -e big.vtk ] && [ ! -e big.json ] || fail "SIG$sig: output left behind"
    no_tmp "SIG$sig"
done

finish
