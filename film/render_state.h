#pragma once
// What a render has done so far, per pixel: the state that checkpoints, interrupted renders and
// sample-range parts store so that they can be resumed or merged exactly (docs/farm.md).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/pixel_sums.h"
#include "film/film.h"

namespace tray {

struct RenderState {
  std::vector<PixelSums> sums;  ///< film-sized, row-major, top row first
  std::vector<uint8_t> done;    ///< 1: every sample of the pixel's range is in `sums`

  /// A state of `pixels` pixels, none done.
  static RenderState empty(size_t pixels);
  size_t pixelsDone() const;
};

/// Name of the film layer holding a RenderState. Its channels hold each double of PixelSums
/// bit for bit as two float32 words (high word first: Rh Rl Gh Gl Bh Bl Ah Al Wh Wl; words are
/// bit patterns, not numbers, as in Cryptomatte's ids) and `done` as 0 or 1.
inline constexpr const char* kStateLayer = "tray";

/// The state layer's channels in storage order: Rh Rl Gh Gl Bh Bl Ah Al Wh Wl done.
const std::vector<std::string>& stateChannels();
/// The sums held by the ten words Rh..Wl (in stateChannels() order), bit for bit.
PixelSums joinSums(const float* words);

/// Adds (or overwrites) the state layer of `film`; state and film have the same pixel count.
void storeState(const RenderState& state, Film& film);
/// The state stored in `film`; throws tray::Error when the film has no state layer.
RenderState loadState(const Film& film);

}  // namespace tray
