#include "mipgloss/ibl/cubemap.h"
#include "test_support.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>

using namespace mipgloss;

TEST(CubeMap, DirectionFaceRoundTripOnEveryFaceAndEdge) {
    // Interior texel centres, edge and corner points of every face: face -> direction -> face.
    constexpr int kSize = 16;
    for (Face f : kAllFaces) {
        for (int y = 0; y <= 2 * kSize; ++y) {
            for (int x = 0; x <= 2 * kSize; ++x) {
                const float s = static_cast<float>(x) / (2 * kSize), t = static_cast<float>(y) / (2 * kSize);
                const glm::vec3 d = faceToDirection(f, s, t);
                ASSERT_NEAR(glm::length(d), 1.0f, 1e-6f);
                const FaceCoord c = directionToFace(d);
                // On an edge two faces own the direction; both must give the same direction back.
                const glm::vec3 back = faceToDirection(c.face, c.s, c.t);
                ASSERT_LT(glm::length(back - d), 1e-6f) << "face " << faceName(f) << " s=" << s << " t=" << t;
                if (x > 0 && x < 2 * kSize && y > 0 && y < 2 * kSize) {
                    ASSERT_EQ(c.face, f);
                    ASSERT_NEAR(c.s, s, 1e-6f);
                    ASSERT_NEAR(c.t, t, 1e-6f);
                }
            }
        }
    }
}

TEST(CubeMap, FaceSelectionMatchesGlTable) {
    // GL 4.5 table 8.19: the major axis picks the face, and (sc, tc) the corner.
    struct Case { glm::vec3 dir; Face face; float s, t; };
    const Case cases[] = {
        {{1, 0.5f, 0.25f}, Face::PX, 0.5f * (-0.25f + 1), 0.5f * (-0.5f + 1)},
        {{-1, 0.5f, 0.25f}, Face::NX, 0.5f * (0.25f + 1), 0.5f * (-0.5f + 1)},
        {{0.5f, 1, 0.25f}, Face::PY, 0.5f * (0.5f + 1), 0.5f * (0.25f + 1)},
        {{0.5f, -1, 0.25f}, Face::NY, 0.5f * (0.5f + 1), 0.5f * (-0.25f + 1)},
        {{0.5f, 0.25f, 1}, Face::PZ, 0.5f * (0.5f + 1), 0.5f * (-0.25f + 1)},
        {{0.5f, 0.25f, -1}, Face::NZ, 0.5f * (-0.5f + 1), 0.5f * (-0.25f + 1)},
    };
    for (const Case& c : cases) {
        const FaceCoord fc = directionToFace(c.dir);
        EXPECT_EQ(fc.face, c.face);
        EXPECT_NEAR(fc.s, c.s, 1e-6f);
        EXPECT_NEAR(fc.t, c.t, 1e-6f);
    }
}

TEST(CubeMap, TexelSolidAnglesSumToFourPi) {
    for (int size : {1, 2, 3, 7, 64, 256}) {
        double sum = 0.0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) sum += 6.0 * texelSolidAngle(x, y, size);
        EXPECT_NEAR(sum, 4.0 * std::numbers::pi, 1e-10) << "size " << size;
    }
    // A whole face is a sixth of the sphere; a texel at the centre of a large face is ~(2/N)².
    EXPECT_NEAR(texelSolidAngle(0, 0, 1), 4.0 * std::numbers::pi / 6.0, 1e-12);
    EXPECT_NEAR(texelSolidAngle(512, 512, 1024) / std::pow(2.0 / 1024, 2), 1.0, 1e-5);
}

TEST(CubeMap, BorderTexelsComeFromTheNeighbourAcrossTheEdge) {
    constexpr int kSize = 8;
    for (Face f : kAllFaces)
        for (int i = 0; i < kSize; ++i) {
            const int ox[4] = {-1, kSize, i, i}, oy[4] = {i, i, -1, kSize};
            for (int k = 0; k < 4; ++k) {
                const TexelRef r = resolveTexel(f, ox[k], oy[k], kSize);
                ASSERT_NE(r.face, f);
                // The neighbour's texel touches the shared edge and lies next to ours.
                const bool onEdge = r.x == 0 || r.y == 0 || r.x == kSize - 1 || r.y == kSize - 1;
                ASSERT_TRUE(onEdge);
                const float angle = std::acos(std::min(1.0f, glm::dot(texelDirection(f, ox[k], oy[k], kSize),
                                                                        texelDirection(r.face, r.x, r.y, kSize))));
                ASSERT_LT(angle, 0.5f * (3.1415927f / 2) / kSize) << faceName(f) << " " << ox[k] << "," << oy[k];
            }
        }
}

TEST(CubeMap, BilinearSamplingIsContinuousAcrossFaceEdges) {
    // A linear environment sampled along a great circle that crosses four faces: consecutive
    // samples may differ only by the field's change plus bilinear error, never by a jump.
    const glm::vec3 a(0.3f, -0.7f, 0.5f);
    const CubeMap c = test::cubeFromFunction(16, [&](const glm::vec3& d) { return Rgb(1.0f + glm::dot(a, d)); });
    float previous = c.sample(glm::vec3(1, 0.2f, 0)).r;
    float maxStep = 0.0f;
    for (int i = 1; i <= 4000; ++i) {
        const float phi = 2.0f * 3.1415927f * static_cast<float>(i) / 4000.0f;
        const float value = c.sample(glm::vec3(std::cos(phi), 0.2f, std::sin(phi))).r;
        maxStep = std::max(maxStep, std::fabs(value - previous));
        previous = value;
    }
    // The field changes by at most |a|·Δφ ≈ 0.93·1.6e-3 per step.
    EXPECT_LT(maxStep, 2.0e-3f);
}

TEST(CubeMap, SamplingAtTexelCentresReturnsTexels) {
    CubeMap c(4);
    for (Face f : kAllFaces)
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) c.at(f, x, y) = Rgb(static_cast<float>(f), static_cast<float>(x), static_cast<float>(y));
    c.makeSeamless();
    for (Face f : kAllFaces)
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) {
                const Rgb v = c.sample(texelDirection(f, x, y, 4));
                EXPECT_NEAR(v.r, static_cast<float>(f), 1e-5f);
                EXPECT_NEAR(v.g, static_cast<float>(x), 1e-5f);
                EXPECT_NEAR(v.b, static_cast<float>(y), 1e-5f);
            }
}

TEST(CubeMap, ChainSizesFollowOpenGl) {
    EXPECT_EQ(fullChainLevelCount(128), 8);
    EXPECT_EQ(fullChainLevelCount(1), 1);
    EXPECT_EQ(fullChainLevelCount(3), 2);
    EXPECT_EQ(levelSize(3, 1), 1);
    EXPECT_EQ(levelSize(96, 5), 3);
    EXPECT_EQ(levelSize(96, 6), 1);
}
