#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "core/light.h"
#include "core/scene.h"
#include "lights/area_light.h"
#include "lights/bvh_light_sampler.h"
#include "lights/environment_light.h"
#include "lights/image_environment_light.h"
#include "lights/light_sampler.h"
#include "lights/punctual_light.h"

namespace tray {

/// Every light of a scene behind the Light interface, chosen by a LightSampler (by estimated
/// contribution at the receiver through a light BVH, or in proportion to power; `kind`):
/// emissive mesh triangles and samplable emissive analytic shapes (AreaLight, in primitive
/// order; triangles sampled as `sampling` says), KHR_lights_punctual lights, and the
/// environment (a constant or an image). Built
/// once per render; queries are const and allocation-free. Refers to the scene's shapes and
/// transforms: the scene must outlive it, unchanged.
class LightSet {
 public:
  explicit LightSet(const Scene& scene, LightSamplerKind kind = LightSamplerKind::kBvh,
                    TriangleSampling sampling = TriangleSampling::kAuto);
  LightSet(const LightSet&) = delete;  // lights_ points into the vectors below
  LightSet& operator=(const LightSet&) = delete;

  size_t size() const { return lights_.size(); }
  bool empty() const { return !anyPower_; }
  const Light& light(size_t i) const { return *lights_[i]; }

  /// Chooses a light with u1, then a direction to it from ctx with u2. The returned pdf
  /// includes the choice probability. Inline, into the integrators (callgrind, Cornell box:
  /// ~23 instructions per vertex fewer than a call, which copied the sample out).
  LightSample sample(const LightSampleContext& ctx, float u1, Vec2 u2) const;
  /// sample(), also giving choose()'s escapePmf.
  LightSample sample(const LightSampleContext& ctx, float u1, Vec2 u2, float& escapePmf) const;
  /// sample()'s choice alone: the light it samples with u1 from ctx and the probability of
  /// that choice (none when the index is negative or pmf is not positive).
  int choose(const LightSampleContext& ctx, float u1, float& pmf) const {
    return bvh_ ? bvh_->sample(ctx, u1, pmf) : chooser_->sample(ctx, u1, pmf);
  }
  /// choose(), also giving in escapePmf pmf(ctx, escapeLight()) bit for bit when the choice
  /// computed it on the way (the light BVH's top level), or -1.
  int choose(const LightSampleContext& ctx, float u1, float& pmf, float& escapePmf) const {
    if (bvh_ && escapeLight_ >= 0) return bvh_->sample(ctx, u1, pmf, &escapePmf);
    escapePmf = -1.0f;
    return choose(ctx, u1, pmf);
  }
  /// The light whose pmf choose() can give on the way: the scene's only infinite light when
  /// the light BVH chooses and has no other infinite light (a sun) beside it; -1 otherwise.
  /// An escaping ray's MIS weight needs that pmf at the vertex it left (PathEstimator::escape).
  int escapeLight() const { return escapeLight_; }
  /// sample() past its choice: light i chosen with probability pmf by choose(ctx, u1, pmf),
  /// for a caller that made the choice already.
  LightSample sampleChosen(int i, float pmf, const LightSampleContext& ctx, Vec2 u2) const;
  /// Light i as an area light, or null when it is another kind.
  const AreaLight* areaLight(size_t i) const { return i < area_.size() ? &area_[i] : nullptr; }
  /// Light i as a punctual light, or null when it is another kind (they follow the area lights).
  const PunctualLight* punctualLight(size_t i) const {
    return i >= area_.size() && i - area_.size() < punctual_.size() ? &punctual_[i - area_.size()]
                                                                    : nullptr;
  }

