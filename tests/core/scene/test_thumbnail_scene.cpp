// What a material thumbnail shows (thumbnail_scene.h): what it needs of the chain, the scene and
// the camera that frames it.
#include "mipgloss/scene/thumbnail_scene.h"

#include "mipgloss/ibl/phong.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mipgloss {

TEST(ThumbnailNeeds, EveryLambdaIsReadFromFilteredLevelsWithIrradiance) {
    for (int size : {16, 32, 64, 128, 256, 512}) {
        const ChainNeeds needs = thumbnailNeeds(size);
        EXPECT_TRUE(needs.irradiance) << size;
        EXPECT_EQ(needs.lastFilteredLevel, lastReadLevel(size)) << "face " << size;
        for (double lambda = 0.0; lambda <= kMaxLambda; lambda += 0.125) {
            Material m;
            m.lambda = static_cast<float>(lambda);
            const ChainNeeds one = chainNeeds(thumbnailScene(m), size);
            EXPECT_LE(one.lastFilteredLevel, needs.lastFilteredLevel) << "face " << size << " λ " << lambda;
        }
    }
}

TEST(ThumbnailScene, OneSphereInFrontOfABlurredBackground) {
    Material m;
    m.lambda = 3.0f;
    const Scene scene = thumbnailScene(m);
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.materialOf(scene.objects[0]), m);
    EXPECT_TRUE(scene.display.showBackground);
    EXPECT_FLOAT_EQ(scene.display.backgroundLambda, 2.0f);
    // The camera frames the unit sphere inside the square: its silhouette's half-angle is below
    // half the field of view, and not far below (the sphere fills most of the picture).
    const OrbitCamera camera = thumbnailCamera();
    const double halfAngle = std::asin(1.0 / camera.distance) * 180.0 / 3.14159265358979;
    EXPECT_LT(halfAngle, 0.5 * camera.fovYDegrees);
    EXPECT_GT(halfAngle, 0.35 * camera.fovYDegrees);
}

}  // namespace mipgloss
