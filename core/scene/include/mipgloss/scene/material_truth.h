// The truth for a material (docs/material-truth.md): the glTF 2.0 BRDF (gltf_brdf.h) of a layered
// material integrated over the environment as the program decodes it,
//     L(v) = ∫ f(v, ω)·L_env(ω)·(N·ω)⁺ dω,
// by RadianceTree's adapted midpoint rule, independent of the renderer and of its model. Every
// figure about a layered material's picture is measured against it (`mipgloss bench truth`,
// tests/ui/render/test_layered_picture.cpp). Optional energy compensation (Fdez-Agüera 2019) is a
// switch whose truth is the compensated integral; the default is the specification's
// single-scattering BRDF. Also the exact Karis split sum on the same texels: the baseline every
// real-time renderer uses.
#pragma once

#include "mipgloss/ibl/cubemap.h"
#include "mipgloss/ibl/gltf_brdf.h"
#include "mipgloss/ibl/radiance_tree.h"
#include "mipgloss/scene/scene.h"

#include <glm/vec3.hpp>

namespace mipgloss {

// The glTF BRDF a layered material means: F0 = mix(layers.specular, base, metallic),
// c_diff = base·(1 − metallic), α = roughness², the coat's α = coatRoughness², its F0 0.04.
GltfBrdf gltfBrdfOf(const Layers& layers);

struct MaterialPixel {
    glm::dvec3 diffuse{0.0}, specular{0.0}, coat{0.0};
    glm::dvec3 total() const { return diffuse + specular + coat; }
};

// What the compensation (ggx_sampling.h, Scattering) multiplies the specular by at N·v, per channel
// of F0 (1 for Single).
glm::dvec3 energyCompensation(const GltfBrdf& brdf, double roughness, double cosView, Scattering scattering);

// The truth at one pixel: unit normal n, unit view v (toward the eye, above the surface).
// Both in the environment's frame (the baked faces').
MaterialPixel materialTruth(const RadianceTree& environment, const Layers& layers, const glm::dvec3& n,
                            const glm::dvec3& v, Scattering scattering = Scattering::Single,
                            const RadianceTree::Accuracy& accuracy = {});

// A pixel's normal and view at its centre (unit, the environment's frame) and their change to the
// next pixel right (x) and down (y): what a pixel's truth over its area moves across.
struct PixelGeometry {
    glm::dvec3 n{0.0, 0.0, 1.0}, v{0.0, 0.0, 1.0};
    glm::dvec3 dndx{0.0}, dndy{0.0}, dvdx{0.0}, dvdy{0.0};
    // N and v at (ox, oy) pixels from the centre, to first order, as a rasterizer's derivatives
    // move them; v raised to just above the surface where that takes it below (a rim's
    // linearization).
    void at(double ox, double oy, glm::dvec3& normal, glm::dvec3& view) const;
};

// Positions per side for a pixel's mean (materialTruthOverPixel): enough that R moves less than
// about half the sharpest lobe's α between them (R turns twice as fast as N, and with v), at
// most `most` (4: 16 positions).
int areaSubdivisions(const PixelGeometry& g, double alpha, int most = 4);

// The truth over a pixel's area, as a path tracer's box filter gives it: the mean of materialTruth
// over s × s positions evenly spread over the pixel (s = areaSubdivisions for the material's sharpest
// layer); s = 1 is the truth at its centre.
MaterialPixel materialTruthOverPixel(const RadianceTree& environment, const Layers& layers, const PixelGeometry& g,
                                     int subdivisions, Scattering scattering = Scattering::Single,
                                     const RadianceTree::Accuracy& accuracy = {});

// The exact Karis split sum (Karis 2013; Filament, three.js and the glTF Sample Viewer compute its
// approximation): the GGX lobe prefiltered with N = v = R (weighted by N·ω), times the exact
// albedo F0·A + B at N·v; the diffuse E(N)/π·c_diff·(1 − F0·A − B); a coat the same way, layered
// by the glTF coat's Fresnel. On the same texels, by the same tree.
MaterialPixel karisSplitSum(const RadianceTree& environment, const Layers& layers, const glm::dvec3& n,
                            const glm::dvec3& v, const RadianceTree::Accuracy& accuracy = {});

}  // namespace mipgloss
