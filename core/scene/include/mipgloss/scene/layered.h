// The layered material's closed forms (docs/layered-materials.md): what each layer reads and the
// weight its exact lobe value is multiplied by. GL-free; object.frag and aov.frag compute the same
// weights from the same split-sum table (specular.h), and the tests hold them to these.
//
// Three lookups into the one chain, each the exact lobe it claims (lobes.h once settled):
//   diffuse   by the normal N at n = 1: E(N)/π (or the irradiance map)
//   specular  by the reflection vector R at n = roughnessToExponent(roughness)
//   coat      by R at n = roughnessToExponent(coatRoughness), only when coat > 0
// and the picture is Σ weight_X ⊙ lobe_X, with μ = N·v:
//   F0        = mix(specular, baseColor, metallic)          (per channel)
//   E_s       = F0·A(n_s, μ) + B(n_s, μ)                     the specular layer's albedo
//   E_c       = coat · (0.04·A(n_c, μ) + B(n_c, μ))          the coat's
//   w_coat    = E_c
//   w_spec    = (1 − E_c) · E_s
//   w_diffuse = (1 − E_c) · (1 − E_s) · baseColor·(1 − metallic)
// Each layer passes on what it does not reflect (albedo scaling): in a uniform white environment
// every lobe reads 1 and a white dielectric sums to exactly 1 (the furnace test).
#pragma once

#include "mipgloss/ibl/cubemap.h"
#include "mipgloss/ibl/specular.h"
#include "mipgloss/scene/scene.h"

#include <vector>

namespace mipgloss {

// λ of the diffuse base's lobe, n = 1 (phong.h: exponentToLambda(1)).
double diffuseLambda();
// λ of the specular layer's and the coat's lobes.
double specularLambda(const Layers& layers);
double coatLambda(const Layers& layers);
bool hasCoat(const Layers& layers);

// The Fresnel terms (glTF 2.0 Appendix B with KHR_materials_specular and KHR_materials_ior): the
// dielectric's F0 = min(specular · specularColor, 1) · specularWeight and F90 = specularWeight;
// specularF0/F90 mix them with the metal's (baseColor, 1) by metallic. The diffuse loses what the
// extension's fresnel_mix takes, specularWeight · max over channels of F, whose F0 is
// diffuseFresnelF0 (the dielectric's max channel, mixed with the metal's likewise) and F90
// specularF90. Without the extension (colour 1, weight 1) all three are glTF's F0 and 1.
struct DielectricFresnel {
    Rgb f0{0.04f};           // min(specular · specularColor, 1) · specularWeight
    float f90 = 1.0f;        // specularWeight
    float diffuseF0 = 0.04f; // f0's largest channel: the F0 of what the diffuse loses
};
// The dielectric's terms alone (metallic 0), which the maps program mixes per fragment with the
// mapped metal's; the three below mix them with the material's own metallic.
DielectricFresnel dielectricFresnel(const Layers& layers);
Rgb specularF0(const Layers& layers);
float specularF90(const Layers& layers);
Rgb diffuseFresnelF0(const Layers& layers);
Rgb diffuseColour(const Layers& layers);

struct LayerWeights {
    Rgb diffuse{0.0f};
    Rgb specular{0.0f};
    Rgb coat{0.0f};  // grey: the coat is colourless
};

// The weights at N·v = cosView (clamped to [0, 1]) from `table`'s A and B.
LayerWeights layerWeights(const Layers& layers, double cosView,
                          const SplitSumTable& table = SplitSumTable::shared());

// The glTF material's weights at N·v (layered.glsl, layerWeightsOf; docs/material-truth.md): what
// each layer returns in a uniform white environment, from the exact albedo table (ggx_sampling.h).
//   coat      c·Fc·(A_c + B_c),  Fc = 0.04 + 0.96 (1 − N·v)⁵
//   specular  (1 − c·Fc)·(F0·A + F90·B)
//   diffuse   (1 − c·Fc)·c_diff·(1 − Fd0 − (F90 − Fd0)·Bd)   Fd0 = diffuseFresnelF0
//             (with F90 = 1: (1 − F0)(1 − Bd))
// The specular × 1 + F0·(1 − A − B)/(A + B) per channel when compensated (ggx_sampling.h).
LayerWeights ggxLayerWeights(const Layers& layers, double cosView, Scattering scattering = Scattering::Single);

// Every λ a material reads (its lobes in use, for stack entries and the chain's depth): the single
// lobe's λ; a layered material's specular λ, its coat's when it has one, and the diffuse λ unless
// it reads the irradiance map.
std::vector<double> lambdasOf(const Material& material);

}  // namespace mipgloss
