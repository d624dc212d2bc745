#include "integrators/path.h"

#include <limits>

#include "integrators/path_estimator.h"

namespace tray {
namespace {

/// The scalar path tracer: each camera sample's path traced to its end, one ray at a time
/// (Veach 1997, ch. 9; the structure of Mitsuba 3's `path` and pbrt-v4's PathIntegrator). The
/// estimator itself is PathEstimator, shared with path-wavefront.
class PathIntegrator final : public Integrator {
 public:
  explicit PathIntegrator(const RenderContext& ctx) : Integrator(ctx), estimator_(ctx_) {}

  uint32_t accumulate(int x, int y, int begin, int end, PixelSums& sums, PrimaryHit& first,
                      RayStats& stats, IdCoverage* coverage, AovSums* aovSums) const override {
    pixelX_ = x, pixelY_ = y;
    return Integrator::accumulate(x, y, begin, end, sums, first, stats, coverage, aovSums);
  }
  bool splitsLightPaths() const override { return true; }

  Color Li(const Ray& cameraRay, Sampler& sampler, RayStats& stats,
           PrimaryHit* primary) const override {
    return estimator_.tracePath(ctx_.accel, cameraRay, sampler, stats, primary, pixelX_, pixelY_);
  }

 private:
  /// The pixel being rendered on this thread, for --debug-nan reports (Li does not know it).
  static thread_local int pixelX_, pixelY_;
  PathEstimator estimator_;
};

thread_local int PathIntegrator::pixelX_ = -1;
thread_local int PathIntegrator::pixelY_ = -1;

}  // namespace

const std::vector<OptionSpec>& pathOptions() {
  static const std::vector<OptionSpec> specs = {
      intOption("max-depth", 8, 0, 1000,
                "maximum path length in segments (1: emitters seen directly; 2: direct light)"),
      intOption("rr-depth", 5, 0, 1000,
                "Russian roulette after this many path segments (Mitsuba's rr_depth): each "
                "further scattering may end the path (--rr-survival); higher: less noise and "
                "more time per sample"),
      choiceOption("rr-survival", "sqrt", {"sqrt", "throughput"},
                   "Russian roulette's survival probability, of the throughput's largest "
                   "component t: min(0.95, sqrt(t)) (Cycles' rule: more dim paths go on; 1-8% "
                   "more efficient on the benchmark scenes) or min(0.95, t) (Mitsuba's rule)"),
      floatOption("clamp-indirect", 0.0f, 0.0f, std::numeric_limits<float>::infinity(),
                  "clamp each indirect contribution to this value (fireflies; biased; 0 = off)"),
      // Prints only: the pixels are the same with or without it.
      diagnostic(flagOption("debug-nan", "print where NaN/Inf samples arise")),
      choiceOption("light-sampler", "bvh", {"bvh", "power"},
                   "how next-event estimation picks a light: bvh (by its estimated "
                   "contribution at the shading point) or power (in proportion to power)"),
      choiceOption("triangle-sampling", "auto", {"auto", "area", "solid-angle"},
                   "how an emissive triangle is sampled from a shading point: area (uniform "
                   "points), solid-angle (directions in the solid angle it subtends, Arvo "
                   "1995, weighted by the receiver's cosine) or auto (solid angle unless it "
                   "is below 3e-4 or above 6.22 sr); solid-angle and auto sample two "
                   "triangles of a mesh that form a rectangle as one (Urena et al. 2013)"),
  };
  return specs;
}

std::unique_ptr<Integrator> makePath(const RenderContext& ctx) {
  return std::make_unique<PathIntegrator>(declaring(ctx, pathOptions()));
}

}  // namespace tray
