#pragma once
// The accelerators by name: accel/registry.cpp holds the table.
#include <memory>
#include <string>
#include <vector>

#include "core/accelerator.h"

namespace tray {

/// Builds the named accelerator ("embree", ...) over the scene. The scene must outlive it.
/// Throws tray::Error for an unknown name.
std::unique_ptr<Accelerator> makeAccelerator(const std::string& name, const Scene& scene);
/// A factory for makeAccelerator(name, scene), for shapes that build their own (MeshSolid).
AcceleratorFactory acceleratorFactory(const std::string& name);
/// Names accepted by makeAccelerator, for --help.
std::vector<std::string> acceleratorNames();

}  // namespace tray
