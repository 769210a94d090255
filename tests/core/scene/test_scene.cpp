// The scene model, the camera maths and "build only what the scene needs".
#include "sphere_scene.h"
#include "test_support.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/metrics.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/io/default_env.h"
#include "mipgloss/scene/camera.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/lobes.h"
#include "mipgloss/scene/scene.h"

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include <string>

namespace mipgloss {
namespace {

// The largest |NDC| coordinate of the box's corners seen by the camera.
float largestNdc(const OrbitCamera& camera, const Bounds& b, float aspect) {
    const glm::mat4 vp = camera.projection(aspect, b) * camera.view();
    float largest = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y,
                          (corner & 4) ? b.max.z : b.min.z);
        const glm::vec4 c = vp * glm::vec4(p, 1.0f);
        largest = std::max({largest, std::abs(c.x / c.w), std::abs(c.y / c.w)});
        EXPECT_GT(c.w, 0.0f) << "corner behind the camera";
        EXPECT_LE(std::abs(c.z / c.w), 1.0f) << "corner clipped by near or far plane";
    }
    return largest;
}

TEST(OrbitCamera, FrameAllFillsTheViewWhateverTheScale) {
    // A 0.2-unit scan and a 120-unit one, off the origin: the same picture.
    for (const float scale : {0.2f, 1.0f, 120.0f}) {
        const Bounds b{glm::vec3(3.0f, -1.0f, 2.0f) * scale, glm::vec3(3.5f, -0.2f, 2.3f) * scale};
        for (const float aspect : {0.5f, 1.0f, 2.667f}) {
            OrbitCamera camera;
            camera.yawDegrees = 40.0f;
            camera.pitchDegrees = 25.0f;
            camera.frame(b, aspect, 1.1f);
            const float largest = largestNdc(camera, b, aspect);
            // Every corner inside the view (margin 1.1), and the box filling it to within the
            // slack of a box seen at an angle (a corner reaches 1/1.1 of the edge at the
            // limiting side).
            EXPECT_LE(largest, 1.0f / 1.1f + 1e-4f) << "scale " << scale << " aspect " << aspect;
            EXPECT_GE(largest, 0.85f / 1.1f) << "scale " << scale << " aspect " << aspect;
        }
    }
}

TEST(OrbitCamera, PitchStaysBelowThePoles) {
    OrbitCamera camera;
    camera.orbit(0.0f, 500.0f);
    EXPECT_LT(camera.pitchDegrees, 90.0f);
    camera.orbit(0.0f, -1000.0f);
    EXPECT_GT(camera.pitchDegrees, -90.0f);
    camera.zoom(0.0f);  // absurd: ignored
    camera.zoom(std::nanf(""));
    EXPECT_TRUE(std::isfinite(camera.distance));
    EXPECT_GT(camera.distance, 0.0f);
}

TEST(Frustum, CullsSpheresWhollyOutsideOnly) {
    OrbitCamera camera;
    camera.target = glm::vec3(0.0f);
    camera.distance = 10.0f;
    const Frustum f = Frustum::fromViewProjection(camera.projection(1.0f, Bounds{glm::vec3(-1.2f), glm::vec3(1.2f)}) * camera.view());
    EXPECT_TRUE(f.intersectsSphere(glm::vec3(0.0f), 1.0f));
    EXPECT_FALSE(f.intersectsSphere(glm::vec3(100.0f, 0.0f, 0.0f), 1.0f));   // far to the side
    EXPECT_FALSE(f.intersectsSphere(camera.position() + glm::vec3(0, 0, 5), 1.0f));  // behind
    // Straddling the left plane: kept.
    const float halfWidth = 10.0f * std::tan(glm::radians(camera.fovYDegrees) * 0.5f);
    EXPECT_TRUE(f.intersectsSphere(glm::vec3(-halfWidth - 0.5f, 0.0f, 0.0f), 1.0f));
}

// Figure 1 on a sphere: the scene model's layout, whatever mesh the caller reads (the default
// scene's teapot is tests/core/assets').
Scene figure1() { return makeFigure1Scene(std::make_shared<const Mesh>(makeSphere(8, 16))); }

