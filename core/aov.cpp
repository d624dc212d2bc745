#include "core/aov.h"

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
  };
  return s;
}

}  // namespace

const std::vector<std::string>& AovSet::known() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& s : specs()) n.push_back(s.name);
    n.push_back("crypto_object");  // core/cryptomatte.h
    n.push_back("crypto_material");
    return n;
  }();
  return names;
}

std::vector<std::string> AovSet::parse(const std::string& list) {
  if (list == "all") return known();
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
    bool ok = false;
    for (const auto& k : known()) ok = ok || k == item;
    if (!ok) {
      std::string names;
      for (const auto& k : known()) names += (names.empty() ? "" : ", ") + k;
      throw Error("--aov: unknown AOV '" + item + "' (known: " + names + ", cryptomatte, all)");
    }
    out.push_back(item);
  }
  return out;
}

AovSet::AovSet(Film& film, const std::vector<std::string>& names) {
  for (const auto& n : names)
    for (size_t i = 0; i < specs().size(); ++i)
      if (n == specs()[i].name)
        slots_.push_back({Kind(i), film.addLayer(specs()[i].layer, specs()[i].channels)});
}

void AovSet::write(Film& film, int x, int y, const PixelValue& v) const {
  const PrimaryHit& h = v.primary;
  for (const Slot& s : slots_) {
    float* p = film.pixel(s.layer, x, y);
    switch (s.kind) {
      case Kind::kDepth: p[0] = h.hit ? h.depth : kInfinity; break;
      case Kind::kNormal: p[0] = h.normal.x, p[1] = h.normal.y, p[2] = h.normal.z; break;
      case Kind::kPosition: p[0] = h.position.x, p[1] = h.position.y, p[2] = h.position.z; break;
      case Kind::kAlbedo: p[0] = h.albedo.x, p[1] = h.albedo.y, p[2] = h.albedo.z; break;
      case Kind::kObjectId: p[0] = float(h.objectId); break;
      case Kind::kMaterialId: p[0] = float(h.materialId); break;
      case Kind::kSamples: p[0] = float(v.samples); break;
    }
  }
}

}  // namespace tray
