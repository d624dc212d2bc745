#include "core/light_paths.h"

namespace tray {
namespace {

/// Per channel, each kind's share of the split's total (shares sum to 1; a channel the BSDF
/// does not reflect at all goes to diffuse, so that nothing is ever lost).
void sharesOf(const LobeSplit& s, Color share[3]) {
  for (int c = 0; c < 3; ++c) {
    const float d = s.diffuse[c], g = s.specular[c], t = s.transmission[c];
    const float sum = d + g + t;
    if (sum > 0) {
      share[0][c] = d / sum, share[1][c] = g / sum, share[2][c] = t / sum;
    } else {
      share[0][c] = 1, share[1][c] = 0, share[2][c] = 0;
    }
  }
}

}  // namespace

const char* lightPathName(LightPath p) {
  switch (p) {
    case LightPath::kDiffuseDirect: return "diffuse_direct";
    case LightPath::kDiffuseIndirect: return "diffuse_indirect";
    case LightPath::kSpecularDirect: return "specular_direct";
    case LightPath::kSpecularIndirect: return "specular_indirect";
    case LightPath::kTransmission: return "transmission";
    case LightPath::kEmission: return "emission";
    case LightPath::kBackground: return "background";
    case LightPath::kCount: break;
  }
  return "";
}

const std::vector<std::string>& lightPathNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (int i = 0; i < kLightPathCount; ++i) n.push_back(lightPathName(LightPath(i)));
    return n;
  }();
  return names;
}

LobeSplit LightPathSplitter::deltaLobe(bool transmission) {
  LobeSplit s;
  (transmission ? s.transmission : s.specular) = Color(1.0f);
  return s;
}

void LightPathSplitter::addShared(const Color& c, const Color share[3], bool direct) {
  auto& r = out_->radiance;
  r[int(direct ? LightPath::kDiffuseDirect : LightPath::kDiffuseIndirect)] += c * share[0];
  r[int(direct ? LightPath::kSpecularDirect : LightPath::kSpecularIndirect)] += c * share[1];
  r[int(LightPath::kTransmission)] += c * share[2];
}

void LightPathSplitter::addFound(const Color& c, bool environment) {
  if (!out_) return;
  if (scatterings_ == 0) {
    out_->radiance[int(environment ? LightPath::kBackground : LightPath::kEmission)] += c;
    return;
  }
  // Found by the ray leaving the first scattering: direct light (emitters and the environment
  // are lights); any later: indirect.
  addShared(c, share_, scatterings_ == 1);
}

void LightPathSplitter::addLightSample(const Color& c, const LobeSplit& toLight,
                                       bool atFirstVertex) {
  if (!out_) return;
  // A later vertex's sample takes the first scattering's shares, fixed once it happened.
  if (!atFirstVertex) return addShared(c, share_, false);
  Color share[3];
  sharesOf(toLight, share);
  addShared(c, share, true);
}

void LightPathSplitter::scattered(const LobeSplit& lobes) {
  if (!out_) return;
  if (scatterings_ == 0) sharesOf(lobes, share_);
  ++scatterings_;
}

}  // namespace tray
