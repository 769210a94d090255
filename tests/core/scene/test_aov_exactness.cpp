#include "mipgloss/scene/aov_exactness.h"

#include <gtest/gtest.h>

#include <limits>

namespace mipgloss {
namespace {

std::vector<float> filled(int width, int height, float value) {
    return std::vector<float>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), value);
}

TEST(WithoutMixedPixels, ClearsPixelsWhoseNeighbourhoodLeavesThePicture) {
    const int width = 4, height = 3;
    const std::vector<float> exact = withoutMixedPixels(width, height, filled(width, height, 10.0f), filled(width, height, 1.0f));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const bool interior = x >= 1 && x <= 2 && y == 1;
            EXPECT_EQ(exact[static_cast<std::size_t>(y * width + x)], interior ? 1.0f : 0.0f) << "pixel " << x << ", " << y;
        }
}

TEST(WithoutMixedPixels, KeepsNeighboursWithinFivePercentAndClearsThoseBesideAnotherLobe) {
    const int width = 5, height = 5;
    std::vector<float> exponent = filled(width, height, 10.0f);
    exponent[1 * width + 1] = 10.4f;  // 4 % sharper: the same lobe, its footprint widened less
    exponent[4 * width + 4] = 10.6f;  // 6 % sharper: another lobe
    const std::vector<float> exact = withoutMixedPixels(width, height, exponent, filled(width, height, 1.0f));
    EXPECT_EQ(exact[2 * width + 2], 1.0f);  // sees 10.4, not 10.6
    EXPECT_EQ(exact[2 * width + 1], 1.0f);
    EXPECT_EQ(exact[3 * width + 3], 0.0f);  // beside 10.6
}

TEST(WithoutMixedPixels, ClearsPixelsBesideTheBackgroundAndKeepsThoseAlreadyInexact) {
    const int width = 5, height = 5;
    std::vector<float> exponent = filled(width, height, 10.0f);
    exponent[3 * width + 2] = 0.0f;  // no object there
    std::vector<float> exact = filled(width, height, 1.0f);
    exact[1 * width + 3] = 0.0f;
    const std::vector<float> result = withoutMixedPixels(width, height, exponent, exact);
    EXPECT_EQ(result[2 * width + 2], 0.0f);
    EXPECT_EQ(result[1 * width + 3], 0.0f);
    EXPECT_EQ(result[1 * width + 1], 1.0f);
}

TEST(WithoutMixedPixels, NeverKeepsAMirrorPixel) {
    const int width = 3, height = 3;
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<float> exact = withoutMixedPixels(width, height, filled(width, height, inf), filled(width, height, 1.0f));
    EXPECT_EQ(exact[1 * width + 1], 0.0f);  // ∞ − ∞ is NaN, never within 5 %
}

}  // namespace
}  // namespace mipgloss