TEST(Figure1Scene, IsThePapersFigure) {
    const Scene scene = figure1();
    ASSERT_EQ(scene.objects.size(), 4u);
    const float lambdas[] = {0.0f, 3.5f, 5.0f, 7.0f};
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(scene.materialOf(scene.objects[i]).lambda, lambdas[i]);
        EXPECT_EQ(scene.materialOf(scene.objects[i]).mode, i == 3 ? LookupMode::Normal : LookupMode::Reflect);
        EXPECT_EQ(scene.objects[i].mesh, scene.objects[0].mesh) << "one teapot, shared";
        EXPECT_FALSE(scene.materialOf(scene.objects[i]).sharperAtGrazing) << "the paper's look by default";
    }
    EXPECT_EQ(scene.environment.faceSize, 128);
    EXPECT_EQ(scene.environment.source, kBuiltinEnvironment);
    // In a row along x, not overlapping.
    for (std::size_t i = 1; i < 4; ++i)
        EXPECT_GT(scene.objects[i].worldCentre().x - scene.objects[i - 1].worldCentre().x,
                  scene.objects[0].mesh->bounds.max.x - scene.objects[0].mesh->bounds.min.x);
}

// The paper's single-lobe material of blur λ.
Material lobe(float lambda, LookupMode mode = LookupMode::Reflect, bool useIrradiance = false) {
    Material m;
    m.lambda = lambda;
    m.mode = mode;
    m.useIrradiance = useIrradiance;
    return m;
}

Scene sceneWith(std::initializer_list<Material> materials) { return test::spheresWearing(materials); }

// The deepest chain level a λ is read at on a base of `n`, rounded up (what chainNeeds promises).
int levelFor(float lambda, int n) {
    return static_cast<int>(std::ceil(chainLevelForExponent(lambdaToExponent(lambda), n) - 1e-9));
}

TEST(ChainNeeds, FollowTheDeepestLobeInUse) {
    // The argument is the base face size. At 128 the read levels hold n = ∞, 128, 32, 8, 1.
    const int base = 128;
    // Figure 1: background λ 2 (n = 3071), teapots λ 0, 3.5 (n = 383), 5 (n = 47) and 7 (n = 2,
    // normal mode on the chain): n = 2 lies between levels 3 (n = 8) and 4 (n = 1), so level 4.
    EXPECT_EQ(levelFor(7.0f, base), 4);
    EXPECT_EQ(levelFor(5.0f, base), 2) << "n = 47 lies between 128 and 32";
    EXPECT_EQ(levelFor(3.5f, base), 1);
    EXPECT_EQ(levelFor(2.0f, base), 1);
    EXPECT_EQ(chainNeeds(figure1(), base), (ChainNeeds{4, false}));
    EXPECT_EQ(chainNeeds(figure1(), 512), (ChainNeeds{6, false})) << "n = 2 between 8 and 1 at 512";
    EXPECT_EQ(chainNeeds(figure1(), 16), (ChainNeeds{1, false})) << "16: one read level";
    EXPECT_EQ(chainNeeds(figure1(), 0), chainNeeds(figure1(), 1)) << "a face size not yet known counts as 1";
    Scene noBackground = sceneWith({Material{}});
    noBackground.display.showBackground = false;
    EXPECT_EQ(chainNeeds(noBackground, base), (ChainNeeds{0, false})) << "mirrors only";
    EXPECT_EQ(chainNeeds(sceneWith({Material{}}), base), (ChainNeeds{0, false})) << "a sharp background too";
    EXPECT_EQ(chainNeeds(sceneWith({lobe(3.2f)}), base).lastFilteredLevel, 1) << "n = 581 blends 0 and 1";
    EXPECT_EQ(chainNeeds(sceneWith({lobe(6.0f)}), base).lastFilteredLevel, 3) << "n = 11 blends 2 and 3";
    EXPECT_EQ(chainNeeds(sceneWith({lobe(40.0f)}), base).lastFilteredLevel, 4) << "n = 0: the last read level";
    Scene hidden = sceneWith({lobe(1.0f), lobe(6.0f)});
    hidden.objects[1].visible = false;
    EXPECT_EQ(chainNeeds(hidden, base).lastFilteredLevel, 1) << "hidden objects need nothing";
    Scene background = sceneWith({lobe(1.0f)});
    background.display.backgroundLambda = 6.0f;
    EXPECT_EQ(chainNeeds(background, base).lastFilteredLevel, 3) << "the background's blur counts";
    background.display.showBackground = false;
    EXPECT_EQ(chainNeeds(background, base).lastFilteredLevel, 1) << "not when hidden";
    const Material irradiance = lobe(7.0f, LookupMode::Normal, true);
    EXPECT_EQ(chainNeeds(sceneWith({lobe(5.0f), irradiance}), base), (ChainNeeds{2, true}))
        << "the irradiance map replaces the chain for that object";
    for (float lambda = 0.0f; lambda <= 8.0f; lambda += 0.25f)
        for (int n : {16, 96, 128, 200, 512}) {
            const int level = chainNeeds(sceneWith({lobe(lambda)}), n).lastFilteredLevel;
            EXPECT_EQ(level, levelFor(lambda, n)) << "λ " << lambda << " base " << n;
            EXPECT_LE(level, lastReadLevel(n));
        }
}

