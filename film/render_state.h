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

/// What a pixel of a render in passes (render/pass_renderer.h) has beside its sums: the sums
/// of its earlier look, which its error estimate compares with (render/noise_estimate.h), its
/// samples so far (samples
/// [begin, begin + count) of its range) and whether a step of the pass under way is still owed
/// to it (kept by checkpoints, so that a resumed render takes the same decisions).
struct PixelProgress {
  PixelSums half;
  uint32_t count = 0;
  bool pending = false;
};

struct RenderState {
  std::vector<PixelSums> sums;  ///< film-sized, row-major, top row first
  std::vector<uint8_t> done;    ///< 1: the pixel will take no more samples
  /// Renders in passes only (film-sized; empty otherwise): while some pixel is not done.
  std::vector<PixelProgress> progress;

  /// A state of `pixels` pixels, none done.
  static RenderState empty(size_t pixels);
  size_t pixelsDone() const;
};

/// Writes a pixel's estimate from its sums to the beauty layer (RGB and coverage alpha).
inline void writeBeauty(Film& film, int x, int y, const PixelSums& s) {
  const Color c = s.radiance();
  float* px = film.pixel(Film::kBeauty, x, y);
  px[0] = c.x, px[1] = c.y, px[2] = c.z, px[3] = s.coverage();
}

/// Name of the film layer holding a RenderState. Its channels hold each double of PixelSums
/// bit for bit as two float32 words (high word first: Rh Rl Gh Gl Bh Bl Ah Al Wh Wl; words are
/// bit patterns, not numbers, as in Cryptomatte's ids) and `done` as 0 or 1.
inline constexpr const char* kStateLayer = "tray";

/// The state layer's channels in storage order: Rh Rl Gh Gl Bh Bl Ah Al Wh Wl done.
const std::vector<std::string>& stateChannels();
/// The sums held by the ten words Rh..Wl (in stateChannels() order), bit for bit.
PixelSums joinSums(const float* words);
/// joinSums, checked: a damaged or edited file may hold any bits in those words, so sums that
/// are not finite numbers throw tray::Error (what is wrong, for the caller to say where).
PixelSums checkedSums(const float* words);
/// A stored flag (`done`, `pending`): 0 or 1, or tray::Error naming `name` and what it holds.
bool checkedFlag(float word, const char* name);

/// Name of the film layer holding RenderState::progress, in the same words: the earlier sums'
/// Rh..Wl, then count and pending (numbers).
inline constexpr const char* kProgressLayer = "tray_progress";

/// Adds (or overwrites) the state layer of `film`, and the progress layer when the state has
/// progress and some pixel is not done; state and film have the same pixel count.
void storeState(const RenderState& state, Film& film);
/// The state stored in `film` (progress too, when the film has that layer); throws tray::Error
/// when the film has no state layer.
RenderState loadState(const Film& film);

}  // namespace tray
