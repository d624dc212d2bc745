#pragma once
// What a pixel has accumulated: the running sums of its filter-weighted estimator, kept in
// double so that sums of parts (sample ranges, checkpoints) combine into the same mean.
#include <algorithm>

#include "core/math.h"

namespace tray {

/// Filter-weighted sums over the samples of a pixel rendered so far (pbrt-v4 8.8's weighted
/// estimator: the pixel is sum(w L) / sum(w)). Coverage (alpha) is the weighted sum of hits.
struct PixelSums {
  double rgb[3] = {0, 0, 0};
  double alpha = 0;
  double weight = 0;

  PixelSums& operator+=(const PixelSums& o) {
    for (int c = 0; c < 3; ++c) rgb[c] += o.rgb[c];
    alpha += o.alpha;
    weight += o.weight;
    return *this;
  }
  /// The pixel's estimate (0 without samples). Alpha is clamped: Mitchell's lobes can overshoot.
  Color radiance() const {
    if (weight == 0) return Color(0.0f);
    return Color(float(rgb[0] / weight), float(rgb[1] / weight), float(rgb[2] / weight));
  }
  float coverage() const {
    return weight == 0 ? 0.0f : std::clamp(float(alpha / weight), 0.0f, 1.0f);
  }
};

}  // namespace tray
