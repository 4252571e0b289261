#!/usr/bin/env bash
# cmake/gpu-check.sh: the CUDA backend's tests and timings on a machine with a CUDA GPU, in one go.
#
#   bash cmake/gpu-check.sh pack        on a build machine with nvcc (no GPU needed): builds grtrace-render, the GPU
#                                       test and the GPU example with the CUDA backend (release preset, sm_90), and
#                                       gathers them with the shared libraries they load into build/gpu-pack/
#                                       (xz-compressed: a device machine lacks OpenEXR, libpng, ...).
#   bash cmake/gpu-check.sh run [DIR]   on the GPU machine (DIR: the pack, default build/gpu-pack): runs the probe
#                                       (one ray step by step on the GPU and the host: where a wrong GPU departs;
#                                       again with the device code at -O0, and under compute-sanitizer's memcheck
#                                       where the machine has it),
#                                       every GPU test, then the timings, each as one JSON line ("check": what it
#                                       measured), GPU against the machine's own cores in the same run. At most
#                                       GRTRACE_GPU_CHECK_SECONDS (290): each step has a timeout, and a step that
#                                       could end later is skipped. Logs and PNGs go to $OUT when it is set.
#                                       GRTRACE_GPU_CHECK_PROFILE=1 adds Nsight Compute's view of the two kernels
#                                       (ncu.log; about a minute more).
#
# The kernels alone (tests/gpu/gpu_kernel_benchmark.cu, against the same with everything inlined), then the timings
# (issue targets in brackets): the Kerr disk frame 1024x1024, kerr-mino (<= 15 ms of tracing, whole
# process <= 0.5 s); the main frame with --tracer general (<= 10 ms of tracing); a 300-frame Kerr flight at
# 1024x1024 with EXR and PNG (<= 30 s wall). "gpu_trace_seconds" is the kernel's time (the EXR header's), "seconds"
# the frame's (tracing, shading, statistics), "wall" the whole process.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mode="${1:-}"

