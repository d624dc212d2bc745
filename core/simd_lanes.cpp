#include "core/simd_lanes.h"

#include <hwy/targets.h>

namespace tray {

bool hasSimdTarget() {
  return (hwy::SupportedTargets() & HWY_TARGETS & ~HWY_SCALAR) != 0;
}

}  // namespace tray
