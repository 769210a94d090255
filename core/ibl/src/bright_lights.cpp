#include "mipgloss/ibl/bright_lights.h"

#include "mipgloss/ibl/colour.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>

namespace mipgloss {

double brightThreshold(const CubeMap& base, double factor) {
    const int n = base.size();
    double sum = 0.0, omega = 0.0;
    for (Face f : kAllFaces)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const double w = texelSolidAngle(x, y, n);
                sum += w * luminance(base.at(f, x, y));
                omega += w;
            }
    return omega > 0.0 ? factor * sum / omega : 0.0;
}

double widestLight(const std::vector<PointLight>& lights) {
    double widest = 0.0;
    for (const PointLight& light : lights) widest = std::max(widest, static_cast<double>(light.radius));
    return widest;
}

CubeMap withoutBrightLights(const CubeMap& base, double factor) {
    CubeMap out = base;
    const double threshold = brightThreshold(base, factor);
    const int n = base.size();
    if (threshold > 0.0)
        for (Face f : kAllFaces)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const double l = luminance(base.at(f, x, y));
                    if (l > threshold) out.at(f, x, y) *= static_cast<float>(threshold / l);
                }
    out.makeSeamless();
    return out;
}

std::vector<PointLight> brightLights(const CubeMap& base, double factor, int maxLights) {
    struct Cluster {
        glm::dvec3 energy{0.0};
        glm::dvec3 moment{0.0};  // Σ lum·direction of its texels' excess
        double weight = 0.0;      // Σ lum
        double omega = 0.0;
        int texels = 0;
    };
    const int n = base.size();
    const double threshold = brightThreshold(base, factor);
    std::map<std::tuple<int, int, int>, Cluster> clusters;  // (face, x, y) at the current level
    if (threshold > 0.0)
        for (Face f : kAllFaces)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const Rgb c = base.at(f, x, y);
                    const double l = luminance(c);
                    if (!(l > threshold)) continue;
                    const glm::dvec3 excess = glm::dvec3(c) * (1.0 - threshold / l) * texelSolidAngle(x, y, n);
                    Cluster& k = clusters[{static_cast<int>(f), x, y}];
                    k.energy += excess;
                    k.omega += texelSolidAngle(x, y, n);
                    ++k.texels;
                    const double lum = 0.2126 * excess.x + 0.7152 * excess.y + 0.0722 * excess.z;
                    k.moment += lum * glm::dvec3(texelDirection(f, x, y, n));
                    k.weight += lum;
                }
    while (static_cast<int>(clusters.size()) > std::max(maxLights, 1)) {
        std::map<std::tuple<int, int, int>, Cluster> coarser;
        for (const auto& [key, k] : clusters) {
            Cluster& c = coarser[{std::get<0>(key), std::get<1>(key) / 2, std::get<2>(key) / 2}];
            c.energy += k.energy;
            c.moment += k.moment;
            c.weight += k.weight;
            c.omega += k.omega;
            c.texels += k.texels;
        }
        if (coarser.size() == clusters.size()) break;  // one texel per face: nothing left to merge
        clusters = std::move(coarser);
    }
    std::vector<PointLight> lights;
    for (const auto& [key, k] : clusters) {
        const double m = glm::length(k.moment);
        if (!(m > 0.0)) continue;
        // Its width: the spread of its texels about their mean, E[θ²] = 2(1 − |Σ w·d| / Σ w), plus
        // a texel's own (a disc of its solid angle Ω has E[θ²] = Ω/(2π)); a uniform disc of radius
        // ρ has E[θ²] = ρ²/2, so ρ = √(2 E[θ²]).
        const double texel = k.omega / std::max(k.texels, 1);
        const double spread = 2.0 * std::max(0.0, 1.0 - m / k.weight) + texel / (2.0 * 3.14159265358979);
        lights.push_back({glm::vec3(k.moment / m), Rgb(k.energy), static_cast<float>(std::sqrt(2.0 * spread))});
    }
    std::sort(lights.begin(), lights.end(),
              [](const PointLight& a, const PointLight& b) { return luminance(a.energy) > luminance(b.energy); });
    if (static_cast<int>(lights.size()) > maxLights) lights.resize(static_cast<std::size_t>(maxLights));
    return lights;
}

