// layered.h and layered_reference.h: the layered material's weights (furnace, Fresnel toward
// grazing, coloured metals, the coat) and the model against the per-direction BRDF integral.
#include "mipgloss/scene/layered.h"

#include "mipgloss/ibl/ggx_fitted_lobes.h"

#include "mipgloss/scene/layered_reference.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "mipgloss/io/import.h"
#include "test_support.h"

using namespace mipgloss;

namespace {

Layers dielectric(Rgb base, float roughness) {
    Layers l;
    l.baseColor = base;
    l.roughness = roughness;
    return l;
}

}  // namespace

// A white dielectric in a uniform white environment: every lobe reads 1, so the picture is the sum
// of the weights, which each layer's albedo scaling makes exactly 1 at every view angle, with a
// coat or without.
TEST(LayeredWeights, AWhiteDielectricSumsToOneAtEveryAngleTheFurnaceTest) {
    for (float coat : {0.0f, 0.5f, 1.0f})
        for (float roughness : {0.0f, 0.2f, 0.5f, 0.9f})
            for (double mu : {0.0, 0.05, 0.3, 0.7, 1.0}) {
                Layers l = dielectric(Rgb(1.0f), roughness);
                l.coat = coat;
                const LayerWeights w = layerWeights(l, mu);
                const Rgb total = w.diffuse + w.specular + w.coat;
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(total[c], 1.0f, 1e-5f) << coat << " " << roughness << " " << mu;
            }
}

TEST(LayeredWeights, ADielectricsSpecularWeightRisesTowardTheSilhouette) {
    const Layers l = dielectric(Rgb(0.5f, 0.1f, 0.1f), 0.3f);
    float previous = 0.0f;
    for (double mu = 1.0; mu >= 0.05; mu -= 0.05) {
        const LayerWeights w = layerWeights(l, mu);
        EXPECT_GE(w.specular.g, previous) << mu;
        previous = w.specular.g;
        EXPECT_FLOAT_EQ(w.specular.r, w.specular.g);  // colourless
    }
    EXPECT_NEAR(layerWeights(l, 1.0).specular.g, 0.04f, 0.01f);  // F0 head-on
    EXPECT_GT(layerWeights(l, 0.1).specular.g, 0.2f);
}

TEST(LayeredWeights, AMetalsReflectionIsColouredAndItHasNoDiffuse) {
    Layers gold = dielectric(Rgb(1.0f, 0.78f, 0.34f), 0.25f);
    gold.metallic = 1.0f;
    const LayerWeights w = layerWeights(gold, 1.0);
    EXPECT_EQ(w.diffuse, Rgb(0.0f));
    EXPECT_GT(w.specular.r, w.specular.g);
    EXPECT_GT(w.specular.g, w.specular.b);
    EXPECT_NEAR(w.specular.b / w.specular.r, 0.34f, 0.03f);  // F0's colour, head-on
}

TEST(LayeredWeights, TheCoatTakesItsShareFromEverythingUnderIt) {
    Layers l = dielectric(Rgb(0.2f, 0.4f, 0.8f), 0.6f);
    const LayerWeights bare = layerWeights(l, 0.4);
    l.coat = 1.0f;
    const LayerWeights coated = layerWeights(l, 0.4);
    const float kept = 1.0f - coated.coat.r;
    EXPECT_GT(coated.coat.r, 0.04f);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(coated.diffuse[c], kept * bare.diffuse[c], 1e-6f);
        EXPECT_NEAR(coated.specular[c], kept * bare.specular[c], 1e-6f);
    }
}

TEST(LayeredWeights, LambdasInUseFollowTheLayers) {
    Material single;
    single.lambda = 3.0f;
    EXPECT_EQ(lambdasOf(single), std::vector<double>{3.0});
    Material m;
    m.layered = true;
    m.layers.roughness = 0.4f;
    // Each GGX layer: its Phong stand-in's λ, its visible normals' sharpest and widest
    // (ggx_sampling.h) and, up to r 0.9, its fitted lobes' (ggx_fitted_lobes.h); then the
    // diffuse base.
    const double roughness = m.layers.roughness;
    const ExponentRange specular = lookupExponentRange(roughness * roughness, kGgxLookups);
    const ExponentRange fitted = fittedLobeExponentRange(roughness);
    EXPECT_EQ(lambdasOf(m), (std::vector<double>{specularLambda(m.layers), exponentToLambda(specular.sharpest),
                                                 exponentToLambda(specular.widest), exponentToLambda(fitted.sharpest),
                                                 exponentToLambda(fitted.widest), diffuseLambda()}));
    m.layers.coat = 0.5f;  // its roughness 0.05: visible normals and r 0.1's fitted lobes at its α
    EXPECT_EQ(lambdasOf(m).size(), 11u);
    m.useIrradiance = true;  // the base from the irradiance map: no diffuse lobe from the chain
    const std::vector<double> lambdas = lambdasOf(m);
    ASSERT_EQ(lambdas.size(), 10u);
    EXPECT_NEAR(lambdas[0], specularLambda(m.layers), 0.0);
    EXPECT_NEAR(lambdas[5], coatLambda(m.layers), 0.0);
    EXPECT_LT(exponentToLambda(specular.sharpest), exponentToLambda(specular.widest));
    EXPECT_NEAR(diffuseLambda(), exponentToLambda(1.0), 0.0);
}

