#pragma once
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "film/film.h"

namespace tray {

struct ImageOutputOptions {
  /// EXR beauty, albedo and N as half (else float); Z, P, ids and counts are always float.
  bool halfFloat = true;
  /// EXR output colorspace (an OCIO name, alias or role); empty: the config's linear Rec.709
  /// space, else its scene_linear role (ColorPipeline::defaultOutputSpace).
  std::string colorspace;
  std::string display, view;              ///< PNG/JPEG display/view; empty = config defaults
  std::vector<std::pair<std::string, std::string>> stringMetadata;
  std::vector<std::pair<std::string, float>> floatMetadata;
  /// EXR m44f attributes (e.g. worldToCamera), row-major in Imath's row-vector convention.
  std::vector<std::pair<std::string, std::array<float, 16>>> matrixMetadata;
  /// The film is the data window placed at (xOffset, yOffset) in a display window of
  /// fullWidth x fullHeight (0 = the film's size): region renders of a larger image.
  int fullWidth = 0, fullHeight = 0, xOffset = 0, yOffset = 0;
};

/// Writes the film to `path` (colour through ColorPipeline::instance()); the format comes from the
/// extension: .exr (every layer, scene-linear, colour-managed beauty) or .png/.jpg/.jpeg (beauty
/// RGB through the display view, 8-bit). The file appears atomically: it is written under a
/// temporary name in the same folder and renamed when complete, so an existing file is never left
/// truncated. Throws tray::Error with a one-line "PATH: problem" message.
/// Half EXR channels hold at most 65504: larger values are clamped to +-65504, each on its own
/// (not +Inf); returns how many were (0 for float EXR, PNG and JPEG). Callers warn with
/// halfClampWarning.
size_t writeImage(const Film& film, const std::string& path,
                  const ImageOutputOptions& options = {});

/// Writes the film to every path as writeImage does, all or nothing: each file is complete
/// under a temporary name before any is renamed into place, so an error (a full disk, a bad
/// colorspace) leaves none of them changed. Returns each path's clamp count.
std::vector<size_t> writeImages(const Film& film, const std::vector<std::string>& paths,
                                const ImageOutputOptions& options = {});

/// Whether `path` names an OpenEXR output (its extension, any case): scene-linear, every layer,
/// resumable; the others (.png, .jpg, .jpeg) are display-referred.
bool isExrPath(const std::string& path);

/// The one-line warning for `clamped` values clamped to half's range in `path`.
std::string halfClampWarning(const std::string& path, size_t clamped);

/// Checks, before anything is rendered, what writeImage would refuse afterwards: each path's
/// format (by extension) and folder, and that its colour conversions (colorspace, display,
/// view; the OCIO config itself) can be made. Throws tray::Error "PATH: problem".
void checkOutputs(const std::vector<std::string>& paths, const ImageOutputOptions& options);

/// A layer's pixels as PNG/JPEG output shows them: 8-bit RGB, row-major, top row first, through
/// the display/view (empty: the config's defaults), rounded from [0, 1] (not finite: 0). The
/// first three channels; a layer of fewer shows its first one as grey. The Python module's
/// Image.to_display() and the PNG writer share it.
std::vector<unsigned char> displayBytes(const Film& film, int layer, const std::string& display,
                                        const std::string& view);

/// EXR channel name of a layer's channel: bare for the beauty layer ("R") and for a layer with
/// one channel of its own name ("Z"); otherwise "layer.channel" ("N.X").
std::string exrChannelName(const FilmLayer& layer, const std::string& channel);

}  // namespace tray
