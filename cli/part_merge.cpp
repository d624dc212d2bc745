#include "cli/part_merge.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numeric>
#include <system_error>

#include "core/error.h"
#include "core/light_paths.h"
#include "film/render_state.h"
#include "render/job_diff.h"

namespace tray {
namespace {

using Layout = std::vector<std::pair<std::string, std::vector<std::string>>>;

/// What the merge needs of a part, from its header alone.
struct Part {
  std::string path;
  ExrHeader header;
  int samplesPerPixel = 0;  ///< of the job (0: the integrator places its own samples)
  int begin = 0, end = 0;   ///< sample range
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

Layout layout(const ExrHeader& h) {
  Layout l = h.layers();
  l.erase(
      std::remove_if(l.begin(), l.end(),
                     [](auto& x) { return x.first == kStateLayer || x.first == kProgressLayer; }),
      l.end());
  return l;
}

/// Layers the renderer averages over every sample (film/aov.h): sample-range parts merge into
/// their mean weighted by each part's filter-weight sum (depth: by its hit weight, the alpha
/// sum), as one machine would have averaged them (to the parts' float or half precision).
bool averagedLayer(const std::string& name) {
  const auto& paths = lightPathNames();
  return name == "albedo" || name == "N" || name == "Z" ||
         std::find(paths.begin(), paths.end(), name) != paths.end();
}

/// Filter-weighted sums of the averaged layers over the sample-range parts of each pixel.
struct LayerMeans {
  std::vector<std::vector<double>> sum, weight;  ///< per output layer; empty if not averaged
  std::vector<uint8_t> ranged;                   ///< pixel covered by sample-range parts
};

bool overlap(int a0, int a1, int b0, int b1) {
  return a0 < b1 && b0 < a1;
}

/// The header of a part, checked on its own: a complete part with a state layer.
Part loadHeader(const std::string& path) {
  Part p{path, readExrHeader(path)};
  const ImageOutputOptions& o = p.header.options;
  // Every number of the header that is used is checked first (a hostile or damaged part: the
  // ranges and counts below would be undefined conversions; the sums would be NaN metadata).
  constexpr int64_t kMaxInt = std::numeric_limits<int>::max();
  const int64_t spp = metadataCount(o, "tray:samplesPerPixel", -1, path, kMaxInt);
  if (spp < 0) throw Error(path + ": not a TRay part (no tray:samplesPerPixel)");
  p.samplesPerPixel = int(spp);
  metadataCount(o, "tray:samplesDone", 0, path);
  metadataAmount(o, "tray:renderSeconds", 0, path);
  metadataAmount(o, "tray:renderCpuSeconds", 0, path);
  const auto layers = p.header.layers();
  if (std::none_of(layers.begin(), layers.end(), [](auto& l) { return l.first == kStateLayer; }))
    throw Error(path +
                ": no render state (layer 'tray'): not a part (render it with --region or "
                "--sample-range)");
  const int64_t done = metadataCount(o, "tray:pixelsDone", -1, path);
  const int64_t total = metadataCount(o, "tray:pixelsTotal", -2, path);
  if (done != total || metadataString(o, "tray:status") != "complete")
    throw Error(path + ": unfinished part (" + std::to_string(done) + " of " +
                std::to_string(total) + " pixels): finish it with --resume");
  // Integrators that place their own samples (adaptive) have one whole "range" per pixel.
  const bool counted = spp > 0;
  p.begin = counted ? int(metadataCount(o, "tray:sampleBegin", 0, path, spp)) : 0;
  p.end = counted ? int(metadataCount(o, "tray:sampleEnd", 0, path, spp)) : 1;
  if (p.begin >= p.end)
    throw Error(path + ": its header's sample range " + std::to_string(p.begin) + ".." +
                std::to_string(p.end) + " holds no sample: an edited or damaged file");
  p.x0 = o.xOffset, p.y0 = o.yOffset;
  p.x1 = p.x0 + p.header.width, p.y1 = p.y0 + p.header.height;
  return p;
}

/// Every check that needs no pixels: one job, one image, the same layers, each sample of each
/// pixel in exactly one part.
void checkParts(const std::vector<Part>& parts) {
  const Part& ref = parts.front();
  const ImageOutputOptions& r = ref.header.options;
  const int width = r.fullWidth, height = r.fullHeight;
  const std::string job = metadataString(r, "tray:job");
  for (const Part& p : parts) {
    const std::string theirs = metadataString(p.header.options, "tray:job");
    if (const std::string d = jobDifference(job, theirs); !d.empty())
      throw Error(p.path + ": a part of another render than " + ref.path + " (tray:job: " + d +
                  ")");
    if (p.header.options.fullWidth != width || p.header.options.fullHeight != height ||
        p.x1 > width || p.y1 > height || p.x0 < 0 || p.y0 < 0)
      throw Error(p.path + ": its window does not fit the " + std::to_string(width) + "x" +
                  std::to_string(height) + " image of " + ref.path);
    if (layout(p.header) != layout(ref.header))
      throw Error(p.path + ": its layers differ from those of " + ref.path);
    if (p.samplesPerPixel != ref.samplesPerPixel)
      throw Error(p.path + ": " + std::to_string(p.samplesPerPixel) + " samples per pixel, " +
                  ref.path + " " + std::to_string(ref.samplesPerPixel));
  }
  for (size_t i = 0; i < parts.size(); ++i)
    for (size_t j = i + 1; j < parts.size(); ++j) {
      const Part &a = parts[i], &b = parts[j];
      if (overlap(a.x0, a.x1, b.x0, b.x1) && overlap(a.y0, a.y1, b.y0, b.y1) &&
          overlap(a.begin, a.end, b.begin, b.end))
        throw Error(b.path + ": renders pixels and samples that " + a.path + " renders too");
    }
  const int samples = ref.samplesPerPixel ? ref.samplesPerPixel : 1;
  // The parts' windows must add up to the image before anything of its size is allocated: a
  // header that claims a 200000x200000 image for 40x8 parts is refused here, not by the
  // memory (overlaps are refused above, so each pixel sample counts once). In doubles: exact
  // below 2^53, and a forged window times a forged range may go beyond 2^63.
  double held = 0;
  for (const Part& p : parts)
    held += double(p.x1 - p.x0) * double(p.y1 - p.y0) * double(p.end - p.begin);
  const double needed = double(width) * double(height) * double(samples);
  if (held < needed) {
    char counts[96];
    std::snprintf(counts, sizeof counts, "%.0f of the %dx%d image's %.0f", held, width, height,
                  needed);
    throw Error(std::string("the parts hold ") + counts + " pixel samples: a part is missing");
  }
  std::vector<int> covered(size_t(width) * height, 0);
  for (const Part& p : parts)
    for (int y = p.y0; y < p.y1; ++y)
      for (int x = p.x0; x < p.x1; ++x) covered[size_t(y) * width + x] += p.end - p.begin;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (covered[size_t(y) * width + x] != samples)
        throw Error("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") has " +
                    std::to_string(covered[size_t(y) * width + x]) + " of its " +
                    std::to_string(samples) + " samples in the parts: a part is missing");
}

/// Adds part `p`'s sums to `total` and its AOVs to `out` (averaged layers of a sample-range part
/// to `means`), reading it a band of rows at a time.
void addPart(const Part& p, int samples, Film& out, std::vector<PixelSums>& total,
             LayerMeans& means) {
  const bool ranged = p.end - p.begin != samples;
  constexpr int kBandRows = 16;
  ExrRowReader reader(p.path);
  const std::vector<std::string>& names = reader.header().channels;
  auto channel = [&](const std::string& name) {
    const auto at = std::find(names.begin(), names.end(), name);
    if (at == names.end()) throw Error(p.path + ": no channel " + name + ": a damaged part");
    return size_t(at - names.begin());
  };
  std::vector<size_t> state;  // file channel of each state word, then of `done`
  for (const std::string& c : stateChannels())
    state.push_back(channel(std::string(kStateLayer) + "." + c));
  enum class How { kCopy, kSum, kMean };
  struct Copy {
    size_t from;
    int layer, channel;
    How how;
  };
  // AOV channels: summed (samples), averaged over the parts (averaged layers of sample ranges)
  // or of sample 0 (the others).
  std::vector<Copy> copies;
  for (size_t l = 1; l < out.layers().size(); ++l) {
    const FilmLayer& layer = out.layers()[l];
    const How how = layer.name == "samples"              ? How::kSum
                    : ranged && !means.weight[l].empty() ? How::kMean
                                                         : How::kCopy;
    if (how == How::kCopy && p.begin != 0) continue;
    for (size_t c = 0; c < layer.channels.size(); ++c)
      copies.push_back({channel(exrChannelName(layer, layer.channels[c])), int(l), int(c), how});
  }
  const size_t nc = names.size();
  const int width = out.width(), partWidth = p.x1 - p.x0;
  std::vector<float> band;
  for (int row = 0; row < p.y1 - p.y0; row += kBandRows) {
    const int rows = std::min(kBandRows, p.y1 - p.y0 - row);
    reader.read(row, rows, band);
    for (int r = 0; r < rows; ++r)
      for (int px = 0; px < partWidth; ++px) {
        const float* src = &band[(size_t(r) * partWidth + px) * nc];
        float words[11];
        for (size_t w = 0; w < state.size(); ++w) words[w] = src[state[w]];
        const int x = p.x0 + px, y = p.y0 + row + r;
        const auto pixel = [&] {
          return p.path + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
        };
        PixelSums sums;
        bool done;
        try {
          sums = checkedSums(words), done = checkedFlag(words[10], "done");
        } catch (const Error& e) {
          throw Error(pixel() + " holds " + e.what() + ": a damaged part");
        }
        if (!done) throw Error(pixel() + " is not done although the part says it is complete");
        const size_t at = size_t(y) * width + x;
        total[at] += sums;
        if (ranged) means.ranged[at] = 1;
        for (const Copy& c : copies) {
          float& dst = out.pixel(c.layer, x, y)[c.channel];
          if (c.how == How::kMean) {
            const double w = out.layers()[size_t(c.layer)].name == "Z" ? sums.alpha : sums.weight;
            if (w == 0) continue;  // no samples (or no hit) here: nothing to average
            const size_t nc = out.layers()[size_t(c.layer)].channels.size();
            means.sum[size_t(c.layer)][at * nc + size_t(c.channel)] += w * src[c.from];
            if (c.channel == 0) means.weight[size_t(c.layer)][at] += w;
          } else {
            dst = c.how == How::kSum ? dst + src[c.from] : src[c.from];
          }
        }
      }
  }
}

}  // namespace

void checkMergeOutput(const std::vector<std::string>& parts, const std::string& output) {
  namespace fs = std::filesystem;
  for (const std::string& part : parts) {
    std::error_code ec;
    // equivalent() is false (with an error code) when the output does not exist yet.
    if (part == output || fs::equivalent(part, output, ec))
      throw Error(output + ": the output is also a part to merge: it would be replaced; " +
                      "choose another name",
                  Error::Kind::kInput);
  }
}

ExrImage mergeParts(const std::vector<std::string>& paths) {
  if (paths.empty()) throw Error("no parts to merge");
  // Every header first: a wrong part is refused before any pixel is read.
  std::vector<Part> parts;
  for (const auto& path : paths) parts.push_back(loadHeader(path));
  checkParts(parts);
  const ImageOutputOptions& r = parts.front().header.options;
  const int width = r.fullWidth, height = r.fullHeight;

  // Sample order: a pixel's sums are added as its samples come, whatever the argument order.
  std::stable_sort(parts.begin(), parts.end(),
                   [](const Part& a, const Part& b) { return a.begin < b.begin; });
  ExrImage out;
  out.film = Film(width, height);
  for (const auto& [name, channels] : layout(parts.front().header))
    if (!name.empty()) out.film.addLayer(name, channels);
  std::vector<PixelSums> total(size_t(width) * height);
  const int n = parts.front().samplesPerPixel;
  const size_t pixels = size_t(width) * height, layers = out.film.layers().size();
  LayerMeans means{std::vector<std::vector<double>>(layers),
                   std::vector<std::vector<double>>(layers), std::vector<uint8_t>(pixels, 0)};
  for (size_t l = 1; l < layers; ++l)
    if (averagedLayer(out.film.layers()[l].name)) {
      means.sum[l].assign(pixels * out.film.layers()[l].channels.size(), 0.0);
      means.weight[l].assign(pixels, 0.0);
    }
  for (const Part& p : parts) addPart(p, n ? n : 1, out.film, total, means);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const PixelSums& s = total[size_t(y) * width + x];
      const Color c = s.radiance();
      float* px = out.film.pixel(Film::kBeauty, x, y);
      px[0] = c.x, px[1] = c.y, px[2] = c.z, px[3] = s.coverage();
    }
  for (size_t l = 1; l < layers; ++l) {
    const size_t nc = out.film.layers()[l].channels.size();
    for (size_t at = 0; !means.weight[l].empty() && at < pixels; ++at) {
      if (!means.ranged[at]) continue;  // one part held all its samples: copied as it is
      const double w = means.weight[l][at];
      float* dst = out.film.pixel(int(l), int(at % width), int(at / width));
      for (size_t c = 0; c < nc; ++c)
        dst[c] = w != 0                             ? float(means.sum[l][at * nc + c] / w)
                 : out.film.layers()[l].name == "Z" ? kInfinity
                                                    : 0.0f;
    }
  }

  // Metadata of the job (all parts agree on it: precision and colorspace are in tray:job), with
  // what the parts did added up.
  auto sum = [&](const char* key) {
    return std::accumulate(parts.begin(), parts.end(), 0.0, [&](double s, const Part& p) {
      return s + metadataFloat(p.header.options, key, 0);
    });
  };
  out.options = r;
  out.options.xOffset = out.options.yOffset = 0;
  for (auto& [k, v] : out.options.floatMetadata) {
    if (k == "tray:renderSeconds" || k == "tray:renderCpuSeconds") v = float(sum(k.c_str()));
    if (k == "tray:samplesDone") v = float(sum("tray:samplesDone"));
    if (k == "tray:pixelsDone" || k == "tray:pixelsTotal") v = float(width) * height;
    if (k == "tray:sampleBegin") v = 0;
    if (k == "tray:sampleEnd") v = float(parts.front().samplesPerPixel);
  }
  for (auto& [k, v] : out.options.stringMetadata)
    if (k == "tray:status") v = "complete";
  out.options.stringMetadata.emplace_back("tray:mergedParts", std::to_string(parts.size()));
  return out;
}

}  // namespace tray
