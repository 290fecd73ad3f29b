"""tests/python/test_cli_equal.py: glpgp.solve is `glpgp solve`: for the same
input and options the oscillators are bit-identical to the CLI's (.vtu read
back exactly), on the reference backend and on OpenCL (PoCL), the statistics
dict equals the --stats JSON but for timings and the output name, the quad
mesh file and its report equal the CLI's --quads ones byte for byte."""
import json
import os
import re

import numpy as np
import pytest

import glpgp
from conftest import run_cli

TIMING = {"seconds", "output", "phases", "solve_split"}


def strip(stats):
    out = {k: v for k, v in stats.items() if k not in TIMING}
    if out.get("device"):  # "...; build 0.15 s)": the program's build time
        out["device"] = re.sub(r"; build [0-9.]+ s", "", out["device"])
    if "cross_field" in out:
        out["cross_field"] = {k: v for k, v in out["cross_field"].items() if k != "seconds"}
    return out


def compare(tmp_path, cli, source, args, kwargs, quads=False):
    files = ["-o", str(tmp_path / "c.vtu"), "--stats", str(tmp_path / "c.json")]
    if quads:
        files += ["--quads", str(tmp_path / "c_quads.obj")]
    run_cli(cli, "solve", source, *args, *files, "--quiet")
    c = glpgp.read_result(tmp_path / "c.vtu")
    mesh = glpgp.read(source)
    r = glpgp.solve(mesh, **kwargs)
    assert r.mesh.n_vertices == c.mesh.n_vertices
    assert np.array_equal(r.mesh.vertices, c.mesh.vertices)
    for k in ("z_u", "z_v", "field"):
        assert np.array_equal(getattr(r, k), getattr(c, k)), k  # bit for bit
    cs = json.loads((tmp_path / "c.json").read_text())
    ps = r.stats
    if quads:
        q = r.quads()
        q.write(tmp_path / "p_quads.obj")
        assert (tmp_path / "p_quads.obj").read_bytes() == (tmp_path / "c_quads.obj").read_bytes()
        assert q.report == cs.pop("quads")
    assert strip(ps) == strip(cs)
    return r


def test_reference_default(tmp_path, cli):
    """the default pipeline: a coarse disk refined for the local size (with --quads the CLI takes the
    cross field unless --field is given; glpgp.solve knows nothing of the quads to come)"""
    r = compare(tmp_path, cli, "shape:disk:3000", ["--backend", "reference", "--field", "boundary"],
                dict(backend="reference"), quads=True)
    assert r.refined is not None and r.mesh.n_vertices > 2923


def test_reference_file_and_options(tmp_path, cli):
    src = str(tmp_path / "annulus.msh")
    glpgp.shape("annulus", 3000).write(src)
    compare(tmp_path, cli, src,
            ["--backend", "reference", "--size", "0.15", "--tr-precond", "jacobi", "--globalization", "line-search",
             "--oscillators", "concurrent", "--newton-rtol", "1e-5", "--center", "0.001,-0.002", "--field", "radial"],
            dict(backend="reference", size=0.15, tr_precond="jacobi", globalization="line-search",
                 oscillators="concurrent", newton_rtol=1e-5, center=(0.001, -0.002), field="radial"))


def test_reference_field_file(tmp_path, cli):
    """--field FILE and field=array: the same guiding field, the same z"""
    m = glpgp.shape("lshape", 2000)
    x, y = m.vertices.T
    f = np.column_stack([np.cos(x + 2 * y), np.sin(x + 2 * y)])
    np.savetxt(tmp_path / "f.txt", f, fmt="%.17g")
    run_cli(cli, "solve", "shape:lshape:2000", "--backend", "reference", "--field", str(tmp_path / "f.txt"),
            "-o", str(tmp_path / "c.vtu"), "--quiet")
    c = glpgp.read_result(tmp_path / "c.vtu")
    r = glpgp.solve(m, backend="reference", field=f)
    assert np.array_equal(r.z_u, c.z_u) and np.array_equal(r.z_v, c.z_v)
    r2 = glpgp.solve(m, backend="reference", field=str(tmp_path / "f.txt"))
    assert np.array_equal(r2.z_u, c.z_u)


def test_reference_cross(tmp_path, cli):
    compare(tmp_path, cli, "shape:disk:1500", ["--backend", "reference", "--field", "cross"],
            dict(backend="reference", field="cross"), quads=True)


def test_opencl(tmp_path, cli, have_opencl):
    if not have_opencl:
        pytest.skip("no OpenCL device")
    r = compare(tmp_path, cli, "shape:disk:3000", ["--backend", "opencl"], dict(backend="opencl"))
    assert r.backend == "opencl" and r.device
    ref = glpgp.solve(glpgp.shape("disk", 3000), backend="reference")
    # the two backends agree to the Newton tolerance (glpgp crosscheck's)
    assert np.abs(r.z_u - ref.z_u).max() < 1e-4
    cc = glpgp.crosscheck(glpgp.shape("disk", 2000), solve=False)
    assert cc["pass"] and len(cc["rows"]) > 20


def test_no_opencl_is_an_error_only_when_asked(have_opencl):
    if have_opencl:
        pytest.skip("an OpenCL device is present")
    with pytest.raises(glpgp.Error):
        glpgp.solve(glpgp.shape("square", 400), backend="opencl")
