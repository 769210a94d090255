// The glTF 2.0 BRDF (gltf_brdf.h), its visible-normal sampling and albedo table (ggx_sampling.h)
// and the radiance tree that integrates it (radiance_tree.h), each against an independent
// quadrature or a closed form, with the tolerance stated where it is checked.
#include "mipgloss/ibl/ggx_sampling.h"
#include "mipgloss/ibl/gltf_brdf.h"
#include "mipgloss/ibl/radiance_tree.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace mipgloss {
namespace {

constexpr double kPi = std::numbers::pi;

// ∫ g(l) dl over the upper hemisphere by the midpoint rule in (cos θ, φ): dl = d(cos θ) dφ.
template <class G>
double hemisphere(G&& g, int steps = 1200) {
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double c = (i + 0.5) / steps, s = std::sqrt(1.0 - c * c);
        for (int j = 0; j < 2 * steps; ++j) {
            const double phi = (j + 0.5) / (2 * steps) * 2.0 * kPi;
            sum += g(glm::dvec3(s * std::cos(phi), s * std::sin(phi), c));
        }
    }
    return sum * (1.0 / steps) * (2.0 * kPi / (2 * steps));
}

glm::dvec3 viewAt(double mu) { return {std::sqrt(1.0 - mu * mu), 0.0, mu}; }

TEST(GltfBrdf, VisibilityIsHeightCorrelatedSmithOverFourCosines) {
    // Appendix B's V against G2 = 1/(1 + Λ(v) + Λ(l)), Λ(c) = (√(1 + α² tan²) − 1)/2 (Heitz 2014).
    for (double alpha : {0.01, 0.2, 0.6, 1.0})
        for (double cl : {0.05, 0.4, 0.9})
            for (double cv : {0.1, 0.7, 1.0}) {
                auto lambda = [alpha](double c) { return 0.5 * (std::sqrt(1.0 + alpha * alpha * (1.0 - c * c) / (c * c)) - 1.0); };
                const double g2 = 1.0 / (1.0 + lambda(cl) + lambda(cv));
                EXPECT_NEAR(smithVisibility(alpha, cl, cv), g2 / (4.0 * cl * cv), 1e-12 * g2 / (cl * cv));
            }
    EXPECT_EQ(smithVisibility(0.5, -0.1, 0.5), 0.0);
    EXPECT_EQ(ggxDistribution(0.5, -0.1), 0.0);
}

TEST(GltfBrdf, DistributionIsNormalizedOverProjectedHalfVectors) {
    // ∫ D(h)(N·h) dh = 1 for every α (tolerance 1e-4 of the midpoint rule on 1200 × 2400).
    for (double alpha : {0.1, 0.3, 0.7, 1.0}) {
        const double total = hemisphere([alpha](const glm::dvec3& h) { return ggxDistribution(alpha, h.z) * h.z; }, 2000);
        EXPECT_NEAR(total, 1.0, 2e-3) << alpha;
    }
}

TEST(GltfBrdf, WeakWhiteFurnaceIntegratesToOne) {
    // ∫ D(h)·G1(v)/(4 N·v) dl = 1 over all l (Heitz 2014's weak white furnace): l below the horizon
    // counts too, so integrate both hemispheres.
    for (double alpha : {0.3, 0.6, 1.0})
        for (double mu : {0.2, 0.6, 1.0}) {
            const glm::dvec3 v = viewAt(mu);
            auto g = [&](const glm::dvec3& l) {
                const glm::dvec3 h = glm::normalize(l + v);
                return ggxDistribution(alpha, h.z) * smithMasking(alpha, mu) / (4.0 * mu);
            };
            const double above = hemisphere(g, 1500);
            const double below = hemisphere([&](const glm::dvec3& l) { return g(glm::dvec3(l.x, l.y, -l.z)); }, 1500);
            EXPECT_NEAR(above + below, 1.0, 5e-3) << "α " << alpha << " N·v " << mu;
        }
}

