#pragma once
// Reading TRay's own EXR files back: checkpoints to resume and parts to merge (docs/farm.md).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "film/film.h"
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

/// What an EXR's header says: windows, precision, colorspace and metadata as in ExrImage, the
/// data window's size and the channel names in file order.
struct ExrHeader {
  ImageOutputOptions options;
  int width = 0, height = 0;
  std::vector<std::string> channels;
  /// The layers as readExr would make them (beauty "" first), with their channels.
  std::vector<std::pair<std::string, std::vector<std::string>>> layers() const;
};

/// Reads the header of `path` only (no pixels): what tray-merge checks of every part before it
/// reads any pixels. Throws as readExr does.
ExrHeader readExrHeader(const std::string& path);

/// An EXR read a band of rows at a time, so that a merge holds one band of each part rather
/// than whole parts.
class ExrRowReader {
 public:
  /// Opens `path` and reads its header; throws as readExr does.
  explicit ExrRowReader(const std::string& path);
  ~ExrRowReader();
  const ExrHeader& header() const { return header_; }
  /// Rows y..y+rows-1 of the data window (0: its top row), every channel as float,
  /// interleaved in header().channels order, into `out` (resized).
  void read(int y, int rows, std::vector<float>& out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  ExrHeader header_;
};

/// The value of a float/string attribute read back, or `fallback`.
float metadataFloat(const ImageOutputOptions& o, const std::string& key, float fallback);
std::string metadataString(const ImageOutputOptions& o, const std::string& key,
                           const std::string& fallback = "");
/// A float attribute that counts something (pixels, samples, a sample index): a whole number in
/// 0..max, or `fallback` when absent. Anything else (NaN, an infinity, a fraction, a negative or
/// a huge number: an edited or damaged header) throws tray::Error naming `path`, the attribute
/// and its value, before it can become an undefined conversion or a nonsense message.
int64_t metadataCount(const ImageOutputOptions& o, const std::string& key, int64_t fallback,
                      const std::string& path, int64_t max = int64_t(1) << 53);
/// A float attribute that measures something (seconds): finite and at least 0, or `fallback`
/// when absent; throws as metadataCount does.
double metadataAmount(const ImageOutputOptions& o, const std::string& key, double fallback,
                      const std::string& path);

}  // namespace tray
