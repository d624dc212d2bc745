#pragma once
// A stand-in for a scene when testing pixel sampling: the "camera" puts the raster position in
// the ray origin and the "integrator" returns a function of it, so filters, sample positions
// and adaptive subdivision can be checked against exact integrals. No accelerator is used.
#include <atomic>
#include <deque>
#include <functional>
#include <mutex>
#include <vector>

#include "core/integrator.h"
#include "render/prepared_scene.h"

namespace tray::test {

class RasterCamera final : public Camera {
 public:
  Ray generateRay(float x, float y) const override { return Ray{{x, y, 0}, {0, 0, -1}}; }
};

class NullAccelerator final : public Accelerator {
 public:
  bool intersect(const Ray&, Hit&) const override { return false; }
  bool occluded(const Ray&) const override { return false; }
  void allHits(const Ray&, std::vector<Hit>&) const override {}
};

/// Image function f(x, y) -> (value, object id); id -1 is "background" (alpha 0).
struct RasterImage {
  std::function<float(float, float)> value;
  std::function<int(float, float)> object = [](float, float) { return 0; };
};

/// Li = the image at the ray's raster position; counts calls and may record positions.
class RasterIntegrator final : public Integrator {
 public:
  RasterIntegrator(const RenderContext& ctx, RasterImage image, bool record = false)
      : Integrator(ctx), image_(std::move(image)), record_(record) {}
  Color Li(const Ray& ray, Sampler&, RayStats&, PrimaryHit* primary) const override {
    ++calls;
    if (record_) {
      std::lock_guard<std::mutex> lock(mutex_);
      positions.push_back({ray.o.x, ray.o.y});
    }
    const int id = image_.object(ray.o.x, ray.o.y);
    if (primary) primary->hit = id >= 0, primary->objectId = id;
    return Color(image_.value(ray.o.x, ray.o.y));
  }
  mutable std::atomic<uint64_t> calls{0};
  mutable std::vector<Vec2> positions;

 private:
  RasterImage image_;
  bool record_;
  mutable std::mutex mutex_;
};

/// An empty scene seen through the raster camera, with no accelerator: each context's
/// PreparedScene is kept alive with the world.
struct RasterWorld {
  Scene scene;
  RenderContext context(const RenderSettings& s, int w, int h) const {
    return prepared
        .emplace_back(scene, ImageSize{w, h}, std::make_unique<RasterCamera>(),
                      std::make_unique<NullAccelerator>())
        .context(s);
  }
  mutable std::deque<PreparedScene> prepared;
};

}  // namespace tray::test