pack() {
  cd "$here"
  cmake --preset release -DGRTRACE_CUDA=ON > /dev/null
  cmake --build --preset release --target grtrace-render gpu_frame_test gpu_probe_unoptimised star_beside_hole_gpu \
    gpu_kernel_benchmark gpu_kernel_benchmark_inline_all
  local out="$here/build/gpu-pack"
  rm -rf "$out"
  mkdir -p "$out/lib"
  local bins=(build/release/examples/render/grtrace-render build/release/tests/gpu/gpu_frame_test
              build/release/tests/gpu/gpu_probe_unoptimised build/release/examples/scenes/star_beside_hole_gpu
              build/release/tests/gpu/gpu_kernel_benchmark build/release/tests/gpu/gpu_kernel_benchmark_inline_all)
  for b in "${bins[@]}"; do
    # Every shared library but the C library's own (the device machine has those).
    ldd "$b" | awk '/=> \// {print $3}' | grep -Ev '/(libc|libm|libpthread|libdl|librt|ld-linux[^/]*)\.so' |
      while read -r lib; do cp -Ln "$lib" "$out/lib/" 2> /dev/null || true; done
    xz -T2 -6 -c "$b" > "$out/$(basename "$b").xz"
  done
  xz -T2 -6 "$out"/lib/*.so*
  echo "gpu-check: packed $(du -sh "$out" | cut -f1) into $out; on the GPU machine: bash cmake/gpu-check.sh run"
}

# One timed run of grtrace-render (at most run_step's limit): a JSON line with the tool's own line and the wall time.
timed() {
  local check="$1"; shift
  local limit="${step_limit:-60}"  # run_step's limit for this step
  local t0 t1 line rc=0
  t0=$(date +%s.%N)
  line=$(GRTRACE_TIMING=1 timeout "$limit" "$bin/grtrace-render" "$@" 2> "$work/err.txt") || rc=$?
  t1=$(date +%s.%N)
  if [ "$rc" = 0 ]; then
    local phases  # GRTRACE_TIMING's phase times, as "name ms" pairs
    phases=$(grep -E '^grtrace-render: ' "$work/err.txt" | awk '{printf "%s%s %s", (NR > 1 ? ", " : ""), $2, $3}')
    echo "{\"check\":\"$check\",\"wall\":$(awk "BEGIN {print $t1 - $t0}"),\"phases_ms\":\"$phases\",\"render\":$(echo "$line" | tail -1)}"
  else
    echo "{\"check\":\"$check\",\"failed\":$rc,\"stderr\":\"$(tail -c 300 "$work/err.txt" | tr '\n"' ' ')\"}"
  fi
}

# run_step SECONDS NAME COMMAND...: COMMAND under a timeout, skipped (saying so) when it could end past the deadline.
run_step() {
  local limit="$1" name="$2"; shift 2
  if (( SECONDS + limit > deadline )); then
    echo "{\"check\":\"$name\",\"skipped\":\"would pass the ${deadline} s deadline (at ${SECONDS} s)\"}"
    return 0
  fi
  step_limit="$limit" "$@"
}

tests() {  # tests LIMIT FILTER LOG: the GPU test program's tests matching FILTER
  local rc=0
  timeout "$1" "$bin/gpu_frame_test" --gtest_filter="$2" > "$keep/$3" 2>&1 || rc=$?
  grep -E '^\[(gpu|  (PASSED|FAILED|SKIPPED))|^\[  FAILED|tests ran|Failure|Expected|Which is|actual|^  (host|device) ' \
    "$keep/$3" || true
  echo "{\"check\":\"$3\",\"exit\":$rc}"
  if [ "$3" = gpu_probe.log ]; then probe_exit=$rc; fi
}

# The probe under compute-sanitizer's memcheck (out-of-bounds and misaligned device accesses, local memory
# included), where the machine has the tool.
sanitized_probe() {
  local tool rc=0
  tool="$(command -v compute-sanitizer || echo /usr/local/cuda/bin/compute-sanitizer)"
  if [ ! -x "$tool" ]; then
    echo '{"check":"sanitizer","skipped":"no compute-sanitizer on this machine"}'
    return 0
  fi
  timeout "$1" "$tool" --tool memcheck --print-limit 20 "$bin/gpu_frame_test" --gtest_filter='GpuProbe.*' \
    > "$keep/sanitizer.log" 2>&1 || rc=$?
  grep -E 'ERROR SUMMARY|Invalid|Address|at 0x|by thread' "$keep/sanitizer.log" | head -20 || true
  echo "{\"check\":\"sanitizer\",\"exit\":$rc}"
}

# The probe's rays with the device code unoptimised (tests/gpu/gpu_probe_unoptimised.cu).
unoptimised_probe() {
  local rc=0
  timeout "$1" "$bin/gpu_probe_unoptimised" > "$keep/gpu_probe_unoptimised.log" 2>&1 || rc=$?
  cat "$keep/gpu_probe_unoptimised.log"
  echo "{\"check\":\"probe_unoptimised\",\"exit\":$rc}"
}

kernels() {  # gpu_kernel_benchmark (the outcomes against the host pass too) and its inline-all build, alternated
  local rc=0
  { timeout "$1" "$bin/gpu_kernel_benchmark" --host && timeout "$1" "$bin/gpu_kernel_benchmark_inline_all" &&
    timeout "$1" "$bin/gpu_kernel_benchmark" && timeout "$1" "$bin/gpu_kernel_benchmark_inline_all"; } || rc=$?
  echo "{\"check\":\"kernel_benchmark\",\"exit\":$rc}"
}

# Nsight Compute on the kernel benchmark's fourth Kerr launch and first main-frame launch (where the warps' cycles go:
# stall reasons, issue rate, occupancy), where the machine has ncu: the text report goes to ncu.log.
profile() {
  local tool rc=0
  tool="$(command -v ncu || ls /usr/local/cuda/bin/ncu /opt/nvidia/nsight-compute/*/ncu 2> /dev/null | head -1 || true)"
  if [ -z "$tool" ] || [ ! -x "$tool" ]; then
    echo '{"check":"profile","skipped":"no ncu on this machine"}'
    return 0
  fi
  timeout "$1" "$tool" -k regex:trace_pixel_block --launch-skip 3 --launch-count 2 --section LaunchStats \
    --section Occupancy --section SchedulerStats --section WarpStateStats --section ComputeWorkloadAnalysis \
    "$bin/gpu_kernel_benchmark" > "$keep/ncu.log" 2>&1 || rc=$?
  grep -E 'trace_pixel_block|Duration|Registers Per|Achieved Occupancy|Warp Cycles Per Issued|Issued Warp Per|No Eligible|Executed Ipc A|Stall' "$keep/ncu.log" | cut -c1-150 | head -40 || true
  echo "{\"check\":\"profile\",\"exit\":$rc}"
}

example() {
  local rc=0
  timeout "$1" "$bin/star_beside_hole_gpu" --size 512 --out "$work/star-gpu.exr" > "$keep/example.log" 2>&1 || rc=$?
  echo "{\"check\":\"example\",\"exit\":$rc}"
  cp "$work/star-gpu.png" "$keep/" 2> /dev/null || true
}