TEST(LayeredWeights, OutOfRangeLayersAreInvalid) {
    Material m;
    EXPECT_TRUE(isValidMaterial(m));
    for (auto bad : {+[](Layers& l) { l.metallic = 1.5f; }, +[](Layers& l) { l.roughness = -0.1f; },
                     +[](Layers& l) { l.coat = std::nanf(""); }, +[](Layers& l) { l.baseColor.g = -0.2f; },
                     +[](Layers& l) { l.specular = 2.0f; }, +[](Layers& l) { l.coatRoughness = INFINITY; }}) {
        Material b;
        bad(b.layers);
        EXPECT_FALSE(isValidMaterial(b));
    }
}

// In a uniform environment the split sum is exact: model and reference agree whatever the layers
// (lobes the 32² cube resolves: σ of several texels; a narrower lobe's texel sum is too coarse to
// carry Fresnel and the horizon direction by direction).
TEST(LayeredModel, EqualsTheReferenceInAUniformEnvironment) {
    const CubeMap white(32, Rgb(1.0f));
    Layers l = dielectric(Rgb(1.0f), 0.5f);
    l.coat = 0.7f;
    l.coatRoughness = 0.3f;
    for (double mu : {0.1, 0.5, 0.95}) {
        const glm::dvec3 n(0, 0, 1), v(std::sqrt(1 - mu * mu), 0, mu);
        const LayeredPixel ref = layeredReference(white, l, n, v);
        const LayeredPixel model = layeredModel(white, l, n, v);
        EXPECT_NEAR(ref.total().r, 1.0f, 0.02f) << mu;  // the furnace, integrated per direction
        EXPECT_NEAR(model.total().r, ref.total().r, 0.02f) << mu;
    }
}

// The split sum against the per-direction integral on real environments (held out: the model has
// no parameter fitted to any map). Relative RMS of the specular layer over random normals and view
// azimuths, per lobe (λ) and view angle (N·v), for a dielectric (F0 0.04, where Fresnel matters
// most) and gold; printed as the table docs/layered-materials.md quotes.
TEST(LayeredModel, SplitSumErrorOnRealEnvironmentsIsPublishedAndBounded) {
    const std::vector<std::string> maps{"sunset", "interior", "forest"};  // a sun, a window, foliage
    std::vector<CubeMap> envs;
    for (const std::string& map : maps) {
        const auto path = test::asset("env/" + map + ".exr");
        MIPGLOSS_REQUIRE_ASSET(path);
        ImportOptions o;
        o.faceSize = 32;
        envs.push_back(loadEnvironment(path, o).cube);
    }
    const std::vector<float> roughnesses{0.3f, 0.45f, 0.6f, 0.8f, 1.0f};
    const std::vector<double> cosines{1.0, 0.8, 0.5, 0.3, 0.15, 0.05};
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (const bool metal : {false, true}) {
        std::printf("[layered] %s specular layer, relative RMS (model vs per-direction integral), %zu maps at 32²\n",
                    metal ? "gold" : "dielectric F0 0.04", envs.size());
        std::printf("[layered]   roughness      n   ");
        for (double mu : cosines) std::printf("  N·v %.2f", mu);
        std::printf("\n");
        for (const float roughness : roughnesses) {
            Layers l = dielectric(Rgb(1.0f, 0.78f, 0.34f), roughness);
            l.metallic = metal ? 1.0f : 0.0f;
            std::printf("[layered]   %9.2f %6.1f   ", roughness, roughnessToExponent(roughness));
            for (double mu : cosines) {
                double err2 = 0.0, ref2 = 0.0;
                for (const CubeMap& env : envs)
                    for (int k = 0; k < 12; ++k) {
                        const double z = 2.0 * uniform(rng) - 1.0, phi = 2.0 * std::numbers::pi * uniform(rng);
                        const glm::dvec3 n(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
                        const glm::dvec3 helper = std::abs(n.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
                        const glm::dvec3 t = glm::normalize(glm::cross(n, helper)), b = glm::cross(n, t);
                        const double a = 2.0 * std::numbers::pi * uniform(rng), s = std::sqrt(1 - mu * mu);
                        const glm::dvec3 v = mu * n + s * (std::cos(a) * t + std::sin(a) * b);
                        const Rgb ref = layeredReference(env, l, n, v).specular;
                        const Rgb model = layeredModel(env, l, n, v).specular;
                        for (int c = 0; c < 3; ++c) {
                            err2 += double(model[c] - ref[c]) * double(model[c] - ref[c]);
                            ref2 += double(ref[c]) * double(ref[c]);
                        }
                    }
                const double rel = std::sqrt(err2 / std::max(ref2, 1e-30));
                std::printf("  %7.2f%%", 100.0 * rel);
                // Regression bounds, about 1.3x the worst measured (2026-11-26): exact head-on up
                // to Fresnel's variation over the lobe; a wide lobe's horizon cut is the model's
                // large error at oblique views (docs/layered-materials.md).
                EXPECT_LT(rel, mu == 1.0 ? 0.01 : 0.7) << roughness << " " << mu << (metal ? " gold" : " dielectric");
            }
            std::printf("\n");
        }
    }
}
