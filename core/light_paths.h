#pragma once
// Light-path AOVs: a camera sample's radiance split by the kind of path that carried it, so that
// a compositor can re-balance diffuse, specular and transmitted light (docs/aovs.md,
// "Light-path layers"). The categories follow Arnold's AOVs and Cycles' passes: a path is
// classified by its FIRST scattering (the lobe that scattered at the surface the camera sees);
// light arriving at that surface is "direct", light that scattered again before is "indirect".
#include <array>
#include <string>
#include <vector>

#include "core/math.h"

namespace tray {

enum class LightPath {
  kDiffuseDirect,
  kDiffuseIndirect,
  kSpecularDirect,
  kSpecularIndirect,
  kTransmission,  ///< direct and indirect together
  kEmission,      ///< emitters (and unlit surfaces) seen before any scattering
  kBackground,    ///< the environment seen before any scattering
  kCount
};
inline constexpr int kLightPathCount = int(LightPath::kCount);

/// Layer (and --aov) name of a category: Arnold's AOV names (diffuse_direct, …, background).
const char* lightPathName(LightPath p);
/// All category names, in enum order.
const std::vector<std::string>& lightPathNames();

/// A BSDF value split by lobe kind (Bsdf::evalLobes): diffuse (Lambert, sheen), specular
/// (every reflecting microfacet or mirror lobe: metal, the plastic's and the clear coat's
/// reflection, a dielectric's reflection), transmission (a dielectric's refraction).
struct LobeSplit {
  Color diffuse{0.0f}, specular{0.0f}, transmission{0.0f};
};

/// One camera sample's radiance by category; the categories sum to the sample's radiance up to
/// float rounding (each contribution is split into shares that sum to 1).
struct LightPathRadiance {
  std::array<Color, kLightPathCount> radiance{};
  void clear() { radiance.fill(Color(0.0f)); }
};

/// Follows one path for the integrator and adds each of its contributions to the category it
/// belongs to. Inactive (a null target) it does nothing, so that renders without light-path
/// AOVs pay one predictable branch per contribution.
class LightPathSplitter {
 public:
  explicit LightPathSplitter(LightPathRadiance* out) : out_(out) {}
  bool active() const { return out_ != nullptr; }
  /// True while the path has not scattered yet: a light sample here needs its lobe split.
  bool atFirstVertex() const { return scatterings_ == 0; }
  /// Emission, an unlit surface or the environment reached by the ray being traced.
  void addFound(const Color& c, bool environment);
  /// A light sample (next-event estimation) drawn at the first vertex (`atFirstVertex`, as
  /// atFirstVertex() said when it was drawn; `toLight` is then the BSDF's split toward the
  /// light) or at a later one. Given, not read, since a wavefront adds the sample once its
  /// shadow ray is traced, after the path has scattered on (docs/wavefront.md).
  void addLightSample(const Color& c, const LobeSplit& toLight, bool atFirstVertex);
  /// The path scattered into a new direction: at the first scattering, `lobes` (the BSDF's
  /// split in that direction) fixes the shares of everything the path gathers later.
  void scattered(const LobeSplit& lobes);
  /// The split of a delta lobe's sample: all transmission or all specular.
  static LobeSplit deltaLobe(bool transmission);

 private:
  /// Adds c to the diffuse, specular and transmission categories in the given shares.
  void addShared(const Color& c, const Color share[3], bool direct);
  LightPathRadiance* out_;
  int scatterings_ = 0;
  Color share_[3] = {Color(0.0f), Color(0.0f), Color(0.0f)};  ///< of the first scattering
};

}  // namespace tray
