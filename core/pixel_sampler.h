#pragma once
// Where a pixel's camera rays go: the pixel sampling strategies of docs/anti-aliasing.md.
#include <string>
#include <vector>

#include "core/math.h"

namespace tray {

/// Places a pixel's samples over its filter's support [-radius, radius]^2 around the pixel
/// centre, so every pixel is computed from its own rays (tiles stay independent).
class PixelSampler {
 public:
  enum class Pattern {
    kCenter,   ///< one ray through the centre (the seed's ray casting)
    kCorners,  ///< four rays through the pixel corners (the seed's supersampling)
    kGrid,     ///< n x n stratum centres, n = floor(sqrt(spp))
    kJitter,   ///< one uniform sample per stratum of an n x n grid; the spp - n^2 rest uniform
  };
  /// Names accepted by --pixel-sampler; "auto" is center at 1 spp, jitter above.
  static const std::vector<std::string>& names();
  /// Resolves a name (throws tray::Error naming the choices for an unknown one).
  static Pattern parse(const std::string& name, int spp);

  PixelSampler(Pattern pattern, int spp, float radius);
  Pattern pattern() const { return pattern_; }
  /// Camera rays per pixel.
  int count() const { return count_; }
  /// Offset from the pixel centre of sample i < count(); `u` is uniform in [0,1)^2 and is only
  /// used by jitter.
  Vec2 offset(int i, const Vec2& u) const;

 private:
  Pattern pattern_;
  int count_, strata_;
  float radius_;
};

}  // namespace tray
