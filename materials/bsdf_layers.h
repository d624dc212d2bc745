#pragma once
// The layers over the glTF base BSDF, outermost first: one line per layer (materials/
// bsdf_layer.h says what a layer provides; docs/materials.md, "Layers", how to add one).
#include "materials/bsdf_layer.h"
#include "materials/clearcoat_layer.h"
#include "materials/sheen_layer.h"

namespace tray {

using BsdfLayers = LayerStack<ClearcoatLayer,  // KHR_materials_clearcoat
                              SheenLayer>;     // KHR_materials_sheen

}  // namespace tray
