// The layered material's BRDF integrated direction by direction over an environment's texels: the
// truth the split-sum model (layered.h) is measured against, in the tests and in
// `mipgloss bench layered` (docs/layered-materials.md).
//
// Per texel ω (solid angle Ω, radiance L) at normal N seen from v (μ = N·v, h = (ω + v)/|ω + v|):
//   coat      coat · F(0.04, ω·h) · [N·ω > 0] · lobe_c(R·ω)
//   specular  (1 − E_c(μ)) · F(F0, ω·h) · [N·ω > 0] · lobe_s(R·ω)
//   diffuse   (1 − E_c(μ)) · (1 − E_s(μ)) · diffuseColour · max(0, N·ω)/π
// with each lobe normalized over the same texels (Σ w·Ω = 1, as referenceLobeAt), and E_c, E_s the
// layers' albedos from splitSumIntegral (not the table): Fresnel and the horizon are applied per
// direction, where the model applies them once per pixel from the table. A mirror layer
// (roughness 0) reads the environment along R (bilinear) times F(F0, μ), as the model does.
#pragma once

#include "mipgloss/ibl/cubemap.h"
#include "mipgloss/scene/layered.h"

#include <glm/vec3.hpp>

namespace mipgloss {

struct LayeredPixel {
    Rgb diffuse{0.0f}, specular{0.0f}, coat{0.0f};
    Rgb total() const { return diffuse + specular + coat; }
};

// The reference at one pixel (N and v need not be normalized; v above the surface).
LayeredPixel layeredReference(const CubeMap& environment, const Layers& layers, const glm::dvec3& normal,
                              const glm::dvec3& view);

// The model on the same texels: each layer's weight (layerWeights, from `table`) times its exact
// lobe (the same normalized sums with neither Fresnel nor horizon).
LayeredPixel layeredModel(const CubeMap& environment, const Layers& layers, const glm::dvec3& normal,
                          const glm::dvec3& view, const SplitSumTable& table = SplitSumTable::shared());

}  // namespace mipgloss
