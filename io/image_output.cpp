#include "io/image_output.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "io/color.h"

namespace fs = std::filesystem;

namespace tray {
namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string oneLine(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

/// Layers holding colours or unit vectors keep the chosen precision (half: 11 bits, ample for
/// both). Depth, positions, ids and counts are always 32-bit: half has integers exact only to
/// 2048 and a relative step of 1/1024, too coarse for world positions and object ids.
bool halfEligible(const FilmLayer& l) {
  return l.name.empty() || l.name == "albedo" || l.name == "N";
}

/// Layers holding colours in the working space, converted to the output colorspace.
bool isColourLayer(const FilmLayer& l) {
  return (l.name.empty() || l.name == "albedo") && l.channels.size() >= 3;
}

/// Opens `tmp` with the writer chosen by the real path's extension, writes, closes.
void writeFile(const std::string& path, const std::string& tmp, const OIIO::ImageSpec& spec,
               OIIO::TypeDesc bufferType, const void* pixels) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw Error(path + ": no image writer for this format: " + oneLine(OIIO::geterror()));
  if (!out->open(tmp, spec)) throw Error(path + ": " + oneLine(out->geterror()));
  bool ok = out->write_image(bufferType, pixels);
  ok = out->close() && ok;  // close() flushes: a full disk may only show here
  if (!ok) throw Error(path + ": writing failed: " + oneLine(out->geterror()));
}

/// Half's largest finite value; larger ones would become +Inf (and smaller ones -Inf).
constexpr float kHalfMax = 65504.0f;

/// Clamps every half channel's values to +-kHalfMax, each value on its own (a clamped pixel may
/// change hue; its other channels stay exact). Returns how many values were clamped.
size_t clampToHalf(std::vector<float>& pixels, const std::vector<OIIO::TypeDesc>& formats) {
  const size_t nc = formats.size();
  size_t clamped = 0;
  for (size_t c = 0; c < nc; ++c) {
    if (formats[c] != OIIO::TypeDesc::HALF) continue;
    for (size_t i = c; i < pixels.size(); i += nc) {
      float& v = pixels[i];
      if (v > kHalfMax || v < -kHalfMax) {  // NaN compares false: stays NaN
        v = v > 0 ? kHalfMax : -kHalfMax;
        ++clamped;
      }
    }
  }
  return clamped;
}

size_t writeExr(const Film& film, const std::string& path, const std::string& tmp,
                const ImageOutputOptions& o) {
  const ColorPipeline& color = ColorPipeline::instance();
  const std::string cs =
      color.canonicalName(o.colorspace.empty() ? color.defaultOutputSpace() : o.colorspace);
  std::vector<std::string> names;
  std::vector<OIIO::TypeDesc> formats;
  for (const FilmLayer& l : film.layers())
    for (const auto& c : l.channels) {
      names.push_back(exrChannelName(l, c));
      formats.push_back(halfEligible(l) && o.halfFloat ? OIIO::TypeDesc::HALF
                                                       : OIIO::TypeDesc::FLOAT);
    }
  OIIO::ImageSpec spec(film.width(), film.height(), int(names.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = names;
  spec.channelformats = formats;
  spec.alpha_channel = 3;  // the beauty layer (layer 0) is R, G, B, A: coverage
  // OpenEXR's dataWindow is the film; displayWindow the full image it belongs to.
  spec.x = o.xOffset, spec.y = o.yOffset;
  spec.full_x = 0, spec.full_y = 0;
  spec.full_width = o.fullWidth > 0 ? o.fullWidth : film.width();
  spec.full_height = o.fullHeight > 0 ? o.fullHeight : film.height();
  spec.attribute("compression", "zip");  // lossless; zip beats piz on noise-free renders

  // Interleave every layer into one pixel (beauty first), then convert the colour layers'
  // RGB (beauty and albedo) like the beauty, so the file's colorspace is true of both; the
  // other AOVs (normals, depth, positions, ids) are data.
  const size_t n = size_t(film.width()) * film.height(), nc = names.size();
  std::vector<float> pixels(n * nc);
  size_t offset = 0;
  for (const FilmLayer& l : film.layers()) {
    const size_t lc = l.channels.size();
    for (size_t p = 0; p < n; ++p)
      for (size_t c = 0; c < lc; ++c) pixels[p * nc + offset + c] = l.data[p * lc + c];
    if (isColourLayer(l)) color.convertFromWorking(pixels.data() + offset, n, int(nc), cs);
    offset += lc;
  }
  const size_t clamped = clampToHalf(pixels, formats);

  // The colorspace is named twice: OIIO's convention and a plain attribute for other readers;
  // chromaticities (OpenEXR standard attribute) let any reader interpret the primaries.
  spec.attribute("oiio:ColorSpace", cs);
  spec.attribute("colorspace", cs);
  if (auto xy = color.chromaticities(cs))
    spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), xy->data());
  for (const auto& [k, v] : o.stringMetadata) spec.attribute(k, v);
  for (const auto& [k, v] : film.metadata()) spec.attribute(k, v);  // e.g. Cryptomatte manifests
  for (const auto& [k, v] : o.floatMetadata) spec.attribute(k, v);
  for (const auto& [k, m] : o.matrixMetadata) spec.attribute(k, OIIO::TypeMatrix44, m.data());
  writeFile(path, tmp, spec, OIIO::TypeDesc::FLOAT, pixels.data());
  return clamped;
}

void writeDisplay(const Film& film, const std::string& path, const std::string& tmp,
                  const ImageOutputOptions& o) {
  // Beauty RGB only, opaque: EXR alpha is coverage with the background's light still in RGB,
  // which straight-alpha PNG cannot express, so a PNG shows what the EXR shows.
  const std::vector<unsigned char> bytes = displayBytes(film, Film::kBeauty, o.display, o.view);
  OIIO::ImageSpec spec(film.width(), film.height(), 3, OIIO::TypeDesc::UINT8);
  spec.attribute("compression", "jpeg:95");  // ignored by PNG
  for (const auto& [k, v] : o.stringMetadata) spec.attribute(k, v);
  writeFile(path, tmp, spec, OIIO::TypeDesc::UINT8, bytes.data());
}

}  // namespace

