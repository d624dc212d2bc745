#include "film/render_state.h"

#include <algorithm>
#include <cstring>

#include "core/error.h"

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

void storeState(const RenderState& state, Film& film) {
  const size_t n = size_t(film.width()) * film.height();
  if (state.sums.size() != n || state.done.size() != n)
    throw Error("render state does not match the film size", Error::Kind::kRender);
  const int layer = film.addLayer(kStateLayer, stateChannels());
  for (size_t p = 0; p < n; ++p) {
    float* out = film.pixel(layer, int(p % film.width()), int(p / film.width()));
    const PixelSums& s = state.sums[p];
    split(s.rgb[0], out), split(s.rgb[1], out + 2), split(s.rgb[2], out + 4);
    split(s.alpha, out + 6), split(s.weight, out + 8);
    out[10] = state.done[p] ? 1.0f : 0.0f;
  }
}

RenderState loadState(const Film& film) {
  // Channels may come back in another order (OpenEXR sorts them by name): look each one up.
  const int layer = film.findLayer(kStateLayer);
  std::vector<size_t> at;
  if (layer >= 0)
    for (const auto& name : stateChannels()) {
      const auto& have = film.layers()[layer].channels;
      at.push_back(size_t(std::find(have.begin(), have.end(), name) - have.begin()));
      if (at.back() == have.size()) at.clear();
      if (at.empty()) break;
    }
  if (at.size() != stateChannels().size())
    throw Error("no render state (layer '" + std::string(kStateLayer) + "')");
  const size_t n = size_t(film.width()) * film.height();
  RenderState state = RenderState::empty(n);
  for (size_t p = 0; p < n; ++p) {
    const float* px = film.pixel(layer, int(p % film.width()), int(p / film.width()));
    float in[11];
    for (size_t c = 0; c < 11; ++c) in[c] = px[at[c]];
    state.sums[p] = joinSums(in);
    state.done[p] = in[10] != 0.0f;
  }
  return state;
}

}  // namespace tray
