"""`pip install .` for the Python module: setuptools runs CMake (the module is python/ in the CMake
build) and copies the extension into the wheel. Works offline with Debian's setuptools:

    python3 -m venv --system-site-packages venv && . venv/bin/activate
    pip install --no-build-isolation .

Needs what the CMake build needs (scripts/install-deps) plus pybind11-dev and python3-numpy.
FRUGAL_CMAKE_ARGS adds CMake options (e.g. "-DFRUGAL_WITH_OSMESA=OFF"). FRUGAL_BUILD_DIR names a
CMake build folder configured with -DFRUGAL_BUILD_PYTHON=ON for this interpreter: its module is built
there (nothing else) and packaged, as the tests do.
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text()
    match = re.search(r"project\(frugal VERSION ([0-9.]+)", text)
    if not match:
        sys.exit("error: setup.py: no 'project(frugal VERSION x.y.z)' in CMakeLists.txt")
    return match.group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        target = Path(self.get_ext_fullpath(ext.name)).resolve()
        given = os.environ.get("FRUGAL_BUILD_DIR")
        build = Path(given).resolve() if given else Path(self.build_temp).resolve() / "cmake"
        if not given:
            self.configure(build)
        subprocess.run(["cmake", "--build", str(build), "--target", "frugal_python",
                        "--parallel", str(os.cpu_count() or 1)], check=True)
        built = list((build / "python" / "frugal").glob("_frugal*.so"))
        if len(built) != 1:
            sys.exit(f"error: setup.py: expected one _frugal*.so in {build / 'python' / 'frugal'}, found {len(built)}")
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)

    @staticmethod
    def configure(build):
        build.mkdir(parents=True, exist_ok=True)
        configure = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                     "-DFRUGAL_BUILD_PYTHON=ON", "-DFRUGAL_BUILD_TESTS=OFF", f"-DPython_EXECUTABLE={sys.executable}"]
        if shutil.which("ninja") and not (build / "CMakeCache.txt").exists():
            configure += ["-G", "Ninja"]
        configure += shlex.split(os.environ.get("FRUGAL_CMAKE_ARGS", ""))
        subprocess.run(configure, check=True)


setup(
    name="frugal",
    version=project_version(),
    description="Offscreen OpenGL renderer that does only the work a scene requires",
    packages=["frugal"],
    package_dir={"": "python"},
    # The extension's type stubs and the marker that the package has them (PEP 561).
    package_data={"frugal": ["_frugal.pyi", "py.typed"]},
    ext_modules=[CMakeExtension("frugal._frugal")],
    cmdclass={"build_ext": CMakeBuild},
    python_requires=">=3.9",
    install_requires=["numpy"],
    zip_safe=False,
    # setuptools' own build folder, apart from a CMake build in build/.
    options={"build": {"build_base": "build/setuptools"}},
)