TEST(GltfBrdf, ClearCoatTakesItsFresnelFromTheBaseAtViewDotNormal) {
    GltfBrdf brdf;
    brdf.f0 = glm::dvec3(0.9);
    brdf.diffuse = glm::dvec3(0.0);
    brdf.alpha = 0.25;
    brdf.clearcoat = 1.0;
    brdf.coatAlpha = 0.09;
    const glm::dvec3 n(0, 0, 1), v = viewAt(0.5), l = glm::normalize(glm::dvec3(-0.3, 0.1, 0.9));
    const BrdfCosine coated = gltfBrdfCosine(brdf, n, v, l);
    GltfBrdf bare = brdf;
    bare.clearcoat = 0.0;
    const BrdfCosine plain = gltfBrdfCosine(bare, n, v, l);
    const double fc = 0.04 + 0.96 * std::pow(0.5, 5.0);
    EXPECT_NEAR(coatFresnelWeight(brdf, 0.5), fc, 1e-15);
    EXPECT_NEAR(coated.specular.x, (1.0 - fc) * plain.specular.x, 1e-12);
    const glm::dvec3 h = glm::normalize(l + v);
    EXPECT_NEAR(coated.coat.x, fc * ggxDistribution(0.09, h.z) * smithVisibility(0.09, l.z, 0.5) * l.z, 1e-12);
}

TEST(GgxAlbedoTable, AgreesWithBruteForceQuadratureOfTheBrdf) {
    // A + B (F0 = 1) and B against ∫ F·D·V·cos over the hemisphere by (cos θ, φ) quadrature;
    // Bd against (1/π)∫ (1 − v·h)⁵ cos. Tolerance 0.5 % of the albedo, 0.002 absolute.
    const GgxAlbedoTable& table = GgxAlbedoTable::shared();
    for (double r : {0.3, 0.5, 0.75, 1.0})
        for (double mu : {0.1, 0.35, 0.8, 1.0}) {
            const double alpha = r * r;
            const glm::dvec3 v = viewAt(mu);
            double whole = 0.0, edge = 0.0, diffuseEdge = 0.0;
            hemisphere([&](const glm::dvec3& l) {
                const glm::dvec3 h = glm::normalize(l + v);
                const double m = 1.0 - std::clamp(glm::dot(v, h), 0.0, 1.0), m5 = m * m * m * m * m;
                const double dvc = ggxDistribution(alpha, h.z) * smithVisibility(alpha, l.z, mu) * l.z;
                whole += dvc;
                edge += m5 * dvc;
                diffuseEdge += m5 * l.z / kPi;
                return 0.0;
            }, 1500);
            const double scale = (1.0 / 1500) * (2.0 * kPi / 3000);
            whole *= scale, edge *= scale, diffuseEdge *= scale;
            const GgxAlbedoTable::Albedo e = table.at(r, mu);
            EXPECT_NEAR(e.a + e.b, whole, 0.002 + 0.005 * whole) << "r " << r << " N·v " << mu;
            EXPECT_NEAR(e.b, edge, 0.002 + 0.005 * edge) << "r " << r << " N·v " << mu;
            EXPECT_NEAR(e.diffuseEdge, diffuseEdge, 0.002) << "N·v " << mu;
        }
}

TEST(GgxAlbedoTable, HoldsTheKnownAlbedosOfAWhiteMetal) {
    // MATHS.md: 1 − ln 2 at r = 1 head-on (the closed form), and 92 % kept at r 0.5 head-on;
    // the mirror keeps everything.
    const GgxAlbedoTable& table = GgxAlbedoTable::shared();
    const auto white = [&](double r, double mu) { return table.at(r, mu).specular(1.0); };
    EXPECT_NEAR(white(1.0, 1.0), 1.0 - std::log(2.0), 0.002);
    EXPECT_NEAR(white(0.5, 1.0), 0.92, 0.01);
    EXPECT_NEAR(white(0.0, 0.5), 1.0, 1e-6);
    EXPECT_NEAR(table.at(0.0, 1.0).a, 1.0, 1e-6);
}

