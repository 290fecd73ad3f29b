"""bench/python_overhead.py: the binding's own share of a solve. The same
solve through the CLI (`glpgp solve INPUT --stats`) and through glpgp.solve
in this process, interleaved; the binding's overhead is the wall time of the
Python calls (glpgp.shape + glpgp.solve) less the library's own time in them
(the stats' seconds.read, which covers generating and preparing the mesh,
plus seconds.total), next to the CLI's wall time less its stats' time (the
process start, backend creation and summary). Issue 31's target: <= 2% of a
1M-vertex solve. JSON with --json.

    PYTHONPATH=build/python python3 bench/python_overhead.py [--vertices 1000000] [--repeat 2] [--backend auto]
"""
import argparse
import json
import os
import subprocess
import tempfile
import time

import glpgp


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shape", default="square")
    ap.add_argument("--vertices", type=int, default=1000000)
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--backend", default="auto")
    ap.add_argument("--cli", default=os.path.join(os.path.dirname(__file__), "..", "build", "glpgp"))
    ap.add_argument("--json", default=None)
    args = ap.parse_args()
    src = "shape:%s:%d" % (args.shape, args.vertices)
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for rep in range(args.repeat):
            t0 = time.perf_counter()
            subprocess.run([args.cli, "solve", src, "--backend", args.backend, "--stats", d + "/s.json", "--quiet"],
                           check=True, stdout=subprocess.DEVNULL)
            cli_wall = time.perf_counter() - t0
            cs = json.load(open(d + "/s.json"))
            t0 = time.perf_counter()
            r = glpgp.solve(glpgp.shape(args.shape, args.vertices), backend=args.backend)
            py_wall = time.perf_counter() - t0
            ps = r.stats
            lib = ps["seconds"]["read"] + ps["seconds"]["total"]
            clib = cs["seconds"]["read"] + cs["seconds"]["total"]
            row = {"cli_wall": cli_wall, "cli_library": clib, "python_wall": py_wall, "python_library": lib,
                   "binding_overhead": py_wall - lib, "binding_share": (py_wall - lib) / py_wall,
                   "cli_outside_library": cli_wall - clib, "newton": ps["newton_iterations"]["total"],
                   "cli_newton": cs["newton_iterations"]["total"]}
            rows.append(row)
            print("run %d: CLI %.2f s wall (library %.2f s); Python %.2f s wall (library %.2f s): binding %.4f s = "
                  "%.3f%%; Newton %d / %d" % (rep + 1, cli_wall, clib, py_wall, lib, row["binding_overhead"],
                                              100 * row["binding_share"], row["cli_newton"], row["newton"]))
    out = {"input": src, "backend": args.backend, "device": r.device, "vertices": r.mesh.n_vertices, "runs": rows}
    if args.json:
        with open(args.json, "w") as f:
            json.dump(out, f, indent=2)


if __name__ == "__main__":
    main()
