#include "mipgloss/scene/camera.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace mipgloss {

namespace {
constexpr float kMaxPitch = 89.0f;

// Unit vector from the target toward the camera.
glm::vec3 viewBack(float yawDegrees, float pitchDegrees) {
    const float yaw = glm::radians(yawDegrees);
    const float pitch = glm::radians(pitchDegrees);
    return {std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw)};
}
}  // namespace

glm::vec3 OrbitCamera::position() const {
    return target + distance * viewBack(yawDegrees, pitchDegrees);
}

glm::mat4 OrbitCamera::view() const {
    const glm::mat4 upright = glm::lookAt(position(), target, glm::vec3(0.0f, 1.0f, 0.0f));
    if (rollDegrees == 0.0f) return upright;
    // The camera's right and up turned by the roll ρ about its back axis: in view space a point's
    // (x, y) turn by −ρ.
    return glm::rotate(glm::mat4(1.0f), -glm::radians(rollDegrees), glm::vec3(0.0f, 0.0f, 1.0f)) * upright;
}

glm::mat4 OrbitCamera::projection(float aspect, const Bounds& scene) const {
    // Depth range: from just in front of the scene's near side to past its far side, with the
    // near plane never closer than 1/1000 of the distance (24-bit depth keeps ~10 bits there).
    // The scene reaches this far from the target.
    const float radius = std::max(glm::length(target - scene.centre()) + scene.radius(), 1e-6f);
    const float nearPlane = std::max(distance - 2.0f * radius, distance * 1e-3f);
    const float farPlane = distance + 2.0f * radius + nearPlane;
    return glm::perspective(glm::radians(fovYDegrees), std::max(aspect, 1e-3f), nearPlane, farPlane);
}

OrbitCamera cameraThrough(const glm::vec3& position, const glm::vec3& forward, const glm::vec3& up, float fovYDegrees,
                          float distance) {
    OrbitCamera camera;
    const glm::vec3 back = -glm::normalize(forward);
    camera.pitchDegrees = std::clamp(glm::degrees(std::asin(std::clamp(back.y, -1.0f, 1.0f))), -kMaxPitch, kMaxPitch);
    camera.yawDegrees = glm::degrees(std::atan2(back.x, back.z));
    camera.fovYDegrees = fovYDegrees;
    camera.distance = distance;
    const glm::vec3 orbitBack = viewBack(camera.yawDegrees, camera.pitchDegrees);
    camera.target = position - distance * orbitBack;
    // The roll: the angle from the upright camera's up to `up`, about the back axis.
    const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), orbitBack));
    const glm::vec3 uprightUp = glm::cross(orbitBack, right);
    camera.rollDegrees = glm::degrees(std::atan2(-glm::dot(up, right), glm::dot(up, uprightUp)));
    return camera;
}

void OrbitCamera::orbit(float dYawDegrees, float dPitchDegrees) {
    yawDegrees = std::fmod(yawDegrees + dYawDegrees, 360.0f);
    pitchDegrees = std::clamp(pitchDegrees + dPitchDegrees, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::pan(float dxViewHeights, float dyViewHeights) {
    // One view height at the target's distance, so the point under the cursor follows it.
    const float viewHeight = 2.0f * distance * std::tan(glm::radians(fovYDegrees) * 0.5f);
    const glm::vec3 back = viewBack(yawDegrees, pitchDegrees);
    const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), back));
    const glm::vec3 up = glm::cross(back, right);
    target += viewHeight * (-dxViewHeights * right + dyViewHeights * up);
}

void OrbitCamera::zoom(float factor) {
    if (!(factor > 0.0f) || !std::isfinite(factor)) return;
    distance = std::clamp(distance * factor, 1e-6f, 1e9f);
}

void OrbitCamera::frame(const Bounds& bounds, float aspect, float margin) {
    // Fit the box's eight corners, not its bounding sphere: a row of objects in a wide image then
    // fills the image. In camera axes (right, up, back) a corner at (x, y, z) from the centre is
    // inside the view from distance d when |x| <= (d - z) tan(halfX) and |y| <= (d - z) tan(halfY).
    const float tanY = std::tan(glm::radians(fovYDegrees) * 0.5f);
    const float tanX = tanY * std::max(aspect, 1e-3f);
    const glm::vec3 back = viewBack(yawDegrees, pitchDegrees);
    const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), back));
    const glm::vec3 up = glm::cross(back, right);
    target = bounds.centre();
    const float radius = std::max(bounds.radius(), 1e-6f);
    float needed = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
                          (corner & 4) ? bounds.max.z : bounds.min.z);
        const glm::vec3 q = p - target;
        const float z = glm::dot(q, back);
        needed = std::max({needed, z + margin * std::abs(glm::dot(q, right)) / tanX,
                           z + margin * std::abs(glm::dot(q, up)) / tanY});
    }
    // Never inside the bounds' sphere (the near plane would cut the objects).
    distance = std::max(needed, 1.05f * radius);
}

Frustum Frustum::fromViewProjection(const glm::mat4& m) {
    // Rows of the matrix (glm is column-major: m[col][row]).
    auto row = [&](int r) { return glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
    const glm::vec4 r0 = row(0), r1 = row(1), r2 = row(2), r3 = row(3);
    Frustum f;
    f.planes = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 + r2, r3 - r2};
    for (glm::vec4& p : f.planes) p /= glm::length(glm::vec3(p));
    return f;
}

bool Frustum::intersectsSphere(const glm::vec3& centre, float radius) const {
    for (const glm::vec4& p : planes)
        if (glm::dot(glm::vec3(p), centre) + p.w < -radius) return false;
    return true;
}

}  // namespace mipgloss
