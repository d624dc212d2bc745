#include "cli/part_merge.h"

#include <algorithm>
#include <numeric>

#include "core/error.h"
#include "core/light_paths.h"
#include "core/render_state.h"

namespace tray {
namespace {

struct Part {
  std::string path;
  ExrImage image;
  RenderState state;
  int begin = 0, end = 0;  ///< sample range
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

std::vector<std::pair<std::string, std::vector<std::string>>> layout(const Film& f) {
  std::vector<std::pair<std::string, std::vector<std::string>>> l;
  for (const FilmLayer& layer : f.layers())
    if (layer.name != kStateLayer) l.emplace_back(layer.name, layer.channels);
  return l;
}

/// Layers the renderer averages over every sample (core/aov.h): sample-range parts merge into
/// their mean weighted by each part's filter-weight sum (depth: by its hit weight, the alpha
/// sum), as one machine would have averaged them (to the parts' float or half precision).
bool averagedLayer(const std::string& name) {
  const auto& paths = lightPathNames();
  return name == "albedo" || name == "N" || name == "Z" ||
         std::find(paths.begin(), paths.end(), name) != paths.end();
}

/// Filter-weighted sums of one averaged layer over the sample-range parts of each pixel.
struct LayerMean {
  std::vector<double> sum, weight;
};

bool overlap(int a0, int a1, int b0, int b1) {
  return a0 < b1 && b0 < a1;
}

Part load(const std::string& path, int samplesPerPixel) {
  Part p{path, readExr(path), {}, 0, 0, 0, 0, 0, 0};
  try {
    p.state = loadState(p.image.film);
  } catch (const Error& e) {
    throw Error(path + ": " + e.what() +
                ": not a part (render it with --region or --sample-range)");
  }
  if (p.state.pixelsDone() != p.state.done.size())
    throw Error(path + ": unfinished part (" + std::to_string(p.state.pixelsDone()) + " of " +
                std::to_string(p.state.done.size()) + " pixels): finish it with --resume");
  const ImageOutputOptions& o = p.image.options;
  // Integrators that place their own samples (adaptive) have one whole "range" per pixel.
  p.begin = samplesPerPixel ? int(metadataFloat(o, "tray:sampleBegin", 0)) : 0;
  p.end = samplesPerPixel ? int(metadataFloat(o, "tray:sampleEnd", 0)) : 1;
  p.x0 = o.xOffset, p.y0 = o.yOffset;
  p.x1 = p.x0 + p.image.film.width(), p.y1 = p.y0 + p.image.film.height();
  return p;
}

}  // namespace

ExrImage mergeParts(const std::vector<std::string>& paths) {
  if (paths.empty()) throw Error("no parts to merge");
  const ExrImage first = readExr(paths.front());
  const int n = int(metadataFloat(first.options, "tray:samplesPerPixel", -1));
  if (n < 0) throw Error(paths.front() + ": not a TRay part (no tray:samplesPerPixel)");
  std::vector<Part> parts;
  for (const auto& path : paths) parts.push_back(load(path, n));

  const Part& ref = parts.front();
  const int width = ref.image.options.fullWidth, height = ref.image.options.fullHeight;
  const std::string job = metadataString(ref.image.options, "tray:job");
  const int samples = n ? n : 1;
  for (const Part& p : parts) {
    if (metadataString(p.image.options, "tray:job") != job)
      throw Error(p.path + ": a part of another render than " + ref.path + " (tray:job differs)");
    if (p.image.options.fullWidth != width || p.image.options.fullHeight != height ||
        p.x1 > width || p.y1 > height || p.x0 < 0 || p.y0 < 0)
      throw Error(p.path + ": its window does not fit the " + std::to_string(width) + "x" +
                  std::to_string(height) + " image of " + ref.path);
    if (layout(p.image.film) != layout(ref.image.film))
      throw Error(p.path + ": its layers differ from those of " + ref.path);
  }
  for (size_t i = 0; i < parts.size(); ++i)
    for (size_t j = i + 1; j < parts.size(); ++j) {
      const Part &a = parts[i], &b = parts[j];
      if (overlap(a.x0, a.x1, b.x0, b.x1) && overlap(a.y0, a.y1, b.y0, b.y1) &&
          overlap(a.begin, a.end, b.begin, b.end))
        throw Error(b.path + ": renders pixels and samples that " + a.path + " renders too");
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

  // Sample order: a pixel's sums are added as its samples come, whatever the argument order.
  std::stable_sort(parts.begin(), parts.end(),
                   [](const Part& a, const Part& b) { return a.begin < b.begin; });
  ExrImage out;
  out.film = Film(width, height);
  for (const auto& [name, channels] : layout(ref.image.film))
    if (!name.empty()) out.film.addLayer(name, channels);
  std::vector<PixelSums> total(size_t(width) * height);
  std::vector<LayerMean> means(out.film.layers().size());
  for (size_t l = 1; l < means.size(); ++l)
    if (averagedLayer(out.film.layers()[l].name)) {
      means[l].sum.assign(size_t(width) * height * out.film.layers()[l].channels.size(), 0.0);
      means[l].weight.assign(size_t(width) * height, 0.0);
    }
  std::vector<uint8_t> ranged(size_t(width) * height, 0);  // covered by sample-range parts
  std::vector<float> seconds;
  for (const Part& p : parts) {
    const Film& f = p.image.film;
    seconds.push_back(metadataFloat(p.image.options, "tray:renderSeconds", 0));
    std::vector<int> from;  // the part's layer for each output layer
    for (const FilmLayer& layer : out.film.layers()) from.push_back(f.findLayer(layer.name));
    for (int y = p.y0; y < p.y1; ++y)
      for (int x = p.x0; x < p.x1; ++x) {
        const int px = x - p.x0, py = y - p.y0;
        const size_t at = size_t(y) * width + x;
        const PixelSums& sums = p.state.sums[size_t(py) * f.width() + px];
        total[at] += sums;
        ranged[at] = p.end - p.begin != samples;
        for (size_t l = 1; l < out.film.layers().size(); ++l) {
          const FilmLayer& layer = out.film.layers()[l];
          const float* src = f.pixel(from[l], px, py);
          float* dst = out.film.pixel(int(l), x, y);
          const size_t nc = layer.channels.size();
          if (!means[l].weight.empty() && p.end - p.begin != samples) {  // a sample range
            const double w = layer.name == "Z" ? sums.alpha : sums.weight;
            if (w == 0) continue;  // no samples (or no hit) here: nothing to average
            for (size_t c = 0; c < nc; ++c) means[l].sum[at * nc + c] += w * src[c];
            means[l].weight[at] += w;
            continue;
          }
          for (size_t c = 0; c < nc; ++c)
            if (layer.name == "samples")
              dst[c] += src[c];  // camera rays: every part's count
            else if (p.begin == 0)
              dst[c] = src[c];  // first-hit AOVs: of sample 0, as one machine writes them
        }
      }
  }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const PixelSums& s = total[size_t(y) * width + x];
      const Color c = s.radiance();
      float* px = out.film.pixel(Film::kBeauty, x, y);
      px[0] = c.x, px[1] = c.y, px[2] = c.z, px[3] = s.coverage();
    }
  for (size_t l = 1; l < means.size(); ++l) {
    const LayerMean& m = means[l];
    const size_t nc = out.film.layers()[l].channels.size();
    for (size_t at = 0; !m.weight.empty() && at < size_t(width) * height; ++at) {
      if (!ranged[at]) continue;  // one part held all its samples: copied as it is
      float* dst = out.film.pixel(int(l), int(at % width), int(at / width));
      for (size_t c = 0; c < nc; ++c)
        dst[c] = m.weight[at] != 0 ? float(m.sum[at * nc + c] / m.weight[at])
                 : out.film.layers()[l].name == "Z" ? kInfinity : 0.0f;
    }
  }

  out.options = ref.image.options;
  out.options.xOffset = out.options.yOffset = 0;
  for (auto& [k, v] : out.options.floatMetadata) {
    if (k == "tray:renderSeconds") v = std::accumulate(seconds.begin(), seconds.end(), 0.0f);
    if (k == "tray:pixelsDone" || k == "tray:pixelsTotal") v = float(width) * height;
    if (k == "tray:sampleBegin") v = 0;
    if (k == "tray:sampleEnd") v = float(n);
  }
  for (auto& [k, v] : out.options.stringMetadata)
    if (k == "tray:status") v = "complete";
  out.options.stringMetadata.emplace_back("tray:mergedParts", std::to_string(parts.size()));
  return out;
}

}  // namespace tray
