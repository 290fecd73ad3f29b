#!/usr/bin/env bash
# install_consumer.sh: glpgp installed into a temporary prefix works for a
# consumer and from the prefix alone.
# Usage: bash install_consumer.sh <cmake> <glpgp-build-dir> <consumer-source-dir> [cmake args...]
#   (the cmake args, e.g. -DCMAKE_C_COMPILER=..., go to the consumer's configure)
# Checks:
#  - `cmake --install BUILD --prefix P` puts the headers (with the generated
#    version.h), the layer libraries, the image modules (when built), the
#    glpgp executable and the package config under P;
#  - tests/install/consumer (find_package(glpgp) + glpgp::glpgp, nothing else)
#    configures, builds and runs against P: a reference-backend solve of a
#    square with no singularity;
#  - P/bin/glpgp --version runs and reports the installed version;
#  - with OpenImageIO and Gmsh built: P/bin/glpgp mesh MASK loads its modules
#    from P/<libdir>/glpgp (LD_DEBUG=files shows the paths), also after P is
#    moved elsewhere (the lookup is relative to the executable);
#  - with the Python package built ($GLPGP_PYTHON names its interpreter):
#    P/<its install dir>/glpgp imports from there alone, solves, and loads
#    the OpenImageIO module from its own glpgp/modules, also after P is moved.
set -u

CMAKE=${1:?usage: install_consumer.sh <cmake> <build-dir> <consumer-dir> [cmake args]}
BUILD=${2:?build dir}
CONSUMER=${3:?consumer source dir}
shift 3
T=$(mktemp -d "${TMPDIR:-/tmp}/glpgp_install.XXXXXX")
trap 'rm -rf "$T"' EXIT
unset GLPGP_MODULE_DIR

fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
finish() {
    if [ "$fails" -ne 0 ]; then
        echo "install_consumer: $fails failure(s)"
        exit 1
    fi
    echo "install_consumer: all checks passed"
    exit 0
}

P="$T/prefix"
if ! "$CMAKE" --install "$BUILD" --prefix "$P" >"$T/install.log" 2>&1; then
    fail "cmake --install: $(tail -c 800 "$T/install.log")"
    finish
fi
LIBDIR=$(dirname "$(find "$P" -name libglpgp_core.a | head -1)")
[ -n "$LIBDIR" ] && [ -d "$LIBDIR" ] || fail "no libglpgp_core.a under $P"
for f in include/glpgp/version.h include/glpgp/glpgp.h include/glpgp/solve.h include/glpgp/image.h bin/glpgp; do
    [ -e "$P/$f" ] || fail "not installed: $f"
done
# the internals (glpgp/internal/: Newton step, CG, multigrid, test switches) stay in the tree
[ ! -e "$P/include/glpgp/internal" ] || fail "installed: include/glpgp/internal/ (internal headers)"
for l in core mesh solver backends quads io image; do
    [ -e "$LIBDIR/libglpgp_$l.a" ] || fail "not installed: libglpgp_$l.a"
done
[ -e "$LIBDIR/cmake/glpgp/glpgpConfig.cmake" ] || fail "no package config in $LIBDIR/cmake/glpgp"
[ -e "$LIBDIR/cmake/glpgp/glpgpConfigVersion.cmake" ] || fail "no package version file"

# ---- the consumer -------------------------------------------------------------
if ! "$CMAKE" -S "$CONSUMER" -B "$T/consumer" -DCMAKE_PREFIX_PATH="$P" -DCMAKE_BUILD_TYPE=Release \
    "$@" >"$T/configure.log" 2>&1; then
    fail "consumer configure: $(tail -c 1500 "$T/configure.log")"
elif ! "$CMAKE" --build "$T/consumer" >"$T/build.log" 2>&1; then
    fail "consumer build: $(tail -c 1500 "$T/build.log")"
else
    # the consumer was linked against the installed libraries, not the build tree
    grep -q "$P" "$T/consumer/CMakeCache.txt" || fail "consumer did not find glpgp in $P"
    "$T/consumer/consumer" >"$T/consumer.txt" 2>&1
    rc=$?
    [ "$rc" -eq 0 ] || fail "consumer: exit $rc: $(head -c 600 "$T/consumer.txt")"
    grep -q "ok$" "$T/consumer.txt" || fail "consumer: $(head -c 600 "$T/consumer.txt")"
    cat "$T/consumer.txt"
fi

# ---- the installed executable --------------------------------------------------
"$P/bin/glpgp" --version >"$T/version.txt" 2>&1 || fail "installed --version: $(cat "$T/version.txt")"
VERSION=$(sed -n 's/^#define GLPGP_VERSION "\(.*\)"/\1/p' "$P/include/glpgp/version.h")
grep -q "^glpgp $VERSION " "$T/version.txt" ||
    fail "installed --version: '$(cat "$T/version.txt")' (installed version.h says $VERSION)"
