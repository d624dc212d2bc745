#include "io/color.h"

#include <OpenColorIO/OpenColorIO.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "core/error.h"

namespace OCIO = OCIO_NAMESPACE;
namespace fs = std::filesystem;

namespace tray {

struct ColorPipeline::Impl {
  OCIO::ConstConfigRcPtr config;
  /// From TRay's linear Rec.709 into bridge_ (null when the config has the working space).
  OCIO::ConstTransformRcPtr bridge;
  /// The transform from the working space to a colorspace of the config.
  OCIO::ConstTransformRcPtr fromWorking(const std::string& working, const std::string& bridge,
                                        const std::string& target) const;
};

namespace {

/// Names under which configs carry linear Rec.709 / D65: TRay's and the OCIO 2.2 CG config's,
/// the ACES 1.x studio config's, Blender's. Tried before the scene_linear role because a
/// studio config's scene_linear is often ACEScg, which is not what the renderer produces.
const char* const kWorkingNames[] = {"lin_rec709",      "Linear Rec.709 (sRGB)",
                                     "lin_rec709_srgb", "Utility - Linear - sRGB",
                                     "Linear Rec.709",  "Linear"};

struct KnownPrimaries {
  std::vector<const char*> names;
  std::array<float, 8> xy;  // R, G, B, white
};

/// Chromaticities as the colorspaces' specifications give them (ITU-R BT.709 / IEC 61966-2-1;
/// ACES AP1 with the ACES white, Academy S-2014-004; AP0, SMPTE ST 2065-1). Looked up by name
/// or alias: the nominal primaries, not values recomputed through Bradford-adapted matrices.
const std::vector<KnownPrimaries>& knownPrimaries() {
  static const std::vector<KnownPrimaries> k = {
      {{"lin_rec709", "sRGB", "sRGB - Texture", "sRGB - Display", "Utility - Linear - sRGB",
        "Utility - sRGB - Texture"},
       {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f}},
      {{"ACEScg", "ACEScct", "ACEScc", "ACES - ACEScg", "ACES - ACEScct", "ACES - ACEScc"},
       {0.713f, 0.293f, 0.165f, 0.830f, 0.128f, 0.044f, 0.32168f, 0.33767f}},
      {{"ACES2065-1", "ACES - ACES2065-1"},
       {0.7347f, 0.2653f, 0.0f, 1.0f, 0.0001f, -0.077f, 0.32168f, 0.33767f}},
  };
  return k;
}

std::string oneLine(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

void applyPacked(const OCIO::ConstCPUProcessorRcPtr& cpu, float* rgb, size_t n, int stride) {
  if (n == 0) return;
  // One row of n pixels; stride lets RGB be converted inside interleaved RGBA or multi-layer
  // pixels without copying (OCIO's PackedImageDesc takes a pixel stride in bytes).
  const auto px = ptrdiff_t(stride) * ptrdiff_t(sizeof(float));
  OCIO::PackedImageDesc img(rgb, long(n), 1, 3, OCIO::BIT_DEPTH_F32, sizeof(float), px,
                            px * ptrdiff_t(n));
  cpu->apply(img);
}

}  // namespace

std::string ColorPipeline::noBridge() const {
  return path_ + ": OpenColorIO config has no linear Rec.709 colorspace and no aces_interchange "
         "or cie_xyz_d65_interchange role: TRay's linear Rec.709 cannot be converted into it";
}

std::string ColorPipeline::defaultConfigPath() {
  if (const char* env = std::getenv("OCIO"); env && *env) return env;
  // An installed binary finds the config in ../share/tray, a build tree's beside it (CMake
  // copies it there): no source-tree path is compiled in.
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec)
    for (const fs::path rel : {"ocio/config.ocio", "../share/tray/ocio/config.ocio"})
      if (fs::path p = exe.parent_path() / rel; fs::is_regular_file(p, ec)) return p.string();
  return "ocio/config.ocio";  // not found: the error names this relative path
}

const ColorPipeline& ColorPipeline::instance() {
  static const ColorPipeline pipeline(defaultConfigPath());  // C++11 magic static: thread-safe
  return pipeline;
}

ColorPipeline::ColorPipeline(const std::string& configPath)
    : impl_(std::make_unique<Impl>()), path_(configPath) {
  std::error_code ec;
  if (!fs::is_regular_file(configPath, ec))
    throw Error(configPath + ": OpenColorIO config not found (set $OCIO to a config.ocio)");
  try {
    impl_->config = OCIO::Config::CreateFromFile(configPath.c_str());
    impl_->config->validate();
  } catch (const OCIO::Exception& e) {
    throw Error(configPath + ": invalid OpenColorIO config: " + oneLine(e.what()));
  }
  const auto& cfg = impl_->config;
  for (const char* name : kWorkingNames)
    if (auto cs = cfg->getColorSpace(name); cs && !cs->isData()) {
      working_ = cs->getName();
      return;
    }
  // A studio config (the ACES configs have no Rec.709-linear space): enter it through an
  // interchange role (OCIO 2.1 roles aces_interchange, cie_xyz_d65_interchange) with OCIO's
  // own built-in transforms, never by pretending its scene_linear is Rec.709.
  auto rec709ToAp1 = OCIO::BuiltinTransform::Create();
  rec709ToAp1->setStyle("UTILITY - ACES-AP1_to_LINEAR-REC709_BFD");
  rec709ToAp1->setDirection(OCIO::TRANSFORM_DIR_INVERSE);
  auto second = OCIO::BuiltinTransform::Create();
  if (auto aces = cfg->getColorSpace(OCIO::ROLE_INTERCHANGE_SCENE)) {
    bridge_ = aces->getName();
    second->setStyle("ACEScg_to_ACES2065-1");
  } else if (auto xyz = cfg->getColorSpace(OCIO::ROLE_INTERCHANGE_DISPLAY)) {
    bridge_ = xyz->getName();
    second->setStyle("UTILITY - ACES-AP1_to_CIE-XYZ-D65_BFD");
  } else {
    return;  // conversions fail with a message naming what is missing (check())
  }
  auto group = OCIO::GroupTransform::Create();
  group->appendTransform(rec709ToAp1);
  group->appendTransform(second);
  impl_->bridge = group;
}

OCIO::ConstTransformRcPtr ColorPipeline::Impl::fromWorking(const std::string& working,
                                                           const std::string& bridgeSpace,
                                                           const std::string& target) const {
  auto toTarget = OCIO::ColorSpaceTransform::Create();
  toTarget->setSrc(working.empty() ? bridgeSpace.c_str() : working.c_str());
  toTarget->setDst(target.c_str());
  if (working.empty()) {
    auto group = OCIO::GroupTransform::Create();
    group->appendTransform(bridge->createEditableCopy());
    group->appendTransform(toTarget);
    return group;
  }
  return toTarget;
}

std::string ColorPipeline::defaultOutputSpace() const {
  if (!working_.empty()) return working_;
  auto cs = impl_->config->getColorSpace(OCIO::ROLE_SCENE_LINEAR);
  if (!cs)
    throw Error(path_ + ": OpenColorIO config has neither a linear Rec.709 colorspace nor a "
                "scene_linear role: name the EXR colorspace with --output-colorspace");
  return cs->getName();
}

void ColorPipeline::check(const std::string& colorspace, const std::string& display,
                          const std::string& view) const {
  float probe[3] = {0.18f, 0.18f, 0.18f};
  convertFromWorking(probe, 1, 3, colorspace);
  float shown[3] = {0.18f, 0.18f, 0.18f};
  toDisplay(shown, 1, 3, display, view);
}

ColorPipeline::~ColorPipeline() = default;

std::vector<std::string> ColorPipeline::colorspaces() const {
  std::vector<std::string> names;
  for (int i = 0; i < impl_->config->getNumColorSpaces(); ++i)
    names.push_back(impl_->config->getColorSpaceNameByIndex(i));
  return names;
}

std::string ColorPipeline::canonicalName(const std::string& colorspace) const {
  // getColorSpace resolves names, aliases and roles, case-insensitively.
  if (auto cs = impl_->config->getColorSpace(colorspace.c_str())) return cs->getName();
  std::string known;
  for (const auto& n : colorspaces()) known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown colorspace '" + colorspace + "' (" + path_ + " has: " + known + ")");
}

void ColorPipeline::convertFromWorking(float* rgb, size_t n, int stride,
                                       const std::string& colorspace) const {
  const std::string target =
      canonicalName(colorspace.empty() ? defaultOutputSpace() : colorspace);
  if (stride < 3) throw Error("colour conversion needs at least 3 floats per pixel");
  if (target == working_) return;
  if (working_.empty() && !impl_->bridge) throw Error(noBridge());
  try {
    auto t = impl_->fromWorking(working_, bridge_, target);
    applyPacked(impl_->config->getProcessor(t)->getDefaultCPUProcessor(), rgb, n, stride);
  } catch (const OCIO::Exception& e) {
    throw Error("OpenColorIO: converting to '" + target + "': " + oneLine(e.what()));
  }
}

void ColorPipeline::convertToWorking(float* rgb, size_t n, int stride,
                                     const std::string& colorspace) const {
  const std::string source = canonicalName(colorspace);
  if (stride < 3) throw Error("colour conversion needs at least 3 floats per pixel");
  if (source == working_) return;
  if (working_.empty() && !impl_->bridge) throw Error(noBridge());
  try {
    auto t = impl_->fromWorking(working_, bridge_, source);
    auto processor = impl_->config->getProcessor(t, OCIO::TRANSFORM_DIR_INVERSE);
    applyPacked(processor->getDefaultCPUProcessor(), rgb, n, stride);
  } catch (const OCIO::Exception& e) {
    throw Error("OpenColorIO: converting from '" + source + "': " + oneLine(e.what()));
  }
}

void ColorPipeline::toDisplay(float* rgb, size_t n, int stride, const std::string& display,
                              const std::string& view) const {
  const auto& cfg = impl_->config;
  if (stride < 3) throw Error("colour conversion needs at least 3 floats per pixel");
  const std::string d = display.empty() ? cfg->getDefaultDisplay() : display;
  std::string displays;
  bool displayKnown = false;
  for (int i = 0; i < cfg->getNumDisplays(); ++i) {
    displayKnown = displayKnown || d == cfg->getDisplay(i);
    displays += (displays.empty() ? "" : ", ") + std::string(cfg->getDisplay(i));
  }
  if (!displayKnown)
    throw Error("unknown display '" + d + "' (" + path_ + " has: " + displays + ")");
  const std::string v = view.empty() ? cfg->getDefaultView(d.c_str()) : view;
  std::string views;
  bool viewKnown = false;
  for (int i = 0; i < cfg->getNumViews(d.c_str()); ++i) {
    viewKnown = viewKnown || v == cfg->getView(d.c_str(), i);
    views += (views.empty() ? "" : ", ") + std::string(cfg->getView(d.c_str(), i));
  }
  if (!viewKnown)
    throw Error("unknown view '" + v + "' for display '" + d + "' (" + path_ + " has: " + views +
                ")");
  if (working_.empty() && !impl_->bridge) throw Error(noBridge());
  try {
    auto t = OCIO::DisplayViewTransform::Create();
    t->setSrc(working_.empty() ? bridge_.c_str() : working_.c_str());
    t->setDisplay(d.c_str());
    t->setView(v.c_str());
    OCIO::ConstTransformRcPtr all = t;
    if (working_.empty()) {
      auto group = OCIO::GroupTransform::Create();
      group->appendTransform(impl_->bridge->createEditableCopy());
      group->appendTransform(t);
      all = group;
    }
    applyPacked(cfg->getProcessor(all)->getDefaultCPUProcessor(), rgb, n, stride);
  } catch (const OCIO::Exception& e) {
    throw Error("OpenColorIO: display '" + d + "' view '" + v + "': " + oneLine(e.what()));
  }
}

std::optional<std::array<float, 8>> ColorPipeline::chromaticities(
    const std::string& colorspace) const {
  auto cs = impl_->config->getColorSpace(canonicalName(colorspace).c_str());
  if (cs->isData()) return std::nullopt;
  for (const KnownPrimaries& k : knownPrimaries())
    for (const char* name : k.names) {
      bool match = name == std::string(cs->getName());
      for (size_t a = 0; a < cs->getNumAliases(); ++a)
        match = match || name == std::string(cs->getAlias(a));
      if (match) return k.xy;
    }
  // Another config's space (Rec.2020, P3-D65, ...): derive its primaries by taking unit RGB
  // back to linear Rec.709 and on to XYZ (through OCIO's built-in Rec.709 -> AP1 -> XYZ D65,
  // whose Bradford steps cancel). Valid only for linear spaces, so check linearity first.
  if (working_.empty() && !impl_->bridge) return std::nullopt;
  try {
    auto toWorking = impl_->config
                         ->getProcessor(impl_->fromWorking(working_, bridge_, cs->getName()),
                                        OCIO::TRANSFORM_DIR_INVERSE)
                         ->getDefaultCPUProcessor();
    auto group = OCIO::GroupTransform::Create();
    auto rec709ToAp1 = OCIO::BuiltinTransform::Create();
    rec709ToAp1->setStyle("UTILITY - ACES-AP1_to_LINEAR-REC709_BFD");
    rec709ToAp1->setDirection(OCIO::TRANSFORM_DIR_INVERSE);
    auto ap1ToXyz = OCIO::BuiltinTransform::Create();
    ap1ToXyz->setStyle("UTILITY - ACES-AP1_to_CIE-XYZ-D65_BFD");
    group->appendTransform(rec709ToAp1);
    group->appendTransform(ap1ToXyz);
    auto toXyz = impl_->config->getProcessor(group)->getDefaultCPUProcessor();
    float probe[3] = {0.2f, 0.5f, 0.7f}, twice[3] = {0.4f, 1.0f, 1.4f};
    toWorking->applyRGB(probe);
    toWorking->applyRGB(twice);
    for (int c = 0; c < 3; ++c)
      if (std::abs(twice[c] - 2 * probe[c]) > 1e-4f * (1 + std::abs(twice[c]))) return std::nullopt;
    std::array<float, 8> xy{};
    const float unit[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    for (int i = 0; i < 4; ++i) {
      float v[3] = {unit[i][0], unit[i][1], unit[i][2]};
      toWorking->applyRGB(v);
      toXyz->applyRGB(v);
      const float sum = v[0] + v[1] + v[2];
      if (!(std::abs(sum) > 1e-6f)) return std::nullopt;
      xy[2 * i] = v[0] / sum, xy[2 * i + 1] = v[1] / sum;
    }
    return xy;
  } catch (const OCIO::Exception&) {
    return std::nullopt;
  }
}

}  // namespace tray
