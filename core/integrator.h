#pragma once
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/accelerator.h"
#include "core/aov_sums.h"
#include "core/camera.h"
#include "core/filter.h"
#include "core/id_coverage.h"
#include "core/math.h"
#include "core/pixel_sampler.h"
#include "core/pixel_sums.h"
#include "core/render_options.h"
#include "core/sampler.h"
#include "core/scene.h"

namespace tray {

/// Counters gathered per tile and summed for the summary line.
struct RayStats {
  uint64_t cameraRays = 0, shadowRays = 0, secondaryRays = 0;
  /// Samples whose radiance was not finite, discarded (counted): NaN, and infinite (radiance
  /// beyond float's range, e.g. an emitter near float max) among them. countNonFinite adds one.
  uint64_t nanSamples = 0, infiniteSamples = 0;
  void countNonFinite(const Color& L) {
    ++nanSamples;
    infiniteSamples += !std::isnan(L.x) && !std::isnan(L.y) && !std::isnan(L.z);
  }
  /// Path vertices whose light and BSDF samples a SIMD stage made (the wavefront's matte and
  /// glossy stages, integrators/matte_batch.h, glossy_batch.h): benchmarks and tests read it.
  uint64_t simdVertices = 0;
  /// Path vertices that scatter (a surface hit below the depth limit, not unlit), by a SIMD
  /// stage or by the scalar estimator: simdVertices' share of them is the stages' coverage.
  uint64_t shadedVertices = 0;
  uint64_t total() const { return cameraRays + shadowRays + secondaryRays; }
  RayStats& operator+=(const RayStats& o) {
    cameraRays += o.cameraRays;
    shadowRays += o.shadowRays;
    secondaryRays += o.secondaryRays;
    nanSamples += o.nanSamples;
    infiniteSamples += o.infiniteSamples;
    simdVertices += o.simdVertices;
    shadedVertices += o.shadedVertices;
    return *this;
  }
};

/// What the camera ray saw first, for alpha and AOVs. Filled by Li for depth-0 rays.
struct PrimaryHit {
  bool hit = false;
  float depth = 0;  ///< distance along the camera ray
  Vec3 position, normal;
  Color albedo;
  int objectId = -1, materialId = -1;
  uint32_t primitive = kNoPrimitive;  ///< Scene::primitives index (motion vectors)
  uint32_t instance = 0;              ///< its instance (SurfacePoint::instance)
  float time = 0;                     ///< the sample's shutter time (Ray::time)
  /// Light-path AOVs: when not null, Li also adds each contribution to its path's category
  /// there (core/light_paths.h). Set by accumulate for the duration of one sample.
  LightPathRadiance* lightPaths = nullptr;
};

/// The averaged result of one pixel.
struct PixelValue {
  Color radiance;
  float alpha = 0;
  PrimaryHit primary;    ///< of the pixel's first sample
  uint32_t samples = 0;  ///< camera rays traced for this pixel
};

/// One pixel of a batch given to Integrator::accumulatePixels: what accumulate() fills for it.
struct PixelTask {
  int x = 0, y = 0;  ///< image coordinates
  PixelSums sums;
  PrimaryHit first;                ///< what the range's first sample hit
  IdCoverage* coverage = nullptr;  ///< Cryptomatte's ids, when not null
  AovSums* aovSums = nullptr;      ///< the AOVs averaged over all samples, when not null
  uint32_t samples = 0;            ///< camera rays traced
  /// Set by accumulatePixels once all of the pixel's samples are in `sums`; a pixel left
  /// unfinished by a stop is not written (its sums hold only some samples).
  bool finished = false;
};

/// The frame-level hook (docs/frame-integrators.md): what the renderer asks of an integrator
/// that renders whole frames (Integrator::rendersFrames) instead of pixel by pixel. Stochastic
/// progressive photon mapping (integrators/sppm.h) needs it: its iteration k depends on every
/// pixel of iteration k - 1 (one pass's photons land on the visible points of all pixels).
/// The pixels of image rectangle [x0, x0 + width) x [y0, y0 + height): a region render's, or
/// the whole image.
struct FrameTask {
  int x0 = 0, y0 = 0, width = 0, height = 0;
  /// Seconds after which the integrator stops at the end of the iteration (pass) under way,
  /// once at least one is done (--time-limit); 0: none.
  double timeLimit = 0;
  /// When it becomes true (a signal), the integrator stops as soon as it can.
  const std::atomic<bool>* stop = nullptr;
  /// Called from the calling thread with the fraction done, e.g. after each iteration.
  std::function<void(double)> onProgress;
  /// Cryptomatte asked for: fill FramePixel::coverage.
  bool wantsIds = false;
};

/// One pixel of a FrameTask, row-major over its rectangle: filled by renderFrame.
struct FramePixel {
  PixelSums sums;        ///< radiance = rgb / weight, coverage = alpha / weight
  PrimaryHit first;      ///< what the pixel's first camera ray hit (the AOVs)
  IdCoverage coverage;   ///< only with FrameTask::wantsIds: the ids of its camera rays
  uint32_t samples = 0;  ///< camera rays traced for the pixel
};

/// What renderFrame did.
struct FrameResult {
  RayStats rays;
  int iterations = 0;             ///< iterations (passes) done
  bool timeLimitReached = false;  ///< FrameTask::timeLimit ended the render
  bool stopped = false;           ///< FrameTask::stop ended it (the pixels are valid iff
                                  ///< iterations > 0)
};

/// What every integrator sees: the scene, its accelerator, the camera and the settings.
struct RenderContext {
  const Scene& scene;
  const Accelerator& accel;
  const Camera& camera;
  RenderSettings settings;
  int width, height;
};

/// `ctx` with `specs` declared in its settings and its values validated (throws tray::Error
/// naming the option): each integrator factory declares its own options this way, so that it
/// reads them (defaults included) however it was created.
RenderContext declaring(const RenderContext& ctx, const std::vector<OptionSpec>& specs);

/// A light transport algorithm. Ray-based integrators implement Li; renderPixel's default
/// averages the "spp" samples placed by the pixel sampler. Wrapping integrators (adaptive
/// anti-aliasing) override renderPixel and call an inner integrator's Li (and report no
/// samplesPerPixel(): their samples cannot be split into ranges).
class Integrator {
 public:
  /// Resolves the render-wide filter, sampler and pixel-sampler names once, for every pixel.
  explicit Integrator(const RenderContext& ctx);
  virtual ~Integrator() = default;
  /// Radiance arriving along ray (towards its origin). `primary`, when not null, receives the
  /// first surface hit.
  virtual Color Li(const Ray& ray, Sampler& sampler, RayStats& stats,
                   PrimaryHit* primary) const = 0;
  /// Li for a camera ray, as every pixel estimator calls it: with a transparent background
  /// (--transparent, TRAY_environment "transparent") a ray that hits nothing gives 0, so that
  /// the film holds premultiplied RGB beside the coverage alpha. `primary` must not be null.
  Color cameraLi(const Ray& ray, Sampler& sampler, RayStats& stats, PrimaryHit* primary) const;
  /// True when Li fills PrimaryHit::lightPaths (the path tracer): light-path AOVs need it.
  virtual bool splitsLightPaths() const { return false; }
  /// One pixel's value. `coverage`, when not null (Cryptomatte), receives every camera sample's
  /// object and material ids with the weight the sample has in the pixel.
  virtual PixelValue renderPixel(int x, int y, RayStats& stats,
                                 IdCoverage* coverage = nullptr) const;
  /// Samples per pixel of renderPixel's estimator (the pixel sampler's count); none when the
  /// integrator places its own samples (adaptive) and accumulate() does not apply.
  virtual std::optional<int> samplesPerPixel() const;
  /// Adds samples [begin, end) of pixel (x, y) to `sums`, each from its own counter-based
  /// Sampler(pixel, sample, seed): sums over consecutive ranges add up to renderPixel's. Fills
  /// `first` with what sample `begin` hit, `coverage` (when not null) as renderPixel does, and
  /// `aovSums` (when not null) with what it asks for of every sample; returns the camera rays
  /// traced.
  virtual uint32_t accumulate(int x, int y, int begin, int end, PixelSums& sums, PrimaryHit& first,
                              RayStats& stats, IdCoverage* coverage = nullptr,
                              AovSums* aovSums = nullptr) const;
  /// Pixels the renderer gives accumulatePixels at once: 1 (the default) for integrators that
  /// trace one sample at a time; a wavefront integrator asks for a tile's worth.
  virtual int pixelBatch() const { return 1; }
  /// accumulate() over samples [begin, end) of every task's pixel, setting each task's
  /// `finished`. The default calls it pixel by pixel; a wavefront integrator overrides it to
  /// trace the batch's samples together, with the same sums per pixel (each sample drawing the
  /// same numbers). Once `*stop` (when not null) is true it returns early: between pixels, or
  /// (wavefront) between waves, so that a signal ends a render whose batch holds hours of
  /// samples within milliseconds.
  virtual void accumulatePixels(std::span<PixelTask> tasks, int begin, int end, RayStats& stats,
                                const std::atomic<bool>* stop = nullptr) const;
  /// True for an integrator that renders whole frames (renderFrame) rather than pixels: the
  /// renderer then calls renderFrame once, instead of accumulate / renderPixel per pixel.
  virtual bool rendersFrames() const { return false; }
  /// Fills `pixels` (task.width x task.height, row-major, zeroed on entry) for the task's
  /// rectangle. Called once per render, inside the renderer's task arena (--threads): it may
  /// use TBB freely. It must give the same pixels, bit for bit, for any thread count, and a
  /// rectangle's pixels must equal the same pixels of the whole image's render. The default
  /// throws (integrators that render pixels).
  virtual FrameResult renderFrame(const FrameTask& task, std::span<FramePixel> pixels) const;
  const RenderContext& context() const { return ctx_; }

