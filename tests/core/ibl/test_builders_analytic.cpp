// Analytic ground truth for the mip builders (docs/phong-lobe.md, "Funk–Hecke band factors"): constant, linear and spherical-harmonic
// environments through the Funk–Hecke theorem, and energy.
#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/irradiance.h"
#include "mipgloss/ibl/phong.h"
#include "test_support.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>

using namespace mipgloss;

namespace {

// Funk–Hecke gains of the normalized Phong lobe: Λ_l = (n+1) ∫₀¹ P_l(t) t^n dt.
double gain1(double n) { return (n + 1.0) / (n + 2.0); }
double gain2(double n) { return n / (n + 3.0); }
double gain3(double n) { return (n + 1.0) * (n - 1.0) / ((n + 2.0) * (n + 4.0)); }

// An environment of spherical-harmonic degree <= 3, split by band so each band can be scaled.
struct ShEnvironment {
    double c = 1.0;
    glm::dvec3 a{0.3, -0.5, 0.4};
    double b2 = 0.35, b3 = 0.8;
    static double band2(const glm::dvec3& d) { return d.x * d.y + 0.5 * (3.0 * d.z * d.z - 1.0) - 0.4 * d.y * d.z; }
    static double band3(const glm::dvec3& d) { return d.x * d.y * d.z; }
    double value(const glm::dvec3& d, double g1 = 1, double g2 = 1, double g3 = 1) const {
        return c + g1 * glm::dot(a, d) + g2 * b2 * band2(d) + g3 * b3 * band3(d);
    }
};

// Largest |level - expected| over every texel centre of a level.
double maxDeviation(const CubeMap& level, const std::function<double(const glm::dvec3&)>& expected) {
    double worst = 0.0;
    const int m = level.size();
    for (Face f : kAllFaces)
        for (int y = 0; y < m; ++y)
            for (int x = 0; x < m; ++x) {
                const glm::dvec3 r(texelDirection(f, x, y, m));
                const double e = expected(r);
                for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, std::fabs(level.at(f, x, y)[ch] - e));
            }
    return worst;
}

}  // namespace

TEST(Builders, ConstantEnvironmentStaysConstantAtEveryLevel) {
    // Every builder normalizes its weights, so a constant maps to itself up to float rounding.
    for (int size : {32, 24}) {
        const CubeMap base(size, Rgb(0.75f));
        for (const Builder method : kAllBuilders) {
            const MipChain chain = buildChain(base, method);
            ASSERT_EQ(chain.levelCount(), fullChainLevelCount(size)) << builderName(method);
            for (int k = 0; k < chain.levelCount(); ++k) {
                const CubeMap& level = chain.levels[static_cast<std::size_t>(k)];
                ASSERT_EQ(level.size(), levelSize(size, k));
                for (Face f : kAllFaces)
                    for (int y = -1; y <= level.size(); ++y)  // borders included
                        for (int x = -1; x <= level.size(); ++x)
                            ASSERT_NEAR(level.at(f, x, y).g, 0.75f, 2e-6f)
                                << builderName(method) << " size " << size << " level " << k << " " << faceName(f) << " " << x << "," << y;
            }
        }
    }
}

TEST(Builders, LinearEnvironmentGetsTheFunkHeckeGainAtEveryLevel) {
    // L = c + a·ω convolved with D_n is c + a·R·(n+1)/(n+2) (docs/phong-lobe.md).
    // Tolerance 0.5 % of |a|: the default builder's deep levels treat each pyramid texel (1/8 of the
    // level's texel, 0.34 σ of its lobe) as a point, which perturbs the lobe's response by about
    // (0.34)²/24 ≈ 0.5 % of the field's variation at worst; the reference is exact to float
    // rounding and to the discrete sampling of the base (checked with the same bound).
    const ShEnvironment env;
    constexpr int kSize = 64;
    const CubeMap base = test::cubeFromFunction(kSize, [&](const glm::vec3& d) {
        return Rgb(static_cast<float>(env.c + glm::dot(env.a, glm::dvec3(d))));
    });
    const double tolerance = 0.005 * glm::length(env.a);
    for (const Builder method : {Builder::Phong, Builder::Reference}) {
        const MipChain chain = buildChain(base, method);
        for (int k = 1; k < chain.levelCount(); ++k) {
            const double n = lambdaToExponent(k, kSize);
            const double err = maxDeviation(chain.levels[static_cast<std::size_t>(k)], [&](const glm::dvec3& r) {
                return env.c + gain1(n) * glm::dot(env.a, r);
            });
            std::printf("[linear] %-9s level %d n=%8.1f max error %.2e (tolerance %.2e)\n", builderName(method), k, n, err, tolerance);
            EXPECT_LT(err, tolerance) << builderName(method) << " level " << k;
        }
    }
}

