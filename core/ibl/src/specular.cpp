#include "mipgloss/ibl/specular.h"

#include "mipgloss/ibl/parallel.h"
#include "mipgloss/ibl/phong.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mipgloss {

namespace {
constexpr double kHalfPi = std::numbers::pi / 2;
}  // namespace

double roughnessToExponent(double roughness) {
    if (std::isnan(roughness)) return roughness;
    const double r = std::clamp(roughness, 0.0, 1.0);
    if (r == 0.0) return kMirrorExponent;
    return kRoughnessFit * (1.0 / (r * r * r * r) - 1.0);
}

double exponentToRoughness(double exponent) {
    if (std::isnan(exponent)) return exponent;
    if (std::isinf(exponent) && exponent > 0.0) return 0.0;
    if (exponent <= 0.0) return 1.0;
    return std::pow(kRoughnessFit / (exponent + kRoughnessFit), 0.25);
}

double schlickFresnel(double f0, double cosine) {
    const double m = 1.0 - std::clamp(cosine, 0.0, 1.0);
    const double m2 = m * m;
    return f0 + (1.0 - f0) * m2 * m2 * m;
}

SplitSum splitSumIntegral(double exponent, double cosView, int samples) {
    const double mu = std::clamp(cosView, 0.0, 1.0);
    // N = +z; v in the xz plane; r = reflect(−v, N).
    const glm::dvec3 v(std::sqrt(1.0 - mu * mu), 0.0, mu);
    const glm::dvec3 r(-v.x, 0.0, mu);
    // An orthonormal frame about r (r has no y component, so y is one axis).
    const glm::dvec3 t1(0.0, 1.0, 0.0);
    const glm::dvec3 t2 = glm::cross(r, t1);
    const bool mirror = std::isinf(exponent);
    const int k = std::max(samples, 1);
    SplitSum sum;
    // The lobe's measure: u = cos(angle to r) has density (n+1)u^n on [0, 1], so with
    // t = u^(n+1) uniform and φ uniform every sample carries weight 1/(k·k).
    for (int i = 0; i < (mirror ? 1 : k); ++i) {
        const double t = (i + 0.5) / k;
        const double u = mirror ? 1.0 : std::exp(std::log(t) / (exponent + 1.0));
        const double s = std::sqrt(std::max(0.0, 1.0 - u * u));
        for (int j = 0; j < (mirror ? 1 : k); ++j) {
            const double phi = 2.0 * std::numbers::pi * (j + 0.5) / k;
            const glm::dvec3 w = u * r + s * (std::cos(phi) * t1 + std::sin(phi) * t2);
            if (w.z < 0.0) continue;  // from below the surface (the mirror at μ = 0 just grazes it)
            // ω = −v only for the mirror at μ = 0, where h is the normal.
            const glm::dvec3 sumWV = w + v;
            const glm::dvec3 h = glm::dot(sumWV, sumWV) > 1e-24 ? glm::normalize(sumWV) : glm::dvec3(0, 0, 1);
            const double m = 1.0 - std::clamp(glm::dot(w, h), 0.0, 1.0);
            const double m5 = m * m * m * m * m;
            sum.a += 1.0 - m5;
            sum.b += m5;
        }
    }
    const double weight = mirror ? 1.0 : 1.0 / (static_cast<double>(k) * k);
    sum.a *= weight;
    sum.b *= weight;
    return sum;
}

SplitSumTable::SplitSumTable(int samples) : nodes_(2u * kLambdaSteps * kCosSteps) {
    parallelFor(0, kLambdaSteps, [&](int row) {
        const double lambda = kMaxLambda * row / (kLambdaSteps - 1);
        const double n = lambdaToExponent(lambda);
        for (int col = 0; col < kCosSteps; ++col) {
            const SplitSum s = splitSumIntegral(n, SplitSumTable::cosViewOfColumn(col), samples);
            const std::size_t at = 2u * (static_cast<std::size_t>(row) * kCosSteps + col);
            nodes_[at] = static_cast<float>(s.a);
            nodes_[at + 1] = static_cast<float>(s.b);
        }
    });
}

const SplitSumTable& SplitSumTable::shared() {
    static const SplitSumTable table(64);
    return table;
}

double SplitSumTable::columnOfCosView(double cosView) {
    const double theta = std::acos(std::clamp(cosView, 0.0, 1.0));
    return 1.0 - std::sqrt(std::max(0.0, 1.0 - theta / kHalfPi));
}

double SplitSumTable::cosViewOfColumn(int column) {
    const double x = static_cast<double>(column) / (kCosSteps - 1);
    return std::cos(kHalfPi * (1.0 - (1.0 - x) * (1.0 - x)));
}

SplitSum SplitSumTable::at(double lambda, double cosView) const {
    const double x = columnOfCosView(std::isnan(cosView) ? 0.0 : cosView) * (kCosSteps - 1);
    const double y = std::clamp(std::isnan(lambda) ? 0.0 : lambda, 0.0, kMaxLambda) / kMaxLambda * (kLambdaSteps - 1);
    const int x0 = std::min(static_cast<int>(x), kCosSteps - 2);
    const int y0 = std::min(static_cast<int>(y), kLambdaSteps - 2);
    const double fx = x - x0, fy = y - y0;
    auto node = [&](int row, int col, int c) {
        return static_cast<double>(nodes_[2u * (static_cast<std::size_t>(row) * kCosSteps + col) + c]);
    };
    SplitSum out;
    for (int c = 0; c < 2; ++c) {
        const double top = node(y0, x0, c) * (1 - fx) + node(y0, x0 + 1, c) * fx;
        const double bottom = node(y0 + 1, x0, c) * (1 - fx) + node(y0 + 1, x0 + 1, c) * fx;
        (c == 0 ? out.a : out.b) = top * (1 - fy) + bottom * fy;
    }
    return out;
}

}  // namespace mipgloss
