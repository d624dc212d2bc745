#pragma once
#include <memory>

#include "core/accelerator.h"

namespace tray {

/// Embree 3 traversal: meshes as triangle geometry built once per mesh and placed by instances;
/// analytic shapes as user geometry calling Scene::intersectShape.
std::unique_ptr<Accelerator> makeEmbreeAccelerator(const Scene& scene);

}  // namespace tray
