"""tests/python/test_api.py: the package's objects and functions: meshes
from arrays (2D, 3D planar) and their validation, files, shapes, reprs, the
option tables behind the keyword arguments (names, defaults and checks of the
CLI), exceptions (InputError is a ValueError, FileError an OSError, carrying
the library's one-line message: the CLI's error line for the same input),
results, quads, writers, meshio interop, docstrings and the .pyi stub."""
import ast
import inspect
import json
import os
import warnings

import numpy as np
import pytest

import glpgp
from conftest import run_cli

SQ = dict(backend="reference", oscillators="sequential", size_field="none", size=0.3)


def square_arrays(n=6):
    x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    v = np.column_stack([x.ravel(), y.ravel()])
    t = []
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            t += [(a, a + 1, a + n + 1), (a, a + n + 1, a + n)]
    return v, np.array(t)


def test_mesh_from_arrays():
    v, t = square_arrays()
    m = glpgp.Mesh(v, t)
    assert m.n_vertices == 36 and m.n_triangles == 50
    assert m.vertices.shape == (36, 2) and m.vertices.dtype == np.float64
    assert m.triangles.shape == (50, 3) and m.triangles.dtype == np.int32
    assert abs(m.area - 1.0) < 1e-12 and m.bbox == (0.0, 0.0, 1.0, 1.0)
    assert len(m.boundary_loops) == 1 and len(m.boundary_loops[0]) == 20
    assert not m.vertices.flags.writeable
    assert m.source is None and "36 vertices" in repr(m)
    # any int / float array-likes, lists too; 3D points in the plane z = 2
    m2 = glpgp.Mesh(v.tolist(), t.astype(np.int16).tolist(), name="sq")
    assert np.array_equal(m2.vertices, m.vertices) and m2.source == "sq"
    m3 = glpgp.Mesh(np.column_stack([v, np.full(len(v), 2.0)]), t)
    assert np.array_equal(m3.vertices, m.vertices)
    # a side view: the plane y = const is solved in (x, z)
    m4 = glpgp.Mesh(np.column_stack([v[:, 0], np.zeros(len(v)), v[:, 1]]), t)
    assert np.array_equal(m4.vertices, m.vertices)
    # copied in: changing the input afterwards changes nothing
    v[0, 0] = 5.0
    assert m.vertices[0, 0] == 0.0


@pytest.mark.parametrize("bad, what", [
    ("shape", "must be an (n, 2) or (n, 3) array"),
    ("index", "uses vertex"),
    ("degenerate", "degenerate"),
    ("nan", "not finite"),
    ("empty", "no triangles"),
])
def test_mesh_rejected(bad, what):
    v, t = square_arrays()
    if bad == "shape":
        v = np.column_stack([v, v])
    elif bad == "index":
        t = t.copy()
        t[3, 1] = 99
    elif bad == "degenerate":
        t = np.vstack([t, [[0, 1, 2]]])  # three vertices on a line
    elif bad == "nan":
        v = v.copy()
        v[4, 1] = np.nan
    elif bad == "empty":
        t = np.zeros((0, 3), int)
    with pytest.raises(glpgp.InputError) as e:
        glpgp.Mesh(v, t)
    assert isinstance(e.value, ValueError) and isinstance(e.value, glpgp.Error)
    assert what in str(e.value)
    with pytest.raises(TypeError):
        glpgp.Mesh(v, t.astype(float) + 0.5)  # indices must be integers


def test_shape_read_write(tmp_path, data):
    m = glpgp.shape("disk", 2000)
    assert m.source == "shape:disk:2000" and m.n_vertices > 1500
    assert glpgp.read("shape:disk:2000").n_vertices == m.n_vertices
    p = tmp_path / "m.msh"
    m.write(p)
    back = glpgp.read(p)
    assert np.array_equal(back.vertices, m.vertices) and np.array_equal(back.triangles, m.triangles)
    assert back.source == str(p)
    plate = glpgp.read(os.path.join(data, "plate_holes.msh"))
    assert len(plate.boundary_loops) > 1
    with pytest.raises(glpgp.InputError):
        glpgp.shape("hexagon", 100)
    with pytest.raises(glpgp.InputError, match="max_elements"):
        glpgp.shape("disk", 1000000, max_elements=1000)


