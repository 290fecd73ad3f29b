"""tests/python/conftest.py: what the Python tests share. ctest runs each
test_*.py file with PYTHONPATH=<build>/python (the package as built),
GLPGP_CLI=<build>/glpgp, GLPGP_DATA=<source>/data and POCL_CACHE_DIR set
(tests/CMakeLists.txt)."""
import os
import subprocess

import pytest

import glpgp

CLI = os.environ.get("GLPGP_CLI", "")
DATA = os.environ.get("GLPGP_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))


@pytest.fixture(scope="session")
def cli():
    """The path of the glpgp executable of the same build."""
    if not CLI or not os.path.exists(CLI):
        pytest.skip("GLPGP_CLI does not name the glpgp executable")
    return CLI


@pytest.fixture(scope="session")
def data():
    return DATA


@pytest.fixture(scope="session")
def have_opencl():
    return bool(glpgp.devices())


def run_cli(cli, *args, cwd=None, check=True):
    """Run the CLI; returns the CompletedProcess (stdout, stderr as text)."""
    p = subprocess.run([cli, *args], cwd=cwd, capture_output=True, text=True, timeout=600)
    if check and p.returncode != 0:
        raise AssertionError("glpgp %s: exit %d: %s" % (" ".join(args), p.returncode, p.stderr[-2000:]))
    return p
