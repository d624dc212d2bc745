#include "core/material.h"

namespace tray {

PhongParams phongFromPbr(const Material& m) {
  // Dielectrics keep their base color as diffuse and a white 4% specular; metals put the base
  // color into the specular and the mirror term. Smoothness maps to the Phong exponent through
  // the usual Blinn-Phong/Beckmann correspondence shininess = 2 / alpha^2 - 2 with alpha =
  // roughness^2 (Walter et al. 2007, eq. 30).
  PhongParams p;
  float alpha = std::max(m.roughness * m.roughness, 1e-3f);
  p.shininess = std::min(2.0f / (alpha * alpha) - 2.0f, 1e4f);
  float dielectric = 1.0f - m.metallic;
  p.diffuse = m.baseColor * (dielectric * (1.0f - m.transmission));
  p.specular = Color(0.04f) * dielectric + m.baseColor * m.metallic;
  float smooth = 1.0f - m.roughness;
  p.reflectance = m.metallic * smooth * smooth;
  p.transmittance = m.transmission * dielectric;
  p.ambient = p.diffuse;  // ambient light is reflected like diffuse light
  return p;
}

}  // namespace tray
