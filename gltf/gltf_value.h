#pragma once
// Reading extension objects (tinygltf::Value) with type, range and spelling checks. TRAY_
// extensions call finish(), so an unknown key, usually a typo, is an error and never silent.
#include <set>
#include <string>

#include "core/math.h"
#include "gltf/gltf_context.h"

namespace tray {

/// The extension `name` of an object, or nullptr.
const tinygltf::Value* findExtension(const tinygltf::ExtensionMap& extensions, const char* name);

class ExtensionReader {
 public:
  /// `where` names the object in messages, e.g. "material 2 TRAY_materials_phong".
  ExtensionReader(const GltfContext& ctx, const tinygltf::Value& value, std::string where);
  bool has(const std::string& key) const { return value_.Has(key); }
  /// A finite number in [lo, hi], or `fallback` when absent.
  double number(const std::string& key, double fallback, double lo = -kInfinity,
                double hi = kInfinity);
  /// An integer (a real with an integral value is accepted).
  int integer(const std::string& key, int fallback);
  std::string string(const std::string& key, const std::string& fallback);
  bool boolean(const std::string& key, bool fallback);
  /// An array of `size` finite numbers, each in [lo, hi].
  void numbers(const std::string& key, float* out, int size, double lo = -kInfinity,
               double hi = kInfinity);
  Vec3 vec3(const std::string& key, Vec3 fallback, double lo = -kInfinity, double hi = kInfinity);
  /// A sub-value, marked as read; nullptr when absent.
  const tinygltf::Value* value(const std::string& key);
  /// Fails naming the first key none of the getters read.
  void finish() const;
  [[noreturn]] void fail(const std::string& problem) const;
  const std::string& where() const { return where_; }

 private:
  const GltfContext& ctx_;
  const tinygltf::Value& value_;
  std::string where_;
  std::set<std::string> read_;
};

}  // namespace tray
