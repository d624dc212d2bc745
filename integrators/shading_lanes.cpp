#include "integrators/shading_lanes.h"

#include <algorithm>

#include "core/simd_lanes.h"

namespace tray {

void ShadingLanes::reset(size_t size) {
  count = 0;
  const size_t padded = wholeSimdVectors(size);
  if (padded <= emitter.size()) return;
  for (std::vector<Vec3>* v : {&p, &ng, &n, &wo, &albedo, &beta, &shadowOrigin, &shadowDir,
                               &contribution, &rayOrigin, &rayDir, &nextBeta})
    v->resize(padded);
  lightDraw.resize(padded), bsdfDraw.resize(padded);
  for (std::vector<float>* v :
       {&pmf, &lobeDraw, &metallic, &roughness, &eta, &pdf, &time, &etaScale})
    v->resize(padded);
  for (std::vector<int32_t>* v : {&emitter, &lit, &shadowUnbounded, &deltaSample, &transmitted, &material})
    v->resize(padded);
  for (std::vector<uint8_t>* v : {&belowMatters, &frontFace, &refractive}) v->resize(padded);
  path.resize(padded);
}

void ShadingLanes::padInputs() {
  const auto from = ptrdiff_t(count), to = ptrdiff_t(wholeSimdVectors(count));
  for (std::vector<Vec3>* v : {&p, &ng, &n, &wo, &albedo, &beta})
    std::fill(v->begin() + from, v->begin() + to, Vec3(0.0f));
  std::fill(lightDraw.begin() + from, lightDraw.begin() + to, Vec2{0.0f, 0.0f});
  std::fill(bsdfDraw.begin() + from, bsdfDraw.begin() + to, Vec2{0.0f, 0.0f});
  for (std::vector<float>* v : {&pmf, &lobeDraw, &metallic, &roughness, &eta})
    std::fill(v->begin() + from, v->begin() + to, 0.0f);
  std::fill(emitter.begin() + from, emitter.begin() + to, int32_t(kNoLightChosen));
}

}  // namespace tray
