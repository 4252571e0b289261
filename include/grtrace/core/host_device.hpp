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
