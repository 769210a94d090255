#include "mipgloss/scene/view_gestures.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mipgloss {

std::optional<Bounds> objectBounds(const SceneObject& object) {
    if (!object.mesh) return std::nullopt;
    constexpr float inf = std::numeric_limits<float>::infinity();
    Bounds out{glm::vec3(inf), glm::vec3(-inf)};
    const glm::mat4 m = object.transform.matrix();
    const Bounds& b = object.mesh->bounds;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y,
                          (corner & 4) ? b.max.z : b.min.z);
        const glm::vec3 w(m * glm::vec4(p, 1.0f));
        out.min = glm::min(out.min, w);
        out.max = glm::max(out.max, w);
    }
    return out;
}

std::optional<glm::vec3> zoomPivot(const Scene& scene, const OrbitCamera& camera, const Ray& ray) {
    // The first picking sphere met (the same spheres as firstObjectHit, so a zoom aims at what a
    // click would select).
    float best = std::numeric_limits<float>::infinity();
    for (const SceneObject& object : scene.objects) {
        if (!object.visible || !object.mesh) continue;
        const glm::vec3 toCentre = object.worldCentre() - ray.origin;
        const float along = glm::dot(toCentre, ray.direction);
        const float radius = object.worldRadius() * 0.8f;
        const float miss2 = glm::dot(toCentre, toCentre) - along * along;
        if (along <= 0.0f || miss2 > radius * radius) continue;
        best = std::min(best, along - std::sqrt(radius * radius - miss2));
    }
    if (std::isfinite(best) && best > 0.0f) return ray.origin + best * ray.direction;
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
