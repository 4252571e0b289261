#!/usr/bin/env bash
# Pictures of the named metrics (grtrace-render --metric ...) at 512x512 into docs/images/metric-*.png (PNG previews
# kept in git; the EXR files stay in a scratch folder). Each frame's command is printed and its JSON line kept in
# the scratch folder. Usage: bash examples/render/metric_pictures.sh [build-dir]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
build="${1:-build/release}"
render="${build}/examples/render/grtrace-render"
[ -x "${render}" ] || { echo "metric_pictures: ${render} not built (cmake --build --preset release)" >&2; exit 1; }
scratch="$(mktemp -d)"
trap 'rm -rf "${scratch}"' EXIT
mkdir -p docs/images

frame() {  # frame NAME ARGS...: render to scratch at 512x512, keep the PNG
  local name="$1"; shift
  echo "== ${name}: grtrace-render $* --width 512 --height 512" >&2
  "${render}" "$@" --width 512 --height 512 --out "${scratch}/${name}.exr" > "${scratch}/${name}.json"
  cp "${scratch}/${name}.png" "docs/images/${name}.png"
  cat "${scratch}/${name}.json"
}

# Ellis wormhole (throat b0 = 1) from l = 4: the throat (sin alpha = b0 / sqrt(l^2 + b0^2), 14 degrees) shows the
# other universe's sky, a green-violet checkerboard / orange stars.
frame metric-wormhole --metric wormhole --throat 1 --scene checker --camera-r 4 --camera-theta 80 --fov 60
frame metric-wormhole-stars --metric wormhole --throat 1 --scene sky --camera-r 4 --camera-theta 80 --fov 60
# Schwarzschild-de Sitter, Lambda = 1e-3 (cosmological horizon at 53.7 M): the sky sphere must lie inside it.
frame metric-sds --metric sds --lambda 1e-3 --scene checker --camera-r 20 --sky-radius 50 --fov 60
# Reissner-Nordstrom, Q = 0.9 M, with a thin disk from 5 M (ISCO 4.2 M ... below 6 M of Schwarzschild).
frame metric-rn-disk --metric rn --charge 0.9 --scene disk --camera-r 50 --camera-theta 80 --fov 40 --disk-inner 5
# Kerr, a = 0.9 M, with a thin disk from 2.4 M (prograde ISCO 2.32 M).
frame metric-kerr-disk --metric kerr --spin 0.9 --scene disk --camera-r 50 --camera-theta 80 --fov 40 --disk-inner 2.4
# Schwarzschild in outgoing Eddington-Finkelstein coordinates: the same picture as Schwarzschild coordinates, with
# the captured rays carried through r = 2M (to r = M).
frame metric-ef --metric schwarzschild-ef --scene checker --camera-r 20 --fov 90
