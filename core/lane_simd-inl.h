// The SIMD lane: one vector of floats of a Highway target, as a value type with the operators
// and the lane ops (core/lane_ops.h) of one float, so that the one-text headers (*_lanes.h)
// compile for it unchanged. A thin wrapper rather than Highway's own types: those live in
// hwy's namespace, where TRay's lane ops cannot join them (argument-dependent lookup), and have
// no && || ! on masks. Everything inlines to Highway's ops: no cost (docs/lanes.md).
//
// Highway's -inl.h convention: included once per target after hwy/highway.h (before any
// *_lanes.h in SIMD mode), guarded per target by HWY_TARGET_TOGGLE.
#if defined(TRAY_CORE_LANE_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TRAY_CORE_LANE_SIMD_INL_H_
#undef TRAY_CORE_LANE_SIMD_INL_H_
#else
#define TRAY_CORE_LANE_SIMD_INL_H_
#endif

#include "core/lane_ops.h"
#include "core/simd_lanes.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The scalar lane's ops, beside the vector ones below: a name declared here hides tray's.
using tray::absOf;
using tray::allOf;
using tray::anyOf;
using tray::bitsOf;
using tray::copySignOf;
using tray::divModOf;
using tray::floatFromBits;
using tray::floorOf;
using tray::gatherOf;
using tray::high32Of;
using tray::intFromBits;
using tray::isFiniteOf;
using tray::isInfOf;
using tray::low32Of;
using tray::maxOf;
using tray::minOf;
using tray::noneOf;
using tray::reverseBitsOf;
using tray::select;
using tray::sqrtOf;
using tray::toFloatOf;
using tray::truncateToInt;
using tray::widenOf;

#if HWY_TARGET != HWY_SCALAR
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using DU = hn::RebindToUnsigned<DF>;
using D64 = hn::Repartition<uint64_t, DU>;  // half as many lanes as DU
static_assert(HWY_MAX_BYTES / sizeof(float) <= kMaxSimdLanes);

