#include "gltf/gltf_value.h"

#include <cmath>

namespace tray {

const tinygltf::Value* findExtension(const tinygltf::ExtensionMap& extensions, const char* name) {
  auto it = extensions.find(name);
  return it == extensions.end() ? nullptr : &it->second;
}

ExtensionReader::ExtensionReader(const GltfContext& ctx, const tinygltf::Value& value,
                                 std::string where)
    : ctx_(ctx), value_(value), where_(std::move(where)) {
  if (!value_.IsObject()) fail("is not a JSON object");
}

void ExtensionReader::fail(const std::string& problem) const {
  ctx_.fail(where_ + " " + problem);
}

const tinygltf::Value* ExtensionReader::value(const std::string& key) {
  read_.insert(key);
  return value_.Has(key) ? &value_.Get(key) : nullptr;
}

double ExtensionReader::number(const std::string& key, double fallback, double lo, double hi) {
  const tinygltf::Value* v = value(key);
  if (!v) return fallback;
  if (!v->IsNumber()) fail("'" + key + "' is not a number");
  double d = v->GetNumberAsDouble();
  // Values end up as floats: 1e300 is finite only as a double.
  if (!std::isfinite(float(d))) fail("'" + key + "' is not finite");
  if (d < lo || d > hi)
    fail("'" + key + "' = " + std::to_string(d) + " is outside [" + std::to_string(lo) + ", " +
         std::to_string(hi) + "]");
  return d;
}

int ExtensionReader::integer(const std::string& key, int fallback) {
  double d = number(key, fallback, -2147483648.0, 2147483647.0);
  if (d != std::floor(d)) fail("'" + key + "' is not an integer");
  return int(d);
}

std::string ExtensionReader::string(const std::string& key, const std::string& fallback) {
  const tinygltf::Value* v = value(key);
  if (!v) return fallback;
  if (!v->IsString()) fail("'" + key + "' is not a string");
  return v->Get<std::string>();
}

bool ExtensionReader::boolean(const std::string& key, bool fallback) {
  const tinygltf::Value* v = value(key);
  if (!v) return fallback;
  if (!v->IsBool()) fail("'" + key + "' is not true or false");
  return v->Get<bool>();
}

void ExtensionReader::numbers(const std::string& key, float* out, int size, double lo, double hi) {
  const tinygltf::Value* v = value(key);
  if (!v) return;
  if (!v->IsArray() || v->ArrayLen() != size_t(size))
    fail("'" + key + "' is not an array of " + std::to_string(size) + " numbers");
  for (int i = 0; i < size; ++i) {
    const tinygltf::Value& e = v->Get(i);
    double d = e.IsNumber() ? e.GetNumberAsDouble() : NAN;
    if (!std::isfinite(float(d)) || d < lo || d > hi)
      fail("'" + key + "'[" + std::to_string(i) + "] is not a finite number in range");
    out[i] = float(d);
  }
}

Vec3 ExtensionReader::vec3(const std::string& key, Vec3 fallback, double lo, double hi) {
  float v[3] = {fallback.x, fallback.y, fallback.z};
  numbers(key, v, 3, lo, hi);
  return {v[0], v[1], v[2]};
}

void ExtensionReader::finish() const {
  for (const auto& key : value_.Keys())
    if (!read_.count(key)) fail("has unknown key '" + key + "'");
}

}  // namespace tray
