#pragma once
// What every stage of the glTF loader shares: the parsed model, the file name for messages, and
// the warning sink.
#include <tiny_gltf.h>

#include <string>
#include <vector>

#include "gltf/gltf_loader.h"

namespace tray {

/// Caps checked before allocating, so a hostile file cannot make the loader exhaust memory.
constexpr size_t kMaxTriangles = 50'000'000;  ///< over all meshes
constexpr size_t kMaxVertices = 50'000'000;   ///< over all meshes
/// Placed objects (node x mesh primitive instances, shapes): each costs ~200 bytes and an Embree
/// instance, and one mesh of many primitives placed by many nodes would otherwise multiply
/// without bound (1000 primitives x 1000 nodes take a 60 KB file).
constexpr size_t kMaxPrimitives = 1'000'000;
/// Per accessor: a triangle list of kMaxTriangles needs three indices each.
constexpr size_t kMaxAccessorCount = 3 * kMaxTriangles;

struct GltfContext {
  const tinygltf::Model& model;
  std::string path;  ///< as the caller named the file; every message starts with it
  LoadReport* report = nullptr;
  bool ignoreRequiredExtensions = false;  ///< LoadOptions::ignoreRequiredExtensions
  int variant = -1;  ///< the KHR_materials_variants variant chosen by --variant (-1: none)

  /// Throws tray::Error("PATH: problem") on one line.
  [[noreturn]] void fail(const std::string& problem) const;
  /// Records "PATH: message" in the report, if any.
  void warn(const std::string& message) const;
};

/// Throws tray::Error("PATH: problem") on one line; for stages before the model exists.
[[noreturn]] void failFile(const std::string& path, const std::string& problem);

/// Collapses a message to one line (tinygltf's errors span several) and caps its length.
std::string oneLine(const std::string& text);

/// "accessor 3", "node 2 'Arm'": how messages name a glTF object.
std::string nameOf(const char* kind, int index, const std::string& name = "");

/// What a command-line choice (--animation, --variant) names among `names`: the first of that
/// name, else a decimal index in range; -1 for neither.
int findByNameOrIndex(const std::vector<std::string>& names, const std::string& which);
/// ": 0 'Walk', 1, 2 'Run'": the choices, for the message that refuses another.
std::string listOfChoices(const std::vector<std::string>& names);

}  // namespace tray