def test_errors_carry_the_library_message(tmp_path, cli):
    """the exception's text is the CLI's error line for the same input"""
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n")
    with pytest.raises(glpgp.InputError) as e:
        glpgp.read(bad)
    p = run_cli(cli, "solve", str(bad), check=False)
    assert p.returncode == 1
    assert p.stderr.strip() == "glpgp: error: " + str(e.value)
    assert e.value.status == "mesh error"
    with pytest.raises(glpgp.FileError) as e:
        glpgp.read(tmp_path / "missing.msh")
    assert isinstance(e.value, OSError) and "missing.msh" in str(e.value)
    with pytest.raises(glpgp.FileError):
        glpgp.shape("square", 100).write(tmp_path / "no" / "dir" / "m.obj")


def test_option_values_checked_by_the_library(cli):
    m = glpgp.shape("square", 400)
    # the CLI's reasons for the same values
    cases = [("size", 0, "--size", "0"), ("newton_max", 0, "--newton-max", "0"), ("method", "x", "--method", "x"),
             ("eps_ratio", 1.0, "--eps-ratio", "1"), ("cross_size_ratio", 0.5, "--cross-size-ratio", "0.5")]
    for key, value, opt, text in cases:
        with pytest.raises(glpgp.InputError) as e:
            glpgp.solve(m, **{key: value})
        p = run_cli(cli, "solve", "shape:square:400", opt, text, check=False)
        assert p.returncode == 2
        reason = p.stderr.splitlines()[0].split("'%s' " % text, 1)[1]
        assert str(e.value).endswith(reason), (str(e.value), reason)
    with pytest.raises(TypeError, match="unexpected keyword argument 'no_such'"):
        glpgp.solve(m, no_such=1)
    with pytest.raises(TypeError):
        glpgp.solve(m, newton_max="5")
    with pytest.raises(TypeError):
        glpgp.solve(m, input_order="yes")
    with pytest.raises(glpgp.InputError):
        glpgp.solve(m, backend="gpu")
    with pytest.raises(glpgp.InputError, match="field"):
        glpgp.solve(m, field=np.ones((3, 2)))
    # a size outside 2 mean edges .. 100 diameters
    with pytest.raises(glpgp.InputError, match="mean edge lengths"):
        glpgp.solve(m, size=1e-4, size_field="none")


def test_options_table_is_the_clis(cli):
    names = {o["name"]: o for o in glpgp.options("solve")}
    assert {"size", "method", "field", "newton_max", "precond", "oscillators", "input_order"} <= set(names)
    assert names["newton_max"]["default"] == "50" and names["newton_max"]["range"] == "an integer >= 1"
    help_text = run_cli(cli, "solve", "--help").stdout
    for o in glpgp.options("solve"):
        assert "--" + o["cli"] in help_text
    quads = {o["name"] for o in glpgp.options("quads")}
    assert quads == {"keep_polygons", "smooth", "all_quads", "repair", "cleanup"}
    assert {o["name"] for o in glpgp.options("render")} == {"size", "kind", "background", "view", "line_width"}
    assert "newton_max" in glpgp.solve.__doc__ and "Newton iterations per eps level" in glpgp.solve.__doc__


