#!/usr/bin/env bash
# Installs the Python package grtrace of a build tree (cmake --install, component python) under a prefix, for
# Debian's python3, and checks that the installed copy imports there and is the build's version.
#   bash cmake/install-python.sh BUILD_DIR [PREFIX]      PREFIX: /usr/local (Debian's python3 reads it) by default
# bash cmake/quickstart.sh python calls it with the release build; the test suite with its own build and a scratch
# prefix (the python_install test), so the tests import exactly what this script installs.
set -euo pipefail

build="${1:?usage: bash cmake/install-python.sh BUILD_DIR [PREFIX]}"
prefix="${2:-/usr/local}"
python=/usr/bin/python3

[ -f "${build}/CMakeCache.txt" ] || { echo "install-python: ${build} is not a configured build tree" >&2; exit 2; }
site=$(sed -n 's/^GRTRACE_PYTHON_SITE:STRING=//p' "${build}/CMakeCache.txt")
[ -n "${site}" ] || { echo "install-python: ${build} has no Python module (configure with pybind11-dev, python3-dev and python3-numpy installed: bash cmake/install-deps.sh)" >&2; exit 2; }

cmake --install "${build}" --component python --prefix "${prefix}"
# Import the installed copy (not a build tree or source one on the path) and say where it came from.
cd /
PYTHONPATH="${prefix}/${site}" "${python}" -c '
import sys, grtrace
expected = sys.argv[1]
where = grtrace.__file__
if not where.startswith(expected):
    sys.exit(f"install-python: imported grtrace from {where}, not from {expected}")
print(f"grtrace {grtrace.__version__} installed for {sys.executable} in {expected}")
' "${prefix}/${site}/grtrace"
