#include "io/image_input.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>

#include "core/error.h"

namespace tray {
namespace {

std::string oneLine(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

bool startsWith(const std::string& s, const char* prefix) {
  return s.rfind(prefix, 0) == 0;
}

/// Layer and channel of an EXR channel name: the inverse of exrChannelName.
std::pair<std::string, std::string> splitChannel(const std::string& name) {
  const size_t dot = name.rfind('.');
  if (dot != std::string::npos) return {name.substr(0, dot), name.substr(dot + 1)};
  if (name == "R" || name == "G" || name == "B" || name == "A") return {"", name};
  return {name, name};
}

}  // namespace

ExrImage readExr(const std::string& path) {
  OIIO::ImageSpec config;
  config.attribute("oiio:try_all_readers", 0);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) throw Error(path + ": cannot read: " + oneLine(OIIO::geterror()));
  if (std::string(in->format_name()) != "openexr") throw Error(path + ": not an OpenEXR file");
  const OIIO::ImageSpec& spec = in->spec();
  const int nc = spec.nchannels;
  std::vector<float> pixels(size_t(spec.width) * spec.height * nc);
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, pixels.data()))
    throw Error(path + ": cannot read pixels: " + oneLine(in->geterror()));

  ExrImage image;
  image.film = Film(spec.width, spec.height);
  Film& film = image.film;
  // Each file channel goes to (layer, channel index) of the film, layers in file order.
  std::vector<std::pair<int, int>> target(nc);
  std::vector<std::pair<std::string, std::vector<std::string>>> layers;
  for (int c = 0; c < nc; ++c) {
    // Not a structured binding: clang 14 (the fuzz build) cannot capture one in a lambda.
    const auto split = splitChannel(spec.channelnames[c]);
    const std::string& layer = split.first;
    auto it = std::find_if(layers.begin(), layers.end(), [&](auto& l) { return l.first == layer; });
    if (it == layers.end()) it = layers.insert(layers.end(), {layer, {}});
    it->second.push_back(split.second);
  }
  const auto& beauty =
      std::find_if(layers.begin(), layers.end(), [](auto& l) { return l.first.empty(); });
  if (beauty == layers.end() || beauty->second != std::vector<std::string>{"R", "G", "B", "A"})
    throw Error(path + ": not a TRay image (no R G B A channels)");
  for (const auto& [name, channels] : layers)
    if (!name.empty()) film.addLayer(name, channels);
  for (int c = 0; c < nc; ++c) {
    auto [layer, channel] = splitChannel(spec.channelnames[c]);
    const int l = film.findLayer(layer);
    const auto& chans = film.layers()[l].channels;
    target[c] = {l, int(std::find(chans.begin(), chans.end(), channel) - chans.begin())};
  }
  for (int y = 0; y < spec.height; ++y)
    for (int x = 0; x < spec.width; ++x) {
      const float* src = &pixels[(size_t(y) * spec.width + x) * nc];
      for (int c = 0; c < nc; ++c) film.pixel(target[c].first, x, y)[target[c].second] = src[c];
    }

  ImageOutputOptions& o = image.options;
  o.halfFloat = spec.channelformat(0) == OIIO::TypeDesc::HALF;
  o.colorspace = spec.get_string_attribute("colorspace", "lin_rec709");
  o.fullWidth = spec.full_width, o.fullHeight = spec.full_height;
  o.xOffset = spec.x - spec.full_x, o.yOffset = spec.y - spec.full_y;
  for (const OIIO::ParamValue& p : spec.extra_attribs) {
    const std::string name = p.name().string();
    if (p.type() == OIIO::TypeMatrix44) {
      std::array<float, 16> m;
      std::copy_n(static_cast<const float*>(p.data()), 16, m.begin());
      o.matrixMetadata.emplace_back(name, m);
    } else if (startsWith(name, "tray:") || startsWith(name, "cryptomatte/")) {
      if (p.type() == OIIO::TypeDesc::FLOAT)
        o.floatMetadata.emplace_back(name, p.get_float());
      else if (p.type() == OIIO::TypeDesc::STRING)
        o.stringMetadata.emplace_back(name, p.get_string());
    }
  }
  return image;
}

float metadataFloat(const ImageOutputOptions& o, const std::string& key, float fallback) {
  for (const auto& [k, v] : o.floatMetadata)
    if (k == key) return v;
  return fallback;
}

std::string metadataString(const ImageOutputOptions& o, const std::string& key,
                           const std::string& fallback) {
  for (const auto& [k, v] : o.stringMetadata)
    if (k == key) return v;
  return fallback;
}

}  // namespace tray
