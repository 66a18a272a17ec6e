"""Builds the geotandem Python package through the repository's CMake project.

The release tree (build/release, the one scripts/setup.sh builds) is reused: CMake compiles only
what changed, then installs into the package directory:
  geotandem/_core*.so           the extension (RPATH $ORIGIN/_native/lib)
  geotandem/_native/bin, lib    the geotandem executable (worker processes) and its libraries
so the installed package does not depend on the build tree. GEOTANDEM_PYTHON_BUILD_DIR and
GEOTANDEM_PYTHON_PRESET choose another tree or preset.
"""

import os
import re
import subprocess
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

here = Path(__file__).resolve().parent


def project_version() -> str:
    text = (here / "CMakeLists.txt").read_text()
    return re.search(r"project\(geotandem VERSION ([0-9.]+)", text).group(1)


class BuildWithCMake(build_py):
    def run(self) -> None:
        super().run()
        preset = os.environ.get("GEOTANDEM_PYTHON_PRESET", "release")
        tree = Path(os.environ.get("GEOTANDEM_PYTHON_BUILD_DIR", here / "build" / preset))
        if not (tree / "CMakeCache.txt").exists():
            subprocess.check_call(["cmake", "--preset", preset], cwd=here)
        jobs = os.environ.get("GEOTANDEM_JOBS", str(os.cpu_count() or 2))
        subprocess.check_call(["cmake", "--build", str(tree), "-j", jobs, "--target", "geotandem_python"], cwd=here)
        package = Path(self.build_lib) / "geotandem"
        native = package / "_native"
        subprocess.check_call(["cmake", "--install", str(tree), "--prefix", str(native)])
        subprocess.check_call(["cmake", "--install", str(tree), "--component", "python", "--prefix", str(package)])
        for unneeded in ("include", "share"):
            target = native / unneeded
            if target.exists():
                subprocess.check_call(["rm", "-rf", str(target)])


class BinaryDistribution(Distribution):
    def has_ext_modules(self) -> bool:  # a platform wheel: it carries compiled code
        return True


setup(
    version=project_version(),
    packages=["geotandem"],
    package_dir={"": "python"},
    package_data={"geotandem": ["py.typed", "*.pyi"]},
    exclude_package_data={"geotandem": ["_build_paths.py"]},
    cmdclass={"build_py": BuildWithCMake},
    distclass=BinaryDistribution,
    zip_safe=False,
)
