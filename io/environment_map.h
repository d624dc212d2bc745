#pragma once
// Environment maps from files (docs/scene-format.md "TRAY_environment", README "Environment
// lighting"): equirectangular HDR images read through OpenImageIO (.exr, .hdr, any format it
// reads), converted to TRay's working space, checked before anything renders, and handed to
// lights/ as plain float data (core/light_desc.h EnvironmentMap).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/light_desc.h"

namespace tray {

class RenderSettings;
struct Scene;

/// Largest map read: 16384 pixels wide and 2^28 pixels in all (3 GiB as float RGB). Checked
/// from the header, before any pixel is decoded.
constexpr int kMaxEnvironmentWidth = 16384;
constexpr uint64_t kMaxEnvironmentPixels = uint64_t(1) << 28;

/// Reads an equirectangular map. One, two (grey), three or more channels (RGB first). A file
/// whose "colorspace" attribute names another OCIO colorspace is converted to linear Rec.709;
/// untagged files are taken as linear Rec.709 (EXR) or as what their format defines (OIIO
/// decodes 8-bit formats to linear). Throws tray::Error "PATH: problem" for a missing or
/// unreadable file, NaN or infinite values, or a size over the limits;
/// negative values (out-of-gamut colours) become 0. A map not 2:1 is
/// used as lat-long anyway, with a warning added to `warnings`. maxBytes (--max-memory; 0:
/// none): a map whose decoded floats (environmentMapBytes) would need more is refused from its
/// header, before any pixel is decoded.
std::shared_ptr<const EnvironmentMap> loadEnvironmentMap(const std::string& path,
                                                         std::vector<std::string>* warnings,
                                                         uint64_t maxBytes = 0);
/// The same from encoded bytes in memory (a glTF image): EXR and Radiance HDR, chosen by their
/// signature; `name` names them in messages.
std::shared_ptr<const EnvironmentMap> decodeEnvironmentMap(const unsigned char* data,
                                                           size_t size, const std::string& name,
                                                           std::vector<std::string>* warnings,
                                                           uint64_t maxBytes = 0);
/// What a width x height map takes decoded (RGB floats): its part of --max-memory.
uint64_t environmentMapBytes(int width, int height);

/// Applies the render-wide options (declared in core/render_options.cpp) --env (loads the map; it replaces the scene's image or background), --env-rotate and
/// --env-intensity (each overrides TRAY_environment's rotation / intensity when given).
void applyEnvironmentOptions(Scene& scene, const RenderSettings& settings,
                             std::vector<std::string>* warnings, uint64_t maxBytes = 0);

}  // namespace tray
