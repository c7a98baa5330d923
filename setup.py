# SPDX-License-Identifier: MIT
"""`pip install --no-build-isolation .`: builds the extension with CMake
(-DSTREAMCLUST_PYTHON=ON, only the target _streamclust) and installs the
package `streamclust` (python/streamclust). Needs Debian's python3-setuptools,
pybind11-dev, python3-numpy and the library's build dependencies
(scripts/install-deps.sh); nothing is downloaded. docs/python.md.
"""

import os
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    """Configures the project with CMake and builds the module target."""

    def build_extension(self, ext):
        build = Path(self.build_temp).resolve() / "cmake"
        build.mkdir(parents=True, exist_ok=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                        "-DSTREAMCLUST_PYTHON=ON", "-DSTREAMCLUST_PYTHON_TESTS=OFF", "-DSTREAMCLUST_BUILD_TESTS=OFF",
                        "-DSTREAMCLUST_BUILD_EXAMPLES=OFF", "-DSTREAMCLUST_BUILD_BENCH=OFF",
                        "-DSTREAMCLUST_BUILD_TOOLS=OFF", f"-DPython3_EXECUTABLE={sys.executable}"], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "_streamclust", "-j", jobs], check=True)
        built = next((build / "python" / "streamclust").glob("_streamclust*.so"))
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        self.copy_file(str(built), str(target))


setup(
    name="streamclust",
    version="0.1.0",
    description="Continuous clustering of LiDAR point streams (C-ARC), from numpy",
    license="MIT",
    packages=["streamclust"],
    package_dir={"": "python"},
    ext_modules=[CMakeExtension("streamclust._streamclust")],
    cmdclass={"build_ext": CMakeBuild},
    python_requires=">=3.9",
    install_requires=["numpy"],
    zip_safe=False,
)
