#!/usr/bin/env bash
# cli_crossquads.sh: quads from a `--field cross` run (issue 14, item 5).
#  - `solve shape:disk:8000 --field cross --quads q.obj` either gives a valid
#    all-quad mesh (exit 0, every OBJ face has 4 corners, "valid": true) or
#    says honestly that it is not (exit 3, no q.obj, "valid": false); the
#    same mesh re-extracted from the saved result and written as .msh passes
#    `glpgp quality` (the same checks, run on the file);
#  - the "quads" report then splits the irregular interior vertices into
#    those within h of a cross-field singularity and the others:
#    near + far = interior, the singularity count is the cross field's, the
#    radius is the solve's h, at most count singularities have one; the
#    summary prints the line; `extract` of the saved result (cross_w read
#    back) reports the same counts;
#  - a `--field boundary` run has no such fields in its report.
# Usage: bash cli_crossquads.sh <path-to-glpgp> <data-dir>
. "$(dirname "$0")/lib.sh" "$@"

"$GLPGP" solve shape:disk:8000 --field cross --backend reference --quads q.obj --stats q.json -o r.vtk \
    >out.txt 2>err.txt </dev/null
rc=$?
runs=$((runs + 1))
case $rc in
0) [ -s q.obj ] || fail "exit 0 but q.obj not written" ;;
3) [ ! -e q.obj ] || fail "exit 3 (invalid) but q.obj written"
   expect_err "invalid|not written" "cross quads exit 3" ;;
*) fail "cross quads: exit $rc (stderr: $(head -c 400 err.txt))" ;;
esac
expect_out "near cross +irregular interior [0-9]+ within" "summary line"
python3 - q.json "$rc" <<'PY' || fail "cross quads report"
import json, sys
d = json.load(open(sys.argv[1]))
rc = int(sys.argv[2])
q, c = d["quads"], d["cross_field"]
assert q["valid"] is (rc == 0), (q["valid"], rc, q.get("invalid_reasons"))
if rc == 0:
    assert q["other_faces"] == 0 and q["quads"] == q["faces"], q
    assert q["inverted"] == 0 and q["degenerate"] == 0 and q["overlapping_faces"] == 0, q
iv = q["irregular_vertices"]
assert iv["interior_near_cross"] >= 0 and iv["interior_far_cross"] >= 0, iv
assert iv["interior_near_cross"] + iv["interior_far_cross"] == iv["interior"], iv
cs = q["cross_singularities"]
assert cs["count"] == c["singularities"] == len(c["singular"]), (cs, c["singularities"])
assert abs(cs["radius"] - d["size"]) <= 1e-12 * d["size"], (cs["radius"], d["size"])
assert 0 <= cs["with_irregular_vertex"] <= cs["count"], cs
PY
if [ "$rc" = 0 ]; then
    awk '/^f /{ if (NF != 5) bad++ } END { exit bad > 0 }' q.obj || fail "q.obj has a face that is not a quad"
fi

# the saved result holds cross_w: extract reports the same split
run "$rc" "extract cross" extract r.vtk --quads e.msh --stats e.json
python3 - q.json e.json <<'PY' || fail "extract cross report"
import json, sys
a = json.load(open(sys.argv[1]))["quads"]
b = json.load(open(sys.argv[2]))["quads"]
for k in ("interior", "interior_near_cross", "interior_far_cross"):
    assert a["irregular_vertices"][k] == b["irregular_vertices"][k], (k, a["irregular_vertices"], b["irregular_vertices"])
assert a["cross_singularities"]["count"] == b["cross_singularities"]["count"]
assert a["cross_singularities"]["with_irregular_vertex"] == b["cross_singularities"]["with_irregular_vertex"]
PY
if [ "$rc" = 0 ]; then # the file itself, through the same checks
    h=$(python3 -c 'import json, sys; print(repr(json.load(open(sys.argv[1]))["size"]))' q.json)
    run_ok "quality of the cross quads" quality e.msh --size "$h"
    expect_out "valid +yes" "quality e.msh"
fi

# no cross field (--field boundary; with --quads the cross field is the default): the fields are absent
run_ok "boundary quads" solve shape:disk:2000 --field boundary --backend reference --quads b.obj --stats b.json
python3 - b.json <<'PY' || fail "boundary report has cross fields"
import json, sys
q = json.load(open(sys.argv[1]))["quads"]
assert "cross_singularities" not in q and "interior_near_cross" not in q["irregular_vertices"], q
PY
grep -q "near cross" out.txt && fail "boundary run prints the near-cross line"

# with --quads and no --field: the cross field (bench/results/quads_fields.md); without --quads: boundary
run_ok "quads default field" solve shape:disk:2000 --backend reference --quads d.obj --stats d.json
python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); assert d["field"] == "cross" and "cross_singularities" in d["quads"], d["field"]' d.json ||
    fail "solve --quads without --field did not take the cross field"
run_ok "default field" solve shape:disk:2000 --backend reference --stats n.json
python3 -c 'import json, sys; assert json.load(open(sys.argv[1]))["field"] == "boundary"' n.json ||
    fail "solve without --quads did not take the boundary field"
finish
