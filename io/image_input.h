#pragma once
// Reading TRay's own EXR files back: checkpoints to resume and parts to merge (docs/farm.md).
#include <string>

#include "core/film.h"
#include "io/image_output.h"

namespace tray {

/// An EXR as TRay wrote it: every channel as a film layer (names split as exrChannelName joins
/// them: "N.X" is layer N channel X, "Z" layer Z, "R G B A" the beauty) and what writeImage
/// needs to write it again: windows, precision, colorspace and the metadata TRay writes
/// ("tray:*" and "cryptomatte/*" attributes, worldToCamera, worldToNDC).
struct ExrImage {
  Film film{1, 1};
  ImageOutputOptions options;
};

/// Reads `path` (an OpenEXR file, first part); the beauty stays in the file's colorspace. Throws
/// tray::Error "PATH: problem" for an unreadable or non-EXR file, or one without R G B A.
ExrImage readExr(const std::string& path);

/// The value of a float/string attribute read back, or `fallback`.
float metadataFloat(const ImageOutputOptions& o, const std::string& key, float fallback);
std::string metadataString(const ImageOutputOptions& o, const std::string& key,
                           const std::string& fallback = "");

}  // namespace tray
