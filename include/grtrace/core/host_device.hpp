// grtrace/core/host_device.hpp
// One source for the CPU and the GPU: GRTRACE_HD marks a function of the hot path (tableaux, steppers, controllers,
// geodesic systems, metrics, scene objects, the camera, the trace loop) callable from device code when a CUDA
// compiler reads the header, and is empty for every other compiler. Nothing else in the core knows about CUDA.
//
// Assumes: device code is compiled with nvcc -std=c++20 --expt-relaxed-constexpr (the standard library's constexpr
//          helpers, std::min, std::array::operator[], std::get, are then callable on the device).
#pragma once

#if defined(__CUDACC__)
#define GRTRACE_HD __host__ __device__
#else
#define GRTRACE_HD
#endif

/// True in the device pass of a CUDA compilation: where a function must take another road on the GPU (no tables in
/// host memory, no atomics of the standard library).
#if defined(__CUDA_ARCH__)
#define GRTRACE_DEVICE_PASS 1
#else
#define GRTRACE_DEVICE_PASS 0
#endif

/// Code size on the GPU. A GPU thread runs a ray's whole trace as one function, and what is inlined into it is
/// instruction cache: with everything inlined (the right-hand side once per stage, the stages again in every
/// event's refinement, the sky continuation), the Kerr frame's kernel was 1.26 MB of machine code, and its warps
/// spent most of their stalls waiting for instruction fetches (Nsight Compute; docs/benchmarks.md, "GPU"). So:
///  - GRTRACE_GPU_CALLED marks a function the GPU calls rather than inlines: one copy of its code, however many
///    places call it (the refinement of a crossing, the end of a ray, its sky continuation; the right-hand side
///    through integrate/rhs_call.hpp). Nothing on the CPU, whose inlining was measured and is kept;
///  - GRTRACE_FLATTEN_CPU is [[gnu::flatten]] on the CPU and nothing on the GPU.
/// GRTRACE_GPU_INLINE_ALL (defined before the first grtrace header) inlines on the GPU as on the CPU: the previous
/// code, for measuring the difference (cmake/gpu-check.sh's kernel benchmark).
#if GRTRACE_DEVICE_PASS && !defined(GRTRACE_GPU_INLINE_ALL)
#define GRTRACE_GPU_CALLED __noinline__
#define GRTRACE_FLATTEN_CPU
#else
#define GRTRACE_GPU_CALLED
#define GRTRACE_FLATTEN_CPU [[gnu::flatten]]
#endif
