// The selected object's outline (Renderer::setHighlightedObject): a band of about
// kOutlineWidthPixels around the silhouette, only outside it, and nothing else of the picture
// changed. Checked on a unit sphere whose silhouette on screen is computed exactly (hitUnitSphere).
#include "render_support.h"

#include "mipgloss/scene/environment.h"

#include <gtest/gtest.h>

#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <cstdio>

namespace mipgloss {
namespace {

TEST(SelectionOutline, IsABandJustOutsideTheSilhouetteAndChangesNothingElse) {
    std::string error;
    ui::OffscreenRenderer* renderer = test::sharedRenderer(&error);
    ASSERT_NE(renderer, nullptr) << error;
    Material material;
    material.lambda = 3.0f;
    Scene scene = test::sphereScene(material);
    scene.display.showBackground = true;  // the band must show over the background too
    const int w = 160, h = 120;
    OrbitCamera camera;
    camera.frame(sceneBounds(scene), static_cast<float>(w) / static_cast<float>(h), 2.0f);
    static const auto env = std::make_shared<const PreparedEnvironment>(
        prepareEnvironment(EnvironmentSettings{}, ChainNeeds{7, false}));

    renderer->setHighlightedObject(-1);
    const QImage plain = renderer->render(scene, camera, env, w, h).convertToFormat(QImage::Format_RGB32);
    renderer->setHighlightedObject(0);
    const QImage outlined = renderer->render(scene, camera, env, w, h).convertToFormat(QImage::Format_RGB32);
    renderer->setHighlightedObject(-1);
    ASSERT_EQ(plain.size(), outlined.size());

    // Distance (pixels) from each pixel centre to the sphere's silhouette: the angle between the
    // pixel's ray and the ray to the centre against the silhouette's half-angle, in pixels.
    const glm::mat4 inverse = glm::inverse(camera.projection(static_cast<float>(w) / static_cast<float>(h), sceneBounds(scene)) * camera.view());
    const glm::vec3 eye = camera.position();
    const float distance = glm::length(eye);
    const float halfAngle = std::asin(1.0f / distance);
    const float pixelAngle = glm::radians(camera.fovYDegrees) / static_cast<float>(h);
    int band = 0, inside = 0, far = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const test::Ray ray = test::pixelRay(inverse, x, y, w, h);
            const float angle = std::acos(std::clamp(glm::dot(ray.direction, -eye / distance), -1.0f, 1.0f));
            const float outside = (angle - halfAngle) / pixelAngle;  // > 0 off the sphere, in pixels
            const QRgb p = plain.pixel(x, h - 1 - y), q = outlined.pixel(x, h - 1 - y);
            const bool changed = std::max({std::abs(qRed(p) - qRed(q)), std::abs(qGreen(p) - qGreen(q)),
                                           std::abs(qBlue(p) - qBlue(q))}) > 2;
            if (!changed) continue;
            if (outside < -1.0f) ++inside;                                              // on the object
            else if (outside > ui::Renderer::kOutlineWidthPixels + 1.5f) ++far;          // beyond the band
            else ++band;
        }
    // The silhouette is a circle of radius r pixels: its band holds about 2πr·width pixels.
    const float r = halfAngle / pixelAngle;
    const float expected = 2.0f * 3.14159265f * r * ui::Renderer::kOutlineWidthPixels;
    std::printf("[ SelectionOutline ] radius %.1f px: %d band pixels changed (about %.0f expected), %d on the "
                "object, %d beyond\n", r, band, expected, inside, far);
    EXPECT_EQ(inside, 0);
    EXPECT_EQ(far, 0);
    EXPECT_GT(static_cast<float>(band), 0.6f * expected);
    EXPECT_LT(static_cast<float>(band), 1.6f * expected);
}

}  // namespace
}  // namespace mipgloss
