#!/usr/bin/env bash
# Renders the example scenes' pictures for the README into docs/images/ (the EXR files stay in a scratch folder).
# Usage: bash examples/scenes/make_pictures.sh [build-dir]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
build="${1:-build/release}/examples/scenes"
scratch="$(mktemp -d)"
trap 'rm -rf "${scratch}"' EXIT
mkdir -p docs/images
run() {  # run PROGRAM PICTURE ARGS...
  local program="$1" picture="$2"; shift 2
  [ -x "${build}/${program}" ] || { echo "make_pictures: ${build}/${program} not built" >&2; exit 1; }
  "${build}/${program}" "$@" --size 512 --out "${scratch}/${picture}.exr"
  cp "${scratch}/${picture}.png" "docs/images/${picture}.png"
}
run star_beside_hole example-star
run reissner_nordstrom example-reissner-nordstrom --charge 0.8
run terrell_rotation example-terrell --beta 0.9
