#pragma once
// Structural validation of a whole glTF document before any of it is converted. Checks what
// tinygltf 2.7.0 leaves unchecked (see /work/shared/notes/input-security.md). Values that are
// converted anyway (materials, cameras, lights, transforms, vertex data) are checked by their
// converters, which run over every object of the file, not only those the scene uses.
#include <string>

#include "gltf/gltf_context.h"

namespace tray {

/// True for the extensions TRay reads or deliberately ignores.
bool isKnownExtension(const std::string& name);

/// Fails on the first problem: unknown required extensions, references out of range, buffer
/// views and accessors outside their storage, attribute types not allowed for their semantic,
/// unequal attribute counts, node cycles or nodes with two parents, scenes listing non-roots.
/// Warns once per unknown extension in extensionsUsed.
void validateDocument(const GltfContext& ctx);

}  // namespace tray
