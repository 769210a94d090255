// The environment's few bright texels as points of energy (docs/material-truth.md): what the
// renderer shades with the material's exact BRDF, leaving the lookups only the smooth remainder.
// A sun or a studio's soft boxes are where a lobe's shape matters most and where a few lookups
// per layer miss most (their error on sunrise falls from 20 % to 1.3 % for a metal of roughness
// 0.3, measured in tests/core/scene/test_ggx_lookups.cpp).
//
// A texel is bright when its luminance exceeds kBrightFactor times the sphere's mean luminance
// (solid-angle weighted); its excess over that threshold, scaled per channel, is its light's
// energy Ω·(L − L·T/lum). Bright texels are merged 2×2 a level at a time (energy summed, direction
// the luminance-weighted mean) until at most `maxLights` remain.
#pragma once

#include "mipgloss/ibl/cubemap.h"

#include <glm/vec3.hpp>

#include <vector>

namespace mipgloss {

inline constexpr double kBrightFactor = 16.0;
inline constexpr int kMaxBrightLights = 32;

struct PointLight {
    glm::vec3 direction{0.0f, 0.0f, 1.0f};  // unit, in the cube's frame
    Rgb energy{0.0f};                       // Σ Ω·(L − clamped L) over its texels
    float radius = 0.0f;                    // the disc it stands for: √(2 E[θ²]) about its direction (radians)
};

// The lights, brightest first; none for a cube with no texel over the threshold.
std::vector<PointLight> brightLights(const CubeMap& base, double factor = kBrightFactor, int maxLights = kMaxBrightLights);

// The luminance above which a texel is bright: factor × the mean luminance.
double brightThreshold(const CubeMap& base, double factor = kBrightFactor);

// The smooth remainder: the base with every bright texel scaled down to the threshold's luminance
// (its colour kept), i.e. the base less exactly what brightLights takes out, texel by texel, so
// remainder + lights = base in energy whatever the lights' merging. The lobe stack's remainder
// entries (scene/lobes.h) are filtered from it: a GGX layer's lookups read them and need not
// subtract the lights from each lookup. Borders filled.
CubeMap withoutBrightLights(const CubeMap& base, double factor = kBrightFactor);

}  // namespace mipgloss
