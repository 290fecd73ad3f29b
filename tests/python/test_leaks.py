"""tests/python/test_leaks.py: no leaks: 1000 small solves (with their
arrays, statistics, quads and a rejected input each) leave the process's
resident memory and Python's traced allocations where they were after the
first 100."""
import gc
import tracemalloc

import pytest

import glpgp


def rss_kib():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4


def one(m, k):
    r = glpgp.solve(m, backend="reference", oscillators="sequential", size_field="none", size=0.3)
    r.z_u.sum()
    r.theta_v.sum()
    r.singular_u
    r.stats
    q = r.quads()
    q.report
    q.faces
    if k % 10 == 0:
        with pytest.raises(glpgp.InputError):
            glpgp.solve(m, newton_max=0)


def test_1000_solves():
    m = glpgp.shape("square", 400)
    for k in range(100):
        one(m, k)
    gc.collect()
    tracemalloc.start()
    snap0 = tracemalloc.take_snapshot()
    rss0 = rss_kib()
    for k in range(900):
        one(m, k)
    gc.collect()
    rss1 = rss_kib()
    snap1 = tracemalloc.take_snapshot()
    tracemalloc.stop()
    grown = sum(s.size_diff for s in snap1.compare_to(snap0, "filename"))
    print("RSS %d -> %d KiB, traced Python allocations %+d bytes" % (rss0, rss1, grown))
    # a leak of one result per solve would be >= 900 x 400 x 40 bytes = 14 MiB
    assert rss1 - rss0 < 2048, (rss0, rss1)
    assert grown < 64 * 1024, grown
