// The SIMD camera rays of integrators/camera_batch.h against the scalar code they replace, bit for
// bit: Sampler's constructor and next2D, PixelSampler::offset and PerspectiveCamera::generateRay.
#include "integrators/camera_batch.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "tests/scene_builder.h"
#include "tests/simd_targets.h"

namespace tray {
namespace {

using Pattern = PixelSampler::Pattern;
using Sequence = Sampler::Sequence;

constexpr Pattern kPatterns[] = {Pattern::kCenter, Pattern::kCorners, Pattern::kGrid,
                                 Pattern::kJitter, Pattern::kSequence};

/// What Integrator::sampler and Integrator::cameraRay give sample i of pixel (x, y) of a
/// pinhole camera without motion: the scalar reference.
struct ScalarSample {
  Sampler sampler;
  Vec2 offset;
  Ray ray;
};
ScalarSample scalarSample(const Camera& camera, const PixelSampler& pixels, uint64_t seed,
                          Sequence sequence, int width, int x, int y, int i) {
  Sampler s(uint32_t(y) * uint32_t(width) + uint32_t(x), uint32_t(i), seed, sequence);
  const Vec2 offset = pixels.offset(i, s.next2D());
  const float cx = x + 0.5f, cy = y + 0.5f;
  const Ray ray = camera.generateRay(cx + offset.x, cy + offset.y);
  return {s, offset, ray};
}

using test::randomPlacement;

void expectSameBits(float a, float b, const char* what, size_t k) {
  EXPECT_EQ(std::bit_cast<uint32_t>(a), std::bit_cast<uint32_t>(b))
      << what << " of path " << k << ": " << a << " vs " << b;
}

/// Random cameras, image sizes, pixel samplers, seeds, sequences and wave lengths, with the
/// dispatched target's kernel; returns the paths compared.
int compareRandomCases() {
  std::mt19937_64 rng(20261202);
  int cases = 0;
  for (int trial = 0; trial < 400; ++trial) {
    CameraDesc desc;
    desc.yfov = std::uniform_real_distribution<float>(0.05f, 2.5f)(rng);
    desc.znear = trial % 3 == 0 ? 0.0f : std::uniform_real_distribution<float>(0.001f, 2)(rng);
    desc.toWorld = randomPlacement(rng);
    const int width = std::uniform_int_distribution<int>(1, 2000)(rng);
    const int height = std::uniform_int_distribution<int>(1, 2000)(rng);
    const auto camera = Camera::create(desc, width, height);
    const Pattern pattern = kPatterns[trial % 5];
    // Small counts, non-squares (jitter's rest), and large ones (high sample indices).
    const int spp = trial % 7 == 0 ? std::uniform_int_distribution<int>(1, 1 << 22)(rng)
                                   : std::uniform_int_distribution<int>(1, 70)(rng);
    const float radius = std::uniform_real_distribution<float>(0.5f, 2.5f)(rng);
    const PixelSampler pixels(pattern, spp, radius);
    const uint64_t seed = trial % 4 == 0 ? uint64_t(trial) : rng();
    const Sequence sequence = trial % 2 ? Sequence::kSobol : Sequence::kIndependent;
    const auto batch = CameraRayBatch::make(*camera, pixels, seed, sequence, false, width);
    EXPECT_TRUE(batch);
    if (!batch) return cases;
    // Any length: whole vectors of every target's width and a partial last one.
    const size_t n = std::uniform_int_distribution<size_t>(1, 100)(rng);
    std::vector<int32_t> x(n), y(n);
    std::vector<uint32_t> sample(n);
    for (size_t k = 0; k < n; ++k) {
      x[k] = std::uniform_int_distribution<int>(0, width - 1)(rng);
      y[k] = std::uniform_int_distribution<int>(0, height - 1)(rng);
      sample[k] = uint32_t(std::uniform_int_distribution<int>(0, pixels.count() - 1)(rng));
    }
    CameraRayLanes lanes;
    batch->generate(n, x.data(), y.data(), sample.data(), lanes);
    for (size_t k = 0; k < n; ++k) {
      const ScalarSample want =
          scalarSample(*camera, pixels, seed, sequence, width, x[k], y[k], int(sample[k]));
      const Sampler got = batch->sampler(lanes, k);
      EXPECT_TRUE(got == want.sampler) << "sampler of path " << k << ", trial " << trial;
      EXPECT_EQ(got.dimension(), 2u);
      const Vec2 offset = CameraRayBatch::offset(lanes, k);
      expectSameBits(offset.x, want.offset.x, "offset.x", k);
      expectSameBits(offset.y, want.offset.y, "offset.y", k);
      const Ray ray = batch->ray(lanes, k);
      for (int a = 0; a < 3; ++a) {
        expectSameBits(ray.o[a], want.ray.o[a], "o", k);
        expectSameBits(ray.d[a], want.ray.d[a], "d", k);
      }
      expectSameBits(ray.tmin, want.ray.tmin, "tmin", k);
      expectSameBits(ray.tmax, want.ray.tmax, "tmax", k);
      expectSameBits(ray.time, want.ray.time, "time", k);
      EXPECT_EQ(ray.blend, want.ray.blend);
      ++cases;
    }
    if (testing::Test::HasFailure()) break;  // one trial's report is enough
  }
  return cases;
}

TEST(CameraBatch, SameBitsAsTheScalarCameraRays) {
  test::onEverySimdTarget(10000, compareRandomCases);
}

TEST(CameraBatch, ConsecutiveSamplesOfOnePixelAsTheWavefrontMakesThem) {
  // The wavefront's order: every sample of a pixel in turn, so lanes share a pixel.
  CameraDesc desc;
  desc.toWorld = Transform(Mat4::translate({0.5f, -2.0f, 7.0f}));
  const auto camera = Camera::create(desc, 64, 48);
  for (Sequence sequence : {Sequence::kIndependent, Sequence::kSobol})
    for (Pattern pattern : kPatterns) {
      const PixelSampler pixels(pattern, 37, 1.5f);
      const auto batch = CameraRayBatch::make(*camera, pixels, 7, sequence, false, 64);
      ASSERT_TRUE(batch);
      std::vector<int32_t> x, y;
      std::vector<uint32_t> sample;
      for (int p = 0; p < 5; ++p)
        for (int i = 0; i < pixels.count(); ++i)
          x.push_back(3 + p), y.push_back(40), sample.push_back(uint32_t(i));
      CameraRayLanes lanes;
      batch->generate(x.size(), x.data(), y.data(), sample.data(), lanes);
      for (size_t k = 0; k < x.size(); ++k) {
        const ScalarSample want =
            scalarSample(*camera, pixels, 7, sequence, 64, x[k], y[k], int(sample[k]));
        EXPECT_TRUE(batch->sampler(lanes, k) == want.sampler) << k;
        expectSameBits(batch->ray(lanes, k).d.x, want.ray.d.x, "d.x", k);
        expectSameBits(CameraRayBatch::offset(lanes, k).y, want.offset.y, "offset.y", k);
      }
    }
}

TEST(CameraBatch, OtherCamerasAndMotionAreLeftToTheScalarCode) {
  const PixelSampler pixels(Pattern::kJitter, 16, 1.5f);
  CameraDesc pinhole;
  const auto perspective = Camera::create(pinhole, 32, 32);
  EXPECT_TRUE(CameraRayBatch::make(*perspective, pixels, 0, Sequence::kSobol, false, 32));
  // Motion blur: rays draw a shutter time (and a moving camera moves them).
  EXPECT_FALSE(CameraRayBatch::make(*perspective, pixels, 0, Sequence::kSobol, true, 32));
  CameraDesc ortho = pinhole;
  ortho.type = CameraDesc::Type::kOrthographic;
  EXPECT_FALSE(
      CameraRayBatch::make(*Camera::create(ortho, 32, 32), pixels, 0, Sequence::kSobol, false, 32));
  CameraDesc lens = pinhole;
  lens.lensRadius = 0.1f, lens.focusDistance = 3.0f;
  const auto thinLens = Camera::create(lens, 32, 32);
  EXPECT_FALSE(thinLens->pinhole());
  EXPECT_FALSE(CameraRayBatch::make(*thinLens, pixels, 0, Sequence::kIndependent, false, 32));
}

}  // namespace
}  // namespace tray