double discAveragedGgx(double alpha, double cosHalf, double radius) {
    const double c = std::max(cosHalf, 1e-3), c2 = c * c;
    const double slope2 = std::max(1.0 - c2, 0.0) / c2;
    const double halfAngle = 0.5 * radius;
    const double r = std::max(std::min(halfAngle, 0.5 * c) / (c * std::sqrt(c)), 1e-6);
    const double a2 = alpha * alpha;
    const double a = a2 + slope2 - r * r;
    const double b = 4.0 * a2 * r * r;
    const double q = std::sqrt(a * a + b);
    // 1 − a/q without its cancellation when a > 0.
    const double inside = 0.5 * (a > 0.0 ? b / (q * (q + a)) : 1.0 - a / q);
    return inside / (std::numbers::pi * r * r * c2 * c2);
}

double horizonCosine(double cosLight, double radius) {
    if (cosLight >= radius) return cosLight;
    if (cosLight <= -radius) return 0.0;
    const double u = cosLight / radius, w = std::sqrt(std::max(0.0, 1.0 - u * u));
    constexpr double pi = std::numbers::pi;
    return radius * (u * (0.5 + (u * w + std::asin(u)) / pi) + (2.0 / (3.0 * pi)) * w * w * w);
}

double lightAveragedGgx(double alpha, const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& l, double radius) {
    const glm::dvec3 sum = l + v;
    const double length = glm::length(sum);
    if (length < 1e-6) return 0.0;
    const glm::dvec3 h = sum / length;
    const double cosHalf = glm::dot(n, h), viewDotHalf = std::max(glm::dot(v, h), 1e-3);
    // The ellipse as the disc of its area where its shape is lost in the lobe or far from it.
    const double disc = discAveragedGgx(alpha, cosHalf, radius / std::sqrt(viewDotHalf));
    if (viewDotHalf >= 0.77 || cosHalf <= 1e-3 || radius <= 0.0) return disc;
    // The ellipse's axes about h: in the plane of l and v (l − v ⟂ h), and across it.
    const glm::dvec3 across0 = glm::cross(h, l - v);
    if (glm::length(across0) < 1e-9) return disc;
    const glm::dvec3 inPlane = glm::normalize(l - v), across = glm::normalize(across0);
    // Radii scaled so the octagon has the ellipse's area (π vs 2√2).
    const double scale = std::sqrt(std::numbers::pi / (2.0 * std::sqrt(2.0)));
    const double a = scale * 0.5 * radius, b = scale * 0.5 * radius / viewDotHalf;
    // Slope space about n.
    const glm::dvec3 t = glm::normalize(std::abs(n.x) < 0.9 ? glm::cross(n, glm::dvec3(1, 0, 0)) : glm::cross(n, glm::dvec3(0, 1, 0)));
    const glm::dvec3 bt = glm::cross(n, t);
    const auto slopeOf = [&](const glm::dvec3& d) {
        const double z = std::max(glm::dot(d, n), 1e-3);
        return glm::dvec2(glm::dot(d, t), glm::dot(d, bt)) / z;
    };
    const glm::dvec2 centre = slopeOf(h);
    // The ellipse's long radius in slope space: below half the lobe's α the light's shape is
    // lost in the lobe, round or not; beyond it and 2α from the peak, the tail.
    const double longRadius = b / (cosHalf * cosHalf);
    if (longRadius < 0.5 * alpha || glm::length(centre) > longRadius + 2.0 * alpha) return disc;
    glm::dvec3 w[8];
    for (int k = 0; k < 8; ++k) {
        const double phi = 2.0 * std::numbers::pi * k / 8.0;
        const glm::dvec2 s = slopeOf(glm::normalize(h + a * std::cos(phi) * inPlane + b * std::sin(phi) * across));
        w[k] = glm::normalize(glm::dvec3(s, -alpha));
    }
    double flux = 0.0;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 p = w[k], q = w[(k + 1) % 8];
        const glm::dvec3 c = glm::cross(p, q);
        const double sine = glm::length(c);
        if (sine <= 0.0) continue;
        flux += std::atan2(sine, glm::dot(p, q)) * (c.z / sine);
    }
    const double formFactor = std::abs(flux) / (2.0 * std::numbers::pi);
    const double solidAngle = 2.0 * std::sqrt(2.0) * a * b;
    return formFactor / (cosHalf * solidAngle);
}

}  // namespace mipgloss
