#include "integrators/adaptive.h"

#include <tbb/concurrent_hash_map.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "integrators/lattice_cache.h"
#include "integrators/registry.h"

namespace tray {
namespace {

/// What one lattice point saw; copied out of the cache.
struct LatticeSample {
  Color L;
  PrimaryHit primary;
};

// Robust mode (docs/anti-aliasing.md, "Thin features"): tiles of kTile x kTile pixels where any
// two neighbouring pixel corners see different objects get kRobustMinDepth levels of
// subdivision everywhere in them and in the 8 tiles around.
constexpr int kTile = 8;
constexpr int kRobustMinDepth = 2;
// Keeps near-black noise from counting as contrast: differences among values far below this
// (in scene-linear units, where a lit diffuse surface is ~0.1 to 1) are invisible.
constexpr float kContrastFloor = 0.01f;

class Adaptive final : public Integrator {
 public:
  Adaptive(const RenderContext& ctx, std::unique_ptr<Integrator> inner)
      : Integrator(ctx),
        inner_(std::move(inner)),
        threshold_(ctx.settings.getFloat("aa-threshold")),
        robust_(ctx.settings.getBool("aa-robust")),
        seed_(uint64_t(ctx.settings.getInt64("seed"))) {
    depth_ = std::clamp(ctx.settings.getInt("aa-depth"), 0, 12);
    scale_ = 1u << depth_;
    cache_ = std::make_unique<LatticeCache<LatticeSample>>(ctx.width, ctx.height, scale_);
    tilesX_ = (ctx.width + kTile - 1) / kTile;
    tilesY_ = (ctx.height + kTile - 1) / kTile;
  }

  Color Li(const Ray& ray, Sampler& sampler, RayStats& stats, PrimaryHit* primary) const override {
    return inner_->Li(ray, sampler, stats, primary);
  }

  /// Adaptive places its own samples: they cannot be split into sample ranges.
  std::optional<int> samplesPerPixel() const override { return std::nullopt; }

  PixelValue renderPixel(int x, int y, RayStats& stats, IdCoverage* coverage) const override {
    Accum acc;
    acc.coverage = coverage;
    int minLevel = 0;
    if (robust_ && nearObjectBoundary(x / kTile, y / kTile, stats))
      minLevel = std::min(kRobustMinDepth, depth_);
    square(uint32_t(x) * scale_, uint32_t(y) * scale_, scale_, 0, minLevel, acc, stats);
    std::sort(acc.keys.begin(), acc.keys.end());
    PixelValue out;
    out.samples = uint32_t(std::unique(acc.keys.begin(), acc.keys.end()) - acc.keys.begin());
    // Leaf areas are in lattice units; a pixel is scale^2 of them.
    const double area = double(scale_) * scale_;
    out.radiance =
        Color(float(acc.sum[0] / area), float(acc.sum[1] / area), float(acc.sum[2] / area));
    out.alpha = float(acc.alpha / area);
    out.primary = sample(uint32_t(x) * scale_, uint32_t(y) * scale_, stats).primary;
    cache_->pixelDone(y);
    return out;
  }

  size_t traced() const { return size_t(cache_->traced()); }
  size_t peakKept() const { return size_t(cache_->peakKept()); }

 private:
  struct Accum {
    double sum[3] = {0, 0, 0}, alpha = 0;
    std::vector<uint64_t> keys;
    IdCoverage* coverage = nullptr;  ///< Cryptomatte: each leaf corner's ids, weighted as above
  };

