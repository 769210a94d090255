// The GGX reflected lobe as eight Phong lobes fitted to it offline (docs/material-truth.md, "Fitted
// lobes"; the fit: scripts/fit-ggx-lobes.py). K lookups at GGX's visible normals, each as wide as
// its share of the lobe (ggx_sampling.h), is filtered importance sampling: with K = 8 a lookup in
// the lobe's tail stands for a whole ring of it and reads a lobe as wide as the ring, on one side,
// so the sum is far wider than GGX where the tail is (a rough metal's reflection of a forest's dark
// ground 34–48 % too bright, on the CPU model with exact lobes). Instead, at each node of a
// (N·v, roughness) grid, eight normalized Phong lobes (direction, exponent, weight) minimize
//     ∫ (p − Σ w_k P_k)² dω / ∫ p² dω  +  λ · mean over half-spaces H of (∫_H (p − Σ w_k P_k) dω)²
// where p is the glTF specular lobe f·(N·l) of a white metal (GGX D, height-correlated Smith G2;
// Appendix B), normalized, over the whole sphere (a Phong lobe that reads below the horizon pays
// for it), and the half-spaces are edges through the lobe at eight azimuths and nine offsets, and
// the horizon: the squared kernel difference and what an edge in the environment (a sky over a
// dark ground) would let through. λ = 10, set before measuring.
//
// The frame is ggx_sampling.h's: N = z, v = (sin θ, 0, cos θ), R = (−sin θ, 0, cos θ); each lobe
// is stored as q, its offset from R in units of α along e1 = (cos θ, 0, sin θ) (toward N) and
// e2 = y, its direction normalize(R + α(q1 e1 + q2 e2)); its exponent as η = ln(1/((n + 2)α²)),
// so n = e^(−η)/α² − 2 (at least 0); its weight split as the lookups' are by Fresnel (F0 and edge: each lobe's overlap with the (1 − v·h)⁵ part of the lobe). In
// α's units a lobe's shape changes slowly with roughness, so the nodes interpolate bilinearly
// (the renderer's texture does the same).
#pragma once

#include "mipgloss/ibl/ggx_sampling.h"

#include <glm/vec3.hpp>

#include <array>
#include <vector>

namespace mipgloss {

inline constexpr int kFittedLobeCount = 8;
// The grid: N·v columns at x = 1 − √(1 − θ/(π/2)) (GgxAlbedoTable's), x = i/(columns − 1);
// roughness rows from kFittedLeastRoughness by kFittedRoughnessStep.
inline constexpr int kFittedCosNodes = 12;
inline constexpr int kFittedRoughnessNodes = 17;  // to r 0.9 (scripts/fit-ggx-lobes.py: why)
inline constexpr double kFittedLeastRoughness = 0.1;
inline constexpr double kFittedRoughnessStep = 0.05;
// Stored per lobe: q1, q2, η, weight (F0 part), weight (edge part).
inline constexpr int kFittedLobeValues = 5;

struct FittedLobe {
    glm::dvec3 direction{0.0, 0.0, 1.0};  // unit, frame N = z, v = (sin θ, 0, cos θ)
    double exponent = 0.0;
    double weightA = 0.0;  // its weight in the F0-weighted mean (the lookups' a_k)
    double weightB = 0.0;  // in the edge-weighted mean (b_k)
};

// Whether a layer of `roughness` reading `lookups` lookups reads the fitted lobes instead: the
// renderer's K (kFittedLobeCount) and a roughness from 0 (not the mirror) to 0.9; below the grid's
// r 0.1 its first row's lobes at the layer's α. From r 0.8 a layer blends them with its mean lobe
// (ggx_sampling.h, meanLobeShare), which it reads alone from 0.9.
bool readsFittedLobes(double roughness, int lookups);

// The fitted lobes at `roughness` and N·v (bilinear between the nodes, clamped to the grid).
std::array<FittedLobe, kFittedLobeCount> fittedLobes(double roughness, double cosView);

// The sharpest and widest fitted lobe a layer of `roughness` reads over N·v (the grid's columns).
ExponentRange fittedLobeExponentRange(double roughness);
// The sharpest head-on (N·v = 1).
double fittedLobeSharpestHeadOn(double roughness);

// The nodes for the renderer's 2D array texture: kFittedCosNodes × kFittedRoughnessNodes texels,
// 2·kFittedLobeCount layers, RGBA: layer 2k = (q1, q2, η, 0), layer 2k + 1 = (weightA, weightB, 0, 0).
std::vector<float> fittedLobeLayers();

}  // namespace mipgloss
