// Diffuse lighting for normal-lookup materials.
//
// Irradiance/π at normal N is E(N)/π = ∫ L(ω) max(0, N·ω)/π dω, which is the normalized Phong
// lobe with n = 1 (docs/irradiance.md: D₁(t) = t/π). We compute it by direct convolution of an
// energy-preserving pyramid level of the base (face size <= 32), output at face size 32: exact up
// to the pyramid's point approximation, unlike a 9-coefficient spherical-harmonic fit whose
// truncation leaves a few percent.
#pragma once

#include "mipgloss/ibl/cubemap.h"

namespace mipgloss {

inline constexpr int kIrradianceFaceSize = 32;

// E(N)/π on a cube of face size min(outSize, base size), borders filled.
CubeMap computeIrradiance(const CubeMap& base, int outSize = kIrradianceFaceSize);

}  // namespace mipgloss
