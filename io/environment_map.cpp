#include "io/environment_map.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/render_options.h"
#include "core/scene.h"
#include "io/color.h"
#include "io/memory_estimate.h"

namespace tray {

namespace {

std::string oneLine(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s.empty() ? "unknown error" : s;
}

/// The header's size against the limits, before any pixel is decoded.
void checkSize(const std::string& name, const OIIO::ImageSpec& spec) {
  if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1 || spec.nchannels < 1)
    throw Error(name + ": the environment map's header states no pixels");
  const uint64_t pixels = uint64_t(spec.width) * uint64_t(spec.height);
  if (spec.width > kMaxEnvironmentWidth || pixels > kMaxEnvironmentPixels)
    throw Error(name + ": environment map of " + std::to_string(spec.width) + "x" +
                std::to_string(spec.height) + " pixels is over the limit (" +
                std::to_string(kMaxEnvironmentWidth) + " wide, " +
                std::to_string(kMaxEnvironmentPixels) + " pixels)");
}

/// Decodes the open image to working-space RGB and checks its values. The header's size is
/// checked first (against the limits, and against maxBytes: --max-memory, 0 none); the map's
/// floats are not zero-filled (EnvironmentMap::rgb), so a header that claims more rows than
/// the file holds costs only the rows decoded before the read fails.
std::shared_ptr<const EnvironmentMap> readPixels(OIIO::ImageInput& in, const std::string& name,
                                                 std::vector<std::string>* warnings,
                                                 uint64_t maxBytes) {
  const OIIO::ImageSpec& spec = in.spec();
  checkSize(name, spec);
  MemoryEstimate need;
  need.environment = environmentMapBytes(spec.width, spec.height);
  checkMemory(name, need, maxBytes);
  const int nc = spec.nchannels;
  const size_t pixels = size_t(spec.width) * size_t(spec.height);
  // RGB straight into the map (grey: one channel, spread below): no full-channel copy.
  auto map = std::make_shared<EnvironmentMap>();
  map->name = name;
  map->width = spec.width, map->height = spec.height;
  map->rgb.resize(pixels * 3);
  const int read = std::min(nc, 3);
  if (!in.read_image(0, 0, 0, read, OIIO::TypeDesc::FLOAT, map->rgb.data(), 3 * sizeof(float)))
    throw Error(name + ": cannot read pixels: " + oneLine(in.geterror()));
  if (read < 3)  // grey (and grey + alpha): the first channel in R, G and B
    for (size_t i = 0; i < pixels; ++i) map->rgb[3 * i + 1] = map->rgb[3 * i + 2] = map->rgb[3 * i];
  const std::string tagged = spec.get_string_attribute("colorspace");
  if (!tagged.empty()) {
    try {
      ColorPipeline::instance().convertToWorking(map->rgb.data(), pixels, 3, tagged);
    } catch (const Error& e) {
      throw Error(name + ": colorspace '" + tagged + "': " + e.what());
    }
  }
  for (size_t i = 0; i < map->rgb.size(); ++i) {
    float& v = map->rgb[i];
    if (!std::isfinite(v)) {
      const size_t p = i / 3;
      throw Error(name + ": environment map has NaN or infinite values (first at pixel " +
                  std::to_string(p % size_t(spec.width)) + "," +
                  std::to_string(p / size_t(spec.width)) + ")");
    }
    v = std::max(v, 0.0f);  // out-of-gamut colours (after a conversion) emit nothing negative
  }
  if (warnings && spec.width != 2 * spec.height)
    warnings->push_back(name + ": environment map is " + std::to_string(spec.width) + "x" +
                        std::to_string(spec.height) +
                        ", not 2:1: used as latitude-longitude anyway (stretched)");
  return map;
}

/// "openexr", "hdr" or "" from the first bytes (the reader is never guessed from content).
const char* formatOf(const unsigned char* b, size_t n) {
  if (n >= 4 && b[0] == 0x76 && b[1] == 0x2f && b[2] == 0x31 && b[3] == 0x01) return "openexr";
  if (n >= 2 && b[0] == '#' && b[1] == '?') return "hdr";
  return "";
}

}  // namespace

std::shared_ptr<const EnvironmentMap> loadEnvironmentMap(const std::string& path,
                                                         std::vector<std::string>* warnings,
                                                         uint64_t maxBytes) {
  if (!OIIO::Filesystem::exists(path)) throw Error(path + ": environment map not found");
  if (!OIIO::Filesystem::is_regular(path))
    throw Error(path + ": environment map is not a regular file");
  OIIO::ImageSpec config;
  config.attribute("oiio:try_all_readers", 0);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) throw Error(path + ": cannot read the environment map: " + oneLine(OIIO::geterror()));
  return readPixels(*in, path, warnings, maxBytes);
}

std::shared_ptr<const EnvironmentMap> decodeEnvironmentMap(const unsigned char* data,
                                                           size_t size, const std::string& name,
                                                           std::vector<std::string>* warnings,
                                                           uint64_t maxBytes) {
  const char* format = formatOf(data, size);
  if (!*format) throw Error(name + ": environment map is not an OpenEXR or Radiance HDR image");
  OIIO::Filesystem::IOMemReader memory(data, size);
  OIIO::ImageSpec config, spec;
  auto in = OIIO::ImageInput::create(format, false, &config);
  if (!in || !in->set_ioproxy(&memory) || !in->open(name, spec, config))
    throw Error(name + ": cannot decode the environment map: " +
                oneLine(in ? in->geterror() : OIIO::geterror()));
  return readPixels(*in, name, warnings, maxBytes);
}

uint64_t environmentMapBytes(int width, int height) {
  return uint64_t(width) * uint64_t(height) * 3 * sizeof(float);
}

void applyEnvironmentOptions(Scene& scene, const RenderSettings& settings,
                             std::vector<std::string>* warnings, uint64_t maxBytes) {
  Environment& env = scene.environment;
  const std::string path = settings.getString("env");
  if (!path.empty()) {
    env.map = loadEnvironmentMap(path, warnings, maxBytes);
    env.rotation = 0, env.intensity = 1;  // the scene's values belonged to its own image
  }
  if (settings.isSet("env-rotate")) env.rotation = settings.getFloat("env-rotate");
  if (settings.isSet("env-intensity")) {
    env.intensity = settings.getFloat("env-intensity");
    if (!env.map) env.background = env.background * env.intensity;  // a constant: scaled too
  }
}

}  // namespace tray
