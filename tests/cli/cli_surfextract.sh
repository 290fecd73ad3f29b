#!/usr/bin/env bash
# tests/cli/cli_surfextract.sh: `glpgp extract` on a surface's result (issue 29):
#  - the mesh extracted from a result written by `solve -o` is solve --quads'
#    mesh byte for byte, from .vtu and legacy .vtk, on a surface with a
#    boundary (a hemisphere: the field at boundary vertices must come back
#    exactly, field_frame) and a closed one (a torus);
#  - the summary names the surface pipeline's steps, --stats writes the
#    report, --verbose reaches the library's log;
#  - --feature-angle (the creases the smoothing and the last resort keep, as
#    solve's) outside [0, 180] is a usage error.
. "$(dirname "$0")/lib.sh" "$@"

check_same() { # NAME SHAPE FACES EXT
    run_ok "$1 solve" solve "$2" --faces "$3" --backend reference -o "$1.$4" --quads "$1.solve.obj" --stats "$1.solve.json"
    run_ok "$1 extract" extract "$1.$4" --quads "$1.extract.obj" --stats "$1.extract.json" --verbose
    expect_out "surface quads +extraction [0-9]+ faces" "$1 extract: the surface steps"
    expect_err "quads: surface extraction: [0-9]+ nodes" "$1 extract --verbose: the library's log"
    [ -s "$1.extract.json" ] || fail "$1 extract: no --stats"
    cmp -s "$1.solve.obj" "$1.extract.obj" || fail "$1: extract from the .$4 result differs from solve --quads"
}
check_same hemi shape:hemisphere:1000 40 vtu
check_same torus shape:torus:1000 40 vtk
run_fail "extract --feature-angle 200" 2 "feature-angle" extract hemi.vtu --quads fa.obj --feature-angle 200
finish
