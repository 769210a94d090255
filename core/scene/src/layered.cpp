#include "mipgloss/scene/layered.h"

#include "mipgloss/ibl/phong.h"

#include <algorithm>

namespace mipgloss {

double diffuseLambda() { return exponentToLambda(1.0); }

double specularLambda(const Layers& layers) { return exponentToLambda(roughnessToExponent(layers.roughness)); }

double coatLambda(const Layers& layers) { return exponentToLambda(roughnessToExponent(layers.coatRoughness)); }

bool hasCoat(const Layers& layers) { return layers.coat > 0.0f; }

Rgb specularF0(const Layers& layers) {
    const float m = std::clamp(layers.metallic, 0.0f, 1.0f);
    return Rgb(layers.specular) * (1.0f - m) + layers.baseColor * m;
}

Rgb diffuseColour(const Layers& layers) { return layers.baseColor * (1.0f - std::clamp(layers.metallic, 0.0f, 1.0f)); }

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

std::vector<double> lambdasOf(const Material& material) {
    if (!material.layered) return {static_cast<double>(material.lambda)};
    std::vector<double> out{specularLambda(material.layers)};
    if (hasCoat(material.layers)) out.push_back(coatLambda(material.layers));
    if (!material.useIrradiance) out.push_back(diffuseLambda());
    return out;
}

}  // namespace mipgloss