TEST(GgxAlbedoTable, HoldsTheLobesMeanLightDirectionAsBruteForceQuadratureGivesIt) {
    // ∫ l·D·V·cos / ∫ D·V·cos over the hemisphere by (cos θ, φ) quadrature: the first moment the
    // mean lobe reads (meanLobe). Tolerance 0.003 (the table's bilinear reading between nodes).
    const GgxAlbedoTable& table = GgxAlbedoTable::shared();
    for (double r : {0.5, 0.75, 0.9, 1.0})
        for (double mu : {0.1, 0.35, 0.8, 1.0}) {
            const double alpha = r * r;
            const glm::dvec3 v = viewAt(mu);
            double whole = 0.0;
            glm::dvec3 moment(0.0);
            hemisphere([&](const glm::dvec3& l) {
                const glm::dvec3 h = glm::normalize(l + v);
                const double dvc = ggxDistribution(alpha, h.z) * smithVisibility(alpha, l.z, mu) * l.z;
                whole += dvc;
                moment += dvc * l;
                return 0.0;
            }, 800);
            const GgxAlbedoTable::Albedo e = table.at(r, mu);
            EXPECT_NEAR(e.meanX, moment.x / whole, 0.003) << "r " << r << " N·v " << mu;
            EXPECT_NEAR(e.meanZ, moment.z / whole, 0.003) << "r " << r << " N·v " << mu;
            // The mean lobe: its direction the mean's, its mean cosine 1 − 1/(n + 2) the mean's length.
            const MeanLobe lobe = meanLobe(e);
            EXPECT_NEAR(lobe.direction.x * std::hypot(e.meanX, e.meanZ), e.meanX, 1e-9);
            EXPECT_NEAR(1.0 - 1.0 / (lobe.exponent + 2.0), std::hypot(e.meanX, e.meanZ), 1e-9);
        }
}

TEST(GgxAlbedoTable, AtRoughnessOneTheMeanLobeIsAboutTheNormalAtEveryView) {
    // At α = 1 GGX's D is 1/π for every half vector, and D·V·cos over l is G2(v, l)/(4 N·v), which
    // depends on l's angle from N alone: the lobe is symmetric about N whatever v is.
    const GgxAlbedoTable& table = GgxAlbedoTable::shared();
    for (double mu : {0.02, 0.1, 0.35, 0.8, 1.0}) {
        const MeanLobe lobe = meanLobe(table.at(1.0, mu));
        EXPECT_NEAR(lobe.direction.z, 1.0, 1e-5) << "N·v " << mu;
    }
    // And a smoother layer's mean leans away from v (toward R), less toward grazing than R does.
    const MeanLobe half = meanLobe(table.at(0.5, 0.5));
    EXPECT_LT(half.direction.x, -0.1);
    EXPECT_GT(half.direction.x, -std::sqrt(0.75)) << "bent toward N from R";
}

TEST(GgxAlbedoTable, MeanLobeIsReadFromRoughnessNineTenthsAndBlendedFromEightTenths) {
    EXPECT_EQ(meanLobeShare(0.5), 0.0);
    EXPECT_EQ(meanLobeShare(kMeanLobeFrom), 0.0);
    EXPECT_NEAR(meanLobeShare(0.5 * (kMeanLobeFrom + kMeanLobeAll)), 0.5, 1e-12);
    EXPECT_EQ(meanLobeShare(kMeanLobeAll), 1.0);
    EXPECT_EQ(meanLobeShare(1.0), 1.0);
    EXPECT_EQ(meanLobeShare(std::nan("")), 0.0);
    const ExponentRange range = meanLobeExponentRange(1.0);
    EXPECT_GE(range.widest, 0.0);
    EXPECT_LT(range.sharpest, 1.0) << "at r 1 the lobe is about as wide as the clamped cosine";
}

TEST(GgxLookup, WeightsAverageToTheAlbedoAndLightsLeaveAboutR) {
    // Sixteen lookups of the renderer's pattern estimate the white metal's albedo within 8 %
    // (their sum is then rescaled by the table, ggx_sampling.h), and the pdf is GGX's.
    for (double r : {0.2, 0.5, 0.9})
        for (double mu : {0.15, 0.6, 1.0}) {
            const double alpha = r * r;
            double sum = 0.0;
            for (int k = 0; k < 16; ++k) sum += ggxLookup(alpha, viewAt(mu), ggxSequence(k, 16)).weight / 16.0;
            const double albedo = GgxAlbedoTable::shared().at(r, mu).specular(1.0);
            EXPECT_NEAR(sum, albedo, 0.08 * albedo) << "r " << r << " N·v " << mu;
            const GgxLookup s = ggxLookup(alpha, viewAt(mu), {0.3, 0.7});
            const glm::dvec3 h = glm::normalize(s.light + viewAt(mu));
            EXPECT_NEAR(s.pdf, smithMasking(alpha, mu) * ggxDistribution(alpha, h.z) / (4.0 * mu), 1e-9 * s.pdf);
        }
    // α = 0: the mirror, the lookup along R with weight 1 and an infinite lobe.
    const GgxLookup mirror = ggxLookup(0.0, viewAt(0.6), {0.5, 0.5});
    EXPECT_NEAR(mirror.light.x, -0.8, 1e-12);
    EXPECT_NEAR(mirror.light.z, 0.6, 1e-12);
    EXPECT_NEAR(mirror.weight, 1.0, 1e-12);
    EXPECT_TRUE(std::isinf(lookupExponent(mirror.pdf, 8)));
}

