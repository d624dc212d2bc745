#pragma once
// Sizes and the target check shared by the SIMD kernels (integrators/camera_batch.cpp,
// integrators/surface_batch.cpp, integrators/sampler_batch.cpp): Highway picks the vector width at
// run time, so buffers are sized for the widest target.
#include <cstddef>

namespace tray {

/// Floats per vector of the widest target (AVX-512): each kernel asserts its target fits.
inline constexpr size_t kMaxSimdLanes = 16;

/// True when the CPU has a SIMD target the kernels were built for (SSSE3 or better); without
/// one, their callers keep to the scalar code.
bool hasSimdTarget();

/// n rounded up to whole vectors of the widest target: a kernel's last, partial vector may
/// read and write that far.
constexpr size_t wholeSimdVectors(size_t n) {
  return (n + kMaxSimdLanes - 1) / kMaxSimdLanes * kMaxSimdLanes;
}

}  // namespace tray
