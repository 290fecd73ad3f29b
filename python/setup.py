"""python/setup.py: the glpgp package built by CMake for pip
(pyproject.toml): configures the repository one level up with the Python
binding on and the tests and benchmark off, builds the extension (and, with
it, the image / PETSc modules the library loads on demand), and puts them in
the package: glpgp/_glpgp*.so, glpgp/modules/*.so."""
import glob
import os
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def version():
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        return re.search(r"project\(glpgp VERSION ([0-9.]+)", f.read()).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.path.abspath(os.path.join(self.build_temp, "cmake"))
        os.makedirs(build, exist_ok=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 2))
        subprocess.check_call(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                               "-DGLPGP_BUILD_TESTS=OFF", "-DGLPGP_BUILD_BENCH=OFF", "-DGLPGP_PYTHON=ON",
                               "-DPython3_EXECUTABLE=" + sys.executable])
        subprocess.check_call(["cmake", "--build", build, "-j", jobs, "--target", "glpgp_python"])
        built = glob.glob(os.path.join(build, "python", "glpgp", "_glpgp*.so"))
        if not built:
            raise RuntimeError("the CMake build made no glpgp extension (see its output: Python headers or "
                               "NumPy missing?)")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built[0], target)
        modules = os.path.join(os.path.dirname(target), "modules")
        os.makedirs(modules, exist_ok=True)
        for mod in glob.glob(os.path.join(build, "modules", "glpgp_*.so")):
            shutil.copyfile(mod, os.path.join(modules, os.path.basename(mod)))


setup(version=version(), ext_modules=[Extension("glpgp._glpgp", sources=[])], cmdclass={"build_ext": CMakeBuild})
