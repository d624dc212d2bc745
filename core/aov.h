#pragma once
#include <string>
#include <vector>

#include "core/film.h"
#include "core/integrator.h"

namespace tray {

/// Arbitrary output variables: extra EXR layers beside the beauty, filled from each pixel's
/// first camera hit. Channel names follow compositing conventions (docs/aovs.md):
/// depth -> Z, normal -> N.X/Y/Z, position -> P.X/Y/Z, albedo -> albedo.R/G/B,
/// objectid -> objectid.id, materialid -> materialid.id, samples -> samples.count.
/// crypto_object and crypto_material (both: "cryptomatte") are parsed here and filled by
/// core/cryptomatte.h from all of a pixel's samples.
class AovSet {
 public:
  /// Parses "depth,normal,..." or "all"; "cryptomatte" stands for crypto_object,crypto_material.
  /// Throws tray::Error naming an unknown AOV.
  static std::vector<std::string> parse(const std::string& list);
  static const std::vector<std::string>& known();
  /// Adds the layers for `names` to the film.
  AovSet(Film& film, const std::vector<std::string>& names);
  /// Writes one pixel's AOV values.
  void write(Film& film, int x, int y, const PixelValue& v) const;

 private:
  enum class Kind { kDepth, kNormal, kPosition, kAlbedo, kObjectId, kMaterialId, kSamples };
  struct Slot {
    Kind kind;
    int layer;
  };
  std::vector<Slot> slots_;
};

}  // namespace tray
