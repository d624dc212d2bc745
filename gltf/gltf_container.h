#pragma once
// The envelope around a glTF document, checked before tinygltf sees it: the GLB chunk layout
// and the JSON root's shape, which tinygltf 2.7.0 checks only partly.
#include <string>
#include <string_view>
#include <vector>

namespace tray {

/// True if the bytes start with the GLB magic "glTF".
bool isGlb(const std::vector<unsigned char>& bytes);

/// Checks a GLB's header and chunks (glTF 2.0 §4.4 "Binary glTF Layout") and returns its JSON
/// chunk. Throws tray::Error("PATH: ...") on a truncated file or inconsistent lengths.
std::string_view glbJson(const std::string& path, const std::vector<unsigned char>& bytes);

/// The GLB `bytes` (already checked by glbJson) with its JSON chunk replaced by `json` (padded
/// with spaces to 4 bytes, §4.4.3.1); the chunks after it are copied unchanged.
std::vector<unsigned char> withGlbJson(const std::vector<unsigned char>& bytes,
                                       std::string_view json);

/// Checks what tinygltf silently skips: the root is an object with an `asset` of version 2.x,
/// and every top-level collection is an array of objects (glTF 2.0 §5, "Properties Reference").
void checkJsonRoot(const std::string& path, std::string_view json);

}  // namespace tray