std::vector<unsigned char> displayBytes(const Film& film, int layer, const std::string& display,
                                        const std::string& view) {
  const size_t n = size_t(film.width()) * film.height();
  const FilmLayer& l = film.layers()[size_t(layer)];
  const size_t lc = l.channels.size();
  std::vector<float> rgb(n * 3);
  for (size_t p = 0; p < n; ++p)
    for (size_t c = 0; c < 3; ++c) rgb[p * 3 + c] = l.data[p * lc + (lc >= 3 ? c : 0)];
  ColorPipeline::instance().toDisplay(rgb.data(), n, 3, display, view);
  std::vector<unsigned char> bytes(n * 3);
  for (size_t i = 0; i < rgb.size(); ++i) {
    const float v = std::isfinite(rgb[i]) ? std::clamp(rgb[i], 0.0f, 1.0f) : 0.0f;
    bytes[i] = static_cast<unsigned char>(std::lround(v * 255.0f));
  }
  return bytes;
}

std::string exrChannelName(const FilmLayer& layer, const std::string& channel) {
  if (layer.name.empty()) return channel;
  if (layer.channels.size() == 1 && layer.channels[0] == layer.name) return channel;
  return layer.name + "." + channel;
}

std::string halfClampWarning(const std::string& path, size_t clamped) {
  return path + ": " + std::to_string(clamped) +
         " value(s) beyond half float's range clamped to +-65504 (use --float to keep them)";
}

bool isExrPath(const std::string& path) {
  return lowerExtension(path) == ".exr";
}

namespace {

/// The path's format, checked: true for EXR, false for PNG/JPEG; throws for anything else, a
/// missing folder or a path that is a folder.
bool checkPath(const std::string& path) {
  const std::string ext = lowerExtension(path);
  const bool exr = isExrPath(path), display = ext == ".png" || ext == ".jpg" || ext == ".jpeg";
  if (!exr && !display)
    throw Error(path + ": unsupported output format '" + ext + "' (use .exr, .png, .jpg or .jpeg)");
  const fs::path folder = fs::path(path).parent_path();
  std::error_code ec;
  if (!folder.empty() && !fs::is_directory(folder, ec))
    throw Error(path + ": folder '" + folder.string() + "' does not exist");
  if (fs::is_directory(path, ec)) throw Error(path + ": is a folder");
  return exr;
}

}  // namespace

void checkOutputs(const std::vector<std::string>& paths, const ImageOutputOptions& options) {
  // A colorspace named for EXR output is checked even when no output is an EXR: a mistyped
  // name is a mistake whether or not this run happens to use it (issue 40).
  if (!options.colorspace.empty()) {
    try {
      ColorPipeline::instance().check(options.colorspace);
    } catch (const Error& e) {
      throw Error(std::string("--output-colorspace: ") + e.what(), e.kind());
    }
  }
  for (const auto& path : paths) {
    const bool exr = checkPath(path);
    try {
      const ColorPipeline& color = ColorPipeline::instance();
      if (exr)
        color.check(options.colorspace.empty() ? color.defaultOutputSpace() : options.colorspace);
      else
        color.check("", options.display, options.view);
    } catch (const Error& e) {
      throw Error(path + ": " + e.what(), e.kind());
    }
  }
}

size_t writeImage(const Film& film, const std::string& path, const ImageOutputOptions& options) {
  return writeImages(film, {path}, options).front();
}

std::vector<size_t> writeImages(const Film& film, const std::vector<std::string>& paths,
                                const ImageOutputOptions& options) {
  if (options.fullWidth < 0 || options.fullHeight < 0)
    throw Error(paths.empty() ? "negative display window size"
                              : paths.front() + ": negative display window size");
  // Each file is written under a temporary name in its folder, and all are renamed into place
  // only once every one is complete: rename(2) is atomic within a file system, so readers never
  // see a partial image, and a failed write leaves every earlier file intact. Unique per
  // process and call.
  static std::atomic<unsigned> counter{0};
  std::vector<std::string> tmps;
  std::vector<size_t> clamped;
  auto removeTmps = [&] {
    std::error_code ignored;
    for (const auto& tmp : tmps) fs::remove(tmp, ignored);
  };
  for (const std::string& path : paths) {
    try {
      const bool exr = checkPath(path);
      tmps.push_back(path + ".tmp-" + std::to_string(getpid()) + "-" +
                     std::to_string(counter.fetch_add(1)));
      if (exr)
        clamped.push_back(writeExr(film, path, tmps.back(), options));
      else
        writeDisplay(film, path, tmps.back(), options), clamped.push_back(0);
    } catch (const Error& e) {
      removeTmps();
      // Colour errors do not know the file: give every message the "PATH: problem" form.
      const std::string what = e.what();
      if (what.rfind(path + ": ", 0) == 0) throw;
      throw Error(path + ": " + what, e.kind());
    } catch (...) {
      removeTmps();
      throw;
    }
  }
  for (size_t i = 0; i < paths.size(); ++i) {
    std::error_code ec;
    fs::rename(tmps[i], paths[i], ec);
    if (ec) {
      tmps.erase(tmps.begin(), tmps.begin() + long(i) + 1);
      removeTmps();
      throw Error(paths[i] + ": cannot move the finished file into place: " + ec.message());
    }
  }
  return clamped;
}

}  // namespace tray
