# tests/cli_bench.sh: ctest smoke test of the benchmark harness: runs
# glpgp-bench --smoke --json (seconds), checks that the JSON parses and has
# the documented keys, and exercises --compare on it; runs the
# preconditioner ladder on a tiny disk and checks its anchors (PETSc GAMG and
# CHOLMOD when present, null otherwise); with an OpenCL device,
# runs bench/gpu_check.sh --smoke (the GPU check's every step on small sizes,
# so that the script a GPU loan depends on keeps working) and checks its
# files; runs bench/oscillators.sh --quick (same result both ways). No timing
# asserts.
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
        assert s["cg_device_bandwidth_ratio"] > 0
        assert d["opencl"]["device_axpby_gbs"] > 0 and d["opencl"]["device_copy_gbs"] > 0
    else:
        assert s["cg_bandwidth_ratio"] is None
    if d["cholmod"]["built"]:
        assert s["cholmod"]["ok"], "CHOLMOD failed: %s" % s["cholmod"]["note"]
print("cli_bench: JSON ok (%d sizes, OpenCL %s, CHOLMOD %s)" % (
    len(d["sizes"]), "yes" if have_cl else "skipped", "yes" if d["cholmod"]["built"] else "skipped"))
EOF

# the preconditioner ladder with its anchors (PETSc GAMG, CHOLMOD), tiny
"$bench" --precond both --sizes 3000 --newton-steps 1 --no-opencl --json pc.json > pc.md 2> pc_err.txt || {
    cat pc.md pc_err.txt >&2
    fail "glpgp-bench --precond both exited non-zero"
}
have_petsc=0
"$glpgp" --version | grep -q "PETSc: yes" && have_petsc=1
python3 - pc.json out.json "$have_petsc" << 'EOF' || fail "--precond JSON check failed"
import json, sys
d = json.load(open(sys.argv[1]))
chol = json.load(open(sys.argv[2]))["cholmod"]["built"]
petsc = sys.argv[3] == "1"
cases = d["precond_ladder"]
assert len(cases) == 2, "one size, two h: %d cases" % len(cases)
for c in cases:
    assert c["jacobi"]["mean_cg"] > c["amg"]["mean_cg"] > 0, (c["jacobi"]["mean_cg"], c["amg"]["mean_cg"])
    assert "gamg" in c and "cholmod" in c, "the reference case carries the anchors"
    if petsc:
        assert c["gamg"] and 0 < c["gamg"]["mean_cg"] < c["jacobi"]["mean_cg"], c["gamg"]
    else:
        assert c["gamg"] is None
    if chol:
        assert c["cholmod"] and all(x["ok"] and x["rel_diff_vs_cg"] < 1e-5 for x in c["cholmod"]), c["cholmod"]
    else:
        assert c["cholmod"] is None
print("cli_bench: --precond anchors ok (PETSc GAMG %s, CHOLMOD %s)" % (
    "yes" if petsc else "skipped", "yes" if chol else "skipped"))
EOF

# --compare of a file with itself: every ratio is 1
"$bench" --compare out.json --against out.json > cmp.md || fail "--compare --against exited non-zero"
grep -q '| new / old |' cmp.md || fail "--compare printed no table"
nrat=$(grep -cE '^\| [^|]+ \| [^|]+ \| [^|]+ \| [0-9.]+ \|$' cmp.md)
[ "$nrat" -ge 5 ] || fail "--compare printed only $nrat ratio rows"
if grep -E '^\| [^|]+ \| [^|]+ \| [^|]+ \| [0-9.]+ \|$' cmp.md | grep -vq '| 1.000 |$'; then
    fail "--compare of a file with itself gave a ratio other than 1"
fi
# bad option: non-zero exit with a message
if "$bench" --sizes nonsense > /dev/null 2> bad.txt; then fail "bad --sizes accepted"; fi
grep -q 'sizes' bad.txt || fail "no message for a bad --sizes"

