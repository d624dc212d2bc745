#pragma once
#include <cmath>

#include "core/math.h"
// fresnelDielectric, fresnelSchlick and refractDirection, written once for scalar code and the
// SIMD stages.
#include "materials/fresnel_lanes.h"
