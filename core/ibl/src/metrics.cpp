#include "mipgloss/ibl/metrics.h"

#include "mipgloss/ibl/builders.h"

#include <random>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace mipgloss {

LevelError compareCubes(const CubeMap& test, const CubeMap& reference) {
    assert(test.size() == reference.size());
    const int m = reference.size();
    double errB = 0, refB = 0, errI = 0, refI = 0, meanT = 0, meanR = 0;
    for (int y = 0; y < m; ++y)
        for (int x = 0; x < m; ++x) {
            const double w = texelSolidAngle(x, y, m);
            const bool border = x == 0 || y == 0 || x == m - 1 || y == m - 1;
            for (Face f : kAllFaces) {
                const glm::dvec3 a(test.at(f, x, y)), b(reference.at(f, x, y));
                const glm::dvec3 d = a - b;
                (border ? errB : errI) += w * glm::dot(d, d);
                (border ? refB : refI) += w * glm::dot(b, b);
                meanT += w * luminance(test.at(f, x, y));
                meanR += w * luminance(reference.at(f, x, y));
            }
        }
    LevelError e;
    auto ratio = [](double err, double ref) { return ref > 0.0 ? std::sqrt(err / ref) : std::sqrt(err); };
    e.relRms = ratio(errB + errI, refB + refI);
    e.relRmsBorder = ratio(errB, refB);
    e.hasInterior = m > 2;
    e.relRmsInterior = e.hasInterior ? ratio(errI, refI) : 0.0;
    e.meanRelDiff = meanR != 0.0 ? (meanT - meanR) / meanR : meanT;
    return e;
}

SeamStats seamStats(const CubeMap& level) {
    const int m = level.size();
    SeamStats s;
    if (m < 2) return s;
    double edge = 0, inside = 0;
    long count = 0;
    auto gradient = [&](Face fa, int xa, int ya, Face fb, int xb, int yb) {
        const double angle = std::acos(std::clamp(
            static_cast<double>(glm::dot(texelDirection(fa, xa, ya, m), texelDirection(fb, xb, yb, m))), -1.0, 1.0));
        return std::fabs(luminance(level.at(fa, xa, ya)) - luminance(level.at(fb, xb, yb))) / angle;
    };
    forEachEdgePair(m, [&](Face f, int ex, int ey, const TexelRef& across, int ix, int iy) {
        edge += gradient(f, ex, ey, across.face, across.x, across.y);
        inside += gradient(f, ex, ey, f, ix, iy);
        ++count;
    });
    s.edgeGradient = edge / static_cast<double>(count);
    s.insideGradient = inside / static_cast<double>(count);
    s.ratio = s.insideGradient > 0.0 ? s.edgeGradient / s.insideGradient : 0.0;
    return s;
}

double goldenSectionMinimum(const std::function<double(double)>& cost, double a, double b, double tolerance,
                            int maxSteps) {
    const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
    double c = b - phi * (b - a), d = a + phi * (b - a);
    double fc = cost(c), fd = cost(d);
    for (int step = 0; step < maxSteps && b - a > tolerance; ++step) {
        if (fc < fd) {
            b = d; d = c; fd = fc; c = b - phi * (b - a); fc = cost(c);
        } else {
            a = c; c = d; fc = fd; d = a + phi * (b - a); fd = cost(d);
        }
    }
    return 0.5 * (a + b);
}

double fitExponent(const CubeMap& level, const CubeMap& base, double guess) {
    auto cost = [&](double logN) {
        return compareCubes(level, referenceConvolution(base, std::exp(logN), level.size(), 1e-8)).relRms;
    };
    // 18 steps: the bracket [guess/16, guess·16] in log n shrunk to 5.5·φ^18 ≈ 1e-3.
    return std::exp(goldenSectionMinimum(cost, std::log(std::max(guess, 1e-3) / 16.0),
                                         std::log(std::max(guess, 1e-3) * 16.0), 0.0, 18));
}

std::vector<glm::vec3> uniformDirections(int count, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> gauss;
    std::vector<glm::vec3> out;
    out.reserve(static_cast<std::size_t>(std::max(count, 0)));
    while (static_cast<int>(out.size()) < count) {
        const glm::vec3 v(gauss(rng), gauss(rng), gauss(rng));
        const float len = glm::length(v);
        if (len > 1e-6f) out.push_back(v / len);  // an isotropic Gaussian, normalized, is uniform
    }
    return out;
}

Rgb sampleChain(const MipChain& chain, const glm::vec3& direction, double lod) {
    const int last = chain.levelCount() - 1;
    lod = std::clamp(std::isfinite(lod) ? lod : 0.0, 0.0, static_cast<double>(std::max(last, 0)));
    const int l0 = static_cast<int>(std::floor(lod));
    const float f = static_cast<float>(lod - l0);
    const Rgb a = chain.levels[static_cast<std::size_t>(l0)].sample(direction);
    if (f <= 0.0f || l0 >= last) return a;
    const Rgb b = chain.levels[static_cast<std::size_t>(l0 + 1)].sample(direction);
    return a + f * (b - a);
}

std::vector<Rgb> readChain(const MipChain& chain, double lod, const std::vector<glm::vec3>& directions) {
    std::vector<Rgb> out(directions.size());
    for (std::size_t i = 0; i < directions.size(); ++i) out[i] = sampleChain(chain, directions[i], lod);
    return out;
}

double relativeRms(const std::vector<Rgb>& test, const std::vector<Rgb>& truth) {
    double se = 0.0, sr = 0.0;
    for (std::size_t i = 0; i < std::min(test.size(), truth.size()); ++i) {
        const glm::dvec3 d = glm::dvec3(test[i]) - glm::dvec3(truth[i]);
        se += glm::dot(d, d);
        sr += glm::dot(glm::dvec3(truth[i]), glm::dvec3(truth[i]));
    }
    return sr > 0.0 ? std::sqrt(se / sr) : std::sqrt(se);
}

double readError(const MipChain& chain, double lod, const CubeMap& base, double exponent,
                 const std::vector<glm::vec3>& directions) {
    return relativeRms(readChain(chain, lod, directions), referenceLobeAt(base, exponent, directions));
}

}  // namespace mipgloss
