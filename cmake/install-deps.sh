#!/usr/bin/env bash
# Installs the Debian 12 packages grtrace needs, skipping those already present.
# Idempotent: a second run with everything installed does not touch apt.
# Usage (as root): bash cmake/install-deps.sh          (GRTRACE_FUZZ=1 bash cmake/install-deps.sh: + afl++)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config   # Ninja: the presets' generator (parallel, a build log with times)
  libeigen3-dev                       # core: numerics and vectors (Eigen)
  libopenexr-dev libpng-dev           # renderer output
  libdeflate-dev                      # renderer: fast deflate of the EXR chunks
  libvtk9-dev                         # viz frontend
  libgtest-dev libbenchmark-dev       # tests and benchmarks
  xvfb xauth                          # headless VTK rendering in tests
  libcli11-dev libtomlplusplus-dev    # tools only: option parsing and TOML scene files (--config)
  nlohmann-json3-dev                  # tools only: JSON output
  ffmpeg                              # grtrace-render --mp4: camera flights assembled into a video
  ccache                              # builds: a rebuild after a touch, branch switch or undone edit reuses objects
  python3-dev pybind11-dev python3-numpy   # the Python module (python/): Debian's python3 and its headers
  python3-pytest                      # the Python module's tests
  python3-scipy python3-matplotlib python3-nbclient python3-ipykernel python3-nbformat  # its notebook, run by the tests
)
# Optional, not part of CI: GRTRACE_FUZZ=1 also installs AFL++ for the fuzz targets in tests/fuzz/.
if [ "${GRTRACE_FUZZ:-0}" = 1 ]; then
  packages+=(afl++)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: missing packages: ${missing[*]}" >&2
  echo "install-deps: run as root (or with sudo) to install them" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -o DPkg::Lock::Timeout=900
apt-get install -y --no-install-recommends -o DPkg::Lock::Timeout=900 "${missing[@]}"
