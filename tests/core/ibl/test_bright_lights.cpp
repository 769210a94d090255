// The environment split into bright lights and the smooth remainder (bright_lights.h): what the
// layered program shades with the exact BRDF and what its lookups read from the remainder stack.
#include "mipgloss/ibl/bright_lights.h"
#include "mipgloss/ibl/colour.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mipgloss {
namespace {

// A dim sky with a warm sun of 3 × 3 texels and one lone bright texel on another face.
CubeMap skyWithASun(int size) {
    CubeMap cube(size, Rgb(0.2f, 0.3f, 0.5f));
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) cube.at(Face::PY, 10 + x, 12 + y) = Rgb(4000.0f, 3000.0f, 2000.0f);
    cube.at(Face::NZ, 5, 7) = Rgb(50.0f, 80.0f, 60.0f);
    cube.makeSeamless();
    return cube;
}

glm::dvec3 energyOf(const CubeMap& cube) {
    glm::dvec3 sum(0.0);
    for (Face f : kAllFaces)
        for (int y = 0; y < cube.size(); ++y)
            for (int x = 0; x < cube.size(); ++x) sum += glm::dvec3(cube.at(f, x, y)) * texelSolidAngle(x, y, cube.size());
    return sum;
}

TEST(BrightLights, TheRemainderAndTheLightsAddUpToTheEnvironmentPerChannel) {
    const CubeMap base = skyWithASun(32);
    const CubeMap remainder = withoutBrightLights(base);
    // However the lights are merged (one, or every bright texel its own), their energy is what the
    // remainder lost: double sums of float texels, within 1e-6 of the whole.
    for (const int maxLights : {1, 4, 1 << 20}) {
        glm::dvec3 lights(0.0);
        for (const PointLight& light : brightLights(base, kBrightFactor, maxLights)) lights += glm::dvec3(light.energy);
        const glm::dvec3 whole = energyOf(base), split = energyOf(remainder) + lights;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(split[c] / whole[c], 1.0, 1e-6) << "channel " << c << ", " << maxLights << " lights";
    }
}

TEST(BrightLights, TheRemainderIsTheBaseClampedAtTheThresholdWithItsColour) {
    const CubeMap base = skyWithASun(32);
    const CubeMap remainder = withoutBrightLights(base);
    const double threshold = brightThreshold(base);
    ASSERT_GT(threshold, luminance(Rgb(0.2f, 0.3f, 0.5f)));
    // The sun's texels come down to the threshold's luminance, hue kept; the sky is untouched.
    const Rgb sun = remainder.at(Face::PY, 11, 13);
    EXPECT_NEAR(luminance(sun) / threshold, 1.0, 1e-5);
    EXPECT_NEAR(sun.r / sun.b, 2.0, 1e-5);
    EXPECT_EQ(remainder.at(Face::PX, 3, 3), base.at(Face::PX, 3, 3));
    for (Face f : kAllFaces)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) EXPECT_LE(luminance(remainder.at(f, x, y)), threshold * (1.0 + 1e-6));
}

TEST(BrightLights, AnEnvironmentWithoutBrightTexelsIsItsOwnRemainder) {
    CubeMap uniform(16, Rgb(1.0f, 2.0f, 3.0f));
    uniform.makeSeamless();
    EXPECT_TRUE(brightLights(uniform).empty());
    const CubeMap remainder = withoutBrightLights(uniform);
    EXPECT_EQ(remainder.at(Face::NY, 7, 9), uniform.at(Face::NY, 7, 9));
    EXPECT_EQ(energyOf(remainder), energyOf(uniform));
}

}  // namespace
}  // namespace mipgloss