run() {
  local dir="${1:-$here/build/gpu-pack}"
  work="$(mktemp -d)"
  bin="$work/bin"
  # Where the logs and pictures go: $OUT when the caller gives one (the device tool does), else the work folder.
  keep="${OUT:-$work}"
  # Every step runs under a timeout and none starts that could end after this many seconds: a GPU that loses its
  # rays (each one integrated to max_steps) costs minutes, and a lent machine's time is short.
  deadline="${GRTRACE_GPU_CHECK_SECONDS:-290}"
  mkdir -p "$bin/lib" "$keep"
  for f in "$dir"/*.xz; do xz -dc "$f" > "$bin/$(basename "$f" .xz)"; chmod +x "$bin/$(basename "$f" .xz)"; done
  for f in "$dir"/lib/*.xz; do xz -dc "$f" > "$bin/lib/$(basename "$f" .xz)"; done
  export LD_LIBRARY_PATH="$bin/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  echo "{\"check\":\"device\",\"gpu\":\"$(nvidia-smi -L 2> /dev/null | head -1 | tr '"' ' ')\",\"cores\":$(nproc)}"
  # First the probe (one ray, step by step: where a wrong GPU departs), then the frames.
  run_step 60 probe tests 60 'GpuNvccHostPass.*:GpuProbe.*' gpu_probe.log
  run_step 30 probe_unoptimised unoptimised_probe 30
  run_step 60 sanitizer sanitized_probe 60
  # A probe that departs means every frame below would integrate its rays to the step cap: minutes of a lent
  # machine for nothing new. Stop here unless told to go on (GRTRACE_GPU_CHECK_ALL=1).
  if [ "${probe_exit:-0}" != 0 ] && [ "${GRTRACE_GPU_CHECK_ALL:-0}" != 1 ]; then
    echo "{\"check\":\"done\",\"seconds\":$SECONDS,\"stopped\":\"the probe departs (exit $probe_exit): frames and timings skipped; GRTRACE_GPU_CHECK_ALL=1 runs them anyway\"}"
    rm -rf "$work"
    return 0
  fi
  run_step 150 frames tests 150 'GpuDevice.*' gpu_frame_test.log
  run_step 40 example example 40
  # The kernels alone, as built and with everything inlined (GRTRACE_GPU_INLINE_ALL), alternated.
  run_step 40 kernel_benchmark kernels 40
  if [ "${GRTRACE_GPU_CHECK_PROFILE:-0}" = 1 ]; then run_step 90 profile profile 90; fi
  local kerr=(--metric kerr --spin 0.9 --scene disk --camera-r 50 --camera-theta 80 --fov 60 --width 1024 --height 1024)
  for device in cuda cpu; do
    run_step 20 "kerr_disk_$device" timed "kerr_disk_$device" "${kerr[@]}" --device "$device" --out "$work/kerr-$device.exr"
    run_step 20 "main_general_$device" timed "main_general_$device" --tracer general --device "$device" \
      --out "$work/main-$device.exr"
  done
  cp "$work/kerr-cuda.png" "$work/main-cuda.png" "$keep/" 2> /dev/null || true
  # What auto picks: the GPU for the Kerr frame; the CPU's table tracer for the default (Schwarzschild) frame.
  run_step 20 kerr_disk_auto timed kerr_disk_auto "${kerr[@]}" --device auto --out "$work/kerr-auto.exr"
  run_step 20 main_auto timed main_auto --device auto --out "$work/main-auto.exr"
  run_step 20 kerr_disk_cuda_again timed kerr_disk_cuda_again "${kerr[@]}" --device cuda --out "$work/kerr-cuda-2.exr"
  run_step 20 kerr_disk_2048_cuda timed kerr_disk_2048_cuda "${kerr[@]/1024/2048}" --device cuda \
    --out "$work/kerr-cuda-2048.exr"
  run_step 60 kerr_flight_300_cuda timed kerr_flight_300_cuda "${kerr[@]}" --device cuda --flight circular \
    --frames 300 --out "$work/flight.exr"
  echo "{\"check\":\"done\",\"seconds\":$SECONDS}"
  rm -rf "$work"
}

case "$mode" in
  pack) pack ;;
  run) shift; run "$@" ;;
  *) echo "usage: bash cmake/gpu-check.sh pack | run [DIR]" >&2; exit 2 ;;
esac
