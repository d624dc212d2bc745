#include "io/memory_estimate.h"

#include "core/error.h"

namespace tray {

namespace {

std::string mb(uint64_t bytes) {
  return std::to_string((bytes + (1u << 20) - 1) >> 20);
}

}  // namespace

void checkMemory(const std::string& scene, const MemoryEstimate& e, uint64_t limitBytes) {
  if (limitBytes == 0 || e.total() <= limitBytes) return;
  const std::string environment =
      e.environment ? ", environment " + mb(e.environment) + " MB" : std::string();
  throw Error(scene + ": needs about " + mb(e.total()) + " MB (buffers " + mb(e.buffers) +
              " MB, textures " + mb(e.textures) + " MB, geometry " + mb(e.geometry) + " MB" +
              environment + "), more than --max-memory " + std::to_string(limitBytes >> 20) +
              " MB");
}

}  // namespace tray
