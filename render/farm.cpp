#include "render/farm.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "integrators/registry.h"
#include "io/image_input.h"
#include "io/image_output.h"
#include "render/job_diff.h"

namespace tray {
namespace {

/// "a,b,..." as exactly `count` integers, or empty.
std::vector<int> parseInts(const std::string& text, size_t count) {
  std::vector<int> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    size_t used = 0;
    int value = 0;
    try {
      value = std::stoi(item, &used);
    } catch (const std::exception&) {
      return {};
    }
    if (used != item.size()) return {};
    v.push_back(value);
  }
  return v.size() == count && text.back() != ',' ? v : std::vector<int>{};
}

}  // namespace

std::string jobSignature(const RenderSettings& settings, const JobFrame& f) {
  std::string job = "scene=" + std::filesystem::path(f.scenePath).filename().string();
  job += " content=" + f.contentHash;
  job += " scene#=" + std::to_string(f.scene) + " camera=" + std::to_string(f.camera);
  job += " size=" + std::to_string(f.width) + "x" + std::to_string(f.height);
  // Every declared option that decides the pixels, of this render's integrator and the one it
  // wraps, by its command-line name: an option added to a table is in the signature at once.
  const RenderSettings bound = withIntegratorOptions(settings);
  for (const OptionSpec& spec : bound.declared())
    if (spec.affectsPixels)
      job += " " + spec.name + "=" + formatOptionValue(bound.value(spec.name));
  job += " accel=" + f.accelerator + " aov=" + f.aovs;
  job += " output=" + f.output + " version=" + TRAY_VERSION;
  return job;
}

std::string firstExr(const std::vector<std::string>& outputs) {
  for (const auto& p : outputs)
    if (isExrPath(p)) return p;
  return "";
}

PixelRegion parseRegion(const std::string& text, int width, int height) {
  if (text.empty()) return {0, 0, width, height};
  const std::vector<int> v = parseInts(text, 4);
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (v.empty())
    throw Error("--region " + text + ": expected x0,y0,x1,y1 (pixels, x1 and y1 exclusive)");
  PixelRegion r{v[0], v[1], v[2], v[3]};
  if (r.x0 < 0 || r.y0 < 0 || r.x1 > width || r.y1 > height || r.x0 >= r.x1 || r.y0 >= r.y1)
    throw Error("--region " + text + ": not a non-empty region of the " + size +
                " image (0 <= x0 < x1 <= " + std::to_string(width) +
                ", 0 <= y0 < y1 <= " + std::to_string(height) + ")");
  return r;
}

SampleRange parseSampleRange(const std::string& text, std::optional<int> samplesPerPixel,
                             const std::string& integrator) {
  if (text.empty()) return {0, samplesPerPixel.value_or(0)};
  if (!samplesPerPixel)
    throw Error("--sample-range: the " + integrator +
                " integrator places its own samples in each pixel, so its renders cannot be split "
                "by samples (split them with --region)");
  const std::vector<int> v = parseInts(text, 2);
  if (v.empty()) throw Error("--sample-range " + text + ": expected a,b (samples a..b-1)");
  if (v[0] < 0 || v[0] >= v[1] || v[1] > *samplesPerPixel)
    throw Error("--sample-range " + text + ": expected 0 <= a < b <= " +
                std::to_string(*samplesPerPixel) + " (the samples per pixel)");
  return {v[0], v[1]};
}

bool loadCheckpoint(const std::string& path, const std::string& job, const PixelRegion& region,
                    int width, int height, const SampleRange& range, Film& film, RenderState& state,
                    RenderTime& previous) {
  // The header first: a checkpoint of another job, size or region is refused before its pixels
  // are read (a forged data window would size them).
  const ExrHeader head = readExrHeader(path);
  const ImageOutputOptions& h = head.options;
  const std::string theirs = metadataString(h, "tray:job");
  if (const std::string d = jobDifference(job, theirs); !d.empty())
    throw Error(path + ": the checkpoint is of another render (tray:job: " + d + ")");
  if (h.fullWidth != width || h.fullHeight != height || h.xOffset != region.x0 ||
      h.yOffset != region.y0 || head.width != region.width() || head.height != region.height())
    throw Error(path + ": the checkpoint covers another region or image size");
  ExrImage image = readExr(path);
  const ImageOutputOptions& o = image.options;
  if (image.film.width() != region.width() || image.film.height() != region.height())
    throw Error(path + ": the checkpoint changed while it was read");
  if (metadataFloat(o, "tray:sampleBegin", -1) != float(range.begin) ||
      metadataFloat(o, "tray:sampleEnd", -1) != float(range.end))
    throw Error(path + ": the checkpoint renders another sample range");
  // A finished full render keeps no state: a requeued job that already ended has nothing to do.
  if (image.film.findLayer(kStateLayer) < 0 && metadataString(o, "tray:status") == "complete")
    return false;
  try {
    state = loadState(image.film);
  } catch (const Error& e) {
    throw Error(path + ": " + e.what() + ": not a checkpoint");
  }
  // The done channel against the header written with it (issue 40: a channel edited to mark
  // pixels done that were never rendered resumed, and the image was labelled complete). Both
  // counts as the writer stored them: float(done).
  const int64_t header = metadataCount(o, "tray:pixelsDone", -1, path);
  if (float(state.pixelsDone()) != float(header))
    throw Error(path + ": the checkpoint's tray.done channel marks " +
                std::to_string(state.pixelsDone()) + " pixels done, its header " +
                (header < 0 ? std::string("none") : std::to_string(header)) +
                ": edited or damaged; remove it to render from the start");
  previous = {metadataAmount(o, "tray:renderSeconds", 0, path),
              metadataAmount(o, "tray:renderCpuSeconds", 0, path)};
  // The film without the state layer: it is written again only if the render stays partial.
  film = Film(image.film.width(), image.film.height());
  for (size_t l = 1; l < image.film.layers().size(); ++l) {
    const FilmLayer& from = image.film.layers()[l];
    if (from.name == kStateLayer || from.name == kProgressLayer) continue;
    const int to = film.addLayer(from.name, from.channels);
    std::copy(from.data.begin(), from.data.end(), film.pixel(to, 0, 0));
  }
  return true;
}

}  // namespace tray
