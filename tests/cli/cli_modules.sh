#!/usr/bin/env bash
# cli_modules.sh: OpenImageIO and Gmsh are loaded on demand (dlopen'd modules
# glpgp_oiio.so / glpgp_gmsh.so), never by commands that do not need them.
# Usage: bash cli_modules.sh <path-to-glpgp> <data-dir>
# Checks:
#  - `ldd glpgp` lists neither libOpenImageIO, libgmsh nor libstdc++;
#  - with LD_DEBUG=files (the dynamic loader's log of every object it maps),
#    `glpgp --version` and `glpgp solve shape:square:2000 --backend reference`
#    map none of them;
#  - positive control (the check can fail): `glpgp render` maps glpgp_oiio.so
#    and libOpenImageIO, and not Gmsh; `glpgp mesh` maps glpgp_gmsh.so;
#  - GLPGP_MODULE_DIR naming an empty directory: render, mesh and
#    solve --image fail with exit 1 and one line naming the module and the
#    directory, leave no file, and --version says "OpenImageIO: no";
#  - a module file that is not loadable: exit 1, one line with its path and
#    the loader's reason.
# The image parts skip themselves when glpgp was built without OpenImageIO or
# Gmsh (the first two checks always run).
. "$(dirname "$0")/lib.sh" "$@"
unset GLPGP_MODULE_DIR

# loaded DESCRIPTION ARGS...: run glpgp under LD_DEBUG=files; the objects it
# mapped (one path per line) go to maps.txt
loaded() {
    local what=$1
    shift
    LD_DEBUG=files LD_DEBUG_OUTPUT="$T/ld" "$GLPGP" "$@" >out.txt 2>err.txt </dev/null
    local rc=$?
    [ "$rc" -eq 0 ] || fail "$what: exit $rc: $(head -c 600 err.txt)"
    cat "$T"/ld.* 2>/dev/null | sed -n 's/.*file=\([^ ]*\) .*/\1/p' | sort -u >maps.txt
    rm -f "$T"/ld.*
    [ -s maps.txt ] || fail "$what: LD_DEBUG=files logged nothing (cannot check what was loaded)"
}
HEAVY='OpenImageIO|gmsh|glpgp_oiio|glpgp_gmsh|libstdc\+\+'
# one_line DESCRIPTION: stderr is exactly one "glpgp: error:" line
one_line() {
    [ "$(wc -l <err.txt)" -eq 1 ] || fail "$1: stderr is not one line: $(head -c 600 err.txt)"
    grep -q '^glpgp: error: ' err.txt || fail "$1: not a 'glpgp: error:' line: $(head -c 300 err.txt)"
}

# ---- nothing heavy linked or loaded ------------------------------------------
if command -v ldd >/dev/null 2>&1; then
    ldd "$GLPGP" >ldd.txt 2>&1 || fail "ldd failed: $(head -c 300 ldd.txt)"
    if grep -q libasan ldd.txt; then # the sanitizer runtime brings libstdc++
        HEAVY='OpenImageIO|gmsh|glpgp_oiio|glpgp_gmsh'
    fi
    if grep -Eq "$HEAVY" ldd.txt; then
        fail "glpgp links a heavy library: $(grep -E "$HEAVY" ldd.txt | tr '\n' ' ')"
    fi
fi
loaded "--version" --version
grep -q "^glpgp " out.txt || fail "--version: $(head -c 200 out.txt)"
grep -Eq "$HEAVY" maps.txt && fail "--version loaded: $(grep -E "$HEAVY" maps.txt | tr '\n' ' ')"
loaded "solve" solve shape:square:2000 --backend reference -o r.vtk --quiet
grep -Eq "$HEAVY" maps.txt && fail "solve loaded: $(grep -E "$HEAVY" maps.txt | tr '\n' ' ')"
[ -s r.vtk ] || fail "solve: r.vtk missing"

"$GLPGP" --version >version.txt
if ! grep -q "OpenImageIO: yes" version.txt || ! grep -q "Gmsh: yes" version.txt; then
    [ "$fails" -ne 0 ] && finish
    skip "(image parts) $(cat version.txt)"
fi

# ---- positive control: the modules load when needed ---------------------------
loaded "render" render r.vtk -o r.png --image-size 64 --quiet
grep -q "glpgp_oiio" maps.txt || fail "render: glpgp_oiio module not loaded"
grep -q "OpenImageIO" maps.txt || fail "render: OpenImageIO not loaded"
grep -q "gmsh" maps.txt && fail "render loaded Gmsh: $(grep gmsh maps.txt | tr '\n' ' ')"
[ -s r.png ] || fail "render: r.png missing"
printf 'P2\n8 8\n255\n' >sq.pgm
for j in 0 1 2 3 4 5 6 7; do echo "0 255 255 255 255 255 255 0"; done >>sq.pgm
loaded "mesh" mesh sq.pgm -o sq.msh --mesh-size 1 --quiet
grep -q "glpgp_gmsh" maps.txt || fail "mesh: glpgp_gmsh module not loaded"
[ -s sq.msh ] || fail "mesh: sq.msh missing"

# ---- module directory without the modules ---------------------------------------
mkdir empty
export GLPGP_MODULE_DIR="$T/empty"
run 1 "render without module" render r.vtk -o x.png
one_line "render without module"
grep -q "glpgp_oiio" err.txt || fail "render without module: module not named: $(cat err.txt)"
grep -q "$T/empty" err.txt || fail "render without module: directory not named: $(cat err.txt)"
[ ! -e x.png ] || fail "render without module: x.png written"
run 1 "mesh without module" mesh sq.pgm -o x.msh
one_line "mesh without module"
grep -q "glpgp_oiio\|glpgp_gmsh" err.txt || fail "mesh without module: module not named: $(cat err.txt)"
[ ! -e x.msh ] || fail "mesh without module: x.msh written"
run 1 "solve --image without module" solve shape:square:500 --backend reference --image x.png -o x.vtk
one_line "solve --image without module"
grep -q "glpgp_oiio" err.txt || fail "solve --image without module: $(cat err.txt)"
[ ! -e x.vtk ] || fail "solve --image without module: x.vtk written (should fail up front)"
run 0 "--version without module" --version
grep -q "OpenImageIO: no" out.txt || fail "--version without module: $(cat out.txt)"

# ---- a module file that does not load -------------------------------------------
mkdir broken
echo "not a shared object" >broken/glpgp_oiio.so
export GLPGP_MODULE_DIR="$T/broken"
run 1 "broken module" render r.vtk -o x.png
one_line "broken module"
grep -q "$T/broken/glpgp_oiio.so" err.txt || fail "broken module: path not named: $(cat err.txt)"
grep -q "cannot load" err.txt || fail "broken module: $(cat err.txt)"
unset GLPGP_MODULE_DIR

finish
