#!/usr/bin/env bash
# cli_readme.sh: README.md says only what runs.
#  - its C block is the run() of examples/c/solve_quads.c, word for word, and
#    that example (built as examples/solve_quads beside glpgp) solves a mesh and
#    writes a valid quad mesh, and fails with one line on a bad input;
#  - every command line of its ```sh blocks runs: `glpgp ...` lines here (each
#    must exit 0; a command whose optional library this build lacks must say
#    "built without"), `python3 -c ...` lines with the built Python package, the
#    set-up lines (.ci/run, ctest, cmake) are the ones the CI script runs; any
#    other line fails the test (a README command nothing runs);
#  - every ```python block runs with the built package (data/ beside it).
. "$(dirname "$0")/lib.sh" "$@"
SRC=$(cd "$DATA/.." && pwd)
README=$SRC/README.md
EXAMPLE=$(dirname "$GLPGP")/examples/solve_quads

# ---- the library example ------------------------------------------------------
awk '/^```c$/{f=1; next} /^```$/{f=0} f' "$README" >readme_c.txt
awk '/^static glpgp_status run/{f=1} f{print} f && /^}$/{exit}' "$SRC/examples/c/solve_quads.c" >example_run.txt
[ -s readme_c.txt ] || fail "README has no C block"
cmp -s readme_c.txt example_run.txt || fail "README's C block differs from examples/c/solve_quads.c: $(diff readme_c.txt example_run.txt | head -5)"
if [ -x "$EXAMPLE" ]; then
    "$EXAMPLE" "$DATA/square.obj" q.obj >ex_out.txt 2>ex_err.txt </dev/null || fail "example: exit $? ($(cat ex_err.txt))"
    grep -q "quads, .* valid$" ex_out.txt || fail "example: $(cat ex_out.txt)"
    grep -q "^f " q.obj || fail "example wrote no quad mesh"
    "$EXAMPLE" nothere.obj q2.obj >ex_out.txt 2>ex_err.txt </dev/null
    rc=$?
    [ $rc -eq 1 ] || fail "example on a missing file: exit $rc"
    [ "$(wc -l <ex_err.txt)" -eq 1 ] && grep -q "^solve_quads: .*nothere.obj" ex_err.txt ||
        fail "example on a missing file: $(cat ex_err.txt)"
    [ -e q2.obj ] && fail "example left q2.obj after a failure"
else
    fail "example binary $EXAMPLE not built"
fi

# ---- the Python package as built (skipped when it is not) ------------------------
PYDIR=$(dirname "$GLPGP")/python
PY=""
if [ -f "$PYDIR/interpreter" ] && ls "$PYDIR"/glpgp/_glpgp*.so >/dev/null 2>&1; then
    PY=$(cat "$PYDIR/interpreter")
else
    echo "(the Python package is not built: README's Python lines are not run)"
fi
if [ -n "$PY" ]; then
    ln -s "$DATA" data
    awk '/^```python$/{f=1; k++; next} /^```$/{f=0} f{print > ("readme_py_" k ".py")}' "$README"
    for f in readme_py_*.py; do
        [ -e "$f" ] || { fail "README has no python block"; break; }
        runs=$((runs + 1))
        PYTHONPATH="$PYDIR" "$PY" "$f" >out.txt 2>err.txt </dev/null || fail "README's $f: $(tail -c 400 err.txt)"
    done
fi

# ---- the shell commands ----------------------------------------------------------
awk '/^```sh$/{f=1; next} /^```$/{f=0} f' "$README" >readme_sh.txt
[ -s readme_sh.txt ] || fail "README has no sh block"
n=0
while IFS= read -r line; do
    [ -n "$line" ] || continue
    case "$line" in
    "bash .ci/run --demo" | "ctest --test-dir build --output-on-failure -j2" | \
        "cmake -S . -B build -DCMAKE_BUILD_TYPE=Release" | "cmake --build build -j2")
        key=${line#bash .ci/run }
        [ "$key" = --demo ] && key='run_demo$'
        grep -q -- "$key" "$SRC/.ci/run" || fail "README line '$line' is not what .ci/run runs"
        ;;
    "python3 -c "*)
        n=$((n + 1))
        if [ -n "$PY" ]; then
            code=${line#python3 -c }
            code=${code#\"}
            code=${code%\"}
            PYTHONPATH="$PYDIR" "$PY" -c "$code" >out.txt 2>err.txt </dev/null ||
                fail "README command '$line': $(tail -c 300 err.txt)"
        fi
        ;;
    "glpgp "* | "build/glpgp "*)
        n=$((n + 1))
        read -r -a argv <<<"${line#*glpgp }"
        "$GLPGP" "${argv[@]}" >out.txt 2>err.txt </dev/null
        rc=$?
        if [ $rc -ne 0 ] && ! grep -qi "built without\|no usable OpenCL\|no OpenCL" err.txt; then
            fail "README command '$line': exit $rc ($(head -c 300 err.txt))"
        fi
        ;;
    *) fail "README command '$line' is run by no test" ;;
    esac
done <readme_sh.txt
[ $n -ge 5 ] || fail "only $n glpgp commands found in README's sh blocks"
finish