  /// Index of the light that a hit on (primitive, triangle) belongs to, or -1 when that
  /// surface is not in the set (it may still glow: BSDF sampling then gets full weight).
  int lightAt(uint32_t primitive, uint32_t triangle) const {
    if (primitive >= firstLight_.size() || firstLight_[primitive] < 0) return -1;
    const int i = firstLight_[primitive] + (isTriangles_[primitive] ? int(triangle) : 0);
    return merged_.empty() ? i : merged_[size_t(i)];
  }
  /// Pdf (choice x solid angle) that sample() from ctx returns direction wi towards light
  /// `index`, meeting it at p with geometric normal n (finite lights; see Light::pdf).
  float pdf(int index, const LightSampleContext& ctx, const Vec3& wi, const Vec3& p,
            const Vec3& n) const {
    if (index < 0 || size_t(index) >= lights_.size()) return 0.0f;
    return pdfChosen(index, this->pmf(ctx, index), ctx, wi, p, n);
  }
  /// pdf() for a valid index whose choice probability pmf(ctx, index) the caller knows.
  float pdfChosen(int index, float pmf, const LightSampleContext& ctx, const Vec3& wi,
                  const Vec3& p, const Vec3& n) const {
    if (!(pmf > 0)) return 0.0f;
    const size_t i = size_t(index);
    // The constant environment through its final class, inline (the escapes of a scene under
    // the sky call this per path: callgrind, heavy spheres).
    return pmf * (i < area_.size()                ? area_[i].pdf(ctx, wi, p, n)
                  : index == constantEnvironment_ ? environment_[0].pdf(ctx, wi, p, n)
                                                  : pdfOther(index, ctx, wi, p, n));
  }
  /// Light i's radiance toward an escaping ray's direction (Light::Le), the constant
  /// environment's inline.
  Color Le(int i, const Vec3& dir) const {
    return i == constantEnvironment_ ? environment_[0].Le(dir) : lights_[size_t(i)]->Le(dir);
  }
  /// The probability that sample() from ctx chooses light `index`.
  float pmf(const LightSampleContext& ctx, int index) const {
    return bvh_ ? bvh_->pmf(ctx, index) : chooser_->pmf(ctx, index);
  }
  /// Indices of the lights that rays escaping the scene see (Light::Le): the environment.
  const std::vector<int>& infinite() const { return infinite_; }
  /// Indices of the delta lights (point, spot, directional), in the scene's order.
  const std::vector<int>& delta() const { return delta_; }
  /// Index of the constant environment (TRAY_environment's background), or -1.
  int constantEnvironment() const { return constantEnvironment_; }
  /// The sphere bounding the scene's finite primitives (radius 1 when there are none):
  /// infinite lights emit from its disk (Light::sampleLe).
  const WorldSphere& world() const { return world_; }
  /// Number of emissive triangles in the set.
  size_t triangleCount() const { return triangleCount_; }
  /// Number of rectangles among them (pairs of triangles sampled as one, lights/quad_lights.h;
  /// none with --triangle-sampling area).
  size_t rectangleCount() const { return rectangleCount_; }
  /// How its emissive triangles are sampled (--triangle-sampling).
  TriangleSampling triangleSampling() const { return triangleSampling_; }

 private:
  /// Light i's sample when it is not an area light (out of line: LightSet::sample stays
  /// small enough to be inlined).
  LightSample sampleOther(int i, const LightSampleContext& ctx, Vec2 u) const;
  /// Light i's pdf when it is not an area light (out of line, as sampleOther).
  float pdfOther(int i, const LightSampleContext& ctx, const Vec3& wi, const Vec3& p,
                 const Vec3& n) const;
  void addPrimitive(const Scene& scene, size_t i, std::vector<float>& power);
  std::vector<AreaLight> area_;
  std::vector<PunctualLight> punctual_;
  std::vector<EnvironmentLight> environment_;
  std::vector<ImageEnvironmentLight> imageEnvironment_;  ///< TRAY_environment image, --env
  std::vector<const Light*> lights_;                     ///< in alias-table order
  std::vector<int> firstLight_;    ///< per primitive: its first light index, or -1
  std::vector<bool> isTriangles_;  ///< per primitive: lights are per triangle
  std::vector<int> infinite_, delta_;
  int constantEnvironment_ = -1;  ///< environment_[0]'s index (sampled inline), or -1
  int escapeLight_ = -1;          ///< see escapeLight()
  WorldSphere world_;
  size_t triangleCount_ = 0, rectangleCount_ = 0;
  /// Per area light: the light that hits on it belong to (a rectangle's second triangle: its
  /// first's); empty (the identity) while there is no rectangle.
  std::vector<int> merged_;
  bool anyRectangle_ = false;
  TriangleSampling triangleSampling_ = TriangleSampling::kAuto;
  bool anyPower_ = false;
  std::unique_ptr<LightSampler> chooser_;
  /// chooser_ when it is the BVH (the default): called through its final class, inline.
  const BvhLightSampler* bvh_ = nullptr;
};

inline LightSample LightSet::sample(const LightSampleContext& ctx, float u1, Vec2 u2) const {
  float pmf;
  // The BVH chooser and area lights through their final classes: inline, no virtual calls
  // (callgrind, Cornell box: LightSet::sample ~248 -> ~188 instructions per vertex).
  const int i = choose(ctx, u1, pmf);
  return sampleChosen(i, pmf, ctx, u2);
}

inline LightSample LightSet::sample(const LightSampleContext& ctx, float u1, Vec2 u2,
                                    float& escapePmf) const {
  float pmf;
  const int i = choose(ctx, u1, pmf, escapePmf);
  return sampleChosen(i, pmf, ctx, u2);
}

inline LightSample LightSet::sampleChosen(int i, float pmf, const LightSampleContext& ctx,
                                          Vec2 u2) const {
  const bool chosen = i >= 0 && pmf > 0;
  // One named result built in place (no `return {}` beside it, which stops the compiler's
  // NRVO): copying the light's sample out of a temporary after writing its pdf cost a
  // store-forwarding stall per sample (see setSpawnRay in core/ray.h).
  LightSample s = !chosen                    ? LightSample{}
                  : size_t(i) < area_.size() ? area_[size_t(i)].sample(ctx, u2)
                                             : sampleOther(i, ctx, u2);
  if (chosen) s.pdf *= pmf;
  return s;
}

}  // namespace tray
