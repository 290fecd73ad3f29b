"""examples/python/size_sweep.py: a parameter sweep over the target size h:
for each h, solve, extract the quads and tabulate singularities, quads,
irregular vertices, the worst scaled Jacobian, validity and time; the table
is printed and written as CSV.

    python3 examples/python/size_sweep.py [--input shape:annulus:20000] [--sizes 0.08,0.1,0.14,0.2] [-o sweep.csv]
"""
import argparse
import csv
import time
import warnings

import glpgp


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--input", default="shape:annulus:20000", help="a mesh file or shape:NAME:N")
    ap.add_argument("--sizes", default="0.08,0.1,0.14,0.2")
    ap.add_argument("--backend", default="auto")
    ap.add_argument("-o", "--out", default="sweep.csv")
    args = ap.parse_args()
    mesh = glpgp.read(args.input)
    print(mesh)
    rows = []
    for h in [float(s) for s in args.sizes.split(",")]:
        t0 = time.perf_counter()
        with warnings.catch_warnings(record=True) as caught:  # unconverged / invalid: recorded in the row
            warnings.simplefilter("always")
            r = glpgp.solve(mesh, size=h, backend=args.backend)
            q = r.quads()
        s = r.stats
        rep = q.report
        rows.append({"h": h, "vertices": s["vertices"], "sing_u": s["singularities"]["u"]["plus"] + s["singularities"]["u"]["minus"],
                     "sing_v": s["singularities"]["v"]["plus"] + s["singularities"]["v"]["minus"],
                     "newton": s["newton_iterations"]["total"], "quads": rep["faces"],
                     "irregular": rep["irregular_vertices"]["total"], "min_sj": round(rep["scaled_jacobian"]["min"], 3),
                     "valid": q.valid, "converged": r.converged, "warnings": len(caught),
                     "seconds": round(time.perf_counter() - t0, 2)})
        print(rows[-1])
    with open(args.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