def test_result_arrays_and_stats(tmp_path):
    m = glpgp.shape("square", 400)
    r = glpgp.solve(m, **SQ)
    n = r.mesh.n_vertices
    assert r.mesh is m  # not refined
    assert r.z_u.dtype == np.complex128 and r.z_u.shape == (n,)
    assert np.allclose(np.abs(r.z_u), 1.0, atol=0.6)
    th = np.angle(r.z_v) / (2 * np.pi) % 1.0
    assert np.allclose(np.where(th >= 1.0, 0.0, th), r.theta_v)
    assert r.field.shape == (n, 2) and np.allclose(np.hypot(*r.field.T), 1.0)
    assert r.dirichlet_u.dtype == bool and r.dirichlet_u.any()
    assert r.winding_u.shape == (m.n_triangles,)
    assert r.singular_u.dtype.names == ("triangle", "index", "x", "y", "z") and len(r.singular_u) == 0
    assert r.cross is None and r.converged and r.size == 0.3 and r.backend == "reference"
    s = r.stats
    assert s["input"] == "shape:square:400" and s["vertices"] == n and s["backend"] == "reference"
    assert s["options"]["oscillators"] == "sequential" and s["converged"]["all"] is True
    assert "400 vertices" in repr(r) and "converged" in repr(r)
    for name in ("r.vtu", "r.vtk", "r.obj", "r.json"):
        r.write(tmp_path / name)
    back = glpgp.read_result(tmp_path / "r.vtu")
    assert np.array_equal(back.z_u, r.z_u) and np.array_equal(back.z_v, r.z_v)
    assert json.loads((tmp_path / "r.json").read_text())["vertices"] == n
    with pytest.raises(glpgp.InputError):
        r.write(tmp_path / "r.txt")
    assert sorted(os.listdir(tmp_path)) == ["r.json", "r.obj", "r.vtk", "r.vtu"]  # no temporaries left


def test_singularities_and_cross_field():
    r = glpgp.solve(glpgp.shape("disk", 3000), backend="reference", field="cross")
    c = r.cross
    assert c is not None and c["poincare_hopf"] and c["index_sum"] == 1.0
    assert len(c["singularities"]) >= 4 and set(np.abs(c["singularities"]["index"])) == {0.25}
    assert c["w"].dtype == np.complex128 and (c["alpha"] >= 0).all() and (c["alpha"] <= np.pi / 2).all()
    assert r.stats["cross_field"]["singularities"] == len(c["singularities"])
    for k in ("u", "v"):
        sing = getattr(r, "singular_" + k)
        wind = getattr(r, "winding_" + k)
        assert len(sing) == np.count_nonzero(wind)
        assert np.array_equal(sing["index"], wind[sing["triangle"]])
        tri = r.mesh.triangles[sing["triangle"]]
        assert np.allclose(sing["x"], r.mesh.vertices[tri, 0].mean(axis=1))


def test_field_array_and_with_z():
    m = glpgp.shape("square", 400)
    f = np.tile([1.0, 0.0], (m.n_vertices, 1))
    r = glpgp.solve(m, field=f, **SQ)
    assert np.allclose(r.field, f) and r.stats["field"] == "file"
    with pytest.raises(glpgp.InputError, match="zero vector"):
        glpgp.solve(m, field=np.zeros((m.n_vertices, 2)), **SQ)
    # the quad extraction on a modified field: a vortex put into z_u
    x, y = m.vertices.T
    z = (x - 0.5 + 1j * (y - 0.5)) * np.exp(2j * np.pi * x / 0.3)
    r2 = r.with_z(z_u=z)
    assert r2.stats["singularities"]["u"]["plus"] + r2.stats["singularities"]["u"]["minus"] >= 1
    assert np.array_equal(r2.z_v, r.z_v) and r2.quads(repair=False, cleanup=False) is not None


def test_quads_and_writers(tmp_path):
    r = glpgp.solve(glpgp.shape("square", 400), **SQ)
    q = r.quads()
    assert q.valid and q.invalid_reasons == "" and "valid" in repr(q)
    assert q.faces.shape == (9, 4) and q.vertices.shape == (16, 2)
    assert q.report["faces"] == 9 and q.report["valid"] is True
    assert np.array_equal(np.diff(q.face_offsets), np.full(9, 4))
    q.write(tmp_path / "q.obj")
    assert (tmp_path / "q.obj").read_text().count("\nf ") == 9
    assert r.quads(all_quads=True).report["faces"] == 36
    with pytest.raises(glpgp.InputError, match="smooth"):
        r.quads(smooth=-1)
    with pytest.raises(TypeError):
        r.quads(keep_polygons="yes")


