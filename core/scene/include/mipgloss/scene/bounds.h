// Axis-aligned bounds: what framing, the view frustum's near and far planes and culling read.
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace mipgloss {

// Axis-aligned bounds plus the bounding sphere used for framing and view culling.
struct Bounds {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
    glm::vec3 centre() const { return 0.5f * (min + max); }
    // Radius of the sphere around centre() that holds the box.
    float radius() const { return 0.5f * glm::length(max - min); }
};

}  // namespace mipgloss
