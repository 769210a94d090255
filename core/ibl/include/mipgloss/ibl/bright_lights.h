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

// The widest of the lights (their radius ρ); 0 for none.
double widestLight(const std::vector<PointLight>& lights);

// The luminance above which a texel is bright: factor × the mean luminance.
double brightThreshold(const CubeMap& base, double factor = kBrightFactor);

// The smooth remainder: the base with every bright texel scaled down to the threshold's luminance
// (its colour kept), i.e. the base less exactly what brightLights takes out, texel by texel, so
// remainder + lights = base in energy whatever the lights' merging. The lobe stack's remainder
// entries (scene/lobes.h) are filtered from it: a GGX layer's lookups read them and need not
// subtract the lights from each lookup. Borders filled.
CubeMap withoutBrightLights(const CubeMap& base, double factor = kBrightFactor);

// How a light's disc meets a GGX layer (the shader's discDistribution, lightDistribution and
// horizonCosine in layered.glsl mirror these; docs/material-truth.md, "The lights' shape").
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
// too bright. Toward grazing the disc about h is an ellipse: lightAveragedGgx.
double discAveragedGgx(double alpha, double cosHalf, double radius);

// GGX's D averaged over the half vectors of a light of angular radius ρ at unit direction l, seen
// from unit v at unit normal n, the light's disc about h taken as the ellipse it is: ρ/2 in the
// plane of l and v, ρ/(2 v·h) across it (δh = (I − hhᵀ)δl / (2 v·h)). Where the ellipse is round
// (v·h ≥ 0.77), lost in the lobe (its long radius in slope space under α/2) or far from the peak
// (its slope-space centre beyond its long radius and 2α) this is discAveragedGgx of the disc of
// the ellipse's area, radius ρ/√(v·h) (which the shader then pays alone); else P22's integral over
// the ellipse mapped to slope space, as an equal-area octagon, is the form factor from the point α
// above the slope plane to that octagon, Lambert's formula Σ Θ_k (n·Γ_k)/2π (Θ_k the angle an edge
// subtends, Γ_k its plane's normal), exact for the octagon; over its solid angle about h and
// cos θh. Far from the peak the edges' terms cancel to the float's precision, hence the disc there.
// Against the mean of D over the light's directions by quadrature, toward grazing (N·v 0.1–0.3):
// within 15 %, 1–2 % about the mirror direction, where the round disc was 0.002–7.8× (tests).
// The equal-area disc alone is no substitute where the ellipse is large against the lobe: it put
// N inside lights it is outside (3.9× at v·h = 0.25, N 0.15 rad off a 0.1 rad light).
double lightAveragedGgx(double alpha, const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& l, double radius);

// (N·l)⁺ averaged over a light's disc of angular radius ρ whose centre has N·l = cosLight: across
// a small disc N·l is its centre's plus the height in it, whose density on [−ρ, ρ] is the
// semicircle's; with u = N·l/ρ the mean is ρ·(u·(½ + (u√(1 − u²) + asin u)/π) + (2/3π)(1 − u²)^{3/2}):
// N·l from ρ above the horizon on, 0 from ρ below it.
double horizonCosine(double cosLight, double radius);

}  // namespace mipgloss
