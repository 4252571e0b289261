#!/usr/bin/env bash
# The camera flights of the README (grtrace-render --flight) as contact sheets in docs/images/: frames of the
# seed report's orbit (r = 100 M down to ~39 M and back, one revolution), of a fall from rest at r = 30 M, and of a
# fall through the horizon (Kerr-Schild chart), tiled by ffmpeg. Usage: bash examples/render/make_flight_figures.sh [build-dir]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
build="${1:-build/release}"
render="${build}/examples/render/grtrace-render"
[ -x "${render}" ] || { echo "make_flight_figures: ${render} not built (cmake --build --preset release)" >&2; exit 1; }
command -v ffmpeg > /dev/null || { echo "make_flight_figures: ffmpeg missing (bash cmake/install-deps.sh)" >&2; exit 1; }
scratch="$(mktemp -d)"
trap 'rm -rf "${scratch}"' EXIT
mkdir -p docs/images

sheet() {  # sheet NAME COLUMNSxROWS ARGS...: fly, then tile the PNG previews into docs/images/NAME.png
  local name="$1" tile="$2"; shift 2
  echo "== ${name}: grtrace-render $*" >&2
  "${render}" "$@" --out "${scratch}/${name}.exr"
  ffmpeg -hide_banner -loglevel error -y -i "${scratch}/${name}-%04d.png" -frames:v 1 \
    -filter_complex "tile=${tile}:padding=4:color=white" "docs/images/${name}.png"
}

# The seed's orbit, 8 frames over one revolution, looking at the hole (the disk is seen edge-on from the orbit's
# plane: its far side is lensed into the ring above and below the shadow).
sheet flight-seed 4x2 --flight seed --frames 8 --scene disk --width 320 --height 240 --fov 40 --look -1,0.08,0
# Released from rest at r = 30 M: 8 frames of the fall to 1.1 r_h; the shadow grows to fill the sky.
sheet flight-infall 4x2 --flight infall --camera-r 30 --camera-theta 80 --frames 8 --scene disk --width 320 \
  --height 240 --fov 90
# Through the horizon (Kerr-Schild, a = 0): released from rest at r = 4 M, 8 frames of the fall to 1.1 r_c = 1.65 M,
# the last one inside r = 2 M; looking sideways (along phi: the hole below, the sky above) at the checker sky.
sheet flight-horizon 4x2 --metric kerr --spin 0 --chart ks --flight infall --camera-r 4 --frames 8 --width 320 \
  --height 240 --fov 120 --look 0,0,1 --up 1,0,0
