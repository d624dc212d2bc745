// libFuzzer target for the glTF loader (docs/fuzzing.md): any byte string, taken as a .gltf or
// (with the GLB magic) a .glb, must either load or be refused with a tray::Error. A crash, a
// sanitizer report, a leak, a hang or any other exception is a bug.
#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "gltf/gltf_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    tray::loadGltfFromMemory(data, size, "fuzz-input");
  } catch (const tray::Error&) {
    // Refused with a message: the expected outcome for almost every input.
  }
  return 0;
}
