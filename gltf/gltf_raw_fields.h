#pragma once
// Numbers checked in the raw JSON, before tinygltf reads them: tinygltf 2.7.0 coerces a bad
// number in an integer field without a word (a byteOffset of -64 becomes 0, 0.5 becomes 0, the
// string "0" is skipped as absent, 1e20 is cast out of range, -1 means "no material"), so the
// validator after it could never see the mistake.
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace tray {

/// Checks every glTF id and byte offset, length, stride and count that TRay reads, and each
/// perspective camera's aspectRatio, in the parsed document `root` (whose top-level collections
/// are arrays of objects). Throws tray::Error("PATH: FIELD is VALUE: expected ...") naming the
/// first bad field as a path into the file, e.g. "bufferViews[0].byteOffset is -64".
void checkRawFields(const std::string& path, const nlohmann::json& root);

}  // namespace tray
