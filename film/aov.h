#pragma once
#include <string>
#include <vector>

#include "core/aov_sums.h"
#include "core/integrator.h"
#include "core/motion_vectors.h"
#include "film/film.h"

namespace tray {

/// Arbitrary output variables: extra EXR layers beside the beauty. Channel names follow
/// compositing conventions (docs/aovs.md): depth -> Z, normal -> N.X/Y/Z, position -> P.X/Y/Z,
/// albedo -> albedo.R/G/B, objectid -> objectid.id, materialid -> materialid.id,
/// samples -> samples.count, motion -> motion.u/v (core/motion_vectors.h); the light-path
/// layers (core/light_paths.h; "lightpaths": all seven) -> diffuse_direct.R/G/B, …,
/// background.R/G/B. Albedo, normal, depth and the light paths are
/// averaged over every sample with the pixel filter (AovSums) when the integrator places its
/// samples through accumulate(); position and the ids are of the first camera hit.
/// crypto_object and crypto_material (both: "cryptomatte") are parsed here and filled by
/// film/cryptomatte.h from all of a pixel's samples.
class AovSet {
 public:
  /// Parses "depth,normal,..." or "all" (every layer but the light paths, which only the path
  /// tracer fills); "cryptomatte" stands for crypto_object,crypto_material, "lightpaths" for
  /// the seven light-path layers. Throws tray::Error naming an unknown AOV.
  static std::vector<std::string> parse(const std::string& list);
  /// parse() for a render whose integrator can (`lightPaths`) or cannot fill the light-path
  /// layers: "all" then means every layer the render makes, the light paths included.
  static std::vector<std::string> parse(const std::string& list, bool lightPaths);
  static const std::vector<std::string>& known();
  /// Adds the layers for `names` to the film. `vectors` fills the motion layer (null: zeros).
  AovSet(Film& film, const std::vector<std::string>& names, const MotionVectors* vectors = nullptr);
  /// True when `names` asks for light-path layers.
  static bool wantsLightPaths(const std::vector<std::string>& names);
  /// What accumulate() must gather for these layers (clears the sums' flags otherwise).
  void configure(AovSums& sums) const;
  /// True when some layer is averaged over all samples (configure sets a flag).
  bool averaged() const { return lightPaths_ || surface_; }
  /// Writes one pixel's AOV values; `sums` (over all samples; null when the integrator placed
  /// its own samples) gives the averaged layers, else they are of the first sample.
  void write(Film& film, int x, int y, const PixelValue& v, const AovSums* sums = nullptr) const;

 private:
  enum class Kind {
    kDepth,
    kNormal,
    kPosition,
    kAlbedo,
    kObjectId,
    kMaterialId,
    kSamples,
    kMotion,
    kPath
  };
  struct Slot {
    Kind kind;
    int layer;
    int path = 0;  ///< kPath: the LightPath category
  };
  std::vector<Slot> slots_;
  const MotionVectors* vectors_;
  bool lightPaths_ = false, surface_ = false;
};

}  // namespace tray