# the GPU check's script, on small sizes (any OpenCL device)
src=$(cd "${2:?}/.." && pwd)
if [ -f "$src/bench/gpu_check.sh" ] && "$glpgp" devices 2>/dev/null | grep -q "fp64 yes"; then
    build=$(cd "$(dirname "$glpgp")" && pwd)
    bash "$src/bench/gpu_check.sh" --smoke "$build" gc > gc.txt 2>&1 || {
        tail -n 30 gc.txt >&2
        fail "bench/gpu_check.sh --smoke failed"
    }
    for f in log.txt devices.txt bench_ladder.md bench_ladder.json precond_1m_k0.json precond_1m_kauto.json \
        square1m_amg.json square1m_amg_concurrent.json square1m_amg_sequential.json square1m_jacobi.json \
        square4m_amg.json square4m_amg_phasesync.json square10m_amg.json profile_square1m.txt summary.md; do
        [ -s "gc/$f" ] || fail "gpu_check.sh --smoke left no gc/$f"
    done
    python3 - gc << 'EOF' || fail "gpu_check.sh --smoke: JSON check failed"
import json, os, sys
d = sys.argv[1]
k0 = json.load(open(os.path.join(d, "precond_1m_k0.json")))
ka = json.load(open(os.path.join(d, "precond_1m_kauto.json")))
c0 = [c for c in k0["precond_ladder"] if c.get("amg")]
ca = [c for c in ka["precond_ladder"] if c.get("amg")]
assert c0 and ca, "no multigrid case"
assert all(c["amg_kcycle_min"] == 0 for c in c0), "--amg-kcycle-min 0 not applied"
assert all(c["amg"]["per_step"][0]["launches_solve"] > 0 for c in c0 + ca), "no launches counted"
for f in ("square1m_amg.json", "square1m_jacobi.json", "square4m_amg.json"):
    s = json.load(open(os.path.join(d, f)))
    assert s["converged"]["all"] and s["device_calls"]["kernel_launches"] > 0, f
assert json.load(open(os.path.join(d, "square1m_amg_concurrent.json")))["oscillators"] == "concurrent"
# every whole solve reports its phases and the host's share of the solve
for f in ("square1m_amg_sequential.json", "square4m_amg_phasesync.json", "square10m_amg.json"):
    s = json.load(open(os.path.join(d, f)))
    assert s["converged"]["all"], f
    ph = s["phases"]
    assert len([k for k in ph if ph[k]["seconds"] > 0]) >= 10, (f, ph)
    assert ph["program_build"]["seconds"] > 0 and ph["linear_solves"]["seconds"] > 0, f
    assert 0.0 < s["solve_split"]["host_share"] <= 1.0, (f, s["solve_split"])
summ = open(os.path.join(d, "summary.md")).read()
assert "| solve-square10m-amg | 0 |" in summ and "host share" in summ, summ
assert "glpgp_amg" in open(os.path.join(d, "profile_square1m.txt")).read(), "no per-kernel profile"
print("cli_bench: gpu_check.sh --smoke ok")
EOF
else
    echo "cli_bench: no OpenCL fp64 device: gpu_check.sh --smoke skipped"
fi

# bench/oscillators.sh --quick: u and v sequential and concurrent give the same
# file (its exit status), on the reference backend and OpenCL when present
if [ -f "$src/bench/oscillators.sh" ] && [ -x /usr/bin/time ]; then
    build=$(cd "$(dirname "$glpgp")" && pwd)
    bash "$src/bench/oscillators.sh" "$build" --quick > osc.md 2>&1 || {
        cat osc.md >&2
        fail "bench/oscillators.sh --quick failed"
    }
    grep -q "| disk4k | reference |.*| yes |" osc.md || fail "bench/oscillators.sh --quick: no reference row: $(cat osc.md)"
else
    echo "cli_bench: /usr/bin/time missing: oscillators.sh --quick skipped"
fi
echo "cli_bench: ok"
