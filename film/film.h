#pragma once
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"

namespace tray {

/// A named group of float channels over the image (an EXR layer). The beauty layer has an
/// empty name and channels R, G, B, A; AOVs are e.g. "N" with X, Y, Z.
struct FilmLayer {
  std::string name;
  std::vector<std::string> channels;
  std::vector<float> data;  ///< pixel-interleaved, row-major, top row first
};

/// The image being rendered: several named layers of the same size. Pixels are written once
/// each by the renderer (the integrator averages its samples), so no locking is needed.
class Film {
 public:
  Film(int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }
  /// Adds a layer and returns its index; channel names follow EXR conventions.
  int addLayer(const std::string& name, const std::vector<std::string>& channels);
  /// Index of a layer, or -1.
  int findLayer(const std::string& name) const;
  float* pixel(int layer, int x, int y) {
    auto& l = layers_[layer];
    return &l.data[(size_t(y) * width_ + x) * l.channels.size()];
  }
  const float* pixel(int layer, int x, int y) const {
    const auto& l = layers_[layer];
    return &l.data[(size_t(y) * width_ + x) * l.channels.size()];
  }
  const std::vector<FilmLayer>& layers() const { return layers_; }
  /// Header attributes that describe layers (Cryptomatte's manifest); written with EXR output.
  /// Setting a key again replaces its value.
  void setMetadata(const std::string& key, const std::string& value);
  const std::vector<std::pair<std::string, std::string>>& metadata() const { return metadata_; }
  static constexpr int kBeauty = 0;

 private:
  int width_, height_;
  std::vector<FilmLayer> layers_;
  std::vector<std::pair<std::string, std::string>> metadata_;
};

}  // namespace tray
