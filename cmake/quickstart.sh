#!/usr/bin/env bash
# The two README commands (Debian 12, as root, from a fresh clone):
#   bash cmake/quickstart.sh render   install what is missing, build (release preset), run the main job
#   bash cmake/quickstart.sh test     install what is missing, build (ci preset), run the whole test suite
#                                     under Xvfb so the VTK tests have a display
# Exits non-zero on any failure.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
root="$(pwd)"

say() { printf '\n==> %s\n' "$*" >&2; }
die() { printf 'quickstart: %s\n' "$*" >&2; exit 1; }

usage() {
  cat >&2 <<'EOF'
usage: bash cmake/quickstart.sh render|test
  render  install missing packages, build the release preset, render the default scene
          (until the renderer exists: trace one geodesic with grtrace-geodesic)
  test    install missing packages, build the ci preset, run every test (VTK tests under Xvfb)
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

cmd_render() {
  install_deps
  configure_and_build release
  local bin="build/release/examples"
  if [ -x "${bin}/render/grtrace-render" ]; then
    mkdir -p out
    say "Rendering the default scene (grtrace-render --out out/default.exr)"
    "${bin}/render/grtrace-render" --out out/default.exr
    [ -f out/default.exr ] || die "grtrace-render finished but out/default.exr is missing"
    say "Done"
    echo "EXR: ${root}/out/default.exr"
    if [ -f out/default.png ]; then
      echo "PNG: ${root}/out/default.png"
    else
      echo "PNG: (no preview written next to the EXR)"
    fi
  elif [ -x "${bin}/geodesic/grtrace-geodesic" ]; then
    say "The renderer is not built yet; tracing one photon instead (grtrace-geodesic --impact 7)"
    "${bin}/geodesic/grtrace-geodesic" --impact 7
    say "Done: the JSON line above is the traced geodesic (see ${bin}/geodesic/grtrace-geodesic --help)"
  else
    die "neither ${bin}/render/grtrace-render nor ${bin}/geodesic/grtrace-geodesic was built"
  fi
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
  -h | --help | help) usage ;;
  *) usage; exit 2 ;;
esac
