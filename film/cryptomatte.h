#pragma once
// Cryptomatte ID mattes (Psyop, Cryptomatte specification 1.2; docs/aovs.md): per pixel, the
// ids of the objects and materials its samples saw, ranked by coverage, with a manifest of
// names in the EXR header, so a compositor picks mattes by name.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/id_coverage.h"
#include "core/scene.h"
#include "film/film.h"

namespace tray {

/// MurmurHash3_x86_32 (Austin Appleby, SMHasher), the only hash Cryptomatte allows.
uint32_t murmurHash3_32(std::string_view key, uint32_t seed = 0);

/// The hash as a pixel value ("uint32_to_float32"): its bits with the exponent clamped to
/// 1..254, so no id is 0, a denormal, an infinity or a NaN.
float cryptomatteId(uint32_t hash);
inline float cryptomatteId(std::string_view name) {
  return cryptomatteId(murmurHash3_32(name));
}

/// The names ids are computed from: the glTF node name of an object (Primitive::name), or
/// "node<objectId>" when empty; a material's name, or "material<index>" when empty.
std::string cryptomatteObjectName(const Primitive& p);
std::string cryptomatteMaterialName(const Scene& scene, int material);

/// The Cryptomatte layers of one render. For each requested type (CryptoObject, CryptoMaterial)
/// it adds ceil(ranks / 2) film layers {type}00, {type}01, ... with channels R, G, B, A = (id,
/// coverage) of ranks 2k and 2k + 1, and the header metadata cryptomatte/<key>/name, hash,
/// conversion and manifest (a JSON object name -> 8 hex digits of the id's float bits).
class Cryptomatte {
 public:
  static constexpr int kDefaultRanks = 6;  ///< the specification's suggested default
  static constexpr int kMaxRanks = 32;

  /// Active when `aovs` holds "crypto_object" and/or "crypto_material"; throws tray::Error when
  /// ranks is outside 1..kMaxRanks.
  Cryptomatte(Film& film, const Scene& scene, const std::vector<std::string>& aovs,
              int ranks = kDefaultRanks);
  bool active() const { return !types_.empty(); }
  /// Whether `aovs` asks for any Cryptomatte layer (what active() will say), before a film exists.
  static bool requested(const std::vector<std::string>& aovs);
  /// Ranks one pixel's coverage and writes its layers. Samples that hit nothing count as id 0
  /// (the specification: "If there is no object in the sample, the recorded hash value should
  /// be zero"), so a pixel's coverages sum to 1 over all ranks when it has few enough ids.
  void write(Film& film, int x, int y, const IdCoverage& coverage) const;

  /// The metadata key of a type name: the first 7 hex digits of its hash.
  static std::string metadataKey(std::string_view typeName);

 private:
  struct IdName {
    int id;
    float value;
  };
  struct Type {
    bool objects;  ///< else materials
    std::vector<IdName> ids;
    int firstLayer;
  };
  static float lookup(const std::vector<IdName>& ids, int id);
  std::vector<Type> types_;
  int ranks_;
};

}  // namespace tray
