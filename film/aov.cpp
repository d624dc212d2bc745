#include "film/aov.h"

#include <sstream>

#include "core/error.h"

namespace tray {
namespace {

struct AovSpec {
  const char* name;
  const char* layer;
  std::vector<std::string> channels;
};

const std::vector<AovSpec>& specs() {
  // Layer names as compositors expect them (Nuke/Houdini conventions: Z, N, P).
  static const std::vector<AovSpec> s = {
      {"depth", "Z", {"Z"}},
      {"normal", "N", {"X", "Y", "Z"}},
      {"position", "P", {"X", "Y", "Z"}},
      {"albedo", "albedo", {"R", "G", "B"}},
      {"objectid", "objectid", {"id"}},
      {"materialid", "materialid", {"id"}},
      {"samples", "samples", {"count"}},
      {"motion", "motion", {"u", "v"}},  // Nuke's motion layer (docs/aovs.md)
  };
  return s;
}

}  // namespace

/// Every AOV but the light paths: what "all" stands for.
const std::vector<std::string>& allButLightPaths() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& s : specs()) n.push_back(s.name);
    n.push_back("crypto_object");  // film/cryptomatte.h
    n.push_back("crypto_material");
    return n;
  }();
  return names;
}

int lightPathIndex(const std::string& name) {
  const auto& names = lightPathNames();
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return int(i);
  return -1;
}

const std::vector<std::string>& AovSet::known() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n = allButLightPaths();
    for (const auto& p : lightPathNames()) n.push_back(p);
    return n;
  }();
  return names;
}

bool AovSet::wantsLightPaths(const std::vector<std::string>& names) {
  for (const auto& n : names)
    if (lightPathIndex(n) >= 0) return true;
  return false;
}

std::vector<std::string> AovSet::parse(const std::string& list, bool lightPaths) {
  std::vector<std::string> out = parse(list);
  if (!lightPaths || wantsLightPaths(out)) return out;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ','))
    if (item == "all") {
      for (const auto& p : lightPathNames()) out.push_back(p);
      break;
    }
  return out;
}

std::vector<std::string> AovSet::parse(const std::string& list) {
  if (list == "all") return allButLightPaths();
  std::vector<std::string> out;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) continue;
    if (item == "cryptomatte") {
      out.push_back("crypto_object");
      out.push_back("crypto_material");
      continue;
    }
    if (item == "lightpaths") {
      for (const auto& p : lightPathNames()) out.push_back(p);
      continue;
    }
    if (item == "all") {
      for (const auto& a : allButLightPaths()) out.push_back(a);
      continue;
    }
    bool ok = false;
    for (const auto& k : known()) ok = ok || k == item;
    if (!ok) {
      std::string names;
      for (const auto& k : known()) names += (names.empty() ? "" : ", ") + k;
      throw Error("--aov: unknown AOV '" + item + "' (known: " + names +
                  ", cryptomatte, lightpaths, all)");
    }
    out.push_back(item);
  }
  return out;
}

AovSet::AovSet(Film& film, const std::vector<std::string>& names, const MotionVectors* vectors)
    : vectors_(vectors) {
  for (const auto& n : names) {
    for (size_t i = 0; i < specs().size(); ++i)
      if (n == specs()[i].name) {
        slots_.push_back({Kind(i), film.addLayer(specs()[i].layer, specs()[i].channels)});
        const Kind k = Kind(i);
        surface_ = surface_ || k == Kind::kDepth || k == Kind::kNormal || k == Kind::kAlbedo;
      }
    if (const int path = lightPathIndex(n); path >= 0) {
      slots_.push_back({Kind::kPath, film.addLayer(n, {"R", "G", "B"}), path});
      lightPaths_ = true;
    }
  }
}

void AovSet::configure(AovSums& sums) const {
  sums.lightPaths = lightPaths_;
  sums.surface = surface_;
}

void AovSet::write(Film& film, int x, int y, const PixelValue& v, const AovSums* sums) const {
  const PrimaryHit& h = v.primary;
  auto put = [](float* p, const Vec3& c) { p[0] = c.x, p[1] = c.y, p[2] = c.z; };
  for (const Slot& s : slots_) {
    float* p = film.pixel(s.layer, x, y);
    switch (s.kind) {
      case Kind::kDepth:
        p[0] = sums ? sums->meanDepth() : h.hit ? h.depth : kInfinity;
        break;
      case Kind::kNormal:
        put(p, sums ? sums->meanNormal() : h.normal);
        break;
      case Kind::kPosition:
        put(p, h.position);
        break;
      case Kind::kAlbedo:
        put(p, sums ? sums->meanAlbedo() : h.albedo);
        break;
      case Kind::kObjectId:
        p[0] = float(h.objectId);
        break;
      case Kind::kMaterialId:
        p[0] = float(h.materialId);
        break;
      case Kind::kSamples:
        p[0] = float(v.samples);
        break;
      case Kind::kMotion: {
        const Vec2 m = vectors_ ? vectors_->at(h) : Vec2{0, 0};
        p[0] = m.x, p[1] = m.y;
        break;
      }
      case Kind::kPath:
        put(p, sums ? sums->path(s.path) : Color(0.0f));
        break;
    }
  }
}

}  // namespace tray
