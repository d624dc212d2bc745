#pragma once
// External buffers before tinygltf reads them: their total size (for --max-memory) and one
// read per file. tinygltf 2.7 gives every glTF buffer its own std::vector and reads its URI
// into it, so a 700-byte .gltf naming one 1.5 GiB file four times read 6 GiB (and peaked at
// 3.3 GB before the 4 GiB cap on URI bytes refused it). Buffers with the same file and
// byteLength are therefore merged in the JSON before tinygltf parses it: every bufferView of
// a later duplicate points at the first, and the duplicate becomes a 1-byte data: buffer that
// nothing uses. The bytes each bufferView sees are unchanged (same file, same length).
#include <cstdint>
#include <string>
#include <string_view>

#include "gltf/gltf_file_access.h"

namespace tray {

struct BufferPlan {
  uint64_t bytes = 0;        ///< sum of byteLength over the distinct buffers (BIN chunk included)
  uint64_t mergedBytes = 0;  ///< byteLength of the merged duplicates (not in `bytes`)
  int merged = 0;            ///< duplicate buffers redirected to their first occurrence
  std::string json;          ///< the rewritten document when merged > 0, else empty
};

/// Plans the buffers of a document's JSON text (already checked by checkJsonRoot). Files are
/// keyed by their path as the policy resolves it; URIs it refuses are left for tinygltf's read
/// to report, as before. Percent-encoded or data: URIs are never merged.
BufferPlan planBuffers(std::string_view json, const UriPolicy& policy);

}  // namespace tray