/// A lane mask (one bit per float lane).
struct MaskVec {
  hn::Mask<DF> m;
  MaskVec() = default;
  HWY_INLINE MaskVec(hn::Mask<DF> x) : m(x) {}  // NOLINT: a lane mask is its mask
  /// Every lane set, or none.
  HWY_INLINE explicit MaskVec(bool all) : m(hn::FirstN(DF(), all ? hn::Lanes(DF()) : 0)) {}
};
/// A vector of floats: one lane per vertex.
struct FloatVec {
  hn::Vec<DF> v;
  FloatVec() = default;
  HWY_INLINE FloatVec(hn::Vec<DF> x) : v(x) {}           // NOLINT: a lane is its vector
  HWY_INLINE FloatVec(float s) : v(hn::Set(DF(), s)) {}  // NOLINT: constants broadcast
};
/// A vector of 32-bit integers, lane for lane with FloatVec.
struct IntVec {
  hn::Vec<DI> v;
  IntVec() = default;
  HWY_INLINE IntVec(hn::Vec<DI> x) : v(x) {}             // NOLINT
  HWY_INLINE IntVec(int32_t s) : v(hn::Set(DI(), s)) {}  // NOLINT
};
/// A vector of unsigned 32-bit integers, lane for lane with FloatVec (wrapping arithmetic).
struct UintVec {
  hn::Vec<DU> v;
  UintVec() = default;
  HWY_INLINE UintVec(hn::Vec<DU> x) : v(x) {}              // NOLINT
  HWY_INLINE UintVec(uint32_t s) : v(hn::Set(DU(), s)) {}  // NOLINT
};
/// Unsigned 64-bit integers, lane for lane with FloatVec: Highway's vectors of uint64 have half
/// as many lanes, so two of them, FloatVec's lower lanes and its upper lanes.
struct U64Vec {
  hn::Vec<D64> lo, hi;
  U64Vec() = default;
  HWY_INLINE U64Vec(hn::Vec<D64> lower, hn::Vec<D64> upper) : lo(lower), hi(upper) {}
  HWY_INLINE U64Vec(uint64_t s) : lo(hn::Set(D64(), s)), hi(lo) {}  // NOLINT
};
struct Vec2Vec {
  FloatVec x, y;
};
/// core/math.h's Vec3, one per lane: the same operators, each in the same order.
struct Vec3Vec {
  FloatVec x, y, z;
};
}  // namespace HWY_NAMESPACE
template <>
struct LaneTypes<HWY_NAMESPACE::FloatVec> {
  using Mask = HWY_NAMESPACE::MaskVec;
  using Int = HWY_NAMESPACE::IntVec;
  using V2 = HWY_NAMESPACE::Vec2Vec;
  using V3 = HWY_NAMESPACE::Vec3Vec;
  using Uint = HWY_NAMESPACE::UintVec;
  using U64 = HWY_NAMESPACE::U64Vec;
};
namespace HWY_NAMESPACE {

HWY_INLINE FloatVec operator+(FloatVec a, FloatVec b) {
  return hn::Add(a.v, b.v);
}
HWY_INLINE FloatVec operator-(FloatVec a, FloatVec b) {
  return hn::Sub(a.v, b.v);
}
HWY_INLINE FloatVec operator*(FloatVec a, FloatVec b) {
  return hn::Mul(a.v, b.v);
}
HWY_INLINE FloatVec operator/(FloatVec a, FloatVec b) {
  return hn::Div(a.v, b.v);
}
HWY_INLINE FloatVec operator-(FloatVec a) {
  return hn::Neg(a.v);
}
HWY_INLINE FloatVec& operator+=(FloatVec& a, FloatVec b) {
  return a = a + b;
}
HWY_INLINE FloatVec& operator-=(FloatVec& a, FloatVec b) {
  return a = a - b;
}
HWY_INLINE FloatVec& operator*=(FloatVec& a, FloatVec b) {
  return a = a * b;
}
HWY_INLINE MaskVec operator<(FloatVec a, FloatVec b) {
  return {hn::Lt(a.v, b.v)};
}
HWY_INLINE MaskVec operator<=(FloatVec a, FloatVec b) {
  return {hn::Le(a.v, b.v)};
}
HWY_INLINE MaskVec operator>(FloatVec a, FloatVec b) {
  return {hn::Gt(a.v, b.v)};
}
HWY_INLINE MaskVec operator>=(FloatVec a, FloatVec b) {
  return {hn::Ge(a.v, b.v)};
}
HWY_INLINE MaskVec operator==(FloatVec a, FloatVec b) {
  return {hn::Eq(a.v, b.v)};
}
HWY_INLINE MaskVec operator!=(FloatVec a, FloatVec b) {
  return {hn::Ne(a.v, b.v)};
}
// Masks combine lane by lane; both operands are always computed (no short circuit).
HWY_INLINE MaskVec operator&&(MaskVec a, MaskVec b) {
  return {hn::And(a.m, b.m)};
}
HWY_INLINE MaskVec operator||(MaskVec a, MaskVec b) {
  return {hn::Or(a.m, b.m)};
}
HWY_INLINE MaskVec operator!(MaskVec a) {
  return {hn::Not(a.m)};
}

HWY_INLINE IntVec operator+(IntVec a, IntVec b) {
  return hn::Add(a.v, b.v);
}
HWY_INLINE IntVec operator-(IntVec a, IntVec b) {
  return hn::Sub(a.v, b.v);
}
HWY_INLINE IntVec operator-(IntVec a) {
  return hn::Neg(a.v);
}
HWY_INLINE IntVec operator&(IntVec a, IntVec b) {
  return hn::And(a.v, b.v);
}
HWY_INLINE IntVec operator*(IntVec a, IntVec b) {
  return hn::Mul(a.v, b.v);
}
HWY_INLINE MaskVec operator==(IntVec a, IntVec b) {
  return {hn::RebindMask(DF(), hn::Eq(a.v, b.v))};
}
HWY_INLINE MaskVec operator>(IntVec a, IntVec b) {
  return {hn::RebindMask(DF(), hn::Gt(a.v, b.v))};
}
HWY_INLINE MaskVec operator<(IntVec a, IntVec b) {
  return {hn::RebindMask(DF(), hn::Lt(a.v, b.v))};
}

HWY_INLINE UintVec operator+(UintVec a, UintVec b) {
  return hn::Add(a.v, b.v);
}
HWY_INLINE UintVec operator*(UintVec a, UintVec b) {  // the low 32 bits of the product
  return hn::Mul(a.v, b.v);
}
HWY_INLINE UintVec operator^(UintVec a, UintVec b) {
  return hn::Xor(a.v, b.v);
}
HWY_INLINE UintVec operator&(UintVec a, UintVec b) {
  return hn::And(a.v, b.v);
}
HWY_INLINE UintVec operator|(UintVec a, UintVec b) {
  return hn::Or(a.v, b.v);
}
HWY_INLINE UintVec operator>>(UintVec a, int bits) {
  return hn::ShiftRightSame(a.v, bits);
}
HWY_INLINE UintVec operator<<(UintVec a, int bits) {
  return hn::ShiftLeftSame(a.v, bits);
}
HWY_INLINE IntVec intFromBits(UintVec a) {
  return hn::BitCast(DI(), a.v);
}
/// sobol::reverseBits per lane: the bytes of each lane reversed, then the bits of each byte by
/// a table of reversed nibbles.
HWY_INLINE UintVec reverseBitsOf(UintVec a) {
  const DU du;
  const hn::Repartition<uint8_t, DU> d8;
  alignas(16) static constexpr uint8_t kByteSwap[16] = {3,  2,  1, 0, 7,  6,  5,  4,
                                                        11, 10, 9, 8, 15, 14, 13, 12};
  alignas(16) static constexpr uint8_t kNibble[16] = {0x0, 0x8, 0x4, 0xc, 0x2, 0xa, 0x6, 0xe,
                                                      0x1, 0x9, 0x5, 0xd, 0x3, 0xb, 0x7, 0xf};
  const auto swapped = hn::TableLookupBytes(hn::BitCast(d8, a.v), hn::LoadDup128(d8, kByteSwap));
  const auto lowNibbles = hn::And(swapped, hn::Set(d8, 0x0f));
  const auto highNibbles = hn::BitCast(
      d8, hn::And(hn::ShiftRight<4>(hn::BitCast(du, swapped)), hn::Set(du, 0x0f0f0f0fu)));
  const auto table = hn::LoadDup128(d8, kNibble);
  const auto low = hn::BitCast(du, hn::TableLookupBytes(table, lowNibbles));
  return hn::Or(hn::ShiftLeft<4>(low), hn::BitCast(du, hn::TableLookupBytes(table, highNibbles)));
}
/// table[index] per lane.
HWY_INLINE UintVec gatherOf(const uint32_t* table, UintVec index) {
  return hn::GatherIndex(DU(), table, hn::BitCast(DI(), index.v));
}

HWY_INLINE U64Vec operator+(const U64Vec& a, const U64Vec& b) {
  return {hn::Add(a.lo, b.lo), hn::Add(a.hi, b.hi)};
}
HWY_INLINE U64Vec operator*(const U64Vec& a, const U64Vec& b) {  // the low 64 bits
  return {hn::Mul(a.lo, b.lo), hn::Mul(a.hi, b.hi)};
}
HWY_INLINE U64Vec operator^(const U64Vec& a, const U64Vec& b) {
  return {hn::Xor(a.lo, b.lo), hn::Xor(a.hi, b.hi)};
}
HWY_INLINE U64Vec operator|(const U64Vec& a, const U64Vec& b) {
  return {hn::Or(a.lo, b.lo), hn::Or(a.hi, b.hi)};
}
HWY_INLINE U64Vec operator>>(const U64Vec& a, int bits) {
  return {hn::ShiftRightSame(a.lo, bits), hn::ShiftRightSame(a.hi, bits)};
}
HWY_INLINE U64Vec operator<<(const U64Vec& a, int bits) {
  return {hn::ShiftLeftSame(a.lo, bits), hn::ShiftLeftSame(a.hi, bits)};
}
/// The low (even) and high (odd) 32-bit halves of the 64-bit lanes, in lane order.
HWY_INLINE UintVec low32Of(const U64Vec& a) {
  const DU du;
  return hn::ConcatEven(du, hn::BitCast(du, a.hi), hn::BitCast(du, a.lo));
}
HWY_INLINE UintVec high32Of(const U64Vec& a) {
  const DU du;
  return hn::ConcatOdd(du, hn::BitCast(du, a.hi), hn::BitCast(du, a.lo));
}
HWY_INLINE U64Vec widenOf(UintVec a) {
  const D64 d64;
  const hn::Rebind<uint32_t, D64> dh;  // DU's lower or upper half
  return {hn::PromoteTo(d64, hn::LowerHalf(dh, a.v)), hn::PromoteTo(d64, hn::UpperHalf(dh, a.v))};
}

HWY_INLINE FloatVec select(MaskVec m, FloatVec a, FloatVec b) {
  return hn::IfThenElse(m.m, a.v, b.v);
}
HWY_INLINE IntVec select(MaskVec m, IntVec a, IntVec b) {
  return hn::IfThenElse(hn::RebindMask(DI(), m.m), a.v, b.v);
}
HWY_INLINE FloatVec maxOf(FloatVec a, FloatVec b) {
  return select(a < b, b, a);
}
HWY_INLINE FloatVec minOf(FloatVec a, FloatVec b) {
  return select(b < a, b, a);
}
HWY_INLINE FloatVec absOf(FloatVec a) {
  return hn::Abs(a.v);
}
HWY_INLINE FloatVec sqrtOf(FloatVec a) {
  return hn::Sqrt(a.v);
}
HWY_INLINE FloatVec floorOf(FloatVec a) {
  return hn::Floor(a.v);
}
HWY_INLINE FloatVec copySignOf(FloatVec magnitude, FloatVec sign) {
  return hn::CopySign(magnitude.v, sign.v);
}
HWY_INLINE MaskVec isInfOf(FloatVec a) {
  return {hn::IsInf(a.v)};
}
HWY_INLINE MaskVec isFiniteOf(FloatVec a) {
  return {hn::IsFinite(a.v)};
}
HWY_INLINE bool anyOf(MaskVec m) {
  return !hn::AllFalse(DF(), m.m);
}
HWY_INLINE bool allOf(MaskVec m) {
  return hn::AllTrue(DF(), m.m);
}
HWY_INLINE bool noneOf(MaskVec m) {
  return hn::AllFalse(DF(), m.m);
}
HWY_INLINE IntVec truncateToInt(FloatVec a) {
  return hn::ConvertTo(DI(), a.v);
}
HWY_INLINE FloatVec toFloatOf(IntVec a) {
  return hn::ConvertTo(DF(), a.v);
}
/// a / n and a % n, truncated, for 0 <= a < 2^31 and 0 < n < 2^16 (no integer division in
/// SIMD): the float quotient, truncated, is off by at most one; one correction each way makes
/// it exact.
HWY_INLINE void divModOf(IntVec a, int32_t n, IntVec& quotient, IntVec& remainder) {
  const IntVec vn(n);
  IntVec q = truncateToInt(toFloatOf(a) / FloatVec(float(n)));
  IntVec r = a - q * vn;
  const MaskVec under = r < IntVec(0);
  q = select(under, q + IntVec(-1), q);
  r = select(under, r + vn, r);
  const MaskVec over = !(r < vn);
  quotient = select(over, q + IntVec(1), q);
  remainder = select(over, r - vn, r);
}
HWY_INLINE IntVec bitsOf(FloatVec a) {
  return hn::BitCast(DI(), a.v);
}
HWY_INLINE FloatVec floatFromBits(IntVec bits) {
  return hn::BitCast(DF(), bits.v);
}
/// All bits set in the lanes of m, none elsewhere (an integer flag per lane).
HWY_INLINE IntVec maskBits(MaskVec m) {
  return hn::VecFromMask(DI(), hn::RebindMask(DI(), m.m));
}

// Vec3 per lane: core/math.h's operators, operation for operation.
HWY_INLINE Vec3Vec operator+(const Vec3Vec& a, const Vec3Vec& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
HWY_INLINE Vec3Vec operator-(const Vec3Vec& a, const Vec3Vec& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
HWY_INLINE Vec3Vec operator*(const Vec3Vec& a, const Vec3Vec& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
HWY_INLINE Vec3Vec operator*(const Vec3Vec& a, FloatVec s) {
  return {a.x * s, a.y * s, a.z * s};
}
HWY_INLINE Vec3Vec operator*(FloatVec s, const Vec3Vec& a) {
  return {a.x * s, a.y * s, a.z * s};
}
/// Vec3's a / s: a * (1 / s).
HWY_INLINE Vec3Vec operator/(const Vec3Vec& a, FloatVec s) {
  return a * (FloatVec(1.0f) / s);
}
HWY_INLINE Vec3Vec operator-(const Vec3Vec& a) {
  return {-a.x, -a.y, -a.z};
}
HWY_INLINE FloatVec dot(const Vec3Vec& a, const Vec3Vec& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
HWY_INLINE Vec3Vec cross(const Vec3Vec& a, const Vec3Vec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
HWY_INLINE FloatVec lengthSquared(const Vec3Vec& a) {
  return dot(a, a);
}
HWY_INLINE FloatVec length(const Vec3Vec& a) {
  return sqrtOf(dot(a, a));
}
HWY_INLINE Vec3Vec normalize(const Vec3Vec& a) {
  return a / length(a);
}
HWY_INLINE FloatVec maxComponent(const Vec3Vec& a) {
  return maxOf(a.x, maxOf(a.y, a.z));
}
HWY_INLINE MaskVec isBlack(const Vec3Vec& c) {
  return c.x == 0.0f && c.y == 0.0f && c.z == 0.0f;
}
HWY_INLINE Vec3Vec select(MaskVec m, const Vec3Vec& a, const Vec3Vec& b) {
  return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}
#endif  // HWY_TARGET != HWY_SCALAR

}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();

#endif  // TRAY_CORE_LANE_SIMD_INL_H_