TEST(Builders, SphericalHarmonicEnvironmentFollowsFunkHecke) {
    // Bands 0-3 are scaled by Λ₀..Λ₃ of the lobe; tolerance as for the linear case, relative to the
    // field's total variation (|a| + b2 + b3).
    const ShEnvironment env;
    constexpr int kSize = 64;
    const CubeMap base = test::cubeFromFunction(kSize, [&](const glm::vec3& d) {
        return Rgb(static_cast<float>(env.value(glm::dvec3(d))));
    });
    const double tolerance = 0.005 * (glm::length(env.a) + env.b2 + env.b3);
    for (const Builder method : {Builder::Phong, Builder::Reference}) {
        const MipChain chain = buildChain(base, method);
        for (int k = 1; k < chain.levelCount(); ++k) {
            const double n = lambdaToExponent(k, kSize);
            const double err = maxDeviation(chain.levels[static_cast<std::size_t>(k)], [&](const glm::dvec3& r) {
                return env.value(r, gain1(n), gain2(n), gain3(n));
            });
            std::printf("[sh] %-9s level %d n=%8.1f max error %.2e (tolerance %.2e)\n", builderName(method), k, n, err, tolerance);
            EXPECT_LT(err, tolerance) << builderName(method) << " level " << k;
        }
    }
}

TEST(Builders, EnergyOfEveryLevelEqualsTheBase) {
    // The texel-centre rule with exact solid angles is invariant under the cube's 48 symmetries,
    // whose invariant spherical harmonics start at degree 4: it integrates every harmonic of degree
    // <= 3 exactly, at any face size. A degree-3 environment convolved with a zonal lobe stays
    // degree 3, so each level's solid-angle-weighted mean must equal the base's (= c) up to the
    // builder's own error, bounded above by 0.5 % of the field's variation; relative to c that is
    // 0.5 % · (|a| + b2 + b3) / c ≈ 0.9 %. We require 0.1 % of the mean, well inside it, because
    // pointwise errors average out: measured ~1e-6.
    const ShEnvironment env;
    constexpr int kSize = 64;
    const CubeMap base = test::cubeFromFunction(kSize, [&](const glm::vec3& d) {
        return Rgb(static_cast<float>(env.value(glm::dvec3(d))));
    });
    const double baseMean = base.weightedMean().x;
    EXPECT_NEAR(baseMean, env.c, 1e-5);
    for (const Builder method : {Builder::Phong, Builder::Reference}) {
        const MipChain chain = buildChain(base, method);
        for (int k = 1; k < chain.levelCount(); ++k) {
            const double mean = chain.levels[static_cast<std::size_t>(k)].weightedMean().x;
            std::printf("[energy] %-9s level %d mean %.7f base %.7f\n", builderName(method), k, mean, baseMean);
            EXPECT_NEAR(mean / baseMean, 1.0, 1e-3) << builderName(method) << " level " << k;
        }
    }
}

TEST(Irradiance, LinearAndQuadraticEnvironmentsAreExact) {
    // E/π is the n = 1 lobe: Λ₁ = 2/3, Λ₂ = 1/4, Λ₃ = 0. Tolerance 1e-3 of the field's variation:
    // the 64² source texels are 1/50 of the cosine lobe's width.
    const ShEnvironment env;
    const CubeMap base = test::cubeFromFunction(128, [&](const glm::vec3& d) {
        return Rgb(static_cast<float>(env.value(glm::dvec3(d))));
    });
    const CubeMap irradiance = computeIrradiance(base);
    EXPECT_EQ(irradiance.size(), kIrradianceFaceSize);
    const double err = maxDeviation(irradiance, [&](const glm::dvec3& r) { return env.value(r, 2.0 / 3.0, 0.25, 0.0); });
    std::printf("[irradiance] max error %.2e\n", err);
    EXPECT_LT(err, 1e-3 * (glm::length(env.a) + env.b2 + env.b3));
}
