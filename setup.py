"""The build step of `pip install .` / `pip wheel .` (pyproject.toml holds the metadata): the
extension aief._aief is built by the project's own CMake, as a static engine linked into one
module, for the Python that runs pip. Nothing is downloaded (docs/install.md).

Environment: CMAKE_BUILD_PARALLEL_LEVEL (default: every core), AIEF_CMAKE_ARGS (extra
configure arguments, split on spaces)."""
import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE_DIR = pathlib.Path(__file__).resolve().parent


def project_version():
    """The version of CMakeLists.txt's project() call."""
    found = re.search(r"project\(aief VERSION ([0-9.]+)", (SOURCE_DIR / "CMakeLists.txt").read_text())
    if not found:
        raise RuntimeError("no 'project(aief VERSION x.y.z' in CMakeLists.txt")
    return found.group(1)


class CMakeBuild(build_ext):
    """Configures a module-only build (no tests, benchmarks, tool or adapter) and builds aief_python."""

    def build_extension(self, ext):
        build_dir = pathlib.Path(self.build_temp).resolve() / "cmake"
        configure = [
            "cmake", "-S", str(SOURCE_DIR), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
            f"-DPython_EXECUTABLE={sys.executable}", "-DBUILD_SHARED_LIBS=OFF", "-DAIEF_BUILD_TESTS=OFF",
            "-DAIEF_BUILD_BENCH=OFF", "-DAIEF_BUILD_TOOLS=OFF", "-DAIEF_BUILD_OPENCV_ADAPTER=OFF",
            *os.environ.get("AIEF_CMAKE_ARGS", "").split(),
        ]
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "aief_python", "-j", jobs], check=True)
        built = sorted((build_dir / "python" / "aief").glob("_aief*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one _aief*.so in {build_dir / 'python' / 'aief'}, found {built}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(
    version=project_version(),
    ext_modules=[Extension("aief._aief", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own work files under build/pip, beside (not inside) a CMake build in build/.
    options={"build": {"build_base": "build/pip"}},
)