cat "$T/version.txt"
if ! grep -q "OpenImageIO: yes" "$T/version.txt" || ! grep -q "Gmsh: yes" "$T/version.txt"; then
    echo "image modules not built: module lookup not checked"
    finish
fi
ls "$LIBDIR"/glpgp/glpgp_oiio.* "$LIBDIR"/glpgp/glpgp_gmsh.* >/dev/null 2>&1 ||
    fail "image modules not installed in $LIBDIR/glpgp"

# a 10 x 10 mask with an 8 x 8 square inside (plain PGM)
{
    printf 'P2\n10 10\n255\n'
    echo "0 0 0 0 0 0 0 0 0 0"
    for j in 1 2 3 4 5 6 7 8; do echo "0 255 255 255 255 255 255 255 255 0"; done
    echo "0 0 0 0 0 0 0 0 0 0"
} >"$T/mask.pgm"
# python_from PREFIX: the installed package imports from PREFIX, solves, and
# renders a picture with the OpenImageIO module of PREFIX
python_from() {
    local pre=$1
    [ -n "${GLPGP_PYTHON:-}" ] || return 0
    local ext pkg
    ext=$(find "$pre" -name '_glpgp*.so' | head -1)
    if [ -z "$ext" ]; then
        fail "python from $pre: the package was not installed (no _glpgp*.so under $pre)"
        return
    fi
    pkg=$(dirname "$(dirname "$ext")")
    [ -e "$(dirname "$ext")/modules/glpgp_oiio.so" ] || fail "python from $pre: no glpgp/modules/glpgp_oiio.so"
    rm -f "$T"/ld.* "$T/py.png"
    (cd "$T" && LD_DEBUG=files LD_DEBUG_OUTPUT="$T/ld" PYTHONPATH="$pkg" "$GLPGP_PYTHON" -c "
import glpgp, sys
assert glpgp.__file__.startswith('$pre'), glpgp.__file__
r = glpgp.solve(glpgp.shape('square', 400), backend='reference', size_field='none', size=0.3)
assert r.stats['singularities']['u'] == {'plus': 0, 'minus': 0}
glpgp.render(r, 'py.png', size=64)
print('python package ok:', glpgp.__file__)
" >"$T/py.txt" 2>&1)
    local rc=$?
    [ "$rc" -eq 0 ] || fail "python from $pre: exit $rc: $(tail -c 800 "$T/py.txt")"
    [ -s "$T/py.png" ] || fail "python from $pre: no picture"
    cat "$T"/ld.* 2>/dev/null | sed -n 's/.*file=\([^ ]*glpgp_oiio\.[^ ]*\) .*/\1/p' | sort -u >"$T/mods.txt"
    while read -r m; do
        case "$m" in
        "$pre"/*) ;;
        *) fail "python from $pre: module loaded from outside the prefix: $m" ;;
        esac
    done <"$T/mods.txt"
    [ -s "$T/mods.txt" ] || fail "python from $pre: the OpenImageIO module was not loaded"
    cat "$T/py.txt"
}

# mesh_from PREFIX: run PREFIX/bin/glpgp mesh; both modules must come from PREFIX
mesh_from() {
    local pre=$1
    rm -f "$T"/ld.* "$T/mask.msh"
    (cd "$T" && LD_DEBUG=files LD_DEBUG_OUTPUT="$T/ld" "$pre/bin/glpgp" mesh mask.pgm -o mask.msh \
        --mesh-size 1 --quiet >"$T/mesh.txt" 2>&1)
    local rc=$?
    [ "$rc" -eq 0 ] || fail "mesh from $pre: exit $rc: $(head -c 600 "$T/mesh.txt")"
    [ -s "$T/mask.msh" ] || fail "mesh from $pre: no mask.msh"
    cat "$T"/ld.* 2>/dev/null | sed -n 's/.*file=\([^ ]*glpgp_[og][a-z]*\.[^ ]*\) .*/\1/p' | sort -u >"$T/mods.txt"
    [ "$(wc -l <"$T/mods.txt")" -eq 2 ] || fail "mesh from $pre: modules loaded: $(tr '\n' ' ' <"$T/mods.txt")"
    while read -r m; do
        case "$m" in
        "$pre"/*) ;;
        *) fail "mesh from $pre: module loaded from outside the prefix: $m" ;;
        esac
    done <"$T/mods.txt"
}
mesh_from "$P"
python_from "$P"
mv "$P" "$T/moved"
mesh_from "$T/moved"
python_from "$T/moved"
finish
