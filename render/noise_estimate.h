#pragma once
// Noise-driven adaptive sampling (docs/adaptive-sampling.md): when a pixel has had enough
// samples. A pixel's samples come in steps (nextStep) and the error of its mean is estimated
// from the difference between the mean now and the mean at its previous look (its first step:
// the mean of its first half), the two-buffer idea of Dammertz et al. 2010 ("A hierarchical
// automatic stopping condition for Monte Carlo global illumination", §2.1, as Cycles and
// Arnold use it) with the earlier samples as the second buffer, so that a step is traced in
// one go; the error is relative to the pixel's value, as relMSE measures it (or absolute, as
// RMSE measures it: --noise-metric). Decisions are
// taken per 8x8 block of image pixels from that block's pixels alone, so that a region whose
// edges are multiples of 8 renders the pixels of the whole image's render, bit for bit.
#include <cstdint>
#include <optional>
#include <span>

#include "core/pixel_sums.h"
#include "core/render_options.h"

namespace tray {

/// The side of the blocks whose pixels decide together (image coordinates, aligned to 0).
inline constexpr int kNoiseBlock = 8;

/// How a render spends its samples in passes (--noise-threshold, --min-spp, --spp, --time-limit).
struct SamplingPasses {
  float threshold = 0;   ///< a pixel stops below this error (0: only the maximum stops it)
  int minSamples = 16;   ///< every pixel's first step (at most maxSamples)
  int maxSamples = 1;    ///< --spp, or the size of the sample range
  double timeLimit = 0;  ///< seconds after which the render ends between steps (0: none)
  /// --noise-rule even: every pixel stops below `threshold`; else (mse) the rule that spends
  /// samples where they lower the image's relMSE most (stoppingError).
  bool evenError = false;
  /// --noise-metric absolute: the error in radiance units (what RMSE measures, the
  /// allocation that minimises it under `mse`); else relative to the pixel's value (relMSE).
  bool absoluteError = false;
  /// --noise-decision: what a pixel's stop is decided from (decideBlock).
  enum class Decision {
    kWide,        ///< wide: the RMS error of the 24 others of its 5x5 (unbiased; the default)
    kNeighbours,  ///< neighbours: the mean error of its 8 neighbours (dark at high thresholds)
    kMax,         ///< max: the largest of the 8 errors (goes on near any noise)
    kPixel,       ///< pixel: its own error too, as Cycles and Arnold (biased dark)
  };
  Decision decision = Decision::kWide;
};

/// The floor of relMSE's denominator (value^2 + 0.01, bench/image_error.cpp): below a value
/// of 0.1 an error counts as absolute, so that black pixels do not ask for endless samples.
inline constexpr double kRelativeFloor = 1e-2;

/// The passes the settings ask for: set when --noise-threshold or --time-limit is (maxSamples
/// is left for the renderer to take from the sample range); none otherwise.
std::optional<SamplingPasses> samplingPassesOf(const RenderSettings& settings);

/// The estimated relative error of `all`, the mean of a pixel's n samples, from `earlier`, the
/// mean of its first m (0 < m < n): for independent samples the difference of the two has
/// standard deviation sqrt((n - m) / m) times that of `all`, so the difference is scaled by
/// sqrt(m / (n - m)); each channel relative to sqrt(mean^2 + kRelativeFloor) (`absolute`: as
/// it is), and the RMS over R, G, B. Infinite without an estimate (m or n - m not positive, a
/// weight of zero).
float pixelError(const PixelSums& all, const PixelSums& earlier, int n, int m,
                 bool absolute = false);

/// How many of a pixel's `count` samples its earlier mean holds: half of the first step,
/// afterwards the count of the look before (counts follow one fixed sequence).
int earlierCount(int count, const SamplingPasses& passes);

/// Samples of a pixel's next step after `count`: minSamples first, then the largest power of
/// two at most half of what it has (16, 24, 32, 48, 64, 96, ...: about two looks per doubling,
/// each step an aligned run of Sobol' points), never past maxSamples; 0 when it has them all.
int nextStep(int count, const SamplingPasses& passes);

/// The error below which a pixel with `count` samples stops. --noise-rule even: the threshold
/// itself (equal error everywhere, as Cycles' and Arnold's thresholds). mse (the default):
/// threshold x sqrt(count / minSamples). One more sample lowers a pixel's squared error e^2 by
/// about e^2 / count, so stopping every pixel where that gain falls below one common value
/// (threshold^2 / minSamples) is the allocation that minimises the image's summed squared
/// error for the samples spent (n proportional to the pixel's standard deviation, not to its
/// variance as with equal error, which over-spends on the noisiest pixels).
float stoppingError(int count, const SamplingPasses& passes);

/// One block's decision: which of its pixels take another step. `error` and `count` hold the
/// block's w x h pixels row by row. A pixel goes on while it has fewer than minSamples, or
/// (threshold > 0) its neighbours' error inside the block is at least its stoppingError, or
/// (threshold 0) until maxSamples. Its own error is not read: a decision from its own samples
/// biases its mean (Kirk & Arvo 1991); its neighbours' samples are independent of them, and a
/// noisy pixel keeps its neighbours going. kWide (the default) reads the RMS of the 24 other
/// errors of the 5x5 neighbourhood (more samples behind each estimate, and a rare bright path
/// weighs as its squared error does in the variance); kNeighbours the mean of the 3x3's 8,
/// kMax their largest. The 8 alone still feed back: a pixel whose samples came out dark lets
/// its neighbours stop, their errors then stay put, and it stops too, measurably dark at high
/// thresholds (tests/render/adaptive_bias_test.cpp); 24 dilute that below the noise. A pixel
/// with no neighbour in the block goes on to maxSamples. With kPixel a pixel also goes on while
/// its own error, or the 3x3 mean with itself, is at least the limit (biased:
/// docs/adaptive-sampling.md). `more` receives 1 for those that go on.
void decideBlock(std::span<const float> error, std::span<const uint32_t> count, int w, int h,
                 const SamplingPasses& passes, std::span<uint8_t> more);

/// decideBlock over a whole w x h image: `error`, `count` and `more` hold its pixels row by row,
/// and each kNoiseBlock x kNoiseBlock block (aligned to the origin, clipped at the image's
/// edges) decides from its own pixels, as the pass renderer's blocks do. Returns whether any
/// pixel goes on. For simulations and replays of the pass loop (the renderer gathers its
/// blocks' errors itself).
bool decideImage(std::span<const float> error, std::span<const uint32_t> count, int w, int h,
                 const SamplingPasses& passes, std::span<uint8_t> more);

}  // namespace tray
