#include "film/film.h"

namespace tray {

Film::Film(int width, int height) : width_(width), height_(height) {
  // 16384^2 RGBA float is 4 GiB: refuse larger images before allocating.
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    throw Error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                " is out of range (1..16384 per side)");
  addLayer("", {"R", "G", "B", "A"});
}

int Film::addLayer(const std::string& name, const std::vector<std::string>& channels) {
  int existing = findLayer(name);
  if (existing >= 0) return existing;
  layers_.push_back(
      {name, channels, std::vector<float>(size_t(width_) * height_ * channels.size())});
  return int(layers_.size()) - 1;
}

void Film::setMetadata(const std::string& key, const std::string& value) {
  for (auto& [k, v] : metadata_)
    if (k == key) {
      v = value;
      return;
    }
  metadata_.emplace_back(key, value);
}

int Film::findLayer(const std::string& name) const {
  for (size_t i = 0; i < layers_.size(); ++i)
    if (layers_[i].name == name) return int(i);
  return -1;
}

}  // namespace tray
