#pragma once
#include "core/integrator.h"

namespace tray {

/// Whitted's recursive ray tracer (Whitted 1980) with the seed's Phong model.
std::unique_ptr<Integrator> makeWhitted(const RenderContext& ctx);
/// Its options: --max-depth (default 5).
const std::vector<OptionSpec>& whittedOptions();

/// Direct Phong reflection at a surface from one light's irradiance E arriving along wi:
/// (kd / pi) E cos(theta_i) + ks (s + 2) / (2 pi) max(0, r . wo)^s E cos(theta_i), the
/// energy-normalised Phong lobe (Lafortune & Willems 1994), r = mirror of wi about n.
Color phongDirect(const PhongParams& p, const Vec3& n, const Vec3& wo, const Vec3& wi,
                  const Color& irradiance);

}  // namespace tray
