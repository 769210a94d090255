#include "mipgloss/scene/lobes.h"

#include <gtest/gtest.h>

namespace mipgloss {
namespace {

// The texel of face f's interior (x, y) of an entry placed at `at`, RGB.
const float* packedTexel(const PackedLobeStack& packed, const AtlasPlacement& at, Face f, int x, int y) {
    const int stride = at.size + 2;
    const int tx = at.x + (static_cast<int>(f) % 3) * stride + 1 + x;
    const int ty = at.y + (static_cast<int>(f) / 3) * stride + 1 + y;
    return &packed.texels[(static_cast<std::size_t>(ty) * static_cast<std::size_t>(packed.atlas.width) +
                           static_cast<std::size_t>(tx)) * 3];
}

TEST(PackLobeStack, PlacesEveryFaceTexelScaledByThePowerOfTwoBelowTheFormatsLargest) {
    CubeMap sharp(2), wide(1);
    for (Face f : kAllFaces)
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 2; ++x) sharp.at(f, x, y) = Rgb(static_cast<float>(f) * 100.0f + static_cast<float>(x + 2 * y), 1.0f, 0.5f);
    for (Face f : kAllFaces) wide.at(f, 0, 0) = Rgb(3.0f);
    const PackedLobeStack packed = packLobeStack({{4, &sharp}, {9, &wide}}, 64);
    ASSERT_EQ(packed.atlas.placed.size(), 2u);
    ASSERT_EQ(packed.scales.size(), 2u);
    // Largest 503: 503·64 = 32192 < 32704 ≤ 503·128 = 64384 < 65408, so 2^7.
    EXPECT_EQ(packed.scales[0], 1.0f / 128.0f);
    // Largest 3: 3·2^14 = 49152 in [32704, 65408).
    EXPECT_EQ(packed.scales[1], 1.0f / 16384.0f);
    EXPECT_EQ(packed.atlas.placed[0].index, 4);
    EXPECT_EQ(packed.atlas.placed[1].index, 9);
    for (Face f : kAllFaces) {
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 2; ++x) {
                const float* t = packedTexel(packed, packed.atlas.placed[0], f, x, y);
                const Rgb& c = sharp.at(f, x, y);
                EXPECT_EQ(t[0], c.r * 128.0f) << "face " << static_cast<int>(f) << " texel " << x << ", " << y;
                EXPECT_EQ(t[1], c.g * 128.0f);
                EXPECT_EQ(t[2], c.b * 128.0f);
            }
        EXPECT_EQ(packedTexel(packed, packed.atlas.placed[1], f, 0, 0)[0], 3.0f * 16384.0f);
    }
    EXPECT_EQ(packed.texels.size(), static_cast<std::size_t>(packed.atlas.width) * static_cast<std::size_t>(packed.atlas.height) * 3);
}

TEST(PackLobeStack, LeavesAnAllZeroEntryUnscaled) {
    CubeMap dark(2);
    const PackedLobeStack packed = packLobeStack({{1, &dark}});
    ASSERT_EQ(packed.scales.size(), 1u);
    EXPECT_EQ(packed.scales[0], 1.0f);
    for (float t : packed.texels) EXPECT_EQ(t, 0.0f);
}

}  // namespace
}  // namespace mipgloss
