#include "mipgloss/scene/placement.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace mipgloss {

Transform inCentredRow(const Bounds& b, int i, int count) {
    const float spacing = 1.15f * (b.max.x - b.min.x);
    const float fromCentre = static_cast<float>(i) - 0.5f * static_cast<float>(count - 1);
    Transform t;
    t.translation = glm::vec3(fromCentre * spacing, 0.0f, 0.0f) - b.centre();
    return t;
}

Transform nextInRow(const Bounds& b, float& cursor) {
    const float r = b.radius();
    Transform t;
    t.translation = glm::vec3(cursor + r, 0.0f, 0.0f) - b.centre();
    cursor += 2.2f * r;
    return t;
}

Transform inGrid(const Bounds& b, int i, int count) {
    const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
    const float spacing = 2.3f * b.radius();
    Transform t;
    t.translation =
        glm::vec3(static_cast<float>(i % columns) * spacing, static_cast<float>(i / columns) * spacing, 0.0f);
    return t;
}

Transform besideScene(const Scene& scene, const Mesh& mesh) {
    std::vector<float> radii;
    for (const SceneObject& o : scene.objects)
        if (o.visible && o.mesh) radii.push_back(o.worldRadius());
    Transform t;
    const float r = mesh.bounds.radius();
    float typical = 0.0f;
    if (!radii.empty()) {
        const auto middle = radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2);
        std::nth_element(radii.begin(), middle, radii.end());
        typical = radii[radii.size() / 2];
    }
    if (typical > 0.0f && r > 0.0f && (r > 4.0f * typical || r < 0.25f * typical))
        t.scale = typical / r;
    const float placedRadius = r * t.scale;
    glm::vec3 centre(0.0f);
    if (!radii.empty()) {
        const Bounds b = sceneBounds(scene);
        const float gap = 0.2f * (typical > 0.0f ? typical : placedRadius);
        centre = glm::vec3(b.max.x + gap + placedRadius, b.centre().y, b.centre().z);
    }
    t.translation = centre - t.scale * mesh.bounds.centre();
    return t;
}

Transform besideOriginal(const SceneObject& original) {
    Transform t = original.transform;
    t.translation.x += 1.2f * 2.0f * original.worldRadius();
    return t;
}

}  // namespace mipgloss