  /// The square with top-left lattice corner (i, j) and side `size` (lattice units), at
  /// subdivision `level`. A leaf contributes the mean of its corners times its area: the
  /// integral of their bilinear interpolant (Whitted's corner averaging).
  void square(uint32_t i, uint32_t j, uint32_t size, int level, int minLevel, Accum& acc,
              RayStats& stats) const {
    const uint32_t ci[4] = {i, i + size, i, i + size}, cj[4] = {j, j, j + size, j + size};
    LatticeSample s[4];
    Color c[4];
    for (int k = 0; k < 4; ++k) {
      s[k] = sample(ci[k], cj[k], stats);
      c[k] = s[k].L;
      acc.keys.push_back(key(ci[k], cj[k]));
    }
    bool split = level < minLevel || adaptiveContrast(c, 4) > threshold_;
    if (robust_)
      for (int k = 1; k < 4; ++k) split |= s[k].primary.objectId != s[0].primary.objectId;
    if (split && level < depth_) {
      const uint32_t h = size / 2;
      square(i, j, h, level + 1, minLevel, acc, stats);
      square(i + h, j, h, level + 1, minLevel, acc, stats);
      square(i, j + h, h, level + 1, minLevel, acc, stats);
      square(i + h, j + h, h, level + 1, minLevel, acc, stats);
      return;
    }
    const double a = double(size) * size / 4;
    for (int k = 0; k < 4; ++k) {
      acc.sum[0] += a * c[k].x, acc.sum[1] += a * c[k].y, acc.sum[2] += a * c[k].z;
      acc.alpha += s[k].primary.hit ? a : 0.0;
      if (acc.coverage) {
        const PrimaryHit& h = s[k].primary;
        acc.coverage->add(h.hit ? h.objectId : -1, h.hit ? h.materialId : -1, a);
      }
    }
  }

  /// A leaf's corner as Accum counts it (distinct keys: the pixel's sample count).
  uint64_t key(uint32_t i, uint32_t j) const { return cache_->key(i, j); }

  /// Lattice point (i, j), traced on first use (integrators/lattice_cache.h).
  LatticeSample sample(uint32_t i, uint32_t j, RayStats& stats) const {
    return cache_->get(i, j, [&] { return trace(i, j, stats); });
  }

  /// The ray through lattice point (i, j), seeded by its coordinate alone (determinism).
  LatticeSample trace(uint32_t i, uint32_t j, RayStats& stats) const {
    Sampler sampler(i, j, seed_);
    Vec2 u = sampler.next2D();
    float x = float(i), y = float(j);
    if (robust_) {
      // Jitter within the point's own cell: the spacing of the coarsest level it belongs to,
      // so that corner samples cover the plane instead of a regular grid (Cook 1986).
      const int trailing =
          std::min({i ? std::countr_zero(i) : 31, j ? std::countr_zero(j) : 31, depth_});
      const float spacing = float(1u << trailing);
      x += (u.x - 0.5f) * spacing, y += (u.y - 0.5f) * spacing;
    }
    const float rx = x / float(scale_), ry = y / float(scale_);
    Ray ray = ctx_.camera.hasLens() ? ctx_.camera.generateLensRay(rx, ry, sampler.next2D())
                                    : ctx_.camera.generateRay(rx, ry);
    setShutterTime(ray, sampler);  // motion blur
    ++stats.cameraRays;
    LatticeSample s;
    s.L = cameraLi(ray, sampler, stats, &s.primary);  // Li is the inner integrator's
    if (!isFinite(s.L)) {
      stats.countNonFinite(s.L);
      s.L = Color(0.0f);
    }
    return s;
  }

  /// Whether tile (tx, ty) or one of its 8 neighbours contains two adjacent pixel corners that
  /// see different objects. The neighbourhood catches thin features its own corners missed.
  bool nearObjectBoundary(int tx, int ty, RayStats& stats) const {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = tx + dx, y = ty + dy;
        if (x >= 0 && y >= 0 && x < tilesX_ && y < tilesY_ && tileHasBoundary(x, y, stats))
          return true;
      }
    return false;
  }

  bool tileHasBoundary(int tx, int ty, RayStats& stats) const {
    {
      TileCache::const_accessor found;
      if (tiles_.find(found, uint64_t(ty) * tilesX_ + tx)) return found->second;
    }
    TileCache::accessor acc;
    if (!tiles_.insert(acc, uint64_t(ty) * tilesX_ + tx)) return acc->second;
    const int x0 = tx * kTile, y0 = ty * kTile;
    const int x1 = std::min(x0 + kTile, ctx_.width), y1 = std::min(y0 + kTile, ctx_.height);
    bool boundary = false;
    for (int y = y0; y <= y1 && !boundary; ++y)
      for (int x = x0; x <= x1 && !boundary; ++x) {
        const int id = sample(uint32_t(x) * scale_, uint32_t(y) * scale_, stats).primary.objectId;
        if (x < x1)
          boundary |=
              id != sample(uint32_t(x + 1) * scale_, uint32_t(y) * scale_, stats).primary.objectId;
        if (y < y1)
          boundary |=
              id != sample(uint32_t(x) * scale_, uint32_t(y + 1) * scale_, stats).primary.objectId;
      }
    acc->second = boundary;
    return boundary;
  }