 protected:
  /// The pieces of accumulate(), for integrators that place samples the same way but trace
  /// them otherwise. The counter-based sampler of sample i of pixel (x, y):
  Sampler sampler(int x, int y, int i) const;
  /// The camera ray of sample i of pixel (x, y), drawn from its sampler as accumulate does;
  /// `offset` receives the sample's position relative to the pixel centre.
  Ray cameraRay(int x, int y, int i, Sampler& sampler, Vec2& offset) const;
  /// Motion blur: gives a camera ray its shutter time, from a dimension of the sample's own
  /// (Sampler::kShutterDimension) so that no other number changes; nothing when nothing moves.
  /// A moving camera then moves the ray (made at the frame's pose) to where it is at that time.
  void setShutterTime(Ray& ray, const Sampler& sampler) const {
    if (!moving_) return;
    ray.time = sampler.reserved1D(Sampler::kShutterDimension);
    if (!cameraMotion_.empty()) moveWithCamera(ray);
  }
  /// --transparent: camera rays that escape give 0 (cameraLi's rule), for integrators that
  /// make their own pixel values (frame-level ones).
  bool transparentBackground() const { return transparent_; }
  /// Samples in the pixel sampler's pattern (accumulate's upper bound for `end`).
  int sampleCount() const { return pixelSampler_.count(); }
  /// What sampler() and cameraRay() draw from, for batch kernels that repeat them
  /// (integrators/camera_batch.h): the pixel sampler, seed, sequence, and whether rays draw a time.
  const PixelSampler& pixelSampler() const { return pixelSampler_; }
  uint64_t seed() const { return seed_; }
  Sampler::Sequence sequence() const { return sequence_; }
  bool moving() const { return moving_; }
  /// Adds one sample, Li's radiance `L`, what it hit first and (when not null) its light-path
  /// split, to a pixel's sums, ids and averaged AOVs as accumulate does: the
  /// transparent-background rule of cameraLi, NaN samples counted and dropped (their split
  /// too), the filter weight at `offset`.
  void addSample(PixelSums& sums, IdCoverage* coverage, AovSums* aovSums, const Vec2& offset,
                 Color L, const PrimaryHit& seen, const LightPathRadiance* paths,
                 RayStats& stats) const;

  RenderContext ctx_;

 private:
  Filter filter_;
  Sampler::Sequence sequence_;
  PixelSampler pixelSampler_;
  uint64_t seed_;
  bool transparent_;                ///< escaped camera rays give 0 (cameraLi)
  bool moving_;                     ///< something moves over the shutter: camera rays draw a time
  std::vector<Mat4> cameraMotion_;  ///< the camera's motion steps (CameraDesc::motion)
  Mat4 cameraFrameInverse_;         ///< world to camera at the frame's pose
  void moveWithCamera(Ray& ray) const;
};

}  // namespace tray
