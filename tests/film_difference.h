#pragma once
// Two renders' beauty RGB set side by side, for the tests that compare accelerators or
// instancing paths: RMSE, the largest single-value difference and each image's mean.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "film/film.h"

namespace tray::test {

struct FilmDifference {
  double rmse = 0, maxAbs = 0, meanA = 0, meanB = 0;
};

/// Over every pixel and R, G, B of two films of the same size.
inline FilmDifference filmDifference(const Film& a, const Film& b) {
  FilmDifference d;
  double sum = 0;
  size_t n = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x)
      for (int c = 0; c < 3; ++c, ++n) {
        const double va = a.pixel(Film::kBeauty, x, y)[c], vb = b.pixel(Film::kBeauty, x, y)[c];
        sum += (va - vb) * (va - vb);
        d.maxAbs = std::max(d.maxAbs, std::fabs(va - vb));
        d.meanA += va, d.meanB += vb;
      }
  d.rmse = std::sqrt(sum / double(n)), d.meanA /= double(n), d.meanB /= double(n);
  return d;
}

}  // namespace tray::test
