#!/usr/bin/env bash
# bench/surface_perf.sh [GLPGP] [OUT.json]: the surface engine's speed against
# planar meshes of the same size, interleaved in one run (BACKEND, default
# opencl; N, default 100000 vertices; BIG, default 500000 vertices = 1M
# triangles, 0: skip):
#  - per Newton step: the coupled oscillators on shape:sphere:N against the
#    coupled planar oscillators on shape:disk:N (--field cross
#    --cross-coupling on: the same 2 nv-node system, planar rows), each with
#    --init one and a fixed 6 Newton steps per eps level (--newton-max 6
#    --newton-rtol 1e-15), seconds.u / Newton steps; and the cross fields
#    (the surface's rows with the corners' turns against the planar
#    stiffness), seconds.field / Newton steps;
#  - a whole default solve of shape:sphere:BIG against shape:disk:BIG (default
#    options: the planar boundary field, u and v apart) and shape:disk:BIG
#    --field cross (coupled), total seconds.
# Each pair runs REPS times (default 2), alternating (A B A B); prints a
# table, writes JSON (and keeps each run's statistics in STATS_DIR if set).
set -eu
G=${1:-build/glpgp}
OUT=${2:-surface_perf.json}
BACKEND=${BACKEND:-opencl}
N=${N:-100000}
BIG=${BIG:-500000}
REPS=${REPS:-2}
STATS_DIR=${STATS_DIR:-}
D=$(mktemp -d "${TMPDIR:-/tmp}/glpgp_surface_perf.XXXXXX")
trap 'rm -rf "$D"' EXIT
rows=()
run() { # name, args...
    local name=$1
    shift
    /usr/bin/time -f "%e %M" -o "$D/time" "$G" solve "$@" --backend "$BACKEND" --stats "$D/s.json" --quiet >/dev/null
    [ -z "$STATS_DIR" ] || cp "$D/s.json" "$STATS_DIR/$(echo "$name $*" | tr -c 'A-Za-z0-9.\n' '_').json"
    local row
    row=$(python3 - "$D/s.json" "$D/time" "$name" "$*" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
wall, rss = open(sys.argv[2]).read().split()[-2:]
c = d.get("cross_field") or {}
nu = d["newton_iterations"]["u"]
r = {"name": sys.argv[3], "args": sys.argv[4], "vertices": d["vertices"], "triangles": d["triangles"],
     "size": d["size"], "newton_u": nu, "cg_u": d["cg_iterations"]["u"], "seconds_u": d["seconds"]["u"],
     "seconds_per_newton_u": d["seconds"]["u"] / nu if nu else None,
     "cg_per_newton_u": d["cg_iterations"]["u"] / nu if nu else None,
     "cross_newton": c.get("newton_iterations"), "cross_cg": c.get("cg_iterations"), "seconds_field": d["seconds"]["field"],
     "seconds_per_newton_cross": d["seconds"]["field"] / c["newton_iterations"] if c.get("newton_iterations") else None,
     "seconds_total": d["seconds"]["total"], "wall": float(wall), "max_rss_mib": int(rss) / 1024.0,
     "median_zabs": min(d["zabs"]["u"]["median"], d["zabs"]["v"]["median"])}
print(json.dumps(r))
PY
)
    rows+=("$row")
    python3 -c "import json,sys; r=json.loads(sys.argv[1]); f=lambda x: '%.4f' % x if x else '-'; print('%-22s %8d %6d %6d %7s %6s %6s %7s %8.1f %7.0f %6.3f' % (r['name'], r['vertices'], r['newton_u'], r['cg_u'], f(r['seconds_per_newton_u']), r['cross_newton'] or '-', r['cross_cg'] or '-', f(r['seconds_per_newton_cross']), r['wall'], r['max_rss_mib'], r['median_zabs']))" "$row"
}
printf '%-22s %8s %6s %6s %7s %6s %6s %7s %8s %7s %6s\n' case vertices newton cg s/newt x_newt x_cg x_s/nwt wall_s rss_MiB zabs
step="--init one --newton-max 6 --newton-rtol 1e-15 --cross-size off --size-field none"
for rep in $(seq "$REPS"); do
    run "sphere, per step" shape:sphere:$N $step
    run "disk coupled, per step" shape:disk:$N --field cross --cross-coupling on $step
done
if [ "$BIG" != 0 ]; then
    for rep in $(seq "$REPS"); do
        run "sphere, whole" shape:sphere:$BIG
        run "disk, whole" shape:disk:$BIG
        run "disk cross, whole" shape:disk:$BIG --field cross
    done
fi
(IFS=,; echo "[${rows[*]}]") | python3 -c "import json,sys; json.dump({'backend': sys.argv[2], 'runs': json.load(sys.stdin)}, open(sys.argv[1], 'w'), indent=1)" "$OUT" "$BACKEND"
echo "wrote $OUT"
