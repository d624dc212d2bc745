#include "film/render_state.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <iterator>
#include <string>

#include "core/error.h"
#include "core/options.h"

namespace tray {
namespace {

/// A double as two float32 bit patterns (memcpy: no conversion, NaN patterns included).
void split(double d, float* out) {
  uint64_t bits;
  std::memcpy(&bits, &d, 8);
  const uint32_t hi = uint32_t(bits >> 32), lo = uint32_t(bits);
  std::memcpy(out, &hi, 4);
  std::memcpy(out + 1, &lo, 4);
}

/// A stored number as a user reads it (4.5, nan, inf, 1e+30): the options' shortest text.
std::string shown(float v) {
  return formatOptionValue(OptionValue(v));
}

double join(const float* in) {
  uint32_t hi, lo;
  std::memcpy(&hi, in, 4);
  std::memcpy(&lo, in + 1, 4);
  const uint64_t bits = uint64_t(hi) << 32 | lo;
  double d;
  std::memcpy(&d, &bits, 8);
  return d;
}

}  // namespace

const std::vector<std::string>& stateChannels() {
  static const std::vector<std::string> c = {"Rh", "Rl", "Gh", "Gl", "Bh",  "Bl",
                                             "Ah", "Al", "Wh", "Wl", "done"};
  return c;
}

PixelSums joinSums(const float* in) {
  PixelSums s;
  s.rgb[0] = join(in), s.rgb[1] = join(in + 2), s.rgb[2] = join(in + 4);
  s.alpha = join(in + 6), s.weight = join(in + 8);
  return s;
}

PixelSums checkedSums(const float* words) {
  const PixelSums s = joinSums(words);
  // What a render can sum: float samples (at most FLT_MAX, filter weights at most about 1) over
  // at most 2^32 samples. A float NaN or infinity written into a high word is a finite double
  // of about 2^1020, so the bound catches those edits too.
  constexpr double kMostARenderSums = double(FLT_MAX) * 4294967296.0;
  const double all[] = {s.rgb[0], s.rgb[1], s.rgb[2], s.alpha, s.weight};
  if (!std::all_of(std::begin(all), std::end(all),
                   [](double d) { return std::abs(d) <= kMostARenderSums; }))
    throw Error("sums that no render makes (not finite, or beyond 2^32 times the largest float)");
  return s;
}

bool checkedFlag(float word, const char* name) {
  if (word != 0.0f && word != 1.0f)
    throw Error(std::string(name) + " " + shown(word) + ", neither 0 nor 1");
  return word == 1.0f;
}

RenderState RenderState::empty(size_t pixels) {
  RenderState s;
  s.sums.resize(pixels);
  s.done.assign(pixels, 0);
  return s;
}

size_t RenderState::pixelsDone() const {
  size_t n = 0;
  for (uint8_t d : done) n += d;
  return n;
}

namespace {

/// The progress layer's channels: the half buffer's words, then count and pending.
const std::vector<std::string>& progressChannels() {
  static const std::vector<std::string> c = {"Rh", "Rl", "Gh", "Gl", "Bh",    "Bl",
                                             "Ah", "Al", "Wh", "Wl", "count", "pending"};
  return c;
}

void splitSums(const PixelSums& s, float* out) {
  split(s.rgb[0], out), split(s.rgb[1], out + 2), split(s.rgb[2], out + 4);
  split(s.alpha, out + 6), split(s.weight, out + 8);
}

/// Where each of `names` is among the channels of `film`'s layer `name` (OpenEXR may have
/// sorted them by name); empty when the layer or a channel is missing.
std::vector<size_t> channelsOf(const Film& film, const char* name,
                               const std::vector<std::string>& names, int& layer) {
  layer = film.findLayer(name);
  std::vector<size_t> at;
  if (layer < 0) return at;
  const auto& have = film.layers()[layer].channels;
  for (const auto& c : names) {
    at.push_back(size_t(std::find(have.begin(), have.end(), c) - have.begin()));
    if (at.back() == have.size()) return {};
  }
  return at;
}

/// Reads layer `layer`'s channels `at` of pixel p into `in`.
void readPixel(const Film& film, int layer, const std::vector<size_t>& at, size_t p, float* in) {
  const float* px = film.pixel(layer, int(p % film.width()), int(p / film.width()));
  for (size_t c = 0; c < at.size(); ++c) in[c] = px[at[c]];
}

}  // namespace

void storeState(const RenderState& state, Film& film) {
  const size_t n = size_t(film.width()) * film.height();
  if (state.sums.size() != n || state.done.size() != n ||
      (!state.progress.empty() && state.progress.size() != n))
    throw Error("render state does not match the film size", Error::Kind::kRender);
  const int layer = film.addLayer(kStateLayer, stateChannels());
  for (size_t p = 0; p < n; ++p) {
    float* out = film.pixel(layer, int(p % film.width()), int(p / film.width()));
    splitSums(state.sums[p], out);
    out[10] = state.done[p] ? 1.0f : 0.0f;
  }
  if (state.progress.empty() || state.pixelsDone() == n) return;
  const int progress = film.addLayer(kProgressLayer, progressChannels());
  for (size_t p = 0; p < n; ++p) {
    float* out = film.pixel(progress, int(p % film.width()), int(p / film.width()));
    const PixelProgress& g = state.progress[p];
    splitSums(g.half, out);
    out[10] = float(g.count);  // at most 2^20 (--spp): exact
    out[11] = g.pending ? 1.0f : 0.0f;
  }
}

RenderState loadState(const Film& film) {
  int layer = -1;
  const std::vector<size_t> at = channelsOf(film, kStateLayer, stateChannels(), layer);
  if (at.empty()) throw Error("no render state (layer '" + std::string(kStateLayer) + "')");
  const size_t n = size_t(film.width()) * film.height();
  RenderState state = RenderState::empty(n);
  float in[12];
  // Which pixel holds a damaged word (the caller names the file).
  const auto where = [&](size_t p) {
    return "pixel (" + std::to_string(p % film.width()) + ", " + std::to_string(p / film.width()) +
           ") holds ";
  };
  for (size_t p = 0; p < n; ++p) {
    readPixel(film, layer, at, p, in);
    try {
      state.sums[p] = checkedSums(in);
      state.done[p] = checkedFlag(in[10], "done");
    } catch (const Error& e) {
      throw Error(where(p) + e.what());
    }
  }
  int progress = -1;
  const std::vector<size_t> g = channelsOf(film, kProgressLayer, progressChannels(), progress);
  if (g.empty()) return state;
  state.progress.resize(n);
  for (size_t p = 0; p < n; ++p) {
    readPixel(film, progress, g, p, in);
    PixelProgress& out = state.progress[p];
    try {
      if (!(in[10] >= 0 && in[10] <= float(1 << 20)) || in[10] != std::floor(in[10]))
        throw Error("a sample count that is not one (" + shown(in[10]) + ")");
      out.count = uint32_t(in[10]);
      out.half = checkedSums(in);
      out.pending = checkedFlag(in[11], "pending");
    } catch (const Error& e) {
      throw Error(where(p) + "in the progress layer " + e.what());
    }
  }
  return state;
}

}  // namespace tray
