#include "mipgloss/ibl/gltf_brdf.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mipgloss {

double ggxDistribution(double alpha, double cosHalf) {
    if (cosHalf <= 0.0 || alpha <= 0.0) return 0.0;
    const double a2 = alpha * alpha;
    const double d = cosHalf * cosHalf * (a2 - 1.0) + 1.0;
    return a2 / (std::numbers::pi * d * d);
}

double smithVisibility(double alpha, double cosLight, double cosView) {
    if (cosLight <= 0.0 || cosView <= 0.0) return 0.0;
    const double a2 = alpha * alpha;
    const double ggxV = cosLight * std::sqrt(cosView * cosView * (1.0 - a2) + a2);
    const double ggxL = cosView * std::sqrt(cosLight * cosLight * (1.0 - a2) + a2);
    const double sum = ggxV + ggxL;
    return sum > 0.0 ? 0.5 / sum : 0.0;
}

double smithMasking(double alpha, double cosine) {
    if (cosine <= 0.0) return 0.0;
    const double a2 = alpha * alpha;
    return 2.0 * cosine / (cosine + std::sqrt(a2 + (1.0 - a2) * cosine * cosine));
}

double coatFresnelWeight(const GltfBrdf& brdf, double cosView) {
    if (brdf.clearcoat <= 0.0) return 0.0;
    const double m = 1.0 - std::clamp(std::abs(cosView), 0.0, 1.0);
    return brdf.clearcoat * (brdf.coatF0 + (1.0 - brdf.coatF0) * m * m * m * m * m);
}

BrdfCosine gltfBrdfCosine(const GltfBrdf& brdf, const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& l) {
    BrdfCosine out;
    const double cosLight = glm::dot(n, l), cosView = glm::dot(n, v);
    if (cosLight <= 0.0 || cosView <= 0.0) return out;
    const glm::dvec3 sum = l + v;
    const double length = glm::length(sum);
    if (!(length > 0.0)) return out;
    const glm::dvec3 h = sum / length;
    const double cosHalf = glm::dot(n, h), vh = std::clamp(glm::dot(v, h), 0.0, 1.0);
    const double m = 1.0 - vh, m5 = m * m * m * m * m;
    const glm::dvec3 fresnel = brdf.f0 + (glm::dvec3(brdf.f90) - brdf.f0) * m5;
    const glm::dvec3 diffuseFresnel = brdf.diffuseF0 + (glm::dvec3(brdf.f90) - brdf.diffuseF0) * m5;
    const double base = 1.0 - coatFresnelWeight(brdf, cosView);
    out.diffuse = base * (glm::dvec3(1.0) - diffuseFresnel) * brdf.diffuse * (cosLight / std::numbers::pi);
    out.specular = base * fresnel * (ggxDistribution(brdf.alpha, cosHalf) * smithVisibility(brdf.alpha, cosLight, cosView) * cosLight);
    if (brdf.clearcoat > 0.0)
        out.coat = glm::dvec3(coatFresnelWeight(brdf, cosView) * ggxDistribution(brdf.coatAlpha, cosHalf) *
                              smithVisibility(brdf.coatAlpha, cosLight, cosView) * cosLight);
    return out;
}

}  // namespace mipgloss
