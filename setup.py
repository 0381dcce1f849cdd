"""Builds the nbar wheel: setuptools for the pure-Python package (python/nbar), CMake for the C++
extension nbar._nbar. pyproject.toml holds the metadata; this file adds the version, read from
CMake's project(nbar VERSION ...), and the CMake step.

The extension is built with only what it needs: the core libraries and the module, without the
program, its web app, the tests or the benchmarks (NBAR_BUILD_APPS, NBAR_BUILD_TESTS and
NBAR_BUILD_BENCH off), in build-wheel/. NBAR_REQUIRE_PYTHON makes a missing pybind11 or
Python.h fail the build with the Debian package to install. NBAR_CMAKE_BUILD_DIR names another
build directory: one already configured is built as it is (scripts/package.sh uses the tree's
own build/), another is configured as above. NBAR_CMAKE_ARGS adds arguments to that configure step (for example
-DCMAKE_CXX_COMPILER_LAUNCHER=ccache).
"""

import os
import re
import shlex
import shutil
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def project_version() -> str:
    text = (ROOT / "CMakeLists.txt").read_text()
    match = re.search(r"project\(\s*nbar\s+VERSION\s+([0-9][0-9.]*)", text)
    if not match:
        raise RuntimeError("CMakeLists.txt has no project(nbar VERSION x.y.z)")
    return match.group(1)


class CMakeExtension(Extension):
    def __init__(self, name: str) -> None:
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext: Extension) -> None:
        cmake = shutil.which("cmake")
        if cmake is None:
            raise RuntimeError("building nbar needs CMake: apt-get install cmake")
        # build-wheel/ is beside build/ and as deep, so that ccache (when installed) finds the objects
        # of a build of the tree there: the relative paths in the compile commands are the same.
        build_dir = Path(os.environ.get("NBAR_CMAKE_BUILD_DIR") or ROOT / "build-wheel").resolve()
        given = "NBAR_CMAKE_BUILD_DIR" in os.environ
        if not given or not (build_dir / "CMakeCache.txt").exists():
            self.spawn([cmake, "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                        "-DNBAR_BUILD_APPS=OFF", "-DNBAR_BUILD_TESTS=OFF", "-DNBAR_BUILD_BENCH=OFF",
                        "-DNBAR_REQUIRE_PYTHON=ON", f"-DPython_EXECUTABLE={sys.executable}",
                        *shlex.split(os.environ.get("NBAR_CMAKE_ARGS", ""))])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        self.spawn([cmake, "--build", str(build_dir), "--target", "nbar_python", "-j", jobs])
        built = sorted((build_dir / "python" / "nbar").glob("_nbar*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one _nbar extension in {build_dir}/python/nbar, found {built}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        # The name CMake gave it carries this interpreter's tag (cpython-311-x86_64-linux-gnu).
        if built[0].name != target.name:
            raise RuntimeError(f"the extension {built[0].name} was built for another Python than {target.name}")
        shutil.copyfile(built[0], target)
        # The examples CMake laid out beside the extension (nbar.examples reads them) go in the wheel too.
        examples = build_dir / "python" / "nbar" / "_examples"
        if not examples.is_dir():
            raise RuntimeError(f"the build has no examples in {examples}")
        shutil.copytree(examples, target.parent / "_examples", dirs_exist_ok=True)


(ROOT / "build-wheel" / "setuptools").mkdir(parents=True, exist_ok=True)  # egg_info's must exist before it runs
setup(
    version=project_version(),
    ext_modules=[CMakeExtension("nbar._nbar")],
    cmdclass={"build_ext": CMakeBuild},
    # Out of CMake's build/ (the tree's own build directory): setuptools' staging goes here.
    options={"build": {"build_base": "build-wheel/setuptools"}, "egg_info": {"egg_base": "build-wheel/setuptools"}},
)
