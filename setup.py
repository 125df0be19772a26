"""Builds the Python module with CMake (pyproject.toml says how to call it; docs/python.md)."""

import glob
import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext
from setuptools.command.build_py import build_py

ROOT = Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    """Configures this tree and builds only the module's target, for this interpreter."""

    def build_extension(self, ext):
        target = Path(self.get_ext_fullpath(ext.name)).resolve()
        build_dir = Path(self.build_temp).resolve() / "cmake"
        args = ["-DCMAKE_BUILD_TYPE=Release", f"-DUBERSIM_PYTHON_EXECUTABLE={sys.executable}",
                "-DUBERSIM_BUILD_DDS_BRIDGE=OFF"]
        if shutil.which("ccache"):
            args += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache", "-DCMAKE_C_COMPILER_LAUNCHER=ccache"]
        subprocess.check_call(["cmake", "-S", str(ROOT), "-B", str(build_dir), *args])
        jobs = str(os.cpu_count() or 1)
        subprocess.check_call(["cmake", "--build", str(build_dir), "--target", "ubersim_python",
                               "-j", jobs])
        built = glob.glob(str(build_dir / "python" / "ubersim" / "_ubersim*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one built module, found {built}")
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


class BuildWithConfig(build_py):
    """Ships config/ (fields, robots, scenarios, profiles) inside the package."""

    def run(self):
        super().run()
        destination = Path(self.build_lib) / "ubersim" / "config"
        shutil.rmtree(destination, ignore_errors=True)
        shutil.copytree(ROOT / "config", destination)


setup(
    packages=["ubersim"],
    package_dir={"": "python"},
    ext_modules=[CMakeExtension("ubersim._ubersim")],
    cmdclass={"build_ext": CMakeBuild, "build_py": BuildWithConfig},
    zip_safe=False,
)
