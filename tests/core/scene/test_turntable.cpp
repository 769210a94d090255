// The turntable as a view (turntable.h): turning the objects by θ about the target's vertical axis
// under a fixed environment is the same picture as the turned camera and environment, checked
// analytically on points (where they land on screen) and on reflections (what they look up).
#include "mipgloss/scene/turntable.h"

#include <gtest/gtest.h>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <vector>

using namespace mipgloss;

namespace {

// The renderer's world -> environment direction (ui/render/src/renderer_impl.h, environmentRotation):
// turning the environment by φ is looking up Ry(−φ)·d. Restated here: core tests link no GL.
glm::mat3 environmentLookup(float degrees) {
    return glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(-degrees), glm::vec3(0, 1, 0)));
}

// Ry(θ), the turn Transform::matrix() gives an object with rotationDegrees.y = θ.
glm::mat3 turn(float degrees) {
    return glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0, 1, 0)));
}

OrbitCamera someCamera() {
    OrbitCamera c;
    c.target = {0.75f, -0.25f, 1.5f};
    c.distance = 6.0f;
    c.yawDegrees = 35.0f;
    c.pitchDegrees = 20.0f;
    c.fovYDegrees = 40.0f;
    return c;
}

const std::vector<float> kAngles = {0.0f, 30.0f, -45.0f, 137.5f, 180.0f, -200.0f, 315.0f, 360.0f, 405.0f, -730.0f, 1000.0f};

// Points around the target (a few units), and unit normals in several directions.
const std::vector<glm::vec3> kPoints = {{0, 0, 0}, {1, 0.5f, -0.25f}, {-1.5f, 1, 0.75f}, {0.2f, -0.8f, 1.2f}};
const std::vector<glm::vec3> kNormals = {glm::normalize(glm::vec3(0, 1, 0)), glm::normalize(glm::vec3(1, 0.2f, 0.3f)),
                                         glm::normalize(glm::vec3(-0.4f, -0.5f, 0.9f)),
                                         glm::normalize(glm::vec3(0.1f, 0.7f, -1.0f))};

}  // namespace

TEST(Turntable, SpinNamesRoundTrip) {
    for (TurntableSpin s : {TurntableSpin::Object, TurntableSpin::Environment}) {
        TurntableSpin back = s == TurntableSpin::Object ? TurntableSpin::Environment : TurntableSpin::Object;
        ASSERT_TRUE(parseTurntableSpin(turntableSpinName(s), back)) << turntableSpinName(s);
        EXPECT_EQ(back, s);
    }
    EXPECT_STREQ(turntableSpinName(TurntableSpin::Object), "object");
    EXPECT_STREQ(turntableSpinName(TurntableSpin::Environment), "environment");
    TurntableSpin out = TurntableSpin::Environment;
    EXPECT_FALSE(parseTurntableSpin("Object", out));
    EXPECT_FALSE(parseTurntableSpin("", out));
    EXPECT_EQ(out, TurntableSpin::Environment);
}

// Object spin: a world point p turned by θ about the target and seen through the original camera
// lands where p lands through the turned camera (view space within 2e-5 of the distance), so the
// view matrices differ by exactly that turn.
TEST(Turntable, ObjectSpinSeesTurnedPointsWhereTheTurnedCameraSeesThePoints) {
    const OrbitCamera camera = someCamera();
    const glm::mat4 view = camera.view();
    const Bounds bounds{camera.target - glm::vec3(3.0f), camera.target + glm::vec3(3.0f)};
    for (float theta : kAngles) {
        const TurnedView turned = turnedView(camera, 20.0f, TurntableSpin::Object, theta);
        EXPECT_EQ(turned.camera.target, camera.target) << theta;
        EXPECT_EQ(turned.camera.distance, camera.distance) << theta;
        EXPECT_EQ(turned.camera.pitchDegrees, camera.pitchDegrees) << theta;
        EXPECT_EQ(turned.camera.fovYDegrees, camera.fovYDegrees) << theta;
        EXPECT_LE(std::abs(turned.camera.yawDegrees), 180.0f) << theta;
        EXPECT_LE(std::abs(turned.environmentRotationDegrees), 180.0f) << theta;
        const glm::mat4 turnedViewMatrix = turned.camera.view();
        const glm::mat4 aboutTarget = glm::translate(glm::mat4(1.0f), camera.target) *
                                      glm::mat4(turn(theta)) * glm::translate(glm::mat4(1.0f), -camera.target);
        const glm::mat4 expected = view * aboutTarget;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                EXPECT_NEAR(turnedViewMatrix[c][r], expected[c][r], 2e-5f * (c == 3 ? camera.distance * 2 : 1.0f))
                    << "θ " << theta << " view[" << c << "][" << r << "]";
        const glm::mat4 projection = camera.projection(4.0f / 3.0f, bounds);
        for (const glm::vec3& p : kPoints) {
            const glm::vec3 turnedP = camera.target + turn(theta) * (p - camera.target);
            const glm::vec4 a = view * glm::vec4(turnedP, 1.0f);
            const glm::vec4 b = turnedViewMatrix * glm::vec4(p, 1.0f);
            EXPECT_LT(glm::length(glm::vec3(a - b)), 2e-5f * camera.distance)
                << "θ " << theta << " p (" << p.x << ", " << p.y << ", " << p.z << ")";
            // And on screen (normalized device coordinates, within 1e-5 of the half-width).
            const glm::vec4 ca = projection * a, cb = turned.camera.projection(4.0f / 3.0f, bounds) * b;
            EXPECT_LT(glm::length(glm::vec2(ca) / ca.w - glm::vec2(cb) / cb.w), 1e-5f) << "θ " << theta;
        }
    }
}

