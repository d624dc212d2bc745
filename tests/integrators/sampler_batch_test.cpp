// The draws integrators/sampler_batch.h makes ahead in SIMD against Sampler::next3D, bit for bit,
// on every SIMD target the CPU has: both sequences, random pixels, samples, seeds and dimensions
// (reached by mixed 1D/2D/3D draws), samplers picked in any order, partial vectors.
#include "integrators/sampler_batch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "tests/simd_targets.h"

namespace tray {
namespace {

using Sequence = Sampler::Sequence;

void expectSameBits(const Vec3& a, const Vec3& b, const char* what, size_t k) {
  for (int c = 0; c < 3; ++c)
    EXPECT_EQ(std::bit_cast<uint32_t>(a[c]), std::bit_cast<uint32_t>(b[c]))
        << what << " of path " << k << ", component " << c << ": " << a[c] << " vs " << b[c];
}

/// A sampler somewhere along its path: a random number of draws of each kind already made.
Sampler randomSampler(std::mt19937_64& rng, Sequence sequence, uint64_t seed) {
  Sampler s(uint32_t(rng()), uint32_t(rng() % (1u << 22)), seed, sequence);
  const int draws = std::uniform_int_distribution<int>(0, 40)(rng);
  for (int d = 0; d < draws; ++d) {
    const int kind = int(rng() % 3);
    if (kind == 0) s.next1D();
    if (kind == 1) s.next2D();
    if (kind == 2) s.next3D();
  }
  return s;
}

/// Random waves of samplers for each sequence with the dispatched target; returns the paths
/// compared.
int compareRandomWaves() {
  std::mt19937_64 rng(20261203);
  int compared = 0;
  SamplerDrawsAhead out;  // reused across waves, as the wavefront does
  for (int trial = 0; trial < 200; ++trial) {
    const Sequence sequence = trial % 2 ? Sequence::kSobol : Sequence::kIndependent;
    const uint64_t seed = trial % 5 == 0 ? 0 : rng();
    const size_t count = std::uniform_int_distribution<size_t>(1, 80)(rng);
    std::vector<Sampler> samplers;
    for (size_t k = 0; k < count; ++k) samplers.push_back(randomSampler(rng, sequence, seed));
    // The live queue: some of the samplers, in any order (as paths end).
    std::vector<uint32_t> live;
    for (uint32_t k = 0; k < count; ++k)
      if (rng() % 4 != 0) live.push_back(k);
    std::shuffle(live.begin(), live.end(), rng);
    if (live.empty()) continue;
    SamplerBatch::drawTwo3D(sequence, samplers.data(), live.data(), live.size(), out);
    for (size_t j = 0; j < live.size(); ++j) {
      Sampler reference = samplers[live[j]];
      const Vec3 first = reference.next3D(), second = reference.next3D();
      expectSameBits(out.first[j], first, "first draw", j);
      expectSameBits(out.second[j], second, "second draw", j);
      // Taking them ahead leaves the sampler where drawing them would.
      Sampler skipped = samplers[live[j]];
      skipped.skip3D(), skipped.skip3D();
      EXPECT_TRUE(skipped == reference) << j;
      EXPECT_EQ(skipped.next1D(), reference.next1D()) << j;
      ++compared;
    }
    if (testing::Test::HasFailure()) break;  // one trial's report is enough
  }
  return compared;
}

TEST(SamplerBatch, SameBitsAsNext3D) {
  ASSERT_TRUE(hasSimdTarget());
  test::onEverySimdTarget(5000, compareRandomWaves);
}

}  // namespace
}  // namespace tray
