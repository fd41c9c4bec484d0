"""The C++ extension of `pip install .`, built by the project's CMake (pyproject.toml has the rest).

The module `tsmframe._core` is the CMake target tsmframe_python. It is built in the directory
TSMFRAME_BUILD_DIR (default: build/, the one scripts/setup.sh makes, so an existing build is
reused) and copied into the wheel; the pure-Python part comes from python/tsmframe/.
"""
import glob
import os
import shutil
import subprocess

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = os.path.dirname(os.path.abspath(__file__))


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.environ.get("TSMFRAME_BUILD_DIR", os.path.join(SOURCE, "build"))
        jobs = os.environ.get("TSMFRAME_JOBS", str(min(os.cpu_count() or 1, 2)))
        subprocess.check_call(["cmake", "-S", SOURCE, "-B", build, "-DCMAKE_BUILD_TYPE=Release"], stdout=subprocess.DEVNULL)
        subprocess.check_call(["cmake", "--build", build, "-j", jobs, "--target", "tsmframe_python"])
        built = glob.glob(os.path.join(build, "python", "tsmframe", "_core*.so"))
        if len(built) != 1:
            raise RuntimeError(f"tsmframe: expected one _core*.so in {build}/python/tsmframe, found {built}")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built[0], target)


setup(ext_modules=[Extension("tsmframe._core", sources=[])], cmdclass={"build_ext": CMakeBuild})
