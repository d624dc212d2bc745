#pragma once
// The scalar lane: what TRay's per-vertex math (the *_lanes.h files: sampling, Fresnel, GGX,
// Lambert, light sampling, MIS) calls on one float. Those files are written once, as templates
// over the lane type F, and compiled twice: with F = float in namespace tray for the scalar
// code, and with F = FloatVec (core/lane_simd-inl.h: one vector of a SIMD target, Highway)
// in each target's namespace for the wavefront's SIMD stages. Every operation has the same
// name and meaning for both, so one text gives both its bits (docs/lanes.md).
//
// The names end in Of where the C library's would collide (::sqrt takes a double).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "core/math.h"

namespace tray {

/// The types that go with a lane type F: its mask, its integer, its 2- and 3-vectors.
template <class F>
struct LaneTypes;
template <>
struct LaneTypes<float> {
  using Mask = bool;
  using Int = int32_t;
  using V2 = Vec2;
  using V3 = Vec3;
  using Uint = uint32_t;  ///< unsigned 32-bit (wrapping) integers, lane for lane
  using U64 = uint64_t;   ///< unsigned 64-bit integers (a vector of them: two halves)
};
template <class F>
using MaskOf = typename LaneTypes<F>::Mask;
template <class F>
using IntOf = typename LaneTypes<F>::Int;
template <class F>
using UintOf = typename LaneTypes<F>::Uint;
template <class F>
using U64Of = typename LaneTypes<F>::U64;
template <class F>
using Vec2Of = typename LaneTypes<F>::V2;
template <class F>
using Vec3Of = typename LaneTypes<F>::V3;

/// m ? a : b (a select: both are computed).
inline float select(bool m, float a, float b) {
  return m ? a : b;
}
inline int32_t select(bool m, int32_t a, int32_t b) {
  return m ? a : b;
}
inline Vec3 select(bool m, const Vec3& a, const Vec3& b) {
  return m ? a : b;
}
/// std::max(a, b): b where a < b, else a (a NaN in b gives a).
inline float maxOf(float a, float b) {
  return std::max(a, b);
}
/// std::min(a, b): b where b < a, else a.
inline float minOf(float a, float b) {
  return std::min(a, b);
}
inline float absOf(float a) {
  return std::fabs(a);
}
inline float sqrtOf(float a) {
  return std::sqrt(a);
}
inline float floorOf(float a) {
  return std::floor(a);
}
/// |magnitude| with the sign of `sign`.
inline float copySignOf(float magnitude, float sign) {
  return std::copysign(magnitude, sign);
}
inline bool isInfOf(float a) {
  return std::isinf(a);
}
inline bool isFiniteOf(float a) {
  return std::isfinite(a);
}
/// Whether any lane, every lane, no lane of the mask is set (one lane: the bool itself).
inline bool anyOf(bool m) {
  return m;
}
inline bool allOf(bool m) {
  return m;
}
inline bool noneOf(bool m) {
  return !m;
}
/// The float's integer value, truncated toward zero (C++'s conversion).
inline int32_t truncateToInt(float a) {
  return static_cast<int32_t>(a);
}
/// The integer's float value (C++'s conversion: rounded to nearest).
inline float toFloatOf(int32_t a) {
  return static_cast<float>(a);
}
/// a / n and a % n (C++'s: truncated), for 0 <= a < 2^31 and 0 < n < 2^16.
inline void divModOf(int32_t a, int32_t n, int32_t& quotient, int32_t& remainder) {
  quotient = a / n;
  remainder = a % n;
}
/// The float's bits as an integer, and back.
inline int32_t bitsOf(float a) {
  return std::bit_cast<int32_t>(a);
}
inline float floatFromBits(int32_t bits) {
  return std::bit_cast<float>(bits);
}

// Unsigned lanes (UintOf, U64Of: C++'s own operators, wrapping, and these).
/// The unsigned integer's bits as a signed one (the value for a < 2^31).
inline int32_t intFromBits(uint32_t a) {
  return std::bit_cast<int32_t>(a);
}
/// Bit k of a at bit 31 - k.
inline uint32_t reverseBitsOf(uint32_t v) {
  v = __builtin_bswap32(v);  // bytes, then the bits within each byte
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  return ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
}
/// The low and the high 32 bits of a 64-bit lane; a 32-bit lane widened to 64 bits.
inline uint32_t low32Of(uint64_t a) {
  return uint32_t(a);
}
inline uint32_t high32Of(uint64_t a) {
  return uint32_t(a >> 32);
}
inline uint64_t widenOf(uint32_t a) {
  return a;
}
/// table[index] (a vector: a gather, one index per lane).
inline uint32_t gatherOf(const uint32_t* table, uint32_t index) {
  return table[index];
}

}  // namespace tray