TEST(GgxLookup, ALobeNearTheHorizonReadsFromWhereItsHalfMaximumClearsIt) {
    // Lobe n's half-maximum cone (cos^n θ = ½) must lie above the horizon: a light lower than
    // that cone's half-angle is raised to it, its azimuth kept; a higher one is left alone.
    for (double n : {0.5, 3.0, 20.0, 400.0}) {
        const double half = std::acos(std::exp2(-1.0 / n));
        const glm::dvec3 high(std::cos(half + 0.05), 0.0, std::sin(half + 0.05));
        EXPECT_EQ(keptAboveHorizon(high, n), high) << n;
        for (double elevation : {half - 0.01, 0.0, -0.3}) {
            const double azimuth = 0.7;
            const glm::dvec3 low(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                                 std::sin(elevation));
            const glm::dvec3 kept = keptAboveHorizon(low, n);
            EXPECT_NEAR(glm::length(kept), 1.0, 1e-12) << n;
            EXPECT_NEAR(std::asin(kept.z), half, 1e-9) << n << " " << elevation;
            EXPECT_NEAR(std::atan2(kept.y, kept.x), azimuth, 1e-9) << n << " " << elevation;
        }
    }
    // n = 0 (a half-maximum at 90°) reads about N; the mirror's infinite lobe reads where it is.
    EXPECT_NEAR(keptAboveHorizon(glm::normalize(glm::dvec3(1.0, 0.0, 0.2)), 0.0).z, 1.0, 1e-12);
    const glm::dvec3 grazing = glm::normalize(glm::dvec3(1.0, 0.0, 1e-3));
    EXPECT_EQ(keptAboveHorizon(grazing, std::numeric_limits<double>::infinity()), grazing);
}

TEST(RadianceTree, IntegratesAUniformSphereExactlyAndTheCosineWithinTheHorizonSplit) {
    const CubeMap white(32, Rgb(1.0f));
    const RadianceTree tree(white);
    EXPECT_NEAR(tree.totalEnergy().y, 4.0 * kPi, 1e-9);
    // ∫ (N·ω)⁺ dω = π, for normals along an axis and off every axis.
    for (const glm::dvec3 n : {glm::dvec3(0, 0, 1), glm::normalize(glm::dvec3(0.3, -0.5, 0.8))}) {
        double sum = 0.0;
        tree.walk(RadianceTree::Focus{n, 0.6, n}, [&](const glm::dvec3& l, const glm::dvec3& e) {
            sum += std::max(0.0, glm::dot(n, l)) * e.y;
        });
        EXPECT_NEAR(sum, kPi, 2e-3 * kPi);
    }
}

TEST(RadianceTree, KeepsALoneBrightTexelWhereItIs) {
    // One lit texel in a black sphere: whatever the tolerance, the walk returns its energy at its
    // centre (the coarse nodes' energy-weighted directions), so a sun's highlight is where it is.
    CubeMap sun(64, Rgb(0.0f));
    sun.at(Face::PZ, 40, 21) = Rgb(1000.0f);
    const glm::dvec3 at = glm::dvec3(texelDirection(Face::PZ, 40, 21, 64));
    const RadianceTree tree(sun);
    for (double tolerance : {0.05, 0.5, 2.0}) {
        glm::dvec3 moment(0.0), total(0.0);
        tree.walk(RadianceTree::Focus{glm::dvec3(1, 0, 0), 0.1, glm::dvec3(0, 0, 1)},
                  [&](const glm::dvec3& l, const glm::dvec3& e) {
                      moment += e.y * l;
                      total += e;
                  },
                  RadianceTree::Accuracy{tolerance, 0.004});
        EXPECT_NEAR(total.y, 1000.0 * texelSolidAngle(40, 21, 64), 1e-9);
        EXPECT_NEAR(glm::length(moment / total.y - at), 0.0, 1e-6) << tolerance;  // texelDirection is float
    }
}

}  // namespace
}  // namespace mipgloss
