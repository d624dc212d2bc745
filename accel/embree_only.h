#pragma once
#include <string>

#include "core/error.h"
#include "core/scene.h"

namespace tray {

/// Refuses a scene holding a shape only Embree intersects (Shape::embreeOnly: curves,
/// subdivision surfaces) before an accelerator without that geometry is built, so that nothing
/// is silently dropped (docs/curves-subdivision.md). `accel`: the accelerator, for the message.
inline void refuseEmbreeOnlyShapes(const Scene& scene, const std::string& accel) {
  for (const Primitive& p : scene.primitives) {
    if (p.kind != Primitive::Kind::kShape || !p.shape) continue;
    if (const char* why = p.shape->embreeOnly()) {
      std::string msg = scene.sourcePath.empty() ? std::string("the scene") : scene.sourcePath;
      msg += ": primitive '";
      msg += p.name;
      msg += "' is Embree-only, ";
      msg += accel;
      msg += " cannot render it: ";
      msg += why;
      throw Error(msg);
    }
  }
}

}  // namespace tray