// Object spin: a turned object's normal reflects the view into the same environment texel as the
// unturned normal seen by the turned camera through the turned environment (within 1e-5).
TEST(Turntable, ObjectSpinLooksUpTheSameEnvironmentDirection) {
    const OrbitCamera camera = someCamera();
    for (float phi : {0.0f, 20.0f, -170.0f}) {
        for (float theta : kAngles) {
            const TurnedView turned = turnedView(camera, phi, TurntableSpin::Object, theta);
            for (const glm::vec3& p : kPoints) {
                for (const glm::vec3& n : kNormals) {
                    // The scene really turned: point, normal; the camera and environment as they were.
                    const glm::vec3 turnedP = camera.target + turn(theta) * (p - camera.target);
                    const glm::vec3 v = glm::normalize(camera.position() - turnedP);
                    const glm::vec3 expected = environmentLookup(phi) * glm::reflect(-v, turn(theta) * n);
                    // The turned view: the scene as it is, the camera and environment turned.
                    const glm::vec3 v2 = glm::normalize(turned.camera.position() - p);
                    const glm::vec3 got = environmentLookup(turned.environmentRotationDegrees) * glm::reflect(-v2, n);
                    EXPECT_LT(glm::length(got - expected), 1e-5f)
                        << "φ " << phi << " θ " << theta << " n (" << n.x << ", " << n.y << ", " << n.z << ")";
                }
            }
            // The background (a view direction through a pixel) looks up the same direction too.
            const glm::vec3 pixelDirection = glm::normalize(glm::vec3(0.3f, -0.2f, -1.0f));
            const glm::vec3 worldBefore = glm::transpose(glm::mat3(camera.view())) * pixelDirection;
            const glm::vec3 worldAfter = glm::transpose(glm::mat3(turned.camera.view())) * pixelDirection;
            EXPECT_LT(glm::length(environmentLookup(turned.environmentRotationDegrees) * worldAfter -
                                  environmentLookup(phi) * worldBefore),
                      1e-5f)
                << "φ " << phi << " θ " << theta;
        }
    }
}

// Environment spin: the camera stays; the environment's picture turns by +θ about +Y (what was seen
// in direction d is now seen in direction Ry(θ)·d), the same sense as the objects in object spin.
TEST(Turntable, EnvironmentSpinTurnsOnlyTheEnvironment) {
    const OrbitCamera camera = someCamera();
    for (float phi : {0.0f, 20.0f, -170.0f}) {
        for (float theta : kAngles) {
            const TurnedView turned = turnedView(camera, phi, TurntableSpin::Environment, theta);
            EXPECT_EQ(turned.camera, camera) << theta;
            EXPECT_LE(std::abs(turned.environmentRotationDegrees), 180.0f) << theta;
            for (const glm::vec3& d : kNormals)
                EXPECT_LT(glm::length(environmentLookup(turned.environmentRotationDegrees) * (turn(theta) * d) -
                                      environmentLookup(phi) * d),
                          1e-5f)
                    << "φ " << phi << " θ " << theta;
        }
    }
}

// A whole number of turns is the view it started from (angles wrapped, within float rounding).
TEST(Turntable, WholeTurnsComeBackToTheStart) {
    const OrbitCamera camera = someCamera();
    for (TurntableSpin spin : {TurntableSpin::Object, TurntableSpin::Environment}) {
        for (float theta : {360.0f, -360.0f, 720.0f, 3600.0f}) {
            const TurnedView turned = turnedView(camera, 20.0f, spin, theta);
            EXPECT_NEAR(turned.camera.yawDegrees, camera.yawDegrees, 1e-4f) << theta;
            EXPECT_NEAR(turned.environmentRotationDegrees, 20.0f, 1e-4f) << theta;
        }
    }
}
