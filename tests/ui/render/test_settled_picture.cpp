// The settled picture against the exact convolution, where the picture reads it: a sphere drawn
// as `mipgloss render` draws it (every lobe in use from its own cube), its AOV telling for every
// pixel the direction the environment was read at, the lobe shown and whether the pixel is meant
// to equal that lobe there; the truth is the exact normalized Phong convolution of the base at
// that direction (referenceLobeAt). Environment: the committed sunrise HDRI, which has a sun.
#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/metrics.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/scene/environment.h"
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

struct PictureCase {
    const char* name;
    double exponent;
    LookupMode mode;
    int size;  // image side: sharp lobes need pixels finer than their cube's texels to be exact
};

std::shared_ptr<const PreparedEnvironment> sunrise(int faceSize) {
    static std::map<int, std::shared_ptr<const PreparedEnvironment>> cache;
    auto& env = cache[faceSize];
    if (!env) {
        EnvironmentSettings settings;
        settings.source = test::asset("env/sunrise.exr").string();
        settings.faceSize = faceSize;
        env = std::make_shared<const PreparedEnvironment>(prepareEnvironment(settings, ChainNeeds{16, false}));
    }
    return env;
}

using test::renderSettled;
using test::SettledRender;

class SettledPicture : public ::testing::TestWithParam<PictureCase> {};

TEST_P(SettledPicture, SphereShowsTheExactLobeAtThePixelsItMarksExact) {
    const PictureCase& param = GetParam();
    std::string error;
    ui::OffscreenRenderer* renderer = test::sharedRenderer(&error);
    ASSERT_NE(renderer, nullptr) << error;
    MIPGLOSS_REQUIRE_ASSET(test::asset("env/sunrise.exr"));
    const auto env = sunrise(128);
    Material material;
    material.lambda = static_cast<float>(exponentToLambda(param.exponent));
    material.mode = param.mode;
    const Scene scene = test::sphereScene(material);
    const SettledRender r = renderSettled(*renderer, scene, env, param.size);
    ASSERT_EQ(r.aov.width, param.size);
    ASSERT_EQ(r.hdr.size(), r.aov.exact.size());

    std::vector<glm::vec3> directions;
    std::vector<Rgb> shown;
    int objectPixels = 0;
    for (std::size_t i = 0; i < r.aov.exact.size(); ++i) {
        if (r.aov.exponent[i] == 0.0f) continue;
        ++objectPixels;
        // The AOV names the lobe the pixel shows: the material's.
        EXPECT_NEAR(r.aov.exponent[i], lambdaToExponent(material.lambda), 1e-4 * param.exponent) << i;
        if (r.aov.exact[i] != 1.0f) continue;
        directions.push_back(r.aov.direction[i]);
        shown.push_back(Rgb(r.hdr[i]));
    }
    ASSERT_GT(objectPixels, param.size * param.size / 8) << "the sphere fills the picture";
    const double markedFraction = static_cast<double>(directions.size()) / objectPixels;
    // The truth costs a sum over the base per direction: every k-th marked pixel, at most 3000.
    const std::size_t stride = std::max<std::size_t>(1, directions.size() / 3000);
    std::vector<glm::vec3> sampledDirections;
    std::vector<Rgb> sampledShown;
    for (std::size_t i = 0; i < directions.size(); i += stride) {
        sampledDirections.push_back(directions[i]);
        sampledShown.push_back(shown[i]);
    }
    directions.swap(sampledDirections);
    shown.swap(sampledShown);
    const std::vector<Rgb> truth = referenceLobeAt(*env->base, lambdaToExponent(material.lambda), directions);
    const double readError = relativeRms(shown, truth);
    double worst = 0.0;
    for (std::size_t i = 0; i < shown.size(); ++i)
        worst = std::max(worst, static_cast<double>(glm::length(shown[i] - truth[i]) / std::max(glm::length(truth[i]), 1e-6f)));
    std::printf("[ SettledPicture ] %s: %d object pixels, %.0f %% marked exact, relative RMS %.2f %%, worst pixel %.1f %%\n",
                param.name, objectPixels, 100.0 * markedFraction, 100.0 * readError, 100.0 * worst);
    // Within 2 % where marked. The mark is the level the GPU really reads (docs/exact-mask.md):
    // where a pixel's footprint covers several texels of the lobe cube (n128 at 384², n1024 at
    // 1024²: 36 % and 32 % of the sphere is read at its base level alone) the rest is not marked.
    // Half was asked for when textureQueryLod decided the mark, which claimed base-level reads
    // that were not; issue 24's footprint-widened lobes are what will mark the rest.
    EXPECT_GE(markedFraction, 0.3) << param.name;
    EXPECT_LE(readError, 0.02) << param.name;
}

INSTANTIATE_TEST_SUITE_P(Lobes, SettledPicture,
                         ::testing::Values(PictureCase{"n2", 2.0, LookupMode::Reflect, 256},
                                           PictureCase{"n16", 16.0, LookupMode::Reflect, 256},
                                           PictureCase{"n128", 128.0, LookupMode::Reflect, 384},
                                           PictureCase{"n1024", 1024.0, LookupMode::Reflect, 1024},
                                           PictureCase{"normal_n1", 1.0, LookupMode::Normal, 256}),
                         [](const auto& testInfo) { return std::string(testInfo.param.name); });

// λ means one lobe: the same material under the same lat-long imported at 128² and at 512²
// shows the same picture (each from its own lobe cube of the same size).
TEST(SettledPicture, LambdaFourLooksTheSameAtFaceSizes128And512) {
    std::string error;
    ui::OffscreenRenderer* renderer = test::sharedRenderer(&error);
    ASSERT_NE(renderer, nullptr) << error;
    Material material;
    material.lambda = 4.0f;
    const Scene scene = test::sphereScene(material);
    const int size = 512;
    const SettledRender small = renderSettled(*renderer, scene, sunrise(128), size);
    const SettledRender large = renderSettled(*renderer, scene, sunrise(512), size);
    std::vector<Rgb> a, b;
    for (std::size_t i = 0; i < small.hdr.size(); ++i)
        if (small.aov.exact[i] == 1.0f && large.aov.exact[i] == 1.0f) {
            a.push_back(Rgb(small.hdr[i]));
            b.push_back(Rgb(large.hdr[i]));
        }
    // Enough pixels marked exact in both to compare (a ninth of the image; 29,803 here).
    ASSERT_GT(a.size(), static_cast<std::size_t>(size * size / 9));
    const double difference = relativeRms(a, b);
    std::printf("[ SettledPicture ] λ 4 (n %.0f): face 128 vs 512, %zu pixels, relative RMS %.2f %%\n",
                lambdaToExponent(4.0), a.size(), 100.0 * difference);
    EXPECT_LE(difference, 0.03);
}

}  // namespace
}  // namespace mipgloss
