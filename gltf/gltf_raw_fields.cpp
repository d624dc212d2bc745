#include "gltf/gltf_raw_fields.h"

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "gltf/gltf_context.h"

namespace tray {
namespace {

using nlohmann::json;

constexpr double kMaxId = 2147483647.0;          // tinygltf keeps ids in an int
constexpr double kMaxSize = 9007199254740992.0;  // 2^53: exact as double and as size_t
// --resolution allows 1..16384 pixels a side: a camera whose aspect ratio lies outside
// [1/16384, 16384] cannot give an image at least one pixel high and wide.
constexpr double kMaxAspect = 16384.0;

struct Checker {
  const std::string& path;

  [[noreturn]] void fail(const std::string& where, const json& value,
                         const std::string& expected) const {
    failFile(path, where + " is " + value.dump() + ": expected " + expected);
  }
  /// `key` of `object`, if present, is an integer in [min, max] (and a multiple of `step`).
  void integer(const json& object, const char* key, const std::string& where, double min,
               double max, int step = 1) const {
    auto it = object.find(key);
    if (it == object.end()) return;
    const std::string field = where + "." + key;
    const bool number = it->is_number();
    const double v = number ? it->get<double>() : 0.0;
    if (!number || std::floor(v) != v || v < min || v > max || std::fmod(v, step) != 0) {
      std::string expected = step > 1 ? "a multiple of " + std::to_string(step) : "an integer";
      if (max == kMaxId || max == kMaxSize)
        expected += " >= " + std::to_string(int64_t(min));
      else
        expected += " from " + std::to_string(int64_t(min)) + " to " + std::to_string(int64_t(max));
      fail(field, *it, expected);
    }
  }
  void id(const json& object, const char* key, const std::string& where) const {
    integer(object, key, where, 0, kMaxId);
  }
  /// `key` of `object`, if present, is an array of ids.
  void ids(const json& object, const char* key, const std::string& where) const {
    auto it = object.find(key);
    if (it == object.end() || !it->is_array()) return;  // tinygltf reports the wrong type
    for (size_t i = 0; i < it->size(); ++i) {
      const json& v = (*it)[i];
      const double d = v.is_number() ? v.get<double>() : -1.0;
      if (!v.is_number() || std::floor(d) != d || d < 0 || d > kMaxId)
        fail(where + "." + key + "[" + std::to_string(i) + "]", v, "an integer >= 0");
    }
  }
  /// Each object of the top-level array `key`, with its name for messages ("nodes[3]").
  template <typename F>
  void each(const json& root, const char* key, F&& check) const {
    auto it = root.find(key);
    if (it == root.end() || !it->is_array()) return;
    for (size_t i = 0; i < it->size(); ++i)
      if ((*it)[i].is_object()) check((*it)[i], std::string(key) + "[" + std::to_string(i) + "]");
  }
  /// A member object (`index` and `texCoord` of a textureInfo, `indices` of a sparse accessor).
  template <typename F>
  void member(const json& object, const char* key, const std::string& where, F&& check) const {
    auto it = object.find(key);
    if (it != object.end() && it->is_object()) check(*it, where + "." + key);
  }
};

}  // namespace

void checkRawFields(const std::string& path, const json& root) {
  const Checker c{path};
  c.each(root, "buffers",
         [&](const json& b, const std::string& w) { c.integer(b, "byteLength", w, 1, kMaxSize); });
  c.each(root, "bufferViews", [&](const json& v, const std::string& w) {
    c.id(v, "buffer", w);
    c.integer(v, "byteOffset", w, 0, kMaxSize);
    c.integer(v, "byteLength", w, 1, kMaxSize);
    c.integer(v, "byteStride", w, 4, 252, 4);  // glTF 2.0 §5.11: 4..252, a multiple of 4
  });
  c.each(root, "accessors", [&](const json& a, const std::string& w) {
    c.id(a, "bufferView", w);
    c.integer(a, "byteOffset", w, 0, kMaxSize);
    c.integer(a, "count", w, 1, kMaxSize);
    c.member(a, "sparse", w, [&](const json& s, const std::string& sw) {
      c.integer(s, "count", sw, 1, kMaxSize);
      for (const char* part : {"indices", "values"})
        c.member(s, part, sw, [&](const json& p, const std::string& pw) {
          c.id(p, "bufferView", pw);
          c.integer(p, "byteOffset", pw, 0, kMaxSize);
        });
    });
  });
  c.each(root, "meshes", [&](const json& m, const std::string& w) {
    auto prims = m.find("primitives");
    if (prims == m.end() || !prims->is_array()) return;
    for (size_t i = 0; i < prims->size(); ++i) {
      const json& p = (*prims)[i];
      if (!p.is_object()) continue;
      const std::string pw = w + ".primitives[" + std::to_string(i) + "]";
      c.id(p, "indices", pw);
      c.id(p, "material", pw);
      c.integer(p, "mode", pw, 0, 6);
      c.member(p, "attributes", pw, [&](const json& attributes, const std::string& aw) {
        for (auto it = attributes.begin(); it != attributes.end(); ++it)
          c.id(attributes, it.key().c_str(), aw);
      });
    }
  });
  c.each(root, "nodes", [&](const json& n, const std::string& w) {
    c.id(n, "camera", w);
    c.id(n, "mesh", w);
    c.id(n, "skin", w);
    c.ids(n, "children", w);
  });
  c.each(root, "scenes", [&](const json& s, const std::string& w) { c.ids(s, "nodes", w); });
  c.each(root, "textures", [&](const json& t, const std::string& w) {
    c.id(t, "sampler", w);
    c.id(t, "source", w);
  });
  c.each(root, "images", [&](const json& i, const std::string& w) { c.id(i, "bufferView", w); });
  c.each(root, "materials", [&](const json& m, const std::string& w) {
    auto textureInfo = [&](const json& t, const std::string& tw) {
      c.id(t, "index", tw);
      c.integer(t, "texCoord", tw, 0, kMaxId);
    };
    for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"})
      c.member(m, key, w, textureInfo);
    c.member(m, "pbrMetallicRoughness", w, [&](const json& pbr, const std::string& pw) {
      for (const char* key : {"baseColorTexture", "metallicRoughnessTexture"})
        c.member(pbr, key, pw, textureInfo);
    });
  });
  c.each(root, "cameras", [&](const json& cam, const std::string& w) {
    c.member(cam, "perspective", w, [&](const json& p, const std::string& pw) {
      auto it = p.find("aspectRatio");
      if (it == p.end()) return;  // optional: the image's own aspect ratio then
      const double a = it->is_number() ? it->get<double>() : 0.0;
      if (!it->is_number() || !(a >= 1.0 / kMaxAspect && a <= kMaxAspect))
        c.fail(pw + ".aspectRatio", *it, "a number from 1/16384 to 16384");
    });
  });
}

}  // namespace tray