TEST(Lobes, TheSameLambdaShowsTheSameLobeAtAnyFaceSize) {
    // λ has one meaning (phong.h): the embedded default imported at 128 and at 512, a λ = 4 lobe
    // (n = 191, cube of 79 at both) from each, read at 1500 uniform directions. Measured 0.24 %
    // relative RMS (what the 128² import lacks of the 512² one); bound 3 %. Under the old meaning (n = 3·N²·4^−λ − 1) the 512 lobe would
    // be n = 3071, 16× sharper.
    PreparedEnvironment small, large;
    small.filter = std::make_shared<const PhongFilter>(loadDefaultEnvironment(128).cube);
    large.filter = std::make_shared<const PhongFilter>(loadDefaultEnvironment(512).cube);
    const LobeStackEntry a = makeStackEntry(small, 4 * kStackStepsPerLevel), b = makeStackEntry(large, 4 * kStackStepsPerLevel);
    EXPECT_EQ(a.exponent, 191.0);
    EXPECT_EQ(a.cube->size(), 79);
    EXPECT_EQ(b.cube->size(), 79);
    const auto dirs = uniformDirections(1500);
    std::vector<Rgb> readA, readB;
    for (const glm::vec3& d : dirs) {
        readA.push_back(a.cube->sample(d));
        readB.push_back(b.cube->sample(d));
    }
    const double diff = relativeRms(readA, readB);
    EXPECT_LE(diff, 0.03);
}

TEST(PrepareEnvironment, BuildsOnlyWhatTheSceneNeedsAndReusesTheRest) {
    EnvironmentSettings settings;
    settings.faceSize = 64;
    const PreparedEnvironment mirrors = prepareEnvironment(settings, ChainNeeds{0, false});
    EXPECT_EQ(mirrors.lastFilteredLevel, 0);
    EXPECT_FALSE(mirrors.irradiance) << "no object asked for it";
    // Beyond the filtered levels: the cheap box filter of the level before.
    const MipChain box = buildBoxChain(*mirrors.base);
    ASSERT_EQ(mirrors.levelCount(), box.levelCount());
    for (int level = 1; level < box.levelCount(); ++level) {
        const CubeMap& a = mirrors.chain->levels[static_cast<std::size_t>(level)];
        const CubeMap& b = box.levels[static_cast<std::size_t>(level)];
        for (Face f : kAllFaces) EXPECT_EQ(a.at(f, 0, 0), b.at(f, 0, 0)) << "level " << level;
    }

    // A glossier object: the chain is rebuilt, the import is not.
    const PreparedEnvironment glossy = prepareEnvironment(settings, ChainNeeds{4, false}, &mirrors);
    EXPECT_EQ(glossy.base, mirrors.base);
    EXPECT_NE(glossy.chain, mirrors.chain);
    EXPECT_EQ(glossy.lastFilteredLevel, 4);
    // Back to a lower λ: nothing to build, the range never shrinks.
    const PreparedEnvironment back = prepareEnvironment(settings, ChainNeeds{2, false}, &glossy);
    EXPECT_EQ(back.chain, glossy.chain);
    EXPECT_TRUE(glossy.satisfies(settings, ChainNeeds{3, false}));
    EXPECT_FALSE(glossy.satisfies(settings, ChainNeeds{5, false}));
    // Irradiance when asked, then kept.
    const PreparedEnvironment diffuse = prepareEnvironment(settings, ChainNeeds{2, true}, &back);
    ASSERT_TRUE(diffuse.irradiance);
    EXPECT_EQ(diffuse.chain, back.chain);
    const PreparedEnvironment again = prepareEnvironment(settings, ChainNeeds{0, false}, &diffuse);
    EXPECT_EQ(again.irradiance, diffuse.irradiance);
    // Another builder: same import, new chain.
    EnvironmentSettings boxSettings = settings;
    boxSettings.builder = Builder::Box;
    const PreparedEnvironment other = prepareEnvironment(boxSettings, ChainNeeds{4, false}, &again);
    EXPECT_EQ(other.base, again.base);
    EXPECT_NE(other.chain, again.chain);
}

TEST(PrepareEnvironment, BadFileIsAnErrorNamingIt) {
    EnvironmentSettings settings;
    settings.source = "/nonexistent/sky.exr";
    try {
        prepareEnvironment(settings, ChainNeeds{});
        FAIL() << "no error";
    } catch (const EnvError& e) {
        EXPECT_NE(std::string(e.what()).find("sky.exr"), std::string::npos) << e.what();
    }
}