  using TileCache = tbb::concurrent_hash_map<uint64_t, bool>;
  std::unique_ptr<Integrator> inner_;
  float threshold_;  ///< --aa-threshold
  bool robust_;      ///< --aa-robust
  uint64_t seed_;
  int depth_;
  uint32_t scale_;
  int tilesX_, tilesY_;
  std::unique_ptr<LatticeCache<LatticeSample>> cache_;
  mutable TileCache tiles_;
};

}  // namespace

float adaptiveContrast(const Color* colors, int count) {
  float contrast = 0;
  for (int ch = 0; ch < 3; ++ch) {
    float lo = kInfinity, hi = 0;
    for (int k = 0; k < count; ++k) {
      const float c = std::max(0.0f, colors[k][ch]);
      lo = std::min(lo, c), hi = std::max(hi, c);
    }
    contrast = std::max(contrast, (hi - lo) / (hi + lo + kContrastFloor));
  }
  return contrast;
}

const std::vector<OptionSpec>& adaptiveOptions() {
  static const std::vector<OptionSpec> specs = {
      // No choices here: the registry checks the name (integrators/registry.cpp).
      choiceOption("inner", "whitted", {}, "the integrator it wraps"),
      // 0.03 reaches the 4x4 grid's RMSE with 32% of its rays (bench/aa_bench).
      floatOption("aa-threshold", 0.03f, 0.0f, 1.0f,
                  "corner contrast (max-min)/(max+min) above which a square subdivides"),
      intOption("aa-depth", 4, 0, 12, "maximum subdivision depth"),
      flagOption("aa-robust",
                 "jittered corners + minimum subdivision near object boundaries (thin "
                 "features)"),
  };
  return specs;
}

std::unique_ptr<Integrator> makeAdaptiveAround(const RenderContext& ctx,
                                               std::unique_ptr<Integrator> inner) {
  return std::make_unique<Adaptive>(declaring(ctx, adaptiveOptions()), std::move(inner));
}

std::unique_ptr<Integrator> makeAdaptive(const RenderContext& ctx) {
  const std::string inner = declaring(ctx, adaptiveOptions()).settings.getString("inner");
  if (inner == "adaptive") throw Error("--inner adaptive: adaptive cannot wrap itself");
  return makeAdaptiveAround(ctx, makeIntegrator(ctx, inner));
}

size_t adaptiveTracedPoints(const Integrator& integrator) {
  auto* a = dynamic_cast<const Adaptive*>(&integrator);
  return a ? a->traced() : 0;
}

size_t adaptivePeakKeptPoints(const Integrator& integrator) {
  auto* a = dynamic_cast<const Adaptive*>(&integrator);
  return a ? a->peakKept() : 0;
}

Film samplesHeatmap(const Film& film) {
  const int layer = film.findLayer("samples");
  if (layer < 0) throw Error("the ray heatmap needs the samples AOV layer");
  float maxCount = 1;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x)
      maxCount = std::max(maxCount, film.pixel(layer, x, y)[0]);
  // Display-referred ramp stops (sRGB), converted to linear so image output shows them as is.
  static const Color stops[] = {{0.05f, 0.03f, 0.35f},
                                {0.1f, 0.45f, 0.85f},
                                {0.2f, 0.8f, 0.3f},
                                {0.98f, 0.85f, 0.1f},
                                {1, 1, 1}};
  constexpr int kStops = 5;
  Film out(film.width(), film.height());
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) {
      const float n = std::max(1.0f, film.pixel(layer, x, y)[0]);
      const float t = maxCount > 1 ? std::log(n) / std::log(maxCount) : 0.0f;
      const float f = t * (kStops - 1);
      const int k = std::min(int(f), kStops - 2);
      const Color c = stops[k] * (1 - (f - k)) + stops[k + 1] * (f - k);
      float* p = out.pixel(Film::kBeauty, x, y);
      for (int ch = 0; ch < 3; ++ch) p[ch] = std::pow(c[ch], 2.2f);
      p[3] = 1;
    }
  return out;
}

}  // namespace tray
