#pragma once
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tray {

/// Colour management through OpenColorIO. TRay renders in scene-linear Rec.709 / D65 (glTF's
/// working space); EXR output may be converted to another colorspace of the config (ACEScg,
/// ACES2065-1, ...), PNG/JPEG go through a display/view. See docs/color.md.
class ColorPipeline {
 public:
  /// The process-wide pipeline on defaultConfigPath(), created on first use (thread-safe).
  static const ColorPipeline& instance();
  /// $OCIO when set and non-empty; else the first existing of ocio/config.ocio (a build tree)
  /// and ../share/tray/ocio/config.ocio (an installed tree) beside the executable.
  static std::string defaultConfigPath();

  /// Throws tray::Error naming the file if the config cannot be read or is invalid.
  explicit ColorPipeline(const std::string& configPath);
  ~ColorPipeline();
  ColorPipeline(const ColorPipeline&) = delete;
  ColorPipeline& operator=(const ColorPipeline&) = delete;

  /// Converts n pixels of working-space RGB in place (stride floats per pixel, RGB first; 3
  /// or more) to `colorspace` (a name, alias or role; empty: defaultOutputSpace()). Throws
  /// tray::Error for unknown names, listing the known ones, and for a config that TRay's
  /// linear Rec.709 cannot be converted into.
  void convertFromWorking(float* rgb, size_t n, int stride, const std::string& colorspace) const;
  /// The inverse: converts n pixels of `colorspace` RGB in place to the working space (an
  /// environment map tagged with its colorspace). Throws tray::Error like convertFromWorking.
  void convertToWorking(float* rgb, size_t n, int stride, const std::string& colorspace) const;
  /// Applies a display/view transform to working-space RGB in place, giving display-referred
  /// values in [0, 1] for 8-bit output. Empty names: the config's default display / its
  /// default view ("sRGB" / "Standard" in TRay's config).
  void toDisplay(float* rgb, size_t n, int stride, const std::string& display = "",
                 const std::string& view = "") const;

  /// Throws tray::Error, before anything is rendered, unless EXR output in `colorspace` and
  /// display output through `display`/`view` (empty: defaults) can be produced.
  void check(const std::string& colorspace, const std::string& display = "",
             const std::string& view = "") const;
  /// What EXRs are written in by default: the config's linear Rec.709 space, else (a studio
  /// config without one) its scene_linear role, reached through an interchange role.
  std::string defaultOutputSpace() const;

  /// Names of the config's active colorspaces.
  std::vector<std::string> colorspaces() const;
  /// The canonical name of a colorspace (resolving aliases and roles); throws tray::Error,
  /// listing the known names, if the config has none of that name.
  std::string canonicalName(const std::string& colorspace) const;
  /// The config's colorspace that is TRay's working space (linear Rec.709 under one of its
  /// usual names or aliases); empty when the config has none, and conversions then enter the
  /// config through its aces_interchange or cie_xyz_d65_interchange role (bridgeSpace()).
  const std::string& workingSpace() const { return working_; }
  /// The interchange space conversions start from when workingSpace() is empty.
  const std::string& bridgeSpace() const { return bridge_; }
  /// CIE xy of the colorspace's red, green, blue primaries and white (the EXR chromaticities
  /// attribute's order), or nothing for data and non-RGB spaces. Throws for unknown names.
  std::optional<std::array<float, 8>> chromaticities(const std::string& colorspace) const;
  const std::string& configPath() const { return path_; }

 private:
  struct Impl;
  std::string noBridge() const;
  std::unique_ptr<Impl> impl_;
  std::string path_;
  std::string working_;
  std::string bridge_;
};

}  // namespace tray
