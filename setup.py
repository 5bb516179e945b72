"""The build of the `wavebake` package (pyproject.toml): its one extension,
wavebake._wavebake, is the CMake target _wavebake (python/CMakeLists.txt).

WAVEBAKE_BUILD_DIR names an already configured CMake build directory (the
one `make build` made): only the _wavebake target is brought up to date there
and copied, so installing after a build compiles nothing twice. Without it
the project is configured in setuptools' temporary directory and only what
_wavebake needs is built. The version is the CMake project's."""
import os
import re
import shutil
import subprocess
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def cmake_version() -> str:
    text = (ROOT / "CMakeLists.txt").read_text()
    match = re.search(r"project\(\s*wavebake\s+VERSION\s+([0-9.]+)", text)
    if not match:
        raise RuntimeError("CMakeLists.txt: no `project(wavebake VERSION x.y.z)`")
    return match.group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext: Extension) -> None:
        build_dir = os.environ.get("WAVEBAKE_BUILD_DIR")
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        if build_dir:
            build = Path(build_dir).resolve()
            if not (build / "CMakeCache.txt").exists():
                raise RuntimeError(f"WAVEBAKE_BUILD_DIR={build_dir}: not a configured CMake build")
        else:
            build = Path(self.build_temp).resolve() / "cmake"
            build.mkdir(parents=True, exist_ok=True)
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), *generator,
                            "-DCMAKE_BUILD_TYPE=Release"], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "_wavebake", "-j", jobs],
                       check=True)
        built = sorted((build / "python" / "wavebake").glob("_wavebake*.so"))
        if len(built) != 1:
            raise RuntimeError(f"{build}/python/wavebake: expected one _wavebake*.so, found {built}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(
    version=cmake_version(),
    ext_modules=[Extension("wavebake._wavebake", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own build tree, kept out of the CMake build directory `build/`.
    options={"build": {"build_base": ".pybuild"}, "egg_info": {"egg_base": ".pybuild"}},
)
