#include "film/cryptomatte.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>

#include "core/error.h"

namespace tray {
namespace {

uint32_t rotl(uint32_t x, int r) {
  return (x << r) | (x >> (32 - r));
}

std::string hex8(uint32_t v) {
  char s[9];
  std::snprintf(s, sizeof s, "%08x", v);
  return s;
}

struct Ranked {
  float id;
  double weight;
};

}  // namespace

uint32_t murmurHash3_32(std::string_view key, uint32_t seed) {
  constexpr uint32_t c1 = 0xcc9e2d51, c2 = 0x1b873593;
  const auto* data = reinterpret_cast<const unsigned char*>(key.data());
  const size_t len = key.size(), blocks = len / 4;
  uint32_t h = seed;
  for (size_t i = 0; i < blocks; ++i) {
    // Blocks are read little-endian, as the reference does on x86.
    const unsigned char* p = data + 4 * i;
    uint32_t k = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
    k *= c1, k = rotl(k, 15), k *= c2;
    h ^= k, h = rotl(h, 13), h = h * 5 + 0xe6546b64;
  }
  const unsigned char* tail = data + 4 * blocks;
  uint32_t k = 0;
  switch (len & 3) {
    case 3:
      k ^= uint32_t(tail[2]) << 16;
      [[fallthrough]];
    case 2:
      k ^= uint32_t(tail[1]) << 8;
      [[fallthrough]];
    case 1:
      k ^= tail[0], k *= c1, k = rotl(k, 15), k *= c2, h ^= k;
  }
  h ^= uint32_t(len);
  // fmix32: the finaliser that makes every input bit affect every output bit.
  h ^= h >> 16, h *= 0x85ebca6b, h ^= h >> 13, h *= 0xc2b2ae35, h ^= h >> 16;
  return h;
}

float cryptomatteId(uint32_t hash) {
  const uint32_t exponent = std::clamp((hash >> 23) & 0xffu, 1u, 254u);
  return std::bit_cast<float>((hash & 0x807fffffu) | exponent << 23);
}

std::string cryptomatteObjectName(const Primitive& p) {
  return p.name.empty() ? "node" + std::to_string(p.objectId) : p.name;  // as Scene::objectName
}

std::string cryptomatteMaterialName(const Scene& scene, int material) {
  const std::string& name = scene.materials[size_t(material)].name;
  return name.empty() ? "material" + std::to_string(material) : name;
}

std::string Cryptomatte::metadataKey(std::string_view typeName) {
  return hex8(murmurHash3_32(typeName)).substr(0, 7);
}

bool Cryptomatte::requested(const std::vector<std::string>& aovs) {
  return std::find(aovs.begin(), aovs.end(), "crypto_object") != aovs.end() ||
         std::find(aovs.begin(), aovs.end(), "crypto_material") != aovs.end();
}

Cryptomatte::Cryptomatte(Film& film, const Scene& scene, const std::vector<std::string>& aovs,
                         int ranks)
    : ranks_(ranks) {
  const bool objects = std::find(aovs.begin(), aovs.end(), "crypto_object") != aovs.end();
  const bool materials = std::find(aovs.begin(), aovs.end(), "crypto_material") != aovs.end();
  if (!objects && !materials) return;
  if (ranks < 1 || ranks > kMaxRanks)
    throw Error("Cryptomatte ranks " + std::to_string(ranks) + ": expected 1.." +
                std::to_string(kMaxRanks));
  for (bool isObjects : {true, false}) {
    if (!(isObjects ? objects : materials)) continue;
    const std::string typeName = isObjects ? "CryptoObject" : "CryptoMaterial";
    // id -> name; the manifest is keyed by name (sorted, so files are reproducible).
    std::map<int, std::string> names;
    if (isObjects)
      for (uint32_t i = 0; i < scene.primitives.size(); ++i)
        for (uint32_t k = 0; k < scene.primitives[i].instanceCount(); ++k)  // arrays: each
          names.emplace(scene.objectId(i, k), scene.objectName(i, k));
    else
      for (size_t m = 0; m < scene.materials.size(); ++m)
        names.emplace(int(m), cryptomatteMaterialName(scene, int(m)));
    Type type{isObjects, {}, -1};
    std::map<std::string, std::string> manifest;
    for (const auto& [id, name] : names) {
      const float value = cryptomatteId(name);
      type.ids.push_back({id, value});
      manifest[name] = hex8(std::bit_cast<uint32_t>(value));
    }
    for (int layer = 0; layer < (ranks + 1) / 2; ++layer) {
      char suffix[3];
      std::snprintf(suffix, sizeof suffix, "%02d", layer);
      const int index = film.addLayer(typeName + suffix, {"R", "G", "B", "A"});
      if (layer == 0) type.firstLayer = index;
    }
    const std::string prefix = "cryptomatte/" + metadataKey(typeName) + "/";
    film.setMetadata(prefix + "name", typeName);
    film.setMetadata(prefix + "hash", "MurmurHash3_32");
    film.setMetadata(prefix + "conversion", "uint32_to_float32");
    // Names are UTF-8 from JSON already; replace keeps a stray invalid byte from throwing.
    film.setMetadata(
        prefix + "manifest",
        nlohmann::json(manifest).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    types_.push_back(std::move(type));
  }
}

float Cryptomatte::lookup(const std::vector<IdName>& ids, int id) {
  auto it =
      std::lower_bound(ids.begin(), ids.end(), id, [](const IdName& e, int v) { return e.id < v; });
  return it != ids.end() && it->id == id ? it->value : 0.0f;  // unknown or background: 0
}

void Cryptomatte::write(Film& film, int x, int y, const IdCoverage& coverage) const {
  std::vector<Ranked> ranked;
  for (const Type& type : types_) {
    ranked.clear();
    // Distinct ids may share a name, hence a value: their weights add up (the specification's
    // "Where these string values overlap, the IDs will be combined").
    for (const auto& e : type.objects ? coverage.objects : coverage.materials) {
      const float value = lookup(type.ids, e.id);
      auto same = std::find_if(ranked.begin(), ranked.end(),
                               [&](const Ranked& r) { return r.id == value; });
      if (same != ranked.end())
        same->weight += e.weight;
      else
        ranked.push_back({value, e.weight});
    }
    // Highest coverage first; equal coverages by id bits, so the order never depends on the
    // order samples arrived in.
    std::sort(ranked.begin(), ranked.end(), [](const Ranked& a, const Ranked& b) {
      if (a.weight != b.weight) return a.weight > b.weight;
      return std::bit_cast<uint32_t>(a.id) < std::bit_cast<uint32_t>(b.id);
    });
    const double norm = coverage.total != 0 ? 1.0 / coverage.total : 0.0;
    for (int r = 0; r < ranks_; ++r) {
      float* p = film.pixel(type.firstLayer + r / 2, x, y) + 2 * (r % 2);
      const bool used = size_t(r) < ranked.size();
      p[0] = used ? ranked[size_t(r)].id : 0.0f;
      p[1] = used ? float(ranked[size_t(r)].weight * norm) : 0.0f;
    }
  }
}

}  // namespace tray
