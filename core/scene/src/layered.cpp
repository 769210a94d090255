#include "mipgloss/scene/layered.h"

#include "mipgloss/ibl/ggx_fitted_lobes.h"
#include "mipgloss/ibl/ggx_sampling.h"
#include "mipgloss/scene/material_truth.h"
#include "mipgloss/ibl/phong.h"

#include <algorithm>

namespace mipgloss {

double diffuseLambda() { return exponentToLambda(1.0); }

double specularLambda(const Layers& layers) { return exponentToLambda(roughnessToExponent(layers.roughness)); }

double coatLambda(const Layers& layers) { return exponentToLambda(roughnessToExponent(layers.coatRoughness)); }

bool hasCoat(const Layers& layers) { return layers.coat > 0.0f; }

namespace {
float metallicOf(const Layers& layers) { return std::clamp(layers.metallic, 0.0f, 1.0f); }
}  // namespace

DielectricFresnel dielectricFresnel(const Layers& layers) {
    DielectricFresnel d;
    d.f90 = std::clamp(layers.specularWeight, 0.0f, 1.0f);
    for (int c = 0; c < 3; ++c) d.f0[c] = std::min(layers.specular * layers.specularColor[c], 1.0f) * d.f90;
    // fresnel_mix's max over channels of F: F grows with F0, so it is the largest channel's.
    d.diffuseF0 = std::max({d.f0.r, d.f0.g, d.f0.b});
    return d;
}

Rgb specularF0(const Layers& layers) {
    const float m = metallicOf(layers);
    return dielectricFresnel(layers).f0 * (1.0f - m) + layers.baseColor * m;
}

float specularF90(const Layers& layers) {
    const float m = metallicOf(layers);
    return dielectricFresnel(layers).f90 * (1.0f - m) + m;
}

Rgb diffuseFresnelF0(const Layers& layers) {
    const float m = metallicOf(layers);
    return Rgb(dielectricFresnel(layers).diffuseF0) * (1.0f - m) + layers.baseColor * m;
}

Rgb diffuseColour(const Layers& layers) { return layers.baseColor * (1.0f - metallicOf(layers)); }

LayerWeights layerWeights(const Layers& layers, double cosView, const SplitSumTable& table) {
    const double mu = std::clamp(cosView, 0.0, 1.0);
    const SplitSum s = table.at(specularLambda(layers), mu);
    const Rgb f0 = specularF0(layers);
    Rgb specularAlbedo;
    for (int c = 0; c < 3; ++c) specularAlbedo[c] = static_cast<float>(s.albedo(f0[c]));
    float coatAlbedo = 0.0f;
    if (hasCoat(layers)) {
        const SplitSum sc = table.at(coatLambda(layers), mu);
        coatAlbedo = static_cast<float>(layers.coat * sc.albedo(kDielectricF0));
    }
    LayerWeights w;
    w.coat = Rgb(coatAlbedo);
    w.specular = (1.0f - coatAlbedo) * specularAlbedo;
    w.diffuse = (1.0f - coatAlbedo) * (Rgb(1.0f) - specularAlbedo) * diffuseColour(layers);
    return w;
}

LayerWeights ggxLayerWeights(const Layers& layers, double cosView, Scattering scattering) {
    const double mu = std::clamp(cosView, 0.0, 1.0);
    const GgxAlbedoTable& table = GgxAlbedoTable::shared();
    const GgxAlbedoTable::Albedo e = table.at(layers.roughness, mu);
    const double coatWeight = coatFresnelWeight(gltfBrdfOf(layers), mu);
    const double base = 1.0 - coatWeight;
    const Rgb f0 = specularF0(layers), fd0 = diffuseFresnelF0(layers);
    const float f90 = specularF90(layers), bd = static_cast<float>(e.diffuseEdge);
    LayerWeights w;
    w.specular = static_cast<float>(base) * (f0 * static_cast<float>(e.a) + Rgb(f90 * static_cast<float>(e.b)));
    w.specular *= Rgb(scatteringCompensation(glm::dvec3(f0), e, scattering));
    w.diffuse = static_cast<float>(base) * diffuseColour(layers) * (Rgb(1.0f) - fd0 - (Rgb(f90) - fd0) * bd);
    if (coatWeight > 0.0) {
        const GgxAlbedoTable::Albedo c = table.at(layers.coatRoughness, mu);
        w.coat = Rgb(static_cast<float>(coatWeight * (c.a + c.b)));
    }
    return w;
}

std::vector<double> lambdasOf(const Material& material) {
    if (!material.layered) return {static_cast<double>(material.lambda)};
    // A GGX layer's lookups read lobes from its sharpest to its widest (ggx_sampling.h), from the
    // chain until the stack holds them.
    std::vector<double> out{specularLambda(material.layers)};
    auto lookups = [&](double roughness) {
        if (!(roughness > 0.0)) return;
        // The visible normals' (a roughness map's fragments read them), and the fitted lobes' where
        // the layer has them (ggx_fitted_lobes.h).
        auto push = [&](const ExponentRange& range) {
            out.push_back(exponentToLambda(range.sharpest));
            out.push_back(exponentToLambda(range.widest));
        };
        push(lookupExponentRange(roughness * roughness, kGgxLookups));
        if (readsFittedLobes(roughness, kGgxLookups)) push(fittedLobeExponentRange(roughness));
    };
    lookups(material.layers.roughness);
    if (hasCoat(material.layers)) {
        out.push_back(coatLambda(material.layers));
        lookups(material.layers.coatRoughness);
    }
    if (!material.useIrradiance) out.push_back(diffuseLambda());
    return out;
}

}  // namespace mipgloss
