#pragma once
// Error of a render against a reference image: the figures the speed/accuracy charts plot.
#include <string>

#include "film/film.h"

namespace tray {

struct ImageError {
  double rmse = 0;    ///< sqrt(mean over pixels and RGB of (x - r)^2)
  double relMse = 0;  ///< mean of (x - r)^2 / (r^2 + 1e-2), robust to dark pixels (Rousselle 2011)
  double bias = 0;    ///< mean(x) - mean(r) over RGB: systematic error that more samples don't fix
  double maxAbs = 0;  ///< largest single-channel difference
  /// relMse without the 0.1% pixels of largest error (at least one): a sun glint or caustic
  /// firefly in a handful of pixels otherwise decides a whole image's figure (issue 37).
  double relMseTrimmed = 0;
};

/// Reads the first three channels of an image file (a converged reference) into the beauty of
/// a film of the file's size; throws tray::Error "PATH: problem".
Film readReference(const std::string& path);

/// readReference, which must have the render's size (throws tray::Error naming both sizes).
Film readReferenceOfSize(const std::string& path, int width, int height);

/// Compares the beauty RGB of two films of the same size (throws tray::Error otherwise).
ImageError compareBeauty(const Film& render, const Film& reference);

}  // namespace tray
