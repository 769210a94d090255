// The glTF 2.0 metallic–roughness BRDF exactly as the specification's Appendix B writes it, and
// KHR_materials_clearcoat's layer as its own text writes it: the material an artist means, and the
// truth every picture of a layered material is measured against (material_truth.h,
// docs/material-truth.md). Pure functions of unit vectors in one frame; no environment, no model.
//
//   f = (1 − F)·c_diff/π + F·D·V                    (Appendix B, "metal_brdf" and "dielectric_brdf"
//                                                     mixed by metallic, in its implementation form)
//   D = α² / (π ((N·H)²(α² − 1) + 1)²),  α = roughness²          (Trowbridge–Reitz / GGX)
//   V = ½ / (N·L √((N·V)²(1 − α²) + α²) + N·V √((N·L)²(1 − α²) + α²))   (height-correlated Smith)
//   F = F0 + (1 − F0)(1 − V·H)⁵,  F0 = mix(0.04, base, metallic),  c_diff = base·(1 − metallic)
// and the clear coat (KHR_materials_clearcoat, "Layering"), with its Fresnel at V·N, not V·H:
//   coated = mix(f, D_c·V_c, clearcoat · (0.04 + 0.96 (1 − V·N)⁵)),  α_c = clearcoatRoughness².
// The dielectric F0 is a parameter (0.04 in glTF; Layers::specular) so the same code serves both.
// KHR_materials_specular (with KHR_materials_ior) generalizes F: F = F0 + (F90 − F0)(1 − V·H)⁵, the
// dielectric's F0 = min(F0_ior · specularColor, 1) · specularWeight and F90 = specularWeight, and
// the diffuse keeps 1 − specularWeight · max_channel(F) (its fresnel_mix), which in the mixed form
// above is 1 − Fd with Fd of F0 `diffuseF0` and the same F90 (layered.h: diffuseFresnelF0).
#pragma once

#include <glm/vec3.hpp>

namespace mipgloss {

// GGX's normal distribution D at N·H = cosHalf (0 below the surface). α = 0 is a delta: 0 here.
double ggxDistribution(double alpha, double cosHalf);
// Height-correlated Smith visibility V = G2 / (4 N·L N·V) as Appendix B writes it (0 unless both
// cosines are positive).
double smithVisibility(double alpha, double cosLight, double cosView);
// Smith's masking G1 for GGX at cosine c: 2c / (c + √(α² + (1 − α²)c²)).
double smithMasking(double alpha, double cosine);

// A layered material as the glTF BRDF reads it (material_truth.h makes one from Layers).
struct GltfBrdf {
    glm::dvec3 f0{0.04};       // mix(dielectric F0, base, metallic)
    double f90 = 1.0;          // mix(specularWeight, 1, metallic)
    glm::dvec3 diffuseF0{0.04};  // the F0 of what the diffuse loses (f0 without KHR_materials_specular)
    glm::dvec3 diffuse{0.0};   // c_diff = base·(1 − metallic)
    double alpha = 0.25;       // roughness²
    double clearcoat = 0.0;    // the coat's weight, 0: none
    double coatAlpha = 0.0025; // clearcoatRoughness²
    double coatF0 = 0.04;      // ((1 − 1.5)/(1 + 1.5))²
};

// f·(N·L)⁺ toward light direction l seen from v at normal n (unit vectors, v above the surface),
// split by term: the base's diffuse and specular already multiplied by the coat's (1 − c·Fc), and
// the coat's own lobe by c·Fc. Sum them for the BRDF times the cosine.
struct BrdfCosine {
    glm::dvec3 diffuse{0.0}, specular{0.0}, coat{0.0};
    glm::dvec3 total() const { return diffuse + specular + coat; }
};
BrdfCosine gltfBrdfCosine(const GltfBrdf& brdf, const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& l);

// The coat's Fresnel weight c·(F0c + (1 − F0c)(1 − N·V)⁵): what the coat takes from the base.
double coatFresnelWeight(const GltfBrdf& brdf, double cosView);

}  // namespace mipgloss
