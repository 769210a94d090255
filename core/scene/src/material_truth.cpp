#include "mipgloss/scene/material_truth.h"

#include "mipgloss/ibl/ggx_sampling.h"
#include "mipgloss/scene/layered.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mipgloss {

namespace {

// Where the integrand is sharp: about R, as wide as the sharper GGX lobe's reflected width: 2α in
// the plane of incidence (reflection doubles the half vector's angle there) and 2α·(v·h) ≈ 2α·N·v
// across it (the lobe is squeezed at grazing), so 2α·N·v, and never wider than 0.6 rad, so no node the
// walk takes whole is wider than 0.09 rad: a node's energy sits at its normalized mean direction,
// which overstates a smooth lobe's cosine-like falloff by about radius²/4 (0.2 % at 0.09 rad;
// 2.2 % at 0.3, measured on the Lambert lobe in test_gltf_brdf.cpp).
constexpr double kWidestFocus = 0.6;
RadianceTree::Focus focusOf(double alpha, const glm::dvec3& n, const glm::dvec3& v) {
    RadianceTree::Focus focus;
    focus.centre = glm::normalize(2.0 * glm::dot(n, v) * n - v);
    focus.width = std::min(2.0 * alpha * std::max(glm::dot(n, v), 0.02), kWidestFocus);
    focus.horizon = n;
    // Along the plane of incidence the lobe is 2α long (two of its widths from the centre hold
    // its peak's shape); across it, focus.width.
    focus.length = std::min(4.0 * alpha, kWidestFocus);
    const glm::dvec3 across = glm::cross(n, v);
    const double acrossLength = glm::length(across);
    focus.across = acrossLength > 1e-9 ? across / acrossLength : glm::dvec3(0.0);
    return focus;
}

glm::dvec3 toD(const Rgb& c) { return glm::dvec3(c); }

}  // namespace

GltfBrdf gltfBrdfOf(const Layers& layers) {
    GltfBrdf brdf;
    brdf.f0 = toD(specularF0(layers));
    brdf.f90 = specularF90(layers);
    brdf.diffuseF0 = toD(diffuseFresnelF0(layers));
    brdf.diffuse = toD(diffuseColour(layers));
    brdf.alpha = static_cast<double>(layers.roughness) * layers.roughness;
    brdf.clearcoat = layers.coat;
    brdf.coatAlpha = static_cast<double>(layers.coatRoughness) * layers.coatRoughness;
    return brdf;
}

glm::dvec3 energyCompensation(const GltfBrdf& brdf, double roughness, double cosView, Scattering scattering) {
    return scatteringCompensation(brdf.f0, GgxAlbedoTable::shared().at(roughness, cosView), scattering);
}

MaterialPixel materialTruth(const RadianceTree& environment, const Layers& layers, const glm::dvec3& n,
                            const glm::dvec3& v, Scattering scattering, const RadianceTree::Accuracy& accuracy) {
    const GltfBrdf brdf = gltfBrdfOf(layers);
    const double mu = glm::dot(n, v);
    MaterialPixel pixel;
    // Each term by the walk that suits it: the diffuse about N, each GGX lobe about R.
    environment.walk(RadianceTree::Focus{n, kWidestFocus, n}, [&](const glm::dvec3& l, const glm::dvec3& energy) {
        pixel.diffuse += gltfBrdfCosine(brdf, n, v, l).diffuse * energy;
    }, accuracy);
    const double base = 1.0 - coatFresnelWeight(brdf, mu);
    // Sharp lobes too: the walk splits the texels under a lobe narrower than they are by area
    // (radiance_tree.cpp), and takes the rest of the map, a sun in GGX's tail included, as its
    // nodes. Sampling the lobe's visible normals instead (64 × 64 strata, before) missed or
    // overstated such a sun by a stratum's area: 15.2 where the integral is 9.2 on a near-mirror
    // pixel of sunrise (docs/material-truth.md, "The near-mirror's tail").
    GltfBrdf bare = brdf;
    bare.clearcoat = 0.0;
    environment.walk(focusOf(brdf.alpha, n, v), [&](const glm::dvec3& l, const glm::dvec3& energy) {
        pixel.specular += gltfBrdfCosine(bare, n, v, l).specular * energy;
    }, accuracy);
    pixel.specular *= base;
    if (brdf.clearcoat > 0.0) {
        environment.walk(focusOf(brdf.coatAlpha, n, v), [&](const glm::dvec3& l, const glm::dvec3& energy) {
            pixel.coat += gltfBrdfCosine(brdf, n, v, l).coat * energy;
        }, accuracy);
    }
    pixel.specular *= energyCompensation(brdf, layers.roughness, mu, scattering);
    return pixel;
}

