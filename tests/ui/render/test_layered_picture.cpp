// Layered materials as the renderer draws them (object.frag, layered.glsl), checked where the
// picture reads them: a settled sphere and its AOV, whose per-layer channels say which direction
// each layer read, its lobe and its weight; at every pixel marked exact the picture must equal
// Σ weight ⊙ exact lobe (referenceLobeAt) within 2 % relative RMS. Environments: forest (no sun)
// and sunrise (a sun); neither was used to fit anything in the model. Plus the furnace: a white
// dielectric in a uniform white environment returns at most 1 (+1 %) and close to 1.
#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/metrics.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/io/image_file.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/layered.h"
#include "mipgloss/scene/lobes.h"
#include "render_support.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace mipgloss {
namespace {

std::shared_ptr<const PreparedEnvironment> prepared(const std::filesystem::path& file, int faceSize) {
    static std::map<std::string, std::shared_ptr<const PreparedEnvironment>> cache;
    auto& env = cache[file.string() + "@" + std::to_string(faceSize)];
    if (!env) {
        EnvironmentSettings settings;
        settings.source = file.string();
        settings.faceSize = faceSize;
        env = std::make_shared<const PreparedEnvironment>(prepareEnvironment(settings, ChainNeeds{16, true}));
    }
    return env;
}

using Settled = test::SettledRender;

// test::renderSettled with the binary's one renderer.
Settled renderSettled(const Scene& scene, const std::shared_ptr<const PreparedEnvironment>& env, int size) {
    std::string error;
    ui::OffscreenRenderer* renderer = test::sharedRenderer(&error);
    EXPECT_NE(renderer, nullptr) << error;
    return renderer ? test::renderSettled(*renderer, scene, env, size) : Settled{};
}

Material layered(const Layers& layers) {
    Material m;
    m.layered = true;
    m.layers = layers;
    return m;
}

struct LayeredCase {
    const char* name;
    Layers layers;
    const char* map;
    int faceSize;  // the environment's base
    int size;      // image side: the sphere fills it, so 384 is large on screen and 96 small
};

class LayeredPicture : public ::testing::TestWithParam<LayeredCase> {};

TEST_P(LayeredPicture, ExactPixelsAreTheWeightedSumOfTheirLayersExactLobes) {
    const LayeredCase& param = GetParam();
    const auto file = test::asset(std::string("env/") + param.map + ".exr");
    MIPGLOSS_REQUIRE_ASSET(file);
    const auto env = prepared(file, param.faceSize);
    const Scene scene = test::sphereScene(layered(param.layers));
    const int size = param.size;
    const Settled r = renderSettled(scene, env, size);
    ASSERT_TRUE(r.aov.layered);
    ASSERT_EQ(r.hdr.size(), r.aov.exact.size());

    // The marked pixels, every k-th (the truth is a sum over the base per direction and layer).
    std::vector<std::size_t> marked;
    int objectPixels = 0;
    for (std::size_t i = 0; i < r.aov.exact.size(); ++i) {
        if (r.aov.exponent[i] == 0.0f) continue;
        ++objectPixels;
        if (r.aov.exact[i] == 1.0f) marked.push_back(i);
    }
    ASSERT_GT(objectPixels, size * size / 8);
    ASSERT_FALSE(marked.empty()) << param.name;
    const double markedFraction = static_cast<double>(marked.size()) / objectPixels;
    const std::size_t stride = std::max<std::size_t>(1, marked.size() / 1500);
    std::vector<std::size_t> sample;
    for (std::size_t k = 0; k < marked.size(); k += stride) sample.push_back(marked[k]);

    std::vector<Rgb> predicted(sample.size(), Rgb(0.0f)), shown;
    for (const ui::AovImage::Layer* layer : {&r.aov.diffuse, &r.aov.specular, &r.aov.coat}) {
        std::map<float, std::vector<std::size_t>> byExponent;  // one lobe per layer, but group anyway
        for (std::size_t k = 0; k < sample.size(); ++k)
            if (layer->weight[sample[k]] != glm::vec3(0.0f)) byExponent[layer->exponent[sample[k]]].push_back(k);
        for (const auto& [exponent, ks] : byExponent) {
            std::vector<glm::vec3> directions;
            for (std::size_t k : ks) directions.push_back(layer->direction[sample[k]]);
            const std::vector<Rgb> lobe = referenceLobeAt(*env->base, exponent, directions);
            for (std::size_t j = 0; j < ks.size(); ++j) predicted[ks[j]] += layer->weight[sample[ks[j]]] * lobe[j];
        }
    }
    for (std::size_t i : sample) shown.push_back(Rgb(r.hdr[i]));
    const double error = relativeRms(shown, predicted);
    std::printf("[ LayeredPicture ] %s on %s at %d², %d² image: %d object pixels, %.0f %% marked exact, "
                "Σ weight ⊙ lobe vs picture relative RMS %.2f %%\n",
                param.name, param.map, param.faceSize, size, objectPixels, 100.0 * markedFraction, 100.0 * error);
    // Large on screen most pixels read their lobes at the cubes' base level; small, a footprint
    // wider than a texel blurs more of them, which the AOV says (not exact) and this does not count.
    if (size >= 384) {
        EXPECT_GE(markedFraction, 0.5) << param.name;
    }
    EXPECT_LE(error, 0.02) << param.name;

    // The AOV's weights are layered.h's at the pixel's N·v (the table read on the GPU).
    for (std::size_t k = 0; k < sample.size(); k += 37) {
        const std::size_t i = sample[k];
        const LayerWeights w = layerWeights(param.layers, r.aov.cosView[i]);
        EXPECT_NEAR(r.aov.specular.weight[i].g, w.specular.g, 0.01f + 0.02f * w.specular.g) << i;
        EXPECT_NEAR(r.aov.diffuse.weight[i].r, w.diffuse.r, 0.01f + 0.02f * w.diffuse.r) << i;
    }
}

// Lobes a stack entry holds at full width (√(32 n) within its size cap, builders.h), so pixels can be
// exact: a coat of roughness 0.25 (n = 94), not a car paint's near-mirror coat.
INSTANTIATE_TEST_SUITE_P(
    Materials, LayeredPicture,
    ::testing::Values(
        LayeredCase{"red_plastic", {Rgb(0.7f, 0.08f, 0.05f), 0.0f, 0.4f, 0.04f, 0.0f, 0.05f, MaterialMaps{}}, "forest", 128, 384},
        LayeredCase{"rough_gold", {Rgb(1.0f, 0.766f, 0.336f), 1.0f, 0.5f, 0.04f, 0.0f, 0.05f, MaterialMaps{}}, "sunrise", 128, 384},
        LayeredCase{"coated_blue", {Rgb(0.1f, 0.2f, 0.6f), 0.3f, 0.6f, 0.04f, 1.0f, 0.25f, MaterialMaps{}}, "sunrise", 128, 384},
        // Other face sizes, and the sphere small on screen.
        LayeredCase{"red_plastic_256", {Rgb(0.7f, 0.08f, 0.05f), 0.0f, 0.4f, 0.04f, 0.0f, 0.05f, MaterialMaps{}}, "sunrise", 256, 384},
        LayeredCase{"coated_blue_64", {Rgb(0.1f, 0.2f, 0.6f), 0.3f, 0.6f, 0.04f, 1.0f, 0.25f, MaterialMaps{}}, "forest", 64, 384},
        LayeredCase{"rough_gold_small", {Rgb(1.0f, 0.766f, 0.336f), 1.0f, 0.5f, 0.04f, 0.0f, 0.05f, MaterialMaps{}}, "sunrise", 128, 96},
        LayeredCase{"red_plastic_small", {Rgb(0.7f, 0.08f, 0.05f), 0.0f, 0.4f, 0.04f, 0.0f, 0.05f, MaterialMaps{}}, "forest", 256, 96}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

// A dielectric's specular weight rises toward the silhouette; a metal's is coloured (its F0).
TEST(LayeredPicture, DielectricWeightRisesTowardTheSilhouetteAndAMetalsIsColoured) {
    const auto file = test::asset("env/forest.exr");
    MIPGLOSS_REQUIRE_ASSET(file);
    const auto env = prepared(file, 64);
    const Settled plastic = renderSettled(test::sphereScene(layered({Rgb(0.5f), 0.0f, 0.3f, 0.04f, 0.0f, 0.05f, MaterialMaps{}})), env, 192);
    double centre = 0.0, rim = 0.0;
    int centreCount = 0, rimCount = 0;
    for (std::size_t i = 0; i < plastic.aov.cosView.size(); ++i) {
        if (plastic.aov.exponent[i] == 0.0f) continue;
        const float mu = plastic.aov.cosView[i];
        if (mu > 0.9f) centre += plastic.aov.specular.weight[i].g, ++centreCount;
        if (mu < 0.2f) rim += plastic.aov.specular.weight[i].g, ++rimCount;
    }
    ASSERT_GT(centreCount, 0);
    ASSERT_GT(rimCount, 0);
    centre /= centreCount;
    rim /= rimCount;
    std::printf("[ LayeredPicture ] dielectric specular weight: %.3f where N·v > 0.9, %.3f where N·v < 0.2\n", centre,
                rim);
    EXPECT_NEAR(centre, 0.04, 0.01);
    EXPECT_GT(rim, 3.0 * centre);

    const Settled gold = renderSettled(test::sphereScene(layered({Rgb(1.0f, 0.766f, 0.336f), 1.0f, 0.3f, 0.04f, 0.0f, 0.05f, MaterialMaps{}})), env, 192);
    for (std::size_t i = 0; i < gold.aov.cosView.size(); i += 97) {
        if (gold.aov.exponent[i] == 0.0f || gold.aov.cosView[i] < 0.5f) continue;
        const glm::vec3 w = gold.aov.specular.weight[i];
        EXPECT_GT(w.r, w.g) << i;
        EXPECT_GT(w.g, w.b) << i;
        EXPECT_EQ(gold.aov.diffuse.weight[i], glm::vec3(0.0f)) << i;
    }
}

// The furnace: a white dielectric (with and without a coat) in a uniform white environment.
TEST(LayeredPicture, AWhiteDielectricInAWhiteFurnaceReturnsAtMostOne) {
    test::TempDir dir;
    const auto file = dir / "white.exr";
    std::vector<float> white(64 * 32 * 3, 1.0f);
    writeFloatChannels(file, 64, 32, {"R", "G", "B"}, white);
    // Two face sizes, the sphere large (384²) and small (64²) on screen, with and without a coat.
    for (const int faceSize : {32, 128})
    for (const int size : {64, 384})
    for (const float coat : {0.0f, 1.0f}) {
        const auto env = prepared(file, faceSize);
        const Settled r = renderSettled(test::sphereScene(layered({Rgb(1.0f), 0.0f, 0.5f, 0.04f, coat, 0.3f, MaterialMaps{}})), env, size);
        float most = 0.0f, least = 2.0f, centre = 0.0f, bestMu = 0.0f;
        for (std::size_t i = 0; i < r.hdr.size(); ++i) {
            if (r.aov.exponent[i] == 0.0f) continue;
            for (int c = 0; c < 3; ++c) {
                most = std::max(most, r.hdr[i][c]);
                least = std::min(least, r.hdr[i][c]);
            }
            if (r.aov.cosView[i] > bestMu) bestMu = r.aov.cosView[i], centre = r.hdr[i].g;
        }
        std::printf("[ LayeredPicture ] furnace at %d², %d² image, coat %.0f: pixels in [%.4f, %.4f], %.4f where N·v "
                    "is %.3f\n",
                    faceSize, size, coat, least, most, centre, bestMu);
        EXPECT_LE(most, 1.01f) << faceSize << " " << size << " " << coat;
        EXPECT_GE(centre, 0.9f) << faceSize << " " << size << " " << coat;
    }
}

}  // namespace
}  // namespace mipgloss
