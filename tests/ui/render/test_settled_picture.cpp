// The picture against the exact convolution, where the picture reads it (issue 24's must-show):
// a sphere drawn as `mipgloss render` draws it (every lobe from the lobe stack), its AOV telling for
// every pixel the direction the environment was read at, the lobe shown (the material's, widened
// by the pixel's footprint) and whether the pixel is meant to equal that lobe there; the truth is
// the exact normalized Phong convolution of the base at that direction and exponent
// (referenceLobeAt). Base 256, held-out HDRIs with and without a sun, exponents 2 … 4096 on and
// between the stack's entries.
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
    const char* map;  // under tests/assets/env
    double exponent;
    LookupMode mode;
};

std::shared_ptr<const PreparedEnvironment> environmentOf(const std::string& map, int faceSize) {
    static std::map<std::pair<std::string, int>, std::shared_ptr<const PreparedEnvironment>> cache;
    auto& env = cache[{map, faceSize}];
    if (!env) {
        EnvironmentSettings settings;
        settings.source = test::asset("env/" + map).string();
        settings.faceSize = faceSize;
        env = std::make_shared<const PreparedEnvironment>(prepareEnvironment(settings, ChainNeeds{16, false}));
    }
    return env;
}

std::shared_ptr<const PreparedEnvironment> sunrise(int faceSize) { return environmentOf("sunrise.exr", faceSize); }

using test::renderSettled;
using test::SettledRender;

class SettledPicture : public ::testing::TestWithParam<PictureCase> {};

TEST_P(SettledPicture, SphereShowsTheExactLobeAtThePixelsItMarksExact) {
    const PictureCase& param = GetParam();
    std::string error;
    ui::OffscreenRenderer* renderer = test::sharedRenderer(&error);
    ASSERT_NE(renderer, nullptr) << error;
    MIPGLOSS_REQUIRE_ASSET(test::asset(std::string("env/") + param.map));
    const auto env = environmentOf(param.map, 256);
    constexpr int kSize = 512;
    Material material;
    material.lambda = static_cast<float>(exponentToLambda(param.exponent));
    material.mode = param.mode;
    const double meant = lambdaToExponent(material.lambda);
    const Scene scene = test::sphereScene(material);
    const SettledRender r = renderSettled(*renderer, scene, env, kSize);
    ASSERT_EQ(r.aov.width, kSize);
    ASSERT_EQ(r.hdr.size(), r.aov.exact.size());

    std::vector<glm::vec3> directions;
    std::vector<double> exponents;
    std::vector<Rgb> shown;
    int objectPixels = 0, widened = 0;
    for (std::size_t i = 0; i < r.aov.exact.size(); ++i) {
        if (r.aov.exponent[i] == 0.0f) continue;
        ++objectPixels;
        // The AOV names the lobe the pixel shows: the material's, widened by the footprint, never sharper.
        EXPECT_LE(r.aov.exponent[i], meant * (1.0 + 1e-5)) << i;
        if (r.aov.exponent[i] < 0.99 * meant) ++widened;
        if (r.aov.exact[i] != 1.0f) continue;
        directions.push_back(r.aov.direction[i]);
        exponents.push_back(r.aov.exponent[i]);
        shown.push_back(Rgb(r.hdr[i]));
    }
    ASSERT_GT(objectPixels, kSize * kSize / 8) << "the sphere fills the picture";
    const double markedFraction = static_cast<double>(directions.size()) / objectPixels;
    // The truth costs a sum over the base per direction: every k-th marked pixel, at most 1500
    // (a wide lobe's sum covers half the base: 30 s for 3000 at n = 2).
    const std::size_t stride = std::max<std::size_t>(1, directions.size() / 1500);
    std::vector<glm::vec3> sampledDirections;
    std::vector<double> sampledExponents;
    std::vector<Rgb> sampledShown;
    for (std::size_t i = 0; i < directions.size(); i += stride) {
        sampledDirections.push_back(directions[i]);
        sampledExponents.push_back(exponents[i]);
        sampledShown.push_back(shown[i]);
    }
    const std::vector<Rgb> truth = test::exactLobesAt(*env->base, sampledExponents, sampledDirections);
    const double readError = relativeRms(sampledShown, truth);
    double worst = 0.0;
    for (std::size_t i = 0; i < sampledShown.size(); ++i)
        worst = std::max(worst, static_cast<double>(glm::length(sampledShown[i] - truth[i]) /
                                                    std::max(glm::length(truth[i]), 1e-6f)));
    std::printf("[ SettledPicture ] %s: %d object pixels, %.1f %% marked exact, %.1f %% widened > 1 %%, "
                "relative RMS %.2f %%, worst pixel %.1f %%\n",
                param.name, objectPixels, 100.0 * markedFraction, 100.0 * widened / objectPixels, 100.0 * readError,
                100.0 * worst);
    // Issue 24: within 2 % where marked, and at least 80 % of the sphere marked.
    EXPECT_GE(markedFraction, 0.8) << param.name;
    EXPECT_LE(readError, 0.02) << param.name;
}

// n on an entry (2, 16, 128, 1024, 4096 round to λ = j/8 only approximately: each is between two)
// and half way between entries (λ = (j + ½)/8); interior.exr has a sun through its window,
// courtyard.exr none.
INSTANTIATE_TEST_SUITE_P(Lobes, SettledPicture,
                         ::testing::Values(PictureCase{"interior_n2", "interior.exr", 2.0, LookupMode::Reflect},
                                           PictureCase{"interior_n16", "interior.exr", 16.0, LookupMode::Reflect},
                                           PictureCase{"interior_n128", "interior.exr", 128.0, LookupMode::Reflect},
                                           PictureCase{"interior_n1024", "interior.exr", 1024.0, LookupMode::Reflect},
                                           PictureCase{"interior_n4096", "interior.exr", 4096.0, LookupMode::Reflect},
                                           PictureCase{"interior_half_step_n497", "interior.exr", 496.986, LookupMode::Reflect},
                                           PictureCase{"interior_normal_n1", "interior.exr", 1.0, LookupMode::Normal},
                                           PictureCase{"courtyard_n2", "courtyard.exr", 2.0, LookupMode::Reflect},
                                           PictureCase{"courtyard_n128", "courtyard.exr", 128.0, LookupMode::Reflect},
                                           PictureCase{"courtyard_n1024", "courtyard.exr", 1024.0, LookupMode::Reflect},
                                           PictureCase{"courtyard_n4096", "courtyard.exr", 4096.0, LookupMode::Reflect},
                                           PictureCase{"courtyard_half_step_n36", "courtyard.exr", 36.0131, LookupMode::Reflect}),
                         [](const auto& testInfo) { return std::string(testInfo.param.name); });

// λ means one lobe: the same material under the same lat-long imported at 128² and at 512²
// shows the same picture (each from its own stack entries of the same size).
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
