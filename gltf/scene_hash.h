#pragma once
// The content of a scene, as one hash: what a farm job's signature holds so that a part
// rendered from an edited scene (same file name, other bytes) is never merged (docs/farm.md).
#include <string>
#include <vector>

namespace tray {

/// XXH3-128 of the glTF/GLB file's bytes followed by those of every external file its JSON
/// names by a "uri" (buffers, images, and URIs inside extensions), in document order, each
/// preceded by its URI. URIs are resolved as the loader resolves them (percent-decoded,
/// relative to the scene's folder, `allowAnyPath`); one that does not resolve adds only its
/// URI (the loader reports it). Returns 32 hex digits; throws tray::Error "PATH: problem" for
/// an unreadable scene file.
/// `outsideFiles`: files outside the scene that shape its pixels (the --env map): their bytes
/// are hashed after the scene's (an unreadable one adds only its path: rendering reports it).
std::string sceneContentHash(const std::string& scenePath, bool allowAnyPath,
                             const std::vector<std::string>& outsideFiles = {});

}  // namespace tray