def test_invalid_quad_mesh_flagged(tmp_path):
    """a collapsed solve (h of 2 mean edges): the repair off, the mesh is invalid: a warning,
    valid False, not written unless allow_invalid"""
    m = glpgp.shape("disk", 2000)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = glpgp.solve(m, backend="reference", size_field="none", size=2.2 * m.mean_edge, newton_max=2)
    with pytest.warns(glpgp.QualityWarning):
        q = r.quads(repair=False, cleanup=False, smooth=0)
    assert not q.valid and q.invalid_reasons
    with pytest.raises(glpgp.InvalidQuadMeshError):
        q.write(tmp_path / "q.obj")
    assert not os.listdir(tmp_path)
    q.write(tmp_path / "q.obj", allow_invalid=True)
    assert os.path.exists(tmp_path / "q.obj")


def test_unconverged_flagged():
    m = glpgp.shape("disk", 2000)
    with pytest.warns(glpgp.ConvergenceWarning, match="Newton cap"):
        r = glpgp.solve(m, backend="reference", newton_max=1)
    assert r.converged is False and r.stats["converged"]["all"] is False
    assert "UNCONVERGED" in repr(r)


def test_logging(caplog):
    import logging
    with caplog.at_level(logging.INFO, logger="glpgp"):
        glpgp.solve(glpgp.shape("square", 400), **SQ)
    msgs = [rec.getMessage() for rec in caplog.records if rec.name == "glpgp"]
    assert any("level 1/" in msg for msg in msgs) and any("done in" in msg for msg in msgs)


def test_render(tmp_path):
    r = glpgp.solve(glpgp.shape("square", 400), **SQ)
    im = glpgp.render(r, size=64, kind="zabs")
    assert im.shape == (64, 64, 4) and im.dtype == np.float32
    with pytest.raises(glpgp.InputError):
        glpgp.render(r, kind="nope")
    if glpgp.build_info()["openimageio"]:
        glpgp.render(r, tmp_path / "r.png", size=64)
        assert (tmp_path / "r.png").read_bytes()[:4] == b"\x89PNG"


def test_meshio_interop(tmp_path):
    meshio = pytest.importorskip("meshio")
    r = glpgp.solve(glpgp.shape("square", 400), **SQ)
    mm = r.to_meshio()
    assert mm.points.shape == (400, 3) and "z_u" in mm.point_data and "singular_u" in mm.cell_data
    meshio.write(tmp_path / "r.vtu", mm)
    back = meshio.read(tmp_path / "r.vtu")
    m2 = glpgp.Mesh.from_meshio(back)
    assert np.array_equal(m2.vertices, r.mesh.vertices) and np.array_equal(m2.triangles, r.mesh.triangles)
    qm = r.quads().to_meshio()
    assert qm.cells[0].type == "quad" and len(qm.cells[0].data) == 9
    # a meshio file read through meshio and solved: the same as glpgp.read
    r.mesh.write(tmp_path / "m.msh")
    a = glpgp.solve(glpgp.Mesh.from_meshio(meshio.read(tmp_path / "m.msh")), **SQ)
    assert np.array_equal(a.z_u, r.z_u)


def test_devices_and_build_info():
    info = glpgp.build_info()
    assert info["version"] == glpgp.__version__
    devs = glpgp.devices()
    assert isinstance(devs, list)
    for d in devs:
        assert {"index", "name", "fp64", "type", "default"} <= set(d)


def test_docstrings_and_stub():
    for name in glpgp.__all__:
        obj = getattr(glpgp, name)
        if name.startswith("__"):
            continue
        assert obj.__doc__ and obj.__doc__.strip(), name
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            for attr, member in vars(obj).items():
                if not attr.startswith("_"):
                    assert getattr(member, "__doc__", None), "%s.%s" % (name, attr)
    stub = os.path.join(os.path.dirname(glpgp.__file__), "__init__.pyi")
    text = open(stub).read()
    ast.parse(text)
    for name in glpgp.__all__:
        if not name.startswith("__"):
            assert ("def %s(" % name) in text or ("class %s(" % name) in text or ("class %s:" % name) in text, name


def test_petsc_backend():
    """--backend petsc on one rank (MPI started in this process on demand)"""
    if not glpgp.build_info()["petsc"]:
        pytest.skip("built without PETSc")
    m = glpgp.shape("square", 400)
    r = glpgp.solve(m, backend="petsc", size_field="none", size=0.3)
    ref = glpgp.solve(m, **SQ)
    assert r.backend == "petsc" and np.abs(r.z_u - ref.z_u).max() < 1e-6
