"""tests/python/test_examples.py: the examples of examples/python run (on
small inputs) and write what they say."""
import os
import subprocess
import sys

import pytest

EX = os.path.join(os.environ.get("GLPGP_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")),
                  "examples", "python")


def run(tmp_path, name, *args):
    env = dict(os.environ, MPLBACKEND="Agg")
    p = subprocess.run([sys.executable, os.path.join(EX, name), *args], cwd=tmp_path, env=env, capture_output=True,
                       text=True, timeout=300)
    assert p.returncode == 0, p.stderr[-3000:]
    return p.stdout


def test_quads_picture(tmp_path):
    out = run(tmp_path, "quads_picture.py", "--vertices", "2000", "-o", "q.png")
    assert "wrote" in out and (tmp_path / "q.png").read_bytes()[:4] == b"\x89PNG"


def test_size_sweep(tmp_path):
    out = run(tmp_path, "size_sweep.py", "--input", "shape:annulus:3000", "--sizes", "0.2,0.3", "--backend",
              "reference", "-o", "s.csv")
    lines = (tmp_path / "s.csv").read_text().splitlines()
    assert len(lines) == 3 and lines[0].startswith("h,") and "wrote" in out


def test_meshio_file(tmp_path):
    pytest.importorskip("meshio")
    run(tmp_path, "meshio_file.py")
    import meshio
    r = meshio.read(tmp_path / "result.vtu")
    assert "z_u" in r.point_data and len(r.points) > 4000
    q = meshio.read(tmp_path / "quads.vtu")
    assert any(c.type == "quad" for c in q.cells)
