#!/usr/bin/env bash
# The two README commands (Debian 12, as root, from a fresh clone):
#   bash cmake/quickstart.sh render   install what is missing, build grtrace-render, render the default scene
#   bash cmake/quickstart.sh test     install what is missing, build (ci preset), run the whole test suite
#                                     under Xvfb so the VTK tests have a display
#   bash cmake/quickstart.sh python   install what is missing, build the Python module (release preset) and install
#                                     it for Debian's python3 (/usr/local: `import grtrace` then works anywhere)
# Exits non-zero on any failure.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
root="$(pwd)"

say() { printf '\n==> %s\n' "$*" >&2; }
die() { printf 'quickstart: %s\n' "$*" >&2; exit 1; }

usage() {
  cat >&2 <<'EOF'
usage: bash cmake/quickstart.sh render|test|python
  render  install missing packages, build grtrace-render (release preset), render the default scene
  test    install missing packages, build the ci preset, run every test (VTK tests under Xvfb)
  python  install missing packages, build the Python module (release preset), install it for /usr/bin/python3
EOF
}

install_deps() {
  say "Checking system packages (cmake/install-deps.sh)"
  bash cmake/install-deps.sh || die "installing the dependencies failed (run as root on Debian 12)"
}

configure_and_build() {
  local preset="$1"
  say "Configuring (cmake --preset ${preset})"
  cmake --preset "${preset}"
  say "Building (cmake --build --preset ${preset}, 2 jobs)"
  cmake --build --preset "${preset}"
}

# The CUDA backend only where it can run: a CUDA compiler alone (a build machine) would add minutes of device code
# compilation to frames rendered on the CPU. Configure with -DGRTRACE_CUDA=ON to build it anyway.
cuda_where_it_runs() {
  if nvidia-smi -L > /dev/null 2>&1; then echo AUTO; else echo OFF; fi
}

cmd_render() {
  install_deps
  local cuda
  cuda=$(cuda_where_it_runs)
  say "Configuring (cmake --preset release -DGRTRACE_CUDA=${cuda})"
  cmake --preset release -DGRTRACE_CUDA="${cuda}"
  say "Building grtrace-render (cmake --build --preset release --target grtrace-render)"
  cmake --build --preset release --target grtrace-render
  local bin="build/release/examples/render/grtrace-render"
  [ -x "${bin}" ] || die "${bin} was not built (OpenMP, OpenEXR and libpng are needed: cmake/install-deps.sh)"
  mkdir -p out
  say "Rendering the default scene (grtrace-render --out out/default.exr)"
  "${bin}" --out out/default.exr
  [ -f out/default.exr ] && [ -f out/default.png ] || die "grtrace-render finished but its outputs are missing"
  say "Done"
  echo "EXR: ${root}/out/default.exr"
  echo "PNG: ${root}/out/default.png"
}

cmd_python() {
  install_deps
  local cuda
  cuda=$(cuda_where_it_runs)
  say "Configuring (cmake --preset release -DGRTRACE_CUDA=${cuda} -DGRTRACE_PYTHON=ON)"
  cmake --preset release -DGRTRACE_CUDA="${cuda}" -DGRTRACE_PYTHON=ON
  say "Building the Python module (cmake --build --preset release --target grtrace_python)"
  cmake --build --preset release --target grtrace_python
  say "Installing it for /usr/bin/python3 (bash cmake/install-python.sh build/release /usr/local)"
  bash cmake/install-python.sh build/release /usr/local
  say "Done: python3 -c 'import grtrace; help(grtrace)'"
}

cmd_test() {
  install_deps
  configure_and_build ci
  command -v xvfb-run >/dev/null || die "xvfb-run not found (apt-get install xvfb xauth)"
  say "Running the test suite under Xvfb (ctest --preset ci)"
  xvfb-run -a -s "-screen 0 1280x1024x24" ctest --preset ci
  say "All tests passed"
}

case "${1:-}" in
  render) cmd_render ;;
  test) cmd_test ;;
  python) cmd_python ;;
  -h | --help | help) usage ;;
  *) usage; exit 2 ;;
esac
