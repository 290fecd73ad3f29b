"""3D surfaces from Python: a built-in surface and arrays of 3D points are surfaces (3 columns of
vertices), solve() takes the cross field on them by default, and the cross field's indices, with
the surface's holonomy, sum to its Euler characteristic; the same result as the CLI's."""
import numpy as np
import pytest

import glpgp
from conftest import run_cli


def test_sphere_cross_field_and_singularities():
    m = glpgp.shape("sphere", 3000)
    assert m.vertices.shape == (m.n_vertices, 3)
    assert np.allclose(np.linalg.norm(m.vertices, axis=1), 1.0, atol=1e-9)
    r = glpgp.solve(m, backend="reference")
    c = r.cross
    assert c is not None  # the cross field is a surface's default
    assert c["index_sum"] == 2.0 and c["poincare_hopf"]
    s = c["singularities"]
    assert len(s) >= 8 and {"x", "y", "z"} <= set(s.dtype.names)
    # the singularities lie on the sphere (the mesh's chords: within 2%)
    assert np.all(np.abs(np.sqrt(s["x"] ** 2 + s["y"] ** 2 + s["z"] ** 2) - 1.0) < 0.02)
    for k in ("u", "v"):
        sing = getattr(r, "singular_" + k)
        assert {"x", "y", "z"} <= set(sing.dtype.names)
    assert np.median(np.abs(r.z_u)) > 0.9


def test_torus_cross_field_follows_the_principal_directions():
    # the principal-curvature term (cross_align, on by default): a torus's cross field has no
    # singularity; the smoothest field alone (cross_align=0) has some
    m = glpgp.shape("torus", 3000)
    a = glpgp.solve(m, backend="reference", method="pgp").cross
    b = glpgp.solve(m, backend="reference", method="pgp", cross_align=0).cross
    assert len(a["singularities"]) == 0 and a["index_sum"] == 0.0
    assert len(b["singularities"]) > 0 and b["index_sum"] == 0.0
    with pytest.raises(Exception, match="cross-align|cross_align"):
        glpgp.solve(m, backend="reference", cross_align=-1)


def test_surface_from_arrays_equals_the_cli(cli, tmp_path):
    # the half cylinder (open, two straight boundary edges) given as arrays of 3D points
    h = glpgp.shape("halfcyl", 2000)
    m = glpgp.Mesh(np.array(h.vertices), np.array(h.triangles))
    assert m.vertices.shape[1] == 3
    assert np.array_equal(m.vertices, h.vertices)
    for field in ("boundary", None):
        kw = {} if field is None else {"field": field}
        r = glpgp.solve(m, backend="reference", **kw)
        assert np.median(np.abs(r.z_u)) > 0.9
        args = [] if field is None else ["--field", field]
        run_cli(cli, "solve", "shape:halfcyl:2000", "--backend", "reference", "-o", str(tmp_path / "c.vtu"),
                "--quiet", *args)
        c = glpgp.read_result(tmp_path / "c.vtu")
        assert np.array_equal(r.z_u, c.z_u) and np.array_equal(r.z_v, c.z_v)  # bit for bit


def test_surface_refuses_vector_field():
    m = glpgp.shape("sphere", 2000)
    with pytest.raises(glpgp.InputError, match="surface"):
        glpgp.solve(m, field=np.ones((m.n_vertices, 2)), backend="reference")


def test_surface_quads(tmp_path):
    """quads of a surface from Python: all quads, 3D points on the sphere, the report's surface block"""
    r = glpgp.solve(glpgp.shape("sphere", 20000), backend="reference")
    q = r.quads()
    assert q.valid and q.vertices.shape[1] == 3
    # vertices lie on the triangle mesh: inside the unit sphere by at most its chords' depth
    assert np.allclose(np.linalg.norm(q.vertices, axis=1), 1.0, atol=1e-3)
    assert q.faces.shape[1] == 4 and len(q.faces) > 50
    assert "surface" in q.report
    steps = q.report["surface"]["steps"]  # what the surface pipeline did, as the CLI's JSON
    assert steps["extracted_faces"] > 0 and steps["path"] in ("grid", "local repair", "local split", "split h/2")
    q.write(tmp_path / "s.obj")
    assert (tmp_path / "s.obj").stat().st_size > 0


def test_surface_arrays_repaired_like_a_file():
    """a closed surface given with one face flipped and a second one touching it at a vertex: Mesh()
    repairs it as the readers do (the face flipped back outward, the vertex split per sheet)"""
    x = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [-1, 0, 0], [0, -1, 0], [0, 0, -1]], float)
    t = np.array([[0, 2, 1], [0, 3, 1], [1, 2, 3], [0, 3, 2],  # tetrahedron, face 1 flipped
                  [0, 4, 5], [0, 6, 4], [4, 6, 5], [0, 5, 6]])  # another one at vertex 0
    m = glpgp.Mesh(x, t)
    assert m.n_vertices == 8 and m.n_triangles == 8
    tri = m.triangles
    assert list(tri[1]) == [0, 1, 3]
    v = m.vertices
    for part in (tri[:4], tri[4:]):  # each part encloses a positive volume: outward
        assert sum(np.dot(v[a], np.cross(v[b], v[c])) for a, b, c in part) > 0


def test_noisy_surface_denoised():
    """a sphere with a radial jitter of half an edge: solve() smooths the noise away first (denoise,
    'auto' by default) and the cross field has the sphere's 8 singularities; the stats say what moved;
    denoise='off' solves the jitter as it is (more singularities) and the stats say nothing moved"""
    s = glpgp.shape("sphere", 3000)
    v = np.array(s.vertices)
    rng = np.random.default_rng(3)
    edge = np.mean(np.linalg.norm(v[s.triangles[:, 0]] - v[s.triangles[:, 1]], axis=1))
    v *= (1.0 + 0.5 * edge * rng.uniform(-1.0, 1.0, len(v)))[:, None]
    m = glpgp.Mesh(v, np.array(s.triangles))
    a = glpgp.solve(m, backend="reference", method="pgp")
    d = a.stats["mesh"]["surface"]["denoise"]
    assert d["noise_edges"] > 100 and d["noise_edges_after"] <= d["noise_edges"] // 100, d
    assert 0 < d["max_move_over_h"] <= 0.1 + 1e-9 and d["defect_rms_after"] < 0.3 * d["defect_rms"], d
    assert len(a.cross["singularities"]) == 8
    b = glpgp.solve(m, backend="reference", method="pgp", denoise="off")
    assert b.stats["mesh"]["surface"]["denoise"] is None
    assert len(b.cross["singularities"]) > 8
    with pytest.raises(Exception, match="denoise"):
        glpgp.solve(m, backend="reference", denoise="sometimes")
