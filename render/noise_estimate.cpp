#include "render/noise_estimate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace tray {
namespace {
/// A pixel's error where there is no estimate yet: it never lets a decision stop.
constexpr float kNoEstimate = std::numeric_limits<float>::infinity();
}  // namespace

std::optional<SamplingPasses> samplingPassesOf(const RenderSettings& settings) {
  if (!rendersInPasses(settings)) return std::nullopt;
  SamplingPasses passes;
  passes.threshold = settings.getFloat("noise-threshold");
  passes.timeLimit = settings.getFloat("time-limit");
  passes.minSamples = int(settings.getInt("min-spp"));
  passes.evenError = settings.getString("noise-rule") == "even";
  passes.absoluteError = settings.getString("noise-metric") == "absolute";
  const std::string decision = settings.getString("noise-decision");
  using D = SamplingPasses::Decision;
  passes.decision = decision == "pixel"        ? D::kPixel
                    : decision == "max"        ? D::kMax
                    : decision == "neighbours" ? D::kNeighbours
                                               : D::kWide;
  return passes;
}

float pixelError(const PixelSums& all, const PixelSums& earlier, int n, int m, bool absolute) {
  // Mitchell's negative lobes can make a weight sum cross zero: no estimate then.
  if (m <= 0 || n <= m || !(std::abs(all.weight) > 0) || !(std::abs(earlier.weight) > 0))
    return kNoEstimate;
  double squared = 0;
  for (int c = 0; c < 3; ++c) {
    const double mean = all.rgb[c] / all.weight, d = mean - earlier.rgb[c] / earlier.weight;
    squared += absolute ? d * d : d * d / (mean * mean + kRelativeFloor);
  }
  return float(std::sqrt(squared / 3 * double(m) / double(n - m)));
}

int earlierCount(int count, const SamplingPasses& passes) {
  const int first = nextStep(0, passes);
  if (count <= first) return count / 2;
  int previous = first;
  for (int next; (next = previous + nextStep(previous, passes)) < count;) previous = next;
  return previous;
}

int nextStep(int count, const SamplingPasses& passes) {
  const int left = passes.maxSamples - count;
  if (left <= 0) return 0;
  if (count == 0) return std::min(std::max(passes.minSamples, 1), left);
  int step = 1;
  while (step * 4 <= count) step *= 2;  // the largest power of two <= count / 2
  return std::min(step, left);
}

float stoppingError(int count, const SamplingPasses& passes) {
  if (passes.evenError) return passes.threshold;
  return passes.threshold * std::sqrt(float(count) / float(std::max(passes.minSamples, 1)));
}

void decideBlock(std::span<const float> error, std::span<const uint32_t> count, int w, int h,
                 const SamplingPasses& passes, std::span<uint8_t> more) {
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int p = y * w + x;
      more[p] = 0;
      if (nextStep(int(count[p]), passes) == 0) continue;
      if (passes.threshold <= 0 || int(count[p]) < passes.minSamples) {
        more[p] = 1;
        continue;
      }
      // The error of the pixel's neighbours (no estimate: infinite), not its own: a
      // decision that read the pixel's own samples would stop it more often when they came
      // out low (a rare bright path not yet found) and bias the image dark (Kirk & Arvo 1991,
      // "Unbiased sampling techniques for image synthesis"; measured: the Cornell box 0.3-0.5%
      // dark, docs/adaptive-sampling.md). Its neighbours' samples are independent of its own.
      using D = SamplingPasses::Decision;
      const int radius = passes.decision == D::kWide ? 2 : 1;
      double sum = 0, squares = 0, largest = 0;
      int n = 0;
      for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          const float e = error[ny * w + nx];
          const double v = std::isfinite(e) ? double(e) : double(kNoEstimate);
          sum += v, squares += v * v, largest = std::max(largest, v);
          ++n;
        }
      const float limit = stoppingError(int(count[p]), passes);
      if (passes.decision == D::kPixel) {
        // Cycles' and Arnold's way: the pixel's own error, and the 3x3 mean with itself.
        const float own = std::isfinite(error[p]) ? error[p] : kNoEstimate;
        more[p] = !(own < limit) || !((sum + own) / (n + 1) < limit);
        continue;
      }
      // No neighbours (a block one pixel wide and high): nothing unbiased to decide from, so
      // the pixel takes every sample.
      const double neighbours = passes.decision == D::kMax    ? largest
                                : passes.decision == D::kWide ? std::sqrt(squares / n)
                                                              : sum / n;
      more[p] = n == 0 || !(neighbours < limit);
    }
}

bool decideImage(std::span<const float> error, std::span<const uint32_t> count, int w, int h,
                 const SamplingPasses& passes, std::span<uint8_t> more) {
  bool any = false;
  std::vector<float> blockError;
  std::vector<uint32_t> blockCount;
  std::vector<uint8_t> blockMore;
  for (int by = 0; by < h; by += kNoiseBlock)
    for (int bx = 0; bx < w; bx += kNoiseBlock) {
      const int bw = std::min(kNoiseBlock, w - bx), bh = std::min(kNoiseBlock, h - by);
      blockError.clear(), blockCount.clear();
      for (int y = by; y < by + bh; ++y)
        for (int x = bx; x < bx + bw; ++x) {
          blockError.push_back(error[size_t(y) * w + x]);
          blockCount.push_back(count[size_t(y) * w + x]);
        }
      blockMore.assign(size_t(bw) * bh, 0);
      decideBlock(blockError, blockCount, bw, bh, passes, blockMore);
      for (int i = 0; i < bw * bh; ++i) {
        more[size_t(by + i / bw) * w + bx + i % bw] = blockMore[i];
        any = any || blockMore[i];
      }
    }
  return any;
}

}  // namespace tray
