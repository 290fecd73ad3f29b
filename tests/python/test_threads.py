"""tests/python/test_threads.py: the GIL is released while the library works:
two solves in two Python threads give the results of one after the other
(bit for bit), and Python code keeps running in the main thread while a
solve runs in another (a solve holding the GIL would let it run only between
log lines). The speed-up itself is a benchmark (bench/python_threads.py)."""
import threading
import time

import numpy as np

import glpgp

OPTS = dict(backend="reference", oscillators="sequential")


def test_two_solves_at_once():
    meshes = [glpgp.shape("disk", 4000), glpgp.shape("annulus", 4000)]
    seq = [glpgp.solve(m, **OPTS) for m in meshes]
    out = [None, None]
    errs = []

    def work(k):
        try:
            out[k] = glpgp.solve(meshes[k], **OPTS)
            out[k].quads()
        except BaseException as e:  # pragma: no cover - reported below
            errs.append(e)

    th = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for t in th:
        t.start()
    for t in th:
        t.join()
    assert not errs, errs
    for k in range(2):
        assert np.array_equal(out[k].z_u, seq[k].z_u) and np.array_equal(out[k].z_v, seq[k].z_v)


def test_main_thread_runs_during_a_solve():
    """the main thread's own CPU time while a solve runs in another thread: a
    solve holding the GIL would leave it none (the library's messages, which
    run Python code, are switched off: no GIL hand-over through them)"""
    m = glpgp.shape("disk", 8000)
    done = threading.Event()
    res = []
    t = threading.Thread(target=lambda: (res.append(glpgp.solve(m, **OPTS)), done.set()))
    glpgp._glpgp._set_logging(False)
    try:
        t0, c0 = time.perf_counter(), time.thread_time()
        t.start()
        while not done.is_set():
            sum(range(200))
        t.join()
        elapsed, cpu = time.perf_counter() - t0, time.thread_time() - c0
    finally:
        glpgp._glpgp._set_logging(True)
    assert res and elapsed > 0.2
    # holding the GIL, the solve would leave the main thread a switch interval or two (5 ms each)
    assert cpu > 0.05 * elapsed and cpu > 0.05, (cpu, elapsed)