// Skipping levels (BuildOptions::lastFilteredLevel, what prepareEnvironment asks for): the levels
// through k are the full chain's, bit for bit, and each level above is one box step of the level
// before; the chain stays full. (What skipping saves is timed by the PhongSkipLevels benchmark in
// tests/bench.)
TEST(PrepareEnvironment, SkippedLevelsAreBoxStepsAndTheFilteredOnesUnchanged) {
    EnvironmentSettings settings;
    settings.faceSize = 32;
    const PreparedEnvironment imported = prepareEnvironment(settings, ChainNeeds{0, false});
    const MipChain full = buildChain(*imported.base, Builder::Phong);
    ASSERT_EQ(full.levelCount(), 6);
    for (const int through : {0, 2, 5}) {
        SCOPED_TRACE("filtered through level " + std::to_string(through));
        BuildOptions options;
        options.lastFilteredLevel = through;
        const MipChain chain = buildChain(*imported.base, Builder::Phong, options);
        ASSERT_EQ(chain.levelCount(), full.levelCount());
        for (int k = 0; k < chain.levelCount(); ++k) {
            const CubeMap& got = chain.levels[static_cast<std::size_t>(k)];
            const CubeMap expected = k <= through ? full.levels[static_cast<std::size_t>(k)]
                                                  : boxDownsample(chain.levels[static_cast<std::size_t>(k - 1)],
                                                                  levelSize(32, k));
            ASSERT_EQ(got.size(), expected.size()) << "level " << k;
            int differing = 0;
            for (Face f : kAllFaces)
                for (int y = 0; y < got.size(); ++y)
                    for (int x = 0; x < got.size(); ++x) differing += got.at(f, x, y) != expected.at(f, x, y);
            EXPECT_EQ(differing, 0) << "level " << k << (k <= through ? " (filtered)" : " (box step)");
        }
    }
}

TEST(MaterialValidity, ALambdaInRangeAndAFiniteNonNegativeTint) {
    EXPECT_TRUE(isValidMaterial(Material{}));
    Material m;
    m.lambda = static_cast<float>(kMaxLambda);
    m.tint = Rgb(0.0f, 2.5f, 1e6f);
    EXPECT_TRUE(isValidMaterial(m));
    for (const float lambda : {-0.01f, static_cast<float>(kMaxLambda) + 0.01f, std::nanf("")}) {
        Material bad;
        bad.lambda = lambda;
        EXPECT_FALSE(isValidMaterial(bad)) << lambda;
    }
    for (const float c : {-1e-6f, std::nanf(""), std::numeric_limits<float>::infinity()}) {
        Material bad;
        bad.tint.g = c;
        EXPECT_FALSE(isValidMaterial(bad)) << c;
    }
}

// A glTF camera (cameraThrough): the view matrix it gives puts the camera's position at the origin,
// its forward along −Z and its up along +Y, roll included (Mixer's camera0 of the 3D Commerce
// suite: a node rotation with a roll of about 4°; and one rolled by 30° about a level forward).
TEST(OrbitCamera, LooksThroughAGltfCameraWithItsRoll) {
    const auto check = [](const glm::vec3& position, const glm::quat& rotation) {
        const glm::vec3 forward = rotation * glm::vec3(0, 0, -1), up = rotation * glm::vec3(0, 1, 0);
        const OrbitCamera camera = cameraThrough(position, forward, up, 40.0f, 2.5f);
        EXPECT_NEAR(glm::length(camera.position() - position), 0.0f, 1e-5f);
        const glm::mat4 view = camera.view();
        const glm::vec3 ahead(view * glm::vec4(position + forward, 1.0f));
        const glm::vec3 above(view * glm::vec4(up, 0.0f));
        EXPECT_NEAR(glm::length(ahead - glm::vec3(0, 0, -1)), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::length(above - glm::vec3(0, 1, 0)), 0.0f, 1e-5f);
        EXPECT_EQ(camera.fovYDegrees, 40.0f);
    };
    check({-0.36f, 0.22f, 0.26f}, glm::normalize(glm::quat(0.8792929f, -0.0879293f, -0.4660252f, -0.0439646f)));
    check({1.0f, 2.0f, 3.0f}, glm::angleAxis(glm::radians(30.0f), glm::vec3(0, 0, -1)));
    const OrbitCamera rolled = cameraThrough({0, 0, 5}, {0, 0, -1},
                                             glm::angleAxis(glm::radians(30.0f), glm::vec3(0, 0, -1)) * glm::vec3(0, 1, 0), 40.0f, 5.0f);
    EXPECT_NEAR(rolled.rollDegrees, -30.0f, 1e-3f) << "a camera turned clockwise as it looks (about −Z by +30°)";
}

}  // namespace
}  // namespace mipgloss
