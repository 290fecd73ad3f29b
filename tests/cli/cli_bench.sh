# tests/cli_bench.sh: ctest smoke test of the benchmark harness: runs
# glpgp-bench --smoke --json (seconds), checks that the JSON parses and has
# the documented keys, and exercises --compare on it. No timing asserts.
# Usage: bash tests/cli_bench.sh <path-to-glpgp-binary> <data-dir>
# Exit 77 (skip) when the bench binary was not built.
set -euo pipefail

glpgp=${1:?usage: cli_bench.sh <glpgp binary> <data dir>}
bench="$(dirname "$glpgp")/bench/glpgp-bench"
if [ ! -x "$bench" ]; then
    echo "cli_bench: $bench not built: skipped"
    exit 77
fi
if ! command -v python3 > /dev/null; then
    echo "cli_bench: python3 not found: skipped"
    exit 77
fi

bench=$(cd "$(dirname "$bench")" && pwd)/glpgp-bench
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"

fail() {
    echo "cli_bench: FAIL: $*" >&2
    exit 1
}

"$bench" --smoke --json out.json > out.md 2> err.txt || {
    cat out.md err.txt >&2
    fail "glpgp-bench --smoke exited non-zero"
}
grep -q '^| vertices | operation |' out.md || fail "no Markdown table on stdout"
grep -q 'STREAM' out.md || fail "no STREAM line on stdout"

python3 - out.json << 'EOF' || fail "JSON check failed"
import json, math, sys
d = json.load(open(sys.argv[1]))
for k in ("machine", "device", "commit", "stream", "opencl", "cholmod", "sizes", "options"):
    assert k in d, "missing top-level key %s" % k
for k in ("cpu", "cores", "memory_bytes"):
    assert k in d["machine"], "missing machine.%s" % k
assert d["stream"]["triad_gbs"] > 0 and d["stream"]["copy_gbs"] > 0
assert len(d["sizes"]) == 2, "smoke mode runs two sizes"
have_cl = d["opencl"]["available"]
for s in d["sizes"]:
    for k in ("vertices", "blocks", "bytes_spmv", "bytes_cg_iter", "cg_bandwidth_ratio",
              "cg_speedup_vs_reference", "peak_rss_bytes", "device_bytes", "reference", "opencl", "cholmod"):
        assert k in s, "missing sizes[].%s" % k
    r = s["reference"]
    assert r["ran"], "reference path did not run: %s" % r["note"]
    for k in ("quad_assembly_s", "newton_assembly_s", "spmv_s", "cg_iter_s", "linear_solve_s"):
        assert r[k]["median"] > 0 and r[k]["min"] > 0, k
    assert r["linear_solve_iterations"] > 0
    assert r["gl_solve"]["ran"] and r["gl_solve"]["newton_iterations"] > 0
    if have_cl:
        assert s["opencl"]["ran"], "OpenCL path did not run: %s" % s["opencl"]["note"]
        assert s["cg_bandwidth_ratio"] > 0 and s["cg_speedup_vs_reference"] > 0
    else:
        assert s["cg_bandwidth_ratio"] is None
    if d["cholmod"]["built"]:
        assert s["cholmod"]["ok"], "CHOLMOD failed: %s" % s["cholmod"]["note"]
print("cli_bench: JSON ok (%d sizes, OpenCL %s, CHOLMOD %s)" % (
    len(d["sizes"]), "yes" if have_cl else "skipped", "yes" if d["cholmod"]["built"] else "skipped"))
EOF

# --compare of a file with itself: every ratio is 1
"$bench" --compare out.json --against out.json > cmp.md || fail "--compare --against exited non-zero"
grep -q '| new / old |' cmp.md || fail "--compare printed no table"
if grep -E '^\| [^|]+ \| [^|]+ \| [^|]+ \| [0-9.]+ \|$' cmp.md | grep -vq '| 1.000 |$'; then
    fail "--compare of a file with itself gave a ratio other than 1"
fi
# bad option: non-zero exit with a message
if "$bench" --sizes nonsense > /dev/null 2> bad.txt; then fail "bad --sizes accepted"; fi
grep -q 'sizes' bad.txt || fail "no message for a bad --sizes"
echo "cli_bench: ok"
