#pragma once
// Four floats at once, for the 4-wide BVH: box tests of four children and triangle tests of four
// triangles per instruction. On x86-64 this is SSE2, part of the base instruction set, so the
// project needs no -march flag and runs on every x86-64 machine; elsewhere a plain loop (which
// compilers auto-vectorise). Only IEEE single-precision +, -, *, / and comparisons are used, so
// each lane computes bit-for-bit what the scalar code does (no FMA contraction: SSE2 has none).
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tray::simd {

#if defined(__SSE2__)

struct F4 {
  __m128 v;
};
struct M4 {
  __m128 v;
};

inline F4 load(const float* p) {
  return {_mm_load_ps(p)};
}  // p 16-byte aligned
inline F4 set1(float x) {
  return {_mm_set1_ps(x)};
}
inline F4 operator+(F4 a, F4 b) {
  return {_mm_add_ps(a.v, b.v)};
}
inline F4 operator-(F4 a, F4 b) {
  return {_mm_sub_ps(a.v, b.v)};
}
inline F4 operator*(F4 a, F4 b) {
  return {_mm_mul_ps(a.v, b.v)};
}
inline F4 operator/(F4 a, F4 b) {
  return {_mm_div_ps(a.v, b.v)};
}
inline F4 min(F4 a, F4 b) {
  return {_mm_min_ps(a.v, b.v)};
}
inline F4 max(F4 a, F4 b) {
  return {_mm_max_ps(a.v, b.v)};
}
inline M4 operator<(F4 a, F4 b) {
  return {_mm_cmplt_ps(a.v, b.v)};
}
inline M4 operator<=(F4 a, F4 b) {
  return {_mm_cmple_ps(a.v, b.v)};
}
inline M4 operator>(F4 a, F4 b) {
  return {_mm_cmpgt_ps(a.v, b.v)};
}
inline M4 operator==(F4 a, F4 b) {
  return {_mm_cmpeq_ps(a.v, b.v)};
}
inline M4 operator&(M4 a, M4 b) {
  return {_mm_and_ps(a.v, b.v)};
}
inline M4 operator|(M4 a, M4 b) {
  return {_mm_or_ps(a.v, b.v)};
}
/// Bit i set when lane i of the mask is true.
inline int bits(M4 m) {
  return _mm_movemask_ps(m.v);
}
/// Lanes of `a` where the mask is true, else of `b`.
inline F4 select(M4 m, F4 a, F4 b) {
  return {_mm_or_ps(_mm_and_ps(m.v, a.v), _mm_andnot_ps(m.v, b.v))};
}
inline void store(float* p, F4 a) {
  _mm_storeu_ps(p, a.v);
}
/// Lanes 0-2 of a, lane 3 cleared to +0 (a bit mask: no arithmetic on lane 3).
inline F4 xyz(F4 a) {
  return {_mm_and_ps(a.v, _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1)))};
}

#else  // portable fallback: same semantics, one lane at a time

struct F4 {
  float v[4];
};
struct M4 {
  bool v[4];
};

template <class Op>
inline F4 map(F4 a, F4 b, Op op) {
  F4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = op(a.v[i], b.v[i]);
  return r;
}
template <class Op>
inline M4 cmp(F4 a, F4 b, Op op) {
  M4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = op(a.v[i], b.v[i]);
  return r;
}
inline F4 load(const float* p) {
  return {{p[0], p[1], p[2], p[3]}};
}
inline F4 set1(float x) {
  return {{x, x, x, x}};
}
inline F4 operator+(F4 a, F4 b) {
  return map(a, b, [](float x, float y) { return x + y; });
}
inline F4 operator-(F4 a, F4 b) {
  return map(a, b, [](float x, float y) { return x - y; });
}
inline F4 operator*(F4 a, F4 b) {
  return map(a, b, [](float x, float y) { return x * y; });
}
inline F4 operator/(F4 a, F4 b) {
  return map(a, b, [](float x, float y) { return x / y; });
}
// As SSE's minps/maxps: the second operand when either is NaN.
inline F4 min(F4 a, F4 b) {
  return map(a, b, [](float x, float y) { return x < y ? x : y; });
}
inline F4 max(F4 a, F4 b) {
  return map(a, b, [](float x, float y) { return x > y ? x : y; });
}
inline M4 operator<(F4 a, F4 b) {
  return cmp(a, b, [](float x, float y) { return x < y; });
}
inline M4 operator<=(F4 a, F4 b) {
  return cmp(a, b, [](float x, float y) { return x <= y; });
}
inline M4 operator>(F4 a, F4 b) {
  return cmp(a, b, [](float x, float y) { return x > y; });
}
inline M4 operator==(F4 a, F4 b) {
  return cmp(a, b, [](float x, float y) { return x == y; });
}
inline M4 operator&(M4 a, M4 b) {
  return {{a.v[0] && b.v[0], a.v[1] && b.v[1], a.v[2] && b.v[2], a.v[3] && b.v[3]}};
}
inline M4 operator|(M4 a, M4 b) {
  return {{a.v[0] || b.v[0], a.v[1] || b.v[1], a.v[2] || b.v[2], a.v[3] || b.v[3]}};
}
inline int bits(M4 m) {
  return m.v[0] | m.v[1] << 1 | m.v[2] << 2 | m.v[3] << 3;
}
inline F4 select(M4 m, F4 a, F4 b) {
  F4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = m.v[i] ? a.v[i] : b.v[i];
  return r;
}
inline void store(float* p, F4 a) {
  for (int i = 0; i < 4; ++i) p[i] = a.v[i];
}
inline F4 xyz(F4 a) {
  return {{a.v[0], a.v[1], a.v[2], 0.0f}};
}

#endif

}  // namespace tray::simd
