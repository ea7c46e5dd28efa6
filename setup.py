"""pip's route to the Python module: one CMake configure and one target (dampbound_python),
in build-pip/ beside the CMake route's build/ (pyproject.toml, README "Python").
DAMPBOUND_CMAKE_BUILD_DIR names a tree the CMake route already configured instead: only the
module's target is built there (what CI does after scripts/test.sh)."""
import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        given = os.environ.get("DAMPBOUND_CMAKE_BUILD_DIR")  # a tree the CMake route configured
        build = pathlib.Path(given).resolve() if given else ROOT / "build-pip" / "cmake"
        args = [
            "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
            "-DDAMPBOUND_PYTHON=ON", "-DDAMPBOUND_GUI=OFF", "-DDAMPBOUND_EGL=OFF",
            "-DDAMPBOUND_TESTS=OFF", "-DDAMPBOUND_BENCH=OFF",
            f"-DPython_EXECUTABLE={sys.executable}",
        ]
        if shutil.which("ninja"):
            args += ["-G", "Ninja"]
        if shutil.which("ccache"):
            args += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"]
        if not given:
            subprocess.run(["cmake", *args], check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", str(build), "--target", "dampbound_python",
                        "-j", jobs], check=True)
        built = next((build / "python").glob("dampbound*.so"))
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built, target)


setup(
    ext_modules=[CMakeExtension("dampbound")],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build-pip/setuptools"},
             "egg_info": {"egg_base": "build-pip"}},
)
