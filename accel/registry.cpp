#include "accel/registry.h"

#include <algorithm>
#include <string>

#include "accel/bvh_accelerator.h"
#include "accel/embree_accelerator.h"
#include "core/error.h"
#include "core/scene.h"

namespace tray {
namespace {

struct AcceleratorEntry {
  const char* name;
  std::unique_ptr<Accelerator> (*create)(const Scene&);
};

// The accelerator table: one line per accelerator.
const AcceleratorEntry kAccelerators[] = {
    {"embree", makeEmbreeAccelerator},
    {"bvh", makeBvhAccelerator},
    {"bvh-gs", makeBvhGoldsmithSalmonAccelerator},
    {"naive", makeNaiveAccelerator},
};

}  // namespace

std::unique_ptr<Accelerator> makeAccelerator(const std::string& name, const Scene& scene) {
  for (const auto& e : kAccelerators)
    if (name == e.name) return e.create(scene);
  std::string known;
  for (const auto& e : kAccelerators) known += std::string(known.empty() ? "" : ", ") + e.name;
  throw Error("unknown accelerator '" + name + "' (known: " + known + ")");
}

AcceleratorFactory acceleratorFactory(const std::string& name) {
  const auto names = acceleratorNames();  // an unknown name fails here, not in a solid
  if (std::find(names.begin(), names.end(), name) == names.end()) makeAccelerator(name, Scene{});
  return [name](const Scene& scene) { return makeAccelerator(name, scene); };
}

std::vector<std::string> acceleratorNames() {
  std::vector<std::string> names;
  for (const auto& e : kAccelerators) names.push_back(e.name);
  return names;
}

}  // namespace tray
