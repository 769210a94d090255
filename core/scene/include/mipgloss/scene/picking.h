// What is under a pixel: the ray through it and the object it meets first. GL-free, so the
// viewport's clicks and drops are tested without a window.
#pragma once

#include "mipgloss/scene/camera.h"
#include "mipgloss/scene/scene.h"

#include <glm/vec3.hpp>

namespace mipgloss {

struct Ray {
    glm::vec3 origin;     // on the near plane
    glm::vec3 direction;  // unit length
};

// The ray through the centre of pixel (x, y) of a width × height view (y down, as windows count),
// for `camera` framing `scene` (its projection's near and far planes come from the scene's bounds).
Ray pixelRay(const OrbitCamera& camera, const Scene& scene, int width, int height, int x, int y);

// The visible object `ray` meets first, or -1. Each object is its bounding sphere shrunk to 0.8 of
// its radius (bounding spheres are loose; this favours the centre), the same spheres the culling
// uses, so what is picked is what could be drawn.
int firstObjectHit(const Scene& scene, const Ray& ray);

// The same, with how far along the ray it is met (negative when the ray starts inside the
// sphere); index -1 when nothing is.
struct ObjectHit {
    int index = -1;
    float distance = 0.0f;
};
ObjectHit firstHit(const Scene& scene, const Ray& ray);

}  // namespace mipgloss