MaterialPixel karisSplitSum(const RadianceTree& environment, const Layers& layers, const glm::dvec3& n,
                            const glm::dvec3& v, const RadianceTree::Accuracy& accuracy) {
    const GltfBrdf brdf = gltfBrdfOf(layers);
    const double mu = std::clamp(glm::dot(n, v), 0.0, 1.0);
    const glm::dvec3 r = glm::normalize(2.0 * glm::dot(n, v) * n - v);
    // The lobe prefiltered with N = v = R (Karis 2013, weighted by N·L): Σ D(h)·(R·ω)·E over the
    // tree, h = (ω + R)/|ω + R|, divided by the same weight's integral over the sphere.
    auto prefiltered = [&](double alpha) {
        alpha = std::max(alpha, 1e-4);
        glm::dvec3 sum(0.0);
        environment.walk(RadianceTree::Focus{r, std::min(2.0 * alpha, kWidestFocus), r}, [&](const glm::dvec3& l, const glm::dvec3& energy) {
            const double cosL = glm::dot(r, l);
            if (cosL > 0.0) sum += ggxDistribution(alpha, glm::dot(r, glm::normalize(l + r))) * cosL * energy;
        }, accuracy);
        // ∫ D(h)(R·ω) dω = ∫ D(h)·4(ω·h)·(R·ω) dh: with h's polar angle θ drawn from GGX's own
        // distribution of D(h)·cos θ, tan²θ = α²·t/(1 − t) for t uniform, ω·h = cos θ cancels the
        // cos θ and R·ω = cos 2θ, counted while 2θ < π/2.
        const int steps = 4096;
        double norm = 0.0;
        for (int i = 0; i < steps; ++i) {
            const double t = (i + 0.5) / steps;
            const double theta = std::atan(alpha * std::sqrt(t / (1.0 - t)));
            norm += 4.0 * std::max(0.0, std::cos(2.0 * theta));
        }
        return sum / (norm / steps);
    };
    MaterialPixel pixel;
    const GgxAlbedoTable::Albedo e = GgxAlbedoTable::shared().at(layers.roughness, mu);
    const double coatWeight = coatFresnelWeight(brdf, mu);
    const glm::dvec3 specularAlbedo = brdf.f0 * e.a + glm::dvec3(brdf.f90 * e.b);
    pixel.specular = (1.0 - coatWeight) * specularAlbedo * prefiltered(brdf.alpha);
    // E(N)/π: the cosine lobe about N.
    glm::dvec3 irradiance(0.0);
    environment.walk(RadianceTree::Focus{n, kWidestFocus, n}, [&](const glm::dvec3& l, const glm::dvec3& energy) {
        irradiance += std::max(0.0, glm::dot(n, l)) * energy;
    }, accuracy);
    pixel.diffuse = (1.0 - coatWeight) * (irradiance / std::numbers::pi) * brdf.diffuse * (glm::dvec3(1.0) - specularAlbedo);
    if (brdf.clearcoat > 0.0) {
        const GgxAlbedoTable::Albedo c = GgxAlbedoTable::shared().at(layers.coatRoughness, mu);
        pixel.coat = coatWeight * (c.a + c.b) * prefiltered(brdf.coatAlpha);
    }
    return pixel;
}

void PixelGeometry::at(double ox, double oy, glm::dvec3& normal, glm::dvec3& view) const {
    normal = glm::normalize(n + ox * dndx + oy * dndy);
    view = glm::normalize(v + ox * dvdx + oy * dvdy);
    const double cosView = glm::dot(normal, view);
    if (cosView < 1e-4) view = glm::normalize(view + (1e-4 - cosView) * normal);
}

int areaSubdivisions(const PixelGeometry& g, double alpha, int most) {
    const double turn = std::max(glm::length(2.0 * g.dndx - g.dvdx), glm::length(2.0 * g.dndy - g.dvdy));
    return std::clamp(static_cast<int>(std::ceil(2.0 * turn / std::max(alpha, 1e-3))), 1, std::max(most, 1));
}

MaterialPixel materialTruthOverPixel(const RadianceTree& environment, const Layers& layers, const PixelGeometry& g,
                                     int subdivisions, Scattering scattering, const RadianceTree::Accuracy& accuracy) {
    const int s = std::max(subdivisions, 1);
    MaterialPixel mean;
    for (int sy = 0; sy < s; ++sy)
        for (int sx = 0; sx < s; ++sx) {
            glm::dvec3 n, v;
            g.at((sx + 0.5) / s - 0.5, (sy + 0.5) / s - 0.5, n, v);
            const MaterialPixel p = materialTruth(environment, layers, n, v, scattering, accuracy);
            mean.diffuse += p.diffuse;
            mean.specular += p.specular;
            mean.coat += p.coat;
        }
    const double count = static_cast<double>(s * s);
    mean.diffuse /= count;
    mean.specular /= count;
    mean.coat /= count;
    return mean;
}

}  // namespace mipgloss
