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

// How a light's disc meets a GGX layer (the shader's discDistribution and horizonCosine in
// layered.glsl mirror these; docs/material-truth.md, "The lights' shape").
//
// GGX's D averaged over the half vectors of a light of angular radius `radius` whose centre has
// N·h = cosHalf. In slope space D·cos θh·dω is P22(s) = α²/(π(α² + |s|²)²) (Walter et al. 2007),
// whose mean over a disc of radius R at distance d is the point-to-parallel-disc form factor over
// πR²: ½(1 − (a − R²)/√((a − R²)² + 4α²R²))/(πR²), a = α² + d², exact. The light's disc about h has
// radius ρ/2 (a reflected direction turns twice as fast as h), and a slope moves by dθ/cos²θ
// radially and dθ/cos θ across: the disc of the same area, R = (ρ/2)/cos^{3/2}θh, kept off the
// horizon (the angle within half its distance to it, where D is its tail). So the highlight has
// the disc's flat core where the light is wider than the lobe, and GGX's own tail α²/(π d⁴) far
// from it: widening α instead (α'² = α² + R², what the lights did before) made the tail (α'/α)²
// too bright. Not modelled: toward grazing the disc about h is wider across the plane of
// incidence than in it (dω_h = dω_l/(4 v·h)), by 1/(v·h); as its equal-area disc it put the peak
// inside lights it is outside (3.9× too bright with N 0.15 rad off a 0.1 rad light at v·h = 0.25,
// against the patch's mean by quadrature), so the disc stays round.
double discAveragedGgx(double alpha, double cosHalf, double radius);

// (N·l)⁺ averaged over a light's disc of angular radius ρ whose centre has N·l = cosLight: across
// a small disc N·l is its centre's plus the height in it, whose density on [−ρ, ρ] is the
// semicircle's; with u = N·l/ρ the mean is ρ·(u·(½ + (u√(1 − u²) + asin u)/π) + (2/3π)(1 − u²)^{3/2}):
// N·l from ρ above the horizon on, 0 from ρ below it.
double horizonCosine(double cosLight, double radius);

}  // namespace mipgloss
