#include "mipgloss/ibl/ggx_sampling.h"

#include "mipgloss/ibl/gltf_brdf.h"
#include "mipgloss/ibl/parallel.h"
#include "mipgloss/ibl/specular.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

namespace mipgloss {

glm::dvec2 ggxSequence(int k, int count) {
    std::uint32_t bits = static_cast<std::uint32_t>(k);
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return {(k + 0.5) / count, static_cast<double>(bits) * 2.3283064365386963e-10};
}

GgxLookup ggxLookup(double alpha, const glm::dvec3& view, const glm::dvec2& u) {
    GgxLookup out;
    const glm::dvec3 v = view.z > kLeastCosView ? view : glm::normalize(glm::dvec3(view.x, view.y, kLeastCosView));
    // Heitz 2018, listing 1 (isotropic α): the view stretched to the unit-roughness configuration,
    // a point on the projected disc, back to the ellipsoid's normal.
    const glm::dvec3 vh = glm::normalize(glm::dvec3(alpha * v.x, alpha * v.y, v.z));
    const double lensq = vh.x * vh.x + vh.y * vh.y;
    const glm::dvec3 t1 = lensq > 0.0 ? glm::dvec3(-vh.y, vh.x, 0.0) / std::sqrt(lensq) : glm::dvec3(1.0, 0.0, 0.0);
    const glm::dvec3 t2 = glm::cross(vh, t1);
    const double r = std::sqrt(u.x), phi = 2.0 * std::numbers::pi * u.y;
    const double p1 = r * std::cos(phi);
    const double s = 0.5 * (1.0 + vh.z);
    const double p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * r * std::sin(phi);
    const glm::dvec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    const glm::dvec3 h = glm::normalize(glm::dvec3(alpha * nh.x, alpha * nh.y, std::max(0.0, nh.z)));
    const double vDotH = std::clamp(glm::dot(v, h), 0.0, 1.0);
    out.light = 2.0 * vDotH * h - v;
    const double m = 1.0 - vDotH;
    out.fresnelEdge = m * m * m * m * m;
    const double g1 = smithMasking(alpha, v.z);
    if (out.light.z > 0.0 && g1 > 0.0) {
        // G2/G1 = 4 V·(N·l)(N·v)/G1 with Appendix B's V.
        out.weight = 4.0 * smithVisibility(alpha, out.light.z, v.z) * out.light.z * v.z / g1;
    }
    out.pdf = alpha > 0.0 ? g1 * ggxDistribution(alpha, h.z) / (4.0 * v.z) : std::numeric_limits<double>::infinity();
    return out;
}

double lookupExponent(double pdf, int count, double spread) {
    if (std::isinf(pdf)) return std::numeric_limits<double>::infinity();
    return std::max(0.0, 2.0 * std::numbers::pi * count * pdf / spread - 1.0);
}

glm::dvec3 keptAboveHorizon(const glm::dvec3& light, double exponent) {
    if (std::isinf(exponent)) return light;
    const double lowest = std::sqrt(std::max(0.0, 1.0 - std::exp2(-2.0 / std::max(exponent, 1e-6))));
    if (light.z >= lowest) return light;
    const double across = std::hypot(light.x, light.y);
    if (across <= 0.0) return glm::dvec3(0.0, 0.0, 1.0);
    const double scale = std::sqrt(1.0 - lowest * lowest) / across;
    return glm::dvec3(light.x * scale, light.y * scale, lowest);
}

ExponentRange lookupExponentRange(double alpha, int count, double spread) {
    ExponentRange range{0.0, std::numeric_limits<double>::infinity()};
    for (int column = 0; column < GgxAlbedoTable::kCosSteps; ++column) {
        const double mu = std::max(SplitSumTable::cosViewOfColumn(column), kLeastCosView);
        const glm::dvec3 v(std::sqrt(1.0 - mu * mu), 0.0, mu);
        for (int k = 0; k < count; ++k) {
            const GgxLookup s = ggxLookup(alpha, v, ggxSequence(k, count));
            if (s.weight <= 0.0) continue;
            const double n = lookupExponent(s.pdf, count, spread);
            range.sharpest = std::max(range.sharpest, n);
            range.widest = std::min(range.widest, n);
        }
    }
    if (std::isinf(range.widest)) range.widest = range.sharpest;
    return range;
}

const char* scatteringName(Scattering scattering) {
    return scattering == Scattering::Compensated ? "compensated" : "single";
}

bool parseScattering(const std::string& text, Scattering& out) {
    for (Scattering s : kAllScatterings)
        if (text == scatteringName(s)) {
            out = s;
            return true;
        }
    return false;
}

glm::dvec3 scatteringCompensation(const glm::dvec3& f0, const GgxAlbedoTable::Albedo& e, Scattering scattering) {
    const double albedo = e.a + e.b;
    if (scattering == Scattering::Single || !(albedo > 0.0)) return glm::dvec3(1.0);
    return glm::dvec3(1.0) + f0 * ((1.0 - albedo) / albedo);
}

GgxAlbedoTable::Albedo ggxAlbedoIntegral(double roughness, double cosView, int samples) {
    const double alpha = roughness * roughness;
    const double mu = std::max(cosView, kLeastCosView);
    const glm::dvec3 v(std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu);
    GgxAlbedoTable::Albedo sum;
    glm::dvec3 mean(0.0);
    double weights = 0.0;
    for (int i = 0; i < samples; ++i)
        for (int j = 0; j < samples; ++j) {
            // Specular: the VNDF estimator f·cos/pdf = F·G2/G1, split by F0.
            const glm::dvec2 u((i + 0.5) / samples, (j + 0.5) / samples);
            const GgxLookup s = ggxLookup(alpha, v, u);
            sum.a += s.weight * (1.0 - s.fresnelEdge);
            sum.b += s.weight * s.fresnelEdge;
            mean += s.weight * s.light;
            weights += s.weight;
            // Diffuse: cosine-weighted directions, (1 − v·h)⁵ averaged (the cosine/π is the pdf).
            const double r = std::sqrt(u.x), phi = 2.0 * std::numbers::pi * u.y;
            const glm::dvec3 l(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u.x)));
            const glm::dvec3 h = glm::normalize(l + v);
            const double m = 1.0 - std::clamp(glm::dot(v, h), 0.0, 1.0);
            sum.diffuseEdge += m * m * m * m * m;
        }
    const double n = static_cast<double>(samples) * samples;
    sum.a /= n;
    sum.b /= n;
    sum.diffuseEdge /= n;
    if (weights > 0.0) {
        sum.meanX = mean.x / weights;
        sum.meanZ = mean.z / weights;
    }
    return sum;
}

