#include "mipgloss/scene/layered_reference.h"

#include "mipgloss/ibl/phong.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mipgloss {

namespace {

// One glossy lobe summed over the texels: Σ w·g(ω)·L·Ω / Σ w·Ω with w = max(0, R·ω)^n, where g is
// Fresnel times the horizon (`withFresnel`) or 1.
Rgb lobeSum(const CubeMap& env, double exponent, const glm::dvec3& r, const glm::dvec3& n, const glm::dvec3& v,
            const Rgb& f0, bool withFresnel) {
    if (std::isinf(exponent)) {  // the mirror: one direction, r
        const Rgb l = env.sample(glm::vec3(r));
        if (!withFresnel) return l;
        Rgb out;
        for (int c = 0; c < 3; ++c)
            out[c] = static_cast<float>(schlickFresnel(f0[c], glm::dot(n, v)) * l[c]);
        return out;
    }
    const int size = env.size();
    glm::dvec3 sum(0.0);
    double weights = 0.0;
    for (Face f : kAllFaces)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const glm::dvec3 w = glm::normalize(glm::dvec3(texelDirection(f, x, y, size)));
                const double c = glm::dot(r, w);
                if (c <= 0.0) continue;
                const double omega = texelSolidAngle(x, y, size);
                const double lobe = std::exp(exponent * std::log(c)) * omega;
                weights += lobe;
                if (withFresnel && glm::dot(n, w) <= 0.0) continue;
                const glm::dvec3 l(env.at(f, x, y));
                if (!withFresnel) {
                    sum += lobe * l;
                    continue;
                }
                const double cosH = glm::dot(w, glm::normalize(w + v));
                for (int k = 0; k < 3; ++k) sum[k] += lobe * schlickFresnel(f0[k], cosH) * l[k];
            }
    return weights > 0.0 ? Rgb(sum / weights) : Rgb(0.0f);
}

struct Frame {
    glm::dvec3 n, v, r;
    double mu;
};

Frame frameOf(const glm::dvec3& normal, const glm::dvec3& view) {
    Frame fr;
    fr.n = glm::normalize(normal);
    fr.v = glm::normalize(view);
    fr.mu = std::clamp(glm::dot(fr.n, fr.v), 0.0, 1.0);
    fr.r = glm::normalize(2.0 * glm::dot(fr.n, fr.v) * fr.n - fr.v);
    return fr;
}

}  // namespace

LayeredPixel layeredReference(const CubeMap& env, const Layers& layers, const glm::dvec3& normal,
                              const glm::dvec3& view) {
    const Frame fr = frameOf(normal, view);
    const double ns = roughnessToExponent(layers.roughness);
    const Rgb f0 = specularF0(layers);
    // The layers' own albedos at μ, integrated (what each passes on is part of the BRDF).
    const SplitSum s = splitSumIntegral(ns, fr.mu);
    Rgb specularAlbedo;
    for (int c = 0; c < 3; ++c) specularAlbedo[c] = static_cast<float>(s.albedo(f0[c]));
    LayeredPixel out;
    float coatAlbedo = 0.0f;
    if (hasCoat(layers)) {
        const double nc = roughnessToExponent(layers.coatRoughness);
        coatAlbedo = static_cast<float>(layers.coat * splitSumIntegral(nc, fr.mu).albedo(kDielectricF0));
        out.coat = layers.coat * lobeSum(env, nc, fr.r, fr.n, fr.v, Rgb(static_cast<float>(kDielectricF0)), true);
    }
    out.specular = (1.0f - coatAlbedo) * lobeSum(env, ns, fr.r, fr.n, fr.v, f0, true);
    out.diffuse = (1.0f - coatAlbedo) * (Rgb(1.0f) - specularAlbedo) * diffuseColour(layers) *
                  lobeSum(env, 1.0, fr.n, fr.n, fr.v, Rgb(0.0f), false);
    return out;
}

LayeredPixel layeredModel(const CubeMap& env, const Layers& layers, const glm::dvec3& normal,
                          const glm::dvec3& view, const SplitSumTable& table) {
    const Frame fr = frameOf(normal, view);
    const LayerWeights w = layerWeights(layers, fr.mu, table);
    LayeredPixel out;
    const Rgb none(0.0f);
    out.specular = w.specular * lobeSum(env, roughnessToExponent(layers.roughness), fr.r, fr.n, fr.v, none, false);
    if (hasCoat(layers))
        out.coat = w.coat * lobeSum(env, roughnessToExponent(layers.coatRoughness), fr.r, fr.n, fr.v, none, false);
    out.diffuse = w.diffuse * lobeSum(env, 1.0, fr.n, fr.n, fr.v, none, false);
    return out;
}

}  // namespace mipgloss
