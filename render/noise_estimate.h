#pragma once
// Noise-driven adaptive sampling (docs/adaptive-sampling.md): when a pixel has had enough
// samples. A pixel's samples come in steps (nextStep); each step's first half also goes to a
// half buffer, and the difference of the two means estimates the error of the whole mean
// (Dammertz et al. 2010, "A hierarchical automatic stopping condition for Monte Carlo global
// illumination", §2.1; Cycles' "adaptive sampling" computes the same number, so a threshold
// means the same in both). Decisions are taken per 8x8 block of image pixels from that
// block's pixels alone, so that a region whose edges are multiples of 8 renders the pixels of
// the whole image's render, bit for bit.
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
};

/// The passes the settings ask for: set when --noise-threshold or --time-limit is (maxSamples
/// is left for the renderer to take from the sample range); none otherwise.
std::optional<SamplingPasses> samplingPassesOf(const RenderSettings& settings);

/// The estimated error of the mean `all` (Dammertz et al. §2.1): the L1 distance of the RGB
/// means of `all` and `half` over the square root of the sum of `all`'s mean RGB (between
/// absolute and relative error, as the eye sees noise after tone mapping). Infinite while
/// either buffer has no weight.
float pixelError(const PixelSums& all, const PixelSums& half);

/// Samples of a pixel's next step after `count`: minSamples first, then the largest power of
/// two at most half of what it has (16, 24, 32, 48, 64, 96, ...: about two looks per doubling,
/// each step an aligned run of Sobol' points), never past maxSamples; 0 when it has them all.
int nextStep(int count, const SamplingPasses& passes);

/// One block's decision: which of its pixels take another step. `error` and `count` hold the
/// block's w x h pixels row by row. A pixel goes on while it has fewer than minSamples, or
/// (threshold > 0) some pixel of its 3x3 neighbourhood inside the block is above the
/// threshold (an isolated pixel whose two halves agree by chance does not stop while its
/// neighbours are noisy), or (threshold 0) until maxSamples. `more` receives 1 for those.
void decideBlock(std::span<const float> error, std::span<const uint32_t> count, int w, int h,
                 const SamplingPasses& passes, std::span<uint8_t> more);

}  // namespace tray
