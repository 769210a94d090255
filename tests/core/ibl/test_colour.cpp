// colour.h: the one definition of sRGB and luminance that import, material panel and tests share.
#include "mipgloss/ibl/colour.h"

#include <gtest/gtest.h>

namespace mipgloss {
namespace {

TEST(Colour, SrgbTransferFunctionsHitKnownPoints) {
    // Known points of IEC 61966-2-1.
    EXPECT_NEAR(srgbToLinear(0.5), 0.214041, 1e-6);
    EXPECT_NEAR(srgbToLinear(0.04045), 0.04045 / 12.92, 1e-12);
    EXPECT_NEAR(linearToSrgb(0.18), 0.461356, 1e-6);
    EXPECT_DOUBLE_EQ(srgbToLinear(0.0), 0.0);
    EXPECT_DOUBLE_EQ(srgbToLinear(1.0), 1.0);
    EXPECT_NEAR(linearToSrgb(1.0), 1.0, 1e-12);
}

TEST(Colour, SrgbEncodeInvertsDecodeAndIsContinuousAtTheKnee) {
    for (int i = 0; i <= 1000; ++i) {
        const double c = i / 1000.0;
        EXPECT_NEAR(linearToSrgb(srgbToLinear(c)), c, 1e-12) << c;
    }
    // The two pieces meet within the standard's rounding of its constants (~1e-7).
    EXPECT_NEAR(srgbToLinear(0.04045 - 1e-12), srgbToLinear(0.04045 + 1e-12), 1e-7);
    EXPECT_NEAR(linearToSrgb(0.0031308 - 1e-12), linearToSrgb(0.0031308 + 1e-12), 1e-7);
}

TEST(Colour, LuminanceWeightsAreRec709AndSumToOne) {
    EXPECT_DOUBLE_EQ(luminance(Rgb(1.0f)), 0.2126 + 0.7152 + 0.0722);
    EXPECT_NEAR(luminance(Rgb(1.0f)), 1.0, 1e-12);
    EXPECT_NEAR(luminance(Rgb(0.0f, 1.0f, 0.0f)), 0.7152, 1e-7);
}

}  // namespace
}  // namespace mipgloss
