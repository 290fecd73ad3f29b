"""bench/python_threads.py: is the GIL really released? Two independent
solves in two Python threads against the same two one after the other,
interleaved, on the reference backend with the oscillators one after the
other (so that each solve is one thread of work), reporting the ratio
parallel / sequential (issue 31's target: <= 0.65 on 2 cores). The same two
solves in two forked processes (no GIL by construction) run in the same
loop: the ceiling the machine gives at that moment, so that a loaded shared
machine shows whether threads reach what processes reach. JSON with --json.

    PYTHONPATH=build/python python3 bench/python_threads.py [--shape disk] [--vertices 64000] [--repeat 3]
"""
import argparse
import json
import os
import statistics
import threading
import time

import glpgp


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shape", default="disk")
    ap.add_argument("--vertices", type=int, default=64000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--json", default=None)
    args = ap.parse_args()
    meshes = [glpgp.shape(args.shape, args.vertices), glpgp.shape(args.shape, args.vertices + 1000)]
    opts = dict(backend="reference", oscillators="sequential")

    def seq():
        for m in meshes:
            glpgp.solve(m, **opts)

    def par():
        th = [threading.Thread(target=glpgp.solve, args=(m,), kwargs=opts) for m in meshes]
        for t in th:
            t.start()
        for t in th:
            t.join()

    def procs():
        pids = []
        for m in meshes:
            pid = os.fork()
            if pid == 0:
                try:
                    glpgp.solve(m, **opts)
                finally:
                    os._exit(0)
            pids.append(pid)
        for pid in pids:
            os.waitpid(pid, 0)

    seq()  # warm-up (page cache, allocator)
    times = {"sequential": [], "two threads": [], "two processes": []}
    for _ in range(args.repeat):
        for name, fn in (("sequential", seq), ("two threads", par), ("two processes", procs)):
            t0 = time.perf_counter()
            fn()
            times[name].append(time.perf_counter() - t0)
    ratios = [p / s for s, p in zip(times["sequential"], times["two threads"])]
    pratios = [p / s for s, p in zip(times["sequential"], times["two processes"])]
    out = {"shape": args.shape, "vertices": [m.n_vertices for m in meshes], "cpus": os.cpu_count(),
           "load_average": os.getloadavg(), "seconds": times, "ratio_median": statistics.median(ratios),
           "ratios": ratios, "process_ratio_median": statistics.median(pratios), "process_ratios": pratios}
    print("%s, %s vertices, %d CPUs, load %.1f: sequential %s s, two threads %s s, two processes %s s" % (
        args.shape, out["vertices"], os.cpu_count(), os.getloadavg()[0], ["%.2f" % t for t in times["sequential"]],
        ["%.2f" % t for t in times["two threads"]], ["%.2f" % t for t in times["two processes"]]))
    print("threads / sequential %s (median %.3f); processes / sequential %s (median %.3f)" % (
        ["%.3f" % r for r in ratios], out["ratio_median"], ["%.3f" % r for r in pratios],
        out["process_ratio_median"]))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(out, f, indent=2)


if __name__ == "__main__":
    main()
