#pragma once
// A wave's camera rays in SIMD (Highway, dynamic dispatch): the counter-based samplers, pixel
// offsets and pinhole rays of many samples at once, bit for bit those of Integrator::sampler
// and Integrator::cameraRay (docs/wavefront.md, "Camera rays in SIMD").
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/camera.h"
#include "core/pixel_sampler.h"
#include "core/ray.h"
#include "core/sampler.h"
#include "core/simd_lanes.h"

namespace tray {

/// What the kernel reads, fixed for a render (plain values, computed once by CameraRayBatch).
struct CameraBatchParams {
  float toWorld[4][4];  ///< the camera's matrix (PinholeProjection's toWorld.m)
  float width, height, znear, tanHalfX, tanHalfY;
  PixelSampler pixels{PixelSampler::Pattern::kCenter, 1, 0.5f};
  int32_t sobol;        ///< 1: Sampler::Sequence::kSobol, 0: kIndependent
  uint32_t imageWidth;  ///< pixels per row (the sampler's pixel index)
  uint64_t seedKey;     ///< the sampler key's first hash, of the seed alone
};

/// The kernel's results, one array per field; entry k is path k's.
struct CameraRayLanes {
  /// Arrays are whole vectors of the widest target (core/simd_lanes.h).
  static constexpr size_t kMaxLanes = kMaxSimdLanes;
  std::vector<uint64_t> key;            ///< its Sampler's state (the dimension is 2)
  std::vector<uint32_t> reversedIndex;  ///< after next2D
  std::vector<float> offsetX, offsetY;  ///< PixelSampler::offset
  std::vector<float> dirX, dirY, dirZ, tmin;
  /// Room for n entries in whole vectors; never shrinks.
  void resize(size_t n);
};

/// Makes the camera rays of samples (x[k], y[k], sample[k]) as Integrator::cameraRay does
/// after Integrator::sampler, for a pinhole perspective camera without motion blur, any pixel
/// sampler pattern and either random sequence; other cameras are left to the scalar code.
class CameraRayBatch {
 public:
  /// The batch for these settings, or nothing when the kernel does not cover them (an
  /// orthographic or thin-lens camera, or motion blur: rays then draw a shutter time).
  static std::optional<CameraRayBatch> make(const Camera& camera, const PixelSampler& pixels,
                                            uint64_t seed, Sampler::Sequence sequence, bool moving,
                                            int imageWidth);
  /// Fills out[0, n) (growing it when smaller) for the n samples given.
  void generate(size_t n, const int32_t* x, const int32_t* y, const uint32_t* sample,
                CameraRayLanes& out) const;
  /// Path k's sampler (after the camera ray drew its 2D point), offset and ray.
  Sampler sampler(const CameraRayLanes& lanes, size_t k) const {
    return Sampler::fromState(lanes.key[k], lanes.reversedIndex[k], 2, sequence_);
  }
  static Vec2 offset(const CameraRayLanes& lanes, size_t k) {
    return {lanes.offsetX[k], lanes.offsetY[k]};
  }
  Ray ray(const CameraRayLanes& lanes, size_t k) const {
    Ray r;
    setRay(lanes, k, r);
    return r;
  }
  /// The same ray written field by field into `r` (a fresh Ray: tmax, blend and time are its
  /// defaults). In place: a Ray returned and copied costs a store-forwarding stall, a 16-byte
  /// load over the 4-byte stores that built it (core/ray.h, setSpawnRay).
  void setRay(const CameraRayLanes& lanes, size_t k, Ray& r) const {
    r.o = origin_;
    r.d.x = lanes.dirX[k], r.d.y = lanes.dirY[k], r.d.z = lanes.dirZ[k];
    r.tmin = lanes.tmin[k];
  }

 private:
  CameraBatchParams params_;
  Vec3 origin_;  ///< toWorld.point(0), every ray's
  Sampler::Sequence sequence_;
};

}  // namespace tray
