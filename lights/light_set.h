#pragma once
#include <cstdint>
#include <vector>

#include "core/scene.h"
#include "lights/alias_table.h"
#include "lights/environment_light.h"
#include "lights/punctual_light.h"
#include "lights/sphere_light.h"
#include "lights/triangle_light.h"

namespace tray {

/// Every light of a scene, chosen in proportion to power with an alias table:
/// emissive mesh triangles, emissive analytic spheres, KHR_lights_punctual lights, and the
/// constant environment. Built once per render; queries are const and allocation-free.
class LightSet {
 public:
  explicit LightSet(const Scene& scene);
  size_t size() const { return refs_.size(); }
  bool empty() const { return table_.empty(); }

  /// Chooses a light with u1, then a direction to it from ref with u2. The receiver's shading
  /// normal n, and whether it transmits, shape the environment's samples. The returned pdf
  /// includes the choice probability.
  LightSample sample(const Vec3& ref, const Vec3& n, bool transmits, float u1, Vec2 u2) const;

  /// Index of the light that a hit on (primitive, triangle) belongs to, or -1 when that
  /// surface is not in the set (it may still glow: BSDF sampling then gets full weight).
  int lightAt(uint32_t primitive, uint32_t triangle) const {
    if (primitive >= firstLight_.size() || firstLight_[primitive] < 0) return -1;
    return firstLight_[primitive] + (isTriangles_[primitive] ? int(triangle) : 0);
  }
  /// Pdf (choice x solid angle) that sample() would have produced the point p on the finite
  /// light `index`, seen from ref.
  float pdf(int index, const Vec3& ref, const Vec3& p) const;
  /// Pdf (choice x solid angle) that sample() from a point with normal n returns the
  /// environment in direction wi; 0 without an environment.
  float environmentPdf(const Vec3& n, bool transmits, const Vec3& wi) const;
  /// Number of emissive triangles in the set.
  size_t triangleCount() const { return triangles_.size(); }

 private:
  enum class Kind : uint8_t { kTriangle, kSphere, kPunctual, kEnvironment };
  struct Ref {
    Kind kind;
    uint32_t index;
  };
  LightSample sampleLight(const Ref& r, const Vec3& ref, const Vec3& n, bool transmits,
                          Vec2 u2) const;
  std::vector<Ref> refs_;
  std::vector<TriangleLight> triangles_;
  std::vector<SphereLight> spheres_;
  std::vector<PunctualLight> punctual_;
  std::vector<EnvironmentLight> environment_;
  std::vector<int> firstLight_;    ///< per primitive: its first light index, or -1
  std::vector<bool> isTriangles_;  ///< per primitive: lights are per triangle
  int environmentIndex_ = -1;
  AliasTable table_;
};

}  // namespace tray
