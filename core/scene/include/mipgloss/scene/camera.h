// The orbit camera and the view maths shared by the window, offscreen rendering and the tests.
// Pure functions and a small value type: no GL, no Qt.
//
// Conventions: right-handed, y up, OpenGL clip space (z in [-1, 1]); the camera looks at `target`
// from `distance` away, turned by `yaw` about +Y and raised by `pitch` (degrees).
#pragma once

#include "mipgloss/scene/bounds.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>

namespace mipgloss {

struct OrbitCamera {
    glm::vec3 target{0.0f};
    float distance = 5.0f;
    float yawDegrees = 0.0f;
    float pitchDegrees = 10.0f;
    float fovYDegrees = 30.0f;
    // The picture turned about the view axis, counter-clockwise as the viewer sees the scene turn
    // clockwise (a camera rolled to its left): a glTF camera's full orientation (cameraThrough).
    // The gestures keep it.
    float rollDegrees = 0.0f;

    glm::vec3 position() const;
    glm::mat4 view() const;
    // Near and far planes hold `scene` (the bounds of what is drawn) wherever the target is, and
    // follow its size, so a 0.2-unit scan and a 120-unit one get the same depth precision.
    glm::mat4 projection(float aspect, const Bounds& scene) const;

    // Mouse gestures. orbit: degrees; pan: fractions of the view height; zoom: factor > 0
    // (< 1 moves closer). Pitch is kept inside (-89°, 89°) so the up vector never flips.
    void orbit(float dYawDegrees, float dPitchDegrees);
    void pan(float dxViewHeights, float dyViewHeights);
    void zoom(float factor);

    // Frame-all: aims at the bounds' centre and backs off until the box's corners fit both fields
    // of view with `margin` (> 1) to spare. Keeps yaw and pitch; scale-free (distance ∝ size).
    void frame(const Bounds& bounds, float aspect, float margin = 1.1f);

    bool operator==(const OrbitCamera&) const = default;
};

// The orbit camera at `position` looking along `forward` with `up` (unit, perpendicular to
// forward: a glTF camera node's −Z and +Y in world space), its target `distance` ahead: yaw and
// pitch from forward, roll from up. Pitch is clamped to ±89° like the gestures', so a camera
// looking straight up or down is drawn 1° off it.
OrbitCamera cameraThrough(const glm::vec3& position, const glm::vec3& forward, const glm::vec3& up, float fovYDegrees,
                          float distance);

// The six planes of a view-projection matrix (Gribb & Hartmann 2001), normalized, pointing in.
struct Frustum {
    std::array<glm::vec4, 6> planes;
    static Frustum fromViewProjection(const glm::mat4& viewProjection);
    // False only when the sphere lies wholly outside one plane (conservative: may keep a sphere
    // that is outside near a frustum corner, never drops a visible one).
    bool intersectsSphere(const glm::vec3& centre, float radius) const;
};

}  // namespace mipgloss
