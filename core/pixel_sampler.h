#pragma once
// Where a pixel's camera rays go: the pixel sampling strategies of docs/anti-aliasing.md.
#include <string>
#include <vector>

#include "core/math.h"
#include "core/options.h"

namespace tray {

/// Places a pixel's samples over its filter's support [-radius, radius]^2 around the pixel
/// centre, so every pixel is computed from its own rays (tiles stay independent).
class PixelSampler {
 public:
  enum class Pattern {
    kCenter,    ///< one ray through the centre (the seed's ray casting)
    kCorners,   ///< four rays through the pixel corners (the seed's supersampling)
    kGrid,      ///< n x n stratum centres, n = floor(sqrt(spp))
    kJitter,    ///< one uniform sample per stratum of an n x n grid; the spp - n^2 rest uniform
    kSequence,  ///< the random sequence's own 2D points (stratified when it is Sobol')
  };
  /// Names accepted by --pixel-sampler; "auto" is center at 1 spp, above it "sequence" when
  /// the sequence stratifies and spp is a power of two (its points are then a (0, m, 2)-net,
  /// which is stratified on every grid of spp cells), jitter otherwise; "sequence" at any
  /// count in a render in passes (see parse).
  static const std::vector<std::string>& names();
  /// --pixel-sampler: declared here, beside the patterns it names.
  static const OptionSpec& option();
  /// Resolves a name (throws tray::Error naming the choices for an unknown one).
  /// `anyPrefix`: a pixel may stop after any number of its samples (renders in passes:
  /// --noise-threshold, --time-limit), so every prefix of its samples must cover it: "auto"
  /// is then "sequence", and grid, jitter and corners (sample i in stratum i) are refused.
  static Pattern parse(const std::string& name, int spp, bool stratifiedSequence = false,
                       bool anyPrefix = false);

  PixelSampler(Pattern pattern, int spp, float radius);
  Pattern pattern() const { return pattern_; }
  /// Camera rays per pixel.
  int count() const { return count_; }
  /// Strata per side of grid and jitter (n), and the filter support's radius.
  int strata() const { return strata_; }
  float radius() const { return radius_; }
  /// Offset from the pixel centre of sample i < count(); `u` is uniform in [0,1)^2 and is only
  /// used by jitter and sequence.
  Vec2 offset(int i, const Vec2& u) const;

 private:
  Pattern pattern_;
  int count_, strata_;
  float radius_;
};

}  // namespace tray
