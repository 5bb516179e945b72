#!/usr/bin/env bash
# The Python tests against the installed package, as a user gets it: a fresh
# venv over Debian's python3 (its numpy, zarr and pytest), `pip install
# --no-build-isolation` of the source tree reusing the build directory's
# _wavebake (WAVEBAKE_BUILD_DIR: nothing is compiled a second time), then
# pytest from outside the source and build trees.
# Usage: run_installed.sh SOURCE_DIR BUILD_DIR [pytest args...]
set -euo pipefail
src=$(realpath "$1") build=$(realpath "$2")
shift 2
venv="$build/python-venv"
rm -rf "$venv"
# --without-pip: Debian's pip, seen through the system site packages, installs
# into the venv all the same; seeding the venv's own pip took 16 s of the
# test's 50 (a loaded 2-core machine), an empty venv 0.2 s.
/usr/bin/python3 -m venv --system-site-packages --without-pip "$venv"
WAVEBAKE_BUILD_DIR="$build" "$venv/bin/python" -m pip install -q --no-build-isolation --no-index "$src"
cd "$(mktemp -d)"
trap 'rm -rf "$PWD"' EXIT
WB_SOURCE_DIR="$src" WB_BINARY_DIR="$build" \
  "$venv/bin/python" -m pytest -q -p no:cacheprovider "$src/tests/python" "$@"
