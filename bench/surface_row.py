#!/usr/bin/env python3
"""bench/surface_row.py: one row of bench/surface_compare.sh's table from a
quad report ({"quads": {...}}: `glpgp solve --stats` for glpgp, `glpgp
quality QUADS.obj --domain INPUT --size H --stats` for a peer's OBJ, so
both are checked by the same code at the same h): quads, valid / manifold /
all-quad, Euler and boundary loops kept, irregular interior vertices, SJ
min / mean (each face's best-fit plane), Hausdorff / h, glpgp's path (from
its log), seconds (whole command, and glpgp's extraction).
Usage: surface_row.py REPORT.json LOG.txt MODEL FACES TOOL SECONDS"""
import json
import re
import sys

js, txt, model, n, tool, secs = sys.argv[1:]
try:
    q = json.load(open(js))["quads"]
    s = q["surface"]
except Exception as e:  # no report: the tool failed or wrote nothing
    print("| %s | %s | %s | failed: %s |" % (model, n, tool, str(e).replace("|", "/")))
    sys.exit(0)
try:
    out = open(txt).read()
except OSError:
    out = ""
vi = q["valence"]["interior"]
nint = sum(vi.values())
irr = nint - vi.get("4", 0)
if tool.startswith("glpgp"):
    path = ("coarse last resort" if "coarsened triangulation" in out else "last resort" if "last resort" in out
            else "split (h/2)" if "Catmull-Clark" in out else "local split" if "split locally" in out
            else "local refinement" if "refined locally" in out else "local repair" if "repaired locally" in out else "grid")
    m = re.search(r"extraction ([0-9.]+)", out)
    secs_s = "%.1f (%s)" % (float(secs), m.group(1) if m else "?")
else:
    path, secs_s = "-", "%.1f" % float(secs)
reasons = q["invalid_reasons"]
manifold = "nonmanifold" not in reasons and "pinched" not in reasons
print("| %s | %s | %s | %d | %s / %s / %s | %s | %d (%.1f%%) | %.3f | %.3f | %.3f | %s | %s |" % (
    model, n, tool, q["quads"], "yes" if q["valid"] else "no", "yes" if manifold else "no",
    "yes" if q["other_faces"] == 0 else "no",
    "yes" if (s["euler"], s["boundary_loops"]) == (s["input_euler"], s["input_boundary_loops"]) else "no",
    irr, 100.0 * irr / max(nint, 1), q["scaled_jacobian"]["min"], q["scaled_jacobian"]["mean"],
    s["hausdorff_over_h"], path, secs_s))
