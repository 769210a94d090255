// What is under a pixel (picking.h): rays through pixels and the first object they meet.
#include "mipgloss/scene/picking.h"

#include "mipgloss/scene/framing.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <memory>

using namespace mipgloss;

namespace {

SceneObject sphereAt(const std::shared_ptr<const Mesh>& mesh, glm::vec3 at) {
    SceneObject o;
    o.mesh = mesh;
    o.transform.translation = at;
    return o;
}

}  // namespace

TEST(Picking, TheCentrePixelLooksAlongTheCameraAndHitsWhatItFrames) {
    const auto sphere = std::make_shared<const Mesh>(makeSphere(8, 16));
    Scene scene;
    scene.objects.push_back(sphereAt(sphere, {0.0f, 0.0f, 0.0f}));
    const OrbitCamera camera = framingCamera(scene, 1.0f);
    // An odd size has a centre pixel: its ray runs through the target.
    const Ray ray = pixelRay(camera, scene, 101, 101, 50, 50);
    EXPECT_NEAR(glm::length(ray.direction), 1.0f, 1e-5f);
    const glm::vec3 toTarget = glm::normalize(camera.target - ray.origin);
    EXPECT_GT(glm::dot(ray.direction, toTarget), 0.99999f);
    EXPECT_EQ(firstObjectHit(scene, ray), 0);
    // A corner pixel misses a sphere the camera frames with room around it.
    EXPECT_EQ(firstObjectHit(scene, pixelRay(camera, scene, 101, 101, 0, 0)), -1);
}

TEST(Picking, TheNearestOfTwoInLineIsPickedAndHiddenOnesAreNot) {
    const auto sphere = std::make_shared<const Mesh>(makeSphere(8, 16));
    Scene scene;
    scene.objects.push_back(sphereAt(sphere, {0.0f, 0.0f, -10.0f}));
    scene.objects.push_back(sphereAt(sphere, {0.0f, 0.0f, -4.0f}));
    const Ray ray{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}};
    EXPECT_EQ(firstObjectHit(scene, ray), 1);
    scene.objects[1].visible = false;
    EXPECT_EQ(firstObjectHit(scene, ray), 0);
    // Behind the ray's origin counts for nothing.
    EXPECT_EQ(firstObjectHit(scene, Ray{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}}), -1);
    // Within 0.8 of the bounding radius hits, beyond it misses.
    const float r = scene.objects[0].worldRadius();
    EXPECT_EQ(firstObjectHit(scene, Ray{{0.79f * r, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}}), 0);
    EXPECT_EQ(firstObjectHit(scene, Ray{{0.81f * r, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}}), -1);
}
