#!/usr/bin/env bash
# cmake/gpu-check.sh: the CUDA backend's tests and timings on a machine with a CUDA GPU, in one go.
#
#   bash cmake/gpu-check.sh pack        on a build machine with nvcc (no GPU needed): builds grtrace-render, the GPU
#                                       test and the GPU example with the CUDA backend (release preset, sm_90), and
#                                       gathers them with the shared libraries they load into build/gpu-pack/
#                                       (xz-compressed: a device machine lacks OpenEXR, libpng, ...).
#   bash cmake/gpu-check.sh run [DIR]   on the GPU machine (DIR: the pack, default build/gpu-pack): runs every GPU
#                                       test, then the timings, each as one JSON line ("check": what it measured),
#                                       GPU against the machine's own cores in the same run. A few minutes.
#
# The timings (issue targets in brackets): the Kerr disk frame 1024x1024, kerr-mino (<= 15 ms of tracing, whole
# process <= 0.5 s); the main frame with --tracer general (<= 10 ms of tracing); a 300-frame Kerr flight at
# 1024x1024 with EXR and PNG (<= 30 s wall). "gpu_trace_seconds" is the kernel's time (the EXR header's), "seconds"
# the frame's (tracing, shading, statistics), "wall" the whole process.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mode="${1:-}"

pack() {
  cd "$here"
  cmake --preset release -DGRTRACE_CUDA=ON > /dev/null
  cmake --build --preset release --target grtrace-render gpu_frame_test star_beside_hole_gpu
  local out="$here/build/gpu-pack"
  rm -rf "$out"
  mkdir -p "$out/lib"
  local bins=(build/release/examples/render/grtrace-render build/release/tests/gpu/gpu_frame_test
              build/release/examples/scenes/star_beside_hole_gpu)
  for b in "${bins[@]}"; do
    # Every shared library but the C library's own (the device machine has those).
    ldd "$b" | awk '/=> \// {print $3}' | grep -Ev '/(libc|libm|libpthread|libdl|librt|ld-linux[^/]*)\.so' |
      while read -r lib; do cp -Ln "$lib" "$out/lib/" 2> /dev/null || true; done
    xz -T2 -6 -c "$b" > "$out/$(basename "$b").xz"
  done
  xz -T2 -6 "$out"/lib/*.so*
  echo "gpu-check: packed $(du -sh "$out" | cut -f1) into $out; on the GPU machine: bash cmake/gpu-check.sh run"
}

# One timed run of grtrace-render: a JSON line with the tool's own line, the wall time and the header's GPU time.
timed() {
  local check="$1"; shift
  local t0 t1 line
  t0=$(date +%s.%N)
  if line=$("$bin/grtrace-render" "$@" 2> "$work/err.txt"); then
    t1=$(date +%s.%N)
    echo "{\"check\":\"$check\",\"wall\":$(awk "BEGIN {print $t1 - $t0}"),\"render\":$line}"
  else
    echo "{\"check\":\"$check\",\"failed\":$?,\"stderr\":\"$(tail -c 300 "$work/err.txt" | tr '\n"' ' ')\"}"
  fi
}

run() {
  local dir="${1:-$here/build/gpu-pack}"
  work="$(mktemp -d)"
  bin="$work/bin"
  mkdir -p "$bin/lib"
  for f in "$dir"/*.xz; do xz -dc "$f" > "$bin/$(basename "$f" .xz)"; chmod +x "$bin/$(basename "$f" .xz)"; done
  for f in "$dir"/lib/*.xz; do xz -dc "$f" > "$bin/lib/$(basename "$f" .xz)"; done
  export LD_LIBRARY_PATH="$bin/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  echo "{\"check\":\"device\",\"gpu\":\"$(nvidia-smi -L 2> /dev/null | head -1 | tr '"' ' ')\",\"cores\":$(nproc)}"
  "$bin/gpu_frame_test" 2>&1 | grep -E '^\[(gpu|  (PASSED|FAILED|SKIPPED))|^\[  FAILED|tests ran|Failure|Expected|Which is|actual' || true
  "$bin/star_beside_hole_gpu" --size 512 --out "$work/star-gpu.exr" > /dev/null && echo '{"check":"example","ok":true}'
  local kerr=(--metric kerr --spin 0.9 --scene disk --camera-r 50 --camera-theta 80 --fov 60 --width 1024 --height 1024)
  for device in cuda cpu; do
    timed "kerr_disk_$device" "${kerr[@]}" --device "$device" --out "$work/kerr-$device.exr"
    timed "main_general_$device" --tracer general --device "$device" --out "$work/main-$device.exr"
  done
  timed kerr_disk_cuda_again "${kerr[@]}" --device cuda --out "$work/kerr-cuda-2.exr"  # warm: driver loaded
  timed kerr_flight_300_cuda "${kerr[@]}" --device cuda --flight circular --frames 300 --out "$work/flight.exr"
  rm -rf "$work"
}

case "$mode" in
  pack) pack ;;
  run) shift; run "$@" ;;
  *) echo "usage: bash cmake/gpu-check.sh pack | run [DIR]" >&2; exit 2 ;;
esac
