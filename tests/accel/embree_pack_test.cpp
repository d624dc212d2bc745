// packRays8 (accel/embree_pack.cpp) transposes eight rays into Embree's packet (by an 8 x 8
// transpose in registers on AVX2 and AVX-512, by gathers on the 128-bit targets): every field of
// every lane must be the ray's own bits, whatever the rays hold, on every SIMD target.
#include "accel/embree_pack.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>

#include "accel/embree_rays.h"
#include "tests/simd_targets.h"

namespace tray {
namespace {

uint32_t bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

TEST(EmbreePack, EveryLaneHoldsItsRaysBits) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> any(-1e3f, 1e3f);
  std::vector<Ray> rays(8 * 50 + 3);  // offsets not a multiple of 8 rays, too
  for (Ray& r : rays) {
    r.o = {any(rng), any(rng), any(rng)}, r.d = {any(rng), any(rng), any(rng)};
    r.tmin = any(rng), r.tmax = any(rng), r.time = any(rng);
    r.blend = rng() & 1 ? BlendRays::kStochastic : BlendRays::kHit;
  }
  rays[5].tmax = kInfinity, rays[6].d.x = -0.0f;
  // Rays Embree refuses (issue 40): packRays8 says so for a packet holding one (embreeAccepts).
  rays[200].o.y = std::numeric_limits<float>::quiet_NaN();
  rays[300].d.z = -2e18f;
  rays[350].tmin = std::numeric_limits<float>::quiet_NaN();
  test::onEverySimdTarget(0, [&] {
    int packets = 0;
    for (size_t b = 0; b + 8 <= rays.size(); b += 3, ++packets) {
      alignas(32) RTCRay8 p;
      std::memset(&p, 0xab, sizeof p);
      const bool accepted = packRays8(&rays[b], uint32_t(1000 + b), p);
      bool each = true;
      for (size_t l = 0; l < 8; ++l) each = each && embreeAccepts(rays[b + l]);
      EXPECT_EQ(accepted, each) << "packet at " << b;
      for (int l = 0; l < 8; ++l) {
        const Ray& r = rays[b + size_t(l)];
        EXPECT_EQ(bits(p.org_x[l]), bits(r.o.x));
        EXPECT_EQ(bits(p.org_y[l]), bits(r.o.y));
        EXPECT_EQ(bits(p.org_z[l]), bits(r.o.z));
        EXPECT_EQ(bits(p.dir_x[l]), bits(r.d.x));
        EXPECT_EQ(bits(p.dir_y[l]), bits(r.d.y));
        EXPECT_EQ(bits(p.dir_z[l]), bits(r.d.z));
        EXPECT_EQ(bits(p.tnear[l]), bits(r.tmin));
        EXPECT_EQ(bits(p.tfar[l]), bits(r.tmax));
        EXPECT_EQ(bits(p.time[l]), bits(r.time));
        EXPECT_EQ(p.mask[l], 0xffffffffu);
        EXPECT_EQ(p.id[l], uint32_t(1000 + b + size_t(l)));
        EXPECT_EQ(p.flags[l], 0u);
      }
    }
    return packets;
  });
}

}  // namespace
}  // namespace tray
