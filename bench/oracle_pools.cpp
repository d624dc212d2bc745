// The oracle benchmarks' pools of independent renders (bench/oracle_pools.h).
#include "bench/oracle_pools.h"

#include <algorithm>
#include <cmath>

#include "render/noise_estimate.h"

namespace tray {

std::vector<double> relativeVariance(const std::vector<float>& means, size_t pixels, int first,
                                     int last, int spp, const Film& ref) {
  std::vector<double> a(pixels, 0.0);
  const int w = ref.width(), k = last - first;
  for (size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c) {
      double sum = 0, squares = 0;
      for (int j = first; j < last; ++j) {
        const double v = means[(size_t(j) * pixels + p) * 3 + c];
        sum += v, squares += v * v;
      }
      const double mean = sum / k, var = std::max(0.0, (squares - k * mean * mean) / (k - 1));
      const double r = ref.pixel(Film::kBeauty, int(p % w), int(p / w))[c];
      a[p] += var * spp / (r * r + kRelativeFloor);
    }
  return a;
}

Film imageOf(const std::vector<float>& means, const std::vector<int>& steps, int first, int w,
             int h) {
  Film film(w, h);
  const size_t pixels = size_t(w) * h;
  for (size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c) {
      double sum = 0;
      for (int j = first; j < first + steps[p]; ++j)
        sum += means[(size_t(j) * pixels + p) * 3 + c];
      film.pixel(Film::kBeauty, int(p % w), int(p / w))[c] = float(sum / steps[p]);
    }
  return film;
}

std::vector<double> boxAverage(const std::vector<double>& a, int w, int h, int radius, bool self) {
  std::vector<double> out(a.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0;
      int n = 0;
      for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx)
          if (x + dx >= 0 && y + dy >= 0 && x + dx < w && y + dy < h && (self || dx || dy))
            s += a[size_t(y + dy) * w + x + dx], ++n;
      out[size_t(y) * w + x] = s / n;
    }
  return out;
}

std::vector<int> replay(const std::vector<float>& means, int first, int available, int w, int h,
                        SamplingPasses passes) {
  const size_t pixels = size_t(w) * h;
  passes.maxSamples = available;
  std::vector<int> count(pixels, 0);
  std::vector<uint8_t> pending(pixels, 1);
  auto sums = [&](size_t p, int n) {  // the pixel's sums over its first n renders
    PixelSums s;
    for (int j = first; j < first + n; ++j)
      for (int c = 0; c < 3; ++c) s.rgb[c] += means[(size_t(j) * pixels + p) * 3 + c];
    s.weight = n;
    return s;
  };
  std::vector<float> error(pixels);
  std::vector<uint32_t> n(pixels);
  for (bool any = true; any;) {
    for (size_t p = 0; p < pixels; ++p) {
      if (pending[p]) count[p] += nextStep(count[p], passes);
      const int m = earlierCount(count[p], passes);
      error[p] = pixelError(sums(p, count[p]), sums(p, m), count[p], m, passes.absoluteError);
      n[p] = uint32_t(count[p]);
    }
    any = decideImage(error, n, w, h, passes, pending);
  }
  return count;
}

double uniformAt(const std::vector<std::pair<double, double>>& uniform, double x) {
  for (size_t i = 1; i < uniform.size(); ++i)
    if (x <= uniform[i].first || i + 1 == uniform.size()) {
      const auto [x0, y0] = uniform[i - 1];
      const auto [x1, y1] = uniform[i];
      const double t = std::log(x / x0) / std::log(x1 / x0);
      return std::exp(std::log(y0) + t * std::log(y1 / y0));
    }
  return 0;
}

}  // namespace tray
