// The renderer's GGX model on the CPU with exact lobes (referenceLobeAt in place of the stack):
// how far K lookups are from the truth of a metal, independent of the GPU.
#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/ggx_sampling.h"
#include "mipgloss/io/import.h"
#include "mipgloss/scene/material_truth.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "test_support.h"

namespace mipgloss {
namespace {

struct Frame {
    glm::dvec3 t, b, n;
    glm::dvec3 local;
};
Frame frameOf(const glm::dvec3& n, const glm::dvec3& v) {
    const double mu = std::clamp(glm::dot(n, v), 1e-4, 1.0);
    glm::dvec3 t = v - mu * n;
    const double tl = glm::length(t);
    t = tl > 1e-9 ? t / tl : glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    return {t, glm::cross(n, t), n, glm::dvec3(std::sqrt(1 - mu * mu), 0, mu)};
}

// The white metal's specular as the renderer models it, each lookup an exact lobe.
double modelled(const CubeMap& base, double roughness, const glm::dvec3& n, const glm::dvec3& v, int count, double spread) {
    const double alpha = roughness * roughness;
    const Frame f = frameOf(n, v);
    double sum = 0.0, weights = 0.0;
    for (int k = 0; k < count; ++k) {
        const GgxLookup g = ggxLookup(alpha, f.local, ggxSequence(k, count));
        if (g.weight <= 0.0) continue;
        const glm::dvec3 l = g.light.x * f.t + g.light.y * f.b + g.light.z * f.n;
        const double e = lookupExponent(g.pdf, count, spread);
        const Rgb value = referenceLobeAt(base, std::min(e, 1e6), {glm::vec3(l)}, 1e-6)[0];
        sum += g.weight * value.g;
        weights += g.weight;
    }
    const GgxAlbedoTable::Albedo a = GgxAlbedoTable::shared().at(roughness, glm::dot(n, v));
    return weights > 0.0 ? (a.a + a.b) * sum / weights : 0.0;
}

// Bins of the visible-normal disk: a core u1 < core, then `sectors` sectors of the ring; each bin
// read as the Phong lobe at its mean light direction with its mean cosine (n = (2Λ − 1)/(1 − Λ)).
double binned(const CubeMap& base, double roughness, const glm::dvec3& n, const glm::dvec3& v, double core, int sectors,
              double sharpen) {
    const double alpha = roughness * roughness;
    const Frame f = frameOf(n, v);
    const int bins = 1 + sectors;
    std::vector<glm::dvec3> moment(bins, glm::dvec3(0.0));
    std::vector<double> weight(bins, 0.0);
    const int dense = 48;
    for (int i = 0; i < dense; ++i)
        for (int j = 0; j < dense; ++j) {
            const glm::dvec2 u((i + 0.5) / dense, (j + 0.5) / dense);
            const GgxLookup g = ggxLookup(alpha, f.local, u);
            if (g.weight <= 0.0) continue;
            const int bin = u.x < core ? 0 : 1 + std::min(sectors - 1, static_cast<int>(u.y * sectors));
            moment[bin] += g.weight * g.light;
            weight[bin] += g.weight;
        }
    double sum = 0.0, total = 0.0;
    for (int b = 0; b < bins; ++b) {
        if (weight[b] <= 0.0) continue;
        const glm::dvec3 mean = moment[b] / weight[b];
        const double lambda = std::min(glm::length(mean), 1.0 - 1e-9);
        const double e = std::max(0.0, sharpen * (2.0 * lambda - 1.0) / (1.0 - lambda));
        const glm::dvec3 d = glm::normalize(mean);
        const glm::dvec3 l = d.x * f.t + d.y * f.b + d.z * f.n;
        sum += weight[b] * referenceLobeAt(base, std::min(e, 1e6), {glm::vec3(l)}, 1e-6)[0].g;
        total += weight[b];
    }
    const GgxAlbedoTable::Albedo a = GgxAlbedoTable::shared().at(roughness, glm::dot(n, v));
    return total > 0.0 ? (a.a + a.b) * sum / total : 0.0;
}

// The environment split at luminance `threshold`: the clamped field, and the excess of each bright
// texel as a point of energy at its centre.
struct Split {
    CubeMap smooth;
    std::vector<std::pair<glm::dvec3, glm::dvec3>> lights;  // direction, energy
};
Split splitAt(const CubeMap& base, double threshold) {
    Split s{base, {}};
    const int n = base.size();
    for (Face f : kAllFaces)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const Rgb c = base.at(f, x, y);
                const double l = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
                if (l <= threshold) continue;
                const Rgb kept = c * static_cast<float>(threshold / l);
                s.smooth.at(f, x, y) = kept;
                s.lights.push_back({glm::dvec3(texelDirection(f, x, y, n)), glm::dvec3(c - kept) * texelSolidAngle(x, y, n)});
            }
    s.smooth.makeSeamless();
    return s;
}

double lightsTerm(const Split& split, double roughness, const glm::dvec3& n, const glm::dvec3& v) {
    GltfBrdf brdf;
    brdf.f0 = glm::dvec3(1.0);
    brdf.diffuse = glm::dvec3(0.0);
    brdf.alpha = roughness * roughness;
    double sum = 0.0;
    for (const auto& [l, e] : split.lights) sum += gltfBrdfCosine(brdf, n, v, l).specular.y * e.y;
    return sum;
}

TEST(GgxLookups, ExperimentSpreadAndCount) {
    if (!std::getenv("MIPGLOSS_EXPERIMENT")) GTEST_SKIP();
    for (const std::string map : {"city", "sunrise"}) {
        const auto path = test::asset("env/" + map + ".exr");
        ImportOptions o;
        o.faceSize = 64;
        const CubeMap base = loadEnvironment(path, o).cube;
        const RadianceTree tree(base);
        Layers metal;
        metal.baseColor = Rgb(1.0f);
        metal.metallic = 1.0f;
        for (float r : {0.3f, 0.6f}) {
            metal.roughness = r;
            std::vector<glm::dvec3> ns;
            const glm::dvec3 v = glm::normalize(glm::dvec3(0.3, 0.2, 1.0));
            for (int y = -6; y <= 6; ++y)
                for (int x = -6; x <= 6; ++x) {
                    const double px = x / 6.5, py = y / 6.5;
                    if (px * px + py * py >= 0.98) continue;
                    // A sphere seen along v: the normal through (px, py) in v's frame.
                    const glm::dvec3 a = glm::normalize(glm::cross(v, glm::dvec3(0, 1, 0))), b = glm::cross(a, v);
                    ns.push_back(glm::normalize(px * a + py * b + std::sqrt(1 - px * px - py * py) * v));
                }
            std::vector<double> truth;
            for (const auto& n : ns) truth.push_back(materialTruth(tree, metal, n, v).specular.y);
            if (std::getenv("MIPGLOSS_BINS"))
            for (double core : {0.15, 0.25, 0.35})
                for (int sectors : {3, 6, 8})
                    for (double sharpen : {1.0}) {
                    double num = 0, den = 0;
                    for (std::size_t i = 0; i < ns.size(); ++i) {
                        const double m = binned(base, r, ns[i], v, core, sectors, sharpen);
                        num += (m - truth[i]) * (m - truth[i]);
                        den += truth[i] * truth[i];
                    }
                    std::printf("%-8s r %.1f binned core %.2f sectors %d sharpen %.1f: %6.2f %%\n", map.c_str(), r, core, sectors,
                                sharpen, 100 * std::sqrt(num / den));
                }
            double mean = 0.0;
            for (Face f : kAllFaces)
                for (int y = 0; y < base.size(); ++y)
                    for (int x = 0; x < base.size(); ++x) mean += base.at(f, x, y).g / (6.0 * base.size() * base.size());
            for (double k : {2.0, 4.0, 16.0}) {
                const Split split = splitAt(base, k * mean);
                for (int count : {4, 8, 16})
                    for (double spread : {2.0, 4.0}) {
                        double num = 0, den = 0;
                        for (std::size_t i = 0; i < ns.size(); ++i) {
                            const double m = modelled(split.smooth, r, ns[i], v, count, spread) + lightsTerm(split, r, ns[i], v);
                            num += (m - truth[i]) * (m - truth[i]);
                            den += truth[i] * truth[i];
                        }
                        std::printf("%-8s r %.1f split %4.0f×mean (%zu lights) K %2d spread %.0f: %6.2f %%\n", map.c_str(), r, k,
                                    split.lights.size(), count, spread, 100 * std::sqrt(num / den));
                    }
            }
            if (std::getenv("MIPGLOSS_FIS"))
            for (int count : {4, 8, 16, 32})
                for (double spread : {1.0, 2.0, 4.0, 8.0}) {
                    double num = 0, den = 0;
                    for (std::size_t i = 0; i < ns.size(); ++i) {
                        const double m = modelled(base, r, ns[i], v, count, spread);
                        num += (m - truth[i]) * (m - truth[i]);
                        den += truth[i] * truth[i];
                    }
                    std::printf("%-8s r %.1f K %2d spread %4.1f: %6.2f %%\n", map.c_str(), r, count, spread,
                                100 * std::sqrt(num / den));
                }
        }
    }
}

}  // namespace
}  // namespace mipgloss
