#include "mipgloss/scene/picking.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include <cmath>
#include <cstddef>
#include <limits>

namespace mipgloss {

Ray pixelRay(const OrbitCamera& camera, const Scene& scene, int width, int height, int x, int y) {
    const float aspect = height > 0 ? static_cast<float>(width) / static_cast<float>(height) : 1.0f;
    const glm::mat4 inverse = glm::inverse(camera.projection(aspect, sceneBounds(scene)) * camera.view());
    const float ndcX = 2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(width) - 1.0f;
    const float ndcY = 1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height);
    const glm::vec4 nearPoint = inverse * glm::vec4(ndcX, ndcY, -1.0f, 1.0f);
    const glm::vec4 farPoint = inverse * glm::vec4(ndcX, ndcY, 1.0f, 1.0f);
    const glm::vec3 origin = glm::vec3(nearPoint) / nearPoint.w;
    return {origin, glm::normalize(glm::vec3(farPoint) / farPoint.w - origin)};
}

int firstObjectHit(const Scene& scene, const Ray& ray) { return firstHit(scene, ray).index; }

ObjectHit firstHit(const Scene& scene, const Ray& ray) {
    int best = -1;
    float bestDistance = std::numeric_limits<float>::infinity();
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        if (!object.visible || !object.mesh) continue;
        const glm::vec3 toCentre = object.worldCentre() - ray.origin;
        const float along = glm::dot(toCentre, ray.direction);
        const float radius = object.worldRadius() * 0.8f;
        const float miss2 = glm::dot(toCentre, toCentre) - along * along;
        if (along <= 0.0f || miss2 > radius * radius) continue;
        const float distance = along - std::sqrt(radius * radius - miss2);
        if (distance < bestDistance) {
            bestDistance = distance;
            best = static_cast<int>(i);
        }
    }
    return {best, best >= 0 ? bestDistance : 0.0f};
}

}  // namespace mipgloss
