// The view's gestures (view_gestures.h): framing one object, zooming toward the cursor.
#include "mipgloss/scene/view_gestures.h"

#include "mipgloss/scene/framing.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <memory>

using namespace mipgloss;

namespace {

// Where world point p lands in normalized device coordinates (x, y in [-1, 1]).
glm::vec2 ndcOf(const OrbitCamera& camera, const Scene& scene, const glm::vec3& p, float aspect) {
    const glm::vec4 clip = camera.projection(aspect, sceneBounds(scene)) * camera.view() * glm::vec4(p, 1.0f);
    return glm::vec2(clip) / clip.w;
}

Scene twoSpheres() {
    const auto sphere = std::make_shared<const Mesh>(makeSphere(8, 16));
    Scene scene;
    for (const float x : {-3.0f, 3.0f}) {
        SceneObject o;
        o.mesh = sphere;
        o.transform.translation = {x, 0.5f, 0.0f};
        o.transform.scale = 0.5f;
        scene.objects.push_back(o);
    }
    return scene;
}

}  // namespace

TEST(ViewGestures, ObjectBoundsAreTheTransformedMeshBox) {
    const Scene scene = twoSpheres();
    const std::optional<Bounds> b = objectBounds(scene.objects[1]);
    ASSERT_TRUE(b);
    // A unit sphere (radius 1), scaled by 0.5 and moved to (3, 0.5, 0).
    EXPECT_NEAR(b->min.x, 2.5f, 1e-5f);
    EXPECT_NEAR(b->max.x, 3.5f, 1e-5f);
    EXPECT_NEAR(b->min.y, 0.0f, 1e-5f);
    EXPECT_NEAR(b->max.y, 1.0f, 1e-5f);
    EXPECT_FALSE(objectBounds(SceneObject{}));
}

TEST(ViewGestures, FramingOneObjectCentresItAndKeepsTheViewAngle) {
    const Scene scene = twoSpheres();
    OrbitCamera camera = framingCamera(scene, 1.5f);
    camera.yawDegrees = 30.0f;
    camera.frame(*objectBounds(scene.objects[0]), 1.5f);
    EXPECT_NEAR(glm::distance(camera.target, glm::vec3(-3.0f, 0.5f, 0.0f)), 0.0f, 1e-5f);
    EXPECT_EQ(camera.yawDegrees, 30.0f);
    // The object's sphere fills the view with the frame's margin: closer than framing both.
    EXPECT_LT(camera.distance, framingCamera(scene, 1.5f).distance);
}

TEST(ViewGestures, ZoomTowardKeepsThePivotUnderTheSamePixel) {
    const Scene scene = twoSpheres();
    const float aspect = 4.0f / 3.0f;
    for (const float factor : {0.5f, 0.85f, 1.3f, 3.0f}) {
        for (const glm::vec3 pivot : {glm::vec3(3.0f, 0.5f, 0.4f), glm::vec3(-2.0f, 1.0f, -1.0f)}) {
            OrbitCamera camera = framingCamera(scene, aspect);
            camera.yawDegrees = 20.0f;
            camera.pitchDegrees = 15.0f;
            const glm::vec2 before = ndcOf(camera, scene, pivot, aspect);
            const float distance = camera.distance;
            zoomToward(camera, pivot, factor);
            const glm::vec2 after = ndcOf(camera, scene, pivot, aspect);
            // Single precision through two matrices: a thousandth of the half-view.
            EXPECT_NEAR(after.x, before.x, 1e-3f) << "factor " << factor;
            EXPECT_NEAR(after.y, before.y, 1e-3f) << "factor " << factor;
            EXPECT_NEAR(camera.distance, distance * factor, 1e-4f * distance);
        }
    }
}

TEST(ViewGestures, ZoomTowardRefusesAbsurdFactors) {
    OrbitCamera camera;
    const OrbitCamera before = camera;
    for (const float factor : {0.0f, -1.0f, std::numeric_limits<float>::infinity(),
                               std::numeric_limits<float>::quiet_NaN()}) {
        zoomToward(camera, glm::vec3(1.0f), factor);
        EXPECT_EQ(camera.distance, before.distance);
        EXPECT_EQ(camera.target, before.target);
    }
}

TEST(ViewGestures, ThePivotIsTheObjectUnderTheCursorElseTheTargetPlane) {
    const Scene scene = twoSpheres();
    const OrbitCamera camera = framingCamera(scene, 1.0f);
    // Straight at the right sphere: its near side (the picking sphere is 0.8 of its radius).
    const glm::vec3 eye = camera.position();
    const Ray atSphere{eye, glm::normalize(glm::vec3(3.0f, 0.5f, 0.0f) - eye)};
    const std::optional<glm::vec3> hit = zoomPivot(scene, camera, atSphere);
    ASSERT_TRUE(hit);
    // The picking sphere holds the mesh's box: radius 0.8 · √3 · 0.5 for this unit sphere.
    EXPECT_NEAR(glm::distance(*hit, glm::vec3(3.0f, 0.5f, 0.0f)), 0.8f * scene.objects[1].worldRadius(), 1e-4f);
    // Between them: the target's plane.
    const Ray between{eye, glm::normalize(camera.target + glm::vec3(0.0f, 0.01f, 0.0f) - eye)};
    const std::optional<glm::vec3> onPlane = zoomPivot(scene, camera, between);
    ASSERT_TRUE(onPlane);
    const glm::vec3 forward = glm::normalize(camera.target - eye);
    EXPECT_NEAR(glm::dot(*onPlane - camera.target, forward), 0.0f, 1e-4f);
    // Looking away: nothing to aim at.
    EXPECT_FALSE(zoomPivot(scene, camera, Ray{eye, -forward}));
}
