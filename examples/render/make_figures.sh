#!/usr/bin/env bash
# Regenerates the seed report's figures with grtrace-render into docs/images/ (PNG previews kept in git;
# the EXR files stay in a scratch folder). Usage: bash examples/render/make_figures.sh [build-dir]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
build="${1:-build/release}"
render="${build}/examples/render/grtrace-render"
[ -x "${render}" ] || { echo "make_figures: ${render} not built (cmake --build --preset release)" >&2; exit 1; }
scratch="$(mktemp -d)"
trap 'rm -rf "${scratch}"' EXIT
mkdir -p docs/images

frame() {  # frame NAME ARGS...: render to scratch, keep the PNG
  local name="$1"; shift
  echo "== ${name}: grtrace-render $*" >&2
  "${render}" "$@" --out "${scratch}/${name}.exr" > "${scratch}/${name}.json"
  cp "${scratch}/${name}.png" "docs/images/${name}.png"
  cat "${scratch}/${name}.json"
}

# The seed's main frame: static camera at r = 200 M, fov 90, 1024x1024, sky sphere at 400 M.
frame main-frame
# Fig. 4: checkerboard seen from r = 20 M, 1024x512, fov 90, sky sphere at 40 M with 20 divisions of 2 pi
# (10 squares along theta), as in the seed; (a) with the seed's (flat) angle correction, (b) without, and our
# default, the exact bending beyond the sky sphere.
fig4="--camera-r 20 --width 1024 --height 512 --sky-radius 40 --checker-squares 10"
# shellcheck disable=SC2086
frame fig4a-flat-correction ${fig4} --angle-correction flat
# shellcheck disable=SC2086
frame fig4b-no-correction ${fig4} --angle-correction none
# shellcheck disable=SC2086
frame fig4-exact-correction ${fig4} --angle-correction exact
# Fig. 5: a camera on the photon sphere (r = 3M) moving tangentially with 4-velocity proportional to
# (1, 0, 0, 0.15): beta_phi = r u^phi / (sqrt(1 - 2M/r) u^t) = 0.45 sqrt(3) = 0.7794; colour by redshift.
beta="0,0,0.7794228634059948"
frame fig5-side --scene redshift --camera-r 3 --velocity "${beta}" --look 0,1,0 --up 1,0,0 --width 512 --height 512
frame fig5-front --scene redshift --camera-r 3 --velocity "${beta}" --look 0,0,1 --up 1,0,0 --width 512 --height 512
frame fig5-back --scene redshift --camera-r 3 --velocity "${beta}" --look 0,0,-1 --up 1,0,0 --width 512 --height 512
frame fig5-out --scene redshift --camera-r 3 --velocity "${beta}" --look 1,0,0 --up 0,-1,0 --width 512 --height 512
# Beyond the seed: a thin Keplerian disk in front of the star field.
frame disk --scene disk --camera-r 30 --camera-theta 82 --fov 55 --width 960 --height 540 --rtol 1e-8
