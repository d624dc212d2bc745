#pragma once
#include <functional>
#include <string>
#include <vector>

#include "core/film.h"
#include "integrators/integrator.h"

namespace tray {

struct RenderOptions {
  int threads = 0;     ///< 0: all cores
  int tileSize = 16;
  /// AOV layers to fill beside the beauty (names from AovSet::known()).
  std::vector<std::string> aovs;
  /// Ranks per Cryptomatte type (crypto_object, crypto_material in aovs): 2 per EXR layer.
  int cryptomatteRanks = 6;
  /// Called (serialised) after each tile with the fraction done; for progress bars.
  std::function<void(double fraction)> onProgress;
};

struct RenderStats {
  double seconds = 0;
  RayStats rays;
  double mraysPerSecond() const { return seconds > 0 ? rays.total() / seconds * 1e-6 : 0; }
};

/// Renders every pixel of the film with the integrator, tiles in parallel (TBB). Each pixel is
/// computed from its own counter-based random numbers, so the image does not depend on the
/// thread count or the order tiles finish in.
RenderStats renderImage(const Integrator& integrator, Film& film, const RenderOptions& options = {});

}  // namespace tray
