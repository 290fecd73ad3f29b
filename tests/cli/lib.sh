# tests/cli/lib.sh: the one helper library of the CLI tests. A test starts with
#     . "$(dirname "$0")/lib.sh" "$@"      # args: <path-to-glpgp> <data-dir>
# which sets GLPGP (absolute path), DATA, a fresh temporary directory T (the
# working directory, removed on exit) and these helpers:
#   run WANT WHAT ARGS...      run glpgp ARGS (stdin /dev/null), stdout -> out.txt,
#                              stderr -> err.txt; WANT is an exit code or "nonzero"
#   run_ok WHAT ARGS...        run 0 ...
#   run_fail WHAT RC REGEX ARGS...  run RC ..., and stderr must match REGEX
#   expect_err REGEX WHAT      stderr (err.txt) matches the case-insensitive ERE
#   expect_out REGEX WHAT      stdout (out.txt) matches
#   one_error_line WHAT        stderr is a single "glpgp: error: ..." line, or a
#                              "glpgp: usage error: ..." line plus its "Try" hint
#   no_tmp WHAT                no temporary file (*.tmp*) left in T
#   fail MESSAGE               record a failure
#   skip REASON                end the test as skipped (exit 77: ctest reports it)
#   need_opencl_fp64           skip unless `glpgp devices` lists an fp64 device
#   finish                     print the summary and exit 1 if anything failed
set -u
GLPGP=${1:?usage: $0 <glpgp> <data-dir>}
DATA=${2:-}
[ -x "$GLPGP" ] || { echo "glpgp binary '$GLPGP' not found"; exit 1; }
GLPGP=$(cd "$(dirname "$GLPGP")" && pwd)/$(basename "$GLPGP")
[ -z "$DATA" ] || DATA=$(cd "$DATA" && pwd)
TEST_NAME=$(basename "$0" .sh)
T=$(mktemp -d "${TMPDIR:-/tmp}/glpgp_${TEST_NAME}.XXXXXX")
trap 'rm -rf "$T"' EXIT
cd "$T" || exit 1

fails=0
runs=0
fail() {
    echo "FAIL: $*"
    fails=$((fails + 1))
}

run() {
    local want=$1 what=$2
    shift 2
    runs=$((runs + 1))
    "$GLPGP" "$@" >out.txt 2>err.txt </dev/null
    local rc=$?
    if [ "$want" = nonzero ]; then
        [ "$rc" -ne 0 ] || fail "$what: expected failure, got exit 0"
    elif [ "$rc" -ne "$want" ]; then
        fail "$what: expected exit $want, got $rc (stderr: $(head -c 400 err.txt))"
    fi
    return 0
}

run_ok() {
    local what=$1
    shift
    run 0 "$what" "$@"
}

run_fail() {
    local what=$1 want=$2 pat=$3
    shift 3
    run "$want" "$what" "$@"
    expect_err "$pat" "$what"
}

expect_err() {
    grep -qiE -e "$1" err.txt || fail "$2: stderr does not match /$1/: $(head -c 300 err.txt)"
}

expect_out() {
    grep -qiE -e "$1" out.txt || fail "$2: stdout does not match /$1/: $(head -c 300 out.txt)"
}

one_error_line() {
    local n
    n=$(wc -l <err.txt)
    if grep -q '^glpgp: usage error: ' err.txt; then
        [ "$n" -le 2 ] || fail "$1: usage error takes $n lines: $(head -c 400 err.txt)"
    else
        [ "$n" -eq 1 ] && grep -q '^glpgp: error: ' err.txt ||
            fail "$1: expected one 'glpgp: error:' line, got $n lines: $(head -c 400 err.txt)"
    fi
}

no_tmp() {
    if ls -A | grep -q '\.tmp'; then fail "$1: temporary file left: $(ls -A | grep '\.tmp')"; fi
}

skip() {
    echo "skipped: $*"
    exit 77
}

need_opencl_fp64() {
    "$GLPGP" devices >devices.txt 2>&1 || skip "no OpenCL device: $(head -c 200 devices.txt)"
    grep -q "fp64 yes" devices.txt || skip "no OpenCL device with fp64"
}

finish() {
    if [ "$fails" -ne 0 ]; then
        echo "$TEST_NAME: $fails failure(s) in $runs runs"
        exit 1
    fi
    echo "$TEST_NAME: all checks passed ($runs runs)"
    exit 0
}
