#include "mipgloss/scene/view_gestures.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mipgloss {

std::optional<glm::vec3> zoomPivot(const Scene& scene, const OrbitCamera& camera, const Ray& ray) {
    // What a click would select (a ray starting inside its sphere aims at the plane instead).
    if (const ObjectHit hit = firstHit(scene, ray); hit.index >= 0 && hit.distance > 0.0f)
        return ray.origin + hit.distance * ray.direction;
    // The target's plane, facing the camera.
    const glm::vec3 forward = glm::normalize(camera.target - camera.position());
    const float facing = glm::dot(ray.direction, forward);
    if (!(facing > 1e-4f)) return std::nullopt;
    const float t = glm::dot(camera.target - ray.origin, forward) / facing;
    if (!(t > 0.0f) || !std::isfinite(t)) return std::nullopt;
    return ray.origin + t * ray.direction;
}

void zoomToward(OrbitCamera& camera, const glm::vec3& pivot, float factor) {
    if (!(factor > 0.0f) || !std::isfinite(factor)) return;
    const float before = camera.distance;
    camera.zoom(factor);
    // The factor zoom() really applied (it clamps), so target and distance stay one scaling.
    const float applied = camera.distance / before;
    camera.target = pivot + (camera.target - pivot) * applied;
}

}  // namespace mipgloss
