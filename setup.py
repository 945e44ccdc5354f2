"""setup.py - builds facet's Python extension (facet._facet) with the project's CMake build, for pip."""
import os
import pathlib
import re
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
    """Configures the release build without tests or benchmarks, builds the module target, copies it in place."""

    def build_extension(self, ext):
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        generator = ["-G", "Ninja"] if shutil.which("ninja") else []
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), *generator, "-DCMAKE_BUILD_TYPE=Release",
                        "-DFACET_BUILD_TESTS=OFF", "-DFACET_BUILD_BENCH=OFF", f"-DPython_EXECUTABLE={sys.executable}"],
                       check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "facet_python", "-j", str(os.cpu_count() or 1)],
                       check=True)
        built = next((build / "python" / "facet").glob("_facet*.so"))
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


def version():
    return re.search(r"project\(facet VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text()).group(1)


setup(version=version(), ext_modules=[CMakeExtension("facet._facet")], cmdclass={"build_ext": CMakeBuild})
