"""tests/python/test_interrupt.py: Ctrl-C stops a solve at its next Newton
step: a SIGINT (or _thread.interrupt_main) during glpgp.solve raises
KeyboardInterrupt within a fraction of the solve's time, with the oscillators
one after the other or in two threads, and leaves nothing behind (no file of
the interrupted run, the next solve works and gives the same result)."""
import _thread
import os
import signal
import threading
import time

import numpy as np
import pytest

import glpgp

MESH = dict(name="disk", n=8000)


@pytest.fixture(scope="module")
def full_time():
    m = glpgp.shape(**MESH)
    t0 = time.perf_counter()
    r = glpgp.solve(m, backend="reference", oscillators="sequential")
    return time.perf_counter() - t0, r


@pytest.mark.parametrize("how", ["interrupt_main", "sigint"])
@pytest.mark.parametrize("osc", ["sequential", "concurrent"])
def test_ctrl_c_stops_the_solve(tmp_path, full_time, how, osc):
    total, ref = full_time
    m = glpgp.shape(**MESH)
    delay = 0.25 * total
    send = _thread.interrupt_main if how == "interrupt_main" else (lambda: os.kill(os.getpid(), signal.SIGINT))
    timer = threading.Timer(delay, send)
    t0 = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        r = glpgp.solve(m, backend="reference", oscillators=osc)
        r.write(tmp_path / "r.vtu")
        time.sleep(10 * total)  # not reached: the interrupt comes during the solve
    elapsed = time.perf_counter() - t0
    timer.join()
    # the solve did not complete: nothing was written (r.write comes after it)
    assert os.listdir(tmp_path) == []
    # nothing left behind: the library works on, with the same result
    t1 = time.perf_counter()
    again = glpgp.solve(m, backend="reference", oscillators=osc)
    full = max(total, time.perf_counter() - t1)
    assert np.array_equal(again.z_u, ref.z_u)
    # stopped at a Newton step soon after the signal, well before a whole solve's time
    assert elapsed < delay + 0.6 * full, (elapsed, delay, full)
