#include "io/image_input.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/options.h"

namespace tray {
namespace {

const float* findFloat(const ImageOutputOptions& o, const std::string& key) {
  for (const auto& [k, v] : o.floatMetadata)
    if (k == key) return &v;
  return nullptr;
}

/// A stored number as a user reads it (4.5, nan, inf, 1e+30): the options' shortest text.
std::string shown(float v) {
  return formatOptionValue(OptionValue(v));
}

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

namespace {

std::unique_ptr<OIIO::ImageInput> openExr(const std::string& path) {
  OIIO::ImageSpec config;
  config.attribute("oiio:try_all_readers", 0);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) throw Error(path + ": cannot read: " + oneLine(OIIO::geterror()));
  if (std::string(in->format_name()) != "openexr") throw Error(path + ": not an OpenEXR file");
  return in;
}

ExrHeader headerOf(const OIIO::ImageSpec& spec, const std::string& path) {
  ExrHeader h;
  h.width = spec.width, h.height = spec.height;
  h.channels.assign(spec.channelnames.begin(), spec.channelnames.end());
  const auto layers = h.layers();
  if (layers.empty() || !layers.front().first.empty() ||
      layers.front().second != std::vector<std::string>{"R", "G", "B", "A"})
    throw Error(path + ": not a TRay image (no R G B A channels)");
  ImageOutputOptions& o = h.options;
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
  return h;
}

}  // namespace

std::vector<std::pair<std::string, std::vector<std::string>>> ExrHeader::layers() const {
  std::vector<std::pair<std::string, std::vector<std::string>>> layers;
  for (const std::string& name : channels) {
    // Not a structured binding: clang 14 (the fuzz build) cannot capture one in a lambda.
    const auto split = splitChannel(name);
    auto it = std::find_if(layers.begin(), layers.end(),
                           [&](auto& l) { return l.first == split.first; });
    if (it == layers.end()) it = layers.insert(layers.end(), {split.first, {}});
    it->second.push_back(split.second);
  }
  // The beauty first, as in a Film (OpenEXR sorts channels by name: "A" may follow "Z"...).
  std::stable_partition(layers.begin(), layers.end(), [](auto& l) { return l.first.empty(); });
  return layers;
}

ExrHeader readExrHeader(const std::string& path) {
  return headerOf(openExr(path)->spec(), path);
}

struct ExrRowReader::Impl {
  std::unique_ptr<OIIO::ImageInput> in;
  std::string path;
};

ExrRowReader::ExrRowReader(const std::string& path) : impl_(new Impl{openExr(path), path}) {
  header_ = headerOf(impl_->in->spec(), path);
}

ExrRowReader::~ExrRowReader() = default;

void ExrRowReader::read(int y, int rows, std::vector<float>& out) {
  const OIIO::ImageSpec& spec = impl_->in->spec();
  out.resize(size_t(rows) * spec.width * spec.nchannels);
  if (!impl_->in->read_scanlines(0, 0, spec.y + y, spec.y + y + rows, 0, 0, spec.nchannels,
                                 OIIO::TypeDesc::FLOAT, out.data()))
    throw Error(impl_->path + ": cannot read pixels: " + oneLine(impl_->in->geterror()));
}

ExrImage readExr(const std::string& path) {
  ExrRowReader reader(path);
  const ExrHeader& header = reader.header();
  const int nc = int(header.channels.size());
  std::vector<float> pixels;
  reader.read(0, header.height, pixels);

  ExrImage image;
  image.film = Film(header.width, header.height);
  Film& film = image.film;
  for (const auto& [name, channels] : header.layers())
    if (!name.empty()) film.addLayer(name, channels);
  // Each file channel goes to (layer, channel index) of the film.
  std::vector<std::pair<int, int>> target(nc);
  for (int c = 0; c < nc; ++c) {
    auto [layer, channel] = splitChannel(header.channels[c]);
    const int l = film.findLayer(layer);
    const auto& chans = film.layers()[l].channels;
    target[c] = {l, int(std::find(chans.begin(), chans.end(), channel) - chans.begin())};
  }
  for (int y = 0; y < header.height; ++y)
    for (int x = 0; x < header.width; ++x) {
      const float* src = &pixels[(size_t(y) * header.width + x) * nc];
      for (int c = 0; c < nc; ++c) film.pixel(target[c].first, x, y)[target[c].second] = src[c];
    }
  image.options = header.options;
  return image;
}

float metadataFloat(const ImageOutputOptions& o, const std::string& key, float fallback) {
  const float* v = findFloat(o, key);
  return v ? *v : fallback;
}

int64_t metadataCount(const ImageOutputOptions& o, const std::string& key, int64_t fallback,
                      const std::string& path, int64_t max) {
  const float* v = findFloat(o, key);
  if (!v) return fallback;
  // The comparisons are false for NaN; max as a double is exact up to 2^53.
  if (!(*v >= 0 && double(*v) <= double(max)) || *v != std::floor(*v))
    throw Error(path + ": its header's " + key + " is " + shown(*v) +
                    ", not a whole number from 0 to " + std::to_string(max) +
                    ": an edited or damaged file",
                Error::Kind::kInput);
  return int64_t(*v);
}

double metadataAmount(const ImageOutputOptions& o, const std::string& key, double fallback,
                      const std::string& path) {
  const float* v = findFloat(o, key);
  if (!v) return fallback;
  if (!(*v >= 0 && std::isfinite(*v)))
    throw Error(path + ": its header's " + key + " is " + shown(*v) +
                    ", not a finite number of at least 0: an edited or damaged file",
                Error::Kind::kInput);
  return *v;
}

std::string metadataString(const ImageOutputOptions& o, const std::string& key,
                           const std::string& fallback) {
  for (const auto& [k, v] : o.stringMetadata)
    if (k == key) return v;
  return fallback;
}

}  // namespace tray