GgxAlbedoTable::GgxAlbedoTable(int samples)
    : nodes_(3u * kRoughnessSteps * kCosSteps), meanNodes_(2u * kRoughnessSteps * kCosSteps) {
    parallelFor(0, kRoughnessSteps, [&](int row) {
        const double roughness = static_cast<double>(row) / (kRoughnessSteps - 1);
        for (int col = 0; col < kCosSteps; ++col) {
            const Albedo e = ggxAlbedoIntegral(roughness, SplitSumTable::cosViewOfColumn(col), samples);
            const std::size_t at = 3u * (static_cast<std::size_t>(row) * kCosSteps + col);
            nodes_[at] = static_cast<float>(e.a);
            nodes_[at + 1] = static_cast<float>(e.b);
            nodes_[at + 2] = static_cast<float>(e.diffuseEdge);
            const std::size_t meanAt = 2u * (static_cast<std::size_t>(row) * kCosSteps + col);
            meanNodes_[meanAt] = static_cast<float>(e.meanX);
            meanNodes_[meanAt + 1] = static_cast<float>(e.meanZ);
        }
    });
}

const GgxAlbedoTable& GgxAlbedoTable::shared() {
    static const GgxAlbedoTable table(64);
    return table;
}

GgxAlbedoTable::Albedo GgxAlbedoTable::at(double roughness, double cosView) const {
    const double x = SplitSumTable::columnOfCosView(std::isnan(cosView) ? 0.0 : cosView) * (kCosSteps - 1);
    const double y = std::clamp(std::isnan(roughness) ? 0.0 : roughness, 0.0, 1.0) * (kRoughnessSteps - 1);
    const int x0 = std::min(static_cast<int>(x), kCosSteps - 2);
    const int y0 = std::min(static_cast<int>(y), kRoughnessSteps - 2);
    const double fx = x - x0, fy = y - y0;
    auto bilinear = [&](const std::vector<float>& nodes, std::size_t stride, std::size_t c) {
        auto node = [&](int row, int col) {
            return static_cast<double>(nodes[stride * (static_cast<std::size_t>(row) * kCosSteps + col) + c]);
        };
        const double top = node(y0, x0) * (1 - fx) + node(y0, x0 + 1) * fx;
        const double bottom = node(y0 + 1, x0) * (1 - fx) + node(y0 + 1, x0 + 1) * fx;
        return top * (1 - fy) + bottom * fy;
    };
    Albedo out;
    out.a = bilinear(nodes_, 3, 0);
    out.b = bilinear(nodes_, 3, 1);
    out.diffuseEdge = bilinear(nodes_, 3, 2);
    out.meanX = bilinear(meanNodes_, 2, 0);
    out.meanZ = bilinear(meanNodes_, 2, 1);
    return out;
}

MeanLobe meanLobe(const GgxAlbedoTable::Albedo& albedo) {
    const glm::dvec3 mean(albedo.meanX, 0.0, albedo.meanZ);
    const double length = glm::length(mean);
    MeanLobe lobe;
    if (!(length > 0.0)) return lobe;
    lobe.direction = mean / length;
    lobe.exponent = length < 1.0 ? std::max(1.0 / (1.0 - length) - 2.0, 0.0) : std::numeric_limits<double>::infinity();
    return lobe;
}

double meanLobeShare(double roughness) {
    if (!(roughness > kMeanLobeFrom)) return 0.0;
    return std::min((roughness - kMeanLobeFrom) / (kMeanLobeAll - kMeanLobeFrom), 1.0);
}

ExponentRange meanLobeExponentRange(double roughness) {
    ExponentRange range{0.0, std::numeric_limits<double>::infinity()};
    const GgxAlbedoTable& table = GgxAlbedoTable::shared();
    for (int column = 0; column < GgxAlbedoTable::kCosSteps; ++column) {
        const double n = meanLobe(table.at(roughness, SplitSumTable::cosViewOfColumn(column))).exponent;
        range.sharpest = std::max(range.sharpest, n);
        range.widest = std::min(range.widest, n);
    }
    return range;
}

}  // namespace mipgloss
